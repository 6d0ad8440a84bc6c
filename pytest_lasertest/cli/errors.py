"""What the `lasertest` command says when it cannot do what it was asked: one message on stderr,
no traceback, exit status 2, and with `--json` the same error as a JSON object on stdout, so
that a script reading stdout always gets JSON.

The JSON error object (a documented contract):

    {"error": {"kind": "usage" | "input" | "git", "message", "file", "line", "field",
               "problem", "fix"}}

`kind` is "usage" for a command line the command cannot act on (a bad option value, a file
argument that is missing, a directory or unreadable, an unknown pair or witness), "input" for a
file that cannot be used as written, "git" for a revision that cannot be read, "controller" for
a pairs file's controller that broke the drive timing a pair's path (`file` and `line` are then
where in its code). `message` is the
text printed on stderr; `file`, `line` and `field` are null where they do not apply.
"""

from __future__ import annotations

import argparse
import difflib
import json
import re
import sys
from pathlib import Path
from typing import Any, NoReturn

from pytest_lasertest.descriptions.gitref import GitError
from pytest_lasertest.inputs.errors import SpecError, display_path

EXIT_ERROR = 2  # argparse's status for a usage error; every error of the command uses it


class CommandError(Exception):
    """A command line the command cannot act on: what is wrong and what to give instead."""

    def __init__(
        self,
        problem: str,
        fix: str,
        file: Path | None = None,
        *,
        kind: str = "usage",
        line: int | None = None,
    ) -> None:
        super().__init__(problem, fix, file)
        self.problem = problem
        self.fix = fix
        self.file = file
        self.kind = kind  # "usage", or "controller" for a controller that broke a drive
        self.line = line

    def __str__(self) -> str:
        return f"{self.problem}\n  fix: {self.fix}"


class ArgumentError(Exception):
    """argparse's complaint about the command line, raised instead of its exit."""

    def __init__(self, parser: Parser, message: str) -> None:
        super().__init__(message)
        self.parser = parser
        self.message = message


class Parser(argparse.ArgumentParser):
    """argparse's parser, raising ArgumentError where argparse would print and exit, so that
    `--json` can print the error as JSON too, with a fix. Its subcommands' parsers are of this
    class; `example` is a command line it takes, which the fix shows."""

    def __init__(self, *args: Any, example: str = "", **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.example = example

    def error(self, message: str) -> NoReturn:
        raise ArgumentError(self, message)

    def commands(self) -> dict[str, Parser]:
        """The subcommands' parsers, by name; none for a subcommand's own parser."""
        found: dict[str, Parser] = {}
        for action in self._actions:
            if isinstance(action, argparse._SubParsersAction):
                found |= action.choices
        return found


def argument_fix(error: ArgumentError) -> str:
    """What to run instead of a command line argparse refused: the command meant, for an
    unknown one, else an example of the parser's command and where its help is."""
    parser = error.parser
    names = list(parser.commands())
    if not names:
        return f"run e.g. `{parser.example}`; `{parser.prog} --help` says what each argument takes"
    typed = re.search(r"invalid choice: '([^']*)'", error.message)
    if typed is None:
        return (
            f"run `{parser.prog} --help` for the commands, or e.g. `{parser.example}` to find the "
            "placements that tell each pair apart"
        )
    close = difflib.get_close_matches(typed.group(1), names, n=1)
    meant = f"did you mean `{parser.prog} {close[0]}`? " if close else ""
    return (
        f"{meant}give one of the commands {', '.join(names)}; `{parser.prog} --help` says what "
        "each does"
    )


def error_json(error: Exception) -> dict[str, object]:
    """The JSON error object of an error the command reports."""
    fields: dict[str, object] = {"kind": "usage", "message": str(error), "file": None}
    fields |= {"line": None, "field": None, "problem": str(error), "fix": None}
    if isinstance(error, SpecError):
        fields |= {"kind": "input", "file": display_path(error.location.path)}
        fields |= {"line": error.location.line, "field": error.field or None}
        fields |= {"problem": error.problem, "fix": error.fix}
    elif isinstance(error, GitError):
        fields |= {"kind": "git", "problem": error.problem, "fix": error.fix}
    elif isinstance(error, CommandError):
        file = None if error.file is None else display_path(error.file)
        fields |= {"kind": error.kind, "file": file, "line": error.line}
        fields |= {"problem": error.problem, "fix": error.fix}
    elif isinstance(error, ArgumentError):
        fix = argument_fix(error)
        fields |= {"message": error.message, "problem": error.message, "fix": fix}
    return {"error": fields}


def report_error(error: Exception, *, as_json: bool) -> None:
    """The error on stderr as argparse or the project's errors write it; with `as_json`, also
    as one JSON object on stdout."""
    if isinstance(error, ArgumentError):
        error.parser.print_usage(sys.stderr)
        print(f"{error.parser.prog}: error: {error.message}", file=sys.stderr)
        print(f"  fix: {argument_fix(error)}", file=sys.stderr)
    else:
        print(f"lasertest: {error}", file=sys.stderr)
    if as_json:
        print(json.dumps(error_json(error), indent=2))


def check_file(path: Path, what: str, example: str) -> None:
    """Refuse, before anything reads it, a file argument that is missing, a directory, not a
    regular file (a pipe would wait for ever) or unreadable; `what` names what the argument
    takes ("a pairs file") and `example` shows a command that gives one."""
    shown = repr(str(path))
    if path.is_dir():
        raise CommandError(f"{shown} is a directory, not {what}", f"give {what}: {example}", path)
    if not path.exists():
        raise CommandError(f"{shown} does not exist", "check the path and its spelling", path)
    if not path.is_file():
        raise CommandError(
            f"{shown} is not a regular file (a pipe, socket or device)",
            f"give {what} saved on disk: {example}",
            path,
        )
    try:
        with path.open("rb"):
            pass
    except OSError as error:
        raise CommandError(
            f"{shown} cannot be read: {error.strerror}",
            "give a file this user can read, or change its permissions",
            path,
        ) from None
