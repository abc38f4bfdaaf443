"""Static method ``discrete``: the equilibrium of the shared lumped-mass line model.

The one line model the dynamic analyses use (:mod:`cablestudy.dynamics.model`) carries
what a cable's static solvers leave out: bending stiffness EI (tensioned-beam
curvature terms; a clamped end holds the static direction, so it is moment-free here
as a pinned one) and a compliant seabed (a contact spring of
``environment.seabed.stiffness`` with stick-slip friction). ``n_nodes - 1`` elements,
equal within each segment.

Newton starts from the semi-analytic cable solution (method ``catenary``, seabed
included) at the nodes and its tension at the element midpoints, laid nodes sunk by
their own penetration with their friction already carried. For T = EA strain it solves
for positions and element tensions together (:mod:`cablestudy.dynamics.mixed`): the
tension never comes from a difference of rounded positions, so EA from 1 N to 1e15 N
and lengths from 1 mm to 100 km are solved alike; a line search, and a continuation in
stiffness where Newton cannot start. Lines with a nonlinear axial law use Newton on
positions (their tension from the chords' stretch, to EA times the positions'
rounding).

Convergence is judged against the nodal loads, not EA: each free node's out-of-balance
force within ``tolerance`` times the largest nodal load (weight and buoyancy,
attachments, end forces, seabed, drag, bending), but not below the rounding of the
residual itself (an element's tension times the relative rounding of its direction).

Status 0 only after the node-level check (:func:`verify_nodes`): every free node in
balance, the support forces balancing the loads on the whole line, the held ends where
the problem puts them. A converged result that fails it keeps its numbers and gets
status 1 with "not verified:" and the residuals in its message.

Accuracy: lumped loads and straight elements converge as h^2 (a tensioned beam's
deflection against the exact beam-string solution: 5e-4 at 40 elements; a catenary
against the exact elastic catenary the same way; on the seabed the touchdown sits at a
node, with a larger constant).

Ends: ``fixed`` ends are held; a ``force`` end is a free node carrying its force; a
``mooring`` end (known horizontal force at a known height) is held at its height, where
its horizontal force is the one given (found by moving it from the cable solution's
position, :func:`_match_mooring_end`).

Outputs at the nodes: positions, tension (the mean of the adjacent element tensions;
at the ends the magnitude of the end force), the forces on the end supports (support reactions of
held ends, minus the applied force at a free end; a held end on the seabed hands the
seabed what presses it in), and the laid length (elements with both nodes on the
seabed spring).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..physics.contact import default_seabed_stiffness
from .base import (
    STATUS_NOT_CONVERGED,
    STATUS_NOT_VERIFIED,
    STATUS_OK,
    STATUS_TIME_LIMIT,
    StaticProblem,
    StaticResult,
)
from .line_state import DiscreteState
from .seabed import seabed_of


class DiscreteSolver:
    """The lumped-mass line model's static equilibrium (bending and compliant seabed)."""

    name = "discrete"

    def unsupported(self, problem: StaticProblem) -> list[str]:
        from .semi_analytic import SemiAnalyticSolver

        missing = list(SemiAnalyticSolver().unsupported(replace(problem, n_nodes=3)))
        if problem.is_installation:
            missing.append("steady cable installation (method 'shooting')")
        if problem.stretched_drag_diameter and problem.medium.has_current:
            missing.append("drag on the stretched diameter (method 'shooting')")
        return missing

    def solve(self, problem: StaticProblem, *, deadline: float | None = None) -> StaticResult:
        from ..dynamics.discrete_line import (
            DynamicExtras,
            discretise_nodes,
            uniform_nodes,
        )

        line, med = problem.line, problem.medium
        s = uniform_nodes(line, max(problem.n_nodes - 1, line.length.size))
        cable = replace(line, bending_stiffness=np.zeros_like(line.bending_stiffness))
        start, carried = _cable_start(problem, cable, s.size, deadline)
        if not start.success:
            return start
        x0 = np.stack([np.interp(s, start.s, start.position[:, k]) for k in range(3)], 1)
        # no clamp here: a clamped end holds the end's static direction (ends.*.bending),
        # the direction of this solution's own end element, and a clamp at its own
        # direction exerts no moment, so the static line is the pinned one. The dynamic
        # analyses clamp to its end elements (analyses.line_model.dynamic_extras) and
        # start at rest from it. (Clamping here to the cable solution's chord instead put
        # a moment no key asks for into the statics and a different direction into the
        # dynamics: 0.24 N, 2e-4, between the static and the time domain's end tension.)
        clamp = np.zeros((2, 3))
        free = [end.kind == "force" for end in (problem.end_a, problem.end_b)]
        end_force = np.zeros((2, 3))
        for k, end in enumerate((problem.end_a, problem.end_b)):
            if free[k]:
                end_force[k] = end.force
        stiffness = 0.0
        if med.depth is not None:
            stiffness = (
                problem.seabed_stiffness
                if problem.seabed_stiffness is not None
                else default_seabed_stiffness(line.weight)
            )
        extras = DynamicExtras(
            attachment_drag_area=line.attachment_drag_area,
            end_force=end_force,
            free_end=(free[0], free[1]),
            clamp_direction=clamp,
            seabed_stiffness=float(stiffness),
            friction_axial=med.friction,
            friction_lateral=med.friction
            if problem.friction_lateral is None
            else problem.friction_lateral,
        )
        disc = discretise_nodes(line, med, s, extras)
        result = _solve_discrete(problem, disc, x0.copy(), start, free, end_force, deadline)
        if carried is not None and result.status == STATUS_NOT_CONVERGED:
            # continuation on the lift, from the loads the start carries to the full ones
            base = discretise_nodes(carried, med, s, extras).force
            step, x = start, x0
            for k in range(1, LIFT_STEPS + 1):
                part = replace(disc, force=base + k / LIFT_STEPS * (disc.force - base))
                step = _solve_discrete(problem, part, x.copy(), step, free, end_force, deadline)
                if not step.success:
                    break
                x = step.position
            result = step if k == LIFT_STEPS else result
        args = (problem, disc, x0, start, free, end_force, deadline, result, carried)
        return _match_mooring_end(*args)


