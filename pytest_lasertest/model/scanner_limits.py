"""What a scanner profile may hold, field by field: the values no scanner can have, and bounds
an order of magnitude beyond any real 2D scanner, so that no real profile is refused while a
typo that would cost hours or gigabytes is. Each check raises ProfileError naming the Gazebo
field, what is wrong and the fix."""

from __future__ import annotations

from pytest_lasertest.model.geometry import FULL_TURN, Pose3D

# Gazebo descriptions write a full turn as 6.28319, a little more than 2 pi.
FULL_TURN_SLACK = 1e-4  # rad
# The gate models a horizontal scan plane; Husky descriptions write roll = 3.14159, not pi.
MAX_TILT = 1e-3  # rad
# The densest 2D scanners give about 25,000 beams a scan (Pepperl+Fuchs R2000 at 0.014 deg); every
# scan of a run casts each beam, and the verifier holds arrays of scans x beams.
MAX_BEAMS = 100_000
# Real 2D scanners scan at 2-600 Hz (SICK LMS4000: 600 Hz), simulated ones are written faster
# (TurtleBot3's SDF: 1800 Hz); every scan along the path is judged. A pairs file bounds the
# scans along its route as well (pairsfile/pairs.py, MAX_SCANS).
MIN_UPDATE_RATE = 0.1  # Hz
MAX_UPDATE_RATE = 10_000.0  # Hz
# The longest-reaching 2D scanners reach about 300 m.
MAX_RANGE = 1000.0  # m
# Angles are written within a turn either way of zero.
MAX_ANGLE = FULL_TURN + FULL_TURN_SLACK  # rad


class ProfileError(ValueError):
    """A profile field has a value no scanner can have."""

    def __init__(self, field: str, problem: str, fix: str) -> None:
        super().__init__(f"{field}: {problem} ({fix})")
        self.field = field
        self.problem = problem
        self.fix = fix


def check_beams(samples: int, resolution: float) -> None:
    """N = samples x resolution must be a whole number of beams, at most MAX_BEAMS."""
    if samples < 1:
        raise ProfileError("samples", f"{samples} beams cannot scan", "set samples to at least 1")
    if samples > MAX_BEAMS:
        raise ProfileError("samples", *_too_many_beams(f"{samples}"))
    if resolution <= 0:
        raise ProfileError("resolution", f"{resolution} must be positive", "leave it out (1)")
    count = samples * resolution
    if count > MAX_BEAMS:
        raise ProfileError("resolution", *_too_many_beams(f"samples x resolution = {count:g}"))
    if count < 1 or abs(count - round(count)) > 1e-9 * count:
        raise ProfileError(
            "resolution",
            f"samples x resolution = {count:g} is not a whole number of beams",
            "choose samples and resolution whose product is a whole number",
        )


def _too_many_beams(what: str) -> tuple[str, str]:
    return (
        f"{what} beams a scan is more than the {MAX_BEAMS:,} the gate accepts: the densest real "
        "2D scanners give about 25,000, and every scan of every run casts each beam",
        f"write the scanner's beams per scan, at most {MAX_BEAMS:,} (e.g. 720)",
    )


def check_angles(min_angle: float, max_angle: float) -> None:
    """A field of view of at most a full turn, each end within a turn of zero (rad)."""
    if min_angle >= max_angle:
        raise ProfileError(
            "min_angle",
            f"min_angle ({min_angle} rad) must be less than max_angle ({max_angle} rad)",
            "swap them or correct one; angles are counter-clockwise, in radians",
        )
    field_of_view = max_angle - min_angle
    if field_of_view > FULL_TURN + FULL_TURN_SLACK:
        raise ProfileError(
            "max_angle",
            f"the field of view {field_of_view:.4f} rad exceeds a full turn",
            "keep max_angle - min_angle within 2 pi (6.2832 rad)",
        )
    for name, angle in (("min_angle", min_angle), ("max_angle", max_angle)):
        if abs(angle) > MAX_ANGLE:
            raise ProfileError(
                name,
                f"{angle} rad is more than a full turn (6.2832 rad) from zero",
                "write the angle in radians within [-2 pi, 2 pi], e.g. -2.35619 for -135 deg",
            )


