"""The `controller:` of a pairs file: the factory that makes the controller each robot drives with.

It is written `module.path:attribute`, the module found next to the pairs file first (as a team
keeps its controller beside its pairs file, like a conftest) and then on sys.path, or as a name
registered in the `lasertest.controllers` entry-point group. It is resolved when the pairs file is
read, so a bad value is a collection error, and every pytest-xdist worker, reading the same file,
resolves the same factory.
"""

from __future__ import annotations

import contextlib
import difflib
import importlib
import importlib.metadata
import inspect
import re
import sys
import sysconfig
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import cast

from pytest_lasertest.inputs.errors import Location, SpecError, display_path
from pytest_lasertest.inputs.node import SpecNode
from pytest_lasertest.nav.laser_filters import ScanFilterChain
from pytest_lasertest.nav.protocol import ControllerFactory

# The controller of a pairs file that names none (and whose conftest hooks choose none).
DEFAULT_CONTROLLER = "nav2"
ENTRY_POINT_GROUP = "lasertest.controllers"
_NAME = r"[A-Za-z_]\w*(?:\.[A-Za-z_]\w*)*"
_REFERENCE = re.compile(rf"(?P<module>{_NAME}):(?P<attribute>{_NAME})\Z")
_FACTORY = (
    "a callable that takes (robot, route) and returns an object with observe(scan, odometry, time)"
)
_COMMAND = "(forward speed m/s, turn rate rad/s)"


@dataclass(frozen=True)
class ControllerChoice:
    """The controller factory a pairs file's robots drive with, and who chose it."""

    name: str  # as the user wrote it, or `module:qualname` for a hook's factory
    source: str  # for reports: where the choice was made
    factory: ControllerFactory
    stack: str = ""  # for reports: what the stack runs, where we know (Nav2's release, say)
    # The laser_filters chain in front of each controller `factory` makes, if the pairs file
    # names one (pairsfile/scan_filters.py): part of what a run is, as the runs cache keys it.
    scan_filters: ScanFilterChain | None = None


def read_controller(node: SpecNode) -> ControllerChoice:
    """The factory `controller:` names: `module:attribute`, or a registered name."""
    text = node.text(
        what="`module:attribute` or the name of a registered controller",
        fix=f"write e.g. `controller: my_controller:make_controller`, or a registered name "
        f"({_listed(registered_controllers())})",
    ).strip()
    factory = _from_module(node, text) if ":" in text else _from_registry(node, text)
    return ControllerChoice(text, f"from {node.location}", factory)


def default_controller(path: Path) -> ControllerChoice:
    """The default controller, for a pairs file at `path` that names none."""
    if DEFAULT_CONTROLLER not in registered_controllers():
        raise SpecError(
            Location(path, 1),
            "controller",
            f"no controller is given and the default, {DEFAULT_CONTROLLER!r}, is not registered "
            f"in the entry-point group {ENTRY_POINT_GROUP}",
            "reinstall pytest-lasertest (`pip install pytest-lasertest`), or name a controller "
            "with `controller: module:factory`",
        )
    node = SpecNode(DEFAULT_CONTROLLER, Location(path, 1), "controller")
    return ControllerChoice(
        DEFAULT_CONTROLLER, "the default", _from_registry(node, DEFAULT_CONTROLLER)
    )


def registered_controllers() -> dict[str, importlib.metadata.EntryPoint]:
    """The controllers installed packages register, by name."""
    return {point.name: point for point in importlib.metadata.entry_points(group=ENTRY_POINT_GROUP)}


def _from_registry(node: SpecNode, name: str) -> ControllerFactory:
    registered = registered_controllers()
    if name not in registered:
        close = difflib.get_close_matches(name, list(registered), n=1, cutoff=0.6)
        hint = f"did you mean {close[0]!r}? " if close else ""
        raise node.error(
            f"{name!r} is neither `module:attribute` nor a controller registered in the "
            f"entry-point group {ENTRY_POINT_GROUP}",
            f"{hint}registered controllers: {_listed(registered)}; or name a factory of your "
            f"own as `module:attribute`",
        )
    point = registered[name]
    try:
        target = point.load()
    except Exception as error:  # noqa: BLE001  (the user needs the package's message, not ours)
        raise node.error(
            f"the controller {name!r} ({point.value}) raises on import: {_one_line(error)}",
            f"fix or reinstall the package that registers it"
            f"{f' ({point.dist.name})' if point.dist else ''}",
        ) from None
    return checked_factory(node, target, f"{name!r} ({point.value})")