#: steps of the continuation on a buoy's lift where Newton cannot take it at once
LIFT_STEPS = 4


def _cable_start(problem: StaticProblem, cable, n_nodes: int, deadline):  # noqa: ANN001, ANN202
    """The cable solution (method ``catenary``, without EI) Newton starts from. A line
    that a buoy or a buoyant piece lifts off the seabed between two touchdowns has
    none (that method models one laid stretch and refuses it by name): then the same
    line without its lift (attachments pulling up lose their force, buoyant pieces
    weigh what they lift), or, where that lies slack on the seabed, the line hanging
    free through the seabed, its nodes below it put onto it; Newton raises the arch.
    Returns the start and the line whose loads it carries (None: ``cable``'s own)."""
    from .semi_analytic import SemiAnalyticSolver

    def solve(line, medium) -> StaticResult:  # noqa: ANN001
        p = replace(problem, line=line, medium=medium, n_nodes=n_nodes)
        return SemiAnalyticSolver().solve(p, deadline=deadline)

    med, up = problem.medium, cable.attachment_force[:, 2] > 0.0
    start = solve(cable, med)
    if start.success or start.status == STATUS_TIME_LIMIT or med.depth is None:
        return start, None
    if not (np.any(up) or np.any(cable.weight < 0.0)):  # nothing lifts it
        return start, None
    force = np.where(up[:, None], 0.0, cable.attachment_force)
    unlifted = replace(cable, weight=np.abs(cable.weight), attachment_force=force)
    trial, carried = solve(unlifted, med), unlifted
    if not trial.success and trial.status != STATUS_TIME_LIMIT:
        trial, carried = solve(cable, replace(med, depth=None)), None
        plane = seabed_of(med)
        below = np.minimum(plane.height_above(trial.position), 0.0)
        trial.position = trial.position - below[:, None] * plane.normal
    return (trial, carried) if trial.success or trial.status == STATUS_TIME_LIMIT else (start, None)


