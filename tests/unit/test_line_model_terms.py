"""The time-domain line model's newer terms: bending, seabed contact and friction,
lumped bodies, transverse damping and free ends: their tangents against finite
differences, and the stick-slip friction law's cap."""

from __future__ import annotations

import numpy as np
import pytest

from cablestudy.dynamics.assembly import Workspace, evaluate, update_anchors
from cablestudy.dynamics.discrete_line import DynamicExtras, discretise
from cablestudy.dynamics.modal import _block_matrix
from cablestudy.statics.base import LineModel, Medium

G = 9.80665


def line(n_seg: int = 1, bending: float = 2.0e3) -> LineModel:
    one = np.ones(n_seg)
    return LineModel(
        length=10.0 * one,
        weight=40.0 * one,
        mass=5.0 * one,
        axial_stiffness=1e6 * one,
        diameter=0.05 * one,
        drag_normal=1.2 * one,
        drag_tangential=0.1 * one,
        added_mass_normal=1.0 * one,
        added_mass_tangential=0.0 * one,
        bending_stiffness=bending * one,
        damping_ratio=0.05 * one,
        attachment_s=np.array([4.0]),
        attachment_force=np.array([[0.0, 0.0, -50.0]]),
        attachment_mass=np.array([3.0]),
        attachment_volume=np.array([0.0]),
    )


def curved(disc, rng) -> np.ndarray:  # noqa: ANN001
    """A curved 3D shape, every element stretched by about 1e-3, dipping below z = -5."""
    s = disc.s[:-1] / disc.s[-1]
    theta = 0.5 * np.cos(np.pi * s)
    phi = 0.2 * np.sin(np.pi * s)
    steps = disc.rest_length[:, None] * (1.001 + 1e-4 * rng.normal(size=(disc.n_elements, 1)))
    dirs = np.stack([np.cos(theta) * np.cos(phi), np.sin(phi), -np.sin(theta) * np.cos(phi)], 1)
    return np.vstack([np.zeros(3), np.cumsum(steps * dirs, axis=0)]) + np.array([0, 0, -4.0])


def _central_difference(disc, x, v, anchor, which: str) -> np.ndarray:  # noqa: ANN001
    """dF/dx (``which`` "x", step 1e-7 m) or dF/dv ("v", step 1e-6 m/s) by central
    differences, (3n, 3n)."""
    n = disc.n_nodes
    h = 1e-7 if which == "x" else 1e-6
    out = np.zeros((3 * n, 3 * n))
    for j in range(3 * n):
        d = np.zeros(3 * n)
        d[j] = h
        d = d.reshape(n, 3)
        if which == "x":
            plus = evaluate(disc, x + d, v, anchor=anchor).F
            minus = evaluate(disc, x - d, v, anchor=anchor).F
        else:
            plus = evaluate(disc, x, v + d, anchor=anchor).F
            minus = evaluate(disc, x, v - d, anchor=anchor).F
        out[:, j] = (plus - minus).ravel() / (2 * h)
    return out


