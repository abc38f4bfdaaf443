"""Frequency domain against time domain on the moustafa cable (configs/moustafa-*.yaml).

Work precision, ``frequency_moustafa_linear``: end B moved 5 mm along the span at
0.5 Hz in water with drag (a near-linear regime: the frequency domain differs from the
nonlinear answer by about 1e-4 of the tension, see tests/validation/
test_frequency_vs_time.py). Output: max and min end-B tension. Error:
max(|dT_max|, |dT_min|) / T_max,ref, as in wp_dynamic_moustafa. Reference:
the time domain, Richardson (4 X_fine - X_coarse) / 3 from (N, P) = (80, 512) and
(160, 1024), 12 periods with the last two read, as in wp_dynamic_moustafa. Times: the
time domain's ``simulate`` and the frequency domain's ``solve_harmonic`` (drag
iteration included) per case, statics and model assembly prepared once, median over
repeats. The time domain is drawn as the "peer", so the table gives the time-domain
time over ours at equal or better error.

Notes: the 92-case Figs. 2-5 sweep (configs/moustafa-figs2-5.yaml) with ``method:
frequency``: compute time in process (``evaluate_chunk`` of all 92 cases, which solves
them in one compiled call, statics and assembly included, caches cleared; median of 3),
static solves and assemblies counted, ``cablestudy run`` wall time in a fresh process
(median of 3); and the same sweep's time-domain compute per case at the same (default)
settings on 8 of its cases, for the per-case ratio.
"""

from __future__ import annotations

import math
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import yaml

from cablestudy.bench import WorkPrecision, median_time

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(HERE))
from wp_dynamic_moustafa import prepare, study, tensions  # noqa: E402

FREQUENCY, AMPLITUDE = 0.5, 0.005
FIGS = REPO / "configs" / "moustafa-figs2-5.yaml"


def frequency_case(elements: int):  # noqa: ANN201
    """(reduced linear line, omega, end motion, drag settings) of the regime."""
    from cablestudy.analyses.frequency import drag_settings, end_displacements, linearised
    from cablestudy.analyses.static import solve_static
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text

    d = study(FREQUENCY, AMPLITUDE, elements, 64)
    dyn = d["analysis"]["dynamic"]
    for key in ("points_per_period", "ramp_periods", "duration"):
        dyn.pop(key)
    dyn["method"] = "frequency"
    _, cases = expand_cases(parse_study_text(yaml.safe_dump(d), "<bench>"))
    case = cases[0]
    red, why = linearised(case, solve_static(case, None), None)
    assert red is not None, why
    X, f, _ = end_displacements(case.study.analysis.dynamic)
    return red, 2.0 * math.pi * f, X, drag_settings(case.study.analysis.dynamic)


def linear_regime(quick: bool) -> WorkPrecision:
    from cablestudy.dynamics.frequency import solve_harmonic
    from cablestudy.dynamics.timedomain import simulate

    f, a = FREQUENCY, AMPLITUDE
    wp = WorkPrecision(
        name="frequency_moustafa_linear",
        title=f"Moustafa cable, {f} Hz, {a * 1e3:g} mm: frequency vs time domain",
        error_name="max(|dT_max|, |dT_min|) / T_max,ref [-]",
        time_name="median wall time per case [s]",
    )
    fine = [tensions(simulate(prepare(study(f, a, n, p)))) for n, p in ((80, 512), (160, 1024))]
    ref = (4.0 * fine[1] - fine[0]) / 3.0
    wp.notes.append(
        f"reference T_max = {ref[0]:.4f} N, T_min = {ref[1]:.4f} N (time domain, "
        f"Richardson from (80, 512) and (160, 1024))"
    )

    def error(t: np.ndarray) -> float:
        return float(np.max(np.abs(t - ref)) / ref[0])

    repeats = 1 if quick else 5
    c = wp.curve("frequency domain")
    for n in (10, 20, 40, 80) if quick else (10, 20, 40, 80, 160, 320):
        red, omega, X, settings = frequency_case(n)
        res = solve_harmonic(red, omega, X, settings)
        assert res.success, res.message
        t_s, amp = float(res.tension_static[1]), float(abs(res.end_tension[1]))
        c.add(
            f"N={n}",
            median_time(
                lambda r=red, o=omega, x=X, s=settings: solve_harmonic(r, o, x, s), repeats=repeats
            ),
            error(np.array([t_s + amp, t_s - amp])),
        )
    for n in (10, 20, 40) if quick else (10, 20, 40, 80):
        c = wp.curve(f"time domain N={n}", peer=True)
        for p in (32, 128) if quick else (32, 64, 128, 256):
            prob = prepare(study(f, a, n, p))
            got = tensions(simulate(prob))
            c.add(
                f"N={n}, P={p}",
                median_time(
                    lambda prob=prob: simulate(prob), repeats=1 if quick else 3, min_time=0.0
                ),
                error(got),
            )
    return wp