def _match_mooring_end(problem, disc, x0, start, free, end_force, deadline, result, carried):  # noqa: ANN001, ANN202
    """A mooring end is held where the cable solution puts it, where the discrete line's
    horizontal force differs from the given one by the discretisation error (O(h^2));
    the verification, which asks for the given force, then failed every such case. The
    held position is moved by Newton steps on the cable's horizontal end stiffness
    (finite differences of the cable solution) until the force is the one given."""
    from .base import EndCondition
    from .semi_analytic import SemiAnalyticSolver

    ends = (problem.end_a, problem.end_b)
    moored = [k for k, end in enumerate(ends) if end.kind == "mooring"]
    if not moored or result.status not in (STATUS_OK, STATUS_NOT_VERIFIED):
        return result
    k = moored[0]  # at most one: the other end is fixed
    node = 0 if k == 0 else -1
    target = -np.asarray(ends[k].force, dtype=float)[:2]  # the line's pull on the end
    scale = max(float(np.linalg.norm(target)), float(np.max(np.abs(result.tension))))
    # the start's line (carried: without its lift, whose cable solution exists)
    cable = carried or replace(problem.line, bending_stiffness=0.0 * problem.line.bending_stiffness)
    step = 1e-6 * problem.line.total_length
    stiffness = np.empty((2, 2))
    for i in range(2):
        moved = x0[node].copy()
        moved[i] += step
        fixed = EndCondition(kind="fixed", position=moved)
        probe = replace(problem, line=cable, n_nodes=3, **{"end_a" if k == 0 else "end_b": fixed})
        shot = SemiAnalyticSolver().solve(probe, deadline=deadline)
        if shot.status == STATUS_TIME_LIMIT:  # a deadline is a status, never "not verified"
            return StaticResult.failed(result.s, STATUS_TIME_LIMIT, shot.message)
        if not shot.success:
            return result
        stiffness[:, i] = ((shot.force_a if k == 0 else shot.force_b)[:2] - target) / step
    if not np.all(np.isfinite(stiffness)) or abs(np.linalg.det(stiffness)) <= 0.0:
        return result  # no horizontal stiffness to step with (the verification judges it)
    error = (result.force_a if k == 0 else result.force_b)[:2] - target
    held = x0[node, :2].copy()
    for _ in range(12):
        if float(np.linalg.norm(error)) <= problem.tolerance * scale:
            break
        # each try starts from the cable solution with the end moved (the seabed's
        # friction state then comes the same way every time)
        move = -np.linalg.solve(stiffness, error)
        held = held + move
        x = x0.copy()
        x[node, :2] = held
        trial = _solve_discrete(problem, disc, x, start, free, end_force, deadline)
        if trial.status == STATUS_TIME_LIMIT:
            # the time limit passed while matching the force: say so, rather than give
            # back the unmatched answer, which the verification then calls not verified
            # (random study seed 225: "not verified" after exactly the time limit)
            return trial
        if trial.status not in (STATUS_OK, STATUS_NOT_VERIFIED):
            break
        result = trial
        before, error = error, (result.force_a if k == 0 else result.force_b)[:2] - target
        # Broyden's update: the cable's stiffness is the discrete line's only to O(h^2)
        # and not at all where laid chain slides on a rough seabed (a leg with friction
        # 0.1 contracted by 0.28 a step and stopped 6x off the verification's allowance
        # after 8 steps); the steps measure the discrete line's own
        if float(move @ move) > 0.0:
            stiffness += np.outer(error - before - stiffness @ move, move) / float(move @ move)
    return result


