"""Robot descriptions a hostile (or careless) user writes: a `ref:` that cannot apply, a FIFO, a
device, a huge or binary file, a symlink loop, a xacro that expands without end, a URDF whose
joints do not make a tree. Each is one collection error naming the file and line, never a hang,
a traceback or a silent pass; real descriptions still read as before."""

from __future__ import annotations

import os
import threading
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

import pytest
import xacro

from pytest_lasertest.descriptions.lasers import DescriptionFile, read_lasers
from pytest_lasertest.descriptions.readers import WorkingTree
from pytest_lasertest.descriptions.xacro_expand import ORIGIN, expand_xacro
from pytest_lasertest.descriptions.xmlfile import XmlElement, parse_xml
from pytest_lasertest.inputs.errors import SpecError
from pytest_lasertest.inputs.files import read_regular_file
from tests.helpers.git import commit_everything, git
from tests.helpers.runs import NO_PLACEMENTS, assert_one_clean_error
from tests.helpers.texts import PAIRS, ROBOT

XACRO_HEAD = (
    '<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
    '  <link name="base_footprint"/>\n'
)


def xacro_file(*body: str) -> str:
    """A xacro description: the head (3 lines), then `body`, one line each."""
    return XACRO_HEAD + "".join(f"{line}\n" for line in body) + "</robot>\n"


def doubling(levels: int, call: str) -> list[str]:
    """Macros m1..m{levels}, each calling the one below it twice; m0 is `call`."""
    return [
        f'  <xacro:macro name="m0">{call}</xacro:macro>',
        *(
            f'  <xacro:macro name="m{i}"><xacro:m{i - 1}/><xacro:m{i - 1}/></xacro:macro>'
            for i in range(1, levels + 1)
        ),
    ]


def blocks_doubling(levels: int) -> list[str]:
    """Macros b1..b{levels}, each passing its block on to the one below it twice."""
    return [
        '  <xacro:macro name="b0" params="*body"><xacro:insert_block name="body"/></xacro:macro>',
        *(
            f'  <xacro:macro name="b{i}" params="*body"><xacro:b{i - 1}><w>'
            '<xacro:insert_block name="body"/><xacro:insert_block name="body"/>'
            f"</w></xacro:b{i - 1}></xacro:macro>"
            for i in range(1, levels + 1)
        ),
    ]


def with_joint(parent: str, name: str = "extra_joint") -> str:
    """ROBOT with one more joint (lines 16-19) that makes `parent` the laser's parent."""
    return ROBOT.replace(
        '  <gazebo reference="laser">',
        f'  <joint name="{name}" type="fixed">\n    <parent link="{parent}"/>\n'
        '    <child link="laser"/>\n  </joint>\n  <gazebo reference="laser">',
    )


def symlink_loop(directory: Path) -> None:
    (directory / "loop_a.urdf").symlink_to("loop_b.urdf")
    (directory / "loop_b.urdf").symlink_to("loop_a.urdf")


def larger_than_16_mb(directory: Path) -> None:
    with (directory / "huge.urdf").open("wb") as file:
        file.truncate(16 * 1024 * 1024 + 1)  # sparse: no disk, and read only to the limit


@dataclass(frozen=True)
class Hostile:
    """A description (or scanner entry) that must not be read, and the error it must give."""

    files: dict[str, str | bytes]  # file name -> contents, next to the pairs file
    scanner: str  # the candidate's YAML
    path: str  # the file the error names
    line: int
    problem: str
    fix: str
    make: Callable[[Path], None] = field(default=lambda _: None)  # what files cannot say


