"""nav2_costmap_2d's obstacle layer integration tests (test/integration/obstacle_tests.cpp),
rebuilt on our Nav2 costmap (`Nav2Costmap`): points observed by its obstacle layer (`cleared`,
`marked`) in a fixed 10 x 10 costmap of 1 m cells, read back as the layers combine them.

Not applicable: testRepeatedResets (layer parameters declared through the node, and reset) and
testDynParamsSetObstacle, testDynParamsSetVoxel and testDynParamsSetStatic (the parameter
service), none of which we imitate; the tests inside `#if (0)` are not compiled upstream.
"""

from __future__ import annotations

from pytest_lasertest.nav.move_base.cost_values import LETHAL, UNKNOWN
from tests.helpers.nav2_costmap import Observation, costmap, count, update
from tests.helpers.upstream import NAVIGATION2_JAZZY, NotPorted, Source

OBSTACLE = Source(
    "Nav2 costmap: obstacle layer",
    NAVIGATION2_JAZZY,
    "nav2_costmap_2d/test/integration/obstacle_tests.cpp",
)
NOT_PORTED = (
    NotPorted(
        OBSTACLE,
        "TestNodeWithoutUnknownOverwrite.testMaxWithoutUnknownOverwriteCombinationMethod",
        1,
        "combination_method is not imitated: our obstacle layer combines as Max (1), Nav2's "
        "default; MaxWithoutUnknownOverwrite (2) cannot be set",
    ),
)


@OBSTACLE.test("TestNode.testRaytracing", assertions=2)
def test_a_point_nearer_than_the_minimum_obstacle_range_marks_nothing() -> None:
    # The static layer of the test never receives its map: it adds nothing.
    layers = costmap(10, 1.0)
    seen = [Observation(0.0, 0.0)]
    update(layers, seen)
    assert count(layers.combined(), LETHAL) == 1
    # sqrt(2) m away, with obstacle and raytrace minimum ranges of 5 m.
    seen.append(Observation(1.0, 1.0, raytrace_min_range=5.0, obstacle_min_range=5.0))
    update(layers, seen)
    assert count(layers.combined(), LETHAL) == 1


@OBSTACLE.test("TestNode.testMaxCombinationMethod", assertions=1)
def test_an_observation_in_unknown_space_makes_only_its_own_cell_known() -> None:
    layers = costmap(10, 1.0, track_unknown_space=True)
    update(layers, [Observation(0.0, 0.0)])
    assert count(layers.combined(), UNKNOWN) == 99
