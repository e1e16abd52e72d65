"""gazebo_ros stand-in: Gazebo's server command line to tianracer_sim's node."""
