"""Unit tests of cablestudy.dynamics.modal: matrices, end conditions, invariances,
failures as data, and the analysis.modal settings."""

from __future__ import annotations

import math
import time

import numpy as np
import pytest
from pydantic import ValidationError

from cablestudy.dynamics.modal import (
    SIGN_TIE,
    STATUS_SLACK,
    STATUS_STATIC_FAILED,
    ModalProblem,
    modal_analysis,
    node_bases,
    tangents,
)
from cablestudy.statics import (
    STATIC_SOLVERS,
    STATUS_NO_SOLUTION,
    STATUS_NUMERICAL,
    STATUS_TIME_LIMIT,
    EndCondition,
    LineModel,
    Medium,
    StaticProblem,
    StaticResult,
)
from cablestudy.study import ModalSettings

G = 9.81


def line_model(
    length: float = 102.0,
    *,
    mass: float = 2.0,
    weight: float | None = None,
    axial_stiffness: float = 1.0e7,
    diameter: float = 0.08,
    ca_n: float = 1.0,
    ca_t: float = 0.0,
    attachments: list[tuple[float, float]] | None = None,
) -> LineModel:
    att = attachments or []

    def one(v: float) -> np.ndarray:
        return np.array([float(v)])

    return LineModel(
        length=one(length),
        weight=one(mass * G if weight is None else weight),
        mass=one(mass),
        axial_stiffness=one(axial_stiffness),
        diameter=one(diameter),
        drag_normal=one(1.2),
        drag_tangential=one(0.01),
        added_mass_normal=one(ca_n),
        added_mass_tangential=one(ca_t),
        bending_stiffness=one(0.0),
        damping_ratio=one(0.0),
        attachment_s=np.array([a[0] for a in att], dtype=float),
        attachment_force=np.zeros((len(att), 3)),
        attachment_mass=np.array([a[1] for a in att], dtype=float),
        attachment_volume=np.zeros(len(att)),
    )


def fixed(p: list[float]) -> EndCondition:
    return EndCondition(kind="fixed", position=np.array(p, dtype=float))


AIR = Medium(density=0.0, gravity=G)
WATER = Medium(density=1025.0, gravity=G)


def sagged(
    a: list[float], b: list[float], n: int = 60, line: LineModel | None = None, medium: Medium = AIR
) -> ModalProblem:
    line = line or line_model()
    ea, eb = fixed(a), fixed(b)
    st = STATIC_SOLVERS["analytic"].solve(
        StaticProblem(line=line, medium=medium, end_a=ea, end_b=eb, n_nodes=n + 1)
    )
    assert st.success
    return ModalProblem(line=line, medium=medium, end_a=ea, end_b=eb, static=st, n_modes=8)


def test_lumped_mass_total_and_added_mass_directions() -> None:
    """Summed blocks: m L0 + attachments along the line, plus the added mass
    rho C_a pi d^2 / 4 per length across it (uniform straight line along x)."""
    L0, m, d, rho = 100.0, 2.0, 0.08, 1025.0
    line = line_model(L0, mass=m, weight=0.0, diameter=d, attachments=[(25.0, 30.0)])
    n = 11
    s = np.linspace(0, L0, n)
    pos = np.zeros((n, 3))
    pos[:, 0] = s * 1.001
    st = StaticResult(
        s=s, position=pos, tension=np.full(n, 1e4), force_a=np.zeros(3), force_b=np.zeros(3)
    )
    prob = ModalProblem(
        line=line, medium=WATER, end_a=fixed([0, 0, 0]), end_b=fixed([100.1, 0, 0]), static=st
    )
    M = tangents(prob)[0]  # lumped nodal mass blocks (n_nodes, 3, 3)
    total = M.sum(axis=0)
    ma = rho * math.pi * d**2 / 4
    np.testing.assert_allclose(
        np.diag(total), [m * L0 + 30, (m + ma) * L0 + 30, (m + ma) * L0 + 30], rtol=1e-13
    )
    np.testing.assert_allclose(total - np.diag(np.diag(total)), 0.0, atol=1e-12)
    # attachment at s = 25 lies between nodes 2 (s = 20) and 3 (s = 30): split 1/2, 1/2
    np.testing.assert_allclose(M[2, 0, 0] - M[1, 0, 0], 15.0, rtol=1e-12)


