"""The system's assembly of all lines in one call (:func:`.assembly.assemble_lines` on
the packed arrays, :func:`.system_kernels.assemble_all`) is each line's own assembly
(:func:`.assembly.assemble`): the same forces, tangents and tensions to the last bit,
for lines that exercise every per-line offset of the packing (bending with its two-off
blocks, a clamped end, a table law's knots after another line's, per-line seabed and
friction, current, transverse damping, an attached body)."""

from __future__ import annotations

import numpy as np
import pytest

from cablestudy.dynamics.assembly import Workspace, assemble
from cablestudy.dynamics.discrete_line import DynamicExtras, discretise, discretise_nodes
from cablestudy.dynamics.system_kernels import assemble_all
from cablestudy.dynamics.system_model import FreePoints, pack, work_arrays
from cablestudy.physics.axial import TableLaw
from cablestudy.statics.base import LineModel, Medium

G = 9.80665


def _line(length: float, ei: float, law: object | None) -> LineModel:
    def arr(a: float, b: float) -> np.ndarray:
        return np.array([a, b])

    return LineModel(
        length=arr(0.4 * length, 0.6 * length),
        weight=arr(50.0, 5.0),
        mass=arr(5.6, 0.9),
        axial_stiffness=arr(5e7, 2e6),
        diameter=arr(0.03, 0.02),
        drag_normal=arr(2.4, 1.2),
        drag_tangential=arr(0.4, 0.01),
        added_mass_normal=arr(1.0, 1.0),
        added_mass_tangential=arr(0.1, 0.0),
        bending_stiffness=arr(ei, ei),
        damping_ratio=arr(0.05, 0.1),
        attachment_s=np.array([0.4 * length]),
        attachment_force=np.array([[0.0, 0.0, -5.0 * G]]),
        attachment_mass=np.array([5.0]),
        attachment_volume=np.array([0.0]),
        axial_law=(law, law) if law is not None else (),
    )


def test_all_lines_in_one_call_are_each_line_bit_for_bit() -> None:
    medium = Medium(
        density=1025.0,
        gravity=G,
        depth=30.0,
        current_z=np.array([-30.0, 0.0]),
        current_velocity=np.array([[0.2, 0.0, 0.0], [0.8, 0.3, 0.0]]),
    )
    table = TableLaw((0.0, 0.005, 0.01, 0.02, 0.04), (0.0, 1.0e4, 3.0e4, 9.0e4, 2.5e5))
    other = TableLaw((0.0, 0.01, 0.03), (0.0, 2.0e4, 1.0e5))  # its knots after table's
    lines = [
        discretise(
            _line(40.0, 0.0, table),
            medium,
            7,
            DynamicExtras(
                seabed_stiffness=3e5,
                friction_axial=0.6,
                friction_lateral=0.9,
                transverse_damping=np.array([3.0, 1.0]),
            ),  # fmt: skip
        ),
        discretise(
            _line(30.0, 2e3, other),
            medium,
            6,
            DynamicExtras(clamp_direction=np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 0.0]])),
        ),
        discretise(_line(25.0, 5e2, None), medium, 5, DynamicExtras(seabed_stiffness=1e5)),
    ]
    assert lines[0].has_seabed and lines[1].has_bending and lines[0].law_knots.shape[0] > 0
    rng = np.random.default_rng(7)
    xs, vs = [], []
    for ln, stretch in zip(lines, (1.01, 1.01, 0.95), strict=True):
        n = ln.n_nodes
        # a sagging, wavy line across the seabed plane (z = -30): slack and taut
        # elements, nodes in and out of contact
        s = ln.s / ln.s[-1]
        x = np.stack([stretch * ln.s, 0.5 * np.sin(7.0 * s), -29.9 - 0.3 * np.sin(np.pi * s)], 1)
        xs.append(x + 0.02 * rng.standard_normal((n, 3)))
        vs.append(0.3 * rng.standard_normal((n, 3)))
    end_point = -np.ones((3, 2), dtype=np.int64)
    end_drive = np.arange(6).reshape(3, 2)
    points = FreePoints(mass=np.zeros(0), force=np.zeros((0, 3)), drag=np.zeros(0))
    pk = pack(lines, end_point, end_drive, points, -np.ones(6, dtype=np.int64))
    x, v = np.concatenate(xs), np.concatenate(vs)
    anchor = x + 0.01 * rng.standard_normal(x.shape)
    W = work_arrays(pk, x, v)
    taut = rng.random(pk.n_elements) < 0.5
    W[9][:] = taut
    W[12][:, :2] = rng.integers(-1, 3, size=(pk.n_nodes, 2))
    slips = W[12].copy()
    assemble_all(x, v, anchor, pk.S, W)
    for k, ln in enumerate(lines):
        work = Workspace(ln.n_elements)
        work.taut0[:] = taut[pk.eo[k] : pk.eo[k + 1]]
        work.slip_state[:] = slips[pk.no[k] : pk.no[k + 1]]
        nodes, els = slice(pk.no[k], pk.no[k + 1]), slice(pk.eo[k], pk.eo[k + 1])
        assemble(xs[k], vs[k], anchor[nodes], ln.kernel_args(), work.assemble_args())
        q = slice(pk.S[2][k], pk.S[2][k + 1])
        pairs = (
            (W[0][nodes], work.F), (W[1][nodes], work.K_d), (W[2][els], work.K_o),
            (W[3][q], work.K_o2), (W[4][nodes], work.C_d), (W[5][els], work.C_o),
            (W[6][nodes], work.M_d), (W[7][els], work.tension), (W[8][els], work.strain),
            (W[10][nodes], work.contact), (W[11][nodes], work.friction),
            (W[12][nodes], work.slip_state), (W[13][nodes], work.trial),
        )  # fmt: skip
        for j, (packed, own) in enumerate(pairs):
            assert np.array_equal(packed, own), (k, j)
    # the case exercises what it claims: contact, friction, slack and taut elements
    assert np.any(W[10] > 0.0) and np.any(W[11] != 0.0)
    assert np.any(W[7] == 0.0) and np.any(W[7] > 0.0)


