"""A test-only stand-in for ROS 2's ament_index_python, so the real xacro command resolves
$(find NAME) in reference runs. Packages come from FISHBOT_TEST_PACKAGES (NAME=PATH entries
separated by os.pathsep)."""
