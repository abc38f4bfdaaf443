"""The dynamic line model of a case: its dynamic-only properties (bodies, damping,
free and clamped ends, seabed contact), the lumped-mass line and its own discrete static
equilibrium (kept per static problem), the end motion of its excitation, its break
conditions and winch, and the force below which a residual is rounding.
"""

from __future__ import annotations

import math
from collections import OrderedDict
from dataclasses import fields
from typing import TYPE_CHECKING, Any

import numpy as np

from ..physics.contact import default_seabed_stiffness
from ..statics import (
    StaticResult,
)
from ..study.analysis import (
    DynamicSettings,
    HarmonicExcitation,
    SpectrumExcitation,
    TimeSeriesExcitation,
)
from ..study.cases import Case
from ..study.ends import ForceEnd
from ..study.problem import line_model, medium
from .counters import COUNTERS, trim_lru

if TYPE_CHECKING:  # imported where used: `cablestudy validate` needs none of them
    from ..dynamics.discrete_line import DiscreteLine
    from ..dynamics.excitation import EndMotion


#: discrete static equilibria of the dynamic model, by (static hash, elements, the
#: dynamic-only line properties); as many as static solutions are kept
#: (cablestudy.analyses.static)
_DISCRETE_CACHE_SIZE = 64
_DISCRETE_CACHE: OrderedDict[tuple, tuple[DiscreteLine, np.ndarray, str, np.ndarray]] = (
    OrderedDict()
)


def _fields_key(obj: Any) -> tuple:
    """A hashable key of a dataclass of numbers, tuples and arrays (arrays by dtype,
    shape and bytes: exact, and a hundred times cheaper than their repr)."""
    out = []
    for f in fields(obj):
        v = getattr(obj, f.name)
        if isinstance(v, np.ndarray):
            v = (v.dtype.str, v.shape, v.tobytes())
        out.append((f.name, v))
    return tuple(out)


def discrete_statics(
    case: Case, static: StaticResult
) -> tuple[DiscreteLine, np.ndarray, str, np.ndarray]:
    """The lumped-mass line of the case and its own static equilibrium, found by Newton
    from the static solution (cached per static problem, element count and dynamic line
    properties). The third item is an error message (empty when the equilibrium was
    found), the fourth the seabed friction anchors holding that equilibrium."""
    from ..dynamics.discrete_line import discretise_nodes, uniform_nodes
    from ..dynamics.model import static_equilibrium

    dyn = case.study.analysis.dynamic
    assert dyn is not None
    lm = line_model(case.study)
    med = medium(case.study)
    # the clamp directions are the static tangents of the end elements of the mesh
    s_nodes = uniform_nodes(lm, dyn.elements)
    start = np.stack([np.interp(s_nodes, static.s, static.position[:, k]) for k in range(3)], 1)
    extras = dynamic_extras(case.study, start)
    key = (case.static_hash, dyn.elements, _fields_key(extras))
    cached = _DISCRETE_CACHE.get(key)
    if cached is not None:
        return cached
    line = discretise_nodes(lm, med, s_nodes, extras)
    COUNTERS["line_assemblies"] += 1
    scale = float(np.nanmax(static.tension))
    if line.has_seabed:
        # the penalty seabed balances each laid node's weight by a penetration of its
        # own: allow the residual the contact stiffness makes of rounding in z
        scale = max(scale, float(np.max(np.abs(line.force))))
    # the static tension at the element midpoints: where Newton on positions cannot
    # start (a stiff line on a seabed), the positions-and-tensions form starts from it
    t_nodes = np.interp(s_nodes, static.s, static.tension)
    x, its, res, ok, anchor = static_equilibrium(
        line,
        start,
        tolerance=max(1e-9 * scale, roundoff_force(line, start)),
        max_iterations=200,
        fallback_tension=0.5 * (t_nodes[:-1] + t_nodes[1:]),
    )
    msg = (
        ""
        if ok
        else (
            f"the discrete static equilibrium of the dynamic model did not "
            f"converge ({its} iterations, residual {res:.3g} N)"
        )
    )
    _DISCRETE_CACHE[key] = (line, x, msg, anchor)
    trim_lru(_DISCRETE_CACHE, _DISCRETE_CACHE_SIZE)
    return line, x, msg, anchor


