"""Static solvers, found by name through :data:`STATIC_SOLVERS` (see :mod:`.base`)."""

from .base import (
    STATUS_BROKEN,
    STATUS_NO_SOLUTION,
    STATUS_NOT_CONVERGED,
    STATUS_NOT_VERIFIED,
    STATUS_NUMERICAL,
    STATUS_OK,
    STATUS_TIME_LIMIT,
    EndCondition,
    LineModel,
    Medium,
    StaticProblem,
    StaticResult,
    StaticSolver,
)
from .discrete import DiscreteSolver
from .elastic_catenary import ElasticCatenarySolver
from .semi_analytic import SemiAnalyticSolver
from .shooting import ShootingSolver
from .verify import tolerance_floor, verified


class VerifiedSolver:
    """A registered solver whose every result goes through :func:`.verify.verified`
    before it is returned: status 0 means verified. Other attributes are the solver's."""

    def __init__(self, solver: StaticSolver) -> None:
        self.solver = solver
        self.name = solver.name

    def unsupported(self, problem: StaticProblem) -> list[str]:
        return self.solver.unsupported(problem)

    def solve(
        self, problem: StaticProblem, *, deadline: float | None = None, **options: object
    ) -> StaticResult:
        result = self.solver.solve(problem, deadline=deadline, **options)  # type: ignore[call-arg]
        return verified(
            problem, result.check_finite(), method=self.name, floor=tolerance_floor(self.solver)
        )

    def __getattr__(self, name: str) -> object:
        if name == "solver":  # not set yet (e.g. while unpickling): no recursion
            raise AttributeError(name)
        return getattr(self.solver, name)


#: name -> solver; ``analysis.static.method`` picks one.
STATIC_SOLVERS: dict[str, StaticSolver] = {
    "analytic": VerifiedSolver(ElasticCatenarySolver()),
    "catenary": VerifiedSolver(SemiAnalyticSolver()),
    "discrete": VerifiedSolver(DiscreteSolver()),
    "shooting": VerifiedSolver(ShootingSolver()),
}

__all__ = [
    "STATIC_SOLVERS",
    "STATUS_BROKEN",
    "STATUS_NO_SOLUTION",
    "STATUS_NOT_CONVERGED",
    "STATUS_NOT_VERIFIED",
    "STATUS_NUMERICAL",
    "STATUS_OK",
    "STATUS_TIME_LIMIT",
    "EndCondition",
    "LineModel",
    "Medium",
    "StaticProblem",
    "StaticResult",
    "StaticSolver",
    "VerifiedSolver",
]
