"""Where the shooting solver starts (:mod:`.shooting`): the setup of a solve
(:class:`_Setup`: the line, environment, start and far ends, seabed), where a shot
starts (:class:`_Start`), and the first guesses of the unknown start values that
Newton's method refines (:class:`_StartGuesses`: from the elastic catenary between the
ends, from a free end, on a seabed, and the alternatives tried when Newton fails).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .base import (
    EndCondition,
)
from .elastic_catenary import CatenarySolution, profile, solve_between
from .shooting_ode import (
    _Env,
    _Integrator,
    _Line,
    _Seabed,
    _ShotFailed,
)


@dataclass
class _Setup:
    line: _Line
    env: _Env
    start: EndCondition
    far: EndCondition
    reverse: bool
    bed: _Seabed | None
    mode: str  # 'fixed', 'grounded', 'force' or 'mooring': the kind of the start end
    force_scale: float


@dataclass
class _Start:
    """Where a shot starts: at s0 with force F(s0-) and position r(s0); ``laid`` is the
    laid direction (grounded start with a laid part), ``t_tdp`` the touchdown tension;
    ``force_start`` is the force of the line on the start fixture [N]; ``origin`` the
    position at s = 0 [m]."""

    s0: float
    force: np.ndarray
    position: np.ndarray
    laid: np.ndarray | None
    t_tdp: float
    force_start: np.ndarray
    origin: np.ndarray


class _StartGuesses:
    """The first guesses of :class:`.shooting.ShootingSolver` (a base class: the
    solver's own methods build the shots they need)."""

    def _guess(self, st: _Setup) -> np.ndarray:
        if st.mode in ("force", "mooring"):
            return self._guess_from_free_end(st)
        line, far = st.line, st.far
        L = line.length
        w = line.mean_weight()
        EA = L / line.compliance()
        assert st.start.position is not None
        p0 = np.asarray(st.start.position, dtype=float)
        loads = line.total_load()
        F0: np.ndarray | None = None
        if far.kind == "force":
            assert far.force is not None
            F0 = np.asarray(far.force, dtype=float) - loads
        elif far.kind == "fixed":
            assert far.position is not None
            res = solve_between(p0, far.position, L, w, EA, np.array([0.0, L]), tolerance=1e-10)
            if res.success:
                F0 = res.force_a.copy()
            else:
                d = np.asarray(far.position) - p0
                chord = float(np.linalg.norm(d))
                F0 = (d / chord if chord > 0 else np.array([0.0, 0.0, 1.0])) * st.force_scale
            for s_k, p in zip(line.att_s, line.att_force, strict=True):
                F0 = F0 + np.asarray(p) * (1.0 - s_k / L)
        else:  # mooring
            assert far.force is not None and far.z is not None
            Hv = np.array([far.force[0], far.force[1]])
            H = float(np.linalg.norm(Hv))
            h = far.z - p0[2]
            VA = self._mooring_va(H, h, L, w, EA)
            F0 = np.array([Hv[0] - loads[0], Hv[1] - loads[1], VA])
        if st.mode == "fixed":
            return F0 / st.force_scale
        return self._grounded_guess(st, F0, w)

    def _guess_from_free_end(self, st: _Setup) -> np.ndarray:
        """Start at a force or mooring end: one still-water shot from a trial position
        gives the offset to the fixed far end (exact without current)."""
        line, far = st.line, st.far
        L = line.length
        assert far.position is not None and st.start.force is not None
        p_far = np.asarray(far.position, dtype=float)
        if st.mode == "force":
            u = p_far / L
        else:
            assert st.start.z is not None
            R = np.asarray(st.start.force, dtype=float)
            H = float(np.linalg.norm(R[:2]))
            w = line.mean_weight()
            EA = L / line.compliance()
            # catenary from the far (fixed) end to the mooring end: tension there is
            # (H e, V_A + w L) along the line towards the mooring end
            VA = self._mooring_va(H, st.start.z - p_far[2], L, w, EA)
            vz = -(VA + w * L)
            u = np.array([vz / st.force_scale, p_far[0] / L, p_far[1] / L])
        integ = _Integrator(
            line, st.env.scaled(0.0), rtol=1e-8, force_scale=st.force_scale, deadline=None
        )
        try:
            shot = integ.run(*self._shot_args(st, integ, u), dense=False)
        except _ShotFailed:
            return u
        shift = p_far - shot.position_end
        if st.mode == "force":
            return u + shift / L
        return np.array([u[0], u[1] + shift[0] / L, u[2] + shift[1] / L])

    @staticmethod
    def _other_guesses(st: _Setup, u0: np.ndarray) -> list[np.ndarray]:
        """Further starting points, tried in turn when Newton fails from the first."""
        if st.mode == "grounded":
            return [
                np.array([u0[0] * f, u0[1], q])
                for f in (1.0, 0.3)
                for q in (0.5, 0.2, 0.05, -0.2)
                if q != u0[2]
            ]
        if st.mode == "fixed":
            return [u0 * f for f in (0.3, 3.0, 10.0)]
        return []

    @staticmethod
    def _mooring_va(H: float, h: float, L: float, w: float, EA: float) -> float:
        """Vertical component V_A of the tension vector at A of a uniform catenary with
        horizontal tension H whose far end is h above A [N]."""
        from scipy.optimize import brentq

        if w == 0.0:
            return H * h / max(math.sqrt(max(L * L - h * h, 1e-12 * L * L)), 1e-12)

        def f(VA: float) -> float:
            sol = CatenarySolution(H, VA, np.array([1.0, 0.0]), L, w, EA, 0, 0.0)
            return float(profile(sol, np.array([L]))[1][0]) - h

        lo, hi = -abs(w) * L - H - 1.0, abs(w) * L + H + 1.0
        for _ in range(200):
            if f(lo) < 0.0:
                break
            lo = 2.0 * lo
        for _ in range(200):
            if f(hi) > 0.0:
                break
            hi = 2.0 * hi
        try:
            return float(brentq(f, lo, hi, xtol=1e-12 * (abs(w) * L + H)))
        except ValueError:
            return 0.5 * w * L

    def _grounded_guess(self, st: _Setup, F0: np.ndarray, w: float) -> np.ndarray:
        """Start unknowns (T_0, beta, q / L) for a start end on the seabed, from a free
        start-force guess and, where the line should rest on the seabed, the inextensible
        catenary with touchdown."""
        from scipy.optimize import brentq

        assert st.bed is not None and st.start.position is not None
        bed, line, far = st.bed, st.line, st.far
        L = line.length
        p0 = np.asarray(st.start.position, dtype=float)
        horiz = np.array([F0[0], F0[1], 0.0])
        if far.kind == "fixed":
            assert far.position is not None
            d = np.asarray(far.position, dtype=float) - p0
            horiz = np.array([d[0], d[1], 0.0])
        if np.linalg.norm(horiz) == 0.0:
            horiz = bed.upslope.copy()
        beta = bed.beta_of(horiz)
        suspended: float | None = None
        H = float(np.linalg.norm(F0[:2]))
        if far.kind == "fixed":
            assert far.position is not None
            d = np.asarray(far.position, dtype=float) - p0
            h = float(np.dot(d, bed.normal))
            X = float(np.linalg.norm(d - h * bed.normal))
            if h > 0.0 and X > 0.0:

                def gap(Ls: float) -> float:
                    a = (Ls * Ls - h * h) / (2.0 * h)
                    return (L - Ls) + a * math.asinh(Ls / a) - X

                # the largest suspended length with a sign change of the gap on a grid
                grid = np.linspace(h * (1.0 + 1e-6), L, 65) if h < L else np.zeros(0)
                gaps = [gap(float(g)) for g in grid]
                for g0, g1, v0, v1 in zip(
                    grid[-2::-1], grid[:0:-1], gaps[-2::-1], gaps[:0:-1], strict=True
                ):
                    if v0 * v1 <= 0.0:
                        suspended = float(brentq(gap, g0, g1, xtol=1e-9 * L))
                        a = (suspended**2 - h * h) / (2.0 * h)
                        H = a * w
                        break
        elif far.kind == "mooring":
            assert far.z is not None
            h = far.z - bed.z(p0[0], p0[1])
            if h > 0.0 and w > 0.0:
                suspended = math.sqrt(h * h + 2.0 * h * H / w)
        else:
            assert far.force is not None
            if w > 0.0 and far.force[2] > 0.0:
                suspended = float(far.force[2]) / w
        if suspended is not None and 0.0 < suspended < L and H > 0.0:
            return np.array([H / st.force_scale, beta, (L - suspended) / L])
        # lifted anchor: the start force as it is
        T = float(np.linalg.norm(F0))
        if T == 0.0:
            return np.array([1.0, beta, 0.0])
        t0 = F0 / T
        gamma = math.asin(max(-1.0, min(1.0, float(np.dot(t0, bed.normal)))))
        beta = bed.beta_of(t0 - np.dot(t0, bed.normal) * bed.normal) if gamma < 1.5 else beta
        return np.array([T / st.force_scale, beta, -max(gamma, 0.0)])
