"""The Hypothesis search around one witness: the only module that imports hypothesis.

Each placement item searches the box of offsets in which its witness stays discriminating
(`offsets.py`). Every axis is drawn as a float that shrinks toward zero, so Hypothesis tries the
witness itself first and shrinks a failure to the witness plus the smallest change that still
fails. Failures are stored in an example database under the item's own node id, so the next run,
in CI or on any pytest-xdist worker, replays them before anything else.

The trial a search runs (`Trial`) decides what one offset does: it raises `Untested` for an offset
it will not simulate (no longer discriminating, or the shrink budget spent), which the search
rejects; it raises any other exception for a failure, and returns the event to count otherwise.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, cast

from hypothesis import HealthCheck, Phase, Verbosity, event, given, reject, settings
from hypothesis import seed as seeded
from hypothesis import strategies as st
from hypothesis.database import DirectoryBasedExampleDatabase, ExampleDatabase
from hypothesis.errors import Unsatisfiable
from hypothesis.statistics import collector, describe_statistics

from pytest_lasertest.search.budgets import Budget
from pytest_lasertest.search.offsets import AXES, Offset, OffsetBox, Untested

Trial = Callable[[Offset], str]


@dataclass(frozen=True)
class SearchOutcome:
    """How a search ended: the minimal failure's exception, if any, and its statistics."""

    failure: Exception | None
    statistics: str  # Hypothesis's own description, for --hypothesis-show-statistics


class KeyedDatabase(ExampleDatabase):
    """A database whose keys are prefixed with the item's node id.

    Hypothesis keys examples by a digest of the test function's source, which every placement
    item shares: the prefix gives each item its own failures to replay.
    """

    def __init__(self, inner: ExampleDatabase, key: str) -> None:
        super().__init__()
        self.inner = inner
        self.prefix = hashlib.sha256(key.encode()).digest()[:16]

    def save(self, key: bytes, value: bytes) -> None:
        self.inner.save(self.prefix + key, value)

    def fetch(self, key: bytes) -> Iterable[bytes]:
        return self.inner.fetch(self.prefix + key)

    def delete(self, key: bytes, value: bytes) -> None:
        self.inner.delete(self.prefix + key, value)

    def move(self, src: bytes, dest: bytes, value: bytes) -> None:
        self.inner.move(self.prefix + src, self.prefix + dest, value)


def offsets(box: OffsetBox) -> st.SearchStrategy[Offset]:
    """Offsets drawn from the box, each axis shrinking toward zero (the witness)."""
    axes = {name: _axis(*box.bounds(name)) for name in AXES}
    return st.builds(Offset, **axes)


def _axis(low: float, high: float) -> st.SearchStrategy[float]:
    if low == high:
        return st.just(low)
    return st.floats(low, high, allow_nan=False, allow_infinity=False)


def search(
    box: OffsetBox,
    trial: Trial,
    failing: type[Exception],
    budget: Budget,
    *,
    key: str,
    seed: int,
    database: Path | None,
) -> SearchOutcome:
    """Run `trial` on offsets from `box` until one raises `failing` or the budget's examples
    are spent, then shrink the failure; `key` (the node id) files it in `database` for the next
    run. Any other exception is a bug, and propagates."""
    found: list[dict[str, Any]] = []

    @settings(_settings(budget, key, database))
    @seeded(seed)
    @given(offsets(box))
    def probe(offset: Offset) -> None:
        try:
            outcome = trial(offset)
        except Untested as untested:
            event(untested.reason)
            reject()
        event(outcome)

    # Hypothesis hands each test's statistics to the collector's current callback.
    with cast(Any, collector).with_value(found.append), _without_local_constants():
        try:
            probe()
        except failing as failure:
            return SearchOutcome(failure, _described(found, key))
        except Unsatisfiable:
            pass  # every draw was rejected: the trial counted them, and nothing failed
    return SearchOutcome(None, _described(found, key))


@contextmanager
def _without_local_constants() -> Iterator[None]:
    """Hypothesis (from 6.131.1) draws some numbers from the constants of every local module
    the process has imported so far, and which modules those are depends on what ran before in
    the process: a Nav2 item before a move_base one, pytest-xdist's distribution, a team's
    conftest. The same seed must try the same offsets in any process, so the search draws
    without them (the constants Hypothesis ships stay). This reaches into Hypothesis's internals
    because no setting turns them off (read at 6.170); the search's tests fail if that changes."""
    try:
        from hypothesis.internal.conjecture import providers
        from hypothesis.internal.constants_ast import Constants
    except ImportError:  # an older Hypothesis, which reads no local constants
        yield
        return
    local = getattr(providers, "_get_local_constants", None)
    if local is None:  # likewise
        yield
        return
    none = Constants()
    providers._get_local_constants = lambda: none
    providers.CONSTANTS_CACHE.cache.clear()  # it holds the pools it drew from before
    try:
        yield
    finally:
        providers._get_local_constants = local
        providers.CONSTANTS_CACHE.cache.clear()


def _settings(budget: Budget, key: str, database: Path | None) -> settings:
    phases = [Phase.explicit, Phase.reuse, Phase.generate, Phase.shrink]
    return settings(
        max_examples=budget.examples,
        phases=phases + [Phase.explain] * budget.explain,
        database=(
            KeyedDatabase(DirectoryBasedExampleDatabase(database), key) if database else None
        ),
        deadline=None,
        derandomize=False,
        report_multiple_bugs=False,
        print_blob=False,
        verbosity=Verbosity.quiet,
        # A simulation takes a third of a second by design; rejections are counted and reported.
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
    )


def _described(found: list[dict[str, Any]], key: str) -> str:
    if not found:
        return ""
    # Hypothesis's plugin heads each test's statistics with its node id, and so do we.
    return describe_statistics(cast(Any, {**found[-1], "nodeid": key}))
