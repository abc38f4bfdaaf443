"""A system study's sweep of its harmonic excitation in the frequency domain run as
arrays (cablestudy.analyses.system_fd_grid, issue 24): from the study file to the
dataset, every case's record is the one the case-by-case evaluation gives it, bit for
bit (values, status, message, warnings, fallback), and a case alone (a chunk of one) is
the same record as in its sweep; what the arrays do not take runs case by case and is
counted. The reference everywhere is the same code's case-by-case path, so the
comparisons are exact (no tolerance): the arrays path computes the same floating-point
operations on the same inputs."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses.counters import COUNTERS
from cablestudy.cli import main

CONFIG = Path(__file__).parents[2] / "configs" / "system-case8-surge.yaml"
DYNAMIC = """\
  dynamic:
    excitation: {body: body1, dof: surge, amplitude: 2.0, frequency: 0.1}
    method: %s
    elements: 6
%s"""
#: a sweep of frequency and amplitude: at 0.45 Hz and 3 m the bridles go slack (the
#: slack warning's text is per case)
SWEEP = """\
sweep:
  analysis.dynamic.excitation.frequency: [0.05, 0.2, 0.45]
  analysis.dynamic.excitation.amplitude: [0.5, 3.0]
"""
#: what a run stamps (as benchmarks/compare_datasets.py drops it)
STAMPS = ("wall_time", "case_hash")


def _text(method: str = "frequency", extra: str = "", sweep: str = SWEEP) -> str:
    text = CONFIG.read_text()
    return text[: text.index("  dynamic:")] + DYNAMIC % (method, extra) + sweep


def _run(tmp_path: Path, text: str, name: str) -> xr.Dataset:
    cfg = tmp_path / f"{name}.yaml"
    cfg.write_text(text)
    out = tmp_path / name
    args = ["run", str(cfg), "--out", str(out), "--no-cache", "--no-progress"]
    assert main([*args, "--scheduler", "synchronous"]) == 0
    ds = xr.load_dataset(out / "system-case8-surge.nc")
    ds = ds.drop_vars([v for v in STAMPS if v in ds.variables])
    ds.attrs = {k: v for k, v in ds.attrs.items() if k not in ("history", "cablestudy_code_sha256")}
    return ds


def _case_by_case(tmp_path: Path, text: str, monkeypatch: pytest.MonkeyPatch) -> xr.Dataset:
    """The study run with its cases unmarked: the case-by-case path of every system
    study (cablestudy.analyses.system.evaluate_system_case)."""
    from cablestudy.analyses import system_fd_grid

    with monkeypatch.context() as m:
        m.setattr(system_fd_grid, "excitation_sweep", lambda grid: grid)
        return _run(tmp_path, text, "cases")


def _grid(text: str):  # noqa: ANN202
    from cablestudy.run.grid_runner import study_grid
    from cablestudy.study.loader import parse_study_text

    return study_grid(parse_study_text(text, "case8.yaml"))


def _same_chunks(a, b) -> None:  # noqa: ANN001
    """Two chunks of the same cases hold the same record of each case, bit for bit."""
    at = {h: j for j, h in enumerate(b.hashes.tolist())}
    order = np.array([at[h] for h in a.hashes.tolist()])
    for attr in ("status", "message", "warning", "fallback_reason", "hashes"):
        np.testing.assert_array_equal(getattr(a, attr), getattr(b, attr)[order], err_msg=attr)
    assert sorted(a.data) == sorted(b.data)
    for name, arr in a.data.items():
        other = b.data[name][order]
        assert arr.dtype.kind == other.dtype.kind, name
        np.testing.assert_array_equal(arr, other, err_msg=name)  # NaN equals NaN here


def test_an_excitation_sweep_runs_as_arrays_with_the_records_of_the_cases_alone(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from cablestudy.analyses.grid_chunk import records_chunk
    from cablestudy.analyses.system import evaluate_system_case
    from cablestudy.analyses.system_fd_grid import ExcitationGrid, evaluate_excitation_chunk

    text = _text()
    grid = _grid(text)
    assert isinstance(grid, ExcitationGrid)
    before = COUNTERS["fd_grid_cases"], COUNTERS["fd_grid_fallback"]
    arrays = _run(tmp_path, text, "arrays")
    assert COUNTERS["fd_grid_cases"] - before[0] == 6  # every case as arrays
    assert COUNTERS["fd_grid_fallback"] == before[1]
    assert np.all(arrays.status.values == 0), arrays.message.values
    assert any("slack" in str(w) for w in arrays.warning.values.ravel())  # warnings per case
    # the dataset is the case-by-case path's, every variable and attribute bit for bit
    xr.testing.assert_identical(arrays, _case_by_case(tmp_path, text, monkeypatch))
    # and chunk by chunk: the sweep as one chunk, each case as a chunk of one, and each
    # case by evaluate_system_case hold the same records
    cases = grid.cases()
    together = evaluate_excitation_chunk(cases)
    reference = records_chunk([evaluate_system_case(c) for c in cases], system=True)
    _same_chunks(together, reference)
    for k, case in enumerate(cases):
        alone = evaluate_excitation_chunk([case])
        row = np.flatnonzero(together.hashes == case.hash)
        for name, arr in alone.data.items():
            got = together.data[name][row]
            if arr.dtype.kind == "U":  # a text column is as wide as its longest text
                got = got.astype(arr.dtype)
            np.testing.assert_array_equal(arr, got, err_msg=f"{name} case {k}")
        assert alone.warning[0] == together.warning[row[0]]


def test_what_the_arrays_cannot_take_runs_case_by_case_counted(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """At most 5 drag iterations: the case at 0.02 Hz converges (3 iterations at the
    default settings), the others do not; they are recorded as the case-by-case path
    records them (status, message, NaN) and counted, and the study carries on."""
    text = _text(
        extra="    linearisation: {max_iterations: 5}\n",
        sweep="sweep:\n  analysis.dynamic.excitation.frequency: [0.02, 0.3, 0.5]\n",
    )
    before = COUNTERS["fd_grid_cases"], COUNTERS["fd_grid_fallback"]
    arrays = _run(tmp_path, text, "arrays")
    status = arrays.status.values
    assert status[0] == 0 and np.all(status[1:] != 0), arrays.message.values
    assert all(str(m).startswith("dynamic analysis:") for m in arrays.message.values[1:])
    assert np.all(np.isnan(arrays.tension_amplitude_a.values[1:]))
    assert COUNTERS["fd_grid_cases"] - before[0] == 1
    assert COUNTERS["fd_grid_fallback"] - before[1] == 2
    xr.testing.assert_identical(arrays, _case_by_case(tmp_path, text, monkeypatch))


@pytest.mark.parametrize(
    ("method", "sweep"),
    [
        ("auto", SWEEP),  # auto judges each case (and may run the time domain)
        ("frequency", "sweep:\n  analysis.dynamic.elements: [4, 6]\n"),  # a new model
        ("frequency", "sweep:\n  bodies.body1.position.0: [0.0, 1.0]\n"),  # new statics
    ],
)
def test_other_sweeps_are_not_run_as_excitation_arrays(method: str, sweep: str) -> None:
    from cablestudy.analyses.system_fd_grid import ExcitationCase, ExcitationGrid

    grid = _grid(_text(method, sweep=sweep))
    assert not isinstance(grid, ExcitationGrid)
    assert not any(isinstance(c, ExcitationCase) for c in grid.cases())


def test_the_cache_is_the_case_by_case_cache(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """The arrays path keeps each case's content hash as its cache key: a sweep cached
    by the case-by-case path and then given one more frequency reuses the cached cases
    and computes the new one as arrays, into the dataset a fresh run gives."""
    from cablestudy.analyses import system_fd_grid

    three = "sweep:\n  analysis.dynamic.excitation.frequency: [0.05, 0.2, 0.45]\n"
    four = "sweep:\n  analysis.dynamic.excitation.frequency: [0.05, 0.1, 0.2, 0.45]\n"
    out = tmp_path / "cached"

    def run(text: str) -> str:
        cfg = tmp_path / "study.yaml"
        cfg.write_text(text)
        args = ["run", str(cfg), "--out", str(out), "--no-progress", "--scheduler", "synchronous"]
        capsys.readouterr()
        assert main(args) == 0
        return capsys.readouterr().out

    with monkeypatch.context() as m:
        m.setattr(system_fd_grid, "excitation_sweep", lambda grid: grid)
        assert "3 computed, 0 reused" in run(_text(sweep=three))
    before = COUNTERS["fd_grid_cases"]
    assert "1 computed, 3 reused" in run(_text(sweep=four))
    assert COUNTERS["fd_grid_cases"] - before == 1
    ds = xr.load_dataset(out / "system-case8-surge.nc")
    ds = ds.drop_vars([v for v in STAMPS if v in ds.variables])
    ds.attrs = {k: v for k, v in ds.attrs.items() if k not in ("history", "cablestudy_code_sha256")}
    xr.testing.assert_identical(ds, _run(tmp_path, _text(sweep=four), "fresh"))
