"""Validation of the shooting static solver (``method: shooting``, vaz-patel seed) against
closed-form solutions, hand derivations and invariances.

Tolerances: the ODE is integrated with DOP853 at rtol = 1e-12, and Newton stops at a
scaled end residual of 1e-9 or below (then polishes towards the integration floor). The
global integration error of a smooth line over O(100) steps is a few times rtol, and the
dense-output interpolant used at the output nodes is 7th order, so positions and forces
agree with exact solutions to ~1e-10 of the length and tension scales; the tests use
1e-9 (a factor of ~10 margin) unless they say otherwise.
"""

from __future__ import annotations

import math
import time

import numpy as np
import pytest
import xarray as xr
from scipy.integrate import simpson
from scipy.optimize import brentq, fsolve

from cablestudy.physics.current import current_velocity
from cablestudy.physics.hydro import drag_per_length
from cablestudy.statics import (
    STATIC_SOLVERS,
    STATUS_OK,
    STATUS_TIME_LIMIT,
    EndCondition,
    LineModel,
    Medium,
    StaticProblem,
)
from cablestudy.statics.elastic_catenary import solve_between
from cablestudy.statics.shooting import ShootingSolver

SOLVER = STATIC_SOLVERS["shooting"]


def make_line(
    lengths: list[float],
    weight: float | list[float],
    stiffness: float | list[float],
    *,
    diameter: float = 0.05,
    drag_normal: float = 1.2,
    drag_tangential: float = 0.0,
    att_s: tuple[float, ...] = (),
    att_force: tuple[tuple[float, ...], ...] = (),
) -> LineModel:
    n = len(lengths)

    def col(v: float | list[float]) -> np.ndarray:
        return np.broadcast_to(np.asarray(v, dtype=float), (n,)).copy()

    return LineModel(
        length=col(lengths),
        weight=col(weight),
        mass=col(1.0),
        axial_stiffness=col(stiffness),
        diameter=col(diameter),
        drag_normal=col(drag_normal),
        drag_tangential=col(drag_tangential),
        added_mass_normal=col(1.0),
        added_mass_tangential=col(0.0),
        bending_stiffness=col(0.0),
        damping_ratio=col(0.0),
        attachment_s=np.asarray(att_s, dtype=float),
        attachment_force=np.asarray(att_force, dtype=float).reshape(-1, 3),
        attachment_mass=np.zeros(len(att_s)),
        attachment_volume=np.zeros(len(att_s)),
    )


def fixed(p: list[float]) -> EndCondition:
    return EndCondition(kind="fixed", position=np.asarray(p, dtype=float))


def force(f: list[float] | np.ndarray) -> EndCondition:
    return EndCondition(kind="force", force=np.asarray(f, dtype=float))


def mooring(h: list[float] | np.ndarray, z: float) -> EndCondition:
    return EndCondition(kind="mooring", force=np.array([h[0], h[1], 0.0]), z=z)


def medium(
    *,
    density: float = 1025.0,
    depth: float | None = None,
    current: list[tuple[float, float, float]] | None = None,
    **kw: float,
) -> Medium:
    """current: (z, speed, heading_deg) points."""
    if current:
        pts = sorted(current)
        z = np.array([p[0] for p in pts])
        h = np.radians([p[2] for p in pts])
        sp = np.array([p[1] for p in pts])
        vel = np.stack([sp * np.cos(h), sp * np.sin(h), 0 * sp], axis=1)
    else:
        z, vel = np.zeros(0), np.zeros((0, 3))
    return Medium(
        density=density, gravity=9.80665, depth=depth, current_z=z, current_velocity=vel, **kw
    )


def solve(problem: StaticProblem, solver: ShootingSolver = SOLVER):  # noqa: ANN201
    res = solver.solve(problem)
    assert res.status == STATUS_OK, res.message
    return res


#: a 3D drag-loaded case with a current that turns and weakens with depth
TURNING = [(0.0, 1.0, 0.0), (-150.0, 0.6, 60.0), (-300.0, 0.2, 120.0)]


# ----------------------------------------------------------------------------------
# exact elastic catenary (Irvine 1981, cablestudy.statics.elastic_catenary)

CATENARY_CASES = {
    # name: (B position, L, w, EA)
    "slack": ([80.0, 0.0, -10.0], 150.0, 30.0, 1e8),
    "taut": ([99.5, 0.0, 5.0], 100.0, 10.0, 1e6),  # stretched by ~0.1 %
    "inclined-3d": ([60.0, 45.0, -50.0], 120.0, 250.0, 5e8),
    "near-vertical": ([0.5, 0.2, -95.0], 100.0, 40.0, 1e7),
    "dodaran-fig4": ([92.5, 0.0, -8.6], 100.0, 2.466 * 9.80665, 6.283e7),
}


