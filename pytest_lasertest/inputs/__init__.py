"""What every file reader shares: values that know the file and line that wrote them, typed
reads that fail naming both, YAML with line numbers, and profile fields built into a
LaserProfile."""
