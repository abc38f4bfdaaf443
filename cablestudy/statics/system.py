"""Statics of a mooring system: lines joined at points, points on bodies.

Pure: arrays and frozen dataclasses in, arrays out (SI units, no I/O).

A system has points (fixed; free, found by equilibrium under a constant net force such
as a clump's weight or a buoy's lift; or on a prescribed body at an offset in the body
frame), prescribed bodies (6-DOF pose: surge, sway, heave [m] and roll, pitch, yaw [rad],
the rotation being R = Rz(yaw) Ry(pitch) Rx(roll), exact at any angle) and lines, each a
:class:`~.base.StaticProblem` whose ends are two of the points.

Free points are found by Newton using each line's exact end-force stiffness from its
cable solution (:func:`line_end_stiffness`): for a free-hanging line the flexibility
F = d(r_B - r_A)/d(T_A) is the sum of the pieces' Jacobians (the matrix the end-force
Newton of :mod:`.semi_analytic` builds), and its inverse G gives the four 3x3 blocks
K_aa = K_bb = G, K_ab = K_ba = -G (K = minus the derivative of the force of the line on
the end's attachment with respect to the end's position). A line lying on the seabed
from an anchored end uses the Jacobian of the seabed-contact Newton (unknowns: the
touchdown tension in the seabed plane and the touchdown arc length).

Body force and stiffness: the points on a body move as r_i = X + R(theta) p_i. With
f_i the force of the lines on point i, u_i = R p_i, and A_i = d(R p_i)/d(theta) (3x3),
the body force is F = sum f_i, M = sum u_i x f_i, and its stiffness
K = -d(F, M)/d(X, theta), with the free points re-equilibrated (the Schur complement
K_c = K_BB - K_BP K_PP^-1 K_PB of the assembled point stiffness), is

    K = sum_ij [I; [u_i]x] K_c,ij [I, A_j] + sum_i [0, 0; 0, [f_i]x A_i]

where [v]x is the cross-product matrix; the last term is the moment arm's rotation
(d u_i / d theta x f_i), which makes the rotational block unsymmetric in general
(the moment of the lines' resultant turns with the body).
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np

from .base import (
    STATUS_NO_SOLUTION,
    STATUS_NOT_CONVERGED,
    STATUS_NUMERICAL,
    STATUS_OK,
    EndCondition,
    StaticProblem,
    StaticResult,
)
from .line_stiffness import laid_stiffness, line_end_stiffness, numeric_stiffness
from .seabed import seabed_of
from .semi_analytic_shape import laid_pulled
from .system_friction import point_friction, pulled_ends
from .system_model import (
    BODY,
    FIXED,
    FREE,
    MooringSystem,
    SystemFailure,
    SystemResult,
    on_seabed_note,
    point_drag,
    unpulled_note,
)
from .system_slack import slack_forces, slack_result
from .verify import verified


def _axis_rotations(angles: np.ndarray) -> tuple[np.ndarray, ...]:
    """Rx(roll), Ry(pitch), Rz(yaw) and their derivatives."""
    c1, s1 = math.cos(angles[0]), math.sin(angles[0])
    c2, s2 = math.cos(angles[1]), math.sin(angles[1])
    c3, s3 = math.cos(angles[2]), math.sin(angles[2])
    rx = np.array([[1.0, 0.0, 0.0], [0.0, c1, -s1], [0.0, s1, c1]])
    ry = np.array([[c2, 0.0, s2], [0.0, 1.0, 0.0], [-s2, 0.0, c2]])
    rz = np.array([[c3, -s3, 0.0], [s3, c3, 0.0], [0.0, 0.0, 1.0]])
    drx = np.array([[0.0, 0.0, 0.0], [0.0, -s1, -c1], [0.0, c1, -s1]])
    dry = np.array([[-s2, 0.0, c2], [0.0, 0.0, 0.0], [-c2, 0.0, -s2]])
    drz = np.array([[-s3, -c3, 0.0], [c3, -s3, 0.0], [0.0, 0.0, 0.0]])
    return rx, ry, rz, drx, dry, drz


def rotation(angles: np.ndarray) -> np.ndarray:
    """R = Rz(yaw) Ry(pitch) Rx(roll) for ``angles`` = (roll, pitch, yaw) [rad]."""
    rx, ry, rz, *_ = _axis_rotations(angles)
    return rz @ ry @ rx


def rotation_derivatives(angles: np.ndarray) -> np.ndarray:
    """dR/d(roll), dR/d(pitch), dR/d(yaw), shape (3, 3, 3) (first axis: the angle)."""
    rx, ry, rz, drx, dry, drz = _axis_rotations(angles)
    return np.stack((rz @ ry @ drx, rz @ dry @ rx, drz @ ry @ rx))


def _skew(v: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


# --------------------------------------------------------------------------- system


def point_positions(system: MooringSystem, free: np.ndarray) -> np.ndarray:
    """Positions [m] (n, 3) of all points, given the free points' positions (k, 3)."""
    pos = np.array(system.point_position, dtype=float, copy=True)
    kind = system.point_kind
    pos[kind == FREE] = free
    for i in np.flatnonzero(kind == BODY):
        b = int(system.point_body[i])
        pose = system.body_position[b]
        pos[i] = pose[:3] + rotation(pose[3:]) @ system.point_position[i]
    return pos


