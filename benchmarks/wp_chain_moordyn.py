"""Work precision of the time-domain dynamics with seabed contact, against MoorDyn: the
chain mooring of configs/chain-mooring-surge.yaml (800 m of 85 mm studless chain,
d_hyd = 0.1533 m, 141 kg/m, EA = 6e8 N, anchor on the seabed at 200 m depth, fairlead at
(750, 0, -10) m, about 310 m laid; penalty seabed with the default stiffness, w / 1 mm,
critically damped, Coulomb friction 0.5; axial damping 0.8 of critical per element) with
the fairlead moved in surge in two regimes:

* ``wave``: 0.1 Hz (10 s), 2 m;
* ``slow_drift``: 0.01 Hz (100 s), 4 m.

Output: the maximum and minimum fairlead tension over the last two of six periods (the
motion ramped in over the first two by ``(1 - cos(pi t / t_r)) / 2``; a fixed duration).
Settings: elements N and points_per_period P. Reference: our solution at (320, 1024)
(wave) and (320, 512) (slow drift). Not Richardson-extrapolated: the sequences stop
converging at a floor of about 1e-4 of T_max (each node landing on or leaving the seabed
is a kink in the response; tests/validation/test_chain_convergence.py), so the
reference's uncertainty is its difference to the run with half the elements, stated in
the notes. Error: max(|dT_max|, |dT_min|) / T_max,ref. Time: our static solution and
the discrete static equilibrium of the mesh (once, caches cleared) plus the median of
three ``simulate`` runs.

Peer: MoorDyn (optional extra ``peers``; 2.7.2 here) running the file cablestudy exports
for the case (``cablestudy export moordyn``: same line, drag, added mass, axial damping
BA = -0.8, its stable step dtM), whose seabed rows are ours (written by the exporter):

* contact stiffness: MoorDyn's seabed force per node is ``kBot * d * l * penetration``
  (kBot is per unit of projected area, Pa/m, not per length), so kBot = stiffness / d.
  Checked: a laid chain sinks 1.000 mm with kBot = w / (1 mm d), 6.5 mm with kBot = w /
  1 mm;
* contact damping: cBot = 2 zeta sqrt(stiffness (m + Ca rho A)) / d, the critical
  damping of a node on its contact spring, as ours;
* friction: MoorDyn 2.7 has one isotropic coefficient (FrictionCoefficient = 0.5) in a
  saturated viscous law, F = min(mu FricDamp |v|, mu N) opposing the horizontal
  velocity (StatDynFricScale = 1); no stick state, so a laid node under a tangential
  load below mu N creeps at F / (mu FricDamp). FricDamp = w l / v_s saturates at v_s =
  2 cm/s (its default 200 N s/m would saturate at about 100 m/s: no friction at all);
  halving v_s (the limit of its explicit stability at 20 segments) moves T_max by 6e-4.
  Ours is elastic-plastic (stick stiffness = contact stiffness, Coulomb cap mu N along
  and across the line) and starts from a static state in which the laid chain's
  friction is already mobilised; MoorDyn's starts frictionless. Part of the remaining
  difference is therefore a model difference, which no refinement of either removes.

MoorDyn runs 10, 20, 40, 80 segments (wave) or 10, 20, 40 (slow drift: 600 s of
simulated time each) at the exported dtM (10, 5, 2, 1 ms), and is handed the motion
128, 256 or 1024 (wave), 64, 128 or 512 (slow drift) times a period: its coupled end
moves between these calls with first-order error, so this interval is a setting of its
accuracy like our step, and each call from Python costs time (at 20 segments, T/1024
takes 4 times as long as T/128). Time = its time stepping + its initial state (a static
solve), median of three runs where one run takes less than 3 s.

Also (``chain_convergence``): the refinement sequences of the validation test with
their observed orders.

Results (2026-11-24, MoorDyn 2.7.2, quiet 2-core machine, two runs agreeing to 10 %;
the errors are the same in every run, both codes being deterministic):

* wave (10 s, 2 m): reference T_max = 1172.74 kN, T_min = 574.63 kN (uncertainty 1.6e-4
  of T_max: 160 against 320 elements). MoorDyn 10/20/40 segments at T/256: errors
  2.8e-2, 9.0e-3, 5.9e-4 in 61, 127-138, 460 ms. Ours: 16 elements, T/16: 8.4e-3 in
  11.2-11.4 ms (statics and the discrete equilibrium included); 160, T/128: 3.9e-6 in
  234 ms. **MoorDyn time / ours at 1 % error: 11 and 12** (MoorDyn 20 segments, T/256,
  against our 16 elements, T/16).
* slow drift (100 s, 4 m): reference T_max = 980.59 kN, T_min = 768.50 kN (uncertainty
  1.5e-5). MoorDyn 10 segments at T/128: 6.5e-3 in 292-299 ms (20 segments 2.1e-3 in
  795 ms). Ours: 12 elements, T/12: 5.3e-3 in 14-16 ms; 160, T/128: 7.0e-5 in 281 ms.
  **MoorDyn time / ours at 1 % error: 18 and 21.**
* what made it (against 2.2 and 2.1 before): the whole step loop compiled (Python once
  per period), seabed contact held fixed during Newton (no step halvings at each node's
  landing: 32 rejected steps to none), stick/slip and contact states checked before
  full convergence, a right start for the laid-line statics (9 -> 5 ms of set-up), and
  meshes of 12-24 elements, which now work with friction.
* convergence (``chain_convergence``): mesh 40/80/160/320 at the slow-drift period,
  observed order 2.02 +- 0.12 (T_max) and 2.13 +- 0.28 (T_min); step T/128..T/1024 at
  the wave period on 40 elements, T_min order 3.4 +- 0.2, T_max at the floor (1e-5)
  from T/256.
"""

