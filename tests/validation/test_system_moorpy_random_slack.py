"""The slack family of the random spread moorings against NREL/MoorPy (2 % to 25 %
longer than taut: junctions resting on the seabed, legs laid): the oracles and their
tolerances are test_system_moorpy_random.py's."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.validation.test_system_moorpy_random import check_spread


# seeds 1, 4, 5: a point no line pulls (refused by name), a slack laid line (refused by
# name), MoorPy's catenary pulling 62 MN at one end and nothing at the other (ours solves)
@pytest.mark.parametrize("seed", [1, 4, 5])
def test_random_slack_spread_matches_moorpy(tmp_path: Path, seed: int) -> None:
    check_spread(tmp_path, seed, (1.02, 1.25))