def _solve_lines(
    system: MooringSystem,
    pos: np.ndarray,
    solver: Any,
    deadline: float | None,
    verify: bool = True,
) -> tuple[list[StaticResult], np.ndarray, np.ndarray]:
    """Each line between the points at ``pos``: results, the net line force on each
    point (n, 3) [N] and the assembled stiffness (3n, 3n) [N/m]. ``verify=False``: the
    catenary kernels' answers unchecked (Newton iterates, re-solved verified at the
    solution), and a line slack on the seabed given its end forces and stiffness
    (:mod:`.system_slack`) instead of failing, so that a free point started there moves
    on to the taut equilibrium."""
    n = len(pos)
    force = np.zeros((n, 3))
    K = np.zeros((3 * n, 3 * n))
    results = []
    problems = [
        replace(
            ln.problem,
            end_a=EndCondition(kind="fixed", position=pos[ln.a].copy()),
            end_b=EndCondition(kind="fixed", position=pos[ln.b].copy()),
        )
        for ln in system.lines
    ]

    def solve_all(problems: list[StaticProblem], check: bool = verify) -> list[StaticResult]:
        if getattr(solver, "name", "") == "catenary":
            # every line of the system in one call of the batch kernels (verified as the
            # registry's solver verifies; the same numbers as one line at a time)
            from .batch import solve_batch

            return solve_batch(problems, deadline=deadline, verify=check)
        return [solver.solve(prob, deadline=deadline) for prob in problems]

    solved = solve_all(problems)
    plane = seabed_of(problems[0].medium)
    pulls = None if plane is None else pulled_ends(system, pos, plane)
    for idx, (ln, prob, res) in enumerate(zip(system.lines, problems, solved, strict=True)):
        res = res.check_finite()
        moving = [system.point_kind[ln.a] != FIXED, system.point_kind[ln.b] != FIXED]
        ends, mu, L = (ln.a, ln.b), prob.medium.friction, prob.line.total_length
        grounded = plane is not None and max(plane.height_above(pos[[ln.a, ln.b]])) <= 1e-6 * L
        laid = res.laid_length >= (1 - 1e-9) * L if res.status == STATUS_OK else mu
        k = slack = None
        if any(moving) and grounded and laid:
            # wholly on the seabed, straight: pulled at the end nearer a rising line's pull
            # (with friction, as MoorPy lays such a line, and held straight where it would
            # lie slack: a point held by friction stays where the single line has it)
            pulled = int(moving[1]) if pulls[idx] < 0 else int(pulls[idx])
            if mu and pulls[idx] < 0:
                raise SystemFailure(
                    STATUS_NO_SOLUTION,
                    f"line {ln.name} lies wholly on the seabed, with seabed friction {mu:g}, "
                    "pulled from neither end or both (no line rising from the seabed pulls "
                    "one end nearer than the other): which way friction acts along it is "
                    "not determined by the statics (friction: 0 solves it; or anchor one end)",
                )
            r = (prob.end_a.position, prob.end_b.position)
            got = laid_pulled(prob.line, r, plane, res.s, pulled, compress=bool(mu))
            if got is not None:
                res = got[0] if mu else res
                taut = float(np.max(res.tension)) > 0.0
                T = float(np.linalg.norm((res.force_a, res.force_b)[pulled]))
                k = laid_stiffness(r[1] - r[0], T if taut else 0.0, got[1])
                if mu and verify:  # the answer: the pushing stand-in has no force
                    if not taut:
                        res = replace(res, force_a=0 * res.force_a, force_b=0 * res.force_b)
                    res = verified(prob, res, method="catenary")
        elif res.status != STATUS_OK and not verify:
            # a Newton trial where the line lies slack on the seabed: its end forces are
            # still defined (.system_slack); never at the verified solution
            slack = slack_forces(prob)
            if slack is not None:
                res, k = slack_result(prob, *slack), slack[2]
        if res.status != STATUS_OK:
            raise SystemFailure(res.status, f"line {ln.name}: {res.message}")
        results.append(res)
        force[ln.a] += res.force_a
        force[ln.b] += res.force_b
        if not any(moving):
            continue
        if k is None:
            try:
                k = line_end_stiffness(prob, res)
            except SystemFailure:
                pass
        pairs = [(i, j) for i in range(2) for j in range(2) if moving[i] and moving[j]]
        if k is None or not all(np.all(np.isfinite(k[i, j])) for i, j in pairs):
            # a line lying on the seabed from an end that moves (friction as its own
            # catenary takes it, from the touchdown towards that end), or touching it
            # between two raised ends (with friction, which way it acts along the laid
            # stretch is not determined: a Newton trial's stand-in, never an answer): by
            # central differences of its solves
            raised = plane is not None and min(plane.height_above(pos[[ln.a, ln.b]])) > 1e-6 * L
            if mu and raised and verify:
                raise SystemFailure(
                    STATUS_NO_SOLUTION,
                    f"line {ln.name} lies on the seabed between two raised ends, with seabed "
                    f"friction {mu:g}: which way friction acts along its laid stretch is not "
                    "determined by the statics (friction: 0 solves it)",
                )
            # (the differences' solves unchecked, as the Newton's trials: not answers)
            k = numeric_stiffness(ln.name, prob, res, lambda p: solve_all(p, False), moving)
        for i, j in pairs:
            K[3 * ends[i] : 3 * ends[i] + 3, 3 * ends[j] : 3 * ends[j] + 3] += k[i, j]
    if plane is not None and plane.friction:
        force += point_friction(system, pos, results, plane, verify)
    drag = point_drag(system, pos)  # current drag on free points, if any
    if drag is not None:
        force += drag[0]
        K += drag[1]
    return results, force, K