def test_stiffness_symmetric_and_translation_free() -> None:
    """K is symmetric and a rigid translation of all nodes stores no energy."""
    prob = sagged([0, 0, 0], [80, 30, -20])
    K = tangents(prob)[1].toarray()  # tangent stiffness before constraints
    np.testing.assert_allclose(K, K.T, atol=1e-9 * np.abs(K).max())
    for c in range(3):
        u = np.zeros(K.shape[0])
        u[c::3] = 1.0
        assert np.abs(K @ u).max() < 1e-9 * np.abs(K).max()


def test_invariant_under_rotation_about_vertical_and_end_swap() -> None:
    """The frequencies do not depend on the azimuth of the span (gravity is vertical) nor
    on which end is called A."""
    base = modal_analysis(sagged([0, 0, 0], [90, 0, -10])).frequency
    c, s = math.cos(0.7), math.sin(0.7)
    rotated = modal_analysis(sagged([5, 5, 0], [5 + 90 * c, 5 + 90 * s, -10])).frequency
    swapped = modal_analysis(sagged([90, 0, -10], [0, 0, 0])).frequency
    np.testing.assert_allclose(rotated, base, rtol=1e-9)
    np.testing.assert_allclose(swapped, base, rtol=1e-9)


def test_mooring_end_is_free_horizontally_and_held_vertically() -> None:
    """A weightless string along x, fixed at A, mooring end at B (dead horizontal force,
    z held). Exact discrete eigenvalues of the lumped chain: fixed-free (quarter-wave)
    in x and y, omega = 2 sqrt(k / M) sin((2n - 1) pi / (4N)); fixed-fixed in z,
    2 sqrt(k / M) sin(n pi / (2N)); k = T / h across, EA / h0 along."""
    N, L0, EA, T, m = 20, 50.0, 1.0e5, 400.0, 1.5
    h0 = L0 / N
    h = h0 * (1 + T / EA)
    line = line_model(L0, mass=m, weight=0.0, axial_stiffness=EA)
    s = np.linspace(0, L0, N + 1)
    pos = np.zeros((N + 1, 3))
    pos[:, 0] = s * (1 + T / EA)
    st = StaticResult(
        s=s,
        position=pos,
        tension=np.full(N + 1, T),
        force_a=np.array([-T, 0, 0]),
        force_b=np.array([T, 0, 0]),
    )
    moor = EndCondition(kind="mooring", force=np.array([T, 0, 0]), z=0.0)
    prob = ModalProblem(
        line=line, medium=AIR, end_a=fixed([0, 0, 0]), end_b=moor, static=st, n_modes=3 * N - 1
    )
    res = modal_analysis(prob)
    assert res.success and res.n_dof == 3 * N - 1
    M = m * h0
    q = np.arange(1, N + 1)
    y = 2 * np.sqrt(T / h / M) * np.sin((2 * q - 1) * np.pi / (4 * N))
    x = 2 * np.sqrt(EA / h0 / M) * np.sin((2 * q - 1) * np.pi / (4 * N))
    z = 2 * np.sqrt(T / h / M) * np.sin(q[:-1] * np.pi / (2 * N))
    expected = np.sort(np.concatenate([x, y, z])) / (2 * np.pi)
    np.testing.assert_allclose(res.frequency, expected, rtol=1e-9)
    assert np.all(res.mode_shape[:, -1, 2] == 0.0)


