"""Nav2 (ROS 2) navigation, as its packages do it: being built; see obstacle_layer.py."""