def _cases(method: str):  # noqa: ANN202
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text

    text = FIGS.read_text().replace("method: auto", f"method: {method}")
    return expand_cases(parse_study_text(text))[1]


def _clear_caches() -> None:
    from cablestudy.analyses.common import _LAST_CHECKED
    from cablestudy.analyses.counters import COUNTERS
    from cablestudy.analyses.frequency import (
        _LINEAR_CACHE,
    )
    from cablestudy.analyses.static import _LAST_STATIC_OUTPUTS, _STATIC_CACHE

    _STATIC_CACHE.clear()
    _LINEAR_CACHE.clear()
    COUNTERS.clear()
    _LAST_STATIC_OUTPUTS.clear()
    _LAST_CHECKED.clear()


def _kernel_time(cases: list, repeats: int) -> tuple[float, int]:
    """Median time of the batched solve of all cases on the cached linear model (the
    per-case work: drag iterations, complex solves, end and element tensions), and the
    drag iterations it took."""
    from cablestudy.analyses.frequency import (
        drag_settings,
        end_displacements,
        linearised,
    )
    from cablestudy.analyses.static import solve_static
    from cablestudy.dynamics.harmonic_cases import solve_harmonic_cases

    static = solve_static(cases[0], None)
    red, why = linearised(cases[0], static, None)
    assert red is not None, why
    omegas, motion = [], []
    for case in cases:
        X, f, _ = end_displacements(case.study.analysis.dynamic)
        omegas.append(2.0 * math.pi * f)
        motion.append(X)
    settings = drag_settings(cases[0].study.analysis.dynamic)
    om, mo = np.array(omegas), np.array(motion)
    res = solve_harmonic_cases(red, om, mo, settings)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        solve_harmonic_cases(red, om, mo, settings)
        times.append(time.perf_counter() - t0)
    return float(np.median(times)), int(res.iterations.sum())


