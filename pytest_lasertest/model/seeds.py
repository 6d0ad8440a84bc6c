"""Seeds: the range `--laser-seed` takes, and the independent scan-noise draws a run's seed
gives (`noise_seed`)."""

from __future__ import annotations

import hashlib

MAX_SEED = 2**32 - 1


def whole_seed(text: str) -> int | None:
    """`text` as a seed, a whole number from 0 to MAX_SEED; None if it is none."""
    try:
        seed = int(text, 10)
    except ValueError:
        return None
    return seed if 0 <= seed <= MAX_SEED else None


def noise_seed(seed: int, draw: int) -> int:
    """The scan-noise seed of draw `draw` of a run seeded `seed`: draw 0 is the run's own, and
    each further one is independent of it and of the others."""
    if draw == 0:
        return seed
    digest = hashlib.sha256(f"lasertest-redraw:{seed}:{draw}".encode()).digest()
    return int.from_bytes(digest[:4], "big")
