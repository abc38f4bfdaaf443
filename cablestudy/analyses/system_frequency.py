"""The frequency domain of a system study case by case (``method: frequency``; issue 24).

The system linearised about its static state
(:func:`cablestudy.dynamics.system_frequency.system_linear`: each line re-solved
between the points the statics found at ``elements + 1`` nodes, its dynamic
properties as the time domain's, the free points' mass, added mass and drag) is built
once per static problem and element count and shared by the cases of a sweep of the
motion (amplitude, frequency, phase, degree of freedom); per case the harmonic
response (:func:`~cablestudy.dynamics.system_frequency_sweep.solve_system_sweep_arrays`)
runs.

Outputs (the issue's names): ``tension_amplitude_a``/``_b`` on ``line``; the linear
extremes ``tension_max_a`` ... (static plus and minus the amplitude, mean the static
tension), ``tension_envelope_max``/``_min`` on (``line``, ``s``), ``body_force_max``/
``_min`` on (``body``, ``dof``), ``dynamic_method`` and its reason, ``linearisation_iterations``.

A system of one line between prescribed points (no free point) is the one-line study
with prescribed end motions: its cases go through the single line's solve and outputs
(:mod:`cablestudy.analyses.system_one_line`), the same numbers bit for bit.
"""

from __future__ import annotations

import math
import threading
import time
from collections import OrderedDict
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import numpy as np

from ..statics import STATIC_SOLVERS, STATUS_NUMERICAL, STATUS_OK
from ..study.cases import Case
from ..study.system import FreePoint
from ..study.system_dynamics import BODY_DOFS, BodyHarmonic, PointHarmonic
from .counters import COUNTERS, trim_lru

_MODEL_CACHE: OrderedDict[tuple, Any] = OrderedDict()
_CACHE_SIZE = 16


def system_frequency_model(case: Case, system: Any, static: Any) -> Any:
    """The case's linearised system (cached per static problem and element count), or
    why it cannot be built (a string)."""
    from ..dynamics.system_frequency import system_linear
    from .line_model import system_line_extras

    study = case.study
    dyn = study.analysis.dynamic
    key = (case.static_hash, dyn.elements)
    hit = _MODEL_CACHE.get(key)
    if hit is not None:
        _MODEL_CACHE.move_to_end(key)
        return hit
    rho = study.environment.density
    points = list(study.points.values())
    free = [isinstance(p, FreePoint) for p in points]
    model, why = system_linear(
        system,
        static,
        point_mass=np.array([p.mass if f else 0.0 for p, f in zip(points, free, strict=True)]),
        point_added_mass=np.array(
            [p.added_mass if f else 0.0 for p, f in zip(points, free, strict=True)]
        ),
        point_drag=np.array(
            [0.5 * rho * p.drag_area if f else 0.0 for p, f in zip(points, free, strict=True)]
        ),
        extras=[
            system_line_extras(study, name, sl.problem.line)
            for name, sl in zip(study.lines, system.lines, strict=True)
        ],
        nodes=dyn.elements + 1,
        solve_many=_catenary_many,
    )
    out = model if model is not None else why
    COUNTERS["system_assemblies"] += 1
    _MODEL_CACHE[key] = out
    trim_lru(_MODEL_CACHE, _CACHE_SIZE)
    return out


def _catenary_many(problems: list[Any]) -> list[Any]:
    """The catenary solver's ``solve`` of each problem, those its compiled kernels take
    stacked into one call per group (:func:`~cablestudy.statics.batch.
    solve_compiled_many`: the same answers, verified as ``solve`` verifies them)."""
    from ..statics.batch import solve_compiled_many

    solve = STATIC_SOLVERS["catenary"].solve
    fast = solve_compiled_many(problems)
    return [r if r is not None else solve(p) for r, p in zip(fast, problems, strict=True)]


_GRID_CACHE: OrderedDict[tuple[int, int], tuple[Any, Any]] = OrderedDict()


