"""The `driver` line of a regression's report: the traits that alone make the candidate pass."""

from __future__ import annotations

from pytest_lasertest.search.blame import TraitTried, blame_text


def test_the_traits_that_alone_make_the_candidate_pass_are_named_with_the_baselines_value() -> None:
    tried = (
        TraitTried("no_return", "inf", passes=True),
        TraitTried("latency", 0.003125, passes=False),
        TraitTried("stamp", "start", passes=True),
    )
    assert blame_text(tried) == (
        "passes with the baseline's no_return (inf), stamp (start): "
        "the failure comes from the driver"
    )


def test_when_no_trait_alone_makes_it_pass_the_line_says_so() -> None:
    tried = (TraitTried("no_return", "inf", False), TraitTried("latency", 0.0, False))
    assert blame_text(tried) == (
        "fails still with the baseline's no_return, latency, each alone: not one trait alone"
    )