_UNBALANCED = "free-point equilibrium: the verified lines"


def _dof_index(mask: np.ndarray) -> np.ndarray:
    return (3 * np.flatnonzero(mask)[:, None] + np.arange(3)).ravel()


def solve_system(
    system: MooringSystem,
    solver: Any,
    *,
    deadline: float | None = None,
    compiled: bool = True,
    extra_poses: np.ndarray | None = None,
) -> SystemResult:
    """Equilibrium of the free points (Newton with the lines' exact stiffness and a
    line search on the system's energy along the step, :func:`_line_search`), then the
    bodies' force and stiffness; free bodies by :func:`solve_free_bodies`.
    ``solver`` solves one line with both ends fixed (a registered static solver). A
    numerical failure is returned as status, message and NaN. With ``compiled`` (the
    default) the compiled system Newton takes what it can (:mod:`.system_fast`);
    ``extra_poses`` (K, m, 6), prescribed bodies only: the compiled path solves the
    system at those body poses too, in the same call (``SystemResult.extra``; the
    system's own solution is the same numbers as without)."""
    n, m = len(system.point_names), len(system.body_names)
    free_mask = system.point_kind == FREE
    # the compiled system Newton first where it takes the system (statics.system_fast);
    # what it leaves comes here, with its reason in ``fallback``
    fallback: list[str] = []

    def solve(sys: MooringSystem, trial: bool = False) -> SystemResult:
        if compiled and getattr(solver, "name", "") == "catenary" and not trial:
            from .system_fast import solve_fast

            fast, why = solve_fast(sys, prescribed=True, extra_poses=extra_poses)
            if fast is not None:
                return fast
            fallback.append(why)
        try:
            return _solve(sys, solver, deadline, free_mask, verified=not trial)
        except SystemFailure as exc:
            # lines sampled at their ends may hang through the seabed unseen: the verified
            # ones do not balance at the Newton's solution; again at the study's nodes
            if not exc.message.startswith(_UNBALANCED):
                raise
            return _solve(sys, solver, deadline, free_mask, verified=not trial, sampled=False)

    try:
        if system.body_free.size and np.any(system.body_free):
            extra_poses = None  # the extra poses are of prescribed bodies
            res = solve_free_bodies(system, solve)
        else:
            res = solve(system)
            res.body_position = np.array(system.body_position, dtype=float)
        res.fallback = fallback[0] if fallback else ""
        return res
    except SystemFailure as exc:
        return SystemResult(
            lines=[],
            point_position=np.full((n, 3), np.nan),
            body_force=np.full((m, 6), np.nan),
            body_stiffness=np.full((m, 6, 6), np.nan),
            status=exc.status,
            message=exc.message,
            fallback=fallback[0] if fallback else "",
        )
    except np.linalg.LinAlgError as exc:
        return SystemResult(
            lines=[],
            point_position=np.full((n, 3), np.nan),
            body_force=np.full((m, 6), np.nan),
            body_stiffness=np.full((m, 6, 6), np.nan),
            status=STATUS_NUMERICAL,
            message=f"singular stiffness of the free points ({exc})",
            fallback=fallback[0] if fallback else "",
        )


