"""How a number reads in a message to the user: whole numbers in full, a number too long to
read shortened to its first digits and its length. Every layer's messages share it, the files'
readers and the navigation stacks' parameter readers alike."""

from __future__ import annotations

import math


def shown(value: float) -> str:
    """A number as a message shows it: whole numbers in full up to 15 digits, else as %g; an
    integer of more digits (YAML reads any length) as `1000... (401 digits)`."""
    if isinstance(value, int) and abs(value) >= 10**15:
        return f"{str(value)[:4]}... ({len(str(abs(value)))} digits)"
    if isinstance(value, int) or (
        math.isfinite(value) and value == round(value) and abs(value) < 1e15
    ):
        return str(int(value))
    return f"{value:g}"
