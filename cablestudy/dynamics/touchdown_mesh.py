"""The frequency domain's nodes on a line lying on the seabed: the uniform nodes plus
a node at each touchdown point, so that the held laid nodes end where the line leaves
the seabed, as in the modal mesh (:func:`cablestudy.analyses.modal.solve_modal`).

Shared by the single line (:mod:`cablestudy.analyses.frequency`) and each line of a
system (:func:`cablestudy.dynamics.system_frequency.system_linear`), so that a system
of one line linearises about the same nodes as the one-line study, bit for bit.
Without the touchdown node the laid node before it holds a partly suspended element
down: the catenary mooring's quasi-static stiffness was 20 % low at 20 elements
(tests/validation/test_frequency_seabed.py).

Pure: a static result in, a static result out.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np

from ..statics.base import EndCondition, Medium, StaticProblem, StaticResult
from ..statics.system_model import MooringSystem, SystemResult
from .modal import snap_to_samples, subset_static

#: static samples per element from which a touchdown node is taken (it lies within
#: half a sample of the touchdown point)
TOUCHDOWN_SAMPLES = 16


def touchdown_mesh(fine: StaticResult, medium: Medium, elements: int) -> StaticResult:
    """Of ``fine``, the static solution at ``elements * TOUCHDOWN_SAMPLES + 1`` equally
    spaced samples, the samples nearest to ``elements + 1`` equally spaced nodes plus
    the last laid sample from each end that lies on the seabed (``medium``'s) while the
    line does not lie there whole."""
    length = float(fine.s[-1])
    ground = medium.seabed_z(fine.position[:, 0], fine.position[:, 1])
    on_bed = np.abs(fine.position[:, 2] - ground) <= 1e-6 * max(length, 1.0)
    touchdown = []
    if on_bed[0] and not on_bed.all():
        touchdown.append(fine.s[int(np.argmin(on_bed)) - 1])  # last laid sample from A
    if on_bed[-1] and not on_bed.all():
        touchdown.append(fine.s[len(on_bed) - int(np.argmin(on_bed[::-1]))])  # from B
    targets = np.union1d(np.linspace(0.0, length, elements + 1), touchdown)
    return subset_static(fine, snap_to_samples(fine.s, targets))


def touchdown_states(
    system: MooringSystem,
    static: SystemResult,
    states: list[StaticResult],
    nodes: int,
    solve: Callable[[StaticProblem], StaticResult] | None,
    solve_many: Callable[[list[StaticProblem]], list[StaticResult]] | None,
) -> None:
    """For :func:`~.system_frequency.system_linear`: each line lying on the seabed in
    the static state takes, in ``states``, a node at each touchdown point besides its
    ``nodes`` equally spaced ones, as the single line's frequency domain does
    (:func:`touchdown_mesh` of the line solved again, between the points where the
    statics put them, at ``TOUCHDOWN_SAMPLES`` samples an element, by ``solve_many``
    or else ``solve``); a line whose fine solution fails keeps its equally spaced
    nodes, as the single line does."""
    laid = [i for i, st in enumerate(static.lines) if st.laid_length > 0.0]
    if not laid:
        return
    problems = [
        replace(
            system.lines[i].problem,
            end_a=EndCondition(kind="fixed", position=static.point_position[system.lines[i].a]),
            end_b=EndCondition(kind="fixed", position=static.point_position[system.lines[i].b]),
            n_nodes=(nodes - 1) * TOUCHDOWN_SAMPLES + 1,
        )
        for i in laid
    ]
    if solve_many is not None:
        solved = solve_many(problems)
    else:
        assert solve is not None
        solved = [solve(problem) for problem in problems]
    for i, problem, fine in zip(laid, problems, solved, strict=True):
        if fine.success:
            states[i] = touchdown_mesh(fine, problem.medium, nodes - 1)
