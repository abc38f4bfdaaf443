"""Whole-line verification of a static result: status 0 means verified.

Every static result, whatever the method, is checked against the problem it answers
before it is called ok. Pure: arrays in, numbers out (no I/O).

Conventions (:mod:`.base`): ``force_a``, ``force_b`` are the forces the line exerts on
its attachments, so the supports pull the line with ``-force_a``, ``-force_b``; the
tension vector at arc length s (the pull of the part beyond s on the part before it) is

    T(s) = force_a - (loads on [0, s])  =  -force_b + (loads on [s, L]).

Checks (each a value against an allowance; a result passes when none exceeds it):

1. **Whole-line force balance.** ``force_a + force_b`` equals the loads on the line: its
   weight in the fluid ``sum(q l)``, the attachments' forces, the drag (recomputed from
   the returned shape) and the seabed reaction. The seabed reaction is not returned by
   the solvers; it is what the balance leaves, and it must be one the seabed can give:
   its normal part between the normal weight of the sample intervals lying on the
   seabed (both ends on the plane to round-off, or pressed into it; the interval at
   each end of such a run left out) and of those near it (either end within
   ``CONTACT_GAP`` of the line length, plus the point loads there; no upper bound with
   bending stiffness, which presses the touchdown region harder), and its tangential
   part (friction) at most ``mu`` times the normal part (``mu`` the larger of the axial
   and lateral coefficients).
2. **Ends.** A fixed end where it was put; a mooring end at its height and carrying its
   horizontal force; a force end carrying its force; the end tensions equal the end
   forces' magnitudes.
3. **Tension along s.** At each sample not separated from an end by seabed contact, the
   returned tension equals ``|T(s)|`` from that end's force and the loads (still water,
   or with the recomputed drag; lines without bending stiffness; samples at a point
   load, whose tension is that of either side, left out).
4. **Stretched length.** No sample interval's chord is longer than the stretched arc
   can be: ``h (1 + e(max T))`` (``e`` the axial law's strain; the tension of a
   catenary piece is convex in s, so its largest value over an interval is at an end;
   across a point load inside the interval, the load and the interval's weight added).

Allowances are set by the loads, never by EA: ``10 * tol * F`` for forces, with ``F``
the total load magnitude (weights, attachments, drag, end forces) and ``tol`` the
requested tolerance (no smaller than the round-off of summing the samples), and
``10 * tol * reach`` for positions (``reach`` the line length or the largest coordinate).
Methods that report a discretised tension (``discrete``: element tensions averaged at
the nodes, attachments lumped on the nearest node) add their resolution: the largest
load of one element or attachment. Drag recomputed from the samples carries a
quadrature error; it is allowed four times its Richardson estimate (the same drag from
intervals twice as long), since the solver's own lumping is of the same order; in full
on intervals near the touchdown point (partly laid: the solvers put no drag on the
laid part), and for ``discrete`` (drag lumped on the nodes with node tangents, on the
elements' rest length) half its change from one interval to the next plus the drag
times the strain. Bodies (``attachment_drag_area``) add
``1/2 rho C_D A |U| U`` at their place. ``shooting`` is held to its own floor,
``100 rtol`` of its integration (:func:`tolerance_floor`).
Steady installation adds the momentum flux ``m V^2`` of the paid-out cable at each end,
which the whole-line balance allows rather than models.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..physics.current import current_velocity
from ..physics.hydro import drag_per_length
from .base import STATUS_NOT_VERIFIED, STATUS_OK, StaticProblem, StaticResult
from .seabed import Plane, seabed_of

#: allowances are this multiple of the requested tolerance times the load (or length)
#: scale: a converged solver meets its tolerance on its own residual, which differs from
#: these sums by a few terms of the same size
MULTIPLE = 10.0


def tolerance_floor(solver: object) -> float:
    """The smallest tolerance ``solver`` can meet [-]: 100 times the relative tolerance
    of its ODE integration where it has one (method ``shooting`` stops its Newton at
    max(tolerance, 100 rtol)), else 0."""
    return 100.0 * float(getattr(solver, "rtol", 0.0))


#: contact with the seabed: within this fraction of the line length of it (the solvers'
#: own test of an end on the seabed)
CONTACT_GAP = 1e-6
#: methods whose tension is a discretisation (see the module docstring)
DISCRETISED = frozenset({"discrete"})


@dataclass(frozen=True)
class Pieces:
    """The line as pieces of uniform load for N cases: boundaries ``bounds`` [m]
    (N, P + 1), per piece ``weight`` [N/m] (down positive) and ``axial_stiffness`` [N]
    (N, P), and point loads on the line ``point`` [N] (N, P + 1, 3) at the boundaries."""

    bounds: np.ndarray
    weight: np.ndarray
    axial_stiffness: np.ndarray
    point: np.ndarray


@dataclass
class Checked:
    """Per case (N,) the value and the allowance of each check (see the module
    docstring), by name; ``ok`` where no value exceeds its allowance."""

    values: dict[str, np.ndarray]
    allowed: dict[str, np.ndarray]
    units: dict[str, str]

    @property
    def ok(self) -> np.ndarray:
        out = None
        for name, v in self.values.items():
            good = ~(v > self.allowed[name]) & ~np.isnan(v)
            out = good if out is None else out & good
        assert out is not None
        return out

    def message(self, i: int) -> str:
        """Why case ``i`` is not verified (empty when it is)."""
        parts = []
        for name, v in self.values.items():
            a = self.allowed[name][i]
            if not (v[i] <= a):
                u = self.units[name]
                parts.append(f"{name} off by {v[i]:.3g} {u} (allowed {a:.3g} {u})")
        return "not verified: " + "; ".join(parts) if parts else ""


def _loads_to_nodes(s: np.ndarray, pieces: Pieces) -> np.ndarray:
    """Weight and point loads on [0, s_i) at the samples ``s`` (N, n): the load vector
    (N, n, 3) [N]. A point load exactly at a sample counts from the next sample on."""
    b = pieces.bounds
    lo = np.clip(s[:, :, None], b[:, None, :-1], b[:, None, 1:])  # (N, n, P)
    covered = lo - b[:, None, :-1]
    w = pieces.weight[:, None, :]
    load = np.zeros(s.shape + (3,))
    load[..., 2] = -(w[..., 0] * covered[..., 0] if b.shape[1] == 2 else np.sum(w * covered, 2))
    if np.any(pieces.point):
        before = (b[:, None, :] < s[:, :, None]).astype(float)  # (N, n, P + 1)
        load += before @ pieces.point
    return load


def _norm(v: np.ndarray) -> np.ndarray:
    """Euclidean norm over the last axis (of length 3)."""
    x, y, z = v[..., 0], v[..., 1], v[..., 2]
    return np.sqrt(x * x + y * y + z * z)


def _strain_bound(
    s: np.ndarray, tension: np.ndarray, pieces: Pieces, laws: tuple | None
) -> np.ndarray:
    """Largest strain over each sample interval (N, n - 1): the strain at the larger end
    tension in the softest piece the interval overlaps. Across a point load inside an
    interval the tension jumps: there the bound adds its magnitude and the weight of
    the interval (the most the tension can change on the way to it)."""
    tmax = np.maximum(tension[:, :-1], tension[:, 1:])
    b = pieces.bounds
    if np.any(pieces.point):
        mag = np.linalg.norm(pieces.point, axis=2)  # (N, P + 1)
        inside = (s[:, :-1, None] < b[:, None, :]) & (b[:, None, :] < s[:, 1:, None])
        jump = np.sum(np.where(inside, mag[:, None, :], 0.0), axis=2)
        w = np.max(np.abs(pieces.weight), axis=1, keepdims=True)
        tmax = tmax + np.where(jump > 0.0, jump + w * (s[:, 1:] - s[:, :-1]), 0.0)
    if b.shape[1] == 2 and not laws:
        return tmax / pieces.axial_stiffness[:, :1]
    out = np.zeros(tmax.shape)
    for p in range(pieces.weight.shape[1]):
        over = (s[:, :-1] < b[:, p + 1, None]) & (s[:, 1:] > b[:, p, None])
        law = laws[p] if laws else None
        if law is None:
            e = tmax / pieces.axial_stiffness[:, p, None]
        else:
            e = np.asarray(law.strain(np.maximum(tmax, 0.0)), dtype=float)
        out = np.where(over, np.maximum(out, e), out)
    return out


def check_lines(
    *,
    s: np.ndarray,
    position: np.ndarray,
    tension: np.ndarray,
    force_a: np.ndarray,
    force_b: np.ndarray,
    pieces: Pieces,
    tolerance: np.ndarray,
    position_a: np.ndarray | None = None,
    position_b: np.ndarray | None = None,
    given_force_b: np.ndarray | None = None,
    given_height_b: np.ndarray | None = None,
    plane: Plane | None = None,
) -> Checked:
    """The checks of the module docstring for N still-water lines without bending
    stiffness: arrays with a leading case axis, ``s`` [m] (N, n), ``position`` [m]
    (N, n, 3), ``tension`` [N] (N, n), end forces [N] (N, 3), ``tolerance`` [-] (N,);
    ``position_a``, ``position_b`` [m] (N, 3) where the end is fixed (rows of NaN, or
    None, where it is not); ``given_force_b`` [N] (N, 3) the force given on the line at
    B (NaN where not given: a mooring end gives x and y) and ``given_height_b`` [m] (N,)
    its given z. The axial laws are linear and the tensions exact (the compiled
    kernels' lines: no tension resolution).
    With ``plane``, the lines rest on that rigid seabed (the compiled contact kernel's
    cases): the whole-line balance leaves a seabed reaction that the laid weight and
    Coulomb friction admit (as :func:`check_one`), and no sample lies below it."""
    seabed: dict[str, object] = {}
    if plane is not None:
        L = pieces.bounds[:, -1]
        height = (position - np.array([0.0, 0.0, -plane.depth])) @ plane.normal  # (N, n)
        reach = np.maximum(
            np.maximum(L, np.max(np.abs(position), axis=(1, 2), initial=0.0)), plane.depth
        )
        seabed = {
            "contact": height <= CONTACT_GAP * L[:, None],
            "laid": height <= 64.0 * float(np.finfo(float).eps) * reach[:, None],
            "seabed": plane,
            "friction": plane.friction,
        }
    checked = _checks(
        s=s,
        position=position,
        tension=tension,
        force_a=force_a,
        force_b=force_b,
        pieces=pieces,
        tolerance=tolerance,
        position_a=position_a,
        position_b=position_b,
        laws=None,
        resolution=np.zeros(tolerance.shape),
        **seabed,  # type: ignore[arg-type]
    )
    f_allow = checked.allowed["end tension"]
    x_allow = checked.allowed["stretched length"]
    if plane is not None:
        tol = np.maximum(tolerance, 16.0 * float(np.finfo(float).eps) * s.shape[1])
        checked.values["seabed penetration"] = np.maximum(-np.min(height, axis=1), 0.0)
        checked.allowed["seabed penetration"] = MULTIPLE * tol * reach
        checked.units["seabed penetration"] = "m"
    if given_force_b is not None:
        off = np.where(np.isfinite(given_force_b), force_b + given_force_b, 0.0)
        checked.values["end B force"] = np.linalg.norm(off, axis=1)
        checked.allowed["end B force"] = f_allow
        checked.units["end B force"] = "N"
    if given_height_b is not None:
        off_z = np.where(np.isfinite(given_height_b), position[:, -1, 2] - given_height_b, 0.0)
        checked.values["end B height"] = np.abs(off_z)
        checked.allowed["end B height"] = x_allow
        checked.units["end B height"] = "m"
    return checked


def _checks(
    *,
    s: np.ndarray,
    position: np.ndarray,
    tension: np.ndarray,
    force_a: np.ndarray,
    force_b: np.ndarray,
    pieces: Pieces,
    tolerance: np.ndarray,
    position_a: np.ndarray | None,
    position_b: np.ndarray | None,
    laws: tuple | None,
    resolution: np.ndarray,
    drag: np.ndarray | None = None,
    drag_allow: np.ndarray | None = None,
    contact: np.ndarray | None = None,
    laid: np.ndarray | None = None,
    seabed: Plane | None = None,
    friction: float = 0.0,
    bending: bool = False,
    extra_allow: np.ndarray | float = 0.0,
) -> Checked:
    N, n = s.shape
    eps = float(np.finfo(float).eps)
    tol = np.maximum(tolerance, 16.0 * eps * (n + pieces.weight.shape[1]))
    load_at = _loads_to_nodes(s, pieces)
    at_point = _near_points(s, pieces)
    ell = np.diff(pieces.bounds, axis=1)
    total = np.zeros((N, 3))
    total[:, 2] = -np.sum(pieces.weight * ell, axis=1)
    total += pieces.point.sum(axis=1)
    scale = (
        np.sum(np.abs(pieces.weight) * ell, axis=1)
        + np.linalg.norm(pieces.point, axis=2).sum(axis=1)
        + np.linalg.norm(force_a, axis=1)
        + np.linalg.norm(force_b, axis=1)
    )
    drag_cum = np.zeros((N, n, 3))
    drag_cum_allow = np.zeros((N, n))
    if drag is not None:
        assert drag_allow is not None
        total = total + drag.sum(axis=1)
        scale = scale + np.linalg.norm(drag, axis=2).sum(axis=1)
        drag_cum[:, 1:] = np.cumsum(drag, axis=1)
        drag_cum_allow[:, 1:] = np.cumsum(drag_allow, axis=1)
    f_allow = MULTIPLE * tol * scale + extra_allow
    if drag_allow is not None:
        f_allow = f_allow + drag_allow.sum(axis=1)
    node_allow = f_allow + resolution
    values: dict[str, np.ndarray] = {}
    allowed: dict[str, np.ndarray] = {}
    units: dict[str, str] = {}

    def put(name: str, value: np.ndarray, allow: np.ndarray, unit: str) -> None:
        values[name], allowed[name], units[name] = value, allow, unit

    # 1. the whole line; what is left is the seabed's reaction
    needed = force_a + force_b - total
    if contact is None or seabed is None or not bool(np.any(contact)):
        put("whole-line force balance", np.linalg.norm(needed, axis=1), f_allow, "N")
    else:
        nrm = seabed.normal
        # the weight of each sample interval, exact across piece boundaries (an interval
        # holding a chain-to-wire joint carries part of each), divided by its length so
        # that normal_w * h below is that weight's normal part
        h = np.diff(s, axis=1)
        normal_w = (
            interval_weight(s, pieces) / np.where(h > 0.0, h, 1.0) * float(nrm[2])
        )  # (N, n - 1) [N/m]
        # lying on it for certain: on the plane to round-off (or pressed into it); near
        # it: within the contact gap (a sample there may be lifting off)
        on = contact if laid is None else laid
        both = on[:, :-1] & on[:, 1:]
        either = contact[:, :-1] | contact[:, 1:]
        # a sample within the contact gap may already be lifting off: the interval at
        # each end of a run of contact is counted in the upper bound only
        prev = np.pad(both[:, :-1], ((0, 0), (1, 0)), constant_values=True)
        succ = np.pad(both[:, 1:], ((0, 0), (0, 1)), constant_values=True)
        inner = both & prev & succ
        lo = np.sum(np.where(inner, normal_w * h, 0.0), axis=1)
        hi = np.sum(np.where(either, np.maximum(normal_w, 0.0) * h, 0.0), axis=1)
        on_bed_points = _points_in(pieces, s, either)
        hi = hi + on_bed_points
        if bending:
            hi = np.full(N, np.inf)  # a bent line presses on its touchdown region
        N_ = needed @ nrm
        tang = np.linalg.norm(needed - N_[:, None] * nrm, axis=1)
        off_normal = np.maximum(np.maximum(lo - N_, N_ - hi), 0.0)
        off_friction = np.maximum(tang - friction * np.maximum(N_, 0.0), 0.0)
        put(
            "whole-line force balance (seabed reaction admissible)",
            np.hypot(off_normal, off_friction),
            f_allow + resolution,
            "N",
        )
        # the seabed only pushes: a buoy or a buoyant piece inside a laid stretch would
        # need it to pull the line down (a lumped line's node lifts within its resolution)
        pull = np.sum(np.where(inner, np.maximum(-normal_w * h, 0.0), 0.0), axis=1)
        pull = pull + _points_in(pieces, s, inner, nrm)
        put("seabed reaction pulling a laid stretch down", pull, f_allow + resolution, "N")
    # 2. ends
    reach = np.maximum(pieces.bounds[:, -1], np.max(np.abs(position), axis=(1, 2), initial=0.0))
    x_allow = MULTIPLE * tol * reach
    for label, target, k in (("A", position_a, 0), ("B", position_b, -1)):
        if target is not None:
            gap = position[:, k] - target  # hypot: no overflow to inf for a far target
            d = np.hypot(np.hypot(gap[:, 0], gap[:, 1]), gap[:, 2])
            fixed = np.all(np.isfinite(target), axis=1)
            put(f"end {label} position", np.where(fixed, d, 0.0), x_allow, "m")
    if not bending:
        end_t = np.maximum(
            np.abs(tension[:, 0] - np.linalg.norm(force_a, axis=1)),
            np.abs(tension[:, -1] - np.linalg.norm(force_b, axis=1)),
        )
        put("end tension", end_t, node_allow, "N")
        # 3. tension along s, from whichever end is not cut off by seabed contact
        inner = load_at + drag_cum if drag is not None else load_at
        from_a = _norm(force_a[:, None, :] - inner)
        allow_a = node_allow[:, None] + drag_cum_allow
        err = np.abs(tension - from_a) - allow_a
        if contact is not None:
            from_b = _norm(-force_b[:, None, :] + (total[:, None, :] - inner))
            allow_b = node_allow[:, None] + (drag_cum_allow[:, -1:] - drag_cum_allow)
            err_b = np.abs(tension - from_b) - allow_b
            use_a = np.cumsum(contact, axis=1) == 0
            use_b = np.cumsum(contact[:, ::-1], axis=1)[:, ::-1] == 0
            err = np.where(use_a, err, np.where(use_b, err_b, -np.inf))
        if np.any(at_point):
            err = np.where(at_point > 0.0, -np.inf, err)
        worst = np.max(err[:, 1:-1], axis=1, initial=-np.inf)
        # reported as the excess over the allowance plus the allowance of that case
        put("tension along s", np.maximum(worst, -np.inf) + node_allow, node_allow, "N")
    # 4. no chord longer than its stretched arc
    chord = _norm(position[:, 1:] - position[:, :-1])
    h = s[:, 1:] - s[:, :-1]
    # at a point load the tension on the other side differs by at most its magnitude
    strain = _strain_bound(s, tension + resolution[:, None] + at_point, pieces, laws)
    arc = h * (1.0 + np.maximum(strain, 0.0)) * (1.0 + MULTIPLE * tol[:, None])
    excess = np.max(chord - arc, axis=1, initial=-np.inf)
    put("stretched length", np.maximum(excess, 0.0), x_allow, "m")
    return Checked(values=values, allowed=allowed, units=units)


def interval_weight(s: np.ndarray, pieces: Pieces) -> np.ndarray:
    """Weight [N] (N, n - 1) of each sample interval: the integral of the pieces' weight
    per length over it (the pieces it spans each in their share)."""
    b = pieces.bounds  # (N, P + 1)
    ell = np.diff(b, axis=1)  # (N, P)

    def cumulative(x: np.ndarray) -> np.ndarray:  # (N, n) [N]: weight from s = 0 to x
        into = np.clip(x[:, :, None] - b[:, None, :-1], 0.0, ell[:, None, :])
        return np.sum(pieces.weight[:, None, :] * into, axis=2)

    return np.diff(cumulative(s), axis=1)


def pieces_weight_at(s: np.ndarray, pieces: Pieces) -> np.ndarray:
    """Weight per length [N/m] of the piece holding the middle of each sample interval
    (N, n - 1)."""
    mid = 0.5 * (s[:, :-1] + s[:, 1:])
    b = pieces.bounds
    k = np.sum(b[:, None, 1:-1] <= mid[:, :, None], axis=2)
    return np.take_along_axis(pieces.weight, k, axis=1)


def _points_in(
    pieces: Pieces, s: np.ndarray, mask: np.ndarray, up: np.ndarray | None = None
) -> np.ndarray:
    """Sum over the point loads lying in the masked sample intervals of their magnitudes
    (an upper bound of what the seabed carries of them), or given the seabed's normal
    ``up``, of their parts lifting the line off it [N] (N,)."""
    b = pieces.bounds
    out = np.zeros(b.shape[0])
    mag = np.linalg.norm(pieces.point, axis=2) if up is None else np.maximum(pieces.point @ up, 0)
    for p in range(b.shape[1]):
        inside = (s[:, :-1] <= b[:, p, None]) & (b[:, p, None] <= s[:, 1:]) & mask
        out += np.where(np.any(inside, axis=1), mag[:, p], 0.0)
    return out


def _near_points(s: np.ndarray, pieces: Pieces) -> np.ndarray:
    """Magnitude [N] (N, n) of the point load at each sample (within 1e-9 of the line
    length; 0 where none): the tension there is that on one side or the other."""
    if not np.any(pieces.point):
        return np.zeros(s.shape)
    L = pieces.bounds[:, -1:]
    mag = np.linalg.norm(pieces.point, axis=2)  # (N, P + 1)
    d = np.abs(s[:, :, None] - pieces.bounds[:, None, :])
    return np.sum(np.where(d <= 1e-9 * L[:, :, None], mag[:, None, :], 0.0), axis=2)


# --------------------------------------------------------------------------- one case


def verified(
    problem: StaticProblem, result: StaticResult, *, method: str = "", floor: float = 0.0
) -> StaticResult:
    """``result`` if it is not ok or passes every check; otherwise the same numbers with
    status :data:`STATUS_NOT_VERIFIED` and the failing checks in the message. ``floor``
    [-] is the smallest tolerance the method can meet (its integration floor)."""
    if result.status != STATUS_OK:
        return result
    checked = check_one(problem, result, method=method, floor=floor)
    if bool(checked.ok[0]):
        return result
    message = checked.message(0) + _cross_slope_hint(problem, result, method, checked)
    return replace(result, status=STATUS_NOT_VERIFIED, message=message)


#: the whole-line check of a line resting on the seabed (:func:`_checks`)
_SEABED_BALANCE = "whole-line force balance (seabed reaction admissible)"


def _cross_slope_hint(
    problem: StaticProblem, result: StaticResult, method: str, checked: Checked
) -> str:
    """Why a cable method's laid line fails the seabed balance on a slope that rises
    across the vertical plane of its ends: those methods solve the line in that plane,
    so the laid line's weight down the cross slope is left to friction together with
    the pull along the line; where Coulomb friction cannot hold both the line would slide
    sideways, which they do not model ('' where that is not the case)."""
    med = problem.medium
    name = _SEABED_BALANCE
    if method not in ("catenary", "shooting") or med.depth is None or med.seabed_slope == 0.0:
        return ""
    if name not in checked.values or checked.values[name][0] <= checked.allowed[name][0]:
        return ""
    chord = np.asarray(result.position[-1], dtype=float) - np.asarray(result.position[0])
    if float(np.hypot(chord[0], chord[1])) == 0.0:
        return ""
    azimuth = math.atan2(float(chord[1]), float(chord[0]))
    across = math.sin(med.seabed_heading - azimuth)
    shown = round(math.degrees(azimuth), 6) + 0.0  # no -7.68e-20 for a line along +x
    if abs(across) <= 1e-6:
        return ""
    return (
        f" (the seabed rises at {math.degrees(med.seabed_slope):.3g} deg towards heading "
        f"{math.degrees(med.seabed_heading):.3g} deg, across the vertical plane of the "
        f"line's ends at azimuth {shown:.6g} deg: method {method!r} solves "
        "the line in that plane, leaving the laid line's weight down the cross slope to "
        "friction with the pull along it, more than Coulomb friction holds here; method "
        "'discrete' models the line sliding sideways)"
    )


def check_one(
    problem: StaticProblem, result: StaticResult, *, method: str = "", floor: float = 0.0
) -> Checked:
    """The checks of the module docstring on one result (any problem); the tolerance is
    the problem's, or ``floor`` where that is larger."""
    from .semi_analytic_shape import make_layout

    line, med = problem.line, problem.medium
    lay = make_layout(line)
    pieces = Pieces(
        bounds=lay.bounds[None],
        weight=lay.weight[None],
        axial_stiffness=lay.EA[None],
        point=lay.point[None],
    )
    s = np.asarray(result.s, dtype=float)[None]
    pos = np.asarray(result.position, dtype=float)[None]
    tension = np.asarray(result.tension, dtype=float)[None]
    L = line.total_length
    ea, eb = problem.end_a, problem.end_b
    extra = 0.0
    # ends other than fixed: their given forces and heights
    end_vals: dict[str, tuple[float, float, str]] = {}
    f_scale = float(np.sum(np.abs(line.weight) * line.length))
    f_scale += float(np.sum(np.linalg.norm(line.attachment_force, axis=1)))
    f_scale += float(np.linalg.norm(result.force_a)) + float(np.linalg.norm(result.force_b))
    requested = max(problem.tolerance, floor)
    tol = max(requested, 16.0 * float(np.finfo(float).eps) * s.shape[1])
    for label, end, force, k in (("A", ea, result.force_a, 0), ("B", eb, result.force_b, -1)):
        if end.kind == "force":
            assert end.force is not None
            end_vals[f"end {label} force"] = (
                float(np.linalg.norm(np.asarray(force) + end.force)),
                MULTIPLE * tol * f_scale,
                "N",
            )
        elif end.kind == "mooring":
            assert end.force is not None and end.z is not None
            end_vals[f"end {label} horizontal force"] = (
                float(np.linalg.norm(np.asarray(force)[:2] + end.force[:2])),
                MULTIPLE * tol * f_scale,
                "N",
            )
            end_vals[f"end {label} height"] = (
                abs(float(pos[0, k, 2]) - end.z),
                MULTIPLE * tol * max(L, float(np.max(np.abs(pos)))),
                "m",
            )
    contact = laid = None
    plane = seabed_of(med)
    if plane is not None:
        height = plane.height_above(pos[0])
        contact = (height <= CONTACT_GAP * L)[None]
        # on the plane to the round-off of the coordinates
        reach = max(L, float(np.max(np.abs(pos))), med.depth)
        laid = (height <= 64.0 * float(np.finfo(float).eps) * reach)[None]
    drag = drag_allow = None
    if (
        (med.has_current or problem.is_installation)
        and med.density > 0.0
        and (
            np.any(line.diameter * (line.drag_normal + line.drag_tangential) > 0.0)
            or np.any(line.attachment_drag_area > 0.0)
        )
    ):
        drag, drag_allow = _drag(problem, s[0], pos[0], contact, laid)
        if method in DISCRETISED and len(drag) > 1:
            # lumped on the nodes with node tangents: a second quadrature of the same
            # drag, differing from ours by at most half its change from one interval on
            jump = 0.25 * np.linalg.norm(np.diff(drag, axis=0), axis=1)
            drag_allow = drag_allow + np.pad(jump, (0, 1)) + np.pad(jump, (1, 0))
            # and on the rest length of the elements, not the stretched one: the drag
            # times the strain
            h = np.diff(s[0])
            lc = np.linalg.norm(np.diff(pos[0], axis=0), axis=1)
            strain = np.abs(lc / np.where(h > 0.0, h, 1.0) - 1.0)
            drag_allow = drag_allow + np.linalg.norm(drag, axis=1) * strain
        drag, drag_allow = drag[None], drag_allow[None]
    if problem.is_installation:
        # momentum flux of the paid-out cable at each end, allowed, not modelled
        v = abs(problem.payout_speed) + float(np.linalg.norm(problem.touchdown_velocity))
        area = math.pi * line.diameter**2 / 4.0
        m = float(np.max(line.mass + line.added_mass_normal * med.density * area))
        extra = 2.0 * m * v * v
    resolution = 0.0
    if method in DISCRETISED:
        h = np.diff(s[0])
        per_el = float(np.max(np.abs(pieces_weight_at(s, pieces)[0]) * h, initial=0.0))
        if drag is not None:
            per_el += float(np.max(np.linalg.norm(drag[0], axis=1), initial=0.0))
        per_att = float(np.max(np.linalg.norm(line.attachment_force, axis=1), initial=0.0))
        resolution = per_el + per_att
    fric = med.friction
    if problem.friction_lateral is not None:
        fric = max(fric, problem.friction_lateral)
    checked = _checks(
        s=s,
        position=pos,
        tension=tension,
        force_a=np.asarray(result.force_a, dtype=float)[None],
        force_b=np.asarray(result.force_b, dtype=float)[None],
        pieces=pieces,
        tolerance=np.array([requested]),
        position_a=None if ea.kind != "fixed" else np.asarray(ea.position, dtype=float)[None],
        position_b=None if eb.kind != "fixed" else np.asarray(eb.position, dtype=float)[None],
        laws=lay.law,
        resolution=np.array([resolution]),
        drag=drag,
        drag_allow=drag_allow,
        contact=contact,
        laid=laid,
        seabed=plane,
        friction=fric,
        bending=bool(np.any(line.bending_stiffness > 0.0)),
        extra_allow=extra,
    )
    if plane is not None and method not in DISCRETISED and drag is None:
        end_vals["seabed penetration"] = (
            _penetration(result, plane, lay),
            MULTIPLE * tol * max(L, float(np.max(np.abs(pos)))),
            "m",
        )
    for name, (v, a, u) in end_vals.items():
        checked.values[name] = np.array([v])
        checked.allowed[name] = np.array([a])
        checked.units[name] = u
    return checked


def _penetration(result: StaticResult, plane: Plane, lay) -> float:  # noqa: ANN001
    """How deep [m] the still-water line goes into a rigid seabed: at the samples, and
    between them at the lowest point of each suspended interval (where the tension's
    normal component turns from down to up: the closed-form piece increment from the
    tension at the sample before, :func:`.law_pieces.piece_increments` with the piece's
    axial law). Intervals across a segment boundary or point load, and those beyond the
    first contact from A, are checked at their samples only."""
    from .law_pieces import piece_increments

    pos = np.asarray(result.position, dtype=float)
    s = np.asarray(result.s, dtype=float)
    height = plane.height_above(pos)
    deepest = max(float(-np.min(height)), 0.0)
    n = plane.normal
    L = float(lay.bounds[-1])
    pieces = Pieces(
        bounds=lay.bounds[None],
        weight=lay.weight[None],
        axial_stiffness=lay.EA[None],
        point=lay.point[None],
    )
    T = np.asarray(result.force_a, dtype=float)[None] - _loads_to_nodes(s[None], pieces)[0]
    k = np.clip(np.searchsorted(lay.bounds, s[:-1], side="right") - 1, 0, len(lay.ell) - 1)
    one_piece = s[1:] <= lay.bounds[k + 1] * (1.0 + 1e-12)
    no_point = ~np.any(
        (lay.bounds[None, :] >= s[:-1, None])
        & (lay.bounds[None, :] < s[1:, None])
        & np.any(lay.point != 0.0, axis=1)[None, :],
        axis=1,
    )
    free = np.cumsum(height[:-1] <= CONTACT_GAP * L) <= (height[0] <= CONTACT_GAP * L)
    q = np.zeros((len(k), 3))
    q[:, 2] = -lay.weight[k]
    qn = q @ n
    V0 = T[:-1] @ n
    V1 = V0 - qn * np.diff(s)
    turn = one_piece & no_point & free & (qn < 0.0) & (V0 < 0.0) & (V1 > 0.0)
    if np.any(turn):
        sigma = V0[turn] / qn[turn]
        laws = None if lay.law is None else [lay.law[j] for j in k[turn]]
        dr, _, _ = piece_increments(
            T[:-1][turn], q[turn], sigma, lay.EA[k[turn]], laws, jacobian=False
        )
        low = height[:-1][turn] + dr @ n
        deepest = max(deepest, float(-np.min(low)))
    return deepest


def _drag(
    problem: StaticProblem,
    s: np.ndarray,
    pos: np.ndarray,
    contact: np.ndarray | None,
    laid: np.ndarray | None,
) -> tuple[np.ndarray, np.ndarray]:
    """Drag force on each sample interval (n - 1, 3) [N] from the returned shape (chord
    tangent, current at mid-height, relative to the laying frame and the pay-out; none
    on intervals lying on the seabed), and its allowance (n - 1,) [N]: four times the
    Richardson estimate of its quadrature error (see the module docstring)."""
    force = _interval_drag(problem, s, pos)
    if laid is not None:
        force[laid[0, :-1] & laid[0, 1:]] = 0.0
    mag = np.linalg.norm(force, axis=1)
    m = (len(s) - 1) // 2
    if m >= 1:
        idx = np.arange(0, 2 * m + 1, 2)
        coarse = _interval_drag(problem, s[idx], pos[idx])
        fine = force[: 2 * m].reshape(m, 2, 3).sum(axis=1)
        if laid is not None:
            coarse[laid[0, idx[:-1]] & laid[0, idx[1:]]] = 0.0
        size = float(np.sum(np.linalg.norm(fine, axis=1)))
        diff = float(np.sum(np.linalg.norm(fine - coarse, axis=1)))
        rho = diff / size if size > 0.0 else 0.0
    else:
        rho = 1.0  # one interval: no estimate, the whole drag is allowed
    allow = 4.0 * min(rho, 1.0) * mag
    area = problem.line.attachment_drag_area
    if area.size and np.any(area > 0.0):
        # lumped bodies: 1/2 rho C_D A |U| U at their place, in their interval
        med = problem.medium
        at = np.stack([np.interp(problem.line.attachment_s, s, pos[:, k]) for k in range(3)], 1)
        U = current_velocity(at[:, 2], med.current_z, med.current_velocity)
        U = U - problem.touchdown_velocity[None, :]
        body = 0.5 * med.density * area[:, None] * np.linalg.norm(U, axis=1)[:, None] * U
        k = np.clip(np.searchsorted(s, problem.line.attachment_s, side="right") - 1, 0, len(s) - 2)
        np.add.at(force, k, body)
        np.add.at(allow, k, 4.0 * min(rho, 1.0) * np.linalg.norm(body, axis=1))
    if contact is not None and laid is not None:
        # an interval near the touchdown point may be partly laid (no drag there)
        edge = (contact[0, :-1] | contact[0, 1:]) & ~(laid[0, :-1] & laid[0, 1:])
        allow = np.where(edge, mag, allow)
    return force, allow


def _interval_drag(problem: StaticProblem, s: np.ndarray, pos: np.ndarray) -> np.ndarray:
    line, med = problem.line, problem.medium
    h = np.diff(s)
    chord = np.diff(pos, axis=0)
    lc = np.linalg.norm(chord, axis=1)
    t = chord / np.where(lc > 0.0, lc, 1.0)[:, None]
    U = current_velocity(0.5 * (pos[:-1, 2] + pos[1:, 2]), med.current_z, med.current_velocity)
    U = U - problem.touchdown_velocity[None, :] + problem.payout_speed * t
    # an interval across a segment boundary takes each segment's drag for its share
    ends = line.segment_ends
    f = np.zeros((h.size, 3))
    for k in range(line.length.size):
        share = np.clip(s[1:], ends[k], ends[k + 1]) - np.clip(s[:-1], ends[k], ends[k + 1])
        part = share > 0.0
        if not np.any(part):
            continue
        m = int(part.sum())
        f[part] += (
            drag_per_length(
                U[part],
                t[part],
                density=med.density,
                diameter=np.full(m, line.diameter[k]),
                drag_normal=np.full(m, line.drag_normal[k]),
                drag_tangential=np.full(m, line.drag_tangential[k]),
            )
            * (share[part] / h[part])[:, None]
        )
    stretch = np.where(h > 0.0, lc / np.where(h > 0.0, h, 1.0), 1.0)
    if problem.stretched_drag_diameter:
        stretch = np.sqrt(stretch)
    return f * (stretch * h)[:, None]