@pytest.mark.parametrize("name", sorted(CATENARY_CASES))
@pytest.mark.parametrize("kind", ["fixed", "force", "mooring", "force-mirrored"])
def test_exact_catenary_all_end_kinds(name: str, kind: str) -> None:
    """All end kinds reproduce Irvine's exact elastic catenary: B fixed; B given the
    exact force; B given the exact horizontal force and height; and A given the exact
    force with B fixed (mirrored)."""
    pb, L, w, EA = CATENARY_CASES[name]
    line = make_line([L], w, EA)
    s = np.linspace(0.0, L, 41)
    exact = solve_between(np.zeros(3), np.array(pb), L, w, EA, s, tolerance=1e-14)
    if kind == "fixed":
        a, b = fixed([0, 0, 0]), fixed(pb)
    elif kind == "force":
        a, b = fixed([0, 0, 0]), force(-exact.force_b)
    elif kind == "mooring":
        a, b = fixed([0, 0, 0]), mooring(-exact.force_b[:2], pb[2])
    else:
        a, b = force(-exact.force_a), fixed(pb)
    res = solve(StaticProblem(line=line, medium=medium(density=0.0), end_a=a, end_b=b, n_nodes=41))
    t_scale = float(np.max(exact.tension))
    assert np.max(np.abs(res.position - exact.position)) < 1e-9 * L
    assert np.max(np.abs(res.tension - exact.tension)) < 1e-9 * t_scale
    assert np.max(np.abs(res.force_a - exact.force_a)) < 1e-9 * t_scale
    assert np.max(np.abs(res.force_b - exact.force_b)) < 1e-9 * t_scale


def test_vertical_line_and_pole_restarts() -> None:
    """A line hanging exactly vertically (tangent on the azimuth pole of the seed's
    angles) and a U-shaped line whose tangent passes through vertical: both equal the
    exact catenary; T(s) of the vertical line is T_B + w (L - s) plus the stretch-free
    weight balance."""
    L, w, EA = 100.0, 40.0, 1e7
    line = make_line([L], w, EA)
    res = solve(
        StaticProblem(
            line=line,
            medium=medium(density=0.0),
            end_a=fixed([0, 0, 0]),
            end_b=fixed([0.0, 0.0, -100.05]),
            n_nodes=21,
        )
    )
    exact = solve_between(
        np.zeros(3), np.array([0.0, 0.0, -100.05]), L, w, EA, res.s, tolerance=1e-14
    )
    assert np.max(np.abs(res.position - exact.position)) < 1e-9 * L
    assert np.max(np.abs(res.tension - exact.tension)) < 1e-9 * exact.tension[0]
    # vertical balance of the whole line: tension difference = weight
    assert abs(res.tension[0] - res.tension[-1] - w * L) < 1e-9 * w * L
    # U shape: the tangent turns from down through horizontal to up
    res = solve(
        StaticProblem(
            line=line,
            medium=medium(density=0.0),
            end_a=fixed([0, 0, 0]),
            end_b=fixed([10.0, 5.0, 0.0]),
            n_nodes=41,
        )
    )
    exact = solve_between(np.zeros(3), np.array([10.0, 5.0, 0.0]), L, w, EA, res.s, tolerance=1e-14)
    assert np.max(np.abs(res.position - exact.position)) < 1e-9 * L


def test_attachment_and_segments_against_piecewise_catenaries() -> None:
    """A segmented line (chain-wire-chain) with a clump weight and a buoy: between
    consecutive segment boundaries and attachments every piece is an exact elastic
    catenary between the solved points (each piece is uniform and unloaded), and the
    force jumps at the attachments equal the attachment forces."""
    lengths = [120.0, 200.0, 80.0]
    w = [900.0, 60.0, 900.0]
    EA = [8e8, 2e8, 8e8]
    att_s = (60.0, 250.0)
    att_force = ((0.0, 0.0, -30000.0), (0.0, 0.0, 25000.0))
    line = make_line(lengths, w, EA, att_s=att_s, att_force=att_force)
    problem = StaticProblem(
        line=line,
        medium=medium(density=0.0),
        end_a=fixed([0, 0, -300]),
        end_b=fixed([280.0, 60.0, 0.0]),
        n_nodes=401,
    )
    res = solve(problem)
    knots = [0.0, 60.0, 120.0, 250.0, 320.0, 400.0]
    seg_w = [900.0, 900.0, 60.0, 60.0, 900.0]
    seg_ea = [8e8, 8e8, 2e8, 2e8, 8e8]
    ends_of = {}
    for k0, k1, wk, ek in zip(knots[:-1], knots[1:], seg_w, seg_ea, strict=True):
        i0, i1 = int(round(k0)), int(round(k1))  # nodes every 1 m
        pa, pb = res.position[i0], res.position[i1]
        sub = solve_between(pa, pb, k1 - k0, wk, ek, res.s[i0 : i1 + 1] - k0, tolerance=1e-14)
        assert np.max(np.abs(sub.position - res.position[i0 : i1 + 1])) < 1e-8 * 400.0
        ends_of[(k0, k1)] = sub
    # force balance at each attachment: F(s+) = F(s-) - P, with F the tension vector
    for s_k, p in zip(att_s, att_force, strict=True):
        left = next(v for (k0, k1), v in ends_of.items() if k1 == s_k)
        right = next(v for (k0, k1), v in ends_of.items() if k0 == s_k)
        jump = right.force_a - (-left.force_b)
        assert np.allclose(jump, -np.asarray(p), atol=1e-7 * 30000.0)
        # the output node at the attachment holds the tension on its B side (s+)
        i = int(round(s_k))
        assert abs(res.tension[i] - np.linalg.norm(right.force_a)) < 1e-7 * 30000.0
    # global balance: the ends carry the weight and the attachment loads
    total = np.array([0.0, 0.0, -float(np.dot(w, lengths))]) + np.sum(att_force, axis=0)
    assert np.allclose(res.force_a + res.force_b, total, atol=1e-9 * abs(total[2]))