def check_ranges(range_min: float, range_max: float, step: float) -> None:
    """0 <= range.min < range.max <= MAX_RANGE (m), and readings rounded to a step finer than
    the range."""
    if range_min < 0:
        raise ProfileError("range.min", f"{range_min} m is negative", "use 0 or more")
    if range_max <= range_min:
        raise ProfileError(
            "range.max",
            f"range.max ({range_max} m) must be greater than range.min ({range_min} m)",
            "raise range.max or lower range.min",
        )
    if range_max > MAX_RANGE:
        raise ProfileError(
            "range.max",
            f"{range_max:g} m is more than the {MAX_RANGE:g} m the gate accepts: the "
            "longest-reaching 2D scanners reach about 300 m",
            f"write the scanner's range in m, at most {MAX_RANGE:g} m (e.g. 30.0)",
        )
    if step < 0:
        raise ProfileError("range.resolution", f"{step} m is negative", "use 0 or more")
    if step >= range_max - range_min:
        raise ProfileError(
            "range.resolution",
            f"a reading step of {step:g} m is no finer than the whole range ({range_min:g}-"
            f"{range_max:g} m): every reading would round to the same few values",
            "write the step readings are rounded to, in m (real scanners: 0.001-0.03), "
            "or leave it out",
        )


def check_rate(rate: float) -> None:
    """A scan rate from MIN_UPDATE_RATE to MAX_UPDATE_RATE (Hz)."""
    if rate <= 0:
        raise ProfileError(
            "update_rate",
            f"{rate} Hz: a scanner must publish scans at a positive rate",
            "set the scan rate in Hz, e.g. 50",
        )
    if not MIN_UPDATE_RATE <= rate <= MAX_UPDATE_RATE:
        why = (
            "the fastest real 2D scanners scan at 600 Hz, and the gate judges every scan"
            if rate > MAX_UPDATE_RATE
            else "a scan every 10 s or less often leaves the robot blind"
        )
        raise ProfileError(
            "update_rate",
            f"{rate:g} Hz is outside the {MIN_UPDATE_RATE:g}-{MAX_UPDATE_RATE:g} Hz the gate "
            f"accepts: {why}",
            f"write the scan rate in Hz, from {MIN_UPDATE_RATE:g} to {MAX_UPDATE_RATE:g} (e.g. 50)",
        )


def check_noise(mean: float, stddev: float, range_min: float, range_max: float) -> None:
    """Gaussian noise narrower than the range (m)."""
    if stddev < 0:
        raise ProfileError("noise.stddev", f"{stddev} m is negative", "use 0 or more")
    for name, value in (("stddev", stddev), ("mean", mean)):
        if abs(value) >= range_max - range_min:
            raise ProfileError(
                f"noise.{name}",
                f"{value:g} m is as wide as the whole range ({range_min:g}-{range_max:g} m): "
                "the readings would be noise",
                f"write the noise's {name} in m (real scanners: a few mm to a few cm)",
            )


def check_mount(pose: Pose3D) -> None:
    """A mount the gate can model: on or above the ground, angles within a turn, the scan
    plane level."""
    z = pose.xyz[2]
    if z < 0:
        raise ProfileError(
            "pose.xyz",
            f"the scanner is mounted {-z:g} m below the ground (z = {z:g} m): the base frame "
            "(base_footprint) lies on the ground, so nothing stands below it",
            "write the scanner's height above the ground as z, in m (the Husky's is 0.44)",
        )
    if any(abs(angle) > MAX_ANGLE for angle in pose.rpy):
        raise ProfileError(
            "pose.rpy",
            f"an angle of {pose.rpy} rad is more than a full turn from zero",
            "write roll, pitch and yaw in radians within [-2 pi, 2 pi]",
        )
    if pose.tilt() > MAX_TILT:
        raise ProfileError(
            "pose.rpy",
            f"the scan plane is tilted by {pose.tilt():.3f} rad; the gate models horizontal scans",
            "mount the scanner level: pitch 0 and roll 0 (or pi when upside down)",
        )
