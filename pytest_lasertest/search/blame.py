"""What a regression comes from: the candidate driven again at the failing placement with one
part of the setup changed back.

A pair whose scanners publish differently (model/driver.py) may fail through any trait in which
they differ, and a reader fixes a driver one parameter at a time: one more run per differing
trait, with that trait set to the baseline's, says which of them the failure needs. A pair
driving behind the team's laser_filters chain (pairsfile/scan_filters.py) may fail only because
the chain was tuned for the old scanner: one more run with the chain taken out says whether the
chain alone explains the failure. Both run only for the minimal failure of a regression.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from pytest_lasertest.model.driver import differences
from pytest_lasertest.model.obstacles import Obstacle
from pytest_lasertest.pairsfile.scan_filters import without_scan_filters
from pytest_lasertest.search.trials import Setting


@dataclass(frozen=True)
class TraitTried:
    """The candidate at the failing placement with one driver trait set to the baseline's."""

    trait: str  # a Driver field
    baseline_value: object  # what the baseline's driver publishes for it
    passes: bool  # whether the candidate then passes


def blame_driver(setting: Setting, obstacle: Obstacle) -> tuple[TraitTried, ...]:
    """Each trait in which the pair's drivers differ, tried alone past `obstacle`."""
    baseline, candidate = setting.pair.baseline.profile, setting.pair.candidate.profile
    tried = []
    for trait, _ in differences(baseline.driver, candidate.driver):
        value = getattr(baseline.driver, trait)
        driver = dataclasses.replace(candidate.driver, **{trait: value})
        run = setting.drive_past(dataclasses.replace(candidate, driver=driver), obstacle)
        tried.append(TraitTried(trait, value, run.passed))
    return tuple(tried)


def blame(setting: Setting, obstacle: Obstacle) -> tuple[tuple[TraitTried, ...], ChainTried | None]:
    """What a regression past `obstacle` comes from: each differing driver trait, and the chain."""
    return blame_driver(setting, obstacle), blame_chain(setting, obstacle)


def blame_lines(driver: tuple[TraitTried, ...], chain: ChainTried | None) -> list[str]:
    """A failure report's `driver` and `filters` lines, for what was tried."""
    return [
        *([f"  driver     {blame_text(driver)}"] if driver else []),
        *([f"  filters    {chain_text(chain)}"] if chain else []),
    ]


def blame_text(tried: tuple[TraitTried, ...]) -> str:
    """One line: the traits that alone make the candidate pass, or that none does."""
    cures = [item for item in tried if item.passes]
    if not cures:
        names = ", ".join(item.trait for item in tried)
        return f"fails still with the baseline's {names}, each alone: not one trait alone"
    named = ", ".join(f"{item.trait} ({_value(item.baseline_value)})" for item in cures)
    return f"passes with the baseline's {named}: the failure comes from the driver"


def _value(value: object) -> str:
    return f"{value:g} s" if isinstance(value, float) else str(value)


@dataclass(frozen=True)
class ChainTried:
    """The candidate at the failing placement with the pair's scan filter chain taken out."""

    file: str  # the chain's params file, as the pairs file names it
    passes: bool  # whether the candidate then passes


def blame_chain(setting: Setting, obstacle: Obstacle) -> ChainTried | None:
    """The candidate driven past `obstacle` straight into the stack; None without a chain."""
    chain = setting.controller.scan_filters
    if chain is None:
        return None
    bare = dataclasses.replace(setting, controller=without_scan_filters(setting.controller))
    run = bare.drive_past(setting.pair.candidate.profile, obstacle)
    return ChainTried(chain.file, run.passed)


def chain_text(tried: ChainTried) -> str:
    """One line: whether the chain alone explains the failure."""
    if tried.passes:
        return (
            f"passes without {tried.file}'s chain: the chain alone explains the failure "
            "(tune it for the candidate's scanner)"
        )
    return f"fails without {tried.file}'s chain too: the chain alone does not explain it"
