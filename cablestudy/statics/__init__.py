"""Static solvers, found by name through :data:`STATIC_SOLVERS` (see :mod:`.base`)."""

from .base import (
    STATUS_BROKEN,
    STATUS_NO_SOLUTION,
    STATUS_NOT_CONVERGED,
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

#: name -> solver; ``analysis.static.method`` picks one.
STATIC_SOLVERS: dict[str, StaticSolver] = {
    "analytic": ElasticCatenarySolver(),
    "catenary": SemiAnalyticSolver(),
    "discrete": DiscreteSolver(),
    "shooting": ShootingSolver(),
}

__all__ = [
    "STATIC_SOLVERS",
    "STATUS_BROKEN",
    "STATUS_NO_SOLUTION",
    "STATUS_NOT_CONVERGED",
    "STATUS_NUMERICAL",
    "STATUS_OK",
    "STATUS_TIME_LIMIT",
    "EndCondition",
    "LineModel",
    "Medium",
    "StaticProblem",
    "StaticResult",
    "StaticSolver",
]