def test_seabed_nodes_do_not_move_normal_to_the_seabed() -> None:
    """Nodes resting on a flat frictionless seabed sit on the contact spring (stiffness
    per length k = the line's weight in the fluid over 1 mm) and are free along it: the
    low modes, whose frequencies are far below the bounce of a laid node on its spring
    (sqrt(k / m)), barely move them normal to the seabed: by about (omega^2 m / k) of the
    suspended motion, under 1e-2 here."""
    N, L0, T = 20, 40.0, 1.0e3
    s = np.linspace(0, L0, N + 1)
    pos = np.zeros((N + 1, 3))
    pos[:, 0] = s
    pos[:, 2] = -30.0
    rise = s > 20.0
    pos[rise, 2] = -30.0 + 0.2 * (s[rise] - 20.0)
    st = StaticResult(
        s=s,
        position=pos,
        tension=np.full(N + 1, T),
        force_a=np.zeros(3),
        force_b=np.zeros(3),
        laid_length=20.0,
    )
    medium = Medium(density=1025.0, gravity=G, depth=30.0)
    prob = ModalProblem(
        line=line_model(L0),
        medium=medium,
        end_a=fixed(list(pos[0])),
        end_b=fixed(list(pos[-1])),
        static=st,
        n_modes=6,
    )
    dims = [b.shape[1] for b in node_bases(prob)]
    assert dims[0] == 0 and dims[-1] == 0 and dims[1:-1] == [3] * (N - 1)
    res = modal_analysis(prob)
    assert res.success
    bounce = np.sqrt(prob.line.weight[0] / 1e-3 / prob.line.mass[0]) / (2 * np.pi)
    assert res.frequency.max() < 0.2 * bounce
    assert np.abs(res.mode_shape[:, 1:11, 2]).max() < 1e-2


def test_mode_shapes_normalised_and_interpolated() -> None:
    res = modal_analysis(sagged([0, 0, 0], [95, 0, 0]))
    mag = np.linalg.norm(res.mode_shape, axis=2)
    np.testing.assert_allclose(mag.max(axis=1), 1.0, rtol=1e-12)
    # the sign convention (dynamics.modal.normalise_modes): of the nodes whose displacement
    # ties with the largest (within SIGN_TIE) the first, of its components tied with its
    # largest the first, is positive
    for U, m in zip(res.mode_shape, mag, strict=True):
        k = int(np.flatnonzero(m >= (1.0 - SIGN_TIE) * m.max())[0])
        size = np.abs(U[k])
        assert U[k, int(np.flatnonzero(size >= (1.0 - SIGN_TIE) * size.max())[0])] > 0.0
    assert np.all(np.diff(res.frequency) >= 0.0)
    fine = res.shape_at(np.linspace(0, res.s[-1], 7))
    assert fine.shape == (8, 7, 3)
    np.testing.assert_allclose(res.shape_at(res.s), res.mode_shape, atol=1e-15)


def test_failures_are_data_not_exceptions() -> None:
    prob = sagged([0, 0, 0], [95, 0, 0])
    s = prob.static.s
    failed_static = StaticResult.failed(s, STATUS_NO_SOLUTION, "no catenary")
    from dataclasses import replace

    res = modal_analysis(replace(prob, static=failed_static))
    assert res.status == STATUS_STATIC_FAILED and "no catenary" in res.message
    assert np.all(np.isnan(res.frequency)) and res.frequency.shape == (8,)

    slack = replace(prob.static, tension=np.where(s > 50, -1.0, prob.static.tension))
    res = modal_analysis(replace(prob, static=slack))
    assert res.status == STATUS_SLACK and "slack" in res.message
    assert np.all(np.isnan(res.mode_shape))

    nan_pos = replace(
        prob.static, position=np.where(s[:, None] > 50, np.nan, 0.0) + prob.static.position
    )
    res = modal_analysis(replace(prob, static=nan_pos))
    assert res.status == STATUS_NUMERICAL and "non-finite" in res.message

    res = modal_analysis(replace(prob, n_modes=10_000))
    assert res.status == STATUS_NUMERICAL and "degrees of freedom" in res.message

    res = modal_analysis(prob, deadline=time.monotonic() - 1.0)
    assert res.status == STATUS_TIME_LIMIT