# ----------------------------------------------------------------------------------
# drag


def test_drag_integral_balances_end_forces() -> None:
    """Global force balance of a 3D line in a turning current: the end forces equal the
    weight plus the drag integrated along the solved shape, evaluated independently with
    cablestudy.physics.hydro.drag_per_length (dodaran eqs. 38-39) per stretched length
    |dr/ds| and Simpson's rule on 2001 nodes. The tangent from second-order differences
    and Simpson's rule carry an error ~ (h/L)^2 ~ 1e-7, hence the 1e-6 tolerance."""
    L, w = 400.0, 25.0
    line = make_line([L], w, 5e7, diameter=0.08, drag_normal=1.2, drag_tangential=0.01)
    med = medium(current=TURNING)
    res = solve(
        StaticProblem(
            line=line,
            medium=med,
            end_a=fixed([0, 0, -300]),
            end_b=fixed([250.0, 0.0, 0.0]),
            n_nodes=2001,
        )
    )
    drdS = np.gradient(res.position, res.s, axis=0, edge_order=2)
    stretch = np.linalg.norm(drdS, axis=1)
    tangent = drdS / stretch[:, None]
    u = current_velocity(res.position[:, 2], med.current_z, med.current_velocity)
    f = (
        drag_per_length(
            u,
            tangent,
            density=med.density,
            diameter=np.full(len(u), 0.08),
            drag_normal=np.full(len(u), 1.2),
            drag_tangential=np.full(len(u), 0.01),
        )
        * stretch[:, None]
    )
    drag = simpson(f, x=res.s, axis=0)
    total = drag + np.array([0.0, 0.0, -w * L])
    scale = float(np.linalg.norm(res.force_a))
    assert np.linalg.norm(drag) > 0.2 * w * L  # the drag is a large part of the load
    assert np.allclose(res.force_a + res.force_b, total, atol=1e-6 * scale)
    # the stretch follows Hooke's law: |dr/ds| = 1 + T/EA
    assert np.max(np.abs(stretch - (1.0 + res.tension / 5e7))[5:-5]) < 1e-7


def critical_angle(w: float, rho: float, cn: float, d: float, u: float) -> float:
    """Pode (1951, DTMB report 687): with normal drag only, a straight cable at angle phi
    to a uniform current of speed U balances its normal weight component w cos(phi)
    against the normal drag 1/2 rho Cn d U^2 sin^2(phi), so
    cos(phi) / sin^2(phi) = 1/2 rho Cn d U^2 / w  [rad, from the current direction]."""
    k = 0.5 * rho * cn * d * u * u / w
    c = (-1.0 + math.sqrt(1.0 + 4.0 * k * k)) / (2.0 * k)  # k c^2 + c - k = 0
    return math.acos(c)


def test_pode_critical_angle_free_end() -> None:
    """A long cable hanging from a fixed point with a free lower end in a uniform
    current, normal drag only: the free end starts along its load, which is the critical
    angle, and the straight line at that angle satisfies the equations exactly, so the
    whole cable lies at Pode's critical angle, with T growing linearly, dT/ds = w sin(phi)
    (drag has no tangential part). Drag acts per stretched length, so the balance holds
    with the strain (1 + T/EA) on the drag: EA = 1e16 N makes that factor 1 to 1e-12."""
    w, rho, cn, d, U = 20.0, 1025.0, 1.2, 0.05, 1.0
    L = 1000.0
    line = make_line([L], w, 1e16, diameter=d, drag_normal=cn)
    res = solve(
        StaticProblem(
            line=line,
            medium=medium(current=[(0.0, U, 0.0)]),
            end_a=fixed([0, 0, 0]),
            end_b=force([0, 0, 0]),
            n_nodes=21,
        )
    )
    phi = critical_angle(w, rho, cn, d, U)
    seg = np.diff(res.position, axis=0)
    angle = np.arctan2(-seg[:, 2], seg[:, 0])
    assert np.max(np.abs(angle - phi)) < 1e-9
    assert np.max(np.abs(seg[:, 1])) < 1e-9 * L
    assert np.max(np.abs(res.tension - w * np.sin(phi) * (L - res.s))) < 1e-9 * w * L


