"""Files as a git revision holds them: the baseline of a description at `ref: origin/main`.

Git runs with an argument list, never through a shell, and a ref that looks like an option is
refused before git sees it."""

from __future__ import annotations

import errno
import os
import subprocess
from dataclasses import dataclass
from pathlib import Path

from pytest_lasertest.inputs.files import MAX_FILE_BYTES

_REPOSITORY_VARIABLES = frozenset(
    {"GIT_DIR", "GIT_WORK_TREE", "GIT_INDEX_FILE", "GIT_OBJECT_DIRECTORY", "GIT_COMMON_DIR"}
)
_REF_FIX = "write a branch, tag or commit, e.g. `origin/main`"


class GitError(Exception):
    """A revision or a file at a revision cannot be read; `problem` and `fix` as in SpecError."""

    def __init__(self, problem: str, fix: str) -> None:
        super().__init__(problem, fix)
        self.problem = problem
        self.fix = fix

    def __str__(self) -> str:
        return f"{self.problem}\n  fix: {self.fix}"


@dataclass(frozen=True)
class GitRevision:
    """One commit of the repository that holds a directory."""

    root: Path  # the repository's top-level directory (resolved, absolute)
    ref: str  # as the user wrote it, e.g. "origin/main"
    commit: str  # the full commit id it resolved to

    @property
    def label(self) -> str:
        """How messages name it: 'origin/main (1a2b3c4)'."""
        return f"{self.ref} ({self.commit[:7]})"

    def holds(self, path: Path) -> bool:
        """Whether `path` (absolute) lies inside the repository's tree (below root)."""
        return self.root in _resolved(path).parents

    def read(self, path: Path) -> bytes:
        """The bytes of `path` (absolute, inside root) at this revision.

        Raises FileNotFoundError when the revision has no such file (or a directory there),
        GitError for anything else git reports or a blob over MAX_FILE_BYTES, and ValueError
        for a path outside root.
        """
        relpath = self._relative(path)
        # The commit is 40 hex digits, so git splits `<commit>:<path>` at the first colon and
        # a path holding ':' or starting with '-' stays a path.
        name = f"{self.commit}:{relpath}"
        if "\n" in name:  # `--batch-check` reads one name per line
            raise _missing(path, f"{relpath!r} has a line break, which git cannot look up here")
        # The object's id, type and size first, so that a huge blob is refused unread:
        # `--batch-check` reads the name from stdin and answers "<id> <type> <size>", or
        # "<name> missing".
        done = _git(self.root, "cat-file", "--batch-check", stdin=os.fsencode(f"{name}\n"))
        header = done.stdout.rstrip(b"\n")
        if done.returncode != 0:
            raise self._unreadable(relpath, _stderr(done))
        if header.endswith((b" missing", b" ambiguous")):
            # It says "missing" too when the tree names an object the store has lost.
            if _git(self.root, "rev-parse", "--verify", "--quiet", name).returncode == 0:
                raise self._unreadable(relpath, f"its object is missing: {os.fsdecode(header)}")
            raise _missing(path, f"{relpath} does not exist at {self.label}")
        blob, kind, size = header.split()
        if kind != b"blob":
            raise _missing(path, f"{relpath} is a directory at {self.label}, not a file")
        if int(size) > MAX_FILE_BYTES:
            raise GitError(
                f"{relpath} at {self.label} is larger than {MAX_FILE_BYTES // (1024 * 1024)} MB, "
                "the most the gate reads of a description file",
                "point `urdf:` at the robot's description; robot descriptions are kilobytes",
            )
        content = _git(self.root, "cat-file", "blob", os.fsdecode(blob))
        if content.returncode != 0:
            raise self._unreadable(relpath, _stderr(content))
        return content.stdout

    def _relative(self, path: Path) -> str:
        """`path` relative to root with '/' between parts, as git names it in a tree."""
        resolved = _resolved(path)
        if self.root not in resolved.parents:
            raise ValueError(f"{path} lies outside the repository at {self.root}")
        return resolved.relative_to(self.root).as_posix()

    def _unreadable(self, relpath: str, message: str) -> GitError:
        return GitError(
            f"git cannot read {relpath} at {self.label}: {message}",
            "check that the repository is intact (`git fsck`) and readable by this user",
        )


def open_revision(directory: Path, ref: str) -> GitRevision:
    """The revision `ref` of the repository holding `directory`.

    GitError when git is missing, `directory` is not inside a work tree, the ref looks like an
    option or is not a commit.
    """
    _check_ref(ref)
    root = _toplevel(directory, directory)
    return GitRevision(root=root, ref=ref, commit=_resolve(root, ref))


