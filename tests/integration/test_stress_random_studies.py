"""Random studies nobody on the team wrote, run YAML -> netCDF and checked independently of
the solvers (tests/stress_studies.py): never a silent NaN, status 0 means verified.

A fixed-seed sample runs here (well under a minute: each study a few cases, small
meshes); ``CABLESTUDY_STRESS_COUNT=N`` runs N more seeds (from 1000), and
``benchmarks/stress_random.py`` runs batches from the command line with a count of the
anomalies by kind.

What is checked, per run and per case (the kinds of :func:`tests.stress_checks.check_run`):
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

from tests.stress_checks import check_run, check_swap, run_study, swapped
from tests.stress_studies import generate

#: seeds chosen (from a batch of 150, benchmarks/stress_random.py --start 500) to cover
#: the generator's branches: statics by each method (500 shooting, 503 catenary, 513
#: analytic, 563 discrete with EI, friction, current and modal), ends swapped (513, 534,
#: 555), a free body on a system (522), frequency domain (517, 613; 546 a spectrum with
#: current, attachments and friction), method auto (508, 528, 568 with modal and
#: current), time domain with a table (628), a study where no case solves (510, exit 3),
#: refusals naming their field (542 an unexcited force end under method frequency, 551
#: bending stiffness under method catenary)
SEEDS = [500, 503, 508, 510, 513, 517, 522, 528, 534, 542, 546, 551, 555, 563, 568, 613, 628]

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


if EXTRA:  # defined only when asked for (no empty parameter set, no skip)

    @pytest.mark.parametrize("seed", range(1000, 1000 + EXTRA))
    def test_more_random_studies_run_clean(seed: int, tmp_path: Path) -> None:
        found = _anomalies(seed, tmp_path)
        assert not found, f"seed {seed}: " + "; ".join(f"[{k}] {t[:300]}" for k, t in found)


def test_the_checks_catch_a_wrong_answer(tmp_path: Path) -> None:
    """The checks are not vacuous: the same dataset with a tension 1 % off along the line,
    an end moved by 1 mm, or a NaN where the case says ok, is caught."""
    import dataclasses

    import xarray as xr

    study, meta = generate(503)
    res = run_study(study, tmp_path / "ok", in_process=True)
    assert check_run(study, meta, res) == []
    assert res.nc is not None
    ds = xr.load_dataset(res.nc)
    wrong = {
        "tension_gradient": ds.assign(tension=ds["tension"] * 1.01),
        "end_position": ds.assign(x=ds["x"] + 1e-3),
        "nan_when_ok": ds.assign(tension=ds["tension"].where(ds["s"] < ds["s"][-1])),
        "balance_z": ds.assign(force_a=ds["force_a"] * 1.001),
    }
    for kind, bad in wrong.items():
        path = tmp_path / f"{kind}.nc"
        bad.to_netcdf(path)
        found = check_run(study, meta, dataclasses.replace(res, nc=path))
        assert kind in {k for k, _ in found}, (kind, found)
