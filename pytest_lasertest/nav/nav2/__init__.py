"""Nav2 (ROS 2) as Jazzy's nav2_bringup runs it, beside move_base: `nav2.Nav2` drives it."""