def _from_module(node: SpecNode, text: str) -> ControllerFactory:
    reference = _REFERENCE.match(text)
    if reference is None:
        raise node.error(
            f"{text!r} is not `module:attribute`",
            "write the module's dotted name, a colon and the factory's name, "
            "e.g. `my_controller:make_controller`",
        )
    module = _import(node, reference["module"])
    target: object = module
    for part in reference["attribute"].split("."):
        if not hasattr(target, part):
            raise node.error(
                f"{_module_label(module)} has no attribute {reference['attribute']!r}",
                _attribute_hint(part, target),
            )
        target = getattr(target, part)
    return checked_factory(node, target, text)


def _import(node: SpecNode, name: str) -> ModuleType:
    """The module `name`, looked for next to the pairs file first, then on sys.path."""
    here = node.location.path.parent
    local = _local_file(here, name)
    try:
        with _searched_first(here if local else None):
            module = importlib.import_module(name)
    except ModuleNotFoundError as error:
        if error.name is None or not _is_prefix(error.name, name):
            raise _raised(node, name, error) from None
        raise _not_found(node, name, here) from None
    except Exception as error:  # noqa: BLE001  (the user needs their module's message, not ours)
        raise _raised(node, name, error) from None
    if local is not None and not _same_file(module, local):
        raise node.error(
            f"{display_path(local)} is next to this file, but a module {name!r} is already "
            f"imported from elsewhere: {_module_label(module)}",
            "rename the module next to this file, and `controller:`, so that its name is unique",
        )
    return module


@contextlib.contextmanager
def _searched_first(directory: Path | None) -> Iterator[None]:
    """The pairs file's directory first on sys.path while its module is imported, and off it
    again after: the run's imports stay as pytest set them up."""
    if directory is None:
        yield
        return
    entry = str(directory)
    sys.path.insert(0, entry)
    importlib.invalidate_caches()  # the file may be newer than the import system's listing
    try:
        yield
    finally:
        with contextlib.suppress(ValueError):
            sys.path.remove(entry)


def _local_file(here: Path, name: str) -> Path | None:
    """The module's file next to the pairs file, if there is one."""
    base = here.joinpath(*name.split("."))
    for candidate in (base.with_suffix(".py"), base / "__init__.py"):
        if candidate.is_file():
            return candidate
    return None


def _same_file(module: ModuleType, path: Path) -> bool:
    file = getattr(module, "__file__", None)
    return file is not None and Path(file).resolve() == path.resolve()


def _is_prefix(missing: str, name: str) -> bool:
    """Whether the module that could not be found is `name` or a package holding it (and not
    something `name` itself imports)."""
    return name == missing or name.startswith(f"{missing}.")


def _not_found(node: SpecNode, name: str, here: Path) -> SpecError:
    relative = name.replace(".", "/")
    local = sorted(path.stem for path in here.glob("*.py")) + sorted(
        path.name for path in here.iterdir() if (path / "__init__.py").is_file()
    )
    close = difflib.get_close_matches(name, local, n=1, cutoff=0.6)
    hint = f"did you mean {close[0]!r}? " if close else ""
    return node.error(
        f"no module {name!r}: looked for {display_path(here / f'{relative}.py')} and "
        f"{display_path(here / relative / '__init__.py')} next to this file, then on sys.path",
        f"{hint}put {relative}.py next to the pairs file, or install the package that provides "
        f"{name!r}",
    )


def _raised(node: SpecNode, name: str, error: BaseException) -> SpecError:
    return node.error(
        f"importing {name!r} raises {_one_line(error)}",
        "fix the module, or what it imports, until it imports cleanly",
    )


def checked_factory(node: SpecNode, target: object, label: str) -> ControllerFactory:
    """`target`, checked to be callable with (robot, route), not from Python's standard library,
    and, if it is a class, to have an `observe` callable with (scan, odometry, time); an error
    points at `node`. What cannot be checked here (what a function returns) the first drive
    checks."""
    if not callable(target):
        raise node.error(f"{label} is {_kind(target)}, not a callable", f"name {_FACTORY}")
    library = _standard_library(target)
    if library is not None:
        raise node.error(
            f"{label} comes from Python's standard library (module {library!r}), which makes "
            "no controller",
            f"name a factory of your own: {_FACTORY}",
        )
    _check_call(node, target, label, "(robot, route)", (None, ()), f"name {_FACTORY}")
    if inspect.isclass(target):
        _check_observe(node, target, label)
    return cast(ControllerFactory, target)