class _Interpolation:
    """``np.interp`` of values at every line's nodes (flat over the lines) onto each
    line's ``n_out`` equally spaced arc lengths, as a linear map applied by ``@``: the
    value at an output is ``(1 - t) v[j] + t v[j + 1]``, the two products summed in
    that order (as a sparse matrix's product sums its row), by two gathers."""

    def __init__(self, left: np.ndarray, weight: np.ndarray, shape: tuple[int, int]) -> None:
        self.left, self.weight, self.shape = left, weight, shape

    def __matmul__(self, values: np.ndarray) -> np.ndarray:
        v = np.asarray(values)
        return (1.0 - self.weight) * v[self.left] + self.weight * v[self.left + 1]

    def rows(self, values: np.ndarray) -> np.ndarray:
        """``self @ values[i]`` of every row ``i`` of ``values`` (cases, nodes), the same
        products and sums."""
        v = np.asarray(values)
        return (1.0 - self.weight) * v[:, self.left] + self.weight * v[:, self.left + 1]


def _envelope_grid(model: Any, n_out: int) -> _Interpolation:
    """The linear interpolation (as ``np.interp``) of values at every line's nodes, flat
    over the lines, onto ``n_out`` equally spaced arc lengths of each line
    (:class:`_Interpolation`, lines x n_out from the nodes), built once per model."""
    key = (id(model), n_out)
    hit = _GRID_CACHE.get(key)
    if hit is not None and hit[0] is model:
        return hit[1]
    left, weight, start = [], [], 0
    for red in model.lines:
        s = red.line.s
        x = np.linspace(0.0, float(s[-1]), n_out)
        j = np.clip(np.searchsorted(s, x, side="right") - 1, 0, s.size - 2)
        weight.append((x - s[j]) / (s[j + 1] - s[j]))
        left.append(start + j)
        start += s.size
    grid = _Interpolation(
        np.concatenate(left), np.concatenate(weight), (len(model.lines) * n_out, start)
    )
    _GRID_CACHE[key] = (model, grid)
    trim_lru(_GRID_CACHE, _CACHE_SIZE)
    return grid


def harmonic_motion(study: Any) -> tuple[np.ndarray, np.ndarray, float]:
    """The complex amplitudes of ``Re(X e^{i w t})`` of the bodies (B, 6) [m, rad] and of
    the points moved on their own (P, 3) [m], and the frequency [Hz]:
    ``a sin(w t + phi)`` is ``Re(-i a e^{i phi} e^{i w t})``."""
    X, U, frequency = body_axes_motion(study)
    return turned_rotations(study, X), U, frequency


def body_axes_motion(study: Any) -> tuple[np.ndarray, np.ndarray, float]:
    """:func:`harmonic_motion` before the bodies' rotations are turned about their
    static orientation (:func:`turned_rotations`): roll, pitch and yaw amplitudes as
    the study gives them."""
    dyn = study.analysis.dynamic
    bodies, points = list(study.bodies), list(study.points)
    X = np.zeros((len(bodies), 6), dtype=complex)
    U = np.zeros((len(points), 3), dtype=complex)
    freqs = set()
    for e in dyn.excitations:
        amp = -1j * e.amplitude * np.exp(1j * math.radians(e.phase_deg))
        freqs.add(e.frequency)
        if isinstance(e, BodyHarmonic):
            X[bodies.index(e.body), BODY_DOFS.index(e.dof)] += amp
        else:
            assert isinstance(e, PointHarmonic)
            d = np.asarray(e.direction, dtype=float)
            U[points.index(e.point)] += amp * d / np.linalg.norm(d)
    (frequency,) = freqs  # one frequency: the study model checked it
    return X, U, float(frequency)


def turned_rotations(study: Any, X: np.ndarray) -> np.ndarray:
    """``X`` with each body's roll, pitch and yaw amplitudes as the global rotation
    vector they make about the body's static orientation (the model moves a point by
    ``Theta x a``: right at zero angles only; the time domain turns a yawed body's pitch
    about its own axis, R = Rz Ry Rx). Unchanged for bodies at zero angles."""
    from ..dynamics.body_rates import rotation_vector

    out = X.copy()
    for b, body in enumerate(study.bodies.values()):
        out[b, 3:] = rotation_vector(np.asarray(body.position[3:], dtype=float), X[b, 3:])
    return out


def run_system_frequency(
    case: Case, system: Any, static: Any
) -> tuple[int, str, dict[str, np.ndarray]]:
    """The case's harmonic response and its outputs: (status, message, outputs)."""
    status, message, out, _, _ = _solve_frequency(case, system, static, "method: frequency")
    return status, message, out


