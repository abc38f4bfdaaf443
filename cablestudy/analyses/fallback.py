"""Why the general static solver, not a batch kernel, solved a case: the reason a chunk
counts per case (:attr:`cablestudy.analyses.grid_chunk.GridChunk.fallback_reason`),
decided where the case is solved, with what the solver reported, never guessed
afterwards. The dataset's ``cases_fallback`` and ``fallback_reasons`` attributes and the
run's summary count these reasons, whatever the study's analyses.
"""

from __future__ import annotations

from typing import Any

#: why the general solver solved a case no batch kernel takes (both ends on the seabed,
#: an end below it, end A resting on it)
NO_KERNEL = "no batch kernel takes these end conditions"


def one_at_a_time(problem: Any) -> bool:
    """Whether the catenary solver first takes the compiled kernels for ``problem`` on
    its own (:func:`cablestudy.statics.batch_kernels.solve_compiled`)."""
    from ..statics.batch_drag import drag_eligible
    from ..statics.batch_kernels import batchable, contact_eligible

    return bool(contact_eligible(problem) or batchable(problem) or drag_eligible(problem))


def fallback_reason(study: Any, problem: Any) -> str:
    """Why no batch kernel takes the case of ``study`` (its static ``problem``, None for
    a spring line): it goes to the general solver."""
    method = study.analysis.static.method
    if method != "catenary":
        return f"method {method!r} has no batch kernel"
    if study.line.is_spring:
        return "a spring line has no batch kernel"
    if study.line.pulleys:
        return "a line over pulleys has no batch kernel"
    if problem is not None and problem.line.is_nonlinear:
        return "a nonlinear axial law has no batch kernel"
    if problem is not None and problem.medium.drags(problem.line):
        from ..statics.batch_drag import drag_eligible

        if not drag_eligible(problem):  # else the compiled drag iteration tried it
            return "current with drag: the drag iteration runs in the general solver"
    return NO_KERNEL


def static_fallback(study: Any, result: Any, presolved: bool) -> str:
    """Why the general solver solved the statics of a one-line case ('' when a batch
    kernel did): ``result`` is its static solution (None if the solve raised),
    ``presolved`` whether it came from the chunk's batch
    (:func:`cablestudy.statics.batch.solve_batch`, which says in ``result.fallback`` why
    it handed a case on). A case solved alone by the catenary solver, which tries the
    compiled kernels first, says the same in its result."""
    if presolved:
        return str(getattr(result, "fallback", "") or "")
    from ..study.problem import static_problem

    problem = None if study.line.is_spring else static_problem(study)
    reason = fallback_reason(study, problem)
    if reason == NO_KERNEL and one_at_a_time(problem):
        return str(getattr(result, "fallback", "") or "")
    return reason
