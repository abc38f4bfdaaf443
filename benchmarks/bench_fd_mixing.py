"""Drag iterations of the system frequency domain (issue 24) and why there are about
ten: the packed case8 model of ``bench_fd_kernel.py`` (``--nodes`` a line) at the 50
frequencies 0.02-0.5 Hz, moved in surge (2 m), sway (1 m), heave (1 m) and pitch (0.05
rad): the compiled iteration's drag iterations a case (mean, max) per motion; with
``--spectrum F`` also the eigenvalues of the fixed-point map's Jacobian ``dG/dD`` at
the converged drag of the surge case at ``F`` Hz (``G`` the fit to the motion the drag
``D`` gives: one solve and one fit per column, by finite differences of 1e-6 of each
entry), the contraction that limits any mixing of the fit.

Measured (issue 24, fditer): at 0.5 Hz the largest are -0.72 +- 0.17i, -0.61 +- 0.05i
(two pairs), -0.50, -0.48, with 6 above 0.5, 18 above 0.2 and 62 above 0.05 in
modulus; at 0.16 Hz the largest is -0.42 and 14 are above 0.05. Anderson mixing of
depth 3 to 12, damped or not, converges at about a factor 3-4 a step on this spectrum,
on the map itself and on its linearisation alike; a start within 1 % of the fixed point
still takes about 10 iterations to the 1e-6 tolerance (0.5 Hz).

    PYTHONPATH=$PWD .venv/bin/python benchmarks/bench_fd_mixing.py [--spectrum 0.5]
"""

from __future__ import annotations

import argparse

import numpy as np
from bench_fd_kernel import model_of

MOTIONS = {
    "surge": [-2j, 0, 0, 0, 0, 0],
    "sway": [0, -1j, 0, 0, 0, 0],
    "heave": [0, 0, -1j, 0, 0, 0],
    "pitch": [0, 0, 0, 0, -0.05j, 0],
}


def spectrum(model, hz: float) -> np.ndarray:  # noqa: ANN001
    """The eigenvalues of ``dG/dD`` at the converged drag of surge at ``hz``."""
    from cablestudy.dynamics import system_fd_sweep as S
    from cablestudy.dynamics.system_frequency import prescribed_motion

    p = model.packed
    m, bw = p.arrays, p.bw
    N, P, L = int(p.node_offset[-1]), model.point_kind.size, len(model.lines)
    ws = S.workspace(m, bw, 32)
    w = 2.0 * np.pi * hz
    pres = prescribed_motion(model, np.array([MOTIONS["surge"]]))
    disp, u_pts = np.zeros((N, 3), complex), np.zeros((P, 3), complex)
    forces, info, finfo = np.zeros((L, 6), complex), np.zeros(4, np.int64), np.zeros(2)
    S.iterate(w, pres, 1e-9, 200, True, m, bw, ws, disp, u_pts, forces, info, finfo)
    assert info[0] == 0, info
    D = ws[13].copy()

    def G(x: np.ndarray) -> np.ndarray:
        ws[13][:] = x
        d, u = np.zeros((N, 3), complex), np.zeros((P, 3), complex)
        code, _ = S._solve_at(w, True, m, bw, ws, pres, d, u, np.zeros((L, 6), complex))
        assert code == 0
        out = np.zeros_like(x)
        S._fit_at(w, m, ws, True, d, u, out)
        return out

    g0 = G(D)
    idx = np.flatnonzero(D != 0.0)
    J = np.empty((idx.size, idx.size))
    for c, k in enumerate(idx):
        h = 1e-6 * abs(D[k])
        x = D.copy()
        x[k] += h
        J[:, c] = (G(x)[idx] - g0[idx]) / h
    return np.linalg.eigvals(J)


def main() -> None:
    from cablestudy.dynamics.frequency_model import DragSettings
    from cablestudy.dynamics.system_frequency import prescribed_motion, sweep_compiled

    ap = argparse.ArgumentParser()
    ap.add_argument("--nodes", type=int, default=21)
    ap.add_argument("--spectrum", type=float)
    a = ap.parse_args()
    model = model_of(a.nodes)
    w = 2.0 * np.pi * np.linspace(0.02, 0.5, 50)
    means = []
    for name, motion in MOTIONS.items():
        pres = np.stack([prescribed_motion(model, np.array([motion]))] * w.size)
        info = sweep_compiled(model, w, pres, DragSettings())[3]
        it = info[:, 1]
        means.append(it.mean())
        print(f"{name}: iterations mean {it.mean():.2f} max {it.max()} status {set(info[:, 0])}")
    print(f"all: mean {np.mean(means):.3f}")
    if a.spectrum:
        ev = spectrum(model, a.spectrum)
        ev = ev[np.argsort(-np.abs(ev))]
        mod = np.abs(ev)
        print(f"dG/dD at {a.spectrum} Hz: largest {np.round(ev[:8], 3)}")
        counts = ", ".join(f"{b}: {(mod > b).sum()}" for b in (0.5, 0.2, 0.05))
        print(f"  how many above {counts}")


if __name__ == "__main__":
    main()