def _solve_frequency(
    case: Case, system: Any, static: Any, reason: str
) -> tuple[int, str, dict[str, np.ndarray], Any, Any]:
    """(status, message, outputs, result, model) of the case's harmonic response, its
    outputs marked as the frequency domain's with ``reason``."""
    from .frequency import drag_settings

    head = {
        "dynamic_method": np.asarray("frequency"),
        "dynamic_method_reason": np.asarray(reason),
    }
    model = system_frequency_model(case, system, static)
    if isinstance(model, str):
        return STATUS_NUMERICAL, model, head, None, None
    hit = _swept.pop(case.hash, None) if _swept.model is model else None
    if hit is None:
        hit = _solve_sweep(case, model, system, static) if _swept.cases else None
    if hit is None:  # alone: a sweep of one
        (hit,) = _solve_group(
            [case],
            model,
            system,
            static,
            drag_settings(case.study.analysis.dynamic),
            full=_needs_result([case]),
        )
    res, values, bad = hit
    if res.status != STATUS_OK:
        return res.status, res.message, head, res, model
    if bad:
        return STATUS_NUMERICAL, f"non-finite values in {', '.join(bad)}", head, res, model
    return STATUS_OK, "", {**head, **values}, res, model


def _needs_result(cases: list[Case]) -> list[bool]:
    """Per case whether its whole harmonic result is read after its outputs (``method:
    auto`` judges it: :func:`run_system_auto`); a case of ``method: frequency`` reads
    only its status and iterations (:class:`~cablestudy.dynamics.
    system_frequency_sweep.SolvedCase`)."""
    return [c.study.analysis.dynamic.method != "frequency" for c in cases]


def _solve_group(
    cases: list[Case],
    model: Any,
    system: Any,
    static: Any,
    settings: Any,
    full: list[bool] | None = None,
) -> list[tuple[Any, dict[str, np.ndarray], list[str]]]:
    """Per case of ``cases`` (of one linear model and drag settings) its harmonic
    response solved in one sweep (:func:`~cablestudy.dynamics.system_frequency_sweep.
    solve_system_sweep_arrays`, each case as alone), its outputs (the issue's names,
    module docstring; computed for all the cases at once, each case's a view of its
    row) and the names of its outputs that are not finite. Outputs (linear response):
    extremes are the static value plus and minus the amplitude, the mean the static
    value; the envelopes on each line's ``s`` grid of the static problem's nodes.
    ``full[i]`` false: case ``i``'s result is only its status and iterations (its
    outputs are whole; None: every result whole)."""
    from .system_one_line import is_one_line, solve_one_line_group

    motions = [harmonic_motion(c.study) for c in cases]
    if is_one_line(system):  # the one-line study's solve and outputs, bit for bit
        return solve_one_line_group(motions, model, system, static, settings)
    results, batch, finite = group_arrays(motions, model, system, static, settings, full)
    return [
        (
            res,
            {k: v[i, ...] for k, v in batch.items()},
            [k for k, ok in finite.items() if not ok[i]],
        )
        for i, res in enumerate(results)
    ]


