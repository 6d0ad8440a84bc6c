"""The schema of `robot:`, a bundled robot's name, a robot.yaml or a robot written in place, and
of the move_base and Nav2 parameters a `navigation:` sets."""

from __future__ import annotations

from pytest_lasertest.model.body import SHAPE_SIZES
from pytest_lasertest.model.robot import MAX_CORNERS, MAX_FOOTPRINT_REACH
from pytest_lasertest.nav.move_base.settings import LIMITS, parameter_types
from pytest_lasertest.nav.nav2.settings import NEWEST_JAZZY, RELEASES
from pytest_lasertest.pairsfile import body, robot
from pytest_lasertest.pairsfile.bundled import bundled_robots
from pytest_lasertest.pairsfile.nav2_params import NAV2_KEYS
from pytest_lasertest.pairsfile.navigation import MAY_BE_NEGATIVE, MUST_BE_POSITIVE
from pytest_lasertest.pairsfile.scan_filters import SCAN_FILTERS
from pytest_lasertest.pairsfile.schema.scanner import description_terms
from pytest_lasertest.pairsfile.schema.terms import (
    Schema,
    choice,
    keyed,
    listing,
    mapping,
    mounted,
    number,
    one_of,
    text,
    triple,
    truth,
)

# A coordinate of a footprint corner or a collision shape (m): no farther from the base.
_REACHED = {
    "type": "number",
    "minimum": -MAX_FOOTPRINT_REACH,
    "maximum": MAX_FOOTPRINT_REACH,
}
# The fields a robot needs whatever gives its laser mount.
ALWAYS_REQUIRED = tuple(
    key for key in robot.REQUIRED_KEYS if key not in ("name", "laser_mount", "body")
)


def robot_schema() -> Schema:
    """`robot:`: a bundled robot or a robot file by name, or a robot written in place."""
    named = text(
        "A bundled robot, or a robot.yaml (or its directory) relative to this file",
        examples=list(bundled_robots()),
    )
    return one_of("The robot both scanners are mounted on.", named, _in_place())


def _in_place() -> Schema:
    terms = {**description_terms("the robot's laser mount and body"), **_robot_terms()}
    described = [{"required": ["urdf"]}, {"required": ["sdf"]}]
    return mapping(
        "A robot written in place: a robot file's fields, where `urdf:` or `sdf:` stands for "
        "`laser_mount:` (and for `body:` and `name:` unless written).",
        keyed(robot.IN_PLACE_KEYS, terms),
        ALWAYS_REQUIRED,
        anyOf=[*described, {"required": ["name", "body", "laser_mount"]}],
    )


def _robot_terms() -> dict[str, Schema]:
    terms = {
        "name": text("How reports name the robot"),
        "body": _body(),
        "laser_mount": mounted("Where the laser sits in the robot's base frame", ("xyz", "rpy")),
        "footprint": _footprint(),
        "max_linear_velocity": number(robot.SPEED, "Its top forward speed"),
        "max_linear_acceleration": number(robot.ACCELERATION, "How hard it speeds up and brakes"),
        "max_angular_velocity": number(robot.TURN_RATE, "Its top turn rate"),
        "max_angular_acceleration": number(
            robot.ANGULAR_ACCELERATION, "How fast it starts turning"
        ),
        "footprint_padding": number(robot.PADDING, "How far costmaps pad the footprint outward"),
        "nominal_speed": number(
            robot.NOMINAL_SPEED, "The pace the solver plans along; the top speed if left out"
        ),
        "nominal_turn_rate": number(
            robot.NOMINAL_TURN_RATE, "The turn rate the solver plans with; the top one if left out"
        ),
        "reaction_time": number(
            robot.REACTION_TIME, "How long a scan takes to reach the wheels; 0.05 if left out"
        ),
        "navigation": text("A navigation.yaml of move_base parameters, relative to this file"),
        **_nav2_terms(),
    }
    return keyed(robot.ROBOT_KEYS, terms)


