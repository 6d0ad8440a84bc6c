"""The items a pairs file yields: one module per kind, one failure base in `base.py`."""
