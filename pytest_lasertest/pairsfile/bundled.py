"""The robots and scanner catalogue shipped inside the package, resolved by name."""

from __future__ import annotations

from pathlib import Path

ROBOTS_DIR = Path(__file__).resolve().parents[1] / "robots"
LIDARS_DIR = ROBOTS_DIR / "lidars"
ROBOT_FILE = "robot.yaml"


def bundled_robots() -> dict[str, Path]:
    """Bundled robot names and their robot.yaml, sorted by name."""
    return {path.parent.name: path for path in sorted(ROBOTS_DIR.glob(f"*/{ROBOT_FILE}"))}