HOSTILE = {
    "a character device that never ends": Hostile(
        {},
        "{urdf: /dev/zero}",
        "/dev/zero",
        1,
        "/dev/zero is a character device, which may never end",
        "point `urdf:` (or the include) at the description file itself",
    ),
    "a file over the size limit": Hostile(
        {},
        "{urdf: huge.urdf}",
        "huge.urdf",
        1,
        "huge.urdf is larger than 16 MB, the most the gate reads of a description file",
        "robot descriptions are kilobytes",
        larger_than_16_mb,
    ),
    "a directory": Hostile(
        {},
        "{urdf: robots}",
        "robots",
        1,
        "robots is a directory, not a file",
        "at the description file itself",
        lambda directory: (directory / "robots").mkdir(),
    ),
    "a symbolic link loop": Hostile(
        {},
        "{urdf: loop_a.urdf}",
        "loop_a.urdf",
        1,
        "loop_a.urdf is a symbolic link that leads round in a loop",
        "`ls -l` shows where each link goes",
        symlink_loop,
    ),
    "a path holding a NUL character": Hostile(
        {},
        '{urdf: "robot\\0.urdf"}',
        "gate.lasertest.yaml",
        6,
        "the path 'robot\\x00.urdf' holds a NUL character, which no file name can hold",
        "write the path as it is on disk",
    ),
    "a binary file": Hostile(
        {"mesh.urdf": b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR" + bytes(range(256))},
        "{urdf: mesh.urdf}",
        "mesh.urdf",
        1,
        "this is not a text file: it holds NUL bytes (is it a mesh, an image or an archive?)",
        "point `urdf:` (or the include) at the robot's URDF, xacro or SDF file",
    ),
    "a Latin-1 file read as UTF-8": Hostile(
        {"latin.urdf": ROBOT.replace('name="front"', 'name="fr\xf6nt"').encode("latin-1")},
        "{urdf: latin.urdf}",
        "latin.urdf",
        17,
        "this file is not UTF-8: byte 0xf6 on this line is no UTF-8 character",
        'encoding="ISO-8859-1"',
    ),
    "elements nested 100,000 deep": Hostile(
        {"deep.urdf": '<?xml version="1.0"?>\n<robot name="r">\n' + "<a>" * 100_000},
        "{urdf: deep.urdf}",
        "deep.urdf",
        3,
        "elements nest more than 100 deep here",
        "close the elements left open above this line",
    ),
    "a link with two parent joints": Hostile(
        {"robot.urdf": with_joint("base_footprint")},
        "{urdf: robot.urdf}",
        "robot.urdf",
        16,
        "link 'laser' has two parent joints: 'laser_joint' (line 11) and 'extra_joint'",
        "a URDF is a tree: give every link one parent joint",
    ),
    "a joint whose parent link is not defined": Hostile(
        {"robot.urdf": ROBOT.replace('<parent link="base_link"/>', '<parent link="chassis"/>')},
        "{urdf: robot.urdf}",
        "robot.urdf",
        11,
        "joint 'laser_joint' names the parent link 'chassis', which this description does not "
        "define",
        'define <link name="chassis"/>, or correct the joint\'s <parent link="...">',
    ),
    "a sensor pose with an absurd angle": Hostile(
        {"robot.urdf": ROBOT.replace("<update_rate>", "<pose>0 0 0 0 0 1e200</pose><update_rate>")},
        "{urdf: robot.urdf}",
        "robot.urdf",
        18,
        "<pose> holds '0 0 0 0 0 1e200': a number beyond 1e+06 (m or rad), which no frame of a "
        "robot holds",
        "write the pose in m and rad",
    ),
    "a macro that calls itself without end": Hostile(
        {
            "robot.urdf.xacro": xacro_file(
                '  <xacro:macro name="forever" params="n">',
                '    <xacro:forever n="${n+1}"/>',
                "  </xacro:macro>",
                '  <xacro:forever n="0"/>',
            )
        },
        "{urdf: robot.urdf.xacro}",
        "robot.urdf.xacro",
        5,
        "the macro 'forever' calls itself without end (forever -> forever): macros nest more "
        "than 50 deep",
        "give the recursion an end",
    ),
    "a macro that expands 2^22 times": Hostile(
        {"robot.urdf.xacro": xacro_file(*doubling(22, "<link/>"), "  <xacro:m22/>")},
        "{urdf: robot.urdf.xacro}",
        "robot.urdf.xacro",
        27,
        "expanding <xacro:m22> makes more than 10000 macro calls (the last through "
        "<xacro:m22> -> <xacro:m21> -> <xacro:m20> -> ... -> ",
        "call each macro once per part it makes; the gate stops at 10000",
    ),
    "a block inserted twice per level": Hostile(
        {"robot.urdf.xacro": xacro_file(*blocks_doubling(20), "  <xacro:b20><link/></xacro:b20>")},
        "{urdf: robot.urdf.xacro}",
        "robot.urdf.xacro",
        25,
        "expanding <xacro:b20> makes more than 50000 XML elements",
        "the gate expands at most 50000",
    ),
    "a file that includes itself": Hostile(
        {"robot.urdf.xacro": xacro_file('  <xacro:include filename="robot.urdf.xacro"/>')},
        "{urdf: robot.urdf.xacro}",
        "robot.urdf.xacro",
        4,
        "robot.urdf.xacro includes itself, so the expansion would never end",
        "remove the include of the file from itself",
    ),
    "two files that include each other": Hostile(
        {
            "robot.urdf.xacro": xacro_file('  <xacro:include filename="b.xacro"/>'),
            "b.xacro": xacro_file('  <xacro:include filename="robot.urdf.xacro"/>'),
        },
        "{urdf: robot.urdf.xacro}",
        "b.xacro",
        4,
        "it includes robot.urdf.xacro, which is already being included: the includes form a "
        "loop (robot.urdf.xacro -> b.xacro -> robot.urdf.xacro)",
        "remove the include that leads back",
    ),
    "an include of a directory": Hostile(
        {"robot.urdf.xacro": xacro_file('  <xacro:include filename="robots"/>')},
        "{urdf: robot.urdf.xacro}",
        "robot.urdf.xacro",
        4,
        "it includes a file that cannot be used: robots is a directory, not a file",
        "at the description file itself",
        lambda directory: (directory / "robots").mkdir(),
    ),
    "an unset environment variable": Hostile(
        {"robot.urdf.xacro": xacro_file('  <link name="$(env LASERTEST_UNSET_VARIABLE)"/>')},
        "{urdf: robot.urdf.xacro}",
        "robot.urdf.xacro",
        4,
        "the description reads the environment variable LASERTEST_UNSET_VARIABLE ($(env "
        "LASERTEST_UNSET_VARIABLE)), which is not set",
        "set LASERTEST_UNSET_VARIABLE where the gate runs, or give it a default",
    ),
    "a laser on a joint that turns": Hostile(
        {
            "turning.urdf": ROBOT.replace(
                'name="laser_joint" type="fixed"', 'name="laser_joint" type="continuous"'
            )
        },
        "{urdf: turning.urdf}",
        "turning.urdf",
        11,
        "the sensor's link 'laser' hangs on the continuous joint 'laser_joint': its pose moves "
        "with the joint",
        "mount the scanner on fixed joints",
    ),
    "a laser on a joint that tilts": Hostile(
        {
            "tilting.urdf": ROBOT.replace(
                '<joint name="laser_joint" type="fixed">',
                '<joint name="laser_joint" type="revolute">\n    <axis xyz="0 1 0"/>\n'
                '    <limit lower="-0.5" upper="0.5" effort="1.0" velocity="1.0"/>',
            )
        },
        "{urdf: tilting.urdf}",
        "tilting.urdf",
        11,
        "the sensor's link 'laser' hangs on the revolute joint 'laser_joint': its pose moves "
        "with the joint",
        "mount the scanner on fixed joints",
    ),
    "a second root link": Hostile(
        {
            "two_roots.urdf": ROBOT.replace(
                '  <link name="laser"/>', '  <link name="laser"/>\n  <link name="spare"/>'
            )
        },
        "{urdf: two_roots.urdf}",
        "two_roots.urdf",
        11,
        "link 'spare' is a second root link: no joint joins it to 'base_footprint'",
        "join 'spare' to the robot with a joint, or remove it",
    ),
}


@pytest.mark.parametrize("case", HOSTILE.values(), ids=HOSTILE.keys())
def test_a_hostile_description_is_one_collection_error_naming_its_file_and_line(
    pytester: pytest.Pytester, repository: Path, monkeypatch: pytest.MonkeyPatch, case: Hostile
) -> None:
    monkeypatch.delenv("LASERTEST_UNSET_VARIABLE", raising=False)
    for name, contents in case.files.items():
        path = repository / name
        path.write_bytes(contents if isinstance(contents, bytes) else contents.encode())
    case.make(repository)
    (repository / "gate.lasertest.yaml").write_text(
        PAIRS.replace("candidate: {urdf: robot.urdf}", f"candidate: {case.scanner}")
    )
    result = pytester.runpytest()
    assert_one_clean_error(result, case.line, "", case, file=case.path)
    if case.path != "gate.lasertest.yaml":
        result.stdout.fnmatch_lines(["*(read for pairs.swap.candidate.urdf at *:6)"])
    # xacro's own words come once, without the class of its exception.
    result.stdout.no_fnmatch_line("*<class *")


@pytest.fixture
def fifo(pytester: pytest.Pytester) -> Iterator[Path]:
    """A FIFO, and a watchdog that writes to it after 30 s, so that a reader blocked on it
    reads and fails instead of hanging the test run."""
    path = pytester.path / "fifo.urdf"
    os.mkfifo(path)

    def unblock() -> None:
        try:
            descriptor = os.open(path, os.O_WRONLY | os.O_NONBLOCK)
        except OSError:  # no reader is waiting
            return
        os.close(descriptor)

    watchdog = threading.Timer(30.0, unblock)
    watchdog.start()
    yield path
    watchdog.cancel()


def test_a_fifo_named_as_a_description_is_refused_before_it_is_opened_for_reading(
    pytester: pytest.Pytester, repository: Path, fifo: Path
) -> None:
    (repository / "gate.lasertest.yaml").write_text(
        PAIRS.replace("candidate: {urdf: robot.urdf}", "candidate: {urdf: fifo.urdf}")
    )
    result = pytester.runpytest()
    assert_one_clean_error(
        result,
        1,
        "",
        Hostile({}, "", "", 1, "fifo.urdf is a FIFO (named pipe), which would wait", "itself"),
        file="fifo.urdf",
    )


def test_an_include_of_a_fifo_is_refused_at_the_including_line(fifo: Path) -> None:
    top = fifo.parent / "robot.urdf.xacro"
    top.write_text(xacro_file('  <xacro:include filename="fifo.urdf"/>'))
    with pytest.raises(SpecError) as raised:
        read_lasers(DescriptionFile(top, WorkingTree()))
    assert (raised.value.location.path, raised.value.location.line) == (top, 4)
    assert raised.value.problem == (
        "it includes a file that cannot be used: fifo.urdf is a FIFO (named pipe), which would "
        "wait for a writer for ever"
    )


def outside_repository(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """ROBOT in a directory no git repository holds."""
    directory = tmp_path_factory.mktemp("outside")
    (directory / "robot.urdf").write_text(ROBOT)
    return directory / "robot.urdf"


def test_a_ref_on_a_description_in_no_repository_is_an_error_not_a_silent_pass(
    pytester: pytest.Pytester,
    repository: Path,
    tmp_path_factory: pytest.TempPathFactory,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    outside = outside_repository(tmp_path_factory)
    # Keeps git from finding a repository that happens to enclose the temporary directories.
    monkeypatch.setenv("GIT_CEILING_DIRECTORIES", str(outside.parent.parent))
    outside.write_text(ROBOT.replace("<samples>32</samples>", "<samples>16</samples>"))
    (repository / "gate.lasertest.yaml").write_text(_pairs_reading(outside))
    result = pytester.runpytest()
    assert_one_clean_error(
        result,
        5,
        "pairs.swap.baseline.ref",
        Hostile(
            {},
            "",
            "",
            5,
            f"{outside} is not inside a git repository, so `ref:` cannot read it at a revision",
            "or drop `ref:` to read the working tree",
        ),
    )
    result.stdout.no_fnmatch_line("*no sensing change*")


def test_a_ref_reads_the_repository_that_holds_the_description_not_the_pairs_file_s(
    pytester: pytest.Pytester, repository: Path, tmp_path_factory: pytest.TempPathFactory
) -> None:
    # The description lives in a clone of its own, beside the pairs file's repository.
    description = outside_repository(tmp_path_factory)
    commit_everything(description.parent)
    description.write_text(ROBOT.replace("<samples>32</samples>", "<samples>16</samples>"))
    (repository / "gate.lasertest.yaml").write_text(_pairs_reading(description))
    result = pytester.runpytest(*NO_PLACEMENTS, "--laser-seed=1")
    head = git(description.parent, "rev-parse", "--short=7", "HEAD")
    result.stdout.fnmatch_lines(
        [
            f"  baseline   front in {description} at HEAD ({head}): 32 beams *",
            f"  candidate  front in {description}: 16 beams *",
        ]
    )


def test_a_ref_on_a_symbolic_link_out_of_the_repository_is_an_error(
    pytester: pytest.Pytester, repository: Path, tmp_path_factory: pytest.TempPathFactory
) -> None:
    target = outside_repository(tmp_path_factory)
    (repository / "robot.urdf").unlink()
    (repository / "robot.urdf").symlink_to(target)
    result = pytester.runpytest()
    assert_one_clean_error(
        result,
        5,
        "pairs.swap.baseline.ref",
        Hostile(
            {},
            "",
            "",
            5,
            f"robot.urdf lies outside the git repository at {repository.resolve()} (it resolves "
            f"to {target.resolve()}), so `ref: HEAD` cannot read it at a revision",
            "point `urdf:` at the file inside the repository",
        ),
    )


def test_a_description_larger_than_16_mb_at_a_ref_is_refused_unread(
    pytester: pytest.Pytester, repository: Path
) -> None:
    (repository / "robot.urdf").write_bytes(b" " * (16 * 1024 * 1024 + 1))
    git(repository, "commit", "-q", "-am", "huge")
    (repository / "robot.urdf").write_text(ROBOT)
    result = pytester.runpytest()
    head = git(repository, "rev-parse", "--short=7", "HEAD")
    assert_one_clean_error(
        result,
        1,
        "",
        Hostile(
            {},
            "",
            "",
            1,
            f"robot.urdf at HEAD ({head}) is larger than 16 MB, the most the gate reads",
            "robot descriptions are kilobytes",
        ),
        file="robot.urdf",
    )


def test_a_device_is_refused_before_a_byte_is_read() -> None:
    with pytest.raises(OSError, match="is a character device") as raised:
        read_regular_file(Path("/dev/zero"))
    assert raised.value.filename == "/dev/zero"


def test_a_macro_that_recurses_to_an_end_within_the_bounds_still_expands(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(
        xacro_file(
            '  <xacro:macro name="chain" params="n">',
            '    <xacro:if value="${n > 0}">',
            '      <link name="l${n}"/>',
            '      <xacro:chain n="${n-1}"/>',
            "    </xacro:if>",
            "  </xacro:macro>",
            '  <xacro:chain n="40"/>',
        )
    )
    expansion = expand_xacro(path, WorkingTree(), {}, {})
    assert [element.get("name") for element in expansion.root.all("link")] == [
        "base_footprint",
        *(f"l{n}" for n in range(40, 0, -1)),
    ]


TRICKY_XACRO = xacro_file(
    "  <!-- c1 -->",
    "  <!-- c2 -->",
    '  <xacro:property name="p" value="3"/>',
    '  <xacro:macro name="m" params="n *first **rest">',
    "    <!-- before the if -->",
    '    <xacro:if value="${n > 0}">',
    '      <link name="l${n}"/>',
    "      <!-- inside -->",
    '      <xacro:m n="${n-1}"><x/><g><xacro:insert_block name="rest"/></g></xacro:m>',
    "    </xacro:if>",
    '    <xacro:insert_block name="first"/>',
    '    <xacro:unless value="${n > 0}"><!-- u --><end/></xacro:unless>',
    "  </xacro:macro>",
    "  <!-- before the call -->",
    "",
    '  <xacro:m n="${p}"><first/><group><a/><b/></group></xacro:m>',
    "  text <!-- mid --> more",
    '  <xacro:if value="1"><!-- kept --><kept/></xacro:if>',
)


def test_the_guarded_expansion_writes_what_xacro_itself_writes(tmp_path: Path) -> None:
    # The gate does xacro's node replacement itself (in linear time): elements, their order
    # and the blank text between them must come out as xacro's own.
    path = tmp_path / "robot.urdf.xacro"
    path.write_text(TRICKY_XACRO)
    own = parse_xml(xacro.process_file(str(path)).toxml().encode(), path)
    guarded = expand_xacro(path, WorkingTree(), {}, {}).root
    assert [_written(element) for element in guarded.walk()] == [
        _written(element) for element in own.walk()
    ]
    assert [element.tag for element in own.walk()].count("kept") == 1


def _written(element: XmlElement) -> tuple[str, dict[str, str], str]:
    """An element as xacro writes it, without the gate's mark of where it came from."""
    attributes = {key: value for key, value in element.attributes.items() if key != ORIGIN}
    return element.tag, attributes, element.text


def _pairs_reading(description: Path) -> str:
    """PAIRS with both scanners read from `description` instead of robot.urdf."""
    return PAIRS.replace("urdf: robot.urdf, ref: HEAD", f"urdf: {description}, ref: HEAD").replace(
        "candidate: {urdf: robot.urdf}", f"candidate: {{urdf: {description}}}"
    )
