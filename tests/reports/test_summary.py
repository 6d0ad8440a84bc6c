"""The run's summary table: each pair's placement items summed up, and where the artifacts are."""

from __future__ import annotations

from pytest_lasertest.reports.summary import Summary


def searched(examples: int, rejected: int, **failure: object) -> list[tuple[str, object]]:
    rows: list[tuple[str, object]] = [
        ("lasertest.examples", examples),
        ("lasertest.rejected", rejected),
    ]
    return rows + [(f"lasertest.{key}", value) for key, value in failure.items()]


def test_the_summary_sums_each_pairs_placement_items_and_ignores_other_items() -> None:
    summary = Summary()
    summary.add("paper.lasertest.yaml::size[coverage]", True, [("lasertest.coverage_losses", 1)])
    summary.add("paper.lasertest.yaml::size[no-obstacle]", False, [])
    summary.add("paper.lasertest.yaml::size[candidate-misses-0]", False, searched(8, 1))
    summary.add(
        "paper.lasertest.yaml::size[candidate-misses-1]",
        True,
        searched(3, 0, failed_oracles="collision,goal", regressions=1),
    )
    summary.add(
        "paper.lasertest.yaml::size[baseline-misses-0]",
        True,
        searched(1, 0, failed_oracles="stuck,goal", pre_existing=1, marginal=1),
    )
    # Under the regression policy a pre-existing failure passes, and is still counted.
    summary.add(
        "paper.lasertest.yaml::size[baseline-misses-1]", False, searched(4, 0, pre_existing=2)
    )
    summary.add("husky.lasertest.yaml::ust[baseline-misses-0]", False, searched(8, 0))
    header, husky, size = (line.split() for line in summary.lines(artifacts=None))
    assert header[0] == "pair"
    assert husky == [
        "husky.lasertest.yaml::ust",
        "1",
        "8",
        "0",
        "(0%)",
        "0",
        "0",
        "0",
        "0",
        "0",
        "0",
        "0",
    ]
    assert size == [
        *("paper.lasertest.yaml::size", "4", "16", "1", "(6%)", "2"),
        *("1", "1", "2", "1", "1", "2"),
    ]


def test_the_summary_says_where_the_artifacts_of_failing_items_are() -> None:
    summary = Summary()
    summary.add("a.lasertest.yaml::p[candidate-misses-0]", True, searched(1, 0))
    assert summary.lines("lasertest-artifacts")[-1] == (
        "artifacts of the failures above and below: lasertest-artifacts"
    )


def test_a_run_without_placement_items_has_no_summary() -> None:
    summary = Summary()
    summary.add("a.lasertest.yaml::p[coverage]", True, [])
    assert summary.lines("out") == []


def test_the_markdown_table_has_a_row_per_pair_and_lists_each_failure_with_its_picture() -> None:
    summary = Summary()
    summary.add("a.lasertest.yaml::p[candidate-misses-0]", True, searched(3, 1, regressions=1))
    summary.add("a.lasertest.yaml::p[candidate-misses-1]", True, searched(2, 0))
    summary.add("b.lasertest.yaml::q|r[avoid-0]", False, searched(5, 0))
    pictures = {"a.lasertest.yaml::p[candidate-misses-0]": "out/a.lasertest.yaml/p_c-0.png"}
    lines = summary.markdown(pictures).splitlines()
    assert lines[2].split(" | ")[:3] == ["| pair", "witnesses", "examples"]
    assert lines[3] == "| --- |" + " ---: |" * 10  # the pair, then ten counts
    assert lines[4].startswith("| a.lasertest.yaml::p | 2 | 5 | 1 (17%) | 2 |")
    # A pipe in a pair's name would end its cell.
    assert lines[5].startswith("| b.lasertest.yaml::q\\|r | 1 | 5 |")
    assert lines[-2:] == [
        "- `a.lasertest.yaml::p[candidate-misses-0]`: picture `out/a.lasertest.yaml/p_c-0.png`",
        "- `a.lasertest.yaml::p[candidate-misses-1]`",
    ]


def test_a_run_without_placement_items_has_no_markdown_table() -> None:
    summary = Summary()
    summary.add("a.lasertest.yaml::p[coverage]", True, [])
    assert summary.markdown({}) == ""


def test_failures_that_do_not_fail_the_run_are_listed_by_category_with_their_headlines() -> None:
    summary = Summary()
    summary.note("b.lasertest.yaml::q[coverage]", "coverage-loss", "the candidate scans less")
    summary.note("a.lasertest.yaml::p[avoid-0]", "pre-existing", "both robots fail")
    summary.note("a.lasertest.yaml::p[avoid-1]", "marginal", "a noise draw undid it")
    assert summary.noted_lines() == [
        "COVERAGE-LOSS  b.lasertest.yaml::q[coverage]: the candidate scans less",
        "MARGINAL       a.lasertest.yaml::p[avoid-1]: a noise draw undid it",
        "PRE-EXISTING   a.lasertest.yaml::p[avoid-0]: both robots fail",
    ]
    # The job summary lists them too, without a table where no placement item searched.
    lines = summary.markdown({}).splitlines()
    assert lines[-3:] == [
        "- pre-existing: `a.lasertest.yaml::p[avoid-0]`: both robots fail",
        "- marginal: `a.lasertest.yaml::p[avoid-1]`: a noise draw undid it",
        "- coverage-loss: `b.lasertest.yaml::q[coverage]`: the candidate scans less",
    ]
    assert not any(line.startswith("| pair") for line in lines)
