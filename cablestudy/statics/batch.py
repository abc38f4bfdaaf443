"""Many static problems of method ``catenary`` at once (:func:`solve_batch`): those the
compiled kernels take (:mod:`.batch_kernels`: lines hanging free stacked and solved
together, lines anchored on the seabed by the contact kernel, those of one seabed plane
stacked too), the others and any case a kernel does not settle one by one by
:class:`.semi_analytic.SemiAnalyticSolver`, so the answer never depends on which path a
case took beyond round-off. :func:`solve_compiled_many` is the kernels' part alone: the
lines of a mooring system re-solved at another number of nodes (the system frequency
domain's model, :func:`cablestudy.dynamics.system_frequency.system_linear`) take one
call per group instead of one per line.

Pure: problems in, results out.
"""

from __future__ import annotations

import numpy as np

from .base import StaticProblem, StaticResult
from .batch_kernels import (
    NOT_SETTLED,
    _contact_call,
    _contact_inputs,
    _contact_result,
    _solve_group,
    batchable,
    contact_eligible,
    solve_contact_arrays,
)
from .semi_analytic import SemiAnalyticSolver
from .semi_analytic_shape import make_layout
from .verify import verified


def contact_many(problems: list[StaticProblem]) -> list[StaticResult | None]:
    """:func:`~.batch_kernels._contact_one` of each problem (seabed-contact eligible),
    those of the same pieces, nodes and seabed plane in one call of the kernels."""
    inputs = [_contact_inputs(p) for p in problems]
    groups: dict[tuple, list[int]] = {}
    for i, x in enumerate(inputs):
        pl = x["plane"]
        key = (
            x["arrays"][0].shape[1],
            x["s"].shape[1],
            pl.depth,
            pl.slope,
            pl.heading,
            pl.friction,
        )
        groups.setdefault(key, []).append(i)
    results: list[StaticResult | None] = [None] * len(problems)
    for idx in groups.values():
        calls = [_contact_call(inputs[i]) for i in idx]
        args = [
            calls[0][k] if k == 7 else np.concatenate([c[k] for c in calls])
            for k in range(len(calls[0]))
        ]
        out = solve_contact_arrays(*args)
        for j, i in enumerate(idx):
            results[i] = _contact_result(inputs[i], out, j)
    return results


def _kernels(
    problems: list[StaticProblem], *, contact: bool = True, verify: bool = True
) -> tuple[list[StaticResult | None], dict[int, str], set[int]]:
    """The kernels' answers (None where a kernel does not take a problem or does not
    settle it), why the batch kernel left a case it tried, and the cases a kernel tried.
    Batchable problems with equal piece and node counts are solved together; lines
    anchored on the seabed (``contact``) by the contact kernel, those of one plane
    together, their answers verified (``verify``) as the batch kernel verifies its own."""
    results: list[StaticResult | None] = [None] * len(problems)
    groups: dict[tuple[int, int], list[int]] = {}
    layouts: dict = {}
    seabed = []
    for i, prob in enumerate(problems):
        if contact and contact_eligible(prob):  # never batchable: anchored on the seabed
            seabed.append(i)
            continue
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
    if seabed:
        for i, res in zip(seabed, contact_many([problems[i] for i in seabed]), strict=True):
            if res is not None and verify:  # status 0 means verified: else the general
                res = verified(problems[i], res, method="catenary")  # solver
            results[i] = res
    tried = {i for members in groups.values() for i in members} | set(seabed)
    return results, why, tried


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
    :data:`ON_SEABED`). ``verify=False`` takes the kernels' settled answers without
    :mod:`.verify`'s checks: only for intermediate iterates whose answer is re-solved
    verified (the system Newton's trials, :func:`.system._solve`)."""
    solver = SemiAnalyticSolver()
    results, why, tried = _kernels(problems, contact=contact, verify=verify)
    out = []
    for i, prob in enumerate(problems):
        res = results[i]
        if res is None or not res.success:
            res = verified(
                prob,
                solver.solve(prob, deadline=deadline, compiled=False).check_finite(),
                method=solver.name,
            )
            if general is not None:
                general.append(i)
            if i in tried:
                res.fallback = why.get(i, NOT_SETTLED)
        out.append(res)
    return out
