"""Random studies nobody on the team wrote, run YAML -> netCDF and checked independently of
the solvers (tests/stress_studies.py): never a silent NaN, status 0 means verified.

A fixed-seed sample runs here (well under a minute: each study a few cases, small
meshes); ``CABLESTUDY_STRESS_COUNT=N`` runs N more seeds (from 1000), and
``benchmarks/stress_random.py`` runs batches from the command line with a count of the
anomalies by kind.

What is checked, per run and per case (the kinds of :func:`tests.stress_studies.check_run`):
no Python traceback, no numpy RuntimeWarning, exit 0/3 with a dataset or 2 with a message
naming the field; a status-0 case has finite outputs, the study's end positions, no
negative tension, no node interval stretched beyond its arc, the whole line's balance of
forces and the tension's change dT = w dz / (1 + e) between suspended nodes where the
loads are known; a failed case has a message and NaN in the failed analysis, the statics
kept when only the dynamics failed; dynamic extremes ordered max >= mean >= min.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from tests.stress_studies import check_run, check_swap, generate, run_study, swapped

#: seeds chosen to cover the generator's branches with studies that solve (statics by
#: each method, force/mooring ends, seabed with friction and slope, current, attachments,
#: bending, modal, time/frequency/auto dynamics with harmonic and table motion, systems
#: on a free point and on a body, a refused key), each a few cases of small meshes
SEEDS = [2, 4, 10, 12, 29, 33, 37, 41, 42, 51, 55, 76, 79, 82]

EXTRA = int(os.environ.get("CABLESTUDY_STRESS_COUNT", "0"))


def _anomalies(seed: int, tmp_path: Path) -> list[tuple[str, str]]:
    study, meta = generate(seed)
    res = run_study(study, tmp_path / str(seed), in_process=True)
    found = check_run(study, meta, res)
    twin = swapped(study) if seed % 3 == 0 else None
    if twin is not None:
        found += check_swap(res, run_study(twin, tmp_path / str(seed), in_process=True), meta)
    # info_* kinds are documented behaviour worth counting in a batch (a refusal naming
    # its field, the elevation's second-order differences), not defects
    return [(k, t) for k, t in found if not k.startswith("info_")]


@pytest.mark.parametrize("seed", SEEDS)
def test_a_random_study_runs_clean(seed: int, tmp_path: Path) -> None:
    found = _anomalies(seed, tmp_path)
    assert not found, f"seed {seed}: " + "; ".join(f"[{k}] {t[:300]}" for k, t in found)


@pytest.mark.parametrize("seed", range(1000, 1000 + EXTRA))
def test_more_random_studies_run_clean(seed: int, tmp_path: Path) -> None:
    found = _anomalies(seed, tmp_path)
    assert not found, f"seed {seed}: " + "; ".join(f"[{k}] {t[:300]}" for k, t in found)
