"""The frequency domain of a system of ONE line between prescribed points (issue 24):
the one-line study's frequency domain, bit for bit.

A system whose one line ends on fixed points or on points of prescribed bodies, with
no free point, is a single line with prescribed end motions: each end moves as its
point does (:func:`~cablestudy.dynamics.system_frequency.prescribed_motion`: the body's
rigid motion ``X + Theta x a`` plus the point's own). Its linear model is the one-line
study's byte for byte (the same nodes, a node at each touchdown point:
:mod:`cablestudy.dynamics.touchdown_mesh`), so its harmonic response goes through the
single line's solve on that model
(:func:`~cablestudy.analyses.line_harmonic.line_harmonic`, which
:func:`~cablestudy.analyses.frequency.solve_frequency_cases` runs) and its outputs
for the line are made by the same operations: the end tension amplitudes and
extremes, the tension envelope (the static tension at the output points plus and
minus the amplitude of its variation), the elevation envelope and the iteration count
are the equivalent one-line study's to the bit. The bodies' force comes from the
line's end force (:func:`~cablestudy.dynamics.system_frequency_sweep.body_forces`, as
for any system).

The single line's drag iteration settles these lines: its fit leans, where a node
hardly moves, on the drag's mean Jacobian, as the system's does
(:mod:`cablestudy.dynamics.drag_lean`; leaning on the small-motion tangent it circled
on 3-D lines, which a system of one line then answered by the system's own
iteration). Where the two studies' conventions differ this keeps the system's: a drag
linearisation that does not converge is a failed case (status
:data:`~cablestudy.dynamics.frequency_model.STATUS_NOT_CONVERGED`, NaN, message), as
in every system (a one-line study records it with ``linearisation_converged`` 0, an
output a system does not have), a singular dynamic matrix too; ``method: auto``
judges the line by the system's checks (:mod:`cablestudy.dynamics.system_validity`).
"""

from __future__ import annotations

import math
import weakref
from typing import Any

import numpy as np

from ..dynamics.frequency_model import STATUS_NOT_CONVERGED, DragSettings, ReducedLine
from ..dynamics.harmonic_cases import solve_harmonic_cases
from ..dynamics.system_frequency import SystemFrequencyResult, SystemLinear, prescribed_motion
from ..dynamics.system_frequency_sweep import body_forces
from ..statics import STATUS_NUMERICAL
from ..statics.system_model import FREE
from .line_harmonic import line_outputs

#: most (cases x nodes) solved in one call (as the one-line study's BATCH_NODES)
BATCH_NODES = 1_000_000

#: per system model its one line as the one-line study reduces it
_REDUCED: weakref.WeakKeyDictionary[SystemLinear, ReducedLine] = weakref.WeakKeyDictionary()


def is_one_line(system: Any) -> bool:
    """Whether the (validated) system is one line between prescribed points: one line,
    no free point (every point fixed or on a prescribed body)."""
    return len(system.lines) == 1 and not bool(np.any(np.asarray(system.point_kind) == FREE))


def _reduced(model: SystemLinear) -> ReducedLine:
    """The model's line reduced as the one-line study reduces its line
    (:meth:`ReducedLine.of` of the same linear line), built once per model."""
    hit = _REDUCED.get(model)
    if hit is None:
        hit = ReducedLine.of(model.lines[0].line)
        _REDUCED[model] = hit
    return hit