def dynamic_extras(study: Any, start: np.ndarray) -> Any:
    """The dynamic-only line properties of ``study``
    (:class:`cablestudy.dynamics.discrete_line.DynamicExtras`): bodies, transverse damping,
    free ends (an unexcited ``force`` end), clamped ends (holding the direction of the
    end elements of ``start`` [m], the static shape at the mesh nodes) and the seabed
    contact."""
    dyn = study.analysis.dynamic
    excited = {e.end for e in dyn.excitations} if dyn is not None else set()
    end_force = np.zeros((2, 3))
    free = [False, False]
    clamp = np.zeros((2, 3))
    for k, label in enumerate(("a", "b")):
        end = getattr(study.ends, label)
        if isinstance(end, ForceEnd) and label not in excited:
            free[k] = True
            end_force[k] = end.force
        if end.bending == "clamped":
            d = start[1] - start[0] if k == 0 else start[-1] - start[-2]
            clamp[k] = d / np.linalg.norm(d)
    lm = line_model(study)
    return _extras(study.environment, study.line, lm, end_force, (free[0], free[1]), clamp)


def system_line_extras(study: Any, name: str, lm: Any) -> Any:
    """The dynamic-only properties of line ``name`` (as a one-line study's: transverse
    damping, attachment added mass and drag, the seabed contact; pinned ends)."""
    none = np.zeros((2, 3))
    return _extras(study.environment, study.lines[name], lm, none, (False, False), none.copy())


def _extras(
    env: Any,
    line: Any,
    lm: Any,
    end_force: np.ndarray,
    free: tuple[bool, bool],
    clamp: np.ndarray,
) -> Any:
    """:class:`cablestudy.dynamics.discrete_line.DynamicExtras` of the study's ``line``
    (its model ``lm``) in ``env``, with the ends' applied forces, free ends and clamp
    directions given."""
    from ..dynamics.discrete_line import DynamicExtras

    sb = env.seabed
    stiffness = 0.0
    if env.depth is not None:
        stiffness = (
            sb.stiffness if sb.stiffness is not None else default_seabed_stiffness(lm.weight)
        )
    atts = line.attachments
    return DynamicExtras(
        transverse_damping=np.array([seg.damping_transverse for seg in line.segments]),
        attachment_added_mass=np.array([a.added_mass for a in atts], dtype=float),
        attachment_drag_area=np.array([a.drag_area for a in atts], dtype=float),
        end_force=end_force,
        free_end=free,
        clamp_direction=clamp,
        seabed_stiffness=float(stiffness),
        seabed_damping_ratio=float(sb.damping_ratio),
        friction_axial=float(sb.friction),
        friction_lateral=float(sb.friction if sb.friction_lateral is None else sb.friction_lateral),
    )


def period_and_step(dyn: Any, periods: list[float]) -> tuple[float, float]:
    """The run's period [s] (``analysis.dynamic.period``, else the longest of the
    motions' ``periods``, else the ``duration``) and its time step [s]: the fastest
    period over ``points_per_period``, shortened to a whole number of steps a period."""
    if dyn.period is not None:
        period = dyn.period
    elif periods:
        period = max(periods)
    else:
        period = dyn.duration  # validated: one of them is set
    fastest = min(periods) if periods else period
    step = fastest / dyn.points_per_period
    return period, period / math.ceil(period / step * (1.0 - 1e-12))


def march_settings(dyn: Any) -> dict[str, Any]:
    """The settings of ``analysis.dynamic`` a time-domain run of a line or a system takes
    as given (:class:`cablestudy.dynamics.time_problem.MarchSettings`)."""
    return {
        "max_refinement": dyn.max_refinement,
        "spectral_radius": dyn.spectral_radius,
        "max_newton_iterations": dyn.max_newton_iterations,
        "steady_tolerance": dyn.steady_tolerance,
        "steady_window": dyn.steady_window,
        "min_periods": dyn.settle_periods,  # a kept record lies in the motion
        "max_periods": dyn.max_periods,
        "duration": dyn.duration,
        "history": dyn.history is not None,
    }


def roundoff_force(
    line: DiscreteLine, x: np.ndarray, parts: tuple[float, float, float] | None = None
) -> float:
    """Nodal force [N] below which a residual is lost in rounding: an element tension
    carries EA * (relative rounding of the node coordinates) / (element length).
    ``parts``: :func:`roundoff_parts` of ``line``, where the caller has them."""
    c, rest, shortest = parts or roundoff_parts(line)
    return c * (float(np.max(np.abs(x))) + rest) / shortest


