"""The still-water batch kernels compiled ahead of time (cablestudy.statics.aot, issue 20,
"Speed"): the same numbers as numba's kernels bit for bit, sweeps of lines hanging free
and of lines resting on the seabed run end to end without importing numba or scipy, and
numba's kernels wherever the module cannot be built or loaded.

The module is built once per version of the source with the static kernels, as
``cablestudy compile`` builds it (about 8 s on the development machine, the price of
numba's own first compilation)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from cablestudy import kernels
from cablestudy.analyses.static_grid import evaluate_grid_chunk
from cablestudy.statics import _fast, aot
from cablestudy.study import parse_study_text
from cablestudy.study.grid import expand_grid

ROOT = Path(__file__).resolve().parents[2]

#: lines hanging free in air and in water: slack to taut (chord 50-99.9 % of the
#: unstretched length), soft to stiff, two segments and a clump weight (point loads
#: between pieces), end A above, level with and below end B
SWEEP = """\
name: aot
environment: {fluid: water}
line:
  segments:
    - {length: 60.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
    - {length: 40.0, diameter: 0.05, mass_per_length: 8.0, axial_stiffness: 2.0e8}
  attachments:
    - {s: 30.0, mass: 50.0, volume: 0.01}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {nodes: 25}
sweep:
  ends.b.position.0: {start: 50.0, stop: 99.9, num: 9, name: span}
  line.segments.0.axial_stiffness: [1.0e5, 1.0e6, 6.283e7, 1.0e10]
  ends.a.position.2: [-30.0, -8.6, 15.0]
"""

IN_AIR = """\
name: light
environment: {fluid: air}
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {nodes: 20}
sweep:
  ends.b.position.0: {start: 60.0, stop: 99.0, num: 14, name: span}
  line.segments.0.axial_stiffness: [1.0e6, 6.283e7]
"""


@pytest.fixture(scope="module")
def built() -> Path:
    if shutil.which(os.environ.get("CC", "cc")) is None and shutil.which("gcc") is None:
        pytest.skip("no C compiler: the module cannot be built (numba's kernel is used)")
    if not kernels.is_compiled("statics"):  # as `cablestudy compile` leaves the cache
        kernels.compile_kind("statics")
    assert aot.build(), "numba.pycc failed to build the module with a C compiler present"
    return aot.module_path()


@pytest.fixture()
def loaded(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(aot, "_LOADED", {})


#: lines from an anchor on a flat seabed with friction (most with a laid part, some
#: lifting off at the anchor, some hanging free of the seabed: both kernels run)
SEABED = """\
name: bed
environment: {fluid: water, depth: 100.0, seabed: {friction: 0.5}}
line:
  segments:
    - {length: 300.0, diameter: 0.076, mass_per_length: 126.0, axial_stiffness: 5.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -100.0]}
  b: {kind: fixed, position: [250.0, 0.0, -10.0]}
analysis:
  static: {nodes: 20}
sweep:
  ends.b.position.0: {start: 215.0, stop: 295.0, num: 16, name: offset}
  line.segments.0.axial_stiffness: [1.0e6, 1.0e8, 2.0e9]