def sweep_notes(quick: bool) -> list[str]:
    """Frequency-domain sweep: compute, counters, CLI wall time; time-domain per case."""
    from cablestudy.analyses.counters import COUNTERS
    from cablestudy.analyses.evaluate import evaluate_chunk, warm_up

    cases = _cases("frequency")
    warm_up(cases)  # the compiled kernels' one-off load, as `cablestudy run`
    computes, compute_cpus = [], []
    for _ in range(3 if quick else 9):
        _clear_caches()
        t0, c0 = time.perf_counter(), time.process_time()
        records = evaluate_chunk(cases)
        computes.append(time.perf_counter() - t0)
        compute_cpus.append(time.process_time() - c0)
        assert all(r.status == 0 for r in records)
    counts = dict(COUNTERS)
    compute = float(np.median(computes))
    compute_cpu = float(np.median(compute_cpus))
    kernel, iterations = _kernel_time(cases, 3 if quick else 9)
    walls, cpus = [], []
    for _ in range(1 if quick else 3):
        with tempfile.TemporaryDirectory() as tmp:
            cfg = Path(tmp) / "figs2-5-frequency.yaml"
            cfg.write_text(FIGS.read_text().replace("method: auto", "method: frequency"))
            t0 = time.perf_counter()
            c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
            proc = subprocess.run(
                [sys.executable, "-m", "cablestudy", "run", str(cfg), "--out", tmp, "--no-cache"],
                cwd=REPO,
                capture_output=True,
                text=True,
                env={**os.environ, "PYTHONPATH": str(REPO)},
            )
            walls.append(time.perf_counter() - t0)
            c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpus.append(c1.ru_utime + c1.ru_stime - c0.ru_utime - c0.ru_stime)
            assert proc.returncode == 0, proc.stderr[-300:]
    # the time domain on the whole sweep (quick: every 12th case, which are cheaper
    # than the mean: 43 against 61 ms measured)
    td_cases = _cases("time")
    if quick:
        td_cases = td_cases[::12]
    _clear_caches()
    t0, c0 = time.perf_counter(), time.process_time()
    td = evaluate_chunk(td_cases)
    td_per_case = (time.perf_counter() - t0) / len(td_cases)
    td_cpu = (time.process_time() - c0) / len(td_cases)
    assert all(r.status == 0 for r in td)
    n = len(cases)
    fd_per_case = compute / n
    return [
        f"92-case Figs. 2-5 sweep, method frequency: {compute * 1e3:.1f} ms compute in process "
        f"(median; {compute_cpu * 1e3:.1f} ms CPU; {fd_per_case * 1e3:.3f} ms per case; "
        f"{counts.get('static_solves', 0)} static solves, "
        f"{counts.get('linear_assemblies', 0)} linear-model assembly); of it the batched "
        f"solve of the 92 cases on the assembled model (drag iterations, complex solves, "
        f"tensions) {kernel * 1e3:.1f} ms ({iterations} drag iterations, "
        f"{kernel / max(iterations, 1) * 1e6:.1f} us each with its share of the set-up); "
        f"{np.median(walls):.1f} s wall ({np.median(cpus):.1f} s CPU) through `cablestudy run "
        "--no-cache` (fresh process, start-up included; wall time counts the waits of a "
        "shared machine)",
        f"time domain on the same sweep and settings: {td_per_case * 1e3:.1f} ms per case "
        f"({td_cpu * 1e3:.1f} ms CPU; {len(td_cases)} cases); per case the frequency domain "
        f"is {td_per_case / fd_per_case:.0f}x faster ({td_cpu * n / compute_cpu:.0f}x in CPU "
        f"time; {td_per_case * n / kernel:.0f}x counting only the batched solve)",
    ]


def equal_error_note(wp: WorkPrecision) -> str:
    """Time-domain time over frequency-domain time at the frequency domain's best error."""
    fd = next(c for c in wp.curves if not c.peer)
    best = int(np.argmin(fd.errors))
    e, t = fd.errors[best], fd.times[best]
    ok = [
        (c.times[i], c.settings[i])
        for c in wp.curves
        if c.peer
        for i in range(len(c.times))
        if c.errors[i] <= e
    ]
    if not ok:
        return f"no time-domain setting reaches the frequency domain's error {e:.1e}"
    t_td, setting = min(ok)
    return (
        f"at the frequency domain's error ({e:.1e}: its linearisation floor at this amplitude; "
        f"{fd.settings[best]}, {t * 1e3:.2f} ms) the cheapest time-domain run is {setting} "
        f"({t_td * 1e3:.0f} ms): {t_td / t:.0f}x"
    )


def run(quick: bool = False) -> list[WorkPrecision]:
    wp = linear_regime(quick)
    wp.notes.append(equal_error_note(wp))
    wp.notes.extend(sweep_notes(quick))
    return [wp]