def test_pode_critical_angle_is_approached() -> None:
    """With a small towing force at the lower end pointing off the critical angle, the
    cable turns towards the critical angle as the tension grows. Linearising
    dphi/ds = -f.n / T about phi_c gives a deviation ~ (T/T_end)^(-p) with
    p = (d(f.n)/dphi) / (w sin phi_c) > 1 here, so 500 m from the end, where T/T_end ~ 50,
    the deviation is below 1 % of the initial 0.5 rad."""
    w, rho, cn, d, U = 20.0, 1025.0, 1.2, 0.05, 1.0
    phi = critical_angle(w, rho, cn, d, U)
    line = make_line([1000.0], w, 1e9, diameter=d, drag_normal=cn)
    off = phi - 0.5
    t_end = 100.0 * np.array([math.cos(off), 0.0, -math.sin(off)])
    res = solve(
        StaticProblem(
            line=line,
            medium=medium(current=[(0.0, U, 0.0)]),
            end_a=fixed([0, 0, 0]),
            end_b=force(t_end),
            n_nodes=101,
        )
    )
    seg = np.diff(res.position, axis=0)
    angle = np.arctan2(-seg[:, 2], seg[:, 0])
    assert abs(angle[-1] - phi) > 0.05  # near B the line is off critical
    assert np.max(np.abs(angle[:50] - phi)) < 0.005  # far from B it is at phi_c


def test_convergence_as_rtol_is_tightened() -> None:
    """The solution converges as the integration tolerance is tightened: the difference
    to the rtol = 1e-13 solution falls with rtol, and at 1e-11 it is below
    1e-9 of the length and tension scales."""
    line = make_line(
        [250.0, 150.0],
        [40.0, 15.0],
        [3e8, 5e7],
        diameter=0.06,
        drag_tangential=0.01,
        att_s=(250.0,),
        att_force=((0.0, 0.0, 2000.0),),
    )
    problem = StaticProblem(
        line=line,
        medium=medium(current=TURNING),
        end_a=fixed([0, 0, -280]),
        end_b=fixed([260.0, 40.0, -5.0]),
        n_nodes=41,
        tolerance=1e-12,
    )
    ref = solve(problem, ShootingSolver(rtol=1e-13))
    errors = []
    for rtol in (1e-6, 1e-8, 1e-11):
        res = solve(problem, ShootingSolver(rtol=rtol))
        errors.append(
            max(
                np.max(np.abs(res.position - ref.position)) / 400.0,
                np.max(np.abs(res.tension - ref.tension)) / ref.tension.max(),
            )
        )
    assert errors[0] > errors[1] > errors[2]
    assert errors[2] < 1e-9


def test_touchdown_with_drag_converged_to_1e8() -> None:
    """A grounded line with friction in a turning current (the shooting map is
    ill-conditioned: a small change of the touchdown tension moves the far end a lot):
    the default solver agrees with rtol = 1e-13 to 1e-8 of the length and tension, the
    accuracy the comparison with the semi-analytic solver needs (1e-6)."""
    line = make_line([600.0], 200.0, 1e9, diameter=0.1, drag_tangential=0.01)
    problem = StaticProblem(
        line=line,
        medium=medium(depth=200.0, friction=0.5, current=TURNING),
        end_a=fixed([0, 0, -200]),
        end_b=fixed([500.0, 100.0, 0.0]),
        n_nodes=61,
        tolerance=1e-12,
    )
    ref = solve(problem, ShootingSolver(rtol=1e-13))
    res = solve(problem)
    assert res.laid_length > 100.0
    assert np.max(np.abs(res.position - ref.position)) < 1e-8 * 600.0
    assert np.max(np.abs(res.tension - ref.tension)) < 1e-8 * ref.tension.max()
    assert abs(res.laid_length - ref.laid_length) < 1e-8 * 600.0


# ----------------------------------------------------------------------------------
# invariances


def _problem_3d(
    rotation: float = 0.0, mirror: bool = False, swap: bool = False, seabed: bool = False
) -> StaticProblem:
    """A drag-loaded two-segment line with an attachment; optionally rotated about z by
    ``rotation`` [rad] (positions, current headings and seabed heading), mirrored in y,
    or with its ends swapped (segments and attachments reversed)."""
    sign = -1.0 if mirror else 1.0
    c, s_ = math.cos(rotation), math.sin(rotation)

    def tr(p: list[float]) -> list[float]:
        x, y, z = p[0], sign * p[1], p[2]
        return [c * x - s_ * y, s_ * x + c * y, z]

    current = [(z, sp, sign * hd + math.degrees(rotation)) for z, sp, hd in TURNING]
    lengths, w, ea = [300.0, 200.0], [300.0, 30.0], [6e8, 8e7]
    att_s, att_f = (300.0,), ((0.0, 0.0, 4000.0),)
    a, b = fixed(tr([0.0, 0.0, -300.0])), fixed(tr([330.0, 80.0, -20.0]))
    if swap:
        lengths, w, ea = lengths[::-1], w[::-1], ea[::-1]
        att_s = (500.0 - att_s[0],)
        a, b = b, a
    line = make_line(
        lengths, w, ea, diameter=0.08, drag_tangential=0.01, att_s=att_s, att_force=att_f
    )
    kw = {}
    if seabed:
        kw = dict(
            depth=300.0,
            seabed_slope=math.radians(3.0),
            seabed_heading=rotation + sign * math.radians(20.0),
            friction=0.3,
        )
        # the anchor at x = y = 0 is on the plane through (0, 0, -depth)
    return StaticProblem(
        line=line, medium=medium(current=current, **kw), end_a=a, end_b=b, n_nodes=51
    )


