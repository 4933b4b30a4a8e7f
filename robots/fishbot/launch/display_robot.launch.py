"""Show a fishbot_description model in RViz2.

Usage:
    ros2 launch fishbot_description display_robot.launch.py
    ros2 launch fishbot_description display_robot.launch.py model:=/path/to/robot.urdf.xacro

The model file is expanded with xacro (a plain .urdf passes through unchanged) and published
as robot_description by robot_state_publisher; joint_state_publisher publishes the joint
states of the wheels, and RViz2 opens with the saved display configuration.
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, LaunchConfiguration
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue


def generate_launch_description():
    share_dir = get_package_share_directory('fishbot_description')
    default_model = os.path.join(share_dir, 'urdf', 'fishbot', 'fishbot.urdf.xacro')
    rviz_config = os.path.join(share_dir, 'config', 'display_robot_model.rviz')

    model_arg = DeclareLaunchArgument(
        name='model',
        default_value=default_model,
        description='Absolute path to the URDF or xacro file to display',
    )

    # The parameter must be a string: without value_type=str, launch_ros would try to
    # parse the generated XML as YAML.
    robot_description = ParameterValue(
        Command(['xacro ', LaunchConfiguration('model')]),
        value_type=str,
    )

    robot_state_publisher = Node(
        package='robot_state_publisher',
        executable='robot_state_publisher',
        parameters=[{'robot_description': robot_description}],
    )

    joint_state_publisher = Node(
        package='joint_state_publisher',
        executable='joint_state_publisher',
    )

    rviz = Node(
        package='rviz2',
        executable='rviz2',
        arguments=['-d', rviz_config],
    )

    return LaunchDescription([
        model_arg,
        robot_state_publisher,
        joint_state_publisher,
        rviz,
    ])
