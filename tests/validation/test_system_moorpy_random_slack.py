"""The slack family of the random spread moorings against NREL/MoorPy (2 % to 25 %
longer than taut: junctions resting on the seabed, legs laid): the oracles and their
tolerances are test_system_moorpy_random.py's."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.validation.test_system_moorpy_random import check_spread


@pytest.mark.parametrize("seed", range(6))
def test_random_slack_spread_matches_moorpy(tmp_path: Path, seed: int) -> None:
    check_spread(tmp_path, seed, (1.02, 1.25))