@pytest.mark.parametrize("seabed", [False, True])
def test_invariance_swap_rotate_mirror(seabed: bool) -> None:
    """The same physical line defined B to A, rotated about the vertical with its current
    and seabed, or mirrored in y gives the same shape and end forces (to the Newton and
    integration tolerances, 1e-8 relative)."""
    ref = solve(_problem_3d(seabed=seabed))
    L, F = 500.0, float(np.linalg.norm(ref.force_a)) + float(np.linalg.norm(ref.force_b))
    if seabed:
        assert ref.laid_length > 10.0

    swapped = solve(_problem_3d(swap=True, seabed=seabed))
    assert np.max(np.abs(swapped.position[::-1] - ref.position)) < 1e-8 * L
    # (the node at the attachment, s = 300 m, holds the tension on either side of it)
    smooth = ref.s != 300.0
    assert np.max(np.abs(swapped.tension[::-1] - ref.tension)[smooth]) < 1e-8 * F
    assert np.allclose(swapped.force_a, ref.force_b, atol=1e-8 * F)
    assert np.allclose(swapped.force_b, ref.force_a, atol=1e-8 * F)
    assert abs(swapped.laid_length - ref.laid_length) < 1e-7 * L

    rot = 0.7
    rotated = solve(_problem_3d(rotation=rot, seabed=seabed))
    R = np.array([[math.cos(rot), -math.sin(rot), 0], [math.sin(rot), math.cos(rot), 0], [0, 0, 1]])
    assert np.max(np.abs(rotated.position - ref.position @ R.T)) < 1e-8 * L
    assert np.allclose(rotated.force_b, R @ ref.force_b, atol=1e-8 * F)

    mirrored = solve(_problem_3d(mirror=True, seabed=seabed))
    M = np.diag([1.0, -1.0, 1.0])
    assert np.max(np.abs(mirrored.position - ref.position @ M)) < 1e-8 * L
    assert np.allclose(mirrored.force_a, M @ ref.force_a, atol=1e-8 * F)


# ----------------------------------------------------------------------------------
# seabed


def _hand_touchdown(
    L: float, w: float, EA: float, D: float, X: float, mu: float
) -> tuple[float, float]:
    """Hand derivation for an anchor on a flat seabed at depth D and a fairlead at
    horizontal distance X on the surface, no current. The suspended part is an elastic
    catenary starting horizontally at the touchdown point (V = 0 there) with horizontal
    tension H and unstretched length Ls (Irvine 1981, eqs. 2.26-2.27 with V_A = 0):
        x_s = H Ls / EA + (H / w) asinh(w Ls / H)
        D   = w Ls^2 / (2 EA) + (H / w) (sqrt(1 + (w Ls / H)^2) - 1).
    On the laid length Lb = L - Ls the tension falls from H by mu w per metre towards the
    anchor, never below zero, so the laid part stretches by (1/EA) * int max(0, H - mu w
    (Lb - s)) ds. Returns (H, Ls)."""

    def laid_stretch(H: float, Lb: float) -> float:
        if mu == 0.0:
            return H * Lb / EA
        if H <= mu * w * Lb:
            return H * H / (2.0 * mu * w * EA)
        return (H - 0.5 * mu * w * Lb) * Lb / EA

    def eqs(v: np.ndarray) -> list[float]:
        H, Ls = v
        xs = H * Ls / EA + (H / w) * math.asinh(w * Ls / H)
        zs = w * Ls * Ls / (2 * EA) + (H / w) * (math.sqrt(1 + (w * Ls / H) ** 2) - 1)
        return [(L - Ls) + laid_stretch(H, L - Ls) + xs - X, zs - D]

    H, Ls = fsolve(eqs, [w * D, 1.5 * D], xtol=1e-13)
    assert max(abs(e) for e in eqs(np.array([H, Ls]))) < 1e-9 * L
    return float(H), float(Ls)


