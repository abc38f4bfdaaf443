"""Static method ``discrete``: the equilibrium of the shared lumped-mass line model.

The one line model the dynamic analyses use (:mod:`cablestudy.dynamics.model`) carries
what a cable's static solvers leave out: bending stiffness EI (tensioned-beam
curvature terms, pinned or clamped ends) and a compliant seabed (a contact spring of
``environment.seabed.stiffness`` with stick-slip friction). Its static equilibrium is
found by Newton on the nodal forces (the time-domain Jacobian without the inertia
terms), started from the semi-analytic cable solution (method ``catenary``) at the
same nodes: ``n_nodes - 1`` elements, equal within each segment.

Accuracy: lumped loads and straight elements converge as h^2 (a tensioned beam's
deflection against the exact beam-string solution: 5e-4 at 40 elements; a catenary
against the exact elastic catenary the same way). The equilibrium is reached to the
``tolerance`` relative to the largest static tension, in force per node.

Ends: ``fixed`` ends are held; a ``force`` end is a free node carrying its force; a
``mooring`` end (known horizontal force at a known height) is held where the cable
solution puts it, so its horizontal force is the cable's to the discretisation error.

Outputs at the nodes: positions, tension (the mean of the adjacent element tensions,
the end element's at the ends), the forces on the end supports (support reactions of
held ends, minus the applied force at a free end), and the laid length (elements
with both nodes on the seabed spring).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from .base import STATUS_NOT_CONVERGED, StaticProblem, StaticResult


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
        from ..dynamics.model import (
            DynamicExtras,
            default_seabed_stiffness,
            discretise_nodes,
            evaluate,
            static_equilibrium,
            uniform_nodes,
        )
        from .semi_analytic import SemiAnalyticSolver

        line, med = problem.line, problem.medium
        s = uniform_nodes(line, max(problem.n_nodes - 1, line.length.size))
        cable = replace(line, bending_stiffness=np.zeros_like(line.bending_stiffness))
        start = SemiAnalyticSolver().solve(
            replace(problem, line=cable, n_nodes=s.size), deadline=deadline
        )
        if not start.success:
            return start
        x0 = np.stack([np.interp(s, start.s, start.position[:, k]) for k in range(3)], 1)
        clamp = np.zeros((2, 3))
        for k, how in enumerate(problem.bending_ends):
            if how == "clamped":
                d = x0[1] - x0[0] if k == 0 else x0[-1] - x0[-2]
                clamp[k] = d / np.linalg.norm(d)
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
                else default_seabed_stiffness(line)
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
        scale = max(float(np.max(start.tension)), float(np.max(np.abs(disc.force))))
        # below the rounding of an element tension EA (l / l0 - 1) no Newton step helps:
        # an ulp of the node coordinates times EA over the shortest element, times 256
        # for the few ulp a converged Newton wanders and the node's several elements
        reach = float(np.max(np.abs(x0))) + float(np.sum(disc.rest_length))
        rounding = (
            256.0 * np.finfo(float).eps * float(np.max(disc.axial_stiffness)) * reach
        ) / float(np.min(disc.rest_length))
        t_nodes = np.interp(s, start.s, start.tension)
        # the residual summed over the nodes is what the end forces carry: ask each node
        # for the tolerance shared out, so the supports balance the weight to it. Newton
        # starts with the chords stretched by the cable's tension (a stiff line's chord
        # error times EA is a large spurious force), else from the cable's nodes
        tol = max(problem.tolerance * scale / s.size, rounding)
        its_all = 0
        for tension in (0.5 * (t_nodes[:-1] + t_nodes[1:]), None):
            x, its, res, ok, anchor = static_equilibrium(
                disc,
                x0,
                tolerance=tol,
                max_iterations=max(problem.max_iterations, 200),
                tension=tension,
            )
            its_all += its
            if ok:
                break
        its = its_all
        work = evaluate(disc, x, np.zeros_like(x), anchor=anchor)
        tension = np.empty(s.size)
        tension[1:-1] = 0.5 * (work.tension[:-1] + work.tension[1:])
        tension[0], tension[-1] = work.tension[0], work.tension[-1]
        forces = []
        for k, node in ((0, 0), (1, -1)):
            forces.append(-end_force[k] if free[k] else -work.F[node].copy())
        on_bed = work.contact > 0.0
        laid = float(np.sum(np.diff(s)[on_bed[:-1] & on_bed[1:]]))
        if not ok:
            return StaticResult.failed(
                s,
                STATUS_NOT_CONVERGED,
                f"the discrete equilibrium did not converge ({its} Newton iterations, "
                f"largest nodal force {res:.3g} N)",
                iterations=its,
                residual=res,
            )
        return StaticResult(
            s=s,
            position=x,
            tension=tension,
            force_a=forces[0],
            force_b=forces[1],
            laid_length=laid,
            iterations=its,
            residual=res,
            drag_iterations=start.drag_iterations,
        )