def test_modal_settings() -> None:
    assert ModalSettings().modes == 10
    assert ModalSettings(modes=10).n_elements == 200
    assert ModalSettings(modes=2).n_elements == 100
    assert ModalSettings(modes=3, elements=7).n_elements == 7
    with pytest.raises(ValidationError, match="modes"):
        ModalSettings(modes=0)
    with pytest.raises(ValidationError, match=r"elements = 3 gives at most 6 degrees"):
        ModalSettings(modes=10, elements=3)
    with pytest.raises(ValidationError, match="extra"):
        ModalSettings(modes=3, shapes=True)  # type: ignore[call-arg]


def test_banded_and_shift_invert_solvers_agree(monkeypatch: pytest.MonkeyPatch) -> None:
    """Both eigen solvers (LAPACK banded for small models, ARPACK shift-invert about 0
    otherwise) give the same modes. Tolerance: the banded solver's eigenvalues carry an
    absolute error ~ eps * lambda_max, with lambda_max <= 4 EA / (m h^2) (the axial
    chain), i.e. a relative frequency error eps * lambda_max / (2 omega^2); ARPACK's is
    ~1e-13 relative."""
    import cablestudy.dynamics.modal as modal

    prob = sagged([0, 0, 0], [90, 0, -10], n=120)
    monkeypatch.setattr(modal, "BANDED_LIMIT", 10**9)
    banded = modal.modal_analysis(prob)
    monkeypatch.setattr(modal, "BANDED_LIMIT", 0)
    arpack = modal.modal_analysis(prob)
    h = 102.0 / 120
    lam_max = 4 * 1.0e7 / (2.0 * h**2)
    tol = np.finfo(float).eps * lam_max / (2 * (2 * np.pi * banded.frequency) ** 2) + 1e-12
    assert np.all(np.abs(arpack.frequency / banded.frequency - 1) <= tol)
    np.testing.assert_allclose(np.abs(arpack.mode_shape), np.abs(banded.mode_shape), atol=1e-7)


def test_graded_arc_lengths_equal_travel_time() -> None:
    """Uniform tension gives uniform elements; tension linear in s gives nodes of equal
    tau = 2 sqrt(m) (sqrt(T) - sqrt(T0)) / w (exact for linear T from any sampling);
    joints are kept."""
    from cablestudy.dynamics.modal import graded_arc_lengths, snap_to_samples

    s = np.linspace(0.0, 50.0, 6)
    mass = np.full(6, 3.0)
    np.testing.assert_allclose(
        graded_arc_lengths(s, np.full(6, 7.0), mass, 10), np.linspace(0, 50, 11), atol=1e-12
    )
    T0, w = 100.0, 80.0
    nodes = graded_arc_lengths(s, T0 + w * s, mass, 16)
    tau = 2 * np.sqrt(3.0) * (np.sqrt(T0 + w * nodes) - np.sqrt(T0)) / w
    np.testing.assert_allclose(np.diff(tau), tau[-1] / 16, rtol=1e-12)
    assert nodes[1] - nodes[0] < 0.2 * (nodes[-1] - nodes[-2])
    with_joint = graded_arc_lengths(s, T0 + w * s, mass, 16, joints=np.array([0.0, 21.0, 50.0]))
    assert 21.0 in with_joint and len(with_joint) == 18

    fine = np.linspace(0.0, 1.0, 11)
    np.testing.assert_array_equal(
        snap_to_samples(fine, np.array([0.0, 0.14, 0.16, 0.5, 1.0])), [0, 1, 2, 5, 10]
    )
