"""A status-0 answer never depends on the machine's load (methods ``discrete`` and ``catenary``).

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


def test_catenary_time_limit_is_not_a_switch_to_the_contact_path(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """Method ``catenary``, a line anchored on a sloping seabed: when the free-hanging
    solve runs out of time, the answer is the time limit, not the seabed-contact path
    tried instead (which would answer only on a loaded machine)."""
    from cablestudy.statics import semi_analytic
    from cablestudy.statics.semi_analytic_shape import _Failure

    line = make_line([120.0], [50.0], 1e8)
    slope = 0.05
    prob = StaticProblem(
        line=line,
        medium=Medium(density=1025.0, gravity=9.80665, depth=100.0, seabed_slope=slope),
        end_a=fixed(0.0, 0.0, -100.0),
        end_b=fixed(100.0, 0.0, -100.0 + 100.0 * np.tan(slope) + 40.0),
        n_nodes=21,
        tolerance=1e-9,
    )
    idle = STATIC_SOLVERS["catenary"].solve(prob, compiled=False)  # the general path
    assert idle.status == STATUS_OK, idle.message

    def out_of_time(*args, **kwargs):  # noqa: ANN002, ANN003, ANN202
        raise _Failure(STATUS_TIME_LIMIT, "time limit reached in the test's free solve")

    monkeypatch.setattr(semi_analytic, "solve_free", out_of_time)
    loaded = STATIC_SOLVERS["catenary"].solve(
        prob, deadline=time.monotonic() + 60.0, compiled=False
    )
    assert loaded.status == STATUS_TIME_LIMIT, (loaded.status, loaded.message)
    assert "time limit" in loaded.message