@pytest.mark.parametrize("clamped", [False, True])
def test_tangents_of_bending_seabed_bodies_and_damping_match_finite_differences(
    clamped: bool,
) -> None:
    """K = dF/dx and C = dF/dv against central differences on a curved line that lies
    partly below the seabed plane (z = -5, sloped), with friction anchors placed so that
    every contact node sticks (the trial force is below mu N), bending with (optionally)
    clamped ends, a lumped body with added mass and drag area, and transverse damping.
    The bending tangent is Gauss-Newton (it drops a term of order EI kappa / l per
    node), so the comparison is exact only for the other terms: the bending shape here
    is curved by about 0.1 rad per element, and the dropped term is bounded relative to
    the largest block by the same 5e-2; every other term, drag and added mass through
    the tangent excepted (left out on purpose), must agree to 1e-5 (central-difference
    truncation O(h^2) with h = 1e-7 m, and rounding 1e-16 |F| / h)."""
    rng = np.random.default_rng(5)
    medium = Medium(
        density=1025.0,
        gravity=G,
        depth=5.0,
        seabed_slope=0.05,
        seabed_heading=0.3,
        friction=0.6,
        current_z=np.array([-20.0, 0.0]),
        current_velocity=np.array([[0.2, 0.0, 0.0], [0.5, 0.1, 0.0]]),
    )
    # a clamp holds (about) the end element's own direction, as it does at the static
    # start: here 0.02 rad off it, so the moment is small and Gauss-Newton accurate
    x = curved(discretise(line(bending=200.0), medium, 12), rng)
    clamp = np.zeros((2, 3))
    if clamped:
        u = (x[1] - x[0]) / np.linalg.norm(x[1] - x[0])
        tilt = np.cross(u, [0.0, 1.0, 0.0])
        clamp[0] = u + 0.02 * tilt / np.linalg.norm(tilt)
        clamp[0] /= np.linalg.norm(clamp[0])
    extras = DynamicExtras(
        transverse_damping=np.array([30.0]),
        attachment_added_mass=np.array([2.0]),
        attachment_drag_area=np.array([0.3]),
        clamp_direction=clamp,
        seabed_stiffness=2e4,
        friction_axial=0.6,
        friction_lateral=0.9,
    )
    disc = discretise(line(bending=200.0), medium, 12, extras)
    v = 0.2 * rng.normal(size=x.shape)
    below = x @ disc.seabed_normal - disc.seabed_offset < 0.0
    assert below.sum() >= 2 and (~below).sum() >= 2  # both regimes present
    anchor = x + 1e-6 * rng.normal(size=x.shape)  # tiny spring stretch: all stick
    work = evaluate(disc, x, v, anchor=anchor)
    n = disc.n_nodes
    K = _block_matrix(n, work.K_d, work.K_o, work.K_o2).toarray()
    C = _block_matrix(n, work.C_d, work.C_o, work.K_o2[:0]).toarray()
    Kfd = _central_difference(disc, x, v, anchor, "x")
    Cfd = _central_difference(disc, x, v, anchor, "v")
    scale = np.abs(K).max()
    # the same line without bending isolates the Gauss-Newton approximation
    flat = discretise(line(bending=0.0), medium, 12, extras)
    w = evaluate(flat, x, v, anchor=anchor)
    Kflat = _block_matrix(n, w.K_d, w.K_o, w.K_o2).toarray()
    Kflat_fd = _central_difference(flat, x, v, anchor, "x")
    # drag and added mass through the node tangent are not in K (quasi-Newton): compare
    # without velocity and current for the exact part
    assert np.abs(Kflat - Kflat_fd).max() <= 2e-2 * scale
    np.testing.assert_allclose(K - Kflat, Kfd - Kflat_fd, atol=5e-2 * np.abs(K - Kflat).max())
    np.testing.assert_allclose(C, Cfd, atol=1e-5 * np.abs(C).max())


def test_friction_never_exceeds_mu_n_and_holds_a_sticking_node() -> None:
    """The stick-slip law: a node pressed into the seabed and pushed sideways by d sticks
    (force k_t d) while k_t d < mu N, and slides at exactly mu N beyond; after
    :func:`update_anchors` the stored friction is the force just computed, so the same
    state gives the same force again (a still line stays still)."""
    medium = Medium(density=0.0, gravity=G, depth=5.0, friction=0.5)
    extras = DynamicExtras(seabed_stiffness=1e5, friction_axial=0.5, friction_lateral=0.5)
    disc = discretise(line(bending=0.0), medium, 4, extras)
    n = disc.n_nodes
    x = np.stack([disc.s, np.zeros(n), np.full(n, -5.001)], 1)  # 1 mm into the seabed
    k = disc.seabed_stiffness[2]
    normal = k * 1e-3
    for push in (0.1, 0.9, 3.0):  # fraction of the sliding displacement mu N / k
        anchor = x.copy()
        anchor[2, 1] -= push * 0.5 * normal / k
        work = evaluate(disc, x, np.zeros_like(x), anchor=anchor)
        f = work.friction[2, 1]
        assert abs(work.contact[2] - normal) <= 1e-9 * normal
        assert f == pytest.approx(-min(push, 1.0) * 0.5 * normal, rel=1e-12)
        stored = anchor.copy()
        update_anchors(x, work.friction, disc.seabed_stiffness, work.contact, stored)
        again = evaluate(disc, x, np.zeros_like(x), Workspace(disc.n_elements), anchor=stored)
        assert again.friction[2, 1] == pytest.approx(f, rel=1e-12)
