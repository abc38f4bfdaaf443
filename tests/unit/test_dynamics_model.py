"""The discretised line model: lumping, tangents, drag, and the discrete statics."""

from __future__ import annotations

import numpy as np
import pytest

from cablestudy.dynamics.assembly import evaluate, solve_banded
from cablestudy.dynamics.discrete_line import discretise, element_counts
from cablestudy.dynamics.excitation import EndMotion, TableMotion
from cablestudy.dynamics.model import static_equilibrium
from cablestudy.physics.hydro import drag_per_length
from cablestudy.statics.base import LineModel, Medium

G = 9.80665


def two_material_line() -> LineModel:
    """A chain (heavy, stiff) then a rope (light), with a 5 kg clump between them."""

    def arr(a: float, b: float) -> np.ndarray:
        return np.array([a, b])

    return LineModel(
        length=arr(4.0, 6.0),
        weight=arr(50.0, 5.0),
        mass=arr(5.6, 0.9),
        axial_stiffness=arr(5e7, 2e6),
        diameter=arr(0.03, 0.02),
        drag_normal=arr(2.4, 1.2),
        drag_tangential=arr(0.4, 0.01),
        added_mass_normal=arr(1.0, 1.0),
        added_mass_tangential=arr(0.0, 0.0),
        bending_stiffness=arr(0.0, 0.0),
        damping_ratio=arr(0.0, 0.1),
        attachment_s=np.array([4.0]),
        attachment_force=np.array([[0.0, 0.0, -5.0 * G]]),
        attachment_mass=np.array([5.0]),
        attachment_volume=np.array([0.0]),
    )


def water(current: bool = False) -> Medium:
    if not current:
        return Medium(density=1025.0, gravity=G)
    return Medium(
        density=1025.0,
        gravity=G,
        current_z=np.array([-20.0, 0.0]),
        current_velocity=np.array([[0.2, 0.0, 0.0], [0.8, 0.3, 0.0]]),
    )


def test_lumping_conserves_mass_and_weight_and_keeps_segment_boundaries() -> None:
    line = two_material_line()
    disc = discretise(line, water(), 20)
    assert disc.n_elements == 20
    assert np.isclose(disc.s, 4.0).any()  # a node on the segment boundary
    assert np.isclose(disc.mass.sum(), 4.0 * 5.6 + 6.0 * 0.9 + 5.0)
    assert np.isclose(-disc.force[:, 2].sum(), 4.0 * 50.0 + 6.0 * 5.0 + 5.0 * G)
    # each element lies in one segment and carries that segment's EA
    assert set(disc.axial_stiffness[disc.s[:-1] < 4.0 - 1e-12]) == {5e7}
    assert set(disc.axial_stiffness[disc.s[1:] > 4.0 + 1e-12]) == {2e6}
    assert list(element_counts(np.array([1.0, 100.0]), 10)) == [1, 9]


def test_discrete_statics_balance_the_weight() -> None:
    line = two_material_line()
    disc = discretise(line, water(), 30)
    # start from a straight-ish sagging guess between supports at different levels
    a, b = np.array([0.0, 0.0, 0.0]), np.array([8.0, 0.0, -2.0])
    u = disc.s / disc.s[-1]
    x0 = a + np.outer(u, b - a)
    x0[:, 2] -= 1.5 * np.sin(np.pi * u)
    x, _, res, ok, _ = static_equilibrium(disc, x0, tolerance=1e-7)
    assert ok, res
    work = evaluate(disc, x, np.zeros_like(x))
    # force of the line on the two supports = total weight (global equilibrium)
    reactions = -work.F[0] - work.F[-1]
    np.testing.assert_allclose(reactions, disc.force.sum(0), atol=1e-6)
    # horizontal tension component constant along the line (no horizontal loads)
    d = np.diff(x, axis=0)
    horizontal = work.tension * d[:, 0] / np.linalg.norm(d, axis=1)
    np.testing.assert_allclose(horizontal, horizontal[0], rtol=1e-8)
    assert np.all(work.tension > 0.0)


