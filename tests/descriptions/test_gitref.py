"""`ref: origin/main` reads a description as a git revision holds it, not as the work tree does."""

from __future__ import annotations

import errno
import os
import subprocess
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from pytest_lasertest.descriptions.gitref import GitError, GitRevision, open_revision

Git = Callable[..., str]


@pytest.fixture(autouse=True)
def isolated_git(monkeypatch: pytest.MonkeyPatch) -> None:
    """Git here sees neither the user's config nor a repository an outer hook points at."""
    monkeypatch.setenv("GIT_CONFIG_GLOBAL", os.devnull)
    monkeypatch.setenv("GIT_CONFIG_NOSYSTEM", "1")
    for name in ("GIT_DIR", "GIT_WORK_TREE", "GIT_INDEX_FILE", "GIT_OBJECT_DIRECTORY"):
        monkeypatch.delenv(name, raising=False)


@pytest.fixture
def repo(tmp_path: Path) -> Path:
    """An empty repository on branch main that keeps line endings as written."""
    root = tmp_path / "repo"
    root.mkdir()
    subprocess.run(
        ["git", "-c", "init.defaultBranch=main", "init", "-q", str(root)],
        check=True,
        capture_output=True,
    )
    subprocess.run(
        ["git", "-C", str(root), "config", "core.autocrlf", "false"],
        check=True,
        capture_output=True,
    )
    return root


@pytest.fixture
def git(repo: Path) -> Git:
    """Run git in `repo` with an argument list and return what it prints."""

    def run(*args: str) -> str:
        done = subprocess.run(
            ["git", "-c", "user.name=t", "-c", "user.email=t@t", "-C", str(repo), *args],
            check=True,
            capture_output=True,
        )
        return done.stdout.decode().strip()

    return run


def commit(git: Git, repo: Path, files: dict[str, bytes], message: str) -> str:
    """Write `files` below `repo`, commit them all and return the commit id."""
    for name, data in files.items():
        path = repo / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data)
    git("add", "-A")
    git("commit", "-q", "-m", message)
    return git("rev-parse", "HEAD")


@pytest.fixture
def history(git: Git, repo: Path) -> dict[str, str]:
    """Three commits of robot.urdf, tagged v1, branched at v2, with a fourth edit uncommitted."""
    ids = {"v1": commit(git, repo, {"robot.urdf": b"one\n"}, "one")}
    git("tag", "v1")
    ids["v2"] = commit(git, repo, {"robot.urdf": b"two\n"}, "two")
    git("branch", "old")
    ids["v3"] = commit(git, repo, {"robot.urdf": b"three\n"}, "three")
    (repo / "robot.urdf").write_bytes(b"working tree\n")
    return ids


@pytest.mark.parametrize(
    ("ref", "version", "expected"),
    [
        ("HEAD~1", "v2", b"two\n"),
        ("v1", "v1", b"one\n"),
        ("old", "v2", b"two\n"),
        ("main", "v3", b"three\n"),
    ],
)
def test_a_file_is_read_as_the_revision_holds_it_not_as_the_working_tree_does(
    repo: Path, history: dict[str, str], ref: str, version: str, expected: bytes
) -> None:
    revision = open_revision(repo, ref)
    assert revision == GitRevision(root=repo.resolve(), ref=ref, commit=history[version])
    assert revision.read(repo / "robot.urdf") == expected
    assert (repo / "robot.urdf").read_bytes() == b"working tree\n"


def test_a_revision_is_found_from_any_directory_below_the_top_level(git: Git, repo: Path) -> None:
    commit(git, repo, {"robots/husky/robot.urdf": b"husky\n"}, "husky")
    revision = open_revision(repo / "robots" / "husky", "main")
    assert revision.root == repo.resolve()
    assert revision.read(repo / "robots" / "husky" / "robot.urdf") == b"husky\n"


def test_the_label_names_the_ref_and_the_short_commit(repo: Path, history: dict[str, str]) -> None:
    revision = open_revision(repo, "v1")
    assert len(revision.commit) == 40
    assert revision.label == f"v1 ({history['v1'][:7]})"


