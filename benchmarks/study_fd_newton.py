"""Does a Newton iteration pay for the system frequency domain's drag linearisation?
(issue 24, `fdnewton`). Iterations a case, to the kernel's criterion (the velocity
amplitudes change by at most 1e-6 of the largest), on the case8 model of
``bench_fd_kernel.py`` surged 2 m, from the kernel's quasi-static start, by:

- ``kernel``: the compiled iteration (Anderson mixing of the drag, depth 4, damped 0.8);
- ``newton``: exact Newton on the harmonic balance ``A0 u + Phi(i w u) = b``, ``Phi(v) =
  D(v) v`` the fitted drag force of each node and point; its Jacobian is real-linear, not
  complex-linear (``P dv + Q conj(dv)``), so each step is a real system of twice the size,
  here with ``Phi``'s derivative by finite differences per node;
- ``lean``: Newton with the complex-linear part alone (the fit's lean, the mean drag
  Jacobian ``P``): the matrix ``A0 + i w P``, the rest as loads;
- ``chord``: ``lean`` with the matrix kept until a change above half the one before, and
  Anderson mixing (depth 4, undamped) of the motion: most steps are a fit and one
  forward and back substitution, no factorisation.

The global system is assembled with SciPy (sparse, all lines and free points at once),
the fits are the NumPy oracle's (tests/system_drag_reference.py): slow, but every method
on the same equations; each answer is compared with the kernel's at tolerance 1e-10.

    PYTHONPATH=$PWD .venv/bin/python benchmarks/study_fd_newton.py [--nodes 21]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_fd_kernel import model_of  # noqa: E402


class Global:
    """case8's lines and free points in one sparse system: nodal motion ``U`` (3 per
    node, then 3 per point) ``= T q + U_p`` with ``q`` the unknowns."""

    def __init__(self, model, settings) -> None:  # noqa: ANN001
        from tests.system_drag_reference import mean_drag_jacobian, node_fits, point_fits

        self.model, self.settings = model, settings
        self.fits_of = (node_fits, point_fits, mean_drag_jacobian)
        lines, P = model.lines, model.point_kind.size
        self.noff = np.concatenate(([0], np.cumsum([r.line.n_nodes for r in lines])))
        nd = 3 * self.noff[-1]
        rows, cols, vals, col = [], [], [], 0
        for i, r in enumerate(lines):
            B = sp.coo_matrix(r.line.free_basis)
            rows.append(B.row + 3 * self.noff[i])
            cols.append(B.col + col)
            vals.append(B.data)
            col += B.shape[1]
        self.col = {int(p): col + 3 * j for j, p in enumerate(model.free_points)}
        for i in range(len(lines)):
            for e, node in ((0, self.noff[i]), (1, self.noff[i + 1] - 1)):
                p = int(model.ends[i, e])
                if p in self.col:
                    rows.append(3 * node + np.arange(3))
                    cols.append(self.col[p] + np.arange(3))
                    vals.append(np.ones(3))
        for p, c in self.col.items():
            rows.append(nd + 3 * p + np.arange(3))
            cols.append(c + np.arange(3))
            vals.append(np.ones(3))
        r_, c_ = np.concatenate(rows), np.concatenate(cols)
        shape = (nd + 3 * P, c_.max() + 1)
        self.T = sp.csr_matrix((np.concatenate(vals), (r_, c_)), shape=shape)
        zero = sp.csr_matrix((3 * P, 3 * P))
        self.K = sp.block_diag([r.line.stiffness for r in lines] + [zero]).tocsr()
        self.C = sp.block_diag([r.line.damping for r in lines] + [zero]).tocsr()
        masses = [m for r in lines for m in r.line.mass] + list(model.point_mass)
        self.M = sp.block_diag(masses).tocsr()

    def prescribed(self, pres: np.ndarray) -> np.ndarray:
        m, nd = self.model, 3 * self.noff[-1]
        up = np.zeros(self.T.shape[0], complex)
        for i in range(len(m.lines)):
            for e, node in ((0, self.noff[i]), (1, self.noff[i + 1] - 1)):
                if int(m.ends[i, e]) not in self.col:
                    up[3 * node : 3 * node + 3] = pres[m.ends[i, e]]
        for p in range(m.point_kind.size):
            if p not in self.col:
                up[nd + 3 * p : nd + 3 * p + 3] = pres[p]
        return up

    def fits(self, w: float, U: np.ndarray) -> tuple[sp.csr_matrix, sp.csr_matrix]:
        """The drag fit ``D`` and its lean ``P`` of every node and point at ``i w U``."""
        node_fits, point_fits, _ = self.fits_of
        m, nd = self.model, 3 * self.noff[-1]
        D, L = [], []
        for i, r in enumerate(m.lines):
            lean, fit = node_fits(
                r.line,
                1j * w * U[3 * self.noff[i] : 3 * self.noff[i + 1]].reshape(-1, 3),
                self.settings,
            )
            D += list(fit)
            L += list(lean)
        vp = 1j * w * U[nd:].reshape(-1, 3)
        Dp = point_fits(m.point_drag, m.point_current, vp, self.settings)
        th = 2 * np.pi * np.arange(4096) / 4096  # the points' lean by dense quadrature
        rel = m.point_current[None] - (
            vp.real[None] * np.cos(th)[:, None, None] - vp.imag[None] * np.sin(th)[:, None, None]
        )
        nr = np.linalg.norm(rel, axis=2)[..., None, None]
        outer = rel[..., :, None] * rel[..., None, :] / np.where(nr > 0, nr, 1.0)
        Lp = m.point_drag[:, None, None] * np.mean(nr * np.eye(3) + outer, axis=0)
        return sp.block_diag(D + list(Dp)).tocsr(), sp.block_diag(L + list(Lp)).tocsr()


def iterate(
    g: Global, w: float, pres: np.ndarray, method: str, tol: float = 1e-6
) -> tuple[int, np.ndarray]:
    """Iterations to ``tol`` (module docstring) and the answer."""
    T, up = g.T, g.prescribed(pres)
    A0 = (g.K + 1j * w * g.C - w * w * g.M).tocsr()
    U = T @ spl.spsolve((T.T @ g.K @ T).tocsc(), -(T.T @ (g.K @ up))) + up
    prev, hist, lu, last, ref = U, [], None, np.inf, None
    for it in range(1, 101):
        D, L = g.fits(w, U)
        if method == "newton":
            F = D @ (1j * w * U)
            h = 1e-7 * np.abs(U).max()
            J = np.zeros((2, U.size // 3, 3, 3), complex)  # d Phi / d (Re, Im) U_a per node
            for k, part in enumerate((1.0, 1j)):
                for a in range(3):
                    dU = np.zeros(U.size, complex)
                    dU[a::3] = part * h
                    Fa = g.fits(w, U + dU)[0] @ (1j * w * (U + dU))
                    J[k, :, :, a] = ((Fa - F) / h).reshape(-1, 3)
            JR, JI = (sp.block_diag(list(Jk)).tocsr() for Jk in J)
            Ar = T.T @ A0 @ T
            Mre, Mim = Ar + T.T @ JR @ T, 1j * Ar + T.T @ JI @ T
            res = T.T @ (A0 @ U + F)
            x = spl.spsolve(
                sp.bmat([[Mre.real, Mim.real], [Mre.imag, Mim.imag]]).tocsc(),
                -np.concatenate([res.real, res.imag]),
            )
            n = T.shape[1]
            Un = U + T @ (x[:n] + 1j * x[n:])
        else:
            if method == "lean" or lu is None:
                ref = L
                lu = spl.splu((T.T @ (A0 + 1j * w * ref) @ T).tocsc())
                hist = []
            rhs = T.T @ (1j * w * ((ref - D) @ U) - (A0 + 1j * w * ref) @ up)
            Un = T @ lu.solve(rhs) + up
        change = np.abs(Un - prev).max() / np.abs(Un).max()
        prev = Un
        if change <= tol:
            return it, Un
        if method == "chord":
            if change > 0.5 * last:
                lu = None
            x, gx = np.concatenate([U.real, U.imag]), np.concatenate([Un.real, Un.imag])
            hist = [*hist[-4:], (gx - x, gx)]
            r = gx - x
            out = gx
            if len(hist) > 1:
                dR = np.array([r - Rj for Rj, _ in hist[:-1]])
                A = dR @ dR.T
                gam = np.linalg.solve(A + 1e-12 * np.trace(A) * np.eye(len(A)), dR @ r)
                out = gx - sum(c * (gx - Gj) for c, (_, Gj) in zip(gam, hist[:-1], strict=True))
            Un = out[: U.size] + 1j * out[U.size :]
        last = change
        U = Un
    return -1, U


def main() -> None:
    from cablestudy.dynamics.frequency_model import DragSettings
    from cablestudy.dynamics.system_frequency import prescribed_motion
    from tests.system_frequency_reference import solve_system_harmonic

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nodes", type=int, default=21)
    ap.add_argument("--methods", default="newton,lean,chord")
    a = ap.parse_args()
    model = model_of(a.nodes)
    g = Global(model, DragSettings())
    motion = np.array([[-2j, 0, 0, 0, 0, 0]])
    pres = prescribed_motion(model, motion)
    methods = a.methods.split(",")
    print("Hz     kernel " + " ".join(f"{m:>7}" for m in methods) + "  (iterations; largest error)")
    for f in np.linspace(0.02, 0.5, 9):
        w = 2 * np.pi * f
        tight = solve_system_harmonic(model, w, motion, DragSettings(tolerance=1e-10))
        exact = np.concatenate(
            [*(d.ravel() for d in tight.displacement), tight.point_displacement.ravel()]
        )
        runs = [iterate(g, w, pres, m) for m in methods]
        err = max(np.abs(U - exact).max() for _, U in runs) / np.abs(exact).max()
        counts = " ".join(f"{n:7d}" for n, _ in runs)
        print(
            f"{f:.3f} {solve_system_harmonic(model, w, motion).iterations:7d} {counts}  {err:.1e}"
        )


if __name__ == "__main__":
    main()
