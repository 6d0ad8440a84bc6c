"""The coverage item of a pair, `PAIR[coverage]`: the candidate must scan everything its
baseline scanned, on the same robot (`model/coverage.py`)."""

from __future__ import annotations

from pytest_lasertest.model.coverage import CoverageComparison, compare_coverage
from pytest_lasertest.plugin.items.base import PairItem
from pytest_lasertest.reports.coverage import coverage_properties, coverage_report
from pytest_lasertest.reports.formats import Artifacts


class CoverageItem(PairItem):
    """Checks that the candidate scans everything its baseline scanned, on the same robot."""

    kind = "coverage"

    def runtest(self) -> None:
        comparison = compare_coverage(
            self.pair.baseline.profile,
            self.pair.candidate.profile,
            min_obstacle_size=self.spec.settings.min_obstacle_size,
            max_speed=self.spec.robot.max_linear_velocity,
        )
        self.user_properties += [
            ("lasertest.seed", self.seed),
            *coverage_properties(comparison),
        ]
        if comparison.losses:
            artifact = self._write_evidence(comparison)
            report = coverage_report(self.pair, comparison, self.replay, artifact)
            raise self.failure("coverage-loss", report, artifact)

    def _write_evidence(self, comparison: CoverageComparison) -> Artifacts:
        """The numbers of the loss, if the run asked for artifacts."""
        options = self.options
        if options.artifacts is None:
            return Artifacts()
        from pytest_lasertest.artifacts.evidence import evidence_header, write_coverage_evidence

        header = evidence_header(self.nodeid, self.spec, self.pair, options.recorded(self.path))
        scanners = (self.pair.baseline, self.pair.candidate)
        return write_coverage_evidence(options.artifacts, self.nodeid, scanners, comparison, header)