def test_a_file_the_revision_lacks_is_not_found_by_its_relative_path_and_ref(
    git: Git, repo: Path, history: dict[str, str]
) -> None:
    commit(git, repo, {"robots/new.urdf": b"new\n"}, "new")
    revision = open_revision(repo, "v1")
    path = repo / "robots" / "new.urdf"
    with pytest.raises(FileNotFoundError) as raised:
        revision.read(path)
    assert raised.value.errno == errno.ENOENT
    assert raised.value.filename == str(path)
    assert raised.value.strerror == f"robots/new.urdf does not exist at {revision.label}"


def test_a_file_only_in_the_working_tree_is_not_found_at_the_revision(
    repo: Path, history: dict[str, str]
) -> None:
    (repo / "untracked.urdf").write_text("draft\n")
    with pytest.raises(FileNotFoundError, match=r"untracked\.urdf does not exist at HEAD \("):
        open_revision(repo, "HEAD").read(repo / "untracked.urdf")


def test_a_directory_at_the_revision_is_not_a_file(git: Git, repo: Path) -> None:
    commit(git, repo, {"robots/husky/robot.urdf": b"husky\n"}, "husky")
    revision = open_revision(repo, "main")
    with pytest.raises(FileNotFoundError, match=r"robots/husky is a directory at main") as raised:
        revision.read(repo / "robots" / "husky")
    assert raised.value.errno == errno.ENOENT


def test_a_ref_naming_no_commit_says_to_fetch_it(repo: Path, history: dict[str, str]) -> None:
    with pytest.raises(GitError) as raised:
        open_revision(repo, "origin/main")
    assert raised.value.problem == (
        f"the ref 'origin/main' names no commit in the repository at {repo.resolve()}"
    )
    assert "fetch-depth: 0" in raised.value.fix
    assert str(raised.value) == f"{raised.value.problem}\n  fix: {raised.value.fix}"


def test_a_ref_naming_a_file_rather_than_a_commit_is_refused(
    repo: Path, history: dict[str, str]
) -> None:
    with pytest.raises(GitError, match="names no commit"):
        open_revision(repo, "HEAD:robot.urdf")


@pytest.fixture
def git_calls(monkeypatch: pytest.MonkeyPatch) -> list[list[str]]:
    """Every argument list handed to subprocess.run while the test runs."""
    calls: list[list[str]] = []
    real_run = subprocess.run

    def recording_run(args: list[str], **kwargs: Any) -> subprocess.CompletedProcess[bytes]:
        calls.append(list(args))
        return real_run(args, **kwargs)

    monkeypatch.setattr(subprocess, "run", recording_run)
    return calls


@pytest.mark.parametrize("option", ["--upload-pack=touch {pwned}", "-h", "--output={pwned}"])
def test_a_ref_that_looks_like_an_option_never_reaches_git(
    repo: Path,
    history: dict[str, str],
    tmp_path: Path,
    git_calls: list[list[str]],
    option: str,
) -> None:
    pwned = tmp_path / "pwned"
    ref = option.format(pwned=pwned)
    with pytest.raises(GitError) as raised:
        open_revision(repo, ref)
    assert (
        raised.value.problem
        == f"the ref {ref!r} starts with '-', so git would read it as an option"
    )
    assert "origin/main" in raised.value.fix
    assert git_calls == []
    assert not pwned.exists()


@pytest.mark.parametrize(
    "ref", ["", "   ", "main branch", "main\n", "ma\tin", "main\0", "ma\x1bin"]
)
def test_a_ref_no_branch_tag_or_commit_can_be_is_refused_before_git_runs(
    repo: Path, history: dict[str, str], git_calls: list[list[str]], ref: str
) -> None:
    with pytest.raises(GitError, match=r"the ref .* (is empty|holds whitespace or a control)"):
        open_revision(repo, ref)
    assert git_calls == []


def test_git_runs_with_an_argument_list_english_messages_and_no_prompt(
    repo: Path, history: dict[str, str], monkeypatch: pytest.MonkeyPatch
) -> None:
    seen: list[tuple[list[str], dict[str, Any]]] = []
    real_run = subprocess.run

    def recording_run(args: list[str], **kwargs: Any) -> subprocess.CompletedProcess[bytes]:
        seen.append((list(args), kwargs))
        return real_run(args, **kwargs)

    monkeypatch.setattr(subprocess, "run", recording_run)
    monkeypatch.setenv("LC_ALL", "de_DE.UTF-8")
    open_revision(repo, "v1").read(repo / "robot.urdf")
    assert seen
    for args, kwargs in seen:
        assert args[:3] == ["git", "-C", str(args[2])]
        assert not kwargs.get("shell", False)
        assert kwargs["env"]["LC_ALL"] == "C"
        assert kwargs["env"]["GIT_TERMINAL_PROMPT"] == "0"
    assert "--end-of-options" in seen[1][0]


