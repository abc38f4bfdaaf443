""":func:`.batch.solve_compiled_many` under the module name its importer uses
(:mod:`cablestudy.analyses.system_frequency`); the kernels' part of
:func:`.batch.solve_batch` lives there.
"""

from __future__ import annotations

from .batch import solve_compiled_many

__all__ = ["solve_compiled_many"]