@pytest.mark.parametrize("current", [False, True])
def test_tangents_match_finite_differences(current: bool) -> None:
    line = two_material_line()
    disc = discretise(line, water(current), 8)
    rng = np.random.default_rng(1)
    # a curved 3D shape with every element stretched by about 1e-3
    theta = 0.4 * np.cos(np.pi * disc.s[:-1] / disc.s[-1])
    phi = 0.2 * np.sin(np.pi * disc.s[:-1] / disc.s[-1])
    steps = disc.rest_length[:, None] * (1.001 + 1e-4 * rng.normal(size=(disc.n_elements, 1)))
    dirs = np.stack([np.cos(theta) * np.cos(phi), np.sin(phi), -np.sin(theta) * np.cos(phi)], 1)
    x = np.vstack([np.zeros(3), np.cumsum(steps * dirs, axis=0)]) + np.array([0, 0, -5.0])
    v = 0.3 * rng.normal(size=x.shape)
    w = evaluate(disc, x, v)
    F, K_d, K_o, C_d, C_o = (w.F.copy(), w.K_d.copy(), w.K_o.copy(), w.C_d.copy(), w.C_o.copy())
    assert np.all(w.strain > 0.0)  # all taut: the tangents are smooth here
    n = disc.n_nodes
    # central differences: truncation O(h^2) with h = 1e-7 m against a stiffness of
    # EA/l ~ 5e7 N/m; rounding ~ 1e-16 * |F| / h; 1e-5 relative to the largest entry
    for i in (2, 4, 5):
        for c in range(3):
            for which, blocks_d, blocks_o, step in (("x", K_d, K_o, 1e-7), ("v", C_d, C_o, 1e-6)):
                xp, xm, vp, vm = x.copy(), x.copy(), v.copy(), v.copy()
                if which == "x":
                    xp[i, c] += step
                    xm[i, c] -= step
                else:
                    vp[i, c] += step
                    vm[i, c] -= step
                col = (evaluate(disc, xp, vp).F - evaluate(disc, xm, vm).F) / (2 * step)
                scale = np.abs(blocks_d).max()
                np.testing.assert_allclose(col[i], blocks_d[i][:, c], atol=1e-5 * scale)
                np.testing.assert_allclose(col[i - 1], blocks_o[i - 1][:, c], atol=1e-5 * scale)
                np.testing.assert_allclose(col[i + 1], blocks_o[i][c, :], atol=1e-5 * scale)
                others = [k for k in range(n) if abs(k - i) > 1]
                if which == "x" and not current:
                    # only drag/added mass through the node tangents reach further
                    np.testing.assert_allclose(col[others], 0.0, atol=1e-5 * scale)
    del F


def test_nodal_drag_is_the_shared_morison_drag_times_the_tributary_length() -> None:
    line = two_material_line()
    medium = water(current=True)
    disc = discretise(line, medium, 10)
    x = np.stack([disc.s, np.zeros_like(disc.s), -5.0 - 0.5 * np.sin(np.pi * disc.s / 10)], 1)
    rng = np.random.default_rng(3)
    v = 0.5 * rng.normal(size=x.shape)
    with_drag = evaluate(disc, x, v).F.copy()
    still = evaluate(disc, x, np.zeros_like(v)).F.copy()  # noqa: F841 (tangent check)
    no_fluid = discretise(line, Medium(density=0.0, gravity=G), 10)
    base = evaluate(no_fluid, x, v).F.copy()
    # nodal drag = -(F - F without fluid), up to the weight difference (buoyancy is in
    # the LineModel's weight, identical in both): compare interior nodes
    drag = -(with_drag - base) + (disc.force - no_fluid.force)
    tangent = np.empty_like(x)
    tangent[1:-1] = x[2:] - x[:-2]
    tangent[0], tangent[-1] = x[1] - x[0], x[-1] - x[-2]
    tangent /= np.linalg.norm(tangent, axis=1, keepdims=True)
    from cablestudy.physics.current import current_velocity

    rel = current_velocity(x[:, 2], medium.current_z, medium.current_velocity) - v
    l0 = np.diff(disc.s)
    trib = np.zeros(disc.n_nodes)
    trib[:-1] += l0 / 2
    trib[1:] += l0 / 2
    seg = (disc.s >= 4.0 - 1e-12).astype(int)  # nodes in the rope (boundary node: mixed)
    interior = [k for k in range(1, disc.n_nodes - 1) if abs(disc.s[k] - 4.0) > 1e-9]
    expected = (
        drag_per_length(
            rel,
            tangent,
            density=1025.0,
            diameter=line.diameter[seg],
            drag_normal=line.drag_normal[seg],
            drag_tangential=line.drag_tangential[seg],
        )
        * trib[:, None]
    )
    np.testing.assert_allclose(drag[interior], expected[interior], rtol=1e-10, atol=1e-12)


