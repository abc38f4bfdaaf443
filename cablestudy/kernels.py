"""Compiling the numba kernels before the first study, and saying so when a run must.

numba compiles a kernel on its first call and keeps the machine code on disk
(``cache=True``, in the per-source cache directory :mod:`cablestudy` chooses). That first
call costs seconds to tens of seconds; without a word it looks like a slow study. So:

- ``make install`` runs ``cablestudy compile``, which compiles every kind of kernel in
  parallel processes (one kind a process, as many processes as cores) and prints what
  it did and how long it took;
- each kind, once compiled, leaves a marker file beside the machine code;
- a run whose analyses need a kind without a marker says so before it starts
  ("compiling the time-domain kernels, first run only, about 25 s"), compiles it in the
  main process (so that worker processes load it instead of each compiling it again),
  and leaves the marker.

The warm-ups run the kernels on small problems of the same types the analyses pass, so
that the signatures compiled are the ones a study needs.
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

#: per kind: what it is, for messages, and about how long its compilation takes on one
#: core of the 2-core development machine [s] (measured by ``cablestudy compile``)
KINDS: dict[str, tuple[str, float]] = {
    "statics": ("the static kernels", 18.0),
    "time": ("the time-domain kernels", 25.0),
    "frequency": ("the frequency-domain kernels", 10.0),
    "systems": ("the mooring-system dynamics kernels", 30.0),
}


def _warm_statics() -> None:
    """The catenary kernels (still water: free-hanging and seabed-contact batches, alone
    and stacked, nonlinear axial laws; the drag iteration in a current) and the
    quasi-static database lookup on small problems; then the still-water batch kernels
    compiled ahead of time."""
    import numpy as np

    from .statics.semi_analytic import SemiAnalyticSolver
    from .study.loader import parse_study_text, validate_data
    from .study.problem import static_problem

    text = """\
name: warm
environment: {fluid: water, depth: 60.0}
line:
  segments:
    - {length: 60.0, diameter: 0.02, mass_per_length: 2.5, axial_stiffness: 6.0e7}
    - {length: 40.0, diameter: 0.03, mass_per_length: 5.0, LAW}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -50.0]}
  b: {kind: fixed, position: [85.0, 0.0, -10.0]}
"""
    linear = text.replace("LAW", "axial_stiffness: 2.0e8")
    anchored = linear.replace("[0.0, 0.0, -50.0]", "[0.0, 0.0, -60.0]")  # on the seabed
    nonlinear = text.replace("LAW", "axial: {law: polynomial, coefficients: [2.0e8, 1.0e9]}")
    # in a current with no seabed: the compiled drag iteration (cablestudy.statics.batch_drag)
    current = linear.replace(
        "{fluid: water, depth: 60.0}", "{fluid: water, current: [{z: 0.0, speed: 0.5}]}"
    )
    for body in (linear, anchored, nonlinear, current):
        src = parse_study_text(body, "warm.yaml")
        problem = static_problem(validate_data(src.data, src))
        SemiAnalyticSolver().solve(problem)
    # the general solver, which calls compiled pieces from Python (a case no kernel
    # settles; a current over a seabed): found by tests/unit/test_compile_coverage.py
    SemiAnalyticSolver().solve(problem, compiled=False)
    # the array path of sweeps calls the batch kernels with stacked cases
    from .analyses.static_grid import evaluate_grid_chunk
    from .study.grid import expand_grid

    sweep = (
        "sweep:\n  ends.b.position.0: [80.0, 85.0]\n"
        "  line.segments.0.axial_stiffness: [6.0e7, 7.0e7]\n"
    )
    for body in (linear, anchored):
        grid = expand_grid(parse_study_text(body + sweep, "warm.yaml"))
        if grid.chunked:
            evaluate_grid_chunk(grid, 0, grid.shape[0])
    # a system's position sweep: the compiled system Newton (cablestudy.analyses.system_grid)
    system = _warm_system_text("warm-system", "sweep:\n  bodies.hull.position.0: [0.0, 2.0]\n")
    from .run.grid_runner import study_grid

    grid = study_grid(parse_study_text(system, "warm.yaml"))
    if grid is not None:
        evaluate_grid_chunk(grid, 0, grid.shape[0])
    from .analyses import database_kernel

    grid = np.array([0.0, 1.0])
    database_kernel.evaluate_cell(np.zeros((1, 1, 2, 16)), grid, grid, 0.5, 0.5)
    # the still-water batch kernels as an extension module: array sweeps then start
    # without numba (cablestudy.statics.aot; where it cannot be built, numba's)
    from .statics.aot import build

    build()


#: a small two-line system moved by its body, for the system warm-ups (a line on the
#: seabed, a free junction with mass, a body point); :func:`_warm_system_text` names it
_WARM_SYSTEM = """\
environment: {fluid: water, depth: 60.0}
points:
  anchor: {kind: fixed, position: [-90.0, 0.0, -60.0]}
  joint: {kind: free, position: [-30.0, 0.0, -30.0], mass: 200.0}
  fair: {kind: body, body: hull, offset: [0.0, 0.0, -5.0]}
