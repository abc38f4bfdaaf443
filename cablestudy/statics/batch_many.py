"""Several still-water problems through the compiled kernels of :mod:`.batch_kernels`
at once, with the answers of one call per problem (the kernels and the verification go
case by case): the lines of a mooring system re-solved at another number of nodes (the
system frequency domain's model, :func:`cablestudy.dynamics.system_frequency.
system_linear`) take one call per group instead of one per line.

Pure: problems in, results out.
"""

from __future__ import annotations

import numpy as np

from .base import StaticProblem, StaticResult
from .batch_kernels import (
    _contact_call,
    _contact_inputs,
    _contact_result,
    _solve_group,
    batchable,
    contact_eligible,
    solve_contact_arrays,
)
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


def solve_compiled_many(problems: list[StaticProblem]) -> list[StaticResult | None]:
    """:func:`~.batch_kernels.solve_compiled` of each problem, the
    batchable ones of the same pieces and nodes stacked into one kernel call, the
    seabed-contact ones of the same plane into another: the same answers, verified the
    same way. None where :func:`~.batch_kernels.solve_compiled` gives None (the general
    solver's then)."""
    out: list[StaticResult | None] = [None] * len(problems)
    groups: dict[tuple, list[int]] = {}
    layouts: list = [None] * len(problems)
    contact = []
    for i, problem in enumerate(problems):
        if contact_eligible(problem):
            contact.append(i)
            continue
        if not batchable(problem):
            continue
        line = problem.line
        if line.length.size == 1 and line.attachment_s.size == 0:
            key: tuple = (1, problem.n_nodes, False)
        else:
            layouts[i] = make_layout(line)
            key = (len(layouts[i].ell), problem.n_nodes, True)
        groups.setdefault(key, []).append(i)
    if contact:  # as solve_compiled: verified one by one, else the general solver's
        solved = contact_many([problems[i] for i in contact])
        for i, res in zip(contact, solved, strict=True):
            if res is not None and verified(problems[i], res, method="catenary").success:
                out[i] = res
    for (P, n_nodes, _), idx in groups.items():
        solved = _solve_group([problems[i] for i in idx], P, n_nodes, [layouts[i] for i in idx])
        for i, res in zip(idx, solved, strict=True):
            out[i] = res
    return out
