"""CF conventions of the result files that are not one variable's units and long name:
the status flags every status variable carries, and the command line for ``history``.
No I/O here (the writers in :mod:`cablestudy.run.dataset` apply them)."""

from __future__ import annotations

import shlex
import sys
from pathlib import Path
from typing import Any

import numpy as np

#: every status code a case or an analysis may carry, with its CF flag meaning (one word):
#: cablestudy.statics.base (0-4, 10, 11), cablestudy.dynamics.modal (5, 6; analyses'
#: STATUS_NOT_RUN is 5 too), cablestudy.dynamics.frequency (7), cablestudy.run.scheduler (9)
STATUS_MEANINGS: dict[int, str] = {
    0: "ok",
    1: "not_converged",
    2: "numerical_failure",
    3: "time_limit",
    4: "no_solution",
    5: "not_run_static_failed",
    6: "slack_no_stable_modes",
    7: "linearisation_not_converged",
    9: "task_failed",
    10: "line_broken",
    11: "not_verified",
}


def is_status_variable(name: str) -> bool:
    """Whether a dataset variable holds status codes (``status``, ``<analysis>_status``,
    ``database_status``, ...): it carries CF ``flag_values`` and ``flag_meanings``."""
    return name == "status" or name.endswith("_status")


def status_flag_attrs(dtype: Any) -> dict[str, Any]:
    """CF ``flag_values`` (of the variable's ``dtype``) and ``flag_meanings`` of the
    status codes (:data:`STATUS_MEANINGS`)."""
    return {
        "flag_values": np.array(list(STATUS_MEANINGS), dtype=dtype),
        "flag_meanings": " ".join(STATUS_MEANINGS.values()),
    }


#: the command that is writing results (set by the command line; see :func:`command_line`)
COMMAND: list[str] = []


def command_line() -> str:
    """The command line for the CF ``history`` attribute: the ``cablestudy`` command as
    typed (recorded by :func:`cablestudy.cli.main`), else the Python program and its
    arguments (a script calling the library)."""
    return shlex.join(COMMAND or [Path(sys.argv[0]).name or "python", *sys.argv[1:]])
