"""The stacks' compiled code: a kernel not yet in numba's cache is compiled by a child process,
and the process that imports it loads the machine code the child cached (keeping none of LLVM's
memory of compiling it); where it cannot, it compiles the kernel itself."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from pytest_lasertest.nav.kernels import COMPILING

KERNEL = """
from pytest_lasertest.nav.kernels import compiled


@compiled("f8(f8)")
def twice(x):
    return 2.0 * x
"""
# What an importing process reports: numba's loads of the kernel from its cache, its own
# compilations of it, and the kernel's answer.
REPORT = """
from kernel_under_test import twice
print(sum(twice.stats.cache_hits.values()), sum(twice.stats.cache_misses.values()), twice(2.0))
"""


def imported(
    folder: Path, *, on_sys_path: bool = False, environment: dict[str, str] | None = None
) -> list[str]:
    """What a fresh process importing the kernel in `folder` reports; it finds `folder` on its
    PYTHONPATH, or, `on_sys_path`, by putting it on sys.path itself (as pytest's rootdir is)."""
    paths = os.pathsep.join(sys.path if on_sys_path else [str(folder), *sys.path])
    report = f"import sys; sys.path.insert(0, {str(folder)!r})\n{REPORT}" if on_sys_path else REPORT
    env = {key: value for key, value in os.environ.items() if key != COMPILING}
    done = subprocess.run(
        [sys.executable, "-c", report],
        env={**env, "PYTHONPATH": paths, **(environment or {})},
        capture_output=True,
        text=True,
        check=True,
    )
    return done.stdout.split()


def test_a_kernel_not_yet_cached_is_compiled_apart_and_loaded_from_the_cache(
    tmp_path: Path,
) -> None:
    (tmp_path / "kernel_under_test.py").write_text(KERNEL)
    assert imported(tmp_path) == ["1", "0", "4.0"]
    assert len(list((tmp_path / "__pycache__").glob("kernel_under_test.twice-*.nbi"))) == 1
    assert imported(tmp_path) == ["1", "0", "4.0"]  # and so on later


def test_a_process_that_may_not_compile_apart_compiles_the_kernel_itself(tmp_path: Path) -> None:
    (tmp_path / "kernel_under_test.py").write_text(KERNEL)
    assert imported(tmp_path, environment={COMPILING: "1"}) == ["0", "1", "4.0"]


def test_a_kernel_whose_source_changed_since_it_was_cached_is_compiled_apart_again(
    tmp_path: Path,
) -> None:
    source = tmp_path / "kernel_under_test.py"
    source.write_text(KERNEL)
    imported(tmp_path)
    source.write_text(KERNEL.replace("2.0 * x", "x + x"))
    later = max(index.stat().st_mtime for index in (tmp_path / "__pycache__").glob("*.nbi")) + 1
    os.utime(source, (later, later))
    assert imported(tmp_path) == ["1", "0", "4.0"]


def test_the_child_finds_a_kernels_module_where_the_process_found_it(tmp_path: Path) -> None:
    (tmp_path / "kernel_under_test.py").write_text(KERNEL)
    assert imported(tmp_path, on_sys_path=True) == ["1", "0", "4.0"]