def roundoff_parts(line: DiscreteLine) -> tuple[float, float, float]:
    """What :func:`roundoff_force` takes of the line alone: 16 eps max(EA) [N], the sum
    and the shortest of the rest lengths [m]."""
    rest = line.rest_length
    c = 16.0 * float(np.finfo(float).eps) * float(np.max(line.axial_stiffness))
    return c, float(np.sum(rest)), float(np.min(rest))


def end_motion(dyn: DynamicSettings) -> tuple[EndMotion, float, float]:
    """(end motion, steady-state period [s], base time step [s]) of the settings."""
    from ..dynamics.excitation import EndMotion, TableMotion

    harmonics = [e for e in dyn.excitations if isinstance(e, HarmonicExcitation)]
    tables = [e for e in dyn.excitations if isinstance(e, TimeSeriesExcitation)]
    spectra = [e for e in dyn.excitations if isinstance(e, SpectrumExcitation)]
    table_motions = tuple(
        TableMotion(
            end=0 if e.end == "a" else 1,
            direction=np.asarray(e.direction) / np.linalg.norm(e.direction),
            times=np.array([r[0] for r in e.table]),
            values=np.array([r[1] for r in e.table]),
            periodic=e.periodic,
        )
        for e in tables
    )
    # a spectrum runs as its lines with random phases (seeded): a periodic motion whose
    # period is that of its lowest line
    lines = [
        (e, f, a, p)
        for e in spectra
        for f, a, p in zip(
            e.line_frequencies,
            e.line_amplitudes,
            np.random.default_rng(e.seed).uniform(0.0, 2.0 * math.pi, e.components),
            strict=True,
        )
    ]
    periods = [1.0 / e.frequency for e in harmonics] + [1.0 / f for _, f, _, _ in lines]
    periods += [m.duration for m in table_motions if m.periodic]
    period, step = period_and_step(dyn, periods)
    every = [(e, e.frequency, e.amplitude, math.radians(e.phase_deg)) for e in harmonics]
    every += lines
    motion = EndMotion(
        harmonic_end=np.array([0 if e.end == "a" else 1 for e, _, _, _ in every], dtype=int),
        harmonic_direction=np.array(
            [np.asarray(e.direction) / np.linalg.norm(e.direction) for e, _, _, _ in every]
        ).reshape(-1, 3),
        harmonic_amplitude=np.array([a for _, _, a, _ in every], dtype=float),
        harmonic_frequency=np.array([f for _, f, _, _ in every], dtype=float),
        harmonic_phase=np.array([p for _, _, _, p in every], dtype=float),
        tables=table_motions,
        ramp_time=dyn.ramp_periods * period,
    )
    return motion, period, step


def element_breaks(study: Any, line: DiscreteLine) -> dict[str, np.ndarray]:
    """Per element of ``line`` its break tension [N] and failure time [s] (inf: none):
    its segment's ``failure``, else ``line.failure`` (empty when neither is given)."""
    segs = study.line.segments
    if study.line.failure is None and all(seg.failure is None for seg in segs):
        return {}
    ends = np.concatenate(([0.0], np.cumsum([seg.length for seg in segs])))
    mid = 0.5 * (line.s[:-1] + line.s[1:])
    of = np.clip(np.searchsorted(ends, mid, side="right") - 1, 0, len(segs) - 1)
    tension, when = np.full(len(segs), np.inf), np.full(len(segs), np.inf)
    for i, seg in enumerate(segs):
        brk = seg.failure or study.line.failure
        if brk is not None:
            tension[i] = brk.limit
            if brk.time is not None:
                when[i] = float(brk.time)
    return {"break_tension": tension[of], "break_at": when[of]}


def winch_settings(winch: Any) -> dict[str, float]:
    """The winch settings of the time domain (the first element's length changes) and of
    a spring line's dynamics (its unstretched length changes)."""
    if winch is None:
        return {}
    return {
        "winch_speed": float(winch.speed),
        "winch_start": float(winch.start),
        "winch_stop": math.inf if winch.stop is None else float(winch.stop),
    }
