"""The discretised line (:mod:`.model`): the lumped-mass line of a line model
(:class:`DiscreteLine`, built by :func:`discretise` / :func:`discretise_nodes` at element
counts per segment), its dynamic-only properties (:class:`DynamicExtras`: bodies,
damping, free and clamped ends, seabed contact), the axial laws as arrays, the seabed
plane, and values at the nodes interpolated along the line.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from ..statics.base import LineModel, Medium
from ..statics.seabed import Plane


class LineArrays(NamedTuple):
    """A line's arrays as the compiled kernels take them (:meth:`DiscreteLine.kernel_args`;
    a kernel reads them by name, ``largs.held``, or passes them on, ``*largs``)."""

    rest_length: np.ndarray
    axial_stiffness: np.ndarray
    internal_damping: np.ndarray
    force: np.ndarray
    drag_normal: np.ndarray
    drag_tangential: np.ndarray
    added_mass_normal: np.ndarray
    added_mass_tangential: np.ndarray
    mass: np.ndarray
    current_z: np.ndarray
    current_velocity: np.ndarray
    has_drag: np.ndarray
    bending: np.ndarray
    clamp_direction: np.ndarray
    transverse_damping: np.ndarray
    body_added_mass: np.ndarray
    body_drag: np.ndarray
    held: np.ndarray
    seabed_normal: np.ndarray
    seabed_offset: np.ndarray
    seabed_stiffness: np.ndarray
    seabed_damping: np.ndarray
    friction: np.ndarray
    law_code: np.ndarray
    law_params: np.ndarray
    law_knots: np.ndarray
    law_start: np.ndarray
    law_count: np.ndarray
    broken: np.ndarray


@dataclass(frozen=True, kw_only=True)
class DynamicExtras:
    """What the dynamic line model needs beyond the static :class:`LineModel`.

    Parameters
    ----------
    transverse_damping : [N s/m^2] (n_segments,) structural damping per length acting
        on the velocity normal to the line (the ajayi seed's ``c``)
    attachment_added_mass : [kg] (n_att,) isotropic added mass of lumped bodies
    attachment_drag_area : [m^2] (n_att,) C_D A of lumped bodies (isotropic drag)
    end_force : [N] (2, 3) constant force on free end nodes (zero for held ends)
    free_end : (2,) whether end A / B is a free node (an unexcited ``force`` end)
    clamp_direction : (2, 3) unit direction held by a clamped end (zeros: pinned)
    seabed_stiffness : [N/m^2] normal contact stiffness per length (0: no contact)
    seabed_damping_ratio : [-] normal contact damping, fraction of critical per node
    friction_axial, friction_lateral : [-] Coulomb coefficients along and across
    """

    transverse_damping: np.ndarray = field(default_factory=lambda: np.zeros(0))
    attachment_added_mass: np.ndarray = field(default_factory=lambda: np.zeros(0))
    attachment_drag_area: np.ndarray = field(default_factory=lambda: np.zeros(0))
    end_force: np.ndarray = field(default_factory=lambda: np.zeros((2, 3)))
    free_end: tuple[bool, bool] = (False, False)
    clamp_direction: np.ndarray = field(default_factory=lambda: np.zeros((2, 3)))
    seabed_stiffness: float = 0.0
    seabed_damping_ratio: float = 1.0
    friction_axial: float = 0.0
    friction_lateral: float = 0.0


@dataclass(frozen=True, kw_only=True)
class DiscreteLine:
    """A line cut into ``n`` elements (``n + 1`` nodes).

    Parameters
    ----------
    s : [m] (n + 1,) unstretched arc length of the nodes from end A
    rest_length : [m] (n,) unstretched element lengths
    axial_stiffness : [N] (n,) EA of each element
    internal_damping : [N s] (n,) axial damping coefficient c (tension c * strain rate)
    mass : [kg] (n + 1,) lumped structural mass (line and attachments)
    added_mass_normal, added_mass_tangential : [kg] (n + 1,) lumped added mass
    drag_normal, drag_tangential : [kg/m] (n + 1,) 1/2 rho C_N d l and 1/2 rho pi C_T d l
    force : [N] (n + 1, 3) constant nodal force (weight in the fluid, attachments, free
        end forces)
    current_z : [m] (m,) heights of the current profile, increasing
    current_velocity : [m/s] (m, 3) current at those heights
    has_drag : whether any drag acts (False in vacuum or with zero coefficients)
    bending : [N m] (n + 1,) EI / h of the curvature term at each node (0: none)
    clamp_direction : (2, 3) unit direction held at clamped ends (zeros: pinned)
    transverse_damping : [N s/m] (n + 1,) lumped transverse structural damping
    body_added_mass : [kg] (n + 1,) isotropic added mass of lumped bodies
    body_drag : [kg/m] (n + 1,) 1/2 rho C_D A of lumped bodies
    held : (n + 1,) nodes whose motion is prescribed
    seabed_normal : (3,) unit upward normal of the seabed plane
    seabed_offset : [m] the plane is ``seabed_normal . x = seabed_offset``
    seabed_stiffness : [N/m] (n + 1,) contact stiffness of each node (0: no seabed)
    seabed_damping : [N s/m] (n + 1,) contact damping of each node
    friction : (2,) [-] Coulomb coefficients (along, across the line)
    law_code : (n,) axial law of each element (:data:`LAW_CODES`; 0: T = EA strain)
    law_params : (n, 5) the law's numbers: polynomial coefficients c1..c5 [N], or the
        steel wire's stiffness [N] and offset [-]
    law_knots : (k, 3) the tabulated laws' knots: strain [-], tension [N], slope [N]
    law_start, law_count : (n,) each element's rows of ``law_knots``
    broken : (n,) elements that have parted (a break in the time domain): no axial
        force, no bending across them, and the nodes beside them take their tangent
        from their remaining element (default: none)
    first_per_length : (8,) what the first element lumps per metre of its unstretched
        length: mass [kg/m], normal and tangential added mass [kg/m], drag_normal and
        drag_tangential [kg/m^2], transverse damping [N s/m^2], weight in the fluid
        [N/m], seabed contact stiffness [N/m^2] (a winch at end A changes that length)
    """

    s: np.ndarray
    rest_length: np.ndarray
    axial_stiffness: np.ndarray
    internal_damping: np.ndarray
    mass: np.ndarray
    added_mass_normal: np.ndarray
    added_mass_tangential: np.ndarray
    drag_normal: np.ndarray
    drag_tangential: np.ndarray
    force: np.ndarray
    current_z: np.ndarray
    current_velocity: np.ndarray
    has_drag: bool
    bending: np.ndarray
    clamp_direction: np.ndarray
    transverse_damping: np.ndarray
    body_added_mass: np.ndarray
    body_drag: np.ndarray
    held: np.ndarray
    seabed_normal: np.ndarray
    seabed_offset: float
    seabed_stiffness: np.ndarray
    seabed_damping: np.ndarray
    friction: np.ndarray
    law_code: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    law_params: np.ndarray = field(default_factory=lambda: np.zeros((0, 5)))
    law_knots: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    law_start: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    law_count: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    broken: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.bool_))
    first_per_length: np.ndarray = field(default_factory=lambda: np.zeros(8))

    def __post_init__(self) -> None:
        if self.broken.size != self.rest_length.size:
            object.__setattr__(self, "broken", np.zeros(self.rest_length.size, dtype=np.bool_))

    @property
    def n_elements(self) -> int:
        return int(self.rest_length.size)

    @property
    def n_nodes(self) -> int:
        return int(self.s.size)

    @property
    def has_bending(self) -> bool:
        return bool(np.any(self.bending > 0.0))

    @property
    def has_seabed(self) -> bool:
        return bool(np.any(self.seabed_stiffness > 0.0))

    def kernel_args(self) -> LineArrays:
        """The arrays in the order the compiled kernels take them."""
        return LineArrays(*(getattr(self, name) for name in LineArrays._fields))


#: axial laws of the compiled kernels (:mod:`cablestudy.physics.axial`)
LAW_CODES = {"linear": 0, "polynomial": 1, "steel_wire": 2, "table": 3}


def law_arrays(laws: list, n_elements_of: np.ndarray) -> tuple[np.ndarray, ...]:
    """Per-element law arrays (code, params, knots, start, count) of segment ``laws``
    (:class:`cablestudy.physics.axial.AxialLaw` or None for T = EA strain), element e
    belonging to segment ``n_elements_of[e]``."""
    from ..physics.axial import is_effectively_linear

    seg_code = np.zeros(len(laws), dtype=np.int64)
    seg_params = np.zeros((len(laws), 5))
    seg_start = np.zeros(len(laws), dtype=np.int64)
    seg_count = np.zeros(len(laws), dtype=np.int64)
    knots: list[np.ndarray] = []
    row = 0
    for i, law in enumerate(laws):
        if law is None or is_effectively_linear(law):
            continue
        seg_code[i] = LAW_CODES[law.name]
        if law.name == "polynomial":
            c = np.asarray(law.coefficients, dtype=float)
            seg_params[i, : c.size] = c
        elif law.name == "steel_wire":
            seg_params[i, :2] = (law.stiffness, law.offset)
        else:
            x, y, m = law._knots()
            knots.append(np.stack([x, y, m], 1))
            seg_start[i], seg_count[i] = row, x.size
            row += x.size
    table = np.concatenate(knots) if knots else np.zeros((0, 3))
    seg = np.asarray(n_elements_of)
    return (
        seg_code[seg],
        np.ascontiguousarray(seg_params[seg]),
        table,
        seg_start[seg],
        seg_count[seg],
    )


def element_counts(lengths: np.ndarray, elements: int) -> np.ndarray:
    """Elements per segment, about proportional to segment length, at least one each."""
    lengths = np.asarray(lengths, dtype=float)
    counts = np.maximum(1, np.round(elements * lengths / lengths.sum()).astype(int))
    while counts.sum() > max(elements, len(lengths)):
        excess = np.where(counts > 1, counts - elements * lengths / lengths.sum(), -np.inf)
        counts[int(np.argmax(excess))] -= 1
    while counts.sum() < elements:
        i = int(np.argmax(elements * lengths / lengths.sum() - counts))
        counts[i] += 1
    return counts


def discretise(
    line: LineModel, medium: Medium, elements: int, extras: DynamicExtras | None = None
) -> DiscreteLine:
    """Lumped-mass model of ``line`` in ``medium`` with about ``elements`` elements
    (at least one per segment; nodes on every segment boundary).

    Parameters
    ----------
    line : the segments and attachments (SI units, see :class:`LineModel`)
    medium : fluid density [kg/m^3], gravity [m/s^2], seabed and current
    elements : target number of elements [-]
    extras : dynamic-only properties (bending ends, bodies, seabed contact, free ends)
    """
    return discretise_nodes(line, medium, uniform_nodes(line, elements), extras)


def uniform_nodes(line: LineModel, elements: int) -> np.ndarray:
    """Arc lengths [m] of about ``elements`` elements, equal within each segment, with a
    node on every segment boundary (:func:`element_counts`)."""
    counts = element_counts(line.length, elements)
    bounds = line.segment_ends
    return np.concatenate(
        [np.linspace(bounds[i], bounds[i + 1], counts[i] + 1)[:-1] for i in range(len(counts))]
        + [bounds[-1:]]
    )


def lump_on_nodes(per_length: np.ndarray, seg: np.ndarray, l0: np.ndarray, n: int) -> np.ndarray:
    """Per node (n,) half of each adjacent element's ``per_length`` (by segment; ``seg``
    each element's) times its length ``l0`` [m]."""
    half = 0.5 * per_length[seg] * l0
    out = np.zeros(n)
    out[:-1] += half
    out[1:] += half
    return out


def discretise_nodes(
    line: LineModel, medium: Medium, s: np.ndarray, extras: DynamicExtras | None = None
) -> DiscreteLine:
    """The lumped-mass model of ``line`` with nodes at the arc lengths ``s`` [m]
    (increasing from 0 to the line length; an element straddling a segment boundary
    takes the segment of its midpoint)."""
    extras = extras or DynamicExtras()
    s = np.asarray(s, dtype=float)
    ends = line.segment_ends
    seg = np.clip(
        np.searchsorted(ends, 0.5 * (s[:-1] + s[1:]), side="right") - 1, 0, line.length.size - 1
    )
    l0 = np.diff(s)
    rho = medium.density
    area = np.pi * line.diameter**2 / 4.0
    ea = line.axial_stiffness[seg]
    m_el = line.mass[seg]
    c_int = line.damping_ratio[seg] * l0 * np.sqrt(ea * m_el)
    n = s.size

    lump = functools.partial(lump_on_nodes, seg=seg, l0=l0, n=n)
    mass = lump(line.mass)
    added_n = lump(line.added_mass_normal * rho * area)
    added_t = lump(line.added_mass_tangential * rho * area)
    drag_n = lump(0.5 * rho * line.drag_normal * line.diameter)
    drag_t = lump(0.5 * rho * np.pi * line.drag_tangential * line.diameter)
    n_seg = line.length.size
    c_tr = extras.transverse_damping if extras.transverse_damping.size else np.zeros(n_seg)
    transverse = lump(np.asarray(c_tr, dtype=float))
    force = np.zeros((n, 3))
    force[:, 2] = -lump(line.weight)
    body_added = np.zeros(n)
    body_drag = np.zeros(n)
    n_att = line.attachment_s.size
    att_added = (
        extras.attachment_added_mass if extras.attachment_added_mass.size else np.zeros(n_att)
    )
    att_drag = extras.attachment_drag_area if extras.attachment_drag_area.size else np.zeros(n_att)
    for k in range(n_att):
        sa = float(line.attachment_s[k])
        e = int(np.clip(np.searchsorted(s, sa, side="right") - 1, 0, n - 2))
        xi = (sa - s[e]) / l0[e]
        for node, share in ((e, 1.0 - xi), (e + 1, xi)):
            force[node] += share * line.attachment_force[k]
            mass[node] += share * line.attachment_mass[k]
            body_added[node] += share * att_added[k]
            body_drag[node] += share * 0.5 * rho * att_drag[k]
    force[0] += extras.end_force[0]
    force[-1] += extras.end_force[1]
    held = np.ones(n, dtype=np.bool_)
    held[1:-1] = False
    held[0] = not extras.free_end[0]
    held[-1] = not extras.free_end[1]
    # bending: EI / h at interior nodes (h the mean of the two element lengths) and at
    # clamped ends (h = half the end element: the end node owns half an element)
    ei_el = line.bending_stiffness[seg]
    bending = np.zeros(n)
    if np.any(ei_el > 0.0):
        bending[1:-1] = 0.5 * (ei_el[:-1] + ei_el[1:]) / (0.5 * (l0[:-1] + l0[1:]))
    clamp = np.asarray(extras.clamp_direction, dtype=float).reshape(2, 3).copy()
    if np.any(clamp[0] != 0.0):
        bending[0] = ei_el[0] / (0.5 * l0[0])
    if np.any(clamp[1] != 0.0):
        bending[-1] = ei_el[-1] / (0.5 * l0[-1])
    # the seabed plane n . x = offset (the statics' plane; without a seabed at infinite depth)
    normal = Plane(0.0, medium.seabed_slope, medium.seabed_heading, 0.0).normal
    offset = float(normal[2] * -(medium.depth if medium.depth is not None else math.inf))
    k_sb = np.zeros(n)
    c_sb = np.zeros(n)
    if medium.depth is not None and extras.seabed_stiffness > 0.0:
        trib = lump(np.ones(n_seg))
        k_sb = extras.seabed_stiffness * trib
        inertia = mass + added_n + body_added
        c_sb = 2.0 * extras.seabed_damping_ratio * np.sqrt(k_sb * inertia)
    has_drag = bool(
        rho > 0.0 and (np.any(drag_n > 0.0) or np.any(drag_t > 0.0) or np.any(body_drag > 0.0))
    )
    laws = [line.law_of(i) for i in range(line.length.size)]
    code, params, knots, start, count = law_arrays(laws, seg)
    s0 = int(seg[0])
    first = np.array(
        [
            line.mass[s0],
            line.added_mass_normal[s0] * rho * area[s0],
            line.added_mass_tangential[s0] * rho * area[s0],
            0.5 * rho * line.drag_normal[s0] * line.diameter[s0],
            0.5 * rho * np.pi * line.drag_tangential[s0] * line.diameter[s0],
            float(np.asarray(c_tr, dtype=float)[s0]),
            line.weight[s0],
            extras.seabed_stiffness if np.any(k_sb > 0.0) else 0.0,
        ],
        dtype=float,
    )
    return DiscreteLine(
        s=s,
        rest_length=l0,
        axial_stiffness=ea,
        internal_damping=c_int,
        mass=mass,
        added_mass_normal=added_n,
        added_mass_tangential=added_t,
        drag_normal=drag_n,
        drag_tangential=drag_t,
        force=force,
        current_z=np.ascontiguousarray(medium.current_z, dtype=float),
        current_velocity=np.ascontiguousarray(medium.current_velocity, dtype=float).reshape(-1, 3),
        has_drag=has_drag,
        bending=bending,
        clamp_direction=clamp,
        transverse_damping=transverse,
        body_added_mass=body_added,
        body_drag=body_drag,
        held=held,
        seabed_normal=normal,
        seabed_offset=offset,
        seabed_stiffness=k_sb,
        seabed_damping=c_sb,
        friction=np.array([extras.friction_axial, extras.friction_lateral], dtype=float),
        law_code=code,
        law_params=params,
        law_knots=knots,
        law_start=start,
        law_count=count,
        first_per_length=first,
    )


def same_inputs(a: object, b: object, *, bitwise: bool = True) -> bool:
    """Whether two inputs of a discretisation are equal in every field (lines alike share
    one model): dataclasses field by field, arrays with their shapes and types, sequences
    item by item. Arrays compare byte for byte (``bitwise``: a NaN or a signed zero by its
    bits, never equal where the bits differ), else element by element where the bytes
    differ (-0.0 equals 0.0)."""
    if a is b:
        return True
    if type(a) is not type(b):
        return False
    if isinstance(a, np.ndarray):
        if a.shape != b.shape or a.dtype != b.dtype:  # type: ignore[attr-defined]
            return False
        return a.tobytes() == b.tobytes() or (not bitwise and bool(np.array_equal(a, b)))
    if dataclasses.is_dataclass(a):
        return all(
            same_inputs(getattr(a, f.name), getattr(b, f.name), bitwise=bitwise)
            for f in dataclasses.fields(a)
        )
    if isinstance(a, tuple | list):
        return len(a) == len(b) and all(  # type: ignore[arg-type]
            same_inputs(x, y, bitwise=bitwise)
            for x, y in zip(a, b, strict=True)  # type: ignore[arg-type]
        )
    return bool(a == b)


def interpolate_nodes(s_nodes: np.ndarray, s_points: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Linear interpolation along the line of nodal ``values`` (..., n + 1, 3) to arc
    lengths ``s_points`` [m]; returns (..., p, 3)."""
    e = np.clip(np.searchsorted(s_nodes, s_points, side="right") - 1, 0, s_nodes.size - 2)
    w = ((s_points - s_nodes[e]) / (s_nodes[e + 1] - s_nodes[e]))[:, None]
    return (1.0 - w) * values[..., e, :] + w * values[..., e + 1, :]