def test_lines_share_a_discretisation_only_when_alike_in_every_input() -> None:
    """The system model discretises lines alike in every input once
    (:func:`cablestudy.dynamics.discrete_line.same_inputs`, arrays compared by value as
    the system model does): a copy is alike; a line that
    differs in one array entry, in one scalar of its extras, or in its medium is not."""
    from dataclasses import replace

    from cablestudy.dynamics.discrete_line import same_inputs

    def _equal(a: object, b: object) -> bool:
        return same_inputs(a, b, bitwise=False)

    table = TableLaw((0.0, 0.005, 0.01, 0.02, 0.04), (0.0, 1.0e4, 3.0e4, 9.0e4, 2.5e5))
    lm = _line(40.0, 0.0, table)
    med = Medium(density=1025.0, gravity=G, depth=30.0)
    ex = DynamicExtras(seabed_stiffness=3e5, transverse_damping=np.array([3.0, 1.0]))
    same = (_line(40.0, 0.0, table), replace(med), replace(ex))
    assert _equal((lm, med, ex), same)
    mass = lm.mass.copy()
    mass[1] *= 1.0 + 1e-12
    assert not _equal((lm, med, ex), (replace(lm, mass=mass), med, ex))
    assert not _equal((lm, med, ex), (lm, med, replace(ex, friction_axial=0.1)))
    assert not _equal((lm, med, ex), (lm, replace(med, depth=31.0), ex))
    assert not _equal((lm, med, ex), (_line(40.0, 0.0, None), med, ex))


def test_a_free_point_on_the_seabed_is_the_one_line_node_it_replaces() -> None:
    """A chain (12 m elements) and a wire (5 m) joined at a 2 t clump: its end nodes'
    seabed springs and dampers add up to the one line's node with the clump attached
    there, the spring per tributary length, the damper 2 zeta sqrt(k m) with the clump's
    mass in m (so the point lands as the node does), to round-off."""
    medium = Medium(density=1025.0, gravity=G, depth=100.0)
    seg = {"length": (36.0, 25.0), "weight": (400.0, 30.0), "mass": (50.0, 4.0)}

    def model(k: slice, mass: float | None) -> LineModel:
        one = {key: np.array(v[k]) for key, v in seg.items()}
        n = one["length"].size
        att = np.zeros(0) if mass is None else np.array([36.0])
        return LineModel(
            **one, axial_stiffness=np.full(n, 1e8), diameter=np.full(n, 0.05),
            drag_normal=np.ones(n), drag_tangential=np.zeros(n),
            added_mass_normal=np.ones(n), added_mass_tangential=np.zeros(n),
            bending_stiffness=np.zeros(n), damping_ratio=np.zeros(n), attachment_s=att,
            attachment_force=np.zeros((att.size, 3)), attachment_mass=np.full(att.size, 2e3),
            attachment_volume=np.zeros(att.size),
        )  # fmt: skip

    extras = DynamicExtras(seabed_stiffness=4e5, seabed_damping_ratio=0.7)
    s1, s2 = np.linspace(0.0, 36.0, 4), np.linspace(0.0, 25.0, 6)
    whole = discretise_nodes(model(slice(0, 2), 2e3), medium, np.r_[s1, 36.0 + s2[1:]], extras)
    parts = [
        discretise_nodes(model(slice(i, i + 1), None), medium, s, extras)
        for i, s in enumerate((s1, s2))
    ]
    point = FreePoints(mass=np.array([2e3]), force=np.zeros((1, 3)), drag=np.zeros(1))
    packed = pack(
        parts, np.array([[-1, 0], [0, -1]]), np.array([[0, -1], [-1, 1]]), point, np.array([-1, -1])
    )
    nodes = packed.S[38]
    for k, want in ((24, whole.seabed_stiffness[3]), (25, whole.seabed_damping[3])):
        assert packed.S[k][nodes].sum() == pytest.approx(want, rel=1e-14)
