"""What every file reader shares: values that know the file and line they were written on, typed reads that fail naming them, YAML with line numbers, and profile fields built into a LaserProfile."""
