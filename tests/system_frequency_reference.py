"""The system frequency domain's drag iteration in NumPy and LAPACK, line by line: the
test oracle the compiled iteration (:mod:`cablestudy.dynamics.system_fd_kernel`) is held
to (same equations, same criterion and iteration; :func:`iterate_reference`;
:func:`solve_reference` is :func:`solve_system_harmonic` by it). Per line one LAPACK band solve with
the six end unit motions as right sides (the condensed end dynamic stiffness ``S``),
the junction system by NumPy, the drag fits by
:func:`tests.system_drag_reference.node_fits` (phase sums, or dense quadrature where the
compiled fit takes exact means) and :func:`tests.system_drag_reference.point_fits`.

Pure: arrays and the linear model in, arrays out.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy.linalg.lapack import zgbsv as _zgbsv

from cablestudy.dynamics.frequency_model import DragSettings, ReducedLine

from .system_drag_reference import node_fits, point_fits

SystemLinear = Any  # :class:`cablestudy.dynamics.system_frequency.SystemLinear`


def _dynamic_parts(
    model: SystemLinear, omega: float
) -> list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    """Per line the parts of its dynamic matrix without drag at ``omega``, shared by
    the drag iterations of a case: the band of ``A_II`` and the blocks ``A_IE``,
    ``A_EI``, ``A_EE``."""
    w2, iw = omega**2, 1j * omega
    out = []
    for red, ec in zip(model.lines, model.couplings, strict=True):
        blocks = tuple(ec.K[j] - w2 * ec.M[j] + iw * ec.C[j] for j in range(3))
        out.append((red.K - w2 * red.M + iw * red.C, *blocks))
    return out


def _condense(
    red: ReducedLine,
    parts: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    omega: float,
    D: np.ndarray | None,
) -> tuple[np.ndarray, np.ndarray] | None:
    """Per line: ``X`` (k, 6), the inner response per unit end motion (``A_II X =
    -A_IE``, one band solve with six right sides), and ``S = A_EE + A_EI X`` (6, 6), the
    condensed end dynamic stiffness; None if ``A_II`` is singular. ``parts``: the
    line's :func:`_dynamic_parts` at ``omega``."""
    iw = 1j * omega
    ab, A_IE, A_EI, A_EE = parts
    if D is not None:
        A_EE = A_EE.copy()
        A_EE[:3, :3] += iw * D[0]
        A_EE[3:, 3:] += iw * D[-1]
    if A_IE.shape[0] == 0:
        return np.zeros((0, 6), dtype=complex), A_EE
    bw = red.bandwidth
    # LAPACK's banded LU with partial pivoting (what solve_banded calls), without
    # solve_banded's argument checks: the band padded by bw rows for the fill-in
    work = np.zeros((3 * bw + 1, ab.shape[1]), dtype=complex)
    work[bw:] = ab
    if D is not None:
        work[bw:] += iw * red.drag_band(D)
    _, _, X, info = _zgbsv(bw, bw, work, -A_IE, overwrite_ab=1, overwrite_b=1)
    if info != 0 or not np.all(np.isfinite(X)):
        return None
    return X, A_EE + A_EI @ X