def _check_call(
    node: SpecNode, target: object, label: str, shown: str, arguments: tuple[object, ...], fix: str
) -> None:
    """An error if `target`'s signature cannot take these positional arguments."""
    try:
        signature = inspect.signature(cast(Callable[..., object], target))
    except (TypeError, ValueError):
        # Some callables (extension types, C++ bindings) have no signature to check: the first
        # drive calls it and says what is wrong.
        return
    try:
        signature.bind(*arguments)
    except TypeError as error:
        raise node.error(f"{label} cannot be called with {shown}: {error}", fix) from None


def _check_observe(node: SpecNode, factory: type, label: str) -> None:
    """An error if the class's objects have no `observe(scan, odometry, time)`."""
    fix = f"define observe(self, scan, odometry, time) on the class, answering {_COMMAND}"
    if inspect.getattr_static(factory, "observe", None) is None:
        if inspect.getattr_static(factory, "__getattr__", None) is not None:
            return  # its objects may make one up: the first drive looks
        raise node.error(f"{label} is a class without an observe method", fix)
    observe = getattr(factory, "observe")  # noqa: B009  (found statically, now bound as used)
    if not callable(observe):
        raise node.error(f"{label}.observe is {_kind(observe)}, not a method", fix)
    # A function on the class is called with the object first; a static or class method,
    # or a callable object, without it.
    unbound = inspect.isfunction(inspect.getattr_static(factory, "observe"))
    arguments = (None, None, None, 0.0) if unbound else (None, None, 0.0)
    _check_call(node, observe, f"{label}.observe", "(scan, odometry, time)", arguments, fix)


def _standard_library(target: object) -> str | None:
    """The standard-library module that defines the function or class `target`, if one does:
    none of them makes a controller (`builtins:print`, `os.path:join`, `subprocess:Popen`)."""
    if not (inspect.isroutine(target) or inspect.isclass(target)):
        return None  # an object made from a library class (a functools.partial) is the user's
    name = getattr(target, "__module__", None)
    module = sys.modules.get(name) if isinstance(name, str) else None
    if module is None:
        return None
    if module.__name__ in sys.builtin_module_names:
        return module.__name__
    file = getattr(module, "__file__", None)
    return module.__name__ if file is not None and _in_standard_library(Path(file)) else None


def _in_standard_library(path: Path) -> bool:
    """Whether the file is in Python's own library, not in a site-packages directory."""
    path = path.resolve()
    paths = sysconfig.get_paths()
    library = {Path(paths[key]).resolve() for key in ("stdlib", "platstdlib")}
    installed = {Path(paths[key]).resolve() for key in ("purelib", "platlib")}
    if not any(path.is_relative_to(root) for root in library):
        return False
    # A system Python may keep its site-packages inside its library directory.
    packages = {"site-packages", "dist-packages"}.intersection(path.parts)
    return not packages and not any(path.is_relative_to(root) for root in installed)


def _attribute_hint(missing: str, target: object) -> str:
    names = sorted(name for name in dir(target) if not name.startswith("_"))
    callables = [name for name in names if _defined_callable(target, getattr(target, name, None))]
    close = difflib.get_close_matches(missing, names, n=1, cutoff=0.6)
    hint = f"did you mean {close[0]!r}? " if close else ""
    return f"{hint}callables there: {', '.join(callables) or 'none'}"


def _defined_callable(owner: object, value: object) -> bool:
    """Whether `value` is callable and, if `owner` is a module, defined there (not imported)."""
    if not callable(value):
        return False
    return not isinstance(owner, ModuleType) or getattr(value, "__module__", None) == owner.__name__


def _module_label(module: ModuleType) -> str:
    file = getattr(module, "__file__", None)
    return f"module {module.__name__!r}" + (f" ({display_path(Path(file))})" if file else "")


def _kind(value: object) -> str:
    kind = type(value).__name__
    return f"{'an' if kind[0] in 'aeiou' else 'a'} {kind} ({value!r:.40})"


def _one_line(error: BaseException) -> str:
    """The exception's type and the first line of its message: no traceback."""
    message = str(error).strip().splitlines()
    return f"{type(error).__name__}: {message[0]}" if message else type(error).__name__


def _listed(registered: dict[str, importlib.metadata.EntryPoint]) -> str:
    return ", ".join(sorted(registered)) or "none"
