"""A sweep of harmonic motions of one linearised system solved together: the cases
(frequency, body motion, the points' own motion) of one :class:`~.system_frequency.
SystemLinear` go to the compiled iteration in one call (:func:`.system_fd_sweep.
solve_sweep`), sorted by frequency, each case started from its neighbour's converged
drag (warm start: the module docstring of :mod:`.system_fd_sweep`). Each case's result
is :func:`~.system_frequency.solve_system_harmonic`'s for that case, the drag iteration
stopped at an iterate within the same tolerance of the same fixed point.

Pure: arrays in, :class:`~.system_frequency.SystemFrequencyResult` out.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .frequency_model import DragSettings
from .system_fd_sweep import INFO, solve_sweep
from .system_frequency import (
    SystemFrequencyResult,
    SystemLinear,
    compiled_outcome,
    harmonic_result,
    prescribed_motion,
)


def solve_system_sweep(
    model: SystemLinear,
    omega: Sequence[float] | np.ndarray,
    body_motion: Sequence[np.ndarray] | np.ndarray,
    settings: DragSettings | None = None,
    point_excitation: Sequence[np.ndarray | None] | None = None,
    *,
    warm: bool = True,
) -> list[SystemFrequencyResult]:
    """Per case ``i`` the steady harmonic response at ``omega[i]`` [rad/s] to the
    bodies' complex motion ``body_motion[i]`` (B, 6) [m, rad] and the points' own
    ``point_excitation[i]`` (P, 3) [m] (None: none), as
    :func:`~.system_frequency.solve_system_harmonic` gives it; with ``warm`` the cases
    in order of frequency each start from the one before (module docstring), without
    it each from the quasi-static start. Never raises for a numerical failure."""
    settings = settings or DragSettings()
    w = np.asarray(omega, dtype=float).reshape(-1)
    n = w.size
    own = [None] * n if point_excitation is None else list(point_excitation)
    prescribed = np.stack(
        [prescribed_motion(model, body_motion[i], own[i]) for i in range(n)]
    ).reshape(n, model.point_kind.size, 3)
    order = np.argsort(w, kind="stable")
    packed = model.packed
    N, L, P = int(packed.node_offset[-1]), len(model.lines), model.point_kind.size
    disp = np.empty((n, N, 3), dtype=complex)
    u_pts = np.empty((n, P, 3), dtype=complex)
    forces = np.empty((n, L, 6), dtype=complex)
    info = np.zeros((n, INFO), dtype=np.int64)
    finfo = np.zeros((n, 2))
    solve_sweep(
        np.ascontiguousarray(w[order]),
        np.ascontiguousarray(prescribed[order], dtype=complex),
        float(settings.tolerance),
        int(settings.max_iterations),
        int(settings.samples),
        bool(settings.exact),
        packed.arrays,
        packed.bw,
        bool(warm),
        disp,
        u_pts,
        forces,
        info,
        finfo,
    )
    out: list[SystemFrequencyResult | None] = [None] * n
    for k, i in enumerate(order):
        outcome = compiled_outcome(
            model, float(w[i]), info[k], finfo[k], disp[k], u_pts[k], forces[k]
        )
        out[i] = harmonic_result(model, float(w[i]), body_motion[i], settings, prescribed[i], outcome)
    return out  # type: ignore[return-value]