@pytest.mark.parametrize("mu", [0.0, 0.3, 2.0])
def test_seabed_touchdown_hand_derivation(mu: float) -> None:
    """Flat seabed, no current, anchor on the seabed: touchdown, laid length, fairlead
    force and anchor tension max(0, H - mu w Lb) from the hand derivation above; mu = 2
    makes the friction capacity exceed H, so the anchor tension is zero."""
    L, w, EA, D, X = 600.0, 200.0, 1e9, 200.0, 500.0
    H, Ls = _hand_touchdown(L, w, EA, D, X, mu)
    res = solve(
        StaticProblem(
            line=make_line([L], w, EA),
            medium=medium(depth=D, friction=mu),
            end_a=fixed([0.0, 0.0, -D]),
            end_b=fixed([X, 0.0, 0.0]),
            n_nodes=61,
        )
    )
    Lb = L - Ls
    assert abs(res.laid_length - Lb) < 1e-8 * L
    assert np.allclose(res.force_b, [-H, 0.0, -w * Ls], atol=1e-8 * w * L)
    anchor = max(0.0, H - mu * w * Lb)
    assert np.allclose(res.force_a, [anchor, 0.0, 0.0], atol=1e-8 * w * L)
    on_bed = res.s <= Lb
    assert np.allclose(res.position[on_bed, 2], -D, atol=1e-9 * L)
    assert np.all(res.position[~on_bed, 2] > -D)
    if mu == 2.0:
        assert anchor == 0.0 and res.tension[0] == 0.0


def test_seabed_mooring_end_hand_derivation() -> None:
    """Mooring end (horizontal force H and height at the fairlead) with the anchor on a
    flat seabed: the suspended length solves D = w Ls^2/(2 EA) + (H/w)(sqrt(1+(w Ls/H)^2)
    - 1), the fairlead's vertical force is w Ls; mirrored (fairlead as end A) agrees."""
    L, w, EA, D, H = 800.0, 150.0, 5e8, 250.0, 40000.0

    def zs(Ls: float) -> float:
        return w * Ls * Ls / (2 * EA) + (H / w) * (math.sqrt(1 + (w * Ls / H) ** 2) - 1) - D

    Ls = brentq(zs, 1.0, L, xtol=1e-13)
    line = make_line([L], w, EA)
    med = medium(depth=D)
    res = solve(
        StaticProblem(
            line=line, medium=med, end_a=fixed([0.0, 0.0, -D]), end_b=mooring([H, 0.0], 0.0)
        )
    )
    assert abs(res.laid_length - (L - Ls)) < 1e-8 * L
    assert np.allclose(res.force_b, [-H, 0.0, -w * Ls], atol=1e-8 * w * L)
    mirrored = solve(
        StaticProblem(
            line=line, medium=med, end_a=mooring([-H, 0.0], 0.0), end_b=fixed([0.0, 0.0, -D])
        )
    )
    assert abs(mirrored.laid_length - (L - Ls)) < 1e-8 * L
    assert np.allclose(mirrored.force_a, [H, 0.0, -w * Ls], atol=1e-8 * w * L)


def test_sloped_seabed_tangent_touchdown() -> None:
    """On a seabed sloping at angle a, falling from the anchor towards the fairlead,
    without friction: the laid part is straight down the slope and its tension falls by
    w sin(a) per metre towards the touchdown point, so T_anchor = T_tdp + w sin(a) Lb; the
    suspended part leaves the seabed tangentially, so the tension vector at touchdown is
    along the slope, T_tdp = H / cos(a) with H the (constant) horizontal tension of the
    suspended part, and the line next to the touchdown point descends at angle a."""
    a = math.radians(5.0)
    L, w, EA, D = 700.0, 200.0, 1e9, 200.0
    med = medium(depth=D, seabed_slope=a, seabed_heading=math.pi)
    res = solve(
        StaticProblem(
            line=make_line([L], w, EA),
            medium=med,
            end_a=fixed([0.0, 0.0, -D]),
            end_b=fixed([560.0, 0.0, 0.0]),
            n_nodes=1401,
        )
    )
    Lb = res.laid_length
    assert 50.0 < Lb < L
    on = res.s <= Lb
    bed = -D - math.tan(a) * res.position[:, 0]
    assert np.allclose(res.position[on, 2], bed[on], atol=1e-9 * L)
    assert np.all(res.position[~on, 2] > bed[~on])
    H = -res.force_b[0]
    expected = H / math.cos(a) + w * math.sin(a) * Lb
    assert abs(np.linalg.norm(res.force_a) - expected) < 1e-8 * w * L
    assert abs(math.atan2(res.force_a[2], res.force_a[0]) + a) < 1e-12
    # the suspended part is Irvine's catenary from the touchdown point (found from the
    # laid length and its stretch under the linearly varying tension) to the fairlead,
    # and that catenary starts along the slope with tension T_tdp
    t_anchor = float(np.linalg.norm(res.force_a))
    t_tdp = t_anchor - w * math.sin(a) * Lb
    e = np.array([math.cos(a), 0.0, -math.sin(a)])
    tdp = np.array([0.0, 0.0, -D]) + e * Lb * (1.0 + 0.5 * (t_anchor + t_tdp) / EA)
    sus = solve_between(tdp, res.position[-1], L - Lb, w, EA, res.s[~on] - Lb, tolerance=1e-14)
    assert np.max(np.abs(sus.position - res.position[~on])) < 1e-8 * L
    assert abs(math.atan2(sus.force_a[2], sus.force_a[0]) + a) < 1e-8
    assert abs(np.linalg.norm(sus.force_a) - t_tdp) < 1e-8 * w * L