from __future__ import annotations

import re
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from cablestudy.bench import WorkPrecision, _fmt_time

HERE = Path(__file__).resolve().parent
CONFIG = HERE.parent / "configs" / "chain-mooring-surge.yaml"
PERIODS, RAMP, WINDOW = 6, 2.0, 2
REGIMES = {"wave": (0.1, 2.0), "slow_drift": (0.01, 4.0)}
REFERENCE = {"wave": (320, 1024), "slow_drift": (320, 512)}
#: our settings: elements -> points per period
OURS = {
    12: (12, 16),
    16: (12, 16, 32),
    20: (16, 32, 64),
    24: (16, 32),
    30: (16, 32, 64),
    40: (16, 32, 64, 128, 256),
    80: (32, 64, 128, 256),
    160: (64, 128),
}
#: MoorDyn: segments, samples of the motion per period (its coupling interval)
MOORDYN = {
    "wave": ((10, 20, 40, 80), (128, 256, 1024)),
    "slow_drift": ((10, 20, 40), (64, 128, 512)),
}
MOORDYN_REPEAT_BELOW = 3.0  # [s] MoorDyn runs shorter than this are repeated 3 times


def study(frequency: float, amplitude: float, elements: int, ppp: int) -> dict[str, Any]:
    """The chain study of the config with one excitation and fixed duration."""
    data = yaml.safe_load(CONFIG.read_text())
    del data["sweep"]
    dyn = data["analysis"]["dynamic"]
    dyn["excitation"].update(amplitude=amplitude, frequency=frequency)
    dyn.update(
        elements=elements,
        points_per_period=ppp,
        duration=PERIODS / frequency,
        ramp_periods=RAMP,
    )
    return data


def _case(data: dict):  # noqa: ANN202
    from cablestudy.study.grid import expand_cases
    from cablestudy.study.loader import parse_study_text

    _, cases = expand_cases(parse_study_text(yaml.safe_dump(data), "<bench>"))
    return cases[0]


def prepare(data: dict, *, fresh: bool = False) -> tuple[Any, float]:
    """The DynamicProblem the pipeline would run, and the time to build it [s] (static
    solution and discrete static equilibrium; with ``fresh`` their caches are emptied
    first so that the time is that of a first run)."""
    from cablestudy.analyses.line_model import _DISCRETE_CACHE
    from cablestudy.analyses.static import _STATIC_CACHE, solve_static
    from cablestudy.analyses.time import dynamic_problem

    if fresh:
        _STATIC_CACHE.clear()
        _DISCRETE_CACHE.clear()
    case = _case(data)
    t0 = time.perf_counter()
    problem = dynamic_problem(case, solve_static(case, None))
    elapsed = time.perf_counter() - t0
    if isinstance(problem, str):
        raise RuntimeError(problem)
    return problem, elapsed


def extremes(res) -> np.ndarray:  # noqa: ANN001
    if res.status != 0:
        raise RuntimeError(res.message)
    return np.array([res.period_max[-WINDOW:].max(), res.period_min[-WINDOW:].min()])


def run_ours(f: float, a: float, n: int, p: int, repeats: int) -> tuple[np.ndarray, float]:
    """Extremes [N] and time [s]: median of ``repeats`` fresh preparations + median of
    ``repeats`` runs (a single preparation, about 5 ms, was now and then timed at 15 ms
    or more: a garbage-collector pass landing in it)."""
    from cablestudy.dynamics.timedomain import simulate

    data = study(f, a, n, p)
    preps = []
    for _ in range(max(repeats, 3)):
        problem, t = prepare(data, fresh=True)
        preps.append(t)
    prep = float(np.median(preps))
    times, got = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        res = simulate(problem)
        times.append(time.perf_counter() - t0)
        got = extremes(res)
    assert got is not None
    return got, prep + float(np.median(times))