def _solve(
    system: MooringSystem,
    solver: Any,
    deadline: float | None,
    free_mask: np.ndarray,
    *,
    verified: bool = True,
    sampled: bool = True,
) -> SystemResult:
    """The free points' Newton (see :func:`solve_system`); ``sampled``: the cable
    solver's lines at their ends only in its trials (still water). ``verified=False``: a trial
    of the free-body Newton where a line would be slack, the lines at the solution as
    the Newton left them (unverified, slack lines by their stand-ins,
    :mod:`.system_slack`); never an answer (:func:`solve_free_bodies` solves its
    solution again verified)."""
    x = np.array(system.point_position[free_mask], dtype=float)
    pf = system.point_force[free_mask]
    P = _dof_index(free_mask)
    pos = point_positions(system, x)
    # the Newton trials use the solver without its final verification (the registry's
    # wrapper, cablestudy.statics.VerifiedSolver); the lines at the solution are verified
    raw = getattr(solver, "solver", solver)
    final = system
    # and, for the cable solver in still water, sample each line at its ends only: its
    # shape is wanted at the solution (the discrete model's nodes are its mesh, and the
    # check of a line in a current sums its drag over the samples: both kept)
    still = not any(ln.problem.medium.has_current for ln in system.lines)
    if getattr(solver, "name", "") == "catenary" and still and sampled:
        system = replace(
            system,
            lines=tuple(
                replace(ln, problem=replace(ln.problem, n_nodes=min(ln.problem.n_nodes, 3)))
                for ln in system.lines
            ),
        )
    plane = seabed_of(system.lines[0].problem.medium)
    # free points resting on the seabed: held on its plane (their motion along it the
    # unknowns, the seabed's reaction across it; released where the net force lifts them)
    contact = np.zeros(len(x), dtype=bool)
    if plane is not None and len(x):
        height = plane.height_above(x)
        contact = height <= 0.0
        x[contact] -= height[contact, None] * plane.normal
        pos = point_positions(system, x)
    try:
        results, force, K = _solve_lines(system, pos, raw, deadline, verify=False)
    except SystemFailure as exc:
        # a start that puts free points on the seabed: name them
        raise SystemFailure(
            exc.status, exc.message + on_seabed_note(system, free_mask, contact, plane)
        ) from None
    it = 0
    res = 0.0
    if P.size:
        cap = 0.5 * min(
            ln.problem.line.total_length
            for ln in system.lines
            if free_mask[ln.a] or free_mask[ln.b]
        )
        scale = max(
            max((float(np.max(r.tension)) for r in results), default=0.0),
            float(np.max(np.abs(pf))),
            1e-300,
        )

        pressed = np.zeros(int(free_mask.sum()), dtype=bool)

        def residual(force: np.ndarray) -> np.ndarray:
            return force[free_mask] + pf

        def size(R: np.ndarray) -> float:  # the net force but the seabed's reaction
            if contact.any():
                R = R - np.where(contact[:, None], (R @ plane.normal)[:, None] * plane.normal, 0.0)
            return float(np.max(np.abs(R))) / scale

        R = residual(force)
        res = size(R)
        polished = 0
        while res > system.tolerance or polished == 0:
            if res <= system.tolerance:
                polished = 1
            if it >= system.max_iterations:
                idle = unpulled_note(system, free_mask, contact, results, scale)
                raise SystemFailure(
                    STATUS_NO_SOLUTION if idle else STATUS_NOT_CONVERGED,
                    f"free-point equilibrium did not converge in {system.max_iterations} "
                    f"iterations (net force / largest tension {res:.3g}, tolerance "
                    f"{system.tolerance:.3g}){on_seabed_note(system, free_mask, pressed, plane)}"
                    f"{idle}",
                )
            it += 1
            T = _plane_dofs(plane, contact)
            Kpp, r = K[np.ix_(P, P)], R.ravel()
            if T is not None:  # points on the seabed move along it
                Kpp, r = T.T @ Kpp @ T, T.T @ r
            try:
                step = np.linalg.solve(Kpp, r)
                phi0 = float(r @ step)
            except np.linalg.LinAlgError:  # e.g. a point held across only by slack lines
                phi0 = math.nan
            if not phi0 > 0.0:  # stiffness not positive definite here: go downhill
                step = r / max(float(np.max(np.diag(Kpp))), 1e-300)
                phi0 = float(r @ step)
            step = (step if T is None else T @ step).reshape(-1, 3)
            longest = float(np.max(np.linalg.norm(step, axis=1)))
            if longest > cap:
                step *= cap / longest
                phi0 *= cap / longest
            if plane is not None:
                # a free point the step would take below the seabed slides along it
                # instead (a projected step; the lines cannot end below the seabed)
                below = plane.height_above(x + step) - np.where(contact, 0.0, 1e-6 * cap)
                pressed = (below < 0.0) & ~contact
                if np.any(pressed):
                    slid = step - np.where(pressed, below, 0.0)[:, None] * plane.normal
                    if float(R.ravel() @ slid.ravel()) > 0.0:  # still downhill
                        step, phi0 = slid, float(R.ravel() @ slid.ravel())
            found = _line_search(
                lambda lam, x=x, step=step: _trial(
                    system, x + lam * step, raw, deadline, residual, step
                ),
                phi0,
                done=res <= system.tolerance,
            )
            if found is None:
                if res <= system.tolerance:
                    break  # round-off: the polishing step cannot reduce it further
                idle = unpulled_note(system, free_mask, contact, results, scale)
                raise SystemFailure(
                    STATUS_NO_SOLUTION if idle else STATUS_NOT_CONVERGED,
                    f"line search failed in the free-point equilibrium (net force / "
                    f"largest tension {res:.3g}){on_seabed_note(system, free_mask, pressed, plane)}"
                    f"{idle}",
                )
            lam, out = found
            xn = x + lam * step
            Rn = residual(out[1])
            assert out is not None
            x, (results, force, K), R = xn, out, Rn
            if plane is not None:
                # a point the step slid onto the seabed rests on it; one the net force
                # lifts off leaves it
                height = plane.height_above(x)
                landed = ~contact & (height <= 2e-6 * cap)
                if landed.any():
                    contact |= landed
                    x[landed] -= height[landed, None] * plane.normal
                    results, force, K = _solve_lines(
                        system, point_positions(system, x), raw, deadline, verify=False
                    )
                    R = residual(force)
                lifted = contact & (R @ plane.normal > system.tolerance * scale)
                if lifted.any():
                    contact &= ~lifted
                    polished = 0
            res = size(R)
            if polished:
                break
        pos = point_positions(system, x)
    T = _plane_dofs(plane, contact)
    reaction = None
    if verified:
        results, force, K = _solve_lines(final, pos, solver, deadline)
    if verified and P.size:
        # the Newton's lines were unverified (the kernels' answers, for speed): the
        # verified lines at the solution must hold the points in equilibrium as well
        net = force[free_mask] + pf
        bar = max(100.0 * system.tolerance, 1e-10)
        if contact.any():
            # the seabed pushes a resting point up (never pulls it down)
            push = np.where(contact, net @ plane.normal, 0.0)
            if np.any(push > bar * scale):
                raise SystemFailure(
                    STATUS_NOT_CONVERGED,
                    f"{_UNBALANCED} lift a point the Newton left resting on the seabed",
                )
            reaction = np.zeros((len(system.point_names), 3))
            reaction[free_mask] = -push[:, None] * plane.normal + 0.0  # no signed zeros
            net = net + reaction[free_mask]
            if plane.friction:  # and its friction, in the lines' force (system_friction)
                reaction += point_friction(final, pos, results, plane)
        final_res = float(np.max(np.abs(net))) / scale
        if not final_res <= bar:
            raise SystemFailure(
                STATUS_NOT_CONVERGED,
                f"{_UNBALANCED} at the Newton's solution leave "
                f"a net force of {final_res:.3g} of the largest tension (tolerance "
                f"{system.tolerance:.3g})",
            )
    body_force, body_stiffness = _bodies(final, pos, force, K, free_mask, T)
    return SystemResult(
        lines=results,
        point_position=pos,
        body_force=body_force,
        body_stiffness=body_stiffness,
        iterations=it,
        residual=res,
        seabed_force=reaction,
        resting=tuple(str(n) for n in np.asarray(system.point_names)[free_mask][contact]),
    )


