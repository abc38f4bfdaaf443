"""The positions-and-tensions Newton (cablestudy.dynamics.mixed) from a start it cannot
use directly: the straight chord between the supports at a guessed uniform tension.
From there Newton's first steps fail on a stiff line (the chord is far shorter than the
line: a huge slack misfit), and the continuation in stiffness carries it to the same
equilibrium the discrete static method finds from the cable solution."""

from __future__ import annotations

import numpy as np
import pytest

from cablestudy.dynamics.discrete_line import discretise
from cablestudy.dynamics.mixed import mixed_equilibrium
from cablestudy.statics.base import EndCondition, LineModel, Medium, StaticProblem
from cablestudy.statics.discrete import DiscreteSolver


def line_model(ea: float, w: float = 24.0, length: float = 100.0) -> LineModel:
    def one(v: float) -> np.ndarray:
        return np.array([v], dtype=float)

    return LineModel(
        length=one(length),
        weight=one(w),
        mass=one(w / 9.80665),
        axial_stiffness=one(ea),
        diameter=one(0.05),
        drag_normal=one(0.0),
        drag_tangential=one(0.0),
        added_mass_normal=one(0.0),
        added_mass_tangential=one(0.0),
        bending_stiffness=one(0.0),
        damping_ratio=one(0.0),
        attachment_s=np.zeros(0),
        attachment_force=np.zeros((0, 3)),
        attachment_mass=np.zeros(0),
        attachment_volume=np.zeros(0),
    )


@pytest.mark.parametrize("ea", [1e6, 1e9, 1e12, 1e15])
def test_straight_start_reaches_the_equilibrium_of_the_cable_start(ea: float) -> None:
    """Same 51 nodes, two starts: the node positions agree to the equilibrium's own
    accuracy, the force tolerance (1e-9 of the 48 N node load) over the softest nodal
    stiffness (T / l ~ 1200 N / 2 m): 1e-10 m, so 1e-6 m is met with room for the
    reference's rounding floor; the supports carry the whole weight."""
    medium = Medium(density=0.0, gravity=9.80665)
    b = np.array([80.0, 0.0, -20.0])
    lm = line_model(ea)
    problem = StaticProblem(
        line=lm,
        medium=medium,
        end_a=EndCondition(kind="fixed", position=np.zeros(3)),
        end_b=EndCondition(kind="fixed", position=b),
        n_nodes=51,
    )
    ref = DiscreteSolver().solve(problem)
    assert ref.status == 0, ref.message
    disc = discretise(lm, medium, 50)
    x0 = np.linspace(0.0, 1.0, 51)[:, None] * b[None, :]
    sol = mixed_equilibrium(
        disc, x0, np.full(50, 2400.0), x0.copy(), tol_force=1e-9 * 48.0, relative=1e-9
    )
    assert sol.converged
    if ea >= 1e9:  # stiff: Newton alone cannot start from the straight chord
        assert sol.stages > 0
    np.testing.assert_allclose(sol.position, ref.position, rtol=0, atol=1e-6)
    # equilibrium of the whole line: the end elements carry the weight less the ends'
    # own lumps (half an element each), 24 N/m * 100 m in all
    lump = 24.0 * 2.0 / 2.0
    d = np.diff(sol.position, axis=0)
    u = d / np.linalg.norm(d, axis=1, keepdims=True)
    vertical = -sol.tension[0] * u[0, 2] + sol.tension[-1] * u[-1, 2] + 2 * lump
    assert abs(vertical - 2400.0) < 1e-6 * 2400.0


def test_a_passed_deadline_stops_newton_and_says_so() -> None:
    """A deadline already passed: the straight start is not an equilibrium, so Newton
    stops unconverged at once and reports the time limit (not a false convergence)."""
    import time

    medium = Medium(density=0.0, gravity=9.80665)
    disc = discretise(line_model(1e12), medium, 50)
    b = np.array([80.0, 0.0, -20.0])
    x0 = np.linspace(0.0, 1.0, 51)[:, None] * b[None, :]
    sol = mixed_equilibrium(
        disc,
        x0,
        np.full(50, 2400.0),
        x0.copy(),
        tol_force=1e-9 * 48.0,
        relative=1e-9,
        deadline=time.monotonic() - 1.0,
    )
    assert not sol.converged and sol.timed_out
    assert sol.iterations == 0 and sol.stages == 0