# ----------------------------------------------------------------------------------
# failures are data


def test_failures_are_reported() -> None:
    line = make_line([300.0], 50.0, 1e8)
    # the line would sag through the seabed between two raised supports
    res = SOLVER.solve(
        StaticProblem(
            line=line,
            medium=medium(depth=60.0),
            end_a=fixed([0, 0, -10]),
            end_b=fixed([100, 0, -10]),
        )
    )
    assert res.status != STATUS_OK and "seabed" in res.message
    assert np.all(np.isnan(res.position))
    # time limit
    res = SOLVER.solve(
        StaticProblem(
            line=line,
            medium=medium(current=TURNING),
            end_a=fixed([0, 0, -200]),
            end_b=fixed([200, 0, 0]),
        ),
        deadline=time.monotonic() - 1.0,
    )
    assert res.status == STATUS_TIME_LIMIT and "time limit" in res.message
    # both ends free: a config error listed before any work
    missing = SOLVER.unsupported(
        StaticProblem(line=line, medium=medium(), end_a=force([0, 0, 1]), end_b=force([0, 0, 1]))
    )
    assert missing and "fixed" in missing[0]
    # a slack weightless line has no unique shape
    res = SOLVER.solve(
        StaticProblem(
            line=make_line([100.0], 0.0, 1e8),
            medium=medium(),
            end_a=fixed([0, 0, 0]),
            end_b=fixed([50, 0, 0]),
        )
    )
    assert res.status != STATUS_OK and res.message


# ----------------------------------------------------------------------------------
# end to end


def test_yaml_to_netcdf(tmp_path) -> None:  # noqa: ANN001
    """A study with method: shooting through the CLI to netCDF: a mooring with a laid
    length, a turning current and a sweep over the current speed."""
    from cablestudy.cli import main

    cfg = tmp_path / "shoot.yaml"
    cfg.write_text("""
name: shoot-e2e
environment:
  fluid: water
  depth: 200.0
  seabed: {friction: 0.5}
  current:
    - {z: 0.0, speed: 0.8, heading_deg: 30.0}
    - {z: -200.0, speed: 0.1, heading_deg: 90.0}
line:
  segments:
    - {length: 300.0, diameter: 0.1, weight_in_fluid: 1500.0, axial_stiffness: 8.0e8}
    - {length: 400.0, diameter: 0.08, weight_in_fluid: 200.0, axial_stiffness: 3.0e8,
       drag_tangential: 0.01}
  attachments:
    - {s: 650.0, force: [0.0, 0.0, 20000.0], name: buoy}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -200.0]}
  b: {kind: mooring, force: [150000.0, 0.0], z: -5.0}
analysis:
  static: {method: shooting, nodes: 71}
sweep:
  environment.current.0.speed: [0.0, 0.8]
""")
    assert main(["run", str(cfg), "--out", str(tmp_path)]) == 0
    ds = xr.load_dataset(tmp_path / "shoot-e2e.nc")
    assert ds["status"].values.tolist() == [0, 0], ds["message"].values
    assert ds["z"].sizes["s"] == 71
    fb = ds["force_b"].values
    assert np.allclose(fb[:, 0], -150000.0, rtol=1e-8)  # the mooring condition holds
    assert np.allclose(ds["z"].values[:, -1], -5.0, atol=1e-7)
    assert np.all(ds["laid_length"].values > 0.0)
    y_b = np.abs(ds["y"].values[:, -1])
    assert y_b[1] > y_b[0] + 1.0  # the current pushes it sideways
    assert np.all(ds["static_iterations"].values >= 0)


# ----------------------------------------------------------------------------------
# installation (vaz-patel seed: pay-out speed and touchdown velocity)