def _plane_dofs(plane: Any, contact: np.ndarray) -> np.ndarray | None:
    """(3 k, d) the free points' motions from their unknowns: three for a point off the
    seabed, two along the seabed's plane (its basis) for one resting on it; None when
    none rests on it."""
    if plane is None or not contact.any():
        return None
    T = np.zeros((3 * len(contact), 3 * len(contact) - int(contact.sum())))
    basis = np.stack(plane.basis, axis=1)
    j = 0
    for i, on in enumerate(contact):
        n = 2 if on else 3
        T[3 * i : 3 * i + 3, j : j + n] = basis if on else np.eye(3)
        j += n
    return T


def _trial(
    system: MooringSystem,
    x: np.ndarray,
    solver: Any,
    deadline: float | None,
    residual: Any,
    step: np.ndarray,
) -> tuple[Any, float] | None:
    """The lines with the free points at ``x``, and phi = R(x) . step (None if a line
    cannot be solved there)."""
    try:
        out = _solve_lines(system, point_positions(system, x), solver, deadline, verify=False)
    except SystemFailure:
        return None
    return out, float(residual(out[1]).ravel() @ step.ravel())


def _line_search(trial: Any, phi0: float, *, done: bool) -> tuple[float, Any] | None:
    """A step length along the Newton direction s by the energy of the system: the lines
    and the points' loads are conservative, so the potential energy along the step has
    the slope -phi(lam) = -R(x + lam s) . s, negative at 0 (K positive definite). The
    step is accepted where that slope has fallen to half its size (strong Wolfe
    curvature condition, c2 = 0.5), or at lam = 1 while the energy still falls; else
    its zero (the energy's minimum along s) is bracketed and found by regula falsi. A
    straight step lets a point swinging on a taut line (stiff along it, soft across it)
    move along its arc by several steps, where a residual-norm search stalls."""
    lo, f_lo, out_lo = 0.0, phi0, None
    hi, f_hi = math.nan, math.nan
    lam = 1.0
    for _ in range(40):
        t = trial(lam)
        if t is None:  # a line could not be solved there: shorter
            if out_lo is not None:
                # the energy falls all the way to lo (phi > 0 there) and the lines
                # cannot be solved a little further on (a free point at the seabed,
                # a line end below it): take the step to lo, the next Newton step
                # starts from there
                return lo, out_lo
            hi, f_hi = lam, math.nan
            lam = 0.5 * (lo + lam)
            continue
        out, f = t
        if abs(f) <= 0.5 * phi0 or (f > 0.0 and lam == 1.0) or (done and lam == 1.0):
            return lam, out
        if f > 0.0:
            lo, f_lo, out_lo = lam, f, out
        else:
            hi, f_hi = lam, f
        if math.isnan(f_hi):
            lam = 0.5 * (lo + hi)
        else:
            guess = lo + (hi - lo) * f_lo / (f_lo - f_hi)
            width = hi - lo
            lam = min(max(guess, lo + 0.1 * width), hi - 0.1 * width)
        if hi - lo <= 1e-12:
            break
    return None


