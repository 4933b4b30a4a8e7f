"""Simulate fishbot in Gazebo Classic.

Usage:
    ros2 launch fishbot_description gazebo_sim.launch.py
    ros2 launch fishbot_description gazebo_sim.launch.py world:=/path/to/a.world

Gazebo starts (gazebo_ros's gazebo.launch.py, an empty world unless `world` names one);
robot_state_publisher publishes the xacro-expanded robot as robot_description, on
simulated time; spawn_entity.py reads that topic and puts the robot into the world. The
robot's <gazebo> plugins then drive it from /cmd_vel and publish /odom, /joint_states,
/imu, /scan, the camera images and the depth camera's point cloud.
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import Command, LaunchConfiguration
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue


def generate_launch_description():
    share_dir = get_package_share_directory('fishbot_description')
    default_model = os.path.join(share_dir, 'urdf', 'fishbot', 'fishbot.urdf.xacro')
    gazebo_launch = os.path.join(
        get_package_share_directory('gazebo_ros'), 'launch', 'gazebo.launch.py'
    )

    model_arg = DeclareLaunchArgument(
        name='model',
        default_value=default_model,
        description='Absolute path to the xacro file of the robot to simulate',
    )
    world_arg = DeclareLaunchArgument(
        name='world',
        default_value='',
        description='Gazebo world file to load (empty: an empty world)',
    )

    # A string, not YAML: see display_robot.launch.py.
    robot_description = ParameterValue(
        Command(['xacro ', LaunchConfiguration('model')]),
        value_type=str,
    )

    robot_state_publisher = Node(
        package='robot_state_publisher',
        executable='robot_state_publisher',
        parameters=[{'robot_description': robot_description, 'use_sim_time': True}],
    )

    gazebo = IncludeLaunchDescription(
        PythonLaunchDescriptionSource(gazebo_launch),
        launch_arguments={'world': LaunchConfiguration('world'), 'verbose': 'true'}.items(),
    )

    spawn_entity = Node(
        package='gazebo_ros',
        executable='spawn_entity.py',
        arguments=['-topic', 'robot_description', '-entity', 'fishbot'],
        output='screen',
    )

    return LaunchDescription([
        model_arg,
        world_arg,
        robot_state_publisher,
        gazebo,
        spawn_entity,
    ])
