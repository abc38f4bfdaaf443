"""Many static problems of method ``catenary`` at once (:func:`solve_batch`): those the
compiled kernels take (:mod:`.batch_kernels`: lines hanging free stacked and solved
together, lines anchored on the seabed by the contact kernel, those of one seabed plane
stacked too, lines hanging free in a current by the drag iteration run per case inside
the batch, :mod:`.batch_drag`), the others and any case a kernel does not settle one by one by
:class:`.semi_analytic.SemiAnalyticSolver`, so the answer never depends on which path a
case took beyond round-off. :func:`solve_compiled_many` is the kernels' part alone: the
lines of a mooring system re-solved at another number of nodes (the system frequency
domain's model, :func:`cablestudy.dynamics.system_frequency.system_linear`) take one
call per group instead of one per line.

Pure: problems in, results out.
"""

from __future__ import annotations

from .base import StaticProblem, StaticResult
from .batch_kernels import NOT_SETTLED, _kernels
from .semi_analytic import SemiAnalyticSolver
from .verify import verified


def solve_compiled_many(problems: list[StaticProblem]) -> list[StaticResult | None]:
    """:func:`~.batch_kernels.solve_compiled` of each problem, the batchable ones of the
    same pieces and nodes stacked into one kernel call, the seabed-contact ones of the
    same plane into another: the same answers, verified the same way. None where
    :func:`~.batch_kernels.solve_compiled` gives None (the general solver's then)."""
    results, _, _ = _kernels(problems)
    return [res if res is not None and res.success else None for res in results]


def solve_batch(
    problems: list[StaticProblem],
    *,
    deadline: float | None = None,
    contact: bool = True,
    general: list[int] | None = None,
    verify: bool = True,
) -> list[StaticResult]:
    """Solve ``problems`` (any mix); batchable ones with equal piece and node counts are
    solved together, lines anchored on the seabed (``contact``) by the compiled contact
    kernel, the others (and any case a kernel does not settle) one by one by the general
    solver; the indices of those are appended to ``general`` if given. A case a kernel
    tried and handed on says why in its ``fallback`` (:data:`NOT_SETTLED`,
    :data:`ON_SEABED`). ``verify=False`` takes the kernels' settled answers, and the
    general solver's, without :mod:`.verify`'s checks: only for intermediate iterates
    whose answer is re-solved verified (the system Newton's trials,
    :func:`.system._solve`)."""
    solver = SemiAnalyticSolver()
    results, why, tried = _kernels(problems, contact=contact, verify=verify, deadline=deadline)
    out = []
    for i, prob in enumerate(problems):
        res = results[i]
        if res is None or not res.success:
            res = solver.solve(prob, deadline=deadline, compiled=False).check_finite()
            if verify:  # an iterate's answer is re-solved and verified where it is kept
                res = verified(prob, res, method=solver.name)
            if general is not None:
                general.append(i)
            if i in tried:
                res.fallback = why.get(i, NOT_SETTLED)
        out.append(res)
    return out
