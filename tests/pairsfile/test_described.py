"""Scanners read from robot descriptions in a pairs file (`pairsfile/described.py`): `urdf:` (or
`sdf:`), at a git `ref:`, with xacro `args:` and `packages:`, and profile fields that override
what the description says; broken descriptions are collection errors naming their line."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pytest

from tests.helpers.git import commit_everything, git
from tests.helpers.runs import assert_one_clean_error
from tests.helpers.texts import PAIRS, ROBOT, XACRO_LIDAR, XACRO_ROBOT


def test_a_pair_read_from_one_description_at_two_revisions_compares_them(
    pytester: pytest.Pytester, repository: Path
) -> None:
    robot = repository / "robot.urdf"
    robot.write_text(ROBOT.replace("<samples>32</samples>", "<samples>16</samples>"))
    result = pytester.runpytest("-k", "coverage", "--laser-seed=1", "--laser-policy=candidate")
    result.assert_outcomes(failed=1)
    head = git(repository, "rev-parse", "--short=7", "HEAD")
    result.stdout.fnmatch_lines(
        [
            f"  baseline   front in robot.urdf at HEAD ({head}): 32 beams over *, "
            "scan plane 0.300 m",
            "  candidate  front in robot.urdf: 16 beams over *",
            "    beam spacing: *(16 beams, was 32)",
        ]
    )


def test_profile_fields_next_to_urdf_override_what_the_description_says(
    pytester: pytest.Pytester, repository: Path
) -> None:
    (repository / "gate.lasertest.yaml").write_text(
        PAIRS.replace(
            "candidate: {urdf: robot.urdf}",
            "candidate: {urdf: robot.urdf, range: {max: 5.0}, "
            "pose: {xyz: [0.3, 0.0, 0.5], rpy: [0.0, 0.0, 0.0]}}",
        )
    )
    result = pytester.runpytest("-k", "coverage", "--laser-seed=1", "--laser-policy=candidate")
    result.stdout.fnmatch_lines(["  candidate  front in robot.urdf: *range 0.10-5.00 m*0.500 m"])


@pytest.fixture
def xacro_robot(pytester: pytest.Pytester) -> Path:
    """robot.urdf.xacro, whose laser macro lives in package `lidars` (directory lidar_pkg)."""
    (pytester.path / "lidar_pkg").mkdir()
    (pytester.path / "lidar_pkg" / "front.xacro").write_text(XACRO_LIDAR)
    path = pytester.path / "robot.urdf.xacro"
    path.write_text(XACRO_ROBOT)
    return path


def test_a_xacro_description_is_expanded_with_its_args_and_packages(
    pytester: pytest.Pytester, xacro_robot: Path
) -> None:
    (pytester.path / "gate.lasertest.yaml").write_text(
        "robot: husky\nworld: {start: {x: 0, y: 0}, goal: {x: 6, y: 0}, time_limit: 30}\n"
        "pairs:\n  fewer:\n"
        "    baseline: {urdf: robot.urdf.xacro, args: {laser_enabled: true}, "
        "packages: {lidars: lidar_pkg}}\n"
        "    candidate: {urdf: robot.urdf.xacro, args: {laser_enabled: 1}, "
        "packages: {lidars: lidar_pkg}, samples: 32}\n"
    )
    result = pytester.runpytest("-k", "coverage", "--laser-seed=1", "--laser-policy=candidate")
    result.stdout.fnmatch_lines(
        [
            "  baseline   front in robot.urdf.xacro: 64 beams over [[]-2.000, 2.000[]] rad, "
            "range 0.20-12.00 m, 10 Hz, scan plane 0.400 m, upside down",
            "  candidate  front in robot.urdf.xacro: 32 beams *",
        ]
    )


@dataclass(frozen=True)
class Broken:
    """A description (or scanner entry) that cannot be read, and the error it must give."""

    files: dict[str, str]  # file name -> text, next to the pairs file
    scanner: str  # the candidate's YAML
    path: str  # the file the error names
    line: int
    problem: str
    fix: str


TWO_LASERS = ROBOT.replace(
    "</robot>",
    '  <gazebo reference="laser">\n    <sensor type="ray" name="rear">\n'
    "      <ray><scan><horizontal><samples>8</samples><min_angle>-1</min_angle>"
    "<max_angle>1</max_angle></horizontal></scan><range><min>0.1</min><max>5</max></range>"
    "</ray>\n    </sensor>\n  </gazebo>\n</robot>",
)
ENTITY_BOMB = """\
<?xml version="1.0"?>
<!DOCTYPE robot [
  <!ENTITY lol "lol">
  <!ENTITY lol1 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
  <!ENTITY lol2 "&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;">
]>
<robot name="&lol2;"/>
"""
BROKEN = {
    "no laser": Broken(
        {"robot.urdf": ROBOT.replace('type="ray"', 'type="imu"')},
        "{urdf: robot.urdf}",
        "robot.urdf",
        1,
        "no laser: the description has no Gazebo laser sensor, only imu 'front'",
        "point `urdf:` at the robot description that holds the laser's <sensor>",
    ),
    "two lasers and no sensor choice": Broken(
        {"robot.urdf": TWO_LASERS},
        "{urdf: robot.urdf}",
        "gate.lasertest.yaml",
        6,
        "robot.urdf has 2 2D lasers: 'front' (line 17), 'rear' (line 30)",
        "say which one the gate reads with `sensor: NAME`",
    ),
    "a sensor name the description lacks": Broken(
        {"robot.urdf": TWO_LASERS},
        "{urdf: robot.urdf, sensor: back}",
        "gate.lasertest.yaml",
        6,
        "robot.urdf has no laser sensor or link named 'back'",
        "its lasers: 'front', 'rear'",
    ),
    "a file that is no robot description": Broken(
        {"robot.urdf": "<?xml version='1.0'?>\n<launch>\n  <arg name='x'/>\n</launch>\n"},
        "{urdf: robot.urdf}",
        "robot.urdf",
        2,
        "the root element is <launch>: this is neither a URDF (<robot>) nor an SDFormat file",
        "point `urdf:` at the robot's URDF, xacro or SDF file",
    ),
    "malformed XML": Broken(
        {"robot.urdf": ROBOT.replace("</horizontal></scan>", "</scan>")},
        "{urdf: robot.urdf}",
        "robot.urdf",
        24,
        "this is not well-formed XML: mismatched tag (line 24, column 11)",
        "every tag closed",
    ),
    "an XML entity bomb": Broken(
        {"robot.urdf": ENTITY_BOMB},
        "{urdf: robot.urdf}",
        "robot.urdf",
        3,
        "the file declares the XML entity 'lol'; entities are refused, not expanded",
        "remove the <!DOCTYPE ...> block",
    ),
    "an unknown xacro macro": Broken(
        {"robot.urdf.xacro": XACRO_ROBOT.replace("xacro:front_laser", "xacro:back_laser")},
        "{urdf: robot.urdf.xacro, args: {laser_enabled: 1}, packages: {lidars: lidar_pkg}}",
        "robot.urdf.xacro",
        7,
        "xacro cannot expand it: unknown macro name: xacro:back_laser",
        "run `xacro FILE` by hand",
    ),
    "a package the pairs file does not map": Broken(
        {},
        "{urdf: robot.urdf.xacro}",
        "robot.urdf.xacro",
        4,
        "the description needs the ROS package 'lidars' ($(find lidars)), which the pairs file "
        "does not map to a directory",
        "`packages: {lidars: path/to/lidars}`",
    ),
    "an include that does not exist": Broken(
        {},
        "{urdf: robot.urdf.xacro, packages: {lidars: .}}",
        "robot.urdf.xacro",
        4,
        "it includes front.xacro, which does not exist",
        "check the include's path",
    ),
    "a laser a xacro arg leaves off": Broken(
        {},
        "{urdf: robot.urdf.xacro, packages: {lidars: lidar_pkg}}",
        "robot.urdf.xacro",
        1,
        "no laser: the description has no Gazebo laser sensor; these xacro args may switch one "
        "on: laser_enabled (default '0'); set one under `args:`, e.g. `args: {laser_enabled: 1}`",
        "point `urdf:` at the robot description that holds the laser's <sensor>",
    ),
    "a 3D lidar": Broken(
        {
            "robot.urdf": ROBOT.replace(
                "</horizontal></scan>",
                "</horizontal><vertical><samples>16</samples></vertical></scan>",
            )
        },
        "{urdf: robot.urdf}",
        "robot.urdf",
        24,
        "the sensor 'front' scans 16 vertical samples: it is a 3D lidar",
        "choose a 2D laser",
    ),
    "a value that is not a number": Broken(
        {"robot.urdf": ROBOT.replace("<max>10.0</max>", "<max>ten</max>")},
        "{urdf: robot.urdf}",
        "robot.urdf",
        25,
        "<max> holds 'ten', not a number",
        "write a number in <max>",
    ),
    "a description that does not exist": Broken(
        {},
        "{urdf: robots/missing.urdf}",
        "robots/missing.urdf",
        1,
        "robots/missing.urdf does not exist",
        "check the path (relative to the pairs file)",
    ),
    "a ref that does not exist": Broken(
        {},
        "{urdf: robot.urdf, ref: origin/mian}",
        "gate.lasertest.yaml",
        6,
        "the ref 'origin/mian' names no commit in the repository",
        "fetch-depth: 0",
    ),
    "a ref that looks like an option": Broken(
        {},
        "{urdf: robot.urdf, ref: '--upload-pack=touch pwned'}",
        "gate.lasertest.yaml",
        6,
        "the ref '--upload-pack=touch pwned' starts with '-', so git would read it as an option",
        "write a branch, tag or commit",
    ),
    "a file the revision lacks": Broken(
        {"new.urdf": ROBOT},
        "{urdf: new.urdf, ref: HEAD}",
        "new.urdf",
        1,
        "new.urdf at HEAD (",
        "check the path",
    ),
    "a catalogue model and a description at once": Broken(
        {},
        "{urdf: robot.urdf, model: sick_lms111}",
        "gate.lasertest.yaml",
        6,
        "a scanner is read from a catalogue `model:` or from a description, not both",
        "drop `model:`",
    ),
    "a ref without a description": Broken(
        {},
        "{model: sick_lms111, ref: HEAD}",
        "gate.lasertest.yaml",
        6,
        "`ref:` belongs to a scanner read from a robot description",
        "add `urdf: PATH`",
    ),
    "xacro args that are not a mapping": Broken(
        {},
        "{urdf: robot.urdf, args: [laser_enabled]}",
        "gate.lasertest.yaml",
        6,
        "expected a mapping of xacro args, NAME: VALUE, got a list",
        "write `key: value` pairs",
    ),
}


@pytest.mark.parametrize("case", BROKEN.values(), ids=BROKEN.keys())
def test_a_description_that_cannot_be_read_is_one_collection_error_naming_its_line(
    pytester: pytest.Pytester, repository: Path, xacro_robot: Path, case: Broken
) -> None:
    for name, text in case.files.items():
        (repository / name).write_text(text)
    (repository / "gate.lasertest.yaml").write_text(
        PAIRS.replace("candidate: {urdf: robot.urdf}", f"candidate: {case.scanner}")
    )
    result = pytester.runpytest()
    assert_one_clean_error(result, case.line, "", case, file=case.path)
    if case.path != "gate.lasertest.yaml":
        # The description's own line first, then the scanner that read it.
        result.stdout.fnmatch_lines(
            [f"{case.path}:*(read for pairs.swap.candidate.urdf at gate.lasertest.yaml:6)"]
        )
    assert not (repository / "pwned").exists()


def test_a_file_that_only_defines_the_laser_macro_says_nobody_calls_it(
    pytester: pytest.Pytester, xacro_robot: Path
) -> None:
    (pytester.path / "gate.lasertest.yaml").write_text(
        PAIRS.replace("{urdf: robot.urdf, ref: HEAD}", "{urdf: lidar_pkg/front.xacro}")
    )
    result = pytester.runpytest()
    result.stdout.fnmatch_lines(
        [
            "lidar_pkg/front.xacro:3: no laser: the description only defines the xacro macro "
            "'front_laser' (line 3), which holds a laser sensor, and nothing calls it *",
            "  fix: point `urdf:` at the robot description that calls the macro, or at a file "
            "of your own that includes this one and calls <xacro:front_laser .../>",
        ]
    )


def test_a_macro_called_without_the_xacro_prefix_is_named_with_the_fix(
    pytester: pytest.Pytester, xacro_robot: Path
) -> None:
    # ROS kinetic's xacro expanded <front_laser/>; xacro 1.14 and later leave it as it is.
    xacro_robot.write_text(XACRO_ROBOT.replace("<xacro:front_laser", "<front_laser"))
    (pytester.path / "gate.lasertest.yaml").write_text(
        PAIRS.replace(
            "{urdf: robot.urdf, ref: HEAD}",
            "{urdf: robot.urdf.xacro, args: {laser_enabled: 1}, packages: {lidars: lidar_pkg}}",
        )
    )
    result = pytester.runpytest()
    result.stdout.fnmatch_lines(
        [
            "robot.urdf.xacro:7: no laser: the macro call <front_laser> has no `xacro:` "
            "prefix, and xacro 1.14 and later leave such calls unexpanded *",
            "  fix: write <xacro:front_laser .../> for each such call: <front_laser> (line 7)",
        ]
    )


def test_a_description_at_a_ref_includes_its_files_as_that_revision_holds_them(
    pytester: pytest.Pytester, xacro_robot: Path
) -> None:
    commit_everything(pytester.path)
    # Only the included file changes: the top file is the same at HEAD and in the working tree.
    included = pytester.path / "lidar_pkg" / "front.xacro"
    included.write_text(XACRO_LIDAR.replace("samples:=64", "samples:=32"))
    scanner = "urdf: robot.urdf.xacro, args: {laser_enabled: 1}, packages: {lidars: lidar_pkg}"
    (pytester.path / "gate.lasertest.yaml").write_text(
        "robot: husky\nworld: {start: {x: 0, y: 0}, goal: {x: 6, y: 0}, time_limit: 30}\n"
        f"pairs:\n  fewer:\n    baseline: {{{scanner}, ref: HEAD}}\n"
        f"    candidate: {{{scanner}}}\n"
    )
    result = pytester.runpytest("-k", "coverage", "--laser-seed=1", "--laser-policy=candidate")
    result.stdout.fnmatch_lines(
        [
            "  baseline   front in robot.urdf.xacro at HEAD (*): 64 beams *",
            "  candidate  front in robot.urdf.xacro: 32 beams *",
        ]
    )
