"""Robot descriptions: URDF, xacro and SDF lasers with their mounts, read from the working
tree or at a git revision."""