def _solve_linear(
    model: SystemLinear,
    omega: float,
    prescribed: np.ndarray,
    D_lines: list[np.ndarray | None],
    D_points: np.ndarray | None,
    parts: list,
    *,
    quasi_static: bool = False,
) -> tuple[np.ndarray, list[np.ndarray], list[np.ndarray]] | str:
    """One linear solve at fixed drag: point displacements (P, 3), per line the nodal
    displacements (n, 3) and end forces ``S u_E`` (6,); or the reason it failed.
    ``parts``: :func:`_dynamic_parts` at the solve's frequency (0 if quasi-static)."""
    w = 0.0 if quasi_static else omega
    free = model.free_points
    slot = np.full(model.point_kind.size, -1)
    slot[free] = np.arange(free.size)
    G = np.zeros((3 * free.size, 3 * free.size), dtype=complex)
    rhs = np.zeros(3 * free.size, dtype=complex)
    for j, p in enumerate(free):
        Z = -(w**2) * model.point_mass[p]
        if D_points is not None and not quasi_static:
            Z = Z + 1j * w * D_points[p]
        G[3 * j : 3 * j + 3, 3 * j : 3 * j + 3] += Z
    condensed = []
    for i, red in enumerate(model.lines):
        c = _condense(red, parts[i], w, None if quasi_static else D_lines[i])
        if c is None:
            hz = omega / (2 * math.pi)
            return f"singular dynamic matrix of line {model.names[i]!r} at {hz:.6g} Hz"
        condensed.append(c)
        _, S = c
        for ea in range(2):
            p = model.ends[i, ea]
            if slot[p] < 0:
                continue
            rows = slice(3 * slot[p], 3 * slot[p] + 3)
            for eb in range(2):
                q = model.ends[i, eb]
                block = S[3 * ea : 3 * ea + 3, 3 * eb : 3 * eb + 3]
                if slot[q] >= 0:
                    G[rows, 3 * slot[q] : 3 * slot[q] + 3] += block
                else:
                    rhs[rows] -= block @ prescribed[q]
    u_points = prescribed.astype(complex).copy()
    if free.size:
        try:
            sol = np.linalg.solve(G, rhs)
        except np.linalg.LinAlgError:
            return f"singular junction system at {omega / (2 * math.pi):.6g} Hz"
        if not np.all(np.isfinite(sol)):
            return f"singular junction system at {omega / (2 * math.pi):.6g} Hz"
        u_points[free] = sol.reshape(-1, 3)
    displacement, forces = [], []
    for i, (X, S) in enumerate(condensed):
        uE = u_points[model.ends[i]].ravel()
        line = model.lines[i].line
        u = (line.free_basis @ (X @ uE)).reshape(-1, 3).astype(complex)
        u[0] += uE[:3]
        u[-1] += uE[3:]
        displacement.append(u)
        forces.append(S @ uE)
    return u_points, displacement, forces


def _flat(D_lines: list, D_points: np.ndarray) -> np.ndarray:
    return np.concatenate([*(d.ravel() for d in D_lines), D_points.ravel()])


def _unflat(
    flat: np.ndarray, sizes: list[int], like_lines: list, like_points: np.ndarray
) -> tuple[list[np.ndarray], np.ndarray]:
    out, start = [], 0
    for size, like in zip(sizes, like_lines, strict=True):
        out.append(flat[start : start + size].reshape(like.shape))
        start += size
    return out, flat[start:].reshape(like_points.shape)


#: secant pairs kept by the Anderson mixing of the drag iteration and the damping of
#: its step (:data:`cablestudy.dynamics.system_fd_fit.DEPTH` and ``MIXING``, where
#: the choice is measured)
ANDERSON_DEPTH = 4
MIXING = 0.8


class _Anderson:
    """Mixing of the fixed point ``D = G(D)`` (``G`` the drag fit to the motion ``D``
    gave): after a change that grew, the mean of ``D`` and ``G`` with the history
    dropped; else damped Anderson mixing over the last pairs of residual ``R = G - D``
    and ``G``: ``D = gbar - (1 - MIXING) rbar`` with ``gbar = G - sum_j g_j (G - G_j)``,
    ``rbar = R - sum_j g_j (R - R_j)`` and ``g`` the least-squares fit of ``R`` by the
    residual differences ``R - R_j`` (with one pair, ``D + MIXING R``)."""

    def __init__(self) -> None:
        self.R: list[np.ndarray] = []
        self.G: list[np.ndarray] = []

    def step(self, d: np.ndarray, g: np.ndarray, change: float, last: float) -> np.ndarray:
        if change >= last:
            self.R.clear()
            self.G.clear()
            return 0.5 * (d + g)
        r = g - d
        self.R.append(r)
        self.G.append(g)
        if len(self.R) > ANDERSON_DEPTH + 1:
            del self.R[0], self.G[0]
        plain = d + MIXING * r
        if len(self.R) == 1:
            return plain
        dR = np.array([r - Rj for Rj in self.R[:-1]])
        A = dR @ dR.T
        trace = float(np.trace(A))
        if not trace > 0.0:
            return plain
        A += 1e-12 * trace * np.eye(A.shape[0])  # a near-dependent pair gets no weight
        gam = np.linalg.solve(A, dR @ r)
        damp = 1.0 - MIXING  # gbar - damp rbar, a pair at a time (as the kernel)
        out = g - damp * r
        for c, Gj, Rj in zip(gam, self.G[:-1], self.R[:-1], strict=True):
            out -= c * ((g - Gj) - damp * (r - Rj))
        return out


def _velocity_change(old: list[np.ndarray], new: list[np.ndarray]) -> float:
    big = max(float(np.max(np.abs(v))) for v in new)
    diff = max(float(np.max(np.abs(a - b))) for a, b in zip(old, new, strict=True))
    return diff / max(big, 1e-300)