@pytest.mark.parametrize("reach", [1, 2])
def test_banded_solver_matches_dense(reach: int) -> None:
    """Block-tri/pentadiagonal systems (lower blocks the transposes of the upper ones,
    diagonal blocks not symmetric: drag damping), with a held node: its row is the
    identity with a zero right side, so its unknown is 0 and the rest solve the
    remaining equations."""
    rng = np.random.default_rng(0)
    m = 7
    D = rng.normal(size=(m, 3, 3)) + 12 * np.eye(3)
    O = rng.normal(size=(m - 1, 3, 3))  # noqa: E741
    O2 = rng.normal(size=(m - 2, 3, 3)) if reach == 2 else np.zeros((0, 3, 3))
    J = np.zeros((3 * m, 3 * m))
    for i in range(m):
        J[3 * i : 3 * i + 3, 3 * i : 3 * i + 3] = D[i]
    for i in range(m - 1):
        J[3 * i : 3 * i + 3, 3 * i + 3 : 3 * i + 6] = O[i]
        J[3 * i + 3 : 3 * i + 6, 3 * i : 3 * i + 3] = O[i].T
    for i in range(O2.shape[0]):
        J[3 * i : 3 * i + 3, 3 * i + 6 : 3 * i + 9] = O2[i]
        J[3 * i + 6 : 3 * i + 9, 3 * i : 3 * i + 3] = O2[i].T
    held = np.zeros(m, dtype=bool)
    held[0] = True
    J[0:3, :] = 0.0
    J[0:3, 0:3] = np.eye(3)
    b = rng.normal(size=(m, 3))
    out, band = np.zeros((m, 3)), np.zeros((3 * m, 17))
    assert solve_banded(D, O, O2, held, b, out, band)
    rhs = b.ravel().copy()
    rhs[0:3] = 0.0
    np.testing.assert_allclose(out.ravel(), np.linalg.solve(J, rhs), rtol=1e-11, atol=1e-13)


def test_end_motion_ramp_and_derivatives() -> None:
    table = TableMotion(
        end=0,
        direction=np.array([0.0, 0.0, 1.0]),
        times=np.linspace(0.0, 2.0, 41),
        values=0.1 * np.sin(np.pi * np.linspace(0.0, 2.0, 41)),
        periodic=True,
    )
    motion = EndMotion(
        harmonic_end=np.array([1]),
        harmonic_direction=np.array([[1.0, 0, 0]]),
        harmonic_amplitude=np.array([0.05]),
        harmonic_frequency=np.array([0.7]),
        harmonic_phase=np.array([0.3]),
        tables=(table,),
        ramp_time=3.0,
    )
    d0, v0, a0 = motion.at(0.0)
    assert np.all(d0 == 0.0) and np.all(v0 == 0.0)  # starts at rest
    # velocity and acceleration are the derivatives of the displacement (central
    # differences, error O(h^2) ~ 1e-8 relative at h = 1e-4 s)
    for t in (1.01, 2.93, 3.52, 7.27):  # off the table's knots (spline d3 jumps there)
        h = 1e-4
        dp, vp, _ = motion.at(t + h)
        dm, vm, _ = motion.at(t - h)
        d, v, a = motion.at(t)
        np.testing.assert_allclose((dp - dm) / (2 * h), v, atol=1e-6)
        np.testing.assert_allclose((vp - vm) / (2 * h), a, atol=1e-5)
    # after the ramp: exactly the harmonic at end B
    d, _, _ = motion.at(10.0)
    assert d[1, 0] == pytest.approx(0.05 * np.sin(2 * np.pi * 0.7 * 10.0 + 0.3))


def test_a_sparse_ramp_and_hold_table_moves_as_written() -> None:
    """A table 0, 2.5, 5, 5, 5 m at 0, 10, 20, 30, 300 s (a ramp, then a long hold):
    the motion stays within the values written (a not-a-knot spline swung to -158 m in
    the long interval), holds 5 m after 30 s, and stops with zero velocity at the
    table's end (it ends on a flat interval)."""
    table = TableMotion(
        end=1,
        direction=np.array([1.0, 0.0, 0.0]),
        times=np.array([0.0, 10.0, 20.0, 30.0, 300.0]),
        values=np.array([0.0, 2.5, 5.0, 5.0, 5.0]),
    )
    u = np.array([table.evaluate(t)[0] for t in np.linspace(0.0, 320.0, 3201)])
    assert u.min() >= 0.0 and u.max() <= 5.0
    assert table.evaluate(150.0) == (5.0, 0.0, 0.0)
    assert abs(table.evaluate(299.999)[1]) < 1e-12 and table.evaluate(300.0)[1] == 0.0