def group_arrays(
    motions: list[tuple[np.ndarray, np.ndarray, float]],
    model: Any,
    system: Any,
    static: Any,
    settings: Any,
    full: list[bool] | None = None,
) -> tuple[list[Any], dict[str, np.ndarray], dict[str, np.ndarray]]:
    """:func:`_solve_group`'s work for a system of more than one line, as arrays: the
    cases' results, their outputs (one array per output, cases first) and per
    floating-point output whether each case's values are all finite. ``motions``: each
    case's :func:`harmonic_motion`."""
    from ..dynamics.system_frequency_sweep import solve_system_sweep_arrays

    results, arr = solve_system_sweep_arrays(
        model,
        [2.0 * math.pi * f for _, _, f in motions],
        [X for X, _, _ in motions],
        settings,
        [U for _, U, _ in motions],
        full,
    )
    n, L = len(motions), len(model.lines)
    amp = np.abs(arr["end_tension"])  # (n, L, 2)
    T = model.post.static  # (L, 2) the static end tensions
    batch: dict[str, np.ndarray] = {
        "tension_amplitude_a": amp[:, :, 0],
        "tension_amplitude_b": amp[:, :, 1],
        "tension_mean_a": np.where(np.isfinite(amp[:, :, 0]), T[:, 0], np.nan),
        "tension_mean_b": np.where(np.isfinite(amp[:, :, 1]), T[:, 1], np.nan),
        "tension_max_a": T[:, 0] + amp[:, :, 0],
        "tension_min_a": T[:, 0] - amp[:, :, 0],
        "tension_max_b": T[:, 1] + amp[:, :, 1],
        "tension_min_b": T[:, 1] - amp[:, :, 1],
    }
    if len(system.body_names) and model.n_bodies:
        F = np.asarray(static.body_force, dtype=float).reshape(model.n_bodies, 6)
        force = np.abs(arr["body_force"])
        batch["body_force_max"] = F + force
        batch["body_force_min"] = F - force
    n_out = system.lines[0].problem.n_nodes
    grid = _envelope_grid(model, n_out)
    # each node's static elevation plus its heave amplitude (the surface warning's)
    z = _node_elevation(model) + np.abs(arr["displacement"][:, :, 2])
    for key, values in (
        ("tension_envelope_max", arr["envelope_max"]),
        ("tension_envelope_min", arr["envelope_min"]),
        ("z_envelope_max", z),
    ):
        batch[key] = grid.rows(values).reshape(n, L, n_out)
    batch["linearisation_iterations"] = np.array([r.iterations for r in results], dtype=np.int64)
    finite = {
        k: np.isfinite(v.reshape(n, -1)).all(axis=1)
        for k, v in batch.items()
        if v.dtype.kind == "f"
    }
    return results, batch, finite


def _node_elevation(model: Any) -> np.ndarray:
    """The static elevation [m] of every node of ``model``, flat over the lines."""
    return np.concatenate([red.line.position[:, 2] for red in model.lines])


class _Sweep(threading.local):
    """The cases of the chunk being evaluated (:func:`sweep_chunk`) and the harmonic
    responses solved ahead for them (by case hash: :func:`_solve_group`'s entries) with
    the model they were solved on;
    one per thread (the threads scheduler runs chunks side by side)."""

    def __init__(self) -> None:
        self.cases: list[Case] = []
        self.results: dict[str, Any] = {}
        self.model: Any = None
        self.seconds: dict[str, float] = {}

    def pop(self, key: str, default: Any) -> Any:
        return self.results.pop(key, default)


_swept = _Sweep()


@contextmanager
def sweep_chunk(cases: list[Case]) -> Iterator[dict[str, float]]:
    """While a chunk of a system study's cases is evaluated: the first case of a group
    that shares a linear model (static problem, element count, drag settings) and runs
    the frequency domain solves the whole group's harmonic responses in one compiled
    sweep (:func:`~cablestudy.dynamics.system_frequency_sweep.solve_system_sweep_arrays`,
    each case as alone); the others take theirs. Yields, per case hash, the seconds of
    that sweep to move to the case's wall time (its share; the first case's less the
    others')."""
    _swept.cases, _swept.results, _swept.model, _swept.seconds = list(cases), {}, None, {}
    try:
        yield _swept.seconds
    finally:
        _swept.cases, _swept.results, _swept.model = [], {}, None


def _sweepable(case: Case) -> bool:
    """Whether the case runs the frequency domain (method frequency, or auto on a
    harmonic motion of one frequency)."""
    dyn = case.study.analysis.dynamic
    if dyn is None or dyn.method not in ("frequency", "auto"):
        return False
    return dyn.method == "frequency" or not auto_ineligible_system(dyn)


