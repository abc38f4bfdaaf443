"""Many static problems of method ``catenary`` at once (:func:`solve_batch`): those the
compiled kernels take (:mod:`.batch_kernels`: lines hanging free stacked and solved
together, lines anchored on the seabed by the contact kernel), the others and any case a
kernel does not settle one by one by :class:`.semi_analytic.SemiAnalyticSolver`, so the
answer never depends on which path a case took beyond round-off.
"""

from __future__ import annotations

from .base import StaticProblem, StaticResult
from .batch_kernels import NOT_SETTLED, _contact_one, _solve_group, batchable, contact_eligible
from .semi_analytic import SemiAnalyticSolver
from .semi_analytic_shape import make_layout
from .verify import verified


def solve_batch(
    problems: list[StaticProblem],
    *,
    deadline: float | None = None,
    solver: SemiAnalyticSolver | None = None,
    contact: bool = True,
    general: list[int] | None = None,
    verify: bool = True,
) -> list[StaticResult]:
    """Solve ``problems`` (any mix); batchable ones with equal piece and node counts are
    solved together, lines anchored on the seabed (``contact``) by the compiled contact
    kernel, the others (and any case a kernel does not settle) one by one by the general
    solver; the indices of those are appended to ``general`` if given. A case a kernel
    tried and handed on says why in its ``fallback`` (:data:`NOT_SETTLED`,
    :data:`ON_SEABED`). ``verify=False`` takes the kernels' settled answers without
    :mod:`.verify`'s checks: only for intermediate iterates whose answer is re-solved
    verified (the system Newton's trials, :func:`.system._solve`)."""
    solver = solver or SemiAnalyticSolver()
    results: list[StaticResult | None] = [None] * len(problems)
    groups: dict[tuple[int, int], list[int]] = {}
    layouts = {}
    for i, prob in enumerate(problems):
        if not batchable(prob):
            continue
        line = prob.line
        if line.length.size == 1 and line.attachment_s.size == 0:
            P = 1
        else:
            layouts[i] = make_layout(line)
            P = len(layouts[i].ell)
        groups.setdefault((P, prob.n_nodes), []).append(i)
    why: dict[int, str] = {}
    for (P, n_nodes), members in groups.items():
        left: dict[int, str] = {}
        for i, res in zip(
            members,
            _solve_group(
                [problems[i] for i in members],
                P,
                n_nodes,
                [layouts.get(i) for i in members],
                why=left,
                verify=verify,
            ),
            strict=True,
        ):
            results[i] = res
        why.update({members[j]: reason for j, reason in left.items()})
    batched = {i for members in groups.values() for i in members}
    out = []
    for i, prob in enumerate(problems):
        res = results[i]
        tried_contact = False
        if res is None and contact and contact_eligible(prob):
            res = _contact_one(prob)
            if res is not None and verify:  # status 0 means verified: else the general
                res = verified(prob, res, method=solver.name)  # solver
            tried_contact = True
        if res is None or not res.success:
            res = verified(
                prob,
                solver.solve(prob, deadline=deadline, compiled=False).check_finite(),
                method=solver.name,
            )
            if general is not None:
                general.append(i)
            if i in batched:
                res.fallback = why.get(i, NOT_SETTLED)
            elif tried_contact:
                res.fallback = NOT_SETTLED
        out.append(res)
    return out
