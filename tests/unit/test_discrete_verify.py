"""The node-level check of method discrete (statics.discrete.verify_nodes): silent on an
equilibrium, and naming what fails on a state that is not one. A wrong result must never
get status 0; this is the check that decides it."""

from __future__ import annotations

import numpy as np

from cablestudy.dynamics.discrete_line import discretise
from cablestudy.dynamics.mixed import mixed_equilibrium, node_forces
from cablestudy.statics.base import EndCondition, Medium, StaticProblem
from cablestudy.statics.discrete import verify_nodes

from .test_dynamics_mixed import line_model

B = np.array([80.0, 0.0, -20.0])
TOL = 1e-9 * 48.0  # 1e-9 of the 48 N node load (24 N/m, 2 m elements)


def equilibrium() -> tuple:
    medium = Medium(density=0.0, gravity=9.80665)
    lm = line_model(1e9)
    problem = StaticProblem(
        line=lm,
        medium=medium,
        end_a=EndCondition(kind="fixed", position=np.zeros(3)),
        end_b=EndCondition(kind="fixed", position=B),
        n_nodes=51,
    )
    disc = discretise(lm, medium, 50)
    x0 = np.linspace(0.0, 1.0, 51)[:, None] * B[None, :]
    sol = mixed_equilibrium(disc, x0, np.full(50, 2400.0), x0.copy(), tol_force=TOL, relative=1e-9)
    assert sol.converged
    return problem, disc, sol


def check(problem, disc, x, tension, anchor) -> list[str]:  # noqa: ANN001
    F, work = node_forces(disc, x, tension, anchor)
    return verify_nodes(problem, disc, x, F, work, tol=TOL, floor=0.0, load=48.0)


def test_an_equilibrium_passes() -> None:
    problem, disc, sol = equilibrium()
    assert check(problem, disc, sol.position, sol.tension, sol.anchor) == []


def test_a_node_out_of_place_fails() -> None:
    """1 mm of a middle node is T / l * 1e-3 ~ 0.6 N out of balance: far above the
    tolerance (5e-8 N). (The whole line still balances: the elements' forces on their
    two nodes cancel, whatever the node's place.)"""
    problem, disc, sol = equilibrium()
    x = sol.position.copy()
    x[25, 2] += 1e-3
    found = check(problem, disc, x, sol.tension, sol.anchor)
    assert any(f.startswith("largest nodal out-of-balance force") for f in found), found


def test_tensions_off_by_a_fraction_of_the_loads_fail() -> None:
    """Every element 1e-6 of its tension too high (the kind of error the old solver
    made at 7.5 %): node by node the error is 1e-6 of the node's weight, 4.8e-5 N,
    and the supports pull 1e-6 of the whole weight (2.4e-3 N) more than it, against
    49 nodes' tolerance (2.4e-6 N): both checks fail."""
    problem, disc, sol = equilibrium()
    found = check(problem, disc, sol.position, sol.tension * (1.0 + 1e-6), sol.anchor)
    assert any(f.startswith("largest nodal out-of-balance force") for f in found), found
    assert any(f.startswith("support forces") for f in found), found


def test_an_end_away_from_its_support_fails() -> None:
    problem, disc, sol = equilibrium()
    x = sol.position.copy()
    x[-1] += np.array([0.0, 0.0, 1e-6])
    found = check(problem, disc, x, sol.tension, sol.anchor)
    assert any(f.startswith("end at s = 100 m") for f in found), found