"""


@pytest.mark.parametrize("text", [SWEEP, SEABED], ids=["hanging", "seabed"])
def test_the_module_gives_numba_s_numbers_bit_for_bit(
    text: str, built: Path, loaded: None, monkeypatch: pytest.MonkeyPatch
) -> None:
    grid = expand_grid(parse_study_text(text, "aot.yaml"))
    assert grid is not None and grid.arrays
    assert aot.kernel("solve_cases") is not _fast.solve_cases  # the built module
    ahead = evaluate_grid_chunk(grid, 0, grid.shape[0])
    monkeypatch.setitem(aot._LOADED, str(built), None)  # as if not built: numba's kernels
    assert aot.kernel("solve_cases") is _fast.solve_cases
    jit = evaluate_grid_chunk(grid, 0, grid.shape[0])
    assert np.array_equal(ahead.fallback_reason, jit.fallback_reason)
    assert np.array_equal(ahead.status, jit.status)
    assert np.array_equal(ahead.message, jit.message)
    assert np.array_equal(ahead.fallback_reason, jit.fallback_reason)
    assert ahead.data.keys() == jit.data.keys()
    for name, values in jit.data.items():
        # the same functions through the same lowering without fast-math: identical bits
        assert ahead.data[name].tobytes() == values.tobytes(), name
    # the sweep did exercise the kernels: most cases settled there, verified
    assert np.count_nonzero(jit.fallback_reason == "") > 0.5 * grid.size
    assert np.count_nonzero(jit.status == 0) > 0.5 * grid.size
    if text is SEABED:
        laid = jit.data["laid_length"]
        assert np.count_nonzero(laid > 0.0) > 0.25 * grid.size  # the contact kernel
        assert np.count_nonzero(laid == 0.0) > 0  # and lines hanging free


def _degenerate() -> list[np.ndarray]:
    """The arguments of :func:`._fast.solve_cases` for a line of zero length between
    coincident ends: its residual scale is 0, so the kernel divides by zero."""
    N, P, n = 1, 1, 5
    return [
        np.zeros((N, P)),  # piece lengths
        np.full((N, P), 1e6),
        np.full((N, P), 10.0),
        np.zeros((N, P + 1, 3)),
        np.zeros((N, P + 1)),  # bounds
        np.zeros(N, dtype=np.int64),
        np.zeros((N, 3)),
        np.zeros((N, 3)),  # B at A
        np.array([[0.0, 0.0, 1.0]]),
        np.full(N, 1e-9),
        np.full(N, 50, dtype=np.int64),
        np.zeros((N, n)),
        np.zeros((N, n, 3)),
        np.zeros((N, n)),
        np.zeros((N, 3)),
        np.zeros((N, 3)),
        np.zeros(N, dtype=np.int64),
        np.zeros(N),
        np.zeros(N, dtype=np.int64),
    ]


def test_a_division_by_zero_is_numba_s_not_an_exception(built: Path, loaded: None) -> None:
    """The kernels' own error model (``error_model="numpy"``: inf or NaN, then the
    kernel's finiteness checks), not pycc's default (which raises ZeroDivisionError and
    would fail the whole chunk of cases)."""
    expected, got = _degenerate(), _degenerate()
    _fast.solve_cases(*expected)
    kernel = aot.kernel("solve_cases")
    assert kernel is not _fast.solve_cases
    kernel(*got)
    assert expected[-1][0] == 1 and np.isnan(expected[-2][0])  # not converged, said so
    for a, b in zip(expected, got, strict=True):
        assert a.tobytes() == b.tobytes()


_CHILD = textwrap.dedent(
    """
    import contextlib, io, json, sys
    from cablestudy.cli import main

    with contextlib.redirect_stdout(io.StringIO()):
        code = main(sys.argv[1:])
    print(json.dumps({"code": code, "modules": sorted(sys.modules)}))
    """
)


@pytest.mark.parametrize(
    ("text", "name", "shape"), [(IN_AIR, "light", (14, 2)), (SEABED, "bed", (16, 3))]
)
def test_a_still_water_sweep_runs_without_numba(
    built: Path, tmp_path: Path, text: str, name: str, shape: tuple[int, int]
) -> None:
    """End to end, YAML to netCDF, in a fresh interpreter (the module is found in the
    cache directory of this source version, which the child inherits)."""
    config = tmp_path / f"{name}.yaml"
    config.write_text(text)
    args = ["run", str(config), "--out", str(tmp_path / "out"), "--no-cache"]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run(
        [sys.executable, "-c", _CHILD, *args],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=env,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    result = json.loads(done.stdout)
    assert result["code"] == 0
    import netCDF4

    with netCDF4.Dataset(tmp_path / "out" / f"{name}.nc") as nc:
        assert nc.variables["tension_b"].shape == shape
        assert np.all(nc.variables["status"][...] == 0)
        if text is IN_AIR:
            assert int(nc.cases_fallback) == 0  # every case from the (compiled) kernel
    heavy = ("numba", "llvmlite", "scipy")
    loaded = sorted({m.split(".")[0] for m in result["modules"] if m.split(".")[0] in heavy})
    assert not loaded, f"the run imported {loaded}"
    assert aot.MODULE in result["modules"]


def test_numba_s_kernel_where_the_module_is_missing_or_broken(
    tmp_path: Path, loaded: None, monkeypatch: pytest.MonkeyPatch
) -> None:
    from cablestudy.statics import _fast_contact

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    assert not aot.module_path().exists()
    assert aot.kernel("solve_cases") is _fast.solve_cases
    assert aot.kernel("contact_cases") is _fast_contact.contact_cases
    monkeypatch.setattr(aot, "_LOADED", {})
    aot.module_path().write_bytes(b"not a shared object")  # e.g. a truncated copy
    assert aot.kernel("solve_cases") is _fast.solve_cases


def test_a_failed_build_leaves_nothing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    monkeypatch.setitem(sys.modules, "numba.pycc", None)  # as without numba: ImportError
    assert aot.build() is False
    assert list(tmp_path.iterdir()) == []