def _solve_discrete(problem, disc, x0, start, free, end_force, deadline):  # noqa: ANN001, ANN202
    """Newton from the cable solution at the nodes, then the node-level verification."""
    from ..dynamics.assembly import Workspace, evaluate
    from ..dynamics.mixed import (
        MixedResult,
        geometry_rounding,
        is_finite_line,
        mixed_equilibrium,
        node_forces,
    )
    from ..dynamics.model import _seated_start, static_equilibrium

    s = disc.s
    t_nodes = np.interp(s, start.s, start.tension)
    t_elements = 0.5 * (t_nodes[:-1] + t_nodes[1:])
    # held ends exactly where the problem puts them (a mooring end: where the cable does)
    for k, (end, node) in enumerate(((problem.end_a, 0), (problem.end_b, -1))):
        if end.kind == "fixed" and not free[k]:
            x0[node] = np.asarray(end.position, dtype=float)
        elif end.kind == "mooring":
            # its height is given: exactly, not as the cable solution's start puts it
            # (to that solver's tolerance, 3.7e-7 m in a current, which the check of
            # the held ends, to the coordinates' rounding, refused: random seed 2031)
            x0[node, 2] = float(end.z)
    tol, floor, load = _force_tolerance(problem, disc, x0, t_elements)
    if is_finite_line(disc):
        work = Workspace(disc.n_elements)
        x1, anchor = x0, x0.copy()
        if disc.has_seabed:
            x1, anchor = _seated_start(disc, x1, work, t_elements)

        def mixed(x: np.ndarray, t: np.ndarray, anchor: np.ndarray) -> MixedResult:
            return mixed_equilibrium(
                disc,
                x,
                t,
                anchor,
                tol_force=tol,
                relative=problem.tolerance,
                max_iterations=max(problem.max_iterations, 200),
                deadline=deadline,
            )

        sol = mixed(x1, t_elements, anchor)
        x, t_el, its, ok = sol.position, sol.tension, sol.iterations, sol.converged
        anchor = sol.anchor
        res = sol.force_residual
        timed_out = sol.timed_out
        if not ok and not sol.timed_out:
            # Newton on positions alone, which the mixed form's start can miss (a beam
            # whose bending carries its weight between supports its own length apart);
            # its tension is a difference of rounded positions, so its tolerance takes
            # that rounding, and the node-level verification below still judges it
            rounding = float(np.max(disc.axial_stiffness)) * geometry_rounding(disc, x0)
            xp, its_p, res_p, ok_p, anchor_p = static_equilibrium(
                disc,
                x0,
                tolerance=max(tol, rounding),
                max_iterations=max(problem.max_iterations, 200),
                tension=t_elements,
            )
            its += its_p
            if ok_p:
                x, anchor, res, ok = xp, anchor_p, res_p, True
                t_el = evaluate(disc, x, np.zeros_like(x), anchor=anchor).tension.copy()
                # polished by the mixed form from there (its tension from equilibrium,
                # not from rounded chords), which now starts close enough to converge
                polish = mixed(x, t_el, anchor)
                its += polish.iterations
                if polish.converged:
                    x, t_el, anchor = polish.position, polish.tension, polish.anchor
                    res = polish.force_residual
                elif polish.timed_out:
                    # not the unpolished answer at the rounding tolerance: which answer
                    # comes back must not depend on the machine's load (a deadline is a
                    # status, never a fallback)
                    timed_out = True
                else:
                    tol, floor = max(tol, rounding), max(floor, rounding)
        if timed_out:
            return StaticResult.failed(
                s,
                STATUS_TIME_LIMIT,
                f"time limit reached in the discrete equilibrium after {its} Newton "
                f"iterations (largest nodal out-of-balance force {res:.3g} N)",
                iterations=its,
                residual=res,
            )
    else:
        # a nonlinear axial law: Newton on positions, the tension from the chords' stretch
        x, its, res, ok, anchor = static_equilibrium(
            disc,
            x0,
            tolerance=tol,
            max_iterations=max(problem.max_iterations, 200),
            tension=t_elements,
        )
        t_el = evaluate(disc, x, np.zeros_like(x), anchor=anchor).tension.copy()
        # its tension is a difference of rounded positions: its residual cannot fall
        # below EA times their rounding (the mixed form, for T = EA strain, has no such
        # floor)
        rounding = float(np.max(disc.axial_stiffness)) * geometry_rounding(disc, x0)
        tol, floor = max(tol, rounding), max(floor, rounding)
    if not ok:
        return StaticResult.failed(
            s,
            STATUS_NOT_CONVERGED,
            f"the discrete equilibrium did not converge ({its} Newton iterations, "
            f"largest nodal out-of-balance force {res:.3g} N against the tolerance "
            f"{tol:.3g} N)",
            iterations=its,
            residual=res,
        )
    F, work = node_forces(disc, x, t_el, anchor)
    tension = np.empty(s.size)
    tension[1:-1] = 0.5 * (t_el[:-1] + t_el[1:])
    forces = []
    # a held end lying on the seabed with the line laid beside it (an anchor on the
    # seabed): the seabed carries what presses the support into it (its node's own
    # lumped weight, and the pull of the first element, tilted by the laid nodes'
    # penetration w / k), as it carries the continuous laid line's weight there; left
    # on the support it is an error of O(h) and of O(T w / (k h))
    bed = np.zeros(3)
    for k, (node, beside) in enumerate(((0, 1), (-1, -2))):
        if free[k]:
            forces.append(-end_force[k])
            continue
        force = -F[node].copy()
        n_hat = disc.seabed_normal
        gap = float(x[node] @ n_hat - disc.seabed_offset)
        into = -float(force @ n_hat)  # the line pressing its support into the seabed
        # on the seabed: within the depth the laid line sinks into it
        sink = -(x @ n_hat - disc.seabed_offset)
        on_bed = gap <= max(float(np.max(sink[work.contact > 0.0], initial=0.0)), 0.0)
        if disc.has_seabed and on_bed and work.contact[beside] > 0.0 and into > 0.0:
            force += into * n_hat
            bed += into * n_hat
        forces.append(force)
    # the tension at the ends is the magnitude of the end force (DESIGN.md): the end
    # element's tension is that at its midpoint, O(h) from the end's (its half weight,
    # drag and the bending shear lumped on the end node lie between)
    tension[0], tension[-1] = np.linalg.norm(forces[0]), np.linalg.norm(forces[1])
    problems = verify_nodes(
        problem, disc, x, F, work, tol=tol, floor=floor, load=load, held_on_bed=bed
    )
    res = float(np.max(np.abs(F[~disc.held]), initial=0.0))
    on_bed = work.contact > 0.0
    laid = float(np.sum(np.diff(s)[on_bed[:-1] & on_bed[1:]]))
    result = StaticResult(
        s=s,
        position=x,
        tension=tension,
        force_a=forces[0],
        force_b=forces[1],
        laid_length=laid,
        iterations=its,
        residual=res,
        drag_iterations=start.drag_iterations,
        # the converged state, for the end stiffness of a system's line (line_state)
        state=DiscreteState(
            line=disc, position=x, tension=t_el, anchor=anchor, mixed=is_finite_line(disc)
        ),
    )
    if problems:
        # the numbers are kept for inspection; the status says they are not verified
        result.status = STATUS_NOT_CONVERGED
        result.message = "not verified: " + "; ".join(problems)
    return result