def _residual(
    model: SystemLinear,
    omega: float,
    u_pts: np.ndarray,
    disp: list[np.ndarray],
    D_lines: list[np.ndarray | None],
    D_points: np.ndarray | None,
) -> float:
    """Largest residual of the assembled equations (inner rows of every line, balance of
    every free point) relative to the force scale: the
    largest end force amplitude or stiffness force."""
    scale = 0.0
    worst = 0.0
    balance = np.zeros(u_pts.shape, dtype=complex)
    for i, red in enumerate(model.lines):
        r = red.apply(disp[i], omega, D_lines[i])
        ku = (red.line.stiffness @ disp[i].ravel()).reshape(-1, 3)
        scale = max(scale, float(np.max(np.abs(r[[0, -1]]))), float(np.max(np.abs(ku))))
        worst = max(worst, float(np.max(np.abs(r[1:-1]), initial=0.0)))
        balance[model.ends[i, 0]] += r[0]
        balance[model.ends[i, 1]] += r[-1]
    free = model.free_points
    if free.size:
        Z = -(omega**2) * model.point_mass[free]
        if D_points is not None:
            Z = Z + 1j * omega * D_points[free]
        balance[free] += np.einsum("pab,pb->pa", Z, u_pts[free])
        worst = max(worst, float(np.max(np.abs(balance[free]))))
    return worst / max(scale, 1e-300)


def iterate_reference(
    model: SystemLinear, omega: float, prescribed: np.ndarray, settings: DragSettings
) -> tuple:
    """The drag iteration of a case (:mod:`.system_frequency`'s docstring): (failure
    kind or "", message, iterations, converged, change, u_pts, displacements, forces
    (L, 6), residual). Failure kinds: "numerical", "not converged"."""
    L = len(model.lines)
    D_lines: list[np.ndarray | None] = [None] * L
    D_points: np.ndarray | None = None
    iterations, converged, change = 0, True, 0.0
    parts = _dynamic_parts(model, omega)
    if model.has_drag:
        start = _solve_linear(
            model, omega, prescribed, D_lines, None, _dynamic_parts(model, 0.0), quasi_static=True
        )
        if isinstance(start, str):
            return (
                "numerical",
                f"quasi-static start: {start}",
                0,
                False,
                0.0,
                None,
                None,
                None,
                math.nan,
            )
        u_pts, disp, _ = start

        def fit(u_pts: np.ndarray, disp: list[np.ndarray]) -> tuple[list, np.ndarray]:
            Dl = []
            for r, u in zip(model.lines, disp, strict=True):
                v = 1j * omega * u
                Dl.append(node_fits(r.line, v, settings)[1])
            Dp = point_fits(model.point_drag, model.point_current, 1j * omega * u_pts, settings)
            return Dl, Dp

        D_lines, D_points = fit(u_pts, disp)
        sizes = [d.size for d in D_lines]
        mixer = _Anderson()
        previous = [*disp, u_pts]
        converged, last = False, math.inf
        for iterations in range(1, settings.max_iterations + 1):  # noqa: B007
            out = _solve_linear(model, omega, prescribed, D_lines, D_points, parts)
            if isinstance(out, str):
                return "numerical", out, iterations, False, change, None, None, None, math.nan
            u_pts, disp, _ = out
            change = _velocity_change(previous, [*disp, u_pts])
            previous = [*disp, u_pts]
            if change <= settings.tolerance:
                converged = True
                break
            new_l, new_p = fit(u_pts, disp)
            flat = mixer.step(_flat(D_lines, D_points), _flat(new_l, new_p), change, last)
            last = change
            D_lines, D_points = _unflat(flat, sizes, D_lines, D_points)
        if not converged:
            return "not converged", "", iterations, False, change, None, None, None, math.nan
    out = _solve_linear(model, omega, prescribed, D_lines, D_points, parts)
    if isinstance(out, str):
        return "numerical", out, iterations, False, change, None, None, None, math.nan
    u_pts, disp, forces = out
    residual = _residual(model, omega, u_pts, disp, D_lines, D_points)
    return "", "", iterations, converged, change, u_pts, disp, np.array(forces), residual


def solve_reference(
    model: SystemLinear,
    omega: float,
    body_motion: np.ndarray,
    settings: DragSettings | None = None,
    point_excitation: np.ndarray | None = None,
    iterate: Any = None,
) -> Any:
    """:func:`solve_system_harmonic` with the drag iterated by ``iterate`` (default
    :func:`iterate_reference`) instead of the compiled kernel."""
    from cablestudy.dynamics.system_frequency import harmonic_result, prescribed_motion

    settings = settings or DragSettings()
    prescribed = prescribed_motion(model, body_motion, point_excitation)
    outcome = (iterate or iterate_reference)(model, omega, prescribed, settings)
    return harmonic_result(model, omega, body_motion, settings, prescribed, outcome)