def _solve_sweep(case: Case, model: Any, system: Any, static: Any) -> Any:
    """:func:`_solve_group`'s entry of ``case`` solved in one sweep with the chunk's
    other cases of its group (:func:`sweep_chunk`), theirs kept for them; None when the
    case has no such group (then alone)."""
    from .frequency import drag_settings

    dyn = case.study.analysis.dynamic
    settings = drag_settings(dyn)
    group = [
        c
        for c in _swept.cases
        if c.static_hash == case.static_hash
        and c.study.analysis.dynamic is not None
        and c.study.analysis.dynamic.elements == dyn.elements
        and drag_settings(c.study.analysis.dynamic) == settings
        and _sweepable(c)
    ]
    taken = {id(c) for c in group}
    _swept.cases = [c for c in _swept.cases if id(c) not in taken]
    if len(group) < 2 or id(case) not in taken:
        return None
    t0 = time.perf_counter()
    solved = _solve_group(group, model, system, static, settings, _needs_result(group))
    share = (time.perf_counter() - t0) / len(group)
    _swept.model = model
    mine = None
    for c, entry in zip(group, solved, strict=True):
        if c is case:
            mine = entry
            _swept.seconds[c.hash] = share - share * len(group)
        else:
            _swept.results[c.hash] = entry
            _swept.seconds[c.hash] = share
    return mine


def auto_ineligible_system(dyn: Any) -> str:
    """Why ``method: auto`` cannot try a system's frequency domain ("" if it can): it
    solves harmonic motions of one frequency; histories and a fixed duration are the
    time domain's."""
    if not all(isinstance(e, (BodyHarmonic, PointHarmonic)) for e in dyn.excitations):
        return "excitation is not harmonic (time domain only)"
    if len({e.frequency for e in dyn.excitations}) > 1:
        return "excitation has several frequencies (time domain only)"
    if dyn.history is not None:
        return "time histories asked for (time domain only)"
    if dyn.duration is not None:
        return "a fixed run duration asked for (time domain only)"
    return ""


def run_system_auto(
    case: Case, system: Any, static: Any
) -> tuple[tuple[int, str, dict[str, np.ndarray]] | None, str]:
    """``method: auto`` for a system: the frequency domain's (status, message,
    outputs) where every line passes the single line's checks
    (:mod:`cablestudy.dynamics.system_validity`), else None and why the time domain
    runs (the reason written to ``dynamic_method_reason``, naming the deciding line)."""
    from ..dynamics.system_validity import judge_system, system_measures
    from ..study.analysis import AutoSettings

    dyn = case.study.analysis.dynamic
    why = auto_ineligible_system(dyn)
    if why:
        return None, f"auto: {why}"
    from .system_prejudge import quasi_static_reason

    settings = dyn.auto or AutoSettings()
    early = quasi_static_reason(case, system, static, settings.max_amplitude_sag_ratio)
    if early:  # the shape change alone is beyond the limit (analyses.system_prejudge)
        return None, f"auto: {early}"
    status, message, out, res, model = _solve_frequency(case, system, static, "auto")
    if status != STATUS_OK:
        return None, f"auto: frequency domain failed ({message})"
    on_bed, weight = _judged_nodes(model, system)
    trusted, reason = judge_system(
        model.names, system_measures(model, res, on_bed, weight), settings
    )
    if not trusted:
        return None, f"auto: {reason}"
    out["dynamic_method_reason"] = np.asarray(f"auto: {reason}")
    return (status, message, out), ""


_NODES_CACHE: OrderedDict[int, tuple[Any, Any]] = OrderedDict()


def _judged_nodes(model: Any, system: Any) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Per line of ``model`` which nodes lie on the seabed and the weight per length
    [N/m] at each node, for :func:`~cablestudy.dynamics.system_validity.system_measures`
    (constants of the model: built once per model)."""
    hit = _NODES_CACHE.get(id(model))
    if hit is not None and hit[0] is model:
        return hit[1]
    on_bed, weight = [], []
    for red, sl in zip(model.lines, system.lines, strict=True):
        line = red.line
        med = sl.problem.medium
        if med.depth is not None:
            ground = med.seabed_z(line.position[:, 0], line.position[:, 1])
            # as system_linear finds the laid nodes
            on_bed.append(line.position[:, 2] - ground <= 1e-6 * max(float(line.s[-1]), 1.0))
        else:
            on_bed.append(np.zeros(line.s.size, dtype=bool))
        lm = sl.problem.line
        idx = np.searchsorted(lm.segment_ends, line.s, side="right") - 1
        weight.append(lm.weight[np.clip(idx, 0, len(lm.length) - 1)])
    _NODES_CACHE[id(model)] = (model, (on_bed, weight))
    trim_lru(_NODES_CACHE, _CACHE_SIZE)
    return on_bed, weight
