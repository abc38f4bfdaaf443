"""The modal analysis of a case about its static shape: the mesh (uniform, or graded by
transverse-wave travel time), the eigenproblem of :mod:`cablestudy.dynamics.modal`, and
its outputs.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..statics import (
    StaticResult,
)
from ..study.cases import Case
from ..study.problem import static_problem
from .line_model import dynamic_extras
from .static import static_at

if TYPE_CHECKING:  # imported where used: `cablestudy validate` needs none of them
    from ..dynamics.modal import ModalResult


#: most static sample points asked for to place the nodes of a graded modal mesh
MODAL_MAX_SAMPLES = 200_001


def solve_modal(case: Case, static: StaticResult, deadline: float | None) -> ModalResult:
    """Modal analysis about the static shape on ``analysis.modal.n_elements`` elements.

    ``uniform`` mesh: the static shape at n_elements + 1 equally spaced points (reused
    when the static output has exactly those). ``graded`` mesh: node positions of equal
    transverse-wave travel time are computed from the static tension, and the static
    solution is sampled uniformly fine enough (at least 8 samples in the shortest
    element, an integer number per uniform element) to take the nearest sample for
    each node, so every node lies exactly on the static solution."""
    from ..dynamics.modal import (
        ModalProblem,
        ModalResult,
        graded_arc_lengths,
        modal_analysis,
        snap_to_samples,
        subset_static,
        transverse_mass,
    )

    settings = case.study.analysis.modal
    assert settings is not None
    problem = static_problem(case.study)
    n_el = settings.n_elements
    if settings.mesh == "uniform" or not static.success:
        n_nodes = n_el + 1
        mesh_static = static if n_nodes == len(static.s) else static_at(case, n_nodes, deadline)
    else:
        mass = transverse_mass(
            problem.line, problem.medium, static.s, include_added_mass=settings.include_added_mass
        )
        tension = static.tension
        joints = problem.line.segment_ends
        med = problem.medium
        if med.friction > 0.0 and static.laid_length > 0.0 and med.depth is not None:
            # the laid part sticks (dynamics.modal): it needs no elements of its own, so
            # grade as if it were as stiff as the most tensioned point, and put a node
            # exactly at the touchdown point, where the pinned part begins
            ground = med.seabed_z(static.position[:, 0], static.position[:, 1])
            on_bed = np.abs(static.position[:, 2] - ground) <= 1e-6 * max(float(static.s[-1]), 1.0)
            tension = np.where(on_bed, float(np.max(static.tension)), static.tension)
            total_length = float(static.s[-1])
            touchdown = [static.laid_length] if on_bed[0] else []
            touchdown += [total_length - static.laid_length] if on_bed[-1] else []
            joints = np.union1d(joints, np.clip(touchdown, 0.0, total_length))
        targets = graded_arc_lengths(static.s, tension, mass, n_el, joints=joints)
        shortest = float(np.min(np.diff(targets)))
        total = float(static.s[-1] - static.s[0])
        per_element = max(8, math.ceil(8.0 * total / (shortest * n_el)))
        per_element = min(per_element, max(1, (MODAL_MAX_SAMPLES - 1) // n_el))
        fine = static_at(case, n_el * per_element + 1, deadline)
        mesh_static = (
            subset_static(fine, snap_to_samples(fine.s, targets)) if fine.success else fine
        )
    if static.success and not mesh_static.success:
        # the case's statics hold (static_status 0): the re-solve at the modal mesh's
        # points failed, and that is the modal analysis's own failure, with the solver's
        # status (1 not converged, 3 time limit, 11 not verified, ...), never 5 ("the
        # statics failed"), which the case's static_status would contradict
        return ModalResult.failed(
            mesh_static.s,
            settings.modes,
            mesh_static.status,
            f"the static shape re-solved at {len(mesh_static.s)} points to place the "
            f"{settings.mesh} modal mesh's nodes failed: {mesh_static.message}",
        )
    return modal_analysis(
        ModalProblem(
            line=problem.line,
            medium=problem.medium,
            end_a=problem.end_a,
            end_b=problem.end_b,
            static=mesh_static,
            n_modes=settings.modes,
            include_added_mass=settings.include_added_mass,
            include_bending=settings.include_bending,
            extras=dynamic_extras(case.study, mesh_static.position),
        ),
        deadline=deadline,
    )


def modal_outputs(res: ModalResult, s: np.ndarray, *, mode_shapes: bool) -> dict[str, np.ndarray]:
    out = {
        "natural_frequency": res.frequency,
        "modal_dof": np.asarray(res.n_dof),
    }
    if mode_shapes:
        out["mode_shape"] = res.shape_at(s)
    return out