def test_a_directory_outside_any_repository_is_refused(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Keeps git from finding a repository that happens to enclose the temporary directory.
    monkeypatch.setenv("GIT_CEILING_DIRECTORIES", str(tmp_path.parent))
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    with pytest.raises(GitError) as raised:
        open_revision(elsewhere, "main")
    assert raised.value.problem == (
        f"{elsewhere} is not inside a git repository, so `ref:` cannot read it at a revision"
    )
    assert "drop `ref:`" in raised.value.fix


def test_a_directory_git_cannot_enter_is_refused_with_what_git_says(tmp_path: Path) -> None:
    with pytest.raises(GitError, match=r"git cannot find the work tree holding .*cannot change to"):
        open_revision(tmp_path / "missing", "main")


def test_without_git_on_the_path_the_error_says_git_is_not_installed(
    repo: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    empty = tmp_path / "empty-bin"
    empty.mkdir()
    monkeypatch.setenv("PATH", str(empty))
    with pytest.raises(GitError) as raised:
        open_revision(repo, "main")
    assert raised.value.problem == "git is not installed (or not on PATH)"
    assert raised.value.fix.startswith("install git")


def test_holds_covers_paths_below_the_top_level_however_they_are_spelled(
    repo: Path, history: dict[str, str], tmp_path: Path
) -> None:
    (repo / "sub").mkdir()
    link = tmp_path / "link"
    link.symlink_to(repo, target_is_directory=True)
    (tmp_path / "repo-other").mkdir()
    revision = open_revision(link, "v1")
    assert revision.root == repo.resolve()
    assert revision.holds(repo / "robot.urdf")
    assert revision.holds(link / "robot.urdf")
    assert revision.holds(repo / "sub" / ".." / "robot.urdf")
    assert revision.read(link / "robot.urdf") == b"one\n"
    assert revision.read(repo / "sub" / ".." / "robot.urdf") == b"one\n"
    assert not revision.holds(tmp_path / "repo-other" / "robot.urdf")
    assert not revision.holds(repo / ".." / "robot.urdf")
    assert not revision.holds(repo)


def test_reading_a_path_outside_the_repository_is_a_caller_error(
    repo: Path, history: dict[str, str], tmp_path: Path
) -> None:
    with pytest.raises(ValueError, match="lies outside the repository"):
        open_revision(repo, "v1").read(tmp_path / "robot.urdf")


@pytest.mark.parametrize("name", ["-x.urdf", "a:b.urdf", "robots/-h", "robots/HEAD:x", "odd name"])
def test_a_file_with_an_odd_name_is_read_at_the_revision(git: Git, repo: Path, name: str) -> None:
    commit(git, repo, {name: b"odd\n"}, "odd")
    (repo / name).write_bytes(b"changed\n")
    assert open_revision(repo, "main").read(repo / name) == b"odd\n"


def test_bytes_come_back_untouched(git: Git, repo: Path) -> None:
    data = b"<robot>\r\n  <link name='base'/>\r\n</robot>\r\n\x00\xff"
    commit(git, repo, {"crlf.urdf": data}, "crlf")
    (repo / "crlf.urdf").write_bytes(b"<robot/>\n")
    assert open_revision(repo, "main").read(repo / "crlf.urdf") == data


def test_a_blob_git_cannot_read_is_a_git_error_not_a_missing_file(
    git: Git, repo: Path, history: dict[str, str]
) -> None:
    blob = git("rev-parse", "v1:robot.urdf")
    (repo / ".git" / "objects" / blob[:2] / blob[2:]).unlink()
    with pytest.raises(GitError, match=r"git cannot read robot\.urdf at v1 \(") as raised:
        open_revision(repo, "v1").read(repo / "robot.urdf")
    assert "git fsck" in raised.value.fix
