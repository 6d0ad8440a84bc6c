"""`--dist loadgroup` as pytest-xdist documents it, under pytest 9.2 too: pytest-xdist 3.8 reads
a test's `xdist_group` from a suffix of its node id that pytest 9.2 no longer lets it add
(pytest-xdist#1386), and so spreads a group over the workers. The groups of this suite are the
documentation pages of tests/docs/test_shown_outputs.py, whose parameters are `PAGE:LINE`: here
the scheduler reads the page from the node id itself, so each page's commands run on one worker,
in order, once."""

from __future__ import annotations

from xdist.scheduler import LoadGroupScheduling

SHOWN_OUTPUTS = "tests/docs/test_shown_outputs.py::test_the_docs_show_what_each_command_prints["


def page_of(nodeid: str) -> str | None:
    """The documentation page whose command the test `nodeid` checks, or None for any other."""
    if not nodeid.startswith(SHOWN_OUTPUTS) or not nodeid.endswith("]"):
        return None
    return nodeid.removeprefix(SHOWN_OUTPUTS).removesuffix("]").rpartition(":")[0] or None


class PageGroups(LoadGroupScheduling):  # type: ignore[misc]  # xdist has no types
    """pytest-xdist's loadgroup scheduling, each page one group."""

    def _split_scope(self, nodeid: str) -> str:
        page = page_of(nodeid)
        return super()._split_scope(nodeid) if page is None else f"page:{page}"
