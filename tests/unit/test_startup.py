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
        timeout=600,  # a bound on a hang, not a speed check (the machine may be loaded)
    )
    assert done.returncode == 0, done.stderr[-3000:]
    result = json.loads(done.stdout)
    assert result["code"] == 0
    loaded = [m for m in result["modules"] if any(m == h or m.startswith(h + ".") for h in HEAVY)]
    assert not loaded, f"{' '.join(args)} imported {sorted({m.split('.')[0] for m in loaded})}"


#: a static catenary sweep run as arrays (cablestudy.analyses.static_grid) needs the
#: compiled batch kernel (numba, which loads scipy.linalg, unless the module compiled ahead
#: of time is built: tests/unit/test_aot.py) and netCDF4; not xarray with pandas, dask or
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


def _run_modules(tmp_path: Path, config: Path) -> list[str]:
    """The modules loaded by ``cablestudy run config`` in a fresh interpreter."""
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
    return result["modules"]


def _loaded(modules: list[str], names: tuple[str, ...]) -> list[str]:
    return sorted(m for m in modules if any(m == n or m.startswith(n + ".") for n in names))


#: what a run of statics alone never needs: the line model and both dynamic solvers
#: (about 0.3 s of imports and kernel loads), and dask's cluster
STATIC_RUN_ABSENT = ("cablestudy.dynamics", "cablestudy.analyses.frequency", "distributed")
#: what a frequency-domain run never needs: the time integrator and its end motions
#: (scipy.interpolate comes with a time table only), and dask's cluster
FREQUENCY_RUN_ABSENT = (
    "cablestudy.dynamics.timedomain",
    "cablestudy.dynamics.integrator",
    "cablestudy.dynamics.pulley_timedomain",
    "cablestudy.dynamics.excitation",
    "scipy.interpolate",
    "distributed",
)


def test_static_run_loads_no_dynamics(tmp_path: Path) -> None:
    """A study of statics alone run case by case (not as an array grid): the chunk
    evaluator asks the frequency domain only for cases that have a dynamic analysis."""
    modules = _run_modules(tmp_path, ROOT / "configs/catenary-in-air.yaml")
    assert (tmp_path / "out" / "catenary-in-air.nc").is_file()
    assert "cablestudy.analyses" in modules  # the case-by-case path did run
    assert not _loaded(modules, STATIC_RUN_ABSENT)


def test_frequency_run_loads_no_time_domain(tmp_path: Path) -> None:
    """A sweep answered in the frequency domain (method: frequency) over amplitude and
    frequency of the Moustafa cable: the harmonic solver runs, the integrator does not
    load."""
    text = (ROOT / "configs/moustafa-figs2-5.yaml").read_text()
    text = text.replace("name: moustafa-figs2-5", "name: frequency-only")
    text = text.replace("method: auto", "method: frequency")
    text = text.replace("[0.025, 0.05, 0.075, 0.1]", "[0.025, 0.05]")
    text = text.replace("num: 23", "num: 3")
    assert "method: frequency" in text and "num: 3" in text  # the edits took
    config = tmp_path / "frequency-only.yaml"
    config.write_text(text)
    modules = _run_modules(tmp_path, config)
    assert (tmp_path / "out" / "frequency-only.nc").is_file()
    assert "cablestudy.dynamics.harmonic_cases" in modules  # the frequency domain ran
    assert not _loaded(modules, FREQUENCY_RUN_ABSENT)


_EXIT_CHILD = textwrap.dedent(
    """
    import atexit, contextlib, gc, io, sys
    from cablestudy.cli import main

    as_program = sys.argv[1] == "program"
    sys.argv = ["cablestudy", "schema"]
    with contextlib.redirect_stdout(io.StringIO()):
        code = main() if as_program else main(["schema"])
    before = gc.get_freeze_count()
    atexit._run_exitfuncs()
    print(code, before, gc.get_freeze_count())
    """
)


@pytest.mark.parametrize("how", ["program", "call"])
def test_program_exit_skips_the_final_collection(how: str) -> None:
    """``cablestudy`` as a program freezes the heap at exit (the interpreter's shutdown
    collections over numba's and pydantic's objects cost about 0.3 s); a caller of
    ``main(argv)`` in its own process keeps its garbage collector as it was."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run(
        [sys.executable, "-c", _EXIT_CHILD, how],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=env,
        timeout=600,  # a bound on a hang, not a speed check (the machine may be loaded)
    )
    assert done.returncode == 0, done.stderr[-3000:]
    code, before, after = (int(v) for v in done.stdout.split())
    assert code == 0 and before == 0
    assert (after > 0) == (how == "program")


_PAUSE_CHILD = textwrap.dedent(
    """
    import contextlib, gc, io, json, sys
    import cablestudy.run.runner as runner
    from cablestudy.cli import main

    seen = {}
    study = runner.run_study

    def spy(*args, **kwargs):
        seen.update(enabled=gc.isenabled(), frozen=gc.get_freeze_count())
        return study(*args, **kwargs)

    runner.run_study = spy
    sys.argv = ["cablestudy", *sys.argv[1:]]
    with contextlib.redirect_stdout(io.StringIO()):
        code = main()
    print(json.dumps({"code": code, "enabled_after": gc.isenabled(), **seen}))
    """
)


def test_run_collects_garbage_during_its_study(tmp_path: Path) -> None:
    """``cablestudy run`` pauses the garbage collector over its start-up only: the study
    (which may run for hours and make cyclic garbage) runs with it on, the start-up's
    objects frozen out of its collections."""
    args = ["run", "configs/catenary-in-air.yaml", "--out", str(tmp_path), "--no-cache"]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run(
        [sys.executable, "-c", _PAUSE_CHILD, *args],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=env,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    result = json.loads(done.stdout)
    assert result["code"] == 0
    assert result["enabled"] and result["enabled_after"]
    # numpy, pydantic and the solvers alone leave tens of thousands of objects
    assert result["frozen"] > 10_000
