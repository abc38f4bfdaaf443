"""Work precision of the time-domain dynamics: the moustafa cable (configs/moustafa-*.yaml:
L = 10.9774 m, span 10.792 m, d = 0.01 m, m = 0.61 kg/m, EA = 7.854e6 N, in water) with
end B moved along the span, in three regimes:

* ``low``: 0.2 Hz, 0.05 m (quasi-static);
* ``resonant``: 0.75 Hz, 0.05 m (near the first in-plane symmetric mode, whose frequency
  the modal analysis of the same cable gives and the notes state);
* ``taut-slack``: 1.2 Hz, 0.1 m (the line goes slack and snaps).

Output: the maximum and minimum end-B tension over the last two of 12 periods (the motion
ramped in over the first two by ``(1 - cos(pi t / t_r)) / 2``; a fixed duration, not the
steady-state detector, so that every run answers exactly the same question). Settings:
elements N and points_per_period P (the step is period / P, refined automatically around
slack-taut events). Reference: Richardson extrapolation (4 X_fine - X_coarse) / 3 from the
two finest runs (N, P) = (80, 512) and (160, 1024) (both errors O(h^2) + O(dt^2), halved
together). Error: max(|dT_max|, |dT_min|) / T_max,ref. Time: ``simulate`` itself (the
static solution and the discrete static equilibrium are prepared once per mesh), median
over repeats.

Peer: MoorDyn (optional extra ``peers``) with the same prescribed motion and ramp, at 10,
20, 40 segments and its stable step (1 ms / segments: it is explicit, and the axial wave,
sqrt(EA / m) = 3.6 km/s, crosses a 40-segment element in 76 us), the motion handed to it
every T/512, T/2048 or T/8192 (its coupled end moves between these calls with a
first-order error: at 0.2 Hz, T/512 alone gives 3 % error). Time = time stepping + its
initial-state computation (both in the notes). MoorDyn's model differs in details (its
structural damping BA = -0.8, its drag and added-mass forms), so part of its remaining
error is a model difference.

Also: wall time of the 92-case Figs. 2-5 sweep through the CLI.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import yaml

from cablestudy.bench import WorkPrecision, _fmt_time, median_time

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
LENGTH, SPAN, MASS, EA, DIAMETER = 10.9774, 10.792, 0.61, 7.854e6, 0.01
PERIODS, RAMP, WINDOW = 12, 2.0, 2
REGIMES = {"low": (0.2, 0.05), "resonant": (0.75, 0.05), "taut_slack": (1.2, 0.1)}
MOORDYN_DT = {10: 1e-4, 20: 5e-5, 40: 2.5e-5}


def study(frequency: float, amplitude: float, elements: int, ppp: int) -> dict:
    return {
        "name": "bench-moustafa",
        "environment": {"fluid": "water", "gravity": 9.80665},
        "line": {
            "segments": [
                {
                    "length": LENGTH,
                    "diameter": DIAMETER,
                    "mass_per_length": MASS,
                    "axial_stiffness": EA,
                    "drag_normal": 1.2,
                    "drag_tangential": 0.01,
                    "added_mass_normal": 1.0,
                }
            ]
        },
        "ends": {
            "a": {"kind": "fixed", "position": [0.0, 0.0, 0.0]},
            "b": {"kind": "fixed", "position": [SPAN, 0.0, 0.0]},
        },
        "analysis": {
            "static": {"method": "analytic", "tolerance": 1e-12},
            "dynamic": {
                "excitation": {
                    "end": "b",
                    "direction": [1.0, 0.0, 0.0],
                    "amplitude": amplitude,
                    "frequency": frequency,
                },
                "elements": elements,
                "points_per_period": ppp,
                "ramp_periods": RAMP,
                "duration": PERIODS / frequency,
            },
        },
    }


def prepare(data: dict):  # noqa: ANN201
    """The DynamicProblem the pipeline would run for this study
    (:func:`cablestudy.analyses.time.dynamic_problem`)."""
    from cablestudy.analyses.static import solve_static
    from cablestudy.analyses.time import dynamic_problem
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text

    _, cases = expand_cases(parse_study_text(yaml.safe_dump(data), "<bench>"))
    case = cases[0]
    problem = dynamic_problem(case, solve_static(case, None))
    assert not isinstance(problem, str), problem
    return problem


def tensions(res) -> np.ndarray:  # noqa: ANN001
    assert res.status == 0, res.message
    return np.array([res.period_max[-WINDOW:].max(), res.period_min[-WINDOW:].min()])


def first_mode() -> float:
    """First natural frequency [Hz] of the cable (modal analysis, 200 elements)."""
    from cablestudy.analyses.evaluate import evaluate_case
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text

    d = study(0.5, 0.05, 20, 32)
    del d["analysis"]["dynamic"]
    d["analysis"]["modal"] = {"modes": 3, "elements": 200, "mode_shapes": False}
    _, cases = expand_cases(parse_study_text(yaml.safe_dump(d), "<bench>"))
    rec = evaluate_case(cases[0])
    return float(np.asarray(rec.data["natural_frequency"])[0])


def regime(label: str, quick: bool) -> WorkPrecision:
    from cablestudy.dynamics.timedomain import simulate

    f, a = REGIMES[label]
    wp = WorkPrecision(
        name=f"dynamic_moustafa_{label}",
        title=f"Moustafa cable, {f} Hz, {a} m: end tension max/min error vs time",
        error_name="max(|dT_max|, |dT_min|) / T_max,ref [-]",
        time_name="median wall time per run [s]",
    )
    fine = [tensions(simulate(prepare(study(f, a, n, p)))) for n, p in ((80, 512), (160, 1024))]
    ref = (4.0 * fine[1] - fine[0]) / 3.0
    wp.notes.append(
        f"reference T_max = {ref[0]:.3f} N, T_min = {ref[1]:.3f} N (Richardson from (80, 512): "
        f"{fine[0][0]:.3f}/{fine[0][1]:.3f} N and (160, 1024): {fine[1][0]:.3f}/"
        f"{fine[1][1]:.3f} N)"
    )

    def error(t: np.ndarray) -> float:
        return float(np.max(np.abs(t - ref)) / ref[0])

    repeats = 1 if quick else 3
    meshes = (10, 20, 40) if quick else (10, 20, 40, 80)
    steps = (32, 128) if quick else (32, 64, 128, 256, 512)
    for n in meshes:
        c = wp.curve(f"cablestudy N={n}")
        for p in steps:
            prob = prepare(study(f, a, n, p))
            got = tensions(simulate(prob))
            c.add(
                f"N={n}, P={p}",
                median_time(lambda prob=prob: simulate(prob), repeats=repeats, min_time=0.0),
                error(got),
            )
    moordyn(wp, f, a, error, quick)
    return wp


def moordyn(wp: WorkPrecision, f: float, a: float, error, quick: bool) -> None:  # noqa: ANN001
    """MoorDyn curves: one per segment count (at its stable step), over the interval at
    which the prescribed motion is handed to it (``samples_per_period``: MoorDyn moves
    the coupled end between calls with first-order error, so this interval is a
    setting of its accuracy like our step)."""
    sys.path.insert(0, str(HERE))
    from peers import CableCase, have, moordyn_harmonic

    if not have("moordyn"):
        wp.notes.append("MoorDyn not installed (pip install '.[peers]'): peer skipped")
        return
    case = CableCase(
        length=LENGTH,
        span=SPAN,
        rise=0.0,
        diameter=DIAMETER,
        mass=MASS,
        axial_stiffness=EA,
        density=1025.0,
    )
    parts = []
    for seg in (10, 20) if quick else (10, 20, 40):
        c = wp.curve(f"MoorDyn {seg} segments (dt {MOORDYN_DT[seg] * 1e6:g} us)", peer=True)
        for spp in (2048,) if quick else (512, 2048, 8192):
            runs = []
            for _ in range(3 if seg == 10 and not quick else 1):
                try:
                    runs.append(
                        moordyn_harmonic(
                            case,
                            amplitude=a,
                            frequency=f,
                            segments=seg,
                            dt=MOORDYN_DT[seg],
                            periods=PERIODS,
                            window=WINDOW,
                            ramp_periods=RAMP,
                            samples_per_period=spp,
                        )
                    )
                except Exception as exc:  # noqa: BLE001 - a peer failure is reported
                    wp.notes.append(f"MoorDyn failed at {seg} segments: {exc}")
                    break
            if not runs:
                continue
            r = runs[0]
            wall = float(np.median([x.wall_time for x in runs]))
            init = float(np.median([x.init_time for x in runs]))
            c.add(
                f"segments={seg}, coupling=T/{spp}",
                wall + init,
                error(np.array([r.tension_max, r.tension_min])),
            )
            parts.append(
                f"{seg} seg, T/{spp}: {r.tension_max:.2f}/{r.tension_min:.2f} N, "
                f"stepping {_fmt_time(wall)} + initial state {_fmt_time(init)}"
            )
    wp.notes.append(
        "MoorDyn (T_max/T_min; times are medians of 3 runs at 10 segments, "
        "1 run otherwise): " + "; ".join(parts)
    )


def cli_sweep(quick: bool) -> str:
    """Wall time of the 92-case Figs. 2-5 sweep through the CLI (fresh process, no cache)."""
    times = []
    for _ in range(1 if quick else 3):
        with tempfile.TemporaryDirectory() as tmp:
            t0 = time.perf_counter()
            proc = subprocess.run(
                [
                    sys.executable,
                    "-m",
                    "cablestudy",
                    "run",
                    "configs/moustafa-figs2-5.yaml",
                    "--out",
                    tmp,
                    "--no-cache",
                ],
                cwd=REPO,
                capture_output=True,
                text=True,
                env={**__import__("os").environ, "PYTHONPATH": str(REPO)},
            )
            times.append(time.perf_counter() - t0)
            if proc.returncode != 0:
                return f"Figs. 2-5 sweep through the CLI failed: {proc.stderr[-300:]}"
    how = "median of 3 runs" if len(times) > 1 else "1 run"
    return (
        f"the 92-case Figs. 2-5 sweep (configs/moustafa-figs2-5.yaml, default settings: "
        f"40 elements, 64 steps a period, steady-state detection) takes "
        f"{np.median(times):.1f} s wall time through `cablestudy run --no-cache` "
        f"({how}, process start and file output included)"
    )


def run(quick: bool = False) -> list[WorkPrecision]:
    out = [regime(label, quick) for label in REGIMES]
    f1 = first_mode()
    out[1].notes.insert(
        0,
        f"first natural frequency of the cable (modal, 200 elements): "
        f"{f1:.3f} Hz; excitation 0.75 Hz",
    )
    out[0].notes.append(cli_sweep(quick))
    return out