def _force_tolerance(
    problem: StaticProblem, disc, x0: np.ndarray, tension: np.ndarray
) -> tuple[float, float, float]:  # noqa: ANN001
    """(tolerance, rounding floor, load scale) [N] of a node's out-of-balance force.

    The load scale is the largest load on a node: weight and buoyancy, attachments and
    end forces (the model's constant nodal forces), and at the start the seabed's
    reaction, friction and drag (the model's other external forces). The
    tolerance is the study's relative ``tolerance`` of it, but never below what the
    residual's own evaluation rounds to: an element's tension times the relative
    rounding of its direction (64 ulp of the coordinates' reach over the shortest
    element), and a seabed node's contact stiffness times the rounding of its height.
    Neither depends on EA."""
    from ..dynamics.assembly import evaluate
    from ..dynamics.mixed import geometry_rounding, other_forces_line

    # the external loads only: bending, like the tension, is internal to the line
    external = replace(other_forces_line(disc), bending=np.zeros_like(disc.bending))
    others = evaluate(external, x0, np.zeros_like(x0), anchor=x0).F
    load = max(
        float(np.max(np.linalg.norm(disc.force, axis=1))),
        float(np.max(np.linalg.norm(others[~disc.held], axis=1), initial=0.0)),
    )
    tmax = float(np.max(tension))
    reach = float(np.max(np.abs(x0))) + float(np.sum(disc.rest_length))
    floor = geometry_rounding(disc, x0) * max(tmax, load)
    floor += 64.0 * np.finfo(float).eps * reach * float(np.max(disc.seabed_stiffness))
    if load == 0.0:
        load = tmax / disc.n_elements  # a weightless line between its supports
    # a line without load or tension (weightless, exactly at rest length) is in balance
    # only at zero force: the smallest positive number leaves 0 / tol defined
    tol = max(problem.tolerance * load, floor, np.finfo(float).tiny)
    return tol, floor, load