bodies:
  hull: {kind: prescribed, position: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]}
lines:
  leg: {a: anchor, b: joint, segments: [SEG70]}
  top: {a: joint, b: fair, segments: [SEG35]}
"""
#: the system dynamics' analysis (METHOD: time or frequency)
_WARM_DYNAMIC = """\
analysis:
  dynamic:
    excitation: {body: hull, dof: surge, amplitude: 0.1, frequency: 0.1}
    method: METHOD
    elements: 4
"""


def _warm_system_text(name: str, tail: str) -> str:
    """:data:`_WARM_SYSTEM` named ``name``, segments filled in, ``tail`` after it."""
    seg = "{length: %s, diameter: 0.05, mass_per_length: 10.0, axial_stiffness: 1.0e8}"
    body = _WARM_SYSTEM.replace("SEG70", seg % 70.0).replace("SEG35", seg % 35.0)
    return f"name: {name}\n{body}{tail}"


def _warm_systems() -> None:
    """The system time domain (all lines and free points stepped together) and the
    system frequency domain (its compiled drag iteration), on a two-line system."""
    from .analyses.counters import COUNTERS
    from .analyses.system import evaluate_system_case
    from .study import parse_study_text
    from .study.grid import expand_cases

    text = _warm_system_text("warm-system-dynamics", _WARM_DYNAMIC)
    counted = COUNTERS.copy()  # the warm-up's solves and builds are no run's work
    try:
        for method in ("time", "frequency"):
            _, cases = expand_cases(parse_study_text(text.replace("METHOD", method), "warm.yaml"))
            for case in cases:
                evaluate_system_case(case)
    finally:
        COUNTERS.clear()
        COUNTERS.update(counted)


def _warm_time() -> None:
    from .dynamics.timedomain import warm_up

    warm_up()


def _warm_frequency() -> None:
    from .dynamics.harmonic_cases import warm_up

    warm_up()


_WARM: dict[str, Callable[[], None]] = {
    "statics": _warm_statics,
    "time": _warm_time,
    "frequency": _warm_frequency,
    "systems": _warm_systems,
}


def _marker(kind: str) -> Path:
    return Path(os.environ.get("NUMBA_CACHE_DIR", ".")) / f"{kind}.compiled"


def is_compiled(kind: str) -> bool:
    """Whether the kernels of ``kind`` were compiled for this version of the source."""
    return _marker(kind).is_file()


def compile_kind(kind: str) -> float:
    """Compile (or load) the kernels of ``kind`` and leave its marker; returns the wall
    time [s]."""
    t0 = time.perf_counter()
    _WARM[kind]()
    seconds = time.perf_counter() - t0
    try:
        marker = _marker(kind)
        marker.parent.mkdir(parents=True, exist_ok=True)
        marker.write_text(f"{seconds:.2f}\n")
    except OSError:  # a read-only cache: it compiles again next time, nothing is wrong
        pass
    return seconds


def compile_all(*, jobs: int | None = None) -> dict[str, float]:
    """Compile every kind in parallel processes, ``jobs`` at a time (default: the number
    of cores). Returns the wall time per kind [s]."""
    from concurrent.futures import ProcessPoolExecutor

    todo = list(KINDS)
    jobs = max(1, min(jobs or os.cpu_count() or 1, len(todo)))
    if jobs == 1:
        return {k: compile_kind(k) for k in todo}
    # the longest first, so that the others fill the remaining cores
    todo.sort(key=lambda k: -KINDS[k][1])
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        return dict(zip(todo, pool.map(compile_kind, todo), strict=True))


def kinds_of(study: Any) -> list[str]:
    """The kinds of kernels the analyses of ``study`` call."""
    kinds = ["statics"]
    dynamic = study.analysis.dynamic
    if dynamic is not None and study.is_system:
        return [*kinds, "systems"]
    if dynamic is not None:
        if dynamic.method != "frequency" and study.line.kind != "spring":
            kinds.append("time")
        if dynamic.method != "time":
            kinds.append("frequency")
    return kinds


def ensure_compiled(kinds: Iterable[str]) -> None:
    """Compile the ``kinds`` not yet compiled, saying so first, in this process (a run
    then forks or spawns workers that load the machine code from disk)."""
    for kind in kinds:
        if is_compiled(kind):
            continue
        label, seconds = KINDS[kind]
        print(
            f"compiling {label}, first run only, about {seconds:.0f} s",
            file=sys.stderr,
            flush=True,
        )
        compile_kind(kind)