def regime(label: str, quick: bool) -> WorkPrecision:
    f, a = REGIMES[label]
    wp = WorkPrecision(
        name=f"chain_moordyn_{label}",
        title=f"Chain mooring, surge {a:g} m at {1 / f:g} s: fairlead tension max/min "
        "error vs time",
        error_name="max(|dT_max|, |dT_min|) / T_max,ref [-]",
        time_name="wall time per run [s] (median)",
    )
    nr, pr = REFERENCE[label]
    ref, t_ref = run_ours(f, a, nr, pr, 1)
    half, _ = run_ours(f, a, nr // 2, pr, 1)
    wp.notes.append(
        f"reference ({nr} elements, T/{pr}): T_max = {ref[0] / 1e3:.3f} kN, T_min = "
        f"{ref[1] / 1e3:.3f} kN ({_fmt_time(t_ref)}); with {nr // 2} elements "
        f"{half[0] / 1e3:.3f}/{half[1] / 1e3:.3f} kN, a difference of "
        f"{np.max(np.abs(half - ref)) / ref[0]:.1e} of T_max (the reference's uncertainty)"
    )

    def error(t: np.ndarray) -> float:
        return float(np.max(np.abs(t - ref)) / ref[0])

    repeats = 1 if quick else 3
    rows = []
    for n, steps in OURS.items():
        if quick and n not in (16, 30, 40, 80):
            continue
        c = None
        for p in steps[:2] if quick else steps:
            try:
                got, seconds = run_ours(f, a, n, p, repeats)
            except RuntimeError as exc:
                wp.notes.append(f"cablestudy failed at {n} elements, T/{p}: {exc}")
                break
            c = c or wp.curve(f"cablestudy N={n}")
            c.add(f"N={n}, P={p}", seconds, error(got))
            rows.append(
                f"{n}/T/{p}: {got[0] / 1e3:.2f}/{got[1] / 1e3:.2f} kN, {_fmt_time(seconds)}"
            )
    wp.notes.append("cablestudy (T_max/T_min, time): " + "; ".join(rows))
    moordyn(wp, label, ref, error, quick)
    wp.notes.append(equal_error(wp, 1e-2))
    return wp


def moordyn_text(f: float, a: float, segments: int) -> tuple[str, np.ndarray, float]:
    """The exported MoorDyn file of the case (its seabed as ours: module notes), the
    coupled point's position [m] and its time step dtM [s]."""
    from cablestudy.interchange.case_export import export_case
    from cablestudy.study.loader import parse_study_text

    data = study(f, a, segments, 64)
    src = parse_study_text(yaml.safe_dump(data), "<bench>")
    exported = export_case(src, [])
    text = exported.text
    assert re.search(r"^\S+\s+FricDamp", text, re.M), "friction not exported"
    (pid,) = exported.coupled
    return text, exported.coupled[pid], exported.time_step


def moordyn(wp: WorkPrecision, label: str, ref: np.ndarray, error, quick: bool) -> None:  # noqa: ANN001
    sys.path.insert(0, str(HERE))
    from peers import have, moordyn_prescribed

    if not have("moordyn"):
        wp.notes.append("MoorDyn not installed (pip install '.[peers]'): peer skipped")
        return
    import moordyn as md

    f, a = REGIMES[label]
    counts, samples = MOORDYN[label]
    parts = []
    for seg in counts[:2] if quick else counts:
        text, x0, dtm = moordyn_text(f, a, seg)
        c = wp.curve(f"MoorDyn {seg} segments (dtM {dtm * 1e3:g} ms)", peer=True)
        for spp in samples[-1:] if quick else samples:
            runs = []
            for _ in range(3):
                try:
                    runs.append(
                        moordyn_prescribed(
                            text,
                            x0=x0,
                            direction=np.array([1.0, 0.0, 0.0]),
                            amplitude=a,
                            frequency=f,
                            periods=PERIODS,
                            window=WINDOW,
                            ramp_periods=RAMP,
                            samples_per_period=spp,
                        )
                    )
                except Exception as exc:  # noqa: BLE001 - a peer failure is reported
                    wp.notes.append(f"MoorDyn failed at {seg} segments, T/{spp}: {exc}")
                    break
                # repeat only the runs that are cheap enough for the time budget
                if quick or runs[0].wall_time + runs[0].init_time > MOORDYN_REPEAT_BELOW:
                    break
            if not runs:
                continue
            r = runs[0]
            wall = float(np.median([x.wall_time for x in runs]))
            init = float(np.median([x.init_time for x in runs]))
            got = np.array([r.tension_max, r.tension_min])
            c.add(f"segments={seg}, coupling=T/{spp}", wall + init, error(got))
            d = (got - ref) / ref[0]
            parts.append(
                f"{seg} seg, T/{spp}: {got[0] / 1e3:.2f}/{got[1] / 1e3:.2f} kN (T_max "
                f"{d[0]:+.1e}, T_min {d[1]:+.1e} of T_max,ref), stepping {_fmt_time(wall)} "
                f"+ initial state {_fmt_time(init)} ({len(runs)} run"
                f"{'s' if len(runs) > 1 else ''})"
            )
    version = getattr(md, "__version__", None) or _moordyn_version()
    wp.notes.append(f"MoorDyn {version} (T_max/T_min, vs reference): " + "; ".join(parts))


def _moordyn_version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("moordyn")
    except PackageNotFoundError:
        return "(version unknown)"


def equal_error(wp: WorkPrecision, target: float) -> str:
    """Time ratio at ``target`` error: the cheapest MoorDyn point within it over our
    cheapest point within it."""
    ours = [(t, s) for c in wp.curves if not c.peer for t, s, e in _pts(c) if e <= target]
    theirs = [(t, s) for c in wp.curves if c.peer for t, s, e in _pts(c) if e <= target]
    if not ours or not theirs:
        who = "MoorDyn" if ours else "cablestudy"
        return f"at {target:.0%} error: {who} never that close to the reference"
    (to, so), (tt, st) = min(ours), min(theirs)
    return (
        f"at {target:.0%} error: cablestudy {so} in {_fmt_time(to)}, MoorDyn {st} in "
        f"{_fmt_time(tt)}: MoorDyn time / ours = {tt / to:.2g}"
    )


def _pts(c) -> list[tuple[float, str, float]]:  # noqa: ANN001
    return list(zip(c.times, c.settings, c.errors, strict=True))


def convergence(quick: bool) -> WorkPrecision:
    """The refinement sequences of tests/validation/test_chain_convergence.py: values,
    successive differences and observed orders (error here: against the finest level)."""
    wp = WorkPrecision(
        name="chain_convergence",
        title="Chain mooring: mesh (slow drift, T/512) and step (wave, 40 elements) "
        "halving, fairlead tension max/min",
        error_name="max(|dT_max|, |dT_min|) / T_max,finest [-]",
        time_name="wall time per run [s] (one run)",
    )
    sequences = {
        "mesh halving (slow drift 100 s, 4 m; T/512)": [
            (0.01, 4.0, n, 512) for n in ((40, 80, 160) if quick else (40, 80, 160, 320))
        ],
        "step halving (wave 10 s, 2 m; 40 elements)": [
            (0.1, 2.0, 40, p) for p in ((128, 256, 512) if quick else (128, 256, 512, 1024))
        ],
    }
    for name, runs in sequences.items():
        values, times = [], []
        for f, a, n, p in runs:
            got, seconds = run_ours(f, a, n, p, 1)
            values.append(got)
            times.append(seconds)
        x = np.array(values)
        c = wp.curve(name)
        for (_, _, n, p), t, v in zip(runs, times, x, strict=True):
            c.add(f"N={n}, P={p}", t, float(np.max(np.abs(v - x[-1])) / x[-1][0]))
        d = np.abs(np.diff(x, axis=0))

        def listed(v: np.ndarray, scale: float, digits: int) -> str:
            return ", ".join(f"{u / scale:.{digits}f}" for u in v)

        text = [
            f"{name}: T_max = {listed(x[:, 0], 1e3, 3)} kN, T_min = {listed(x[:, 1], 1e3, 3)} "
            f"kN; successive differences T_max {listed(d[:, 0], 1.0, 1)} N, T_min "
            f"{listed(d[:, 1], 1.0, 1)} N"
        ]
        if d.shape[0] >= 3:
            p_obs = np.log2(d[0] / d[1])
            dp = (d[2] / d[0] + d[2] / d[1]) / np.log(2.0)
            text.append(
                f"observed order log2(d1/d2): T_max {p_obs[0]:.2f} +- {dp[0]:.2f}, T_min "
                f"{p_obs[1]:.2f} +- {dp[1]:.2f} (uncertainty from the finest difference, "
                "the floor)"
            )
        wp.notes.append("; ".join(text))
    return wp


def run(quick: bool = False) -> list[WorkPrecision]:
    return [regime(label, quick) for label in REGIMES] + [convergence(quick)]
