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


def _stress_example(n_nodes: int) -> StaticProblem:
    """The shrunk failing example of ``tests/stress/test_static_methods_property.py``
    at 6979c64: 1 m of a very soft line (EA 1 N) anchored on the seabed, B 1.74 cm above
    it; the catenary leaves only 7.5 cm hanging, less than one element of 11 nodes."""
    from dataclasses import replace

    line = make_line([1.0], [0.01], 1.0, diameter=0.01)
    line = replace(line, mass=np.array([0.08152303]))
    return StaticProblem(
        line=line,
        medium=Medium(density=1025.0, gravity=9.80665, depth=1.0),
        end_a=fixed(0.0, 0.0, -1.0),
        end_b=fixed(0.99884785, 0.0, -0.98256505),
        n_nodes=n_nodes,
        tolerance=1e-9,
    )


def test_stress_example_is_the_mesh_not_the_clock() -> None:
    """The discrete answer there is the same with any deadline (bit for bit), and its
    distance from the catenary is discretisation error: it shrinks under refinement."""
    prob = _stress_example(11)
    cat = STATIC_SOLVERS["catenary"].solve(prob)
    assert cat.status == STATUS_OK
    free = STATIC_SOLVERS["discrete"].solve(prob)
    timed = STATIC_SOLVERS["discrete"].solve(prob, deadline=time.monotonic() + 0.5)
    assert free.status == timed.status == STATUS_OK
    assert np.array_equal(free.position, timed.position)
    assert np.array_equal(free.force_a, timed.force_a)

    def gap(n: int) -> float:
        res = STATIC_SOLVERS["discrete"].solve(_stress_example(n))
        c = STATIC_SOLVERS["catenary"].solve(_stress_example(n))
        assert res.status == c.status == STATUS_OK
        return float(np.linalg.norm(res.force_a - c.force_a))

    gaps = [gap(n) for n in (11, 101, 1001)]
    # 11 nodes: the 7.5 cm hanging part inside one 10 cm element, whose straight chord
    # is shorter than the arc by ~h turn^2 / 24 ~ 1e-3 m against the line's 1.5e-3 m
    # stretch, so the horizontal force is off by most of itself (measured 1.19e-3 N of
    # 1.55e-3 N). Once elements are shorter than the hanging part the error falls at
    # least as h (touchdown on a node): tenfold finer, at least tenfold smaller.
    assert gaps[0] > 0.5 * float(np.linalg.norm(cat.force_a))
    assert gaps[1] < gaps[0] / 10.0
    assert gaps[2] < gaps[1] / 2.0  # measured 6.6e-7 after 3.1e-6: the compliant
    # bed's sink w / k = 1e-5 m, the same on every mesh, now weighs in
