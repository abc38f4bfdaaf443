"""Shooting solver (``analysis.static.method: shooting``): the 3D static line written in
tension, elevation and azimuth angles and Cartesian coordinates, integrated as an
initial-value problem from one end, with Newton's method on the unknown start values.

Formulation (vaz-patel seed, section 2 and eqs. 2, 4a-4c and A1 without the installation
terms V_po, V_0): along the unstretched arc length s of a segment of weight w [N/m] per
unstretched length and axial stiffness EA [N], the line force F = T t (T tension, t the
unit tangent towards increasing s) obeys dF/ds = -f, with f the external load per
unstretched length. Writing t through an elevation angle phi and an azimuth angle psi
about a reference frame (e1, e2, e3),

    t = cos(phi) cos(psi) e1 + cos(phi) sin(psi) e2 + sin(phi) e3,
    n = dt/dphi,   b = (dt/dpsi) / cos(phi),

the equilibrium equations resolved on (t, n, b) and the compatibility relations are

    dT/ds   = -f . t
    dphi/ds = -f . n / T
    dpsi/ds = -f . b / (T cos(phi))
    dr/ds   = (1 + T / EA) t                   (elastic stretch, Hooke's law)

with f = (0, 0, -w) + (1 + T / EA) f_drag(t, z). The drag per unit *stretched* length is
Morison's split into normal and tangential parts of the current velocity relative to the
tangent (dodaran-park seed eqs. 38-39, :func:`cablestudy.physics.hydro.drag_per_length`;
there, as here, the drag of an element is proportional to its stretched length and the
unstretched diameter; with ``stretched_drag_diameter`` (study key
``analysis.static.drag_diameter: stretched``) the diameter thins as d (1 + e)^(-1/2), as
in the vaz-patel seed, a change of relative size T / 2EA). The current is the
piecewise-linear profile in z of the study, so it may turn with depth; drag depends on
the local tangent and height and so sits inside the ODE (no outer iteration).

Azimuth singularity: psi is undefined where t is parallel to e3. The reference frame is
chosen afresh at the start of every integration leg with e1 = t and e3 perpendicular to t
(the binormal of the local load plane when it exists, so a plane catenary stays on phi =
0), and a leg ends by an event when |sin(phi)| reaches 0.95; the integration then
restarts at that point with a new frame. The angle form is therefore used everywhere and
|cos(phi)| >= 0.31 in every leg.

Legs also end at segment boundaries and at attachments (point forces, clump weights,
buoys: F(s+) = F(s-) - P for a force P applied to the line), where the angles are
recomputed from the force after the jump. The ODE is integrated with scipy's DOP853
(Dormand-Prince 8(5,3)), relative tolerance 1e-12 by default.

Shooting: the line is mirrored internally so that the integration starts at end A' and
runs to B'. The start end is, in this order of preference, a fixed end on the seabed
(see below), a `force` or `mooring` end (integration from its known force towards the
fixed end, the stable direction from low to high tension: the unknowns are its position,
or its horizontal position and vertical force), or a fixed end (unknowns: the three
components of the force there). Newton's method meets the three conditions at the other
end: its position (fixed), the force on the line there (force), or the horizontal force
and height (mooring). The Jacobian is by central differences, updated by Broyden's
formula between refreshes; the line search uses the 2-norm of the scaled residual.
Strong currents are reached by continuation in current speed from the still-water
solution, with a secant predictor. A free end (zero force) starts along its own load
(so a cable with a free end in a uniform current starts at Pode's critical angle).

Seabed (vaz-patel: the integration starts at the touchdown point): when the start end is
fixed on the seabed, the unknowns become the tension T_0 at the touchdown point, the
direction of the laid part in the seabed plane and the laid length. The laid part is
straight, in the seabed plane, and the line leaves the seabed tangentially at the
touchdown point; a negative third unknown instead lifts the line off at the anchor at an
angle, so grounded and lifted anchors are one smooth family of shots. Friction follows the
usual quasi-static convention: fully mobilised along the laid length towards the anchor,

    T(s) = max(0, T_0 - sum over the laid length beyond s of (mu w cos(a) + w e_z)),

(e_z the rise of the laid direction, a the seabed slope), so friction reduces the anchor
tension but never below zero and does not change the suspended shape. An end counts as
on the seabed within 1e-6 of the line length; contact elsewhere (a line sagging onto the
seabed between raised ends) is reported as a failure, never ignored.

Installation (vaz-patel seed, eqs. 3b-4c, ``analysis.static.installation``): in the
frame of a laying ship moving at the constant horizontal velocity V_0 with the cable
paid out from end B towards end A at speed V_po, the flow relative to the cable is the
current minus V_0 plus V_po along the tangent, and the cable flowing round its own
curvature replaces T by T - mu V_po^2 in the normal and binormal equations (mu: mass
per stretched length plus the normal added mass Cm rho pi d^2 / 4). The continuation
then ramps the frame flow and pay-out before the current.

Convergence: Newton stops when the scaled end residual (positions / line length,
forces / total weight and applied loads) is below max(tolerance, 100 rtol) and then
polishes for up to four more steps towards the integration floor.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np

from .base import (
    STATUS_NO_SOLUTION,
    STATUS_NOT_CONVERGED,
    STATUS_NUMERICAL,
    STATUS_OK,
    STATUS_TIME_LIMIT,
    EndCondition,
    StaticProblem,
    StaticResult,
)
from .contact_pin import arch_refusal
from .seabed import seabed_of
from .semi_analytic_shape import make_layout
from .shooting_ode import (
    _Env,
    _Integrator,
    _laid_profile,
    _laid_tension,
    _load,
    _make_line,
    _seabed,
    _Shot,
    _ShotFailed,
    _TimeUp,
    _unit,
)
from .shooting_start import _Setup, _Start, _StartGuesses

#: an end is on the seabed when within this fraction of the line length of it [-]
_GROUND_TOL = 1e-6
#: Newton iterations allowed per current-continuation step before it is shortened
_CONTINUATION_ITERATIONS = 15
#: Newton iterations allowed from each alternative starting point
_ALTERNATIVE_ITERATIONS = 30
#: finite-difference step of the Newton Jacobian, in the scaled unknowns [-]
_FD_STEP = 1e-7


# ----------------------------------------------------------------------------------
# the solver


class ShootingSolver(_StartGuesses):
    """Registry entry ``shooting``: angle-form ODE shooting (vaz-patel seed), see the
    module docstring.

    Parameters
    ----------
    rtol : float
        relative tolerance of the DOP853 integration [-]
    """

    name = "shooting"

    def __init__(self, *, rtol: float = 1e-12) -> None:
        self.rtol = rtol

    # -- contract ------------------------------------------------------------------
    def unsupported(self, problem: StaticProblem) -> list[str]:
        out = []
        kinds = (problem.end_a.kind, problem.end_b.kind)
        if "fixed" not in kinds:
            out.append(
                f"end kinds a={kinds[0]!r}, b={kinds[1]!r} (at least one end must be "
                "'fixed': a line held only by forces has no unique position)"
            )
        med = problem.medium
        if med.depth is not None:
            L = problem.line.total_length
            for label, end in (("a", problem.end_a), ("b", problem.end_b)):
                if end.kind == "fixed" and end.position is not None:
                    ground = float(med.seabed_z(end.position[0], end.position[1]))
                    if end.position[2] < ground - _GROUND_TOL * L:
                        out.append(
                            f"end {label} at z = {end.position[2]:.6g} m below the "
                            f"seabed (z = {ground:.6g} m there)"
                        )
                if (
                    end.kind == "mooring"
                    and end.z is not None
                    and end.z < -med.depth - (_GROUND_TOL * L)
                    and med.seabed_slope == 0.0
                ):
                    out.append(f"end {label} mooring height z = {end.z:.6g} m below the seabed")
        return out

    def solve(self, problem: StaticProblem, *, deadline: float | None = None) -> StaticResult:
        s_out = np.linspace(0.0, problem.line.total_length, problem.n_nodes)
        missing = self.unsupported(problem)
        if missing:
            return StaticResult.failed(s_out, STATUS_NO_SOLUTION, "; ".join(missing))
        try:
            result = self._solve(problem, s_out, deadline).check_finite()
        except _TimeUp:
            return StaticResult.failed(
                s_out, STATUS_TIME_LIMIT, "time limit reached in the shooting solver"
            )
        except Exception as exc:  # noqa: BLE001 - a numerical fault is data, not a crash
            return StaticResult.failed(
                s_out, STATUS_NUMERICAL, f"shooting solver: {type(exc).__name__}: {exc}"
            )
        plane, L = seabed_of(problem.medium), problem.line.total_length
        if result.laid_length > 0.0 and plane is not None:  # laid from the lower end
            low = plane.height_above(result.position[[0, -1]])
            laid = (0.0, result.laid_length) if low[0] <= low[1] else (L - result.laid_length, L)
            why = arch_refusal(make_layout(problem.line), plane.normal, laid, "shooting")
            if why:
                return StaticResult.failed(s_out, STATUS_NO_SOLUTION, why)
        return result

    # -- set-up ---------------------------------------------------------------------
    def _setup(self, problem: StaticProblem) -> _Setup:
        """Choose the start end: a fixed end on the seabed (touchdown integration), else
        a force or mooring end (integration from its known force towards the fixed end,
        the stable direction from low to high tension), else end A."""
        a, b = problem.end_a, problem.end_b
        med = problem.medium
        model = problem.line
        L = model.total_length
        bed = None
        if med.depth is not None:
            bed = _seabed(med.depth, med.seabed_slope, med.seabed_heading, med.friction)

        def on_ground(end: EndCondition, weight: float) -> bool:
            if bed is None or end.kind != "fixed" or end.position is None or weight <= 0.0:
                return False
            return abs(end.position[2] - bed.z(end.position[0], end.position[1])) <= (
                _GROUND_TOL * L
            )

        if on_ground(a, float(model.weight[0])):
            reverse, mode = False, "grounded"
        elif on_ground(b, float(model.weight[-1])):
            reverse, mode = True, "grounded"
        elif a.kind != "fixed":
            reverse, mode = False, a.kind
        elif b.kind != "fixed":
            reverse, mode = True, b.kind
        else:
            reverse, mode = False, "fixed"
        start, far = (b, a) if reverse else (a, b)
        line = _make_line(model, reverse)
        # installation: the flow seen in the laying frame is the current minus the
        # frame velocity; the cable moves along itself from B to A at the pay-out speed
        if med.current_velocity.size:
            cz, cu = med.current_z, med.current_velocity
        else:
            cz, cu = np.zeros(1), np.zeros((1, 3))
        env = _Env(
            density=med.density,
            current_z=tuple(float(z) for z in cz),
            current_u=tuple(tuple(float(c) for c in u) for u in cu),  # type: ignore[misc]
            frame=tuple(float(c) for c in problem.touchdown_velocity),  # type: ignore[arg-type]
            payout=-problem.payout_speed if reverse else problem.payout_speed,
            stretched=problem.stretched_drag_diameter,
        )
        scale = float(np.sum(np.abs(model.weight) * model.length))
        if model.attachment_force.size:
            scale += float(np.sum(np.linalg.norm(model.attachment_force, axis=1)))
        for end in (a, b):
            if end.force is not None:
                scale = max(scale, float(np.linalg.norm(end.force)))
        if scale <= 0.0:
            scale = 1e-6 * float(np.min(model.axial_stiffness))
        return _Setup(line, env, start, far, reverse, bed, mode, scale)

    # -- residual -------------------------------------------------------------------
    def _start_state(self, st: _Setup, env: _Env, u: np.ndarray) -> _Start:
        """The start of a shot from the scaled unknowns ``u``."""
        L = st.line.length
        if st.mode == "fixed":
            assert st.start.position is not None
            p0 = np.asarray(st.start.position, dtype=float)
            return _Start(0.0, u * st.force_scale, p0, None, 0.0, u * st.force_scale, p0)
        if st.mode == "grounded":
            assert st.bed is not None and st.start.position is not None
            p0 = np.asarray(st.start.position, dtype=float)
            T0 = float(u[0]) * st.force_scale
            if T0 <= 0.0:
                raise _ShotFailed("non-positive tension at the touchdown point")
            e = st.bed.direction(float(u[1]))
            q = float(u[2]) * L
            if q >= 0.0:
                if q >= L:
                    raise _ShotFailed("laid length would exceed the line length")
                _, T_anchor = _laid_tension(st.line, st.bed, e, q, T0)
                _, _, total = _laid_profile(st.line, st.bed, e, q, T0, np.zeros(0))
                return _Start(q, T0 * e, p0 + total * e, e, T0, max(0.0, T_anchor) * e, p0)
            gamma = -float(u[2])
            t0 = math.cos(gamma) * e + math.sin(gamma) * st.bed.normal
            return _Start(0.0, T0 * t0, p0, None, T0, T0 * t0, p0)
        assert st.start.force is not None
        R = np.asarray(st.start.force, dtype=float)
        if st.mode == "force":
            p0 = u * L
            F0 = -R
        else:  # mooring: unknown vertical force and horizontal position
            assert st.start.z is not None
            p0 = np.array([u[1] * L, u[2] * L, st.start.z])
            F0 = np.array([-R[0], -R[1], u[0] * st.force_scale])
        # attachments at the start end act on the line there
        F_plus = F0.copy()
        if st.line.att_s and st.line.att_s[0] == 0.0:
            F_plus = F_plus - np.asarray(st.line.att_force[0])
        if float(np.linalg.norm(F_plus)) > 1e-9 * st.force_scale:
            return _Start(0.0, F0, p0, None, 0.0, F0, p0)
        # a free end: the line leaves it along its load, F(s) = -f s for small s
        return self._free_end_start(st, env, p0, F0)

    def _free_end_start(self, st: _Setup, env: _Env, p0: np.ndarray, F0: np.ndarray) -> _Start:
        line = st.line
        k = line.segment_at(0.0)
        f = np.asarray(_load(env, line, k, (0.0, 0.0, 1.0), float(p0[2]), 0.0))
        if not np.any(f):
            raise _ShotFailed("a free end with no load on the line next to it")
        t0 = -f / np.linalg.norm(f)
        for _ in range(200):  # tangent along minus the load it produces (fixed point)
            f = np.asarray(_load(env, line, k, tuple(t0), float(p0[2]), 0.0))
            t_new = -f / np.linalg.norm(f)
            if np.linalg.norm(t_new - t0) < 1e-15:
                break
            t0 = _unit(0.5 * (t0 + t_new))
        delta = 1e-9 * line.length
        fmag = float(np.linalg.norm(f))
        return _Start(delta, fmag * delta * t0, p0 + delta * t0, None, 0.0, F0, p0)

    def _residual(
        self, st: _Setup, integ: _Integrator, u: np.ndarray, dense: bool = False
    ) -> tuple[np.ndarray, _Shot, _Start]:
        start = self._start_state(st, integ.env, u)
        shot = integ.run(start.s0, start.force, start.position, dense=dense)
        L = st.line.length
        far = st.far
        if far.kind == "fixed":
            assert far.position is not None
            r = (shot.position_end - far.position) / L
        elif far.kind == "force":
            assert far.force is not None
            r = (shot.force_end - far.force) / st.force_scale
        else:
            assert far.force is not None and far.z is not None
            r = np.array(
                [
                    (shot.force_end[0] - far.force[0]) / st.force_scale,
                    (shot.force_end[1] - far.force[1]) / st.force_scale,
                    (shot.position_end[2] - far.z) / L,
                ]
            )
        return r, shot, start

    # -- initial guesses --------------------------------------------------------------

    def _shot_args(
        self, st: _Setup, integ: _Integrator, u: np.ndarray
    ) -> tuple[float, np.ndarray, np.ndarray]:
        start = self._start_state(st, integ.env, u)
        return start.s0, start.force, start.position

    # -- Newton ---------------------------------------------------------------------
    def _newton(
        self,
        st: _Setup,
        integ: _Integrator,
        u0: np.ndarray,
        tol: float,
        max_iterations: int,
        deadline: float | None,
    ) -> tuple[np.ndarray, float, int, int, str]:
        """Damped Newton on the scaled end residual. The Jacobian is a central-difference
        one, refreshed when a step does not reduce the residual well and otherwise
        updated by Broyden's rank-one formula (each refresh costs six shots). Returns
        (u, residual norm, iterations, status, message)."""

        failures: list[str] = []

        def resid(u: np.ndarray) -> np.ndarray | None:
            try:
                return self._residual(st, integ, u)[0]
            except _ShotFailed as exc:
                failures.append(str(exc))
                return None

        u = np.array(u0, dtype=float)
        r = resid(u)
        if r is None:
            return u, math.inf, 0, STATUS_NOT_CONVERGED, f"the first shot failed: {failures[-1]}"
        norm = float(np.max(np.abs(r)))
        it = 0
        polish = 0
        J: np.ndarray | None = None
        fresh = False
        while True:
            if norm <= tol:
                # a few more steps towards the round-off floor of the integration
                polish += 1
                if polish > 4 or norm <= 10.0 * integ.rtol:
                    return u, norm, it, STATUS_OK, ""
            if it >= max_iterations:
                if norm <= tol:
                    return u, norm, it, STATUS_OK, ""
                return (
                    u,
                    norm,
                    it,
                    STATUS_NOT_CONVERGED,
                    (
                        f"shooting Newton did not converge in {max_iterations} iterations "
                        f"(residual {norm:.3g}, tolerance {tol:.3g})"
                    ),
                )
            if deadline is not None and time.monotonic() > deadline:
                raise _TimeUp
            it += 1
            if J is None:
                J = self._jacobian(resid, u, r)
                fresh = True
                if J is None:
                    return (
                        u,
                        norm,
                        it,
                        STATUS_NOT_CONVERGED,
                        ("shots next to the current iterate fail (tension vanishes)"),
                    )
            step = np.linalg.lstsq(J, -r, rcond=None)[0]
            if not np.all(np.isfinite(step)):
                return u, norm, it, STATUS_NUMERICAL, "non-finite Newton step"
            lam = 1.0
            accepted = False
            merit = float(np.linalg.norm(r))  # the step is a descent direction of |r|_2
            while lam >= 1.0 / 4096.0:
                un = u + lam * step
                rn = resid(un)
                if rn is not None:
                    nn = float(np.max(np.abs(rn)))
                    if float(np.linalg.norm(rn)) < (1.0 - 1e-4 * lam) * merit:
                        accepted = True
                        break
                lam *= 0.5
                if not fresh and lam < 0.2:
                    break  # a stale Jacobian: refresh it before searching further
            if not accepted:
                if not fresh:
                    J = None
                    continue
                if norm <= tol:
                    return u, norm, it, STATUS_OK, ""
                if norm < 1e-5 and integ.tighten():
                    # stalled near the solution: the integration error of an
                    # ill-conditioned shot is the floor; integrate more tightly
                    r = resid(u)
                    if r is None:
                        return u, norm, it, STATUS_NOT_CONVERGED, "a tighter shot failed"
                    norm = float(np.max(np.abs(r)))
                    J = None
                    continue
                return (
                    u,
                    norm,
                    it,
                    STATUS_NOT_CONVERGED,
                    (
                        f"shooting Newton line search failed (residual {norm:.3g}, "
                        f"tolerance {tol:.3g})"
                    ),
                )
            slow = float(np.linalg.norm(rn)) > 0.5 * merit
            if slow and fresh:
                if norm <= tol:
                    return un, nn, it, STATUS_OK, ""
                if nn < 1e-5:
                    integ.tighten()
                    rn = resid(un)
                    if rn is None:
                        return u, norm, it, STATUS_NOT_CONVERGED, "a tighter shot failed"
                    nn = float(np.max(np.abs(rn)))
            # Broyden's update of the Jacobian along the step taken; a slow step with
            # an updated Jacobian asks for a fresh one
            du = un - u
            J = J + np.outer(rn - r - J @ du, du) / float(du @ du)
            fresh = False
            if slow:
                J = None
            u, r, norm = un, rn, nn

    @staticmethod
    def _jacobian(
        resid: Callable[[np.ndarray], np.ndarray | None], u: np.ndarray, r: np.ndarray
    ) -> np.ndarray | None:
        """Central-difference Jacobian (one-sided where a shot fails): the shooting map
        of a drag-loaded line is strongly nonlinear, and central differences keep
        Newton quadratic down to the integration round-off."""
        J = np.empty((len(r), len(u)))
        for j in range(len(u)):
            h = _FD_STEP * max(1.0, abs(u[j]))
            du = np.zeros_like(u)
            du[j] = h
            rp, rm = resid(u + du), resid(u - du)
            if rp is not None and rm is not None:
                J[:, j] = (rp - rm) / (2.0 * h)
            elif rp is not None:
                J[:, j] = (rp - r) / h
            elif rm is not None:
                J[:, j] = (r - rm) / h
            else:
                return None
        return J

    # -- driver ---------------------------------------------------------------------
    def _solve(
        self, problem: StaticProblem, s_out: np.ndarray, deadline: float | None
    ) -> StaticResult:
        st = self._setup(problem)
        tol = max(problem.tolerance, 100.0 * self.rtol)
        u = self._guess(st)
        total_it = 0

        def newton(factor: float, u0: np.ndarray, cap: int) -> tuple[np.ndarray, float, int, str]:
            nonlocal total_it
            integ = _Integrator(
                st.line,
                st.env.scaled(factor),
                rtol=self.rtol,
                force_scale=st.force_scale,
                deadline=deadline,
            )
            u1, norm1, it, status1, msg1 = self._newton(st, integ, u0, tol, cap, deadline)
            total_it += it
            return u1, norm1, status1, msg1

        u0 = u
        u, norm, status, msg = newton(0.0, u0, problem.max_iterations)
        for alt in self._other_guesses(st, u0):
            if status == STATUS_OK or (st.mode == "grounded" and u[0] < 1e-4):
                break  # converged, or heading for a slack line (diagnosed below)
            u, norm, status, msg = newton(
                0.0, alt, min(problem.max_iterations, _ALTERNATIVE_ITERATIONS)
            )
        unloaded = not any(st.line.weight) and not st.line.att_force
        if status != STATUS_OK and st.env.has_current and unloaded:
            # no still-water shape (a slack weightless line): go straight to the full
            # current
            for start in [u0, *self._other_guesses(st, u0)]:
                u, norm, status, msg = newton(
                    1.0, start, min(problem.max_iterations, _ALTERNATIVE_ITERATIONS)
                )
                if status == STATUS_OK:
                    return self._finish(st, s_out, u, norm, total_it, deadline)
        if status != STATUS_OK and st.mode == "grounded" and u[0] < 1e-4:
            return StaticResult.failed(
                s_out,
                STATUS_NO_SOLUTION,
                "slack line: the touchdown tension tends to zero (the line is longer than a "
                "straight laid part and a vertical hanging part can take, so it would pile "
                "on the seabed; there is no taut static shape)",
                iterations=total_it,
                residual=norm,
            )
        if status != STATUS_OK and st.mode == "grounded" and st.far.kind == "force":
            assert st.far.force is not None
            lift = float(st.far.force[2]) + sum(max(0.0, p[2]) for p in st.line.att_force)
            if lift <= 0.0:
                return StaticResult.failed(
                    s_out,
                    STATUS_NO_SOLUTION,
                    f"the force at the free end (vertical component {st.far.force[2]:.6g} N) "
                    "and the attachments do not lift the line off the seabed: it would be "
                    "pulled into the seabed",
                    iterations=total_it,
                    residual=norm,
                )
        if status != STATUS_OK and st.mode == "grounded" and u[2] > 0.0:
            L = st.line.length
            near = [x for x in st.line.att_s if abs(x - u[2] * L) < 0.02 * L]
            if near:
                return StaticResult.failed(
                    s_out,
                    status,
                    f"the touchdown point runs into the attachment at s = {near[0]:.6g} m "
                    "(from the seabed end): a point load resting on the seabed at the "
                    "touchdown point, with a kink in the line there, is not modelled "
                    "here (method 'catenary' models it, the seabed carrying part of the "
                    f"load); {msg}",
                    iterations=total_it,
                    residual=norm,
                )
        if status != STATUS_OK:
            hint = (
                "; no equilibrium above the seabed may exist for these end conditions"
                if st.mode == "grounded"
                else ""
            )
            return StaticResult.failed(
                s_out, status, f"still water: {msg}{hint}", iterations=total_it, residual=norm
            )
        if st.env.has_current:
            # continuation in current speed from the still-water solution, with a secant
            # predictor from the last two converged steps
            done, step, n_steps = 0.0, 1.0, 0
            prev: tuple[float, np.ndarray] | None = None
            while done < 1.0:
                n_steps += 1
                trial = min(1.0, done + step)
                if n_steps > 80:
                    return StaticResult.failed(
                        s_out,
                        STATUS_NOT_CONVERGED,
                        f"current-speed continuation stalled at {done:.3g} of the current",
                        iterations=total_it,
                        residual=norm,
                    )
                u_pred = u
                if prev is not None:
                    u_pred = u + (trial - done) * (u - prev[1]) / (done - prev[0])
                # a continuation step that needs many iterations is retried shorter
                cap = (
                    problem.max_iterations
                    if step < 2e-3
                    else min(problem.max_iterations, _CONTINUATION_ITERATIONS)
                )
                u_try, norm_t, status_t, msg_t = newton(trial, u_pred, cap)
                if status_t == STATUS_OK:
                    prev = (done, u)
                    done, u, norm = trial, u_try, norm_t
                    step = min(1.0 - done, 2.0 * step) if done < 1.0 else step
                    continue
                step *= 0.25
                if step < 1e-3:
                    return StaticResult.failed(
                        s_out,
                        status_t,
                        f"current-speed continuation failed at {trial:.3g} of the current: {msg_t}",
                        iterations=total_it,
                        residual=norm_t,
                    )
        return self._finish(st, s_out, u, norm, total_it, deadline)

    def _finish(
        self,
        st: _Setup,
        s_out: np.ndarray,
        u: np.ndarray,
        norm: float,
        total_it: int,
        deadline: float | None,
    ) -> StaticResult:
        """The converged shot again, with dense output, sampled at the output nodes."""
        integ = _Integrator(
            st.line, st.env, rtol=self.rtol, force_scale=st.force_scale, deadline=deadline
        )
        try:
            r, shot, start = self._residual(st, integ, u, dense=True)
        except _ShotFailed as exc:
            return StaticResult.failed(
                s_out,
                STATUS_NUMERICAL,
                f"final shot failed: {exc}",
                iterations=total_it,
                residual=norm,
            )
        return self._result(st, s_out, shot, start, total_it, float(np.max(np.abs(r))))

    def _result(
        self,
        st: _Setup,
        s_out: np.ndarray,
        shot: _Shot,
        start: _Start,
        iterations: int,
        residual: float,
    ) -> StaticResult:
        L = st.line.length
        s_loc = (L - s_out) if st.reverse else s_out.copy()
        position = np.full((len(s_out), 3), np.nan)
        tension = np.full(len(s_out), np.nan)
        laid = 0.0
        before = s_loc < start.s0
        if start.laid is not None:
            assert st.bed is not None
            laid = start.s0
            dist, tens, _ = _laid_profile(st.line, st.bed, start.laid, start.s0, start.t_tdp, s_loc)
            position[before] = start.origin + dist[before, None] * start.laid
            tension[before] = tens[before]
        elif np.any(before):  # the short straight piece next to a free end
            frac = s_loc[before] / start.s0
            position[before] = start.origin + frac[:, None] * (start.position - start.origin)
            tension[before] = frac * float(np.linalg.norm(start.force))
        for piece in shot.pieces:
            inside = (s_loc >= piece.s0) & (s_loc <= piece.s1) & np.isnan(tension)
            if np.any(inside):
                y = piece.sol(s_loc[inside])
                tension[inside] = y[0]
                position[inside] = y[3:6].T
        # a node exactly at an attachment reports the tension on its B side (s+)
        for j in np.nonzero(np.isin(s_loc, st.line.att_s))[0]:
            for piece in shot.pieces:
                if (piece.s1 if st.reverse else piece.s0) == s_loc[j]:
                    tension[j] = float(piece.sol(np.array([s_loc[j]]))[0, 0])
                    break
        force_start = start.force_start
        force_far = -shot.force_end
        force_a, force_b = (force_far, force_start) if st.reverse else (force_start, force_far)
        # an attachment exactly at an end: the end tension is the magnitude of the end
        # force, its load included (DESIGN.md; the other methods, the verification)
        for j, force in ((0, force_a), (len(s_out) - 1, force_b)):
            if s_out[j] in (0.0, L) and np.isin(s_loc[j], st.line.att_s):
                tension[j] = float(np.linalg.norm(force))
        if st.bed is not None:
            ground = np.array([st.bed.z(x, y) for x, y in position[:, :2]])
            below = float(np.max(ground - position[:, 2]))
            if below > 1e-6 * L:
                return StaticResult.failed(
                    s_out,
                    STATUS_NO_SOLUTION,
                    f"the line passes {below:.4g} m below the seabed; the shooting solver "
                    "models seabed contact only from a fixed end on the seabed (within "
                    "1e-6 of the line length; touchdown integration)",
                    iterations=iterations,
                    residual=residual,
                )
        return StaticResult(
            s=s_out,
            position=position,
            tension=tension,
            force_a=force_a,
            force_b=force_b,
            laid_length=float(laid),
            status=STATUS_OK,
            message="",
            iterations=iterations,
            residual=residual,
        )