def _body() -> Schema:
    height = mapping(
        "A prism of the footprint, moved at the commanded twist.",
        {"height": number(body.BODY_HEIGHT, "Its height")},
        ("height",),
    )
    shapes = listing("Its collision shapes, in base_footprint.", _collision(), least=1)
    collisions = mapping(
        "Its description's collision shapes, driven through those marked `wheel: true`.",
        {"collisions": {**shapes, "maxItems": body.MAX_COLLISIONS}},
        ("collisions",),
    )
    husky = choice(["husky"], "pybullet_data's Husky, driven through its wheels")
    return one_of("The body the simulator drives.", husky, height, collisions)


def _collision() -> Schema:
    size = {
        "type": "array",
        "items": number(body.LENGTH, "A side"),
        "minItems": 3,
        "maxItems": 3,
        "description": "Its sides along x, y and z (m)",
    }
    shapes = {"box": mapping("A box.", {"size": size}, ("size",))}
    for shape in ("cylinder", "sphere"):
        names = SHAPE_SIZES[shape]
        lengths = {name: number(body.LENGTH, f"Its {name}") for name in names}
        shapes[shape] = mapping(f"A {shape}.", lengths, names)
    xyz = triple("m", "Its centre in base_footprint")
    terms = {
        **shapes,
        "xyz": {**xyz, "items": _REACHED},
        "rpy": triple("rad", "Its roll, pitch and yaw; 0 0 0 when left out"),
        "wheel": truth("Whether the base rolls on it, about its axis; false when left out"),
    }
    return mapping(
        "One collision shape, placed as URDF places it.",
        terms,
        ("xyz",),
        oneOf=[{"required": [shape]} for shape in shapes],
    )


def _footprint() -> Schema:
    corner = {
        "type": "array",
        "items": _REACHED,
        "minItems": 2,
        "maxItems": 2,
        "description": "A corner [x, y] in the robot's base frame (m)",
    }
    return listing(
        "The convex outline around the base origin, as costmap_2d's `footprint`.",
        corner,
        least=3,
        most=MAX_CORNERS,
    )


def _nav2_terms() -> dict[str, Schema]:
    patches = "|".join(str(patch) for patch in range(NEWEST_JAZZY + 1))
    releases = {
        "type": "string",
        "pattern": rf"^1\.3\.0*({patches})$",
        "description": f"A Jazzy release number, 1.3.0 to 1.3.{NEWEST_JAZZY}",
    }
    terms = {
        "nav2": text("A Nav2 params file (as nav2_bringup's), relative to this file"),
        "nav2_version": one_of(
            "The Nav2 release whose obstacle marking the imitation follows.",
            choice(list(RELEASES), "A distribution's release"),
            releases,
        ),
    }
    return keyed(NAV2_KEYS, terms)


def navigation() -> Schema:
    """`navigation:`: move_base parameters by section, a Nav2 params file and release, and a
    laser_filters params file."""
    sections = {
        section: mapping(
            f"move_base's `{section}` parameters, by their ROS names, as the ROS 1 "
            "packages document them.",
            {name: _parameter(section, name, kind) for name, kind in parameters.items()},
        )
        for section, parameters in parameter_types().items()
    }
    scan_filters = text(
        "A laser_filters params file (ROS 1 or ROS 2), relative to this file: its chain runs "
        "on every scan before the stack"
    )
    terms = {**sections, **_nav2_terms(), SCAN_FILTERS: scan_filters}
    return mapping("Navigation parameters set over the robot's.", terms)


def _parameter(section: str, name: str, kind: type) -> Schema:
    if kind is bool:
        return truth("")
    limit = LIMITS[section][name]
    term: Schema = {
        "type": "integer" if kind is int else "number",
        "minimum": limit.low if name in MAY_BE_NEGATIVE else max(limit.low, 0.0),
        "maximum": limit.high,
        "description": f"In {limit.unit}" if limit.unit else "",
    }
    if name in MUST_BE_POSITIVE and term["minimum"] <= 0:
        del term["minimum"]
        term["exclusiveMinimum"] = 0
    return term