def test_installation_payout_adds_mu_v_squared() -> None:
    """A cable paid out at speed V along itself in still water, with no tangential drag
    (the relative flow is tangential, so normal drag is zero): with EA -> infinity the
    normal equations hold T - mu V^2 in place of T (seed eqs. 4b-4c), the tangential one
    is unchanged, so T - mu V^2 solves the static equations: the shape is the static
    catenary between the same points and T = T_static + mu V^2, mu = m + Cm rho pi d^2/4
    (structural plus normal added mass per length)."""
    L, w, EA, d, V = 150.0, 30.0, 1e15, 0.05, 5.0
    line = make_line([L], w, EA, diameter=d, drag_normal=1.2, drag_tangential=0.0)
    mass = 4.0  # make_line sets 1 kg/m; use a line with 4 kg/m
    line = LineModel(**{**line.__dict__, "mass": np.array([mass])})
    pb = [80.0, 30.0, -10.0]
    problem = StaticProblem(
        line=line,
        medium=medium(),
        end_a=fixed([0, 0, 0]),
        end_b=fixed(pb),
        n_nodes=31,
        payout_speed=V,
    )
    res = solve(problem)
    exact = solve_between(np.zeros(3), np.array(pb), L, w, EA, res.s, tolerance=1e-14)
    mu_v2 = (mass + 1.0 * 1025.0 * math.pi * d * d / 4.0) * V * V
    assert mu_v2 > 0.1 * exact.tension.min()  # a large effect
    assert np.max(np.abs(res.position - exact.position)) < 1e-9 * L
    assert np.max(np.abs(res.tension - (exact.tension + mu_v2))) < 1e-9 * exact.tension.max()


def test_installation_tangential_drag_and_frame_velocity() -> None:
    """A cable hanging vertically from A with a weight force at B, hauled in from B
    towards A at speed V (negative pay-out is laying, positive is towards A): the water
    flows down along it, the tangential drag (dodaran eq. 39) pi/2 rho Ct d V^2 adds to
    the weight, T_A = T_B + (w + pi/2 rho Ct d V^2) L. And a laying frame moving at V0
    in a current U is the same as a frame at rest in the current U - V0."""
    L, w, d, ct, V = 200.0, 15.0, 0.04, 0.02, 2.0
    line = make_line([L], w, 1e15, diameter=d, drag_normal=1.2, drag_tangential=ct)
    res = solve(
        StaticProblem(
            line=line,
            medium=medium(),
            end_a=fixed([0, 0, 0]),
            end_b=force([0, 0, -1000.0]),
            n_nodes=11,
            payout_speed=V,
        )
    )
    drag = 0.5 * math.pi * 1025.0 * ct * d * V * V
    assert abs(res.tension[0] - (1000.0 + (w + drag) * L)) < 1e-9 * w * L
    assert np.max(np.abs(res.position[:, :2])) < 1e-9 * L

    v0 = np.array([0.4, -0.3, 0.0])
    moving = solve(
        StaticProblem(
            line=line,
            medium=medium(current=TURNING),
            end_a=fixed([0, 0, -150]),
            end_b=fixed([120, 40, 0]),
            n_nodes=21,
            touchdown_velocity=v0,
        )
    )
    turning = medium(current=TURNING)
    rest_medium = Medium(
        density=1025.0,
        gravity=9.80665,
        current_z=turning.current_z,
        current_velocity=turning.current_velocity - v0,
    )
    rest = solve(
        StaticProblem(
            line=line,
            medium=rest_medium,
            end_a=fixed([0, 0, -150]),
            end_b=fixed([120, 40, 0]),
            n_nodes=21,
        )
    )
    assert np.max(np.abs(moving.position - rest.position)) < 1e-10 * 200.0
    assert np.allclose(moving.force_a, rest.force_a, atol=1e-10 * np.abs(rest.force_a).max())


def test_installation_config_rejected_by_solvers_without_it() -> None:
    """The exact-catenary solver lists installation among what it cannot do (a config
    error before any work), the shooting solver supports it."""
    problem = StaticProblem(
        line=make_line([100.0], 10.0, 1e8),
        medium=medium(density=0.0),
        end_a=fixed([0, 0, 0]),
        end_b=fixed([90, 0, 0]),
        payout_speed=1.0,
    )
    assert any("installation" in m for m in STATIC_SOLVERS["analytic"].unsupported(problem))
    assert SOLVER.unsupported(problem) == []


def test_weightless_line_in_a_current() -> None:
    """A weightless slack line has no still-water shape, so the solver goes straight to
    the full current: in a uniform current across the chord the line bows downstream,
    symmetric about its mid-point (the ends exchange roles under a reflection through
    the mid-height plane), with the whole drag taken by the ends along the current."""
    line = make_line([100.0], 0.0, 1e8, diameter=0.05, drag_normal=1.2)
    res = solve(
        StaticProblem(
            line=line,
            medium=medium(current=[(0.0, 0.5, 0.0)]),
            end_a=fixed([0, 0, 0]),
            end_b=fixed([0, 0, -90]),
            n_nodes=41,
        )
    )
    scale = float(np.linalg.norm(res.force_a))
    assert res.force_a[0] > 0.1 * scale  # pulled downstream
    assert np.allclose(res.force_a[[0, 1]], res.force_b[[0, 1]], atol=1e-8 * scale)
    assert abs(res.force_a[2] + res.force_b[2]) < 1e-8 * scale
    mirrored = res.position[::-1] * np.array([1.0, 1.0, -1.0]) + np.array([0.0, 0.0, -90.0])
    assert np.max(np.abs(mirrored - res.position)) < 1e-8 * 100.0