def _iterate_compiled(
    model: SystemLinear, omega: float, prescribed: np.ndarray, settings: DragSettings
) -> tuple:
    """The compiled iteration a study runs (:func:`cablestudy.dynamics.system_fd_sweep.
    solve_sweep`) for one case, a sweep of one, as :func:`iterate_reference`'s outcome."""
    from cablestudy.dynamics.system_frequency import compiled_outcome, sweep_compiled

    w = np.array([float(omega)])
    disp, u_pts, forces, info, finfo = sweep_compiled(model, w, prescribed, settings)
    return compiled_outcome(model, omega, info[0], finfo[0], disp[0], u_pts[0], forces[0])


def solve_system_harmonic(
    model: SystemLinear,
    omega: float,
    body_motion: np.ndarray,
    settings: DragSettings | None = None,
    point_excitation: np.ndarray | None = None,
) -> Any:
    """Steady harmonic response at ``omega`` [rad/s] to the bodies' complex motion
    amplitudes ``body_motion`` [m, rad] (B, 6) and the points' own complex displacement
    amplitudes ``point_excitation`` [m] (P, 3) (fixed or body points moved on their own,
    added to their bodies' motion; None: none): one case alone through the compiled
    iteration a study runs (:func:`_iterate_compiled`). Never raises for a numerical
    failure: status and message."""
    return solve_reference(
        model, omega, body_motion, settings, point_excitation, iterate=_iterate_compiled
    )


def envelope(result: Any) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Per line the linear tension envelope at its nodes [N] (n_l,), (max, min), as a
    solve gives it (``result.envelope_lines``), else from the element tensions: static
    plus and minus the amplitude of the variation; at the ends the end tensions, inside
    the mean of the two elements a node joins (static and complex variation)."""
    if result.envelope_lines is not None:
        return result.envelope_lines
    hi, lo = [], []
    T, dT = result.tension_static, result.end_tension
    for i, (t, d) in enumerate(
        zip(result.element_tension_static, result.element_tension, strict=True)
    ):
        static = np.concatenate(([T[i, 0]], 0.5 * (t[:-1] + t[1:]), [T[i, 1]]))
        var = np.concatenate(([dT[i, 0]], 0.5 * (d[:-1] + d[1:]), [dT[i, 1]]))
        hi.append(static + np.abs(var))
        lo.append(static - np.abs(var))
    return hi, lo


def system_frequency_outputs(
    result: Any, body_force_static: np.ndarray | None = None
) -> dict[str, Any]:
    """The issue's outputs of one solved case from its own result (linear response:
    extremes are the static value plus and minus the amplitude, the mean the static
    value): the oracle of a study's outputs computed for all cases of a sweep at once
    (:func:`cablestudy.analyses.system_frequency.group_arrays`). On ``line``
    ``tension_amplitude_a``/``_b``, ``tension_max_a``, ``tension_min_a``,
    ``tension_mean_a`` (and ``_b``); per line at its nodes ``tension_envelope_max``/
    ``_min`` (list of arrays); with the bodies' static force and moment
    ``body_force_static`` (B, 6) [N, N m], ``body_force_max``/``_min`` on (``body``,
    ``dof``). NaN where the case failed (status says why)."""
    amp = np.abs(result.end_tension)
    T = result.tension_static
    hi, lo = envelope(result)
    out: dict[str, Any] = {
        "tension_amplitude_a": amp[:, 0],
        "tension_amplitude_b": amp[:, 1],
        "tension_mean_a": np.where(np.isfinite(amp[:, 0]), T[:, 0], np.nan),
        "tension_mean_b": np.where(np.isfinite(amp[:, 1]), T[:, 1], np.nan),
        "tension_max_a": T[:, 0] + amp[:, 0],
        "tension_min_a": T[:, 0] - amp[:, 0],
        "tension_max_b": T[:, 1] + amp[:, 1],
        "tension_min_b": T[:, 1] - amp[:, 1],
        "tension_envelope_max": hi,
        "tension_envelope_min": lo,
    }
    if body_force_static is not None and result.body_force.size:
        F = np.asarray(body_force_static, dtype=float).reshape(result.body_force.shape)
        out["body_force_max"] = F + np.abs(result.body_force)
        out["body_force_min"] = F - np.abs(result.body_force)
    return out