def solve_one_line_group(
    motions: list[tuple[np.ndarray, np.ndarray, float]],
    model: SystemLinear,
    system: Any,
    static: Any,
    settings: DragSettings,
) -> list[tuple[SystemFrequencyResult, dict[str, np.ndarray], list[str]]]:
    """Per case of ``motions`` (the bodies' complex motion (B, 6), the points' own
    (P, 3), the frequency [Hz]) of one model and drag settings: its result (status,
    message, the line's response as a :class:`SystemFrequencyResult`), its outputs (the
    system's names, on ``line``) and the names of its outputs that are not finite, as
    :func:`cablestudy.analyses.system_frequency._solve_group` gives them. Each case is
    solved as alone (the single line's solve: the same numbers in any group)."""
    red = _reduced(model)
    step = max(1, BATCH_NODES // red.line.n_nodes)
    out = []
    for i in range(0, len(motions), step):
        out += _group(motions[i : i + step], model, red, system, static, settings)
    return out


def _group(
    motions: list[tuple[np.ndarray, np.ndarray, float]],
    model: SystemLinear,
    red: ReducedLine,
    system: Any,
    static: Any,
    settings: DragSettings,
) -> list[tuple[SystemFrequencyResult, dict[str, np.ndarray], list[str]]]:
    K = len(motions)
    prescribed = np.stack([prescribed_motion(model, X, U) for X, U, _ in motions])
    ends = model.ends[0]
    motion = np.ascontiguousarray(prescribed[:, ends])  # (K, 2, 3): A and B
    omegas = np.array([2.0 * math.pi * f for _, _, f in motions])
    sl = system.lines[0]
    res = solve_harmonic_cases(red, omegas, motion, settings)
    got = line_outputs(red.line, res, static.lines[0], sl.problem.medium, sl.problem.line)
    amp = got.amplitude[:, None, :]  # (K, 1, 2): the one line's
    T = res.tension_static  # (2,)
    support = res.end_force[:, None]  # (K, 1, 2, 3)
    theta = np.stack([np.asarray(X, dtype=complex) for X, _, _ in motions]).reshape(
        K, model.n_bodies, 6
    )[:, :, 3:]
    force = body_forces(model, theta, support)
    batch: dict[str, np.ndarray] = {
        "tension_amplitude_a": amp[:, :, 0],
        "tension_amplitude_b": amp[:, :, 1],
        "tension_mean_a": np.where(np.isfinite(amp[:, :, 0]), T[0], np.nan),
        "tension_mean_b": np.where(np.isfinite(amp[:, :, 1]), T[1], np.nan),
        # the one-line study's tension_max (t_end + |dT| at its end), at both ends
        "tension_max_a": T[0] + amp[:, :, 0],
        "tension_min_a": T[0] - amp[:, :, 0],
        "tension_max_b": T[1] + amp[:, :, 1],
        "tension_min_b": T[1] - amp[:, :, 1],
        "tension_envelope_max": got.envelope_max[:, None, :],
        "tension_envelope_min": got.envelope_min[:, None, :],
        "z_envelope_max": got.z_max[:, None, :],
    }
    if len(system.body_names) and model.n_bodies:
        F = np.asarray(static.body_force, dtype=float).reshape(model.n_bodies, 6)
        batch["body_force_max"] = F + np.abs(force)
        batch["body_force_min"] = F - np.abs(force)
    batch["linearisation_iterations"] = res.iterations.astype(np.int64)
    finite = {
        k: np.isfinite(v.reshape(K, -1)).all(axis=1)
        for k, v in batch.items()
        if v.dtype.kind == "f"
    }
    out = []
    for k in range(K):
        result = SystemFrequencyResult(
            end_tension=res.end_tension[k][None],
            tension_static=T[None],
            element_tension=[res.element_tension[k]],
            displacement=[res.displacement[k]],
            point_displacement=prescribed[k],
            end_force=support[k],
            body_force=force[k],
            iterations=int(res.iterations[k]),
            converged=bool(res.converged[k]),
            change=float(res.change[k]),
            residual=math.nan,  # not computed by the single line's solve
            element_tension_static=[red.line.tension.copy()],
        )
        hz = omegas[k] / (2 * math.pi)
        if not res.ok[k]:
            result.status = STATUS_NUMERICAL
            result.message = f"singular dynamic matrix at {hz:.6g} Hz"
        elif not res.converged[k]:  # a system's status 0 is a converged answer
            result.status = STATUS_NOT_CONVERGED
            result.message = (
                f"drag linearisation did not converge in {settings.max_iterations} "
                f"iterations (last change {res.change[k]:.3g}, tolerance "
                f"{settings.tolerance:.3g})"
            )
        out.append(
            (
                result,
                {name: v[k, ...] for name, v in batch.items()},
                [name for name, ok in finite.items() if not ok[k]],
            )
        )
    return out