def revision_holding(path: Path, ref: str) -> GitRevision:
    """The revision `ref` of the repository that holds the file `path` (absolute), which the
    working tree may lack (a file the change deletes).

    GitError as open_revision's, and when the file lies outside that repository (a symbolic
    link out of it, or a directory that only exists in another repository's tree).
    """
    _check_ref(ref)
    directory = next(parent for parent in path.parents if parent.is_dir())
    root = _toplevel(directory, path)
    revision = GitRevision(root=root, ref=ref, commit=_resolve(root, ref))
    if not revision.holds(path):
        raise GitError(
            f"{path} lies outside the git repository at {root} (it resolves to "
            f"{_resolved(path)}), so `ref: {ref}` cannot read it at a revision",
            "point `urdf:` at the file inside the repository, or drop `ref:` to read the "
            "working tree",
        )
    return revision


def _check_ref(ref: str) -> None:
    """Refuse, before git runs, a ref that git could take for an option or that no ref can be."""
    if not ref.strip():
        raise GitError(f"the ref {ref!r} is empty", _REF_FIX)
    if ref.startswith("-"):
        raise GitError(
            f"the ref {ref!r} starts with '-', so git would read it as an option", _REF_FIX
        )
    if any(char.isspace() or not char.isprintable() for char in ref):
        raise GitError(
            f"the ref {ref!r} holds whitespace or a control character, which no ref can hold",
            _REF_FIX,
        )


def _toplevel(directory: Path, subject: Path) -> Path:
    """The top-level directory of the work tree that holds `directory`; errors name `subject`
    (the directory, or the file looked up in it)."""
    done = _git(directory, "rev-parse", "--show-toplevel")
    message = _stderr(done)
    if done.returncode != 0 and "not a git repository" in message:
        raise GitError(
            f"{subject} is not inside a git repository, so `ref:` cannot read it at a revision",
            "keep the description in a git repository (a clone of yours) and commit it, or drop "
            "`ref:` to read the working tree",
        )
    top = done.stdout.rstrip(b"\r\n")
    if done.returncode != 0 or not top:
        # Kept apart from "not a repository": a checkout owned by another user, a bare
        # repository or a missing directory needs a different fix, and git says which.
        raise GitError(
            f"git cannot find the work tree holding {directory}: {message}",
            "fix what git reports, or drop `ref:` to read the working tree",
        )
    return Path(os.fsdecode(top)).resolve()


def _resolve(root: Path, ref: str) -> str:
    """The full id of the commit `ref` names in the repository at `root`."""
    # `--end-of-options` guards again, should a ref starting with '-' ever get past _check_ref.
    done = _git(root, "rev-parse", "--verify", "--quiet", "--end-of-options", f"{ref}^{{commit}}")
    commit = done.stdout.decode("ascii", errors="replace").strip()
    if done.returncode != 0 or not commit:
        raise GitError(
            f"the ref {ref!r} names no commit in the repository at {root}",
            "check the spelling; in CI, fetch it first, e.g. actions/checkout with"
            " `fetch-depth: 0` or `git fetch origin main`",
        )
    return commit


def _git(directory: Path, *args: str, stdin: bytes = b"") -> subprocess.CompletedProcess[bytes]:
    """Run git in `directory`: English messages, and never a prompt for credentials."""
    # A git hook (pre-push, say) that runs the gate sets GIT_DIR and friends, which would win
    # over `-C` and point git at the hook's repository instead of the pairs file's.
    inherited = {
        key: value for key, value in os.environ.items() if key not in _REPOSITORY_VARIABLES
    }
    env = {**inherited, "GIT_TERMINAL_PROMPT": "0", "LC_ALL": "C"}
    try:
        return subprocess.run(
            ["git", "-C", str(directory), *args],
            input=stdin,
            capture_output=True,
            check=False,
            env=env,
        )
    except FileNotFoundError:
        raise GitError(
            "git is not installed (or not on PATH)",
            "install git; the `ref:` form reads files with it",
        ) from None


def _stderr(done: subprocess.CompletedProcess[bytes]) -> str:
    return done.stderr.decode(errors="replace").strip()


def _missing(path: Path, message: str) -> FileNotFoundError:
    return FileNotFoundError(errno.ENOENT, message, str(path))


def _resolved(path: Path) -> Path:
    """`path` with its symbolic links followed; a link loop is left as it is (Path.resolve
    raises RuntimeError on one) and reading it reports the loop."""
    return Path(os.path.realpath(path))