def verify_nodes(  # noqa: PLR0913
    problem: StaticProblem,
    disc,  # noqa: ANN001
    x: np.ndarray,
    F: np.ndarray,
    work,  # noqa: ANN001
    *,
    tol: float,
    floor: float,
    load: float,
    held_on_bed: np.ndarray | None = None,
) -> list[str]:
    """The checks a discrete equilibrium passes before status 0; what fails, in words.

    ``F`` [N] (n + 1, 3) are the out-of-balance nodal forces, recomputed from the
    positions ``x`` [m] and the element tensions (held nodes: their reactions). Checks:

    * each free node within ``tol`` [N];
    * the whole line: the forces on the supports equal the loads on the line (weight
      and buoyancy, attachments, free end forces, seabed reaction and friction, drag),
      within the free nodes' residuals allowed summed (``tol`` times their number);
    * the held ends where the problem puts them (to the rounding of the coordinates);
    * finite numbers everywhere.
    """
    out: list[str] = []
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(F))):
        return ["non-finite positions or forces"]
    free = ~np.asarray(disc.held, dtype=bool)
    node = float(np.max(np.abs(F[free]), initial=0.0))
    if node > tol:
        out.append(f"largest nodal out-of-balance force {node:.3g} N > tolerance {tol:.3g} N")
    # loads on the line: the model's forces without the elements' (bending sums to 0)
    loads = -(work.F.sum(axis=0))
    if held_on_bed is not None:  # the seabed's reaction under held ends on it
        loads = loads + held_on_bed
    supports = -F[~free].sum(axis=0) + (0.0 if held_on_bed is None else held_on_bed)
    whole = float(np.linalg.norm(supports - loads))
    allowed = max(int(free.sum()), 1) * tol + floor
    if whole > allowed:
        out.append(
            f"support forces {supports.tolist()} N do not balance the loads "
            f"{loads.tolist()} N (residual {whole:.3g} N > {allowed:.3g} N)"
        )
    reach = float(np.max(np.abs(x))) + float(np.sum(disc.rest_length))
    for end, node_i in ((problem.end_a, 0), (problem.end_b, -1)):
        if end.kind == "fixed":
            miss = float(np.linalg.norm(x[node_i] - np.asarray(end.position, dtype=float)))
        elif end.kind == "mooring":
            miss = abs(float(x[node_i, 2]) - float(end.z))
        else:
            continue
        if miss > 16.0 * np.finfo(float).eps * reach:
            out.append(f"end at s = {disc.s[node_i]:.6g} m is {miss:.3g} m from its position")
    return out
