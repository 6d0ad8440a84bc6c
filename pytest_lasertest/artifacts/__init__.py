"""Evidence files for failing items, written atomically below `--laser-artifacts`."""
