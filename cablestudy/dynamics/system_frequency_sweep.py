"""A sweep of harmonic motions of one linearised system solved together: the cases
(frequency, body motion, the points' own motion) of one :class:`~.system_frequency.
SystemLinear` go to the compiled iteration in one call (:func:`.system_fd_sweep.
solve_sweep`), each case started from its own quasi-static start, as alone: each
case's result is that case's alone (a sweep of one) bit for bit, whatever the cases
beside it.

Pure: arrays in, :class:`~.system_frequency.SystemFrequencyResult` out.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .frequency_model import DragSettings
from .system_frequency import (
    RESIDUAL_BAR,
    SystemFrequencyResult,
    SystemLinear,
    compiled_outcome,
    cross,
    harmonic_result,
    prescribed_motion,
    sweep_compiled,
)


@dataclass(frozen=True)
class SolvedCase:
    """What a study's case of ``method: frequency`` reads of a solved case's result
    (:func:`solve_system_sweep_arrays` with ``full`` false for it): its outputs are the
    sweep's arrays, so the per-line lists of a :class:`~.system_frequency.
    SystemFrequencyResult` are not built."""

    iterations: int
    status: int = 0
    message: str = ""


def solve_system_sweep_arrays(
    model: SystemLinear,
    omega: Sequence[float] | np.ndarray,
    body_motion: Sequence[np.ndarray] | np.ndarray,
    settings: DragSettings | None = None,
    point_excitation: Sequence[np.ndarray | None] | None = None,
    full: Sequence[bool] | None = None,
) -> tuple[list[SystemFrequencyResult | SolvedCase], dict[str, np.ndarray]]:
    """Per case ``i`` the steady harmonic response at ``omega[i]`` [rad/s] to the
    bodies' complex motion ``body_motion[i]`` (B, 6) [m, rad] and the points' own
    ``point_excitation[i]`` (P, 3) [m] (None: none), as
    a sweep of that case alone gives it bit for bit, each case from the quasi-static
    start; and the results of all cases as arrays, cases first
    (``end_tension`` (n, L, 2), ``body_force`` (n, B, 6), the envelope at every node
    ``envelope_max``/``_min`` (n, nodes), ``displacement`` (n, nodes, 3), flat over the
    lines; the rows of the cases whose result has status 0 hold it, the others are not
    results). ``full[i]`` false: a solved case's result is a :class:`SolvedCase` (its
    iterations; a failed one is always the whole result). Never raises for a numerical
    failure."""
    settings = settings or DragSettings()
    w = np.asarray(omega, dtype=float).reshape(-1)
    n = w.size
    own = [None] * n if point_excitation is None else list(point_excitation)
    # the points' motion of each distinct motion once (a sweep of frequency has one)
    seen: dict[bytes, np.ndarray] = {}
    rows = []
    for i in range(n):
        X = np.asarray(body_motion[i], dtype=complex)
        U = None if own[i] is None else np.asarray(own[i], dtype=complex)
        key = X.tobytes() + (b"" if U is None else b"U" + U.tobytes())
        if key not in seen:
            seen[key] = prescribed_motion(model, X, U)
        rows.append(seen[key])
    prescribed = np.stack(rows).reshape(n, model.point_kind.size, 3)
    disp, u_pts, forces, info, finfo = sweep_compiled(model, w, prescribed, settings)
    theta = np.asarray(body_motion, dtype=complex).reshape(n, model.n_bodies, 6)[:, :, 3:]
    post = _post_all(model, w, theta, disp, forces)
    out: list[SystemFrequencyResult | SolvedCase] = []
    for i in range(n):
        if info[i, 0] == 0 and finfo[i, 1] <= RESIDUAL_BAR:
            if full is None or full[i]:
                out.append(_result(model, post, i, info[i], finfo[i], disp[i], u_pts[i]))
            else:
                out.append(SolvedCase(int(info[i, 1])))
            continue
        outcome = compiled_outcome(
            model, float(w[i]), info[i], finfo[i], disp[i], u_pts[i], forces[i]
        )
        out.append(
            harmonic_result(model, float(w[i]), body_motion[i], settings, prescribed[i], outcome)
        )
    _, end_tension, body_force, _, hi, lo = post
    arrays = {
        "end_tension": end_tension,
        "body_force": body_force,
        "envelope_max": hi,
        "envelope_min": lo,
        "displacement": disp,
    }
    return out, arrays


def _post_all(
    model: SystemLinear, w: np.ndarray, theta: np.ndarray, disp: np.ndarray, forces: np.ndarray
) -> tuple[np.ndarray, ...]:
    """:func:`~.system_frequency.harmonic_result`'s outputs of every case at once (cases
    first): end forces on the points (n, L, 2, 3), end tensions (n, L, 2), the bodies'
    force (n, B, 6), the element tensions (n, elements) and the envelope over the
    nodes (n, nodes) above and below."""
    post = model.post
    n, L = w.size, len(model.lines)
    support = -forces.reshape(n, L, 2, 3)
    end_tension = np.sum(post.unit[None] * support, axis=3)
    body_force = body_forces(model, theta, support)
    du = disp[:, post.element + 1] - disp[:, post.element]
    axial = post.axial_stiffness[None] + 1j * w[:, None] * post.axial_damping[None]
    # the sum over the three directions written out: np.sum's order ((0 + 1) + 2), the
    # same values, without its reduction over a short axis (most of this function's cost)
    d = post.direction[None]
    tension = axial * (d[..., 0] * du[..., 0] + d[..., 1] * du[..., 1] + d[..., 2] * du[..., 2])
    var = np.empty((n, post.node_static.size), dtype=complex)
    var[:, post.inner] = 0.5 * (tension[:, post.left] + tension[:, post.right])
    var[:, post.first] = end_tension[:, :, 0]
    var[:, post.last] = end_tension[:, :, 1]
    amp = np.abs(var)
    return support, end_tension, body_force, tension, post.node_static + amp, post.node_static - amp


def body_forces(model: SystemLinear, theta: np.ndarray, support: np.ndarray) -> np.ndarray:
    """The variation of the force and moment [N, N m] (n, B, 6) of the lines on each
    body about its reference point, of n cases: ``support`` (n, L, 2, 3) the variation
    of the force of each line end on its point, ``theta`` (n, B, 3) the bodies' complex
    rotation amplitudes (the static end force turning with the arm;
    :class:`~.system_frequency.SystemFrequencyResult`)."""
    post = model.post
    body_force = np.zeros((support.shape[0], model.n_bodies, 6), dtype=complex)
    if post.body_line.size:
        sup = support[:, post.body_line, post.body_end]
        arm = post.body_arm[None]
        turned = cross(cross(theta[:, post.body], arm), post.body_static[None])
        moment = cross(arm, sup) + turned
        np.add.at(body_force, (slice(None), post.body, slice(0, 3)), sup)
        np.add.at(body_force, (slice(None), post.body, slice(3, 6)), moment)
    return body_force


def _result(
    model: SystemLinear,
    post: tuple[np.ndarray, ...],
    k: int,
    info: np.ndarray,
    finfo: np.ndarray,
    disp: np.ndarray,
    u_pts: np.ndarray,
) -> SystemFrequencyResult:
    """The :class:`~.system_frequency.SystemFrequencyResult` of the solved case ``k`` of
    :func:`_post_all`'s arrays ``post``."""
    support, end_tension, body_force, tension, hi, lo = post
    noff = model.packed.node_offset
    eoff = noff - np.arange(noff.size)  # elements: a line's nodes less one
    L = len(model.lines)

    def split(v: np.ndarray, at: np.ndarray) -> list[np.ndarray]:
        return [v[at[j] : at[j + 1]] for j in range(L)]

    return SystemFrequencyResult(
        end_tension=end_tension[k],
        tension_static=model.post.static,
        element_tension=split(tension[k], eoff),
        displacement=split(disp, noff),
        point_displacement=u_pts,
        end_force=support[k],
        body_force=body_force[k],
        iterations=int(info[1]),
        converged=True,
        change=float(finfo[0]),
        residual=float(finfo[1]),
        element_tension_static=[r.line.tension.copy() for r in model.lines],
        envelope_lines=(split(hi[k], noff), split(lo[k], noff)),
    )
