"""``cablestudy validate`` and ``cablestudy schema`` start fast because they import none
of the heavy libraries the solvers and the output need (issue 10, item 6).

Checked as a set of modules in a fresh interpreter rather than as a wall time (the
project asserts no wall-clock speed in tests; ``make bench`` and the README report it):
importing xarray (with pandas), dask, numba, matplotlib or scipy's interpolate, sparse,
integrate and optimize costs about a second, several times the budget of 0.5 s.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HEAVY = (
    "xarray",
    "pandas",
    "dask",
    "distributed",
    "numba",
    "llvmlite",
    "matplotlib",
    "netCDF4",
    "h5netcdf",
    "scipy.interpolate",
    "scipy.sparse",
    "scipy.integrate",
    "scipy.optimize",
)

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
    "args",
    [
        ["validate", "configs/catenary-in-air.yaml"],
        ["validate", "configs/moustafa-fig6.yaml"],  # dynamic analysis and a sweep
        ["validate", "configs/vaz-patel-turning-current.yaml"],  # shooting, current
        ["validate", "configs/irvine-modal-lambda.yaml"],  # modal analysis
        ["schema"],
    ],
    ids=lambda a: "-".join(Path(p).stem for p in a),
)
def test_command_imports_no_heavy_library(args: list[str]) -> None:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run(
        [sys.executable, "-c", _CHILD, *args],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=env,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    result = json.loads(done.stdout)
    assert result["code"] == 0
    loaded = [m for m in result["modules"] if any(m == h or m.startswith(h + ".") for h in HEAVY)]
    assert not loaded, f"{' '.join(args)} imported {sorted({m.split('.')[0] for m in loaded})}"


#: a static catenary sweep run as arrays (cablestudy.grid) needs the compiled batch kernel
#: (numba, which loads scipy.linalg) and netCDF4; not xarray with pandas, dask or
#: distributed (xarray imports the last two when they are installed), nor the rest of scipy
ARRAY_RUN_HEAVY = tuple(h for h in HEAVY if h not in ("numba", "llvmlite", "netCDF4"))

ARRAY_SWEEP = """\
name: light
environment: {fluid: air}
line:
  segments:
    - {length: 100.0, diameter: 0.02, mass_per_length: 2.466, axial_stiffness: 6.283e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, 0.0]}
  b: {kind: fixed, position: [92.5, 0.0, -8.6]}
analysis:
  static: {method: catenary, nodes: 20}
sweep:
  ends.b.position.0: {start: 60.0, stop: 99.0, num: 14, name: span}
  line.segments.0.axial_stiffness: [1.0e6, 6.283e7]
"""


@pytest.mark.parametrize("cache", [False, True], ids=["no-cache", "cache"])
def test_array_sweep_run_imports_no_output_framework(tmp_path: Path, cache: bool) -> None:
    config = tmp_path / "light.yaml"
    config.write_text(ARRAY_SWEEP)
    args = ["run", str(config), "--out", str(tmp_path / "out"), "--scheduler", "synchronous"]
    args += [] if cache else ["--no-cache"]
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
    assert (tmp_path / "out" / "light.nc").is_file()
    loaded = [
        m
        for m in result["modules"]
        if any(m == h or m.startswith(h + ".") for h in ARRAY_RUN_HEAVY)
    ]
    assert not loaded, f"run imported {sorted({m.split('.')[0] for m in loaded})}"
    assert "cablestudy.dynamics" not in result["modules"]