def _bodies(
    system: MooringSystem,
    pos: np.ndarray,
    force: np.ndarray,
    K: np.ndarray,
    free_mask: np.ndarray,
    T: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """The lines' force on each body and its stiffness, the free points re-equilibrated
    (those resting on the seabed along it: ``T``, :func:`_plane_dofs`)."""
    m = len(system.body_names)
    body_force = np.zeros((m, 6))
    body_stiffness = np.zeros((m, 6, 6))
    on_body = system.point_kind == BODY
    if not np.any(on_body):
        return body_force, body_stiffness
    B, P = _dof_index(on_body), _dof_index(free_mask)
    Kc = K[np.ix_(B, B)]
    if P.size and T is None:
        Kc = Kc - K[np.ix_(B, P)] @ np.linalg.solve(K[np.ix_(P, P)], K[np.ix_(P, B)])
    elif P.size:
        Kbp, Kpb = K[np.ix_(B, P)] @ T, T.T @ K[np.ix_(P, B)]
        Kc = Kc - Kbp @ np.linalg.solve(T.T @ K[np.ix_(P, P)] @ T, Kpb)
    idx = np.flatnonzero(on_body)
    for b in range(m):
        pose = system.body_position[b]
        dR = rotation_derivatives(pose[3:])
        mine = [k for k, i in enumerate(idx) if system.point_body[i] == b]
        lever, trans = {}, {}
        for k in mine:
            i = idx[k]
            u = pos[i] - pose[:3]
            A = np.stack([dR[a] @ system.point_position[i] for a in range(3)], axis=1)
            f = force[i]
            body_force[b, :3] += f
            body_force[b, 3:] += np.cross(u, f)
            lever[k] = np.vstack((np.eye(3), _skew(u)))  # (6, 3)
            trans[k] = np.hstack((np.eye(3), A))  # (3, 6)
            body_stiffness[b, 3:, 3:] += _skew(f) @ A
        for k in mine:
            for j in mine:
                block = Kc[3 * k : 3 * k + 3, 3 * j : 3 * j + 3]
                body_stiffness[b] += lever[k] @ block @ trans[j]
    return body_force, body_stiffness


# ----------------------------------------------------------------------------
# Free bodies of a mooring system: each body's 6-DOF position found by equilibrium of
# its lines, its weight, its buoyancy and a constant applied force.
#
# Pure (arrays in, arrays out). The lines' part of the Jacobian is the body stiffness of
# :mod:`.system` (free points re-equilibrated, exact); the loads add the turning of their
# moment arms: a force W at the body-frame point p has the moment u x W about the
# reference point, u = R p, whose derivative by the angles is A x W with A = d(R p)/d
# theta, so the stiffness gains [W]x A in its rotational block. Bodies joined by lines
# are coupled only through the outer iteration (the Jacobian is block diagonal per
# body), which still converges, linearly where the coupling is strong.


def body_loads(system: MooringSystem, body: int, pose: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Weight, buoyancy, the waterplane's heave force and the applied force on ``body`` at
    ``pose``: the load [N, N m] (6,) about the reference point and its stiffness -d load /
    d pose (6, 6)."""
    R = rotation(pose[3:])
    dR = rotation_derivatives(pose[3:])
    load = np.zeros(6)
    K = np.zeros((6, 6))
    forces = (
        (np.array([0.0, 0.0, -system.body_weight[body]]), system.body_cog[body]),
        (np.array([0.0, 0.0, system.body_buoyancy[body]]), system.body_cob[body]),
    )
    for f, p in forces:
        load[:3] += f
        load[3:] += np.cross(R @ p, f)
        A = np.stack([dR[k] @ p for k in range(3)], axis=1)
        K[3:, 3:] += _skew(f) @ A
    load[:3] += system.body_applied[body]
    if system.body_waterplane.size:
        load[2] -= system.body_waterplane[body] * pose[2]
        K[2, 2] += system.body_waterplane[body]
    return load, K


def solve_free_bodies(system: MooringSystem, solve: Any) -> SystemResult:
    """Newton on the free bodies' positions; ``solve(system)`` solves the system with the
    bodies where ``system`` puts them (free points re-equilibrated) or raises
    :class:`SystemFailure`. The step length comes from the energy along the step (the
    loads are conservative): see :func:`_line_search`."""
    free = np.flatnonzero(system.body_free)
    free_points = system.point_kind == FREE
    state: dict[str, Any] = {"guess": np.array(system.point_position, dtype=float)}
    state["verified"] = True
    longest_line = min(ln.problem.line.total_length for ln in system.lines)
    force_scale = max(
        float(np.max(system.body_weight[free], initial=0.0)),
        float(np.max(system.body_buoyancy[free], initial=0.0)),
        float(np.max(np.abs(system.body_applied[free]), initial=0.0)),
        1e-300,
    )
    arm = max(
        float(np.max(np.abs(system.point_position[system.point_kind == BODY]), initial=0.0)),
        float(np.max(np.abs(system.body_cog[free]), initial=0.0)),
        float(np.max(np.abs(system.body_cob[free]), initial=0.0)),
        1.0,
    )

    def evaluate(q: np.ndarray, trial: bool = True) -> tuple[SystemResult, np.ndarray, np.ndarray]:
        poses = np.array(system.body_position, dtype=float)
        poses[free] = q
        placed = replace(system, body_position=poses, point_position=state["guess"])
        try:
            res = solve(placed)
            state["verified"] = True
        except SystemFailure:
            if not trial:
                raise
            # a line slack at this pose (.system_slack): the Newton's unverified lines
            res = solve(placed, trial=True)
            state["verified"] = False
        R = np.zeros((len(free), 6))
        K = np.zeros((6 * len(free), 6 * len(free)))
        for k, b in enumerate(free):
            load, k_load = body_loads(system, b, poses[b])
            R[k] = res.body_force[b] + load
            K[6 * k : 6 * k + 6, 6 * k : 6 * k + 6] = res.body_stiffness[b] + k_load
        res.body_position = poses
        return res, R, K

    def size(R: np.ndarray) -> float:
        scale = max(force_scale, max((float(np.max(r.tension)) for r in res.lines), default=0.0))
        return max(
            float(np.max(np.abs(R[:, :3]))) / scale, float(np.max(np.abs(R[:, 3:]))) / (scale * arm)
        )

    q = np.array(system.body_position[free], dtype=float)
    res, R, K = evaluate(q)
    err = size(R)
    it, polished = 0, 0
    while err > system.tolerance or polished == 0:
        if err <= system.tolerance:
            polished = 1
        if it >= system.max_iterations:
            raise SystemFailure(
                STATUS_NOT_CONVERGED,
                f"free-body equilibrium did not converge in {system.max_iterations} "
                f"iterations (net load / largest tension {err:.3g})",
            )
        it += 1
        try:
            step = np.linalg.solve(K, R.ravel()).reshape(-1, 6)
        except np.linalg.LinAlgError:
            raise SystemFailure(
                STATUS_NUMERICAL,
                "the free bodies' stiffness (lines, weight and buoyancy) is singular: a "
                "body free to move without restoring force (a body on a single point, or "
                "with no rotational restraint)",
            ) from None
        phi0 = float(R.ravel() @ step.ravel())
        if not phi0 > 0.0:  # not positive definite here: go downhill
            step = R / max(float(np.max(np.abs(np.diag(K)))), 1e-300)
            phi0 = float(R.ravel() @ step.ravel())
        shrink = min(
            1.0,
            0.5 * longest_line / max(float(np.max(np.abs(step[:, :3]))), 1e-300),
            0.3 / max(float(np.max(np.abs(step[:, 3:]))), 1e-300),
        )
        step *= shrink
        phi0 *= shrink

        def trial(lam: float, q: np.ndarray = q, step: np.ndarray = step) -> Any:
            try:
                out = evaluate(q + lam * step)
            except SystemFailure:
                return None
            return out, float(out[1].ravel() @ step.ravel())

        found = _line_search(trial, phi0, done=err <= system.tolerance)
        if found is None:
            if err <= system.tolerance:
                break
            raise SystemFailure(
                STATUS_NOT_CONVERGED,
                f"line search failed in the free-body equilibrium (net load / largest "
                f"tension {err:.3g})",
            )
        lam, (res, R, K) = found
        q = q + lam * step
        state["guess"] = np.where(free_points[:, None], res.point_position, state["guess"])
        err = size(R)
        if polished:
            break
    if not state["verified"]:
        # the last iterate was a trial (a line slack there): solved again, verified, at
        # the solution, where it must balance as the free points' solution does
        res, R, _ = evaluate(q, trial=False)
        err = size(R)
        if not err <= max(100.0 * system.tolerance, 1e-10):
            raise SystemFailure(
                STATUS_NOT_CONVERGED,
                f"free-body equilibrium: the verified lines at the Newton's solution leave "
                f"a net load of {err:.3g} of the largest tension (tolerance "
                f"{system.tolerance:.3g})",
            )
    res.iterations = it
    res.residual = err if math.isfinite(err) else res.residual
    return res
