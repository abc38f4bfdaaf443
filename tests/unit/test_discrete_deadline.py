"""Method ``discrete``: a status-0 answer never depends on the machine's load.

When the mixed Newton fails, the solver falls back to Newton on positions and then
polishes with the mixed form under the caller's deadline. A polish stopped by the
deadline used to keep the unpolished answer at the (looser) rounding tolerance with
status 0, so a loaded machine returned a different status-0 answer than an idle one.
The load is simulated here by the deadline passing exactly during the polish.
"""

from __future__ import annotations

import time

import numpy as np
import pytest

from cablestudy.dynamics import mixed
from cablestudy.statics import STATIC_SOLVERS, STATUS_OK, STATUS_TIME_LIMIT, Medium, StaticProblem
from tests.statics_helpers import fixed, make_line


def _problem() -> StaticProblem:
    line = make_line([100.0], [50.0], 1e8)
    return StaticProblem(
        line=line,
        medium=Medium(density=1025.0, gravity=9.80665),
        end_a=fixed(0.0, 0.0, -200.0),
        end_b=fixed(90.0, 0.0, -170.0),
        n_nodes=21,
        tolerance=1e-9,
    )


def _force_polish(monkeypatch: pytest.MonkeyPatch, *, late: bool) -> list[int]:
    """The first mixed solve stops unconverged after one iteration (not by time), so the
    position-Newton fallback and its polish run; with ``late`` the deadline has passed by
    the polish. Returns the calls' count."""
    real = mixed.mixed_equilibrium
    calls: list[int] = []

    def staged(*args, **kwargs):  # noqa: ANN002, ANN003, ANN202
        calls.append(1)
        if len(calls) == 1:
            kwargs["max_iterations"] = 1
            kwargs["deadline"] = None
        elif late:
            kwargs["deadline"] = time.monotonic() - 1.0
        return real(*args, **kwargs)

    monkeypatch.setattr(mixed, "mixed_equilibrium", staged)
    return calls


def test_polish_stopped_by_the_deadline_is_a_time_limit(monkeypatch: pytest.MonkeyPatch) -> None:
    prob = _problem()
    plain = STATIC_SOLVERS["discrete"].solve(prob)
    assert plain.status == STATUS_OK

    calls = _force_polish(monkeypatch, late=False)
    idle = STATIC_SOLVERS["discrete"].solve(prob, deadline=time.monotonic() + 60.0)
    assert len(calls) == 2  # the fallback and its polish ran
    assert idle.status == STATUS_OK
    # both are the mixed form's answer to the same force tolerance (1e-9 of the nodal
    # loads): the same nodes to far below a micrometre on a 100 m line
    assert np.max(np.abs(idle.position - plain.position)) < 1e-6
    assert np.max(np.abs(idle.tension - plain.tension)) < 1e-9 * 50.0 * 100.0 * 10.0

    calls = _force_polish(monkeypatch, late=True)
    loaded = STATIC_SOLVERS["discrete"].solve(prob, deadline=time.monotonic() + 60.0)
    assert len(calls) == 2
    assert loaded.status == STATUS_TIME_LIMIT, (loaded.status, loaded.message)
    assert "time limit" in loaded.message
    assert np.all(np.isnan(loaded.force_a))
