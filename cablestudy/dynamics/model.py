"""Discretised line model: lumped masses at nodes joined by straight elastic elements.

One line model serves the time-domain solver (its forces and their tangents drive the
implicit step) and the discrete statics that start it. The line is cut along its
unstretched arc length ``s`` into elements (nodes at every segment boundary, so each
element has one material). Element ``e`` joins nodes ``e`` and ``e + 1``; with
``d = x[e+1] - x[e]``, ``l = |d|`` and unit vector ``u = d / l`` its strain and
tension are

    eps = l / l0 - 1                                  (exact for large displacements)
    T   = max(EA eps + c eps_dot, 0)  if eps > 0 else 0   (tension-only)

with ``eps_dot = u . (v[e+1] - v[e]) / l0`` and the internal damping ``c = zeta l0
sqrt(EA m)`` [N s] (``zeta``: fraction of critical damping of the element's axial
mode, the segments' ``damping_ratio``). This is the moustafa seed's nonlinear strain
(its eq. 2 is the same stretch written relative to the static catenary, eqs. 4-6)
without the small-strain truncation, and its tension law eq. (6) with the
compression cut off.

Bending (the ajayi seed's tensioned-beam term ``EI q''''``). The discrete curvature at
an interior node ``i`` is ``(u_i - u_{i-1}) / h_i`` with ``h_i`` the mean unstretched
length of its two elements; the bending energy is ``sum EI_i |u_i - u_{i-1}|^2 /
(2 h_i)``. Its gradient is the nodal bending force; its tangent is taken as the
Gauss-Newton part ``(EI/h) J^T J`` (exact for a straight line; the dropped term is of
order EI times the curvature, a quasi-Newton approximation). A ``pinned`` end carries
no curvature term (zero moment); a ``clamped`` end adds ``EI |u_end - d|^2 / l0`` with
``d`` the end's fixed direction (its static tangent), i.e. the end node owns half an
element of curvature. Bending couples a node to its second neighbours, so the
tangent has blocks two nodes off the diagonal.

Loads at nodes (tributary length = half of each adjacent element):

* weight in the fluid (weight minus buoyancy), attachment forces, and the constant
  force of a free ``force`` end, all constant;
* Morison drag on the relative velocity ``U = U_current(z) - v``, split along the node
  tangent ``t``: ``f = 1/2 rho d l (C_N |U_N| U_N + pi C_T |U_T| U_T)``
  (:mod:`cablestudy.physics.hydro`, the dodaran-park seed eqs. 38-39); lumped bodies
  (attachments with ``drag_area`` = C_D A) add ``1/2 rho C_D A |U| U``;
* transverse structural damping (the ajayi seed's ``c dq/dt``): ``-c l (v - (v.t) t)``;
* inertia ``M = m l I + C_a rho A l (I - t t) + C_at rho A l t t`` (structural mass
  plus added mass, normal and tangential), plus attachment masses and their
  isotropic added mass;
* seabed contact (:func:`seabed_contact_force` documents the law): a normal penalty
  spring and dashpot per unit length on the plane ``n . x = offset``, and Coulomb
  friction along and across the line as an elastic-plastic (stick-slip) law with a
  per-node anchor: the trial force ``-k_t (x - anchor)`` sticks while it is below
  ``mu N`` in each direction and slides at ``mu N`` otherwise. After each accepted step
  the anchors move so that the force is carried exactly (:func:`update_anchors`): at
  rest the friction force of the static solution is held, so a still line stays
  still; in sliding the friction always opposes the slip (it dissipates energy).

Nodes may be held (their motion prescribed: fixed or excited ends) or free (every
interior node, and an unexcited ``force`` end).

Everything here is pure: arrays in, arrays out, SI units. The kernels are compiled
with numba (cached on disk) because a time step is a few microseconds of arithmetic
on short arrays, where interpreter overhead would dominate.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from ..physics.contact import default_seabed_stiffness as contact_stiffness
from ..statics.base import LineModel, Medium


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

    def kernel_args(self) -> tuple:
        """The arrays in the order the compiled kernels take them."""
        return (
            self.rest_length,
            self.axial_stiffness,
            self.internal_damping,
            self.force,
            self.drag_normal,
            self.drag_tangential,
            self.added_mass_normal,
            self.added_mass_tangential,
            self.mass,
            self.current_z,
            self.current_velocity,
            self.has_drag,
            self.bending,
            self.clamp_direction,
            self.transverse_damping,
            self.body_added_mass,
            self.body_drag,
            self.held,
            self.seabed_normal,
            self.seabed_offset,
            self.seabed_stiffness,
            self.seabed_damping,
            self.friction,
            self.law_code,
            self.law_params,
            self.law_knots,
            self.law_start,
            self.law_count,
            self.broken,
        )


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


def seabed_plane(medium: Medium) -> tuple[np.ndarray, float]:
    """Unit upward normal and offset of the seabed plane ``n . x = offset`` (the plane
    through (0, 0, -depth) rising at ``seabed_slope`` towards ``seabed_heading``)."""
    rise = math.tan(medium.seabed_slope)
    ch, sh = math.cos(medium.seabed_heading), math.sin(medium.seabed_heading)
    normal = np.array([-rise * ch, -rise * sh, 1.0])
    normal /= np.linalg.norm(normal)
    depth = medium.depth if medium.depth is not None else math.inf
    return normal, float(normal[2] * -depth)


def default_seabed_stiffness(line: LineModel) -> float:
    """Default normal contact stiffness per length [N/m^2]
    (:func:`cablestudy.physics.contact.default_seabed_stiffness` of the line's weights)."""
    return contact_stiffness(line.weight)


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

    def lump(per_length: np.ndarray) -> np.ndarray:
        half = 0.5 * per_length[seg] * l0
        out = np.zeros(n)
        out[:-1] += half
        out[1:] += half
        return out

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
    normal, offset = seabed_plane(medium)
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


def interpolate_nodes(s_nodes: np.ndarray, s_points: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Linear interpolation along the line of nodal ``values`` (..., n + 1, 3) to arc
    lengths ``s_points`` [m]; returns (..., p, 3)."""
    e = np.clip(np.searchsorted(s_nodes, s_points, side="right") - 1, 0, s_nodes.size - 2)
    w = ((s_points - s_nodes[e]) / (s_nodes[e + 1] - s_nodes[e]))[:, None]
    return (1.0 - w) * values[..., e, :] + w * values[..., e + 1, :]


# ------------------------------------------------------------------ compiled kernels


@njit(cache=True)
def _add_bend_blocks(K_d, K_o, K_o2, kb, nodes, G, count):  # noqa: ANN001, ANN202
    """Add the Gauss-Newton blocks ``kb G_p G_q`` of one curvature term over the
    ``count`` nodes in ``nodes`` (increasing, consecutive) with 3 x 3 blocks ``G``."""
    for p in range(count):
        for q in range(p, count):
            i = nodes[p]
            j = nodes[q]
            for a in range(3):
                for b in range(3):
                    acc = 0.0
                    for c in range(3):
                        acc += G[p, a, c] * G[q, c, b]
                    acc *= kb
                    if j == i:
                        K_d[i, a, b] += acc
                    elif j == i + 1:
                        K_o[i, a, b] += acc
                    else:
                        K_o2[i, a, b] += acc


@njit(cache=True)
def axial_law(code, params, knots, start, count, ea, eps):  # noqa: ANN001, ANN201
    """Tension [N] and tangent dT/d(strain) [N] of an element's axial law at strain
    ``eps`` > 0 (the kernels' copy of :mod:`cablestudy.physics.axial`): 0 linear
    ``ea eps``; 1 polynomial ``sum c_i eps^i``; 2 steel wire ``k (eps - d (1 -
    exp(-eps/d)))``; 3 a table's monotone cubic Hermite curve, continued linearly."""
    if code == 0:
        return ea * eps, ea
    if code == 1:
        t = 0.0
        dt = 0.0
        for i in range(4, -1, -1):
            t = (t + params[i]) * eps
            dt = dt * eps + (i + 1) * params[i]
        return t, dt
    if code == 2:
        k = params[0]
        d = params[1]
        return k * (eps + d * math.expm1(-eps / d)), -k * math.expm1(-eps / d)
    lo = start
    hi = start + count - 1
    if eps >= knots[hi, 0]:
        return knots[hi, 1] + knots[hi, 2] * (eps - knots[hi, 0]), knots[hi, 2]
    j = lo
    while j < hi - 1 and knots[j + 1, 0] <= eps:
        j += 1
    h = knots[j + 1, 0] - knots[j, 0]
    u = (eps - knots[j, 0]) / h
    y0, y1 = knots[j, 1], knots[j + 1, 1]
    m0, m1 = knots[j, 2], knots[j + 1, 2]
    h00 = 2 * u**3 - 3 * u**2 + 1
    h10 = u**3 - 2 * u**2 + u
    h01 = -2 * u**3 + 3 * u**2
    h11 = u**3 - u**2
    t = h00 * y0 + h10 * h * m0 + h01 * y1 + h11 * h * m1
    dt = ((6 * u**2 - 6 * u) * y0 + (6 * u - 6 * u**2) * y1) / h + (
        (3 * u**2 - 4 * u + 1) * m0 + (3 * u**2 - 2 * u) * m1
    )
    return t, dt


@njit(cache=True, nogil=True)
def assemble(
    x,
    v,
    anchor,
    rest_length,
    axial_stiffness,
    internal_damping,
    force,
    drag_normal,
    drag_tangential,
    added_mass_normal,
    added_mass_tangential,
    mass,
    current_z,
    current_velocity,
    has_drag,
    bending,
    clamp_direction,
    transverse_damping,
    body_added_mass,
    body_drag,
    held,
    seabed_normal,
    seabed_offset,
    seabed_stiffness,
    seabed_damping,
    friction,
    law_code,
    law_params,
    law_knots,
    law_start,
    law_count,
    broken,
    F,
    K_d,
    K_o,
    K_o2,
    C_d,
    C_o,
    M_d,
    tension,
    strain,
    taut0,
    contact,
    friction_force,
    slip_state,
    trial,
):  # noqa: ANN001, ANN201
    """Nodal out-of-balance force ``F = f_internal - f_external`` [N] (n + 1, 3) at
    positions ``x`` [m] and velocities ``v`` [m/s] (friction anchors ``anchor`` [m]),
    so that ``M a + F = 0``; its tangents: stiffness ``K = dF/dx`` and damping
    ``C = dF/dv`` as diagonal blocks (n + 1, 3, 3), the blocks coupling node e to
    e + 1 (n, 3, 3) and (stiffness, bending only) node e to e + 2 (n - 1, 3, 3), the
    lower blocks being the transposes; the mass blocks ``M_d`` (n + 1, 3, 3) [kg];
    element tension [N] and strain [-] (n,); the seabed's normal force [N] (n + 1,)
    and friction force [N] (n + 1, 3) on each node.

    The derivatives of drag and added mass through the node tangent, of the current
    through z, of the friction through the normal force and of bending beyond its
    Gauss-Newton part are left out of the tangents (quasi-Newton). An element flagged
    in ``taut0`` (taut at the start of the time step) keeps its axial stiffness in
    ``K`` even where this iterate makes it slack: otherwise a predictor a few
    micrometres short would drop the axial stiffness of a taut element, and Newton
    would take a huge step along the line's soft (inextensional) modes."""
    n_el = rest_length.shape[0]
    n = n_el + 1
    for i in range(n):
        contact[i] = 0.0
        for a in range(3):
            F[i, a] = -force[i, a]
            friction_force[i, a] = 0.0
            for b in range(3):
                K_d[i, a, b] = 0.0
                C_d[i, a, b] = 0.0
                M_d[i, a, b] = 0.0
    for e in range(K_o2.shape[0]):
        for a in range(3):
            for b in range(3):
                K_o2[e, a, b] = 0.0
    uel = np.empty((n_el, 3))
    lel = np.empty(n_el)
    u = np.empty(3)
    for e in range(n_el):
        length2 = 0.0
        for a in range(3):
            u[a] = x[e + 1, a] - x[e, a]
            length2 += u[a] * u[a]
        length = math.sqrt(length2)
        rate = 0.0
        for a in range(3):
            u[a] /= length
            uel[e, a] = u[a]
            rate += u[a] * (v[e + 1, a] - v[e, a])
        lel[e] = length
        l0 = rest_length[e]
        eps = length / l0 - 1.0
        strain[e] = eps
        if broken[e]:
            tension[e] = 0.0
            for a in range(3):
                for b in range(3):
                    K_o[e, a, b] = 0.0
                    C_o[e, a, b] = 0.0
            continue
        t = 0.0
        kax = 0.0
        cax = 0.0
        if eps > 0.0:
            t_el, k_el = axial_law(
                law_code[e],
                law_params[e],
                law_knots,
                law_start[e],
                law_count[e],
                axial_stiffness[e],
                eps,
            )
            t = t_el + internal_damping[e] * rate / l0
            if t > 0.0:
                kax = k_el / l0
                cax = internal_damping[e] / l0
            else:
                t = 0.0
        if taut0[e] and kax == 0.0:
            kax = axial_stiffness[e] / l0
        tension[e] = t
        kg = t / length
        for a in range(3):
            F[e + 1, a] += t * u[a]
            F[e, a] -= t * u[a]
            for b in range(3):
                k = (kax - kg) * u[a] * u[b]
                if a == b:
                    k += kg
                c = cax * u[a] * u[b]
                K_d[e, a, b] += k
                K_d[e + 1, a, b] += k
                K_o[e, a, b] = -k
                C_d[e, a, b] += c
                C_d[e + 1, a, b] += c
                C_o[e, a, b] = -c
    # bending: curvature terms at interior nodes and clamped ends
    G = np.zeros((3, 3, 3))
    nodes = np.zeros(3, dtype=np.int64)
    for i in range(n):
        kb = bending[i]
        if kb == 0.0:
            continue
        if 0 < i < n - 1:
            ea_ = i - 1
            eb_ = i
            if broken[ea_] or broken[eb_]:
                continue  # no moment across a parted element
            la = lel[ea_]
            lb = lel[eb_]
            # r = u_b - u_a; E = kb/2 |r|^2; G_p = d r / d x_p
            for a in range(3):
                for b in range(3):
                    pa = (1.0 if a == b else 0.0) - uel[ea_, a] * uel[ea_, b]
                    pb = (1.0 if a == b else 0.0) - uel[eb_, a] * uel[eb_, b]
                    G[0, a, b] = pa / la
                    G[1, a, b] = -pa / la - pb / lb
                    G[2, a, b] = pb / lb
            nodes[0] = i - 1
            nodes[1] = i
            nodes[2] = i + 1
            count = 3
            for a in range(3):
                r_a = uel[eb_, a] - uel[ea_, a]
                u[a] = r_a
        else:
            end = 0 if i == 0 else 1
            e = 0 if i == 0 else n_el - 1
            if broken[e]:
                continue
            le = lel[e]
            # r = u_e - d; G for the element's first and second node
            for a in range(3):
                for b in range(3):
                    p = (1.0 if a == b else 0.0) - uel[e, a] * uel[e, b]
                    G[0, a, b] = -p / le
                    G[1, a, b] = p / le
                u[a] = uel[e, a] - clamp_direction[end, a]
            nodes[0] = e
            nodes[1] = e + 1
            count = 2
        # force: kb G_p^T r (G symmetric)
        for p in range(count):
            node = nodes[p]
            for a in range(3):
                acc = 0.0
                for c in range(3):
                    acc += G[p, a, c] * u[c]
                F[node, a] += kb * acc
        _add_bend_blocks(K_d, K_o, K_o2, kb, nodes, G, count)
    tan = np.empty(3)
    rel = np.empty(3)
    un = np.empty(3)
    nrm = seabed_normal
    for i in range(n):
        lo = i - 1 if i > 0 else 0
        hi = i + 1 if i < n - 1 else n - 1
        if 0 < i < n - 1:
            # a node beside a parted element is the end of its part
            if broken[i - 1]:
                lo = i
            elif broken[i]:
                hi = i
        norm2 = 0.0
        for a in range(3):
            tan[a] = x[hi, a] - x[lo, a]
            norm2 += tan[a] * tan[a]
        norm = math.sqrt(norm2)
        for a in range(3):
            tan[a] /= norm
        mn = added_mass_normal[i]
        mt = added_mass_tangential[i]
        for a in range(3):
            for b in range(3):
                M_d[i, a, b] = (mt - mn) * tan[a] * tan[b]
            M_d[i, a, a] += mass[i] + mn + body_added_mass[i]
        ctr = transverse_damping[i]
        if ctr > 0.0:
            vt = v[i, 0] * tan[0] + v[i, 1] * tan[1] + v[i, 2] * tan[2]
            for a in range(3):
                F[i, a] += ctr * (v[i, a] - vt * tan[a])
                for b in range(3):
                    C_d[i, a, b] += ctr * ((1.0 if a == b else 0.0) - tan[a] * tan[b])
        if has_drag:
            for a in range(3):
                if current_z.shape[0] > 0:
                    rel[a] = np.interp(x[i, 2], current_z, current_velocity[:, a]) - v[i, a]
                else:
                    rel[a] = -v[i, a]
            rt = rel[0] * tan[0] + rel[1] * tan[1] + rel[2] * tan[2]
            sn2 = 0.0
            for a in range(3):
                un[a] = rel[a] - rt * tan[a]
                sn2 += un[a] * un[a]
            sn = math.sqrt(sn2)
            cn = drag_normal[i]
            ct = drag_tangential[i]
            st = abs(rt)
            for a in range(3):
                F[i, a] -= cn * sn * un[a] + ct * st * rt * tan[a]
                for b in range(3):
                    c = 2.0 * ct * st * tan[a] * tan[b] - cn * sn * tan[a] * tan[b]
                    if sn > 0.0:
                        c += cn * un[a] * un[b] / sn
                    if a == b:
                        c += cn * sn
                    C_d[i, a, b] += c
            cb = body_drag[i]
            if cb > 0.0:
                sr = math.sqrt(rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2])
                for a in range(3):
                    F[i, a] -= cb * sr * rel[a]
                    for b in range(3):
                        c = 0.0
                        if sr > 0.0:
                            c = cb * rel[a] * rel[b] / sr
                        if a == b:
                            c += cb * sr
                        C_d[i, a, b] += c
        ks = seabed_stiffness[i]
        if ks > 0.0:
            gap = nrm[0] * x[i, 0] + nrm[1] * x[i, 1] + nrm[2] * x[i, 2] - seabed_offset
            # contact: by the law (state 0: touching where gap <= 0, pushing only), or
            # held fixed during a time step's Newton iterations (1: touching, the
            # spring and damper linear, 2: not), see contact_changed
            cstate = slip_state[i, 2] if slip_state.shape[1] > 2 else 0
            if ((cstate == 0 or cstate == 3) and gap <= 0.0) or cstate == 1:
                vn = nrm[0] * v[i, 0] + nrm[1] * v[i, 1] + nrm[2] * v[i, 2]
                cs = seabed_damping[i] if cstate != 3 else 0.0
                fn = -ks * gap - cs * vn
                if fn < 0.0 and cstate != 1:
                    fn = 0.0
                    cs = 0.0
                contact[i] = max(fn, 0.0)
                for a in range(3):
                    F[i, a] -= fn * nrm[a]
                    for b in range(3):
                        K_d[i, a, b] += ks * nrm[a] * nrm[b]
                        C_d[i, a, b] += cs * nrm[a] * nrm[b]
                if fn > 0.0 and (friction[0] > 0.0 or friction[1] > 0.0):
                    _friction(
                        i,
                        x,
                        anchor,
                        tan,
                        nrm,
                        ks,
                        cs,
                        fn,
                        friction,
                        F,
                        K_d,
                        C_d,
                        friction_force,
                        slip_state,
                        trial,
                    )


@njit(cache=True)
def _friction(  # noqa: ANN202
    i,  # noqa: ANN001
    x,  # noqa: ANN001
    anchor,  # noqa: ANN001
    tan,  # noqa: ANN001
    nrm,  # noqa: ANN001
    kt,  # noqa: ANN001
    cs,  # noqa: ANN001
    fn,  # noqa: ANN001
    friction,  # noqa: ANN001
    F,  # noqa: ANN001
    K_d,  # noqa: ANN001
    C_d,  # noqa: ANN001
    friction_force,  # noqa: ANN001
    slip_state,  # noqa: ANN001
    trial,  # noqa: ANN001
):
    """Elastic-plastic Coulomb friction at contact node ``i``: along the line (the node
    tangent projected on the seabed) and across it, each a spring of stiffness ``kt``
    [N/m] to the node's anchor, capped at ``mu N``.

    ``slip_state[i, k]`` (k = 0 along, 1 across) chooses how: 0 by the trial spring
    force (stick below mu N, else slide at mu N); 2 stick (the spring, uncapped);
    +1 / -1 slide at +- mu N, with the tangent of mu N through the normal force
    (``mu k_n`` and ``mu c_n`` coupling the normal motion). The time step fixes the
    states during its Newton iterations, so that they see a smooth force, and checks
    them when it has converged (:func:`cablestudy.dynamics.integrator.alpha_step`).
    The trial spring force is written to ``trial[i, k]`` [N]."""
    ea = np.empty(3)
    el = np.empty(3)
    tn = tan[0] * nrm[0] + tan[1] * nrm[1] + tan[2] * nrm[2]
    s2 = 0.0
    for a in range(3):
        ea[a] = tan[a] - tn * nrm[a]
        s2 += ea[a] * ea[a]
    if s2 < 1e-24:  # tangent normal to the seabed: any direction in the plane
        ea[0], ea[1], ea[2] = nrm[1], -nrm[0], 0.0
        s2 = ea[0] * ea[0] + ea[1] * ea[1]
        if s2 < 1e-24:
            ea[0], ea[1], ea[2] = 1.0, 0.0, 0.0
            s2 = 1.0
    sn = math.sqrt(s2)
    for a in range(3):
        ea[a] /= sn
    el[0] = nrm[1] * ea[2] - nrm[2] * ea[1]
    el[1] = nrm[2] * ea[0] - nrm[0] * ea[2]
    el[2] = nrm[0] * ea[1] - nrm[1] * ea[0]
    da = 0.0
    dl = 0.0
    for a in range(3):
        d = x[i, a] - anchor[i, a]
        da += d * ea[a]
        dl += d * el[a]
    for k in range(2):
        mu = friction[k]
        if mu <= 0.0:
            continue
        e = ea if k == 0 else el
        f = -kt * (da if k == 0 else dl)
        trial[i, k] = f
        cap = mu * fn
        state = slip_state[i, k]
        stick = True
        sign = 0.0
        if state == 1 or state == -1:
            sign = float(state)
        elif state == 0:
            if f > cap:
                sign = 1.0
            elif f < -cap:
                sign = -1.0
        if sign != 0.0:
            f = sign * cap
            stick = False
        for a in range(3):
            F[i, a] -= f * e[a]
            friction_force[i, a] += f * e[a]
            if stick:
                for b in range(3):
                    K_d[i, a, b] += kt * e[a] * e[b]
            elif state != 0:
                # d(-f e)/dx with f = sign mu N(x, v): N = -k_n gap - c_n v_n
                for b in range(3):
                    K_d[i, a, b] += sign * mu * kt * e[a] * nrm[b]
                    C_d[i, a, b] += sign * mu * cs * e[a] * nrm[b]


@njit(cache=True)
def update_anchors(x, friction_force, seabed_stiffness, contact, anchor):  # noqa: ANN001, ANN201
    """Friction anchors after an accepted state: where the node touches the seabed, the
    point at which the friction spring carries the friction force just computed
    (``anchor = x + f / k_t``); elsewhere the node itself (no friction stored)."""
    for i in range(x.shape[0]):
        kt = seabed_stiffness[i]
        for a in range(3):
            if contact[i] > 0.0 and kt > 0.0:
                anchor[i, a] = x[i, a] + friction_force[i, a] / kt
            else:
                anchor[i, a] = x[i, a]


@njit(cache=True)
def solve_banded(J_d, J_o, J_o2, held, rhs, out, band):  # noqa: ANN001, ANN201
    """Solve ``J dx = rhs`` for a block-banded ``J`` with 3 x 3 blocks: diagonal blocks
    ``J_d`` (m, 3, 3), upper blocks one node off ``J_o`` (m - 1, 3, 3) and two nodes
    off ``J_o2`` (m - 2, 3, 3) (empty when the tangent has none), the lower blocks
    being their transposes. Rows of ``held`` nodes are replaced by the identity with a
    zero right side. LU without pivoting on the scalar band (half-bandwidth 5 or 8) in
    the work array ``band`` (3m, 17): the systems here are dominated by their
    diagonal (mass, or stiffness plus regularisation). Returns False on a zero or
    non-finite pivot."""
    m = J_d.shape[0]
    N = 3 * m
    reach = 2 if J_o2.shape[0] > 0 else 1
    bw = 3 * reach + 2
    W = 2 * bw + 1
    for r_ in range(N):
        for c in range(W):
            band[r_, c] = 0.0
    for i in range(m):
        for a in range(3):
            row = 3 * i + a
            if held[i]:
                band[row, bw] = 1.0
                continue
            for b in range(3):
                band[row, bw + b - a] += J_d[i, a, b]
                if i + 1 < m:
                    band[row, bw + 3 + b - a] += J_o[i, a, b]
                if i >= 1:
                    band[row, bw - 3 + b - a] += J_o[i - 1, b, a]
                if reach == 2:
                    if i + 2 < m:
                        band[row, bw + 6 + b - a] += J_o2[i, a, b]
                    if i >= 2:
                        band[row, bw - 6 + b - a] += J_o2[i - 2, b, a]
    for i in range(m):
        for a in range(3):
            out[i, a] = 0.0 if held[i] else rhs[i, a]
    y = out.reshape(N)
    for k in range(N):
        piv = band[k, bw]
        if not (abs(piv) > 0.0) or not math.isfinite(piv):
            return False
        top = min(k + bw + 1, N)
        for r_ in range(k + 1, top):
            lf = band[r_, bw + k - r_]
            if lf == 0.0:
                continue
            lf /= piv
            band[r_, bw + k - r_] = lf
            for c in range(k + 1, top):
                band[r_, bw + c - r_] -= lf * band[k, bw + c - k]
            y[r_] -= lf * y[k]
    for k in range(N - 1, -1, -1):
        acc = y[k]
        top = min(k + bw + 1, N)
        for c in range(k + 1, top):
            acc -= band[k, bw + c - k] * y[c]
        y[k] = acc / band[k, bw]
    return True


class Workspace:
    """Scratch arrays of the kernels for a line of ``n`` elements (allocated once per
    run, reused every step), and the friction anchors (state carried between steps)."""

    def __init__(self, n_elements: int) -> None:
        n = n_elements + 1
        self.F = np.zeros((n, 3))
        self.K_d = np.zeros((n, 3, 3))
        self.K_o = np.zeros((n - 1, 3, 3))
        self.K_o2 = np.zeros((max(n - 2, 0), 3, 3))
        self.C_d = np.zeros((n, 3, 3))
        self.C_o = np.zeros((n - 1, 3, 3))
        self.M_d = np.zeros((n, 3, 3))
        self.tension = np.zeros(n - 1)
        self.strain = np.zeros(n - 1)
        self.taut0 = np.zeros(n - 1, dtype=np.bool_)
        self.contact = np.zeros(n)
        self.friction = np.zeros((n, 3))
        self.anchor = np.zeros((n, 3))
        # stick/slip along and across the line, and the contact state (assemble)
        self.slip_state = np.zeros((n, 3), dtype=np.int64)
        self.trial = np.zeros((n, 2))
        self.J_d = np.zeros((n, 3, 3))
        self.J_o = np.zeros((n - 1, 3, 3))
        self.J_o2 = np.zeros((max(n - 2, 0), 3, 3))
        self.r = np.zeros((n, 3))
        self.dx = np.zeros((n, 3))
        self.band = np.zeros((3 * n, 17))

    def assemble_args(self) -> tuple:
        return (
            self.F,
            self.K_d,
            self.K_o,
            self.K_o2,
            self.C_d,
            self.C_o,
            self.M_d,
            self.tension,
            self.strain,
            self.taut0,
            self.contact,
            self.friction,
            self.slip_state,
            self.trial,
        )

    def solver_args(self, line: DiscreteLine) -> tuple:
        """Jacobian blocks, residual, correction and band work array (the two-off
        blocks empty unless the line bends)."""
        J_o2 = self.J_o2 if line.has_bending else self.J_o2[:0]
        return (self.J_d, self.J_o, J_o2, self.r, self.dx, self.band)


def evaluate(
    line: DiscreteLine,
    x: np.ndarray,
    v: np.ndarray,
    work: Workspace | None = None,
    anchor: np.ndarray | None = None,
) -> Workspace:
    """Forces, tangents, masses and tensions at state (``x`` [m], ``v`` [m/s]), with
    friction anchors ``anchor`` [m] (default: the workspace's)."""
    work = work or Workspace(line.n_elements)
    if anchor is not None:
        work.anchor[:] = anchor
    assemble(
        np.ascontiguousarray(x, dtype=float),
        np.ascontiguousarray(v, dtype=float),
        work.anchor,
        *line.kernel_args(),
        *work.assemble_args(),
    )
    return work


@njit(cache=True)
def _trial_states(slip_state, trial, contact, friction, keep=False):  # noqa: ANN001, ANN202
    """Stick/slip state of every contact node from its trial spring force: stick (2)
    within mu N, else slide (+-1) with the force's sign; 0 off the seabed. With
    ``keep``, a contact node that has a state keeps it."""
    for i in range(slip_state.shape[0]):
        for k in range(2):
            if keep and contact[i] > 0.0 and slip_state[i, k] != 0:
                continue
            slip_state[i, k] = 0
            if contact[i] > 0.0 and friction[k] > 0.0:
                cap = friction[k] * contact[i]
                if trial[i, k] > cap:
                    slip_state[i, k] = 1
                elif trial[i, k] < -cap:
                    slip_state[i, k] = -1
                else:
                    slip_state[i, k] = 2


@njit(cache=True)
def contact_states(
    x, v, seabed_normal, seabed_offset, seabed_stiffness, seabed_damping, slip_state, fix, count
):  # noqa: ANN001, ANN201, E501
    """Contact states from the contact law at (``x``, ``v``): touching (1) where the
    node is at or below the seabed plane and the spring and damper push, else not (2).
    With ``fix`` False, set them all (the start of a time step); else update them after
    Newton converged with states held fixed and return whether any changed: a node whose
    state has changed ``MAX_CONTACT_FLIPS`` times in the step (it sits on the plane,
    where neither state is consistent) goes back to the law itself (0), which the
    Newton iterations then meet with their landing clip."""
    changed = False
    for i in range(x.shape[0]):
        ks = seabed_stiffness[i]
        if ks <= 0.0 or slip_state[i, 2] == 3 and fix:
            continue
        gap = -seabed_offset
        vn = 0.0
        for a in range(3):
            gap += seabed_normal[a] * x[i, a]
            vn += seabed_normal[a] * v[i, a]
        touching = gap <= 0.0 and -ks * gap - seabed_damping[i] * vn > 0.0
        want = 1 if touching else 2
        if not fix:
            slip_state[i, 2] = want
            count[i] = 0
        elif slip_state[i, 2] != want and count[i] < MAX_CONTACT_FLIPS:
            count[i] += 1
            slip_state[i, 2] = want if count[i] < MAX_CONTACT_FLIPS else 1
            changed = True
    return changed


#: contact state changes of a node within one time step before the law takes over
MAX_CONTACT_FLIPS = 2


@njit(cache=True)
def states_changed(slip_state, trial, contact, friction):  # noqa: ANN001, ANN201
    """Update fixed stick/slip states from a converged state; True if any changed.

    A sticking node whose spring force exceeds mu N slides (with the spring's sign); a
    sliding node whose spring force is back within mu N, or points the other way,
    sticks. Nodes that lost contact, or gained it (state 0), take the trial rule."""
    changed = False
    for i in range(slip_state.shape[0]):
        for k in range(2):
            state = slip_state[i, k]
            if friction[k] <= 0.0:
                continue
            if contact[i] <= 0.0:
                if state != 0:
                    slip_state[i, k] = 0
                continue
            cap = friction[k] * contact[i] * (1.0 + 1e-9)
            f = trial[i, k]
            if state == 0:
                continue
            if state == 2 and abs(f) > cap:
                slip_state[i, k] = 1 if f > 0.0 else -1
                changed = True
            elif (state == 1 or state == -1) and state * f < cap * (1.0 - 2e-9):
                slip_state[i, k] = 2
                changed = True
    return changed


@njit(cache=True, nogil=True)
def _static_newton(
    x,
    anchor,
    rest_length,
    axial_stiffness,
    internal_damping,
    force,
    drag_normal,
    drag_tangential,
    added_mass_normal,
    added_mass_tangential,
    mass,
    current_z,
    current_velocity,
    has_drag,
    bending,
    clamp_direction,
    transverse_damping,
    body_added_mass,
    body_drag,
    held,
    seabed_normal,
    seabed_offset,
    seabed_stiffness,
    seabed_damping,
    friction,
    law_code,
    law_params,
    law_knots,
    law_start,
    law_count,
    broken,
    F,
    K_d,
    K_o,
    K_o2,
    C_d,
    C_o,
    M_d,
    tension,
    strain,
    taut0,
    contact,
    friction_force,
    slip_state,
    trial,
    J_d,
    J_o,
    J_o2,
    r,
    dx,
    band,
    tol,
    max_iterations,
):  # noqa: ANN001, ANN201
    n = x.shape[0]
    v = np.zeros_like(x)
    res = np.inf
    lmin = rest_length.min()
    reg = 1e-9 * (axial_stiffness.max() / lmin)
    # a Newton correction below ~1000 ulp of the coordinates cannot lower the residual
    # further (the solve of a stiff line, EA / T up to 1e10, carries its condition
    # number's rounding): the equilibrium is then found to rounding
    reach = 0.0
    for i in range(n):
        for a in range(3):
            reach = max(reach, abs(x[i, a]))
    reach += rest_length.sum()
    floor = 1024.0 * 2.220446049250313e-16 * reach
    has_friction = (friction[0] > 0.0 or friction[1] > 0.0) and seabed_stiffness.max() > 0.0
    has_friction = has_friction and math.isfinite(friction[0]) and math.isfinite(friction[1])
    fix_states = has_friction
    for i in range(n):
        for k in range(2):
            slip_state[i, k] = 0
    checks = 0
    it = 0
    while True:
        assemble(
            x,
            v,
            anchor,
            rest_length,
            axial_stiffness,
            internal_damping,
            force,
            drag_normal,
            drag_tangential,
            added_mass_normal,
            added_mass_tangential,
            mass,
            current_z,
            current_velocity,
            has_drag,
            bending,
            clamp_direction,
            transverse_damping,
            body_added_mass,
            body_drag,
            held,
            seabed_normal,
            seabed_offset,
            seabed_stiffness,
            seabed_damping,
            friction,
            law_code,
            law_params,
            law_knots,
            law_start,
            law_count,
            broken,
            F,
            K_d,
            K_o,
            K_o2,
            C_d,
            C_o,
            M_d,
            tension,
            strain,
            taut0,
            contact,
            friction_force,
            slip_state,
            trial,
        )
        if fix_states:
            # friction as an active set, as in the time step: the trial decides which
            # contact nodes stick and which slide, Newton keeps those states
            fix_states = False
            _trial_states(slip_state, trial, contact, friction)
            continue
        res = 0.0
        for i in range(n):
            if held[i]:
                continue
            for a in range(3):
                res = max(res, abs(F[i, a]))
        if res <= tol:
            if (
                has_friction
                and checks < 20
                and states_changed(slip_state, trial, contact, friction)
            ):
                checks += 1
                continue
            return it, res, True
        if it >= max_iterations:
            break
        it += 1
        # a little mass-like regularisation keeps slack nodes solvable; kept well below
        # the geometric stiffness T / l of the taut elements, or a light line's soft
        # modes would converge only linearly
        tmax = 0.0
        for e in range(tension.shape[0]):
            tmax = max(tmax, tension[e])
        reg_it = min(reg, max(1e-6 * tmax / lmin, 1e-6 * reg))
        for i in range(n):
            for a in range(3):
                r[i, a] = -F[i, a]
                for b in range(3):
                    J_d[i, a, b] = K_d[i, a, b]
                J_d[i, a, a] += reg_it
        for i in range(n - 1):
            for a in range(3):
                for b in range(3):
                    J_o[i, a, b] = K_o[i, a, b]
        for i in range(J_o2.shape[0]):
            for a in range(3):
                for b in range(3):
                    J_o2[i, a, b] = K_o2[i, a, b]
        ok = solve_banded(J_d, J_o, J_o2, held, r, dx, band)
        if not ok:
            return it, res, False
        big = 0.0
        for i in range(n):
            for a in range(3):
                big = max(big, abs(dx[i, a]))
        if big <= floor:
            return it, res, True
        scale = 1.0
        if big > 0.25 * lmin:
            scale = 0.25 * lmin / big
        for i in range(n):
            for a in range(3):
                x[i, a] += scale * dx[i, a]
    return max_iterations, res, False


def stretched_start(line: DiscreteLine, x0: np.ndarray, tension: np.ndarray) -> np.ndarray:
    """Node positions with the directions of ``x0``'s chords and the lengths the element
    ``tension`` [N] (n,) stretches them to, ``l0 (1 + T / EA)``, rebuilt from end A,
    with the misclosure at end B (if held) spread along the line in proportion to arc
    length. The chords of a smooth curve sampled at the nodes are shorter than its arcs
    by O(h^2 kappa^2): on a stiff line that error times EA is a large spurious tension,
    which this start removes before Newton."""
    d = np.diff(x0, axis=0)
    u = d / np.linalg.norm(d, axis=1, keepdims=True)
    chord = line.rest_length * (1.0 + np.maximum(tension, 0.0) / line.axial_stiffness)
    x = np.vstack([x0[:1], x0[0] + np.cumsum(u * chord[:, None], axis=0)])
    if line.held[-1]:
        frac = (line.s - line.s[0]) / (line.s[-1] - line.s[0])
        x += frac[:, None] * (x0[-1] - x[-1])[None, :]
    return x


def static_equilibrium(
    line: DiscreteLine,
    x0: np.ndarray,
    *,
    tolerance: float,
    max_iterations: int = 100,
    tension: np.ndarray | None = None,
    fallback_tension: np.ndarray | None = None,
) -> tuple[np.ndarray, int, float, bool, np.ndarray]:
    """Equilibrium of the discrete line with its held nodes where ``x0`` puts them.

    Newton from ``x0`` (the continuous static solution at the nodes), so that the time
    integration starts at rest in the discrete model's own equilibrium. Seabed friction
    starts from anchors at ``x0``: friction is mobilised by the small displacement
    from the continuous solution (at most ``mu N / k_t``), never beyond ``mu N``.

    Given the element ``tension`` [N] (n,) of the continuous solution, Newton starts
    from :func:`stretched_start`. Where Newton on positions fails (a stiff line, on a
    seabed), Newton on positions and element tensions
    (:func:`cablestudy.dynamics.mixed.mixed_equilibrium`) from ``x0`` and that tension
    (or ``fallback_tension`` [N] (n,), which leaves the first start at ``x0``) gives
    the equilibrium.

    Returns positions [m] (n + 1, 3), iterations, the largest nodal out-of-balance
    force [N], whether it fell below ``tolerance`` [N], and the friction anchors [m]
    that hold the friction forces of that equilibrium.
    """
    x = np.array(x0, dtype=float, copy=True)
    if tension is not None:
        x = stretched_start(line, x, np.asarray(tension, dtype=float))
    work = Workspace(line.n_elements)
    work.anchor[:] = x
    if line.has_seabed:
        x, work.anchor[:] = _seated_start(line, x, work)
    start, start_anchor = x.copy(), work.anchor.copy()
    it, res, ok = _static_newton(
        x,
        work.anchor,
        *line.kernel_args(),
        *work.assemble_args(),
        *work.solver_args(line),
        tolerance,
        max_iterations,
    )
    if tension is None:
        tension = fallback_tension
    if not ok and tension is not None:
        from .mixed import is_finite_line, mixed_equilibrium

        if is_finite_line(line):
            # Newton on positions cannot start (a stiff line: EA times the start's chord
            # error is a large spurious force): Newton on positions and tensions from
            # the same start, which has no such force
            t0 = np.maximum(np.asarray(tension, dtype=float), 0.0)
            xm = np.array(x0, dtype=float, copy=True)
            anchor_m = xm.copy()
            if line.has_seabed:
                xm, anchor_m = _seated_start(line, xm, Workspace(line.n_elements), t0)
            sol = mixed_equilibrium(
                line,
                xm,
                t0,
                anchor_m,
                tol_force=tolerance,
                relative=tolerance / max(float(np.max(t0)), tolerance),
                max_iterations=max_iterations,
            )
            it += sol.iterations
            if sol.converged:
                return sol.position, int(it), sol.force_residual, True, sol.anchor
            x = start
            work.anchor[:] = start_anchor
            evaluate(line, x, np.zeros_like(x), work)
    anchor = work.anchor.copy()
    update_anchors(x, work.friction, line.seabed_stiffness, work.contact, anchor)
    return x, int(it), float(res), bool(ok), anchor


def _seated_start(
    line: DiscreteLine, x: np.ndarray, work: Workspace, tension: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Newton's start on a penalty seabed: nodes that the continuous (rigid-seabed)
    solution lays on the seabed sink by their own penetration (normal load over contact
    stiffness), and their friction anchors are placed so that the friction springs
    already carry the tangential force the laid line needs there (the continuous
    solution's mobilised friction), capped at ``mu N`` along and across the line.
    Given the element ``tension`` [N] (n,), the elements pull with it rather than with
    the tension their chords' stretch gives (on a stiff line that is EA times the
    chords' error). Returns the positions [m] and anchors [m]."""
    normal = line.seabed_normal
    scale = float(np.max(np.abs(x))) + float(np.sum(line.rest_length))
    laid = (x @ normal - line.seabed_offset <= 1e-9 * scale) & (line.seabed_stiffness > 0.0)
    laid &= ~np.asarray(line.held, dtype=bool)  # a held node stays where it is held
    if not np.any(laid):
        return x, x.copy()
    x = x.copy()
    x[laid] += np.outer(line.seabed_offset - x[laid] @ normal, normal)  # onto the plane
    still = np.zeros_like(x)

    def out_of_balance(x: np.ndarray) -> np.ndarray:
        if tension is None:
            return evaluate(line, x, still, work, anchor=x).F.copy()
        from .mixed import axial_forces, other_forces_line

        f = evaluate(other_forces_line(line), x, still, work, anchor=x).F
        return f + axial_forces(x, tension)[0]

    press = out_of_balance(x) @ normal  # load on the seabed
    sink = np.where(laid, np.maximum(press, 0.0) / np.maximum(line.seabed_stiffness, 1e-300), 0.0)
    x -= sink[:, None] * normal
    out = out_of_balance(x)
    w = work
    need = out - np.outer(out @ normal, normal)  # tangential out-of-balance: friction needed
    n = line.n_nodes
    tan = x[np.minimum(np.arange(n) + 1, n - 1)] - x[np.maximum(np.arange(n) - 1, 0)]
    along = tan - np.outer(tan @ normal, normal)
    along /= np.maximum(np.linalg.norm(along, axis=1, keepdims=True), 1e-300)
    across = np.cross(normal, along)
    cap = line.friction[:, None] * w.contact[None, :]
    fa = np.clip(np.einsum("ia,ia->i", need, along), -cap[0], cap[0])
    fl = np.clip(np.einsum("ia,ia->i", need, across), -cap[1], cap[1])
    f = np.where(laid[:, None], fa[:, None] * along + fl[:, None] * across, 0.0)
    return x, x + f / np.maximum(line.seabed_stiffness, 1e-300)[:, None]


def energies(
    line: DiscreteLine, x: np.ndarray, v: np.ndarray, anchor: np.ndarray | None = None
) -> tuple[float, float, float]:
    """(kinetic, stored elastic, potential of the constant nodal forces) energy [J] of
    the discrete line; the stored energy is the axial strain energy plus the bending
    and seabed-spring energies, and the potential is ``-sum(force . x)``."""
    if np.any(line.law_code != 0):
        raise ValueError("energies: the stored axial energy is written for T = EA strain")
    work = evaluate(line, x, v, anchor=anchor if anchor is not None else x)
    kinetic = 0.5 * float(np.einsum("ia,iab,ib->", v, work.M_d, v))
    eps = np.maximum(work.strain, 0.0)
    stored = 0.5 * float(np.sum(line.axial_stiffness * line.rest_length * eps**2))
    d = np.diff(x, axis=0)
    u = d / np.linalg.norm(d, axis=1, keepdims=True)
    if line.has_bending:
        stored += 0.5 * float(np.sum(line.bending[1:-1] * np.sum((u[1:] - u[:-1]) ** 2, 1)))
        for end, (e, node) in enumerate(((0, 0), (-1, -1))):
            if line.bending[node] > 0.0:
                r = u[e] - line.clamp_direction[end]
                stored += 0.5 * float(line.bending[node] * r @ r)
    if line.has_seabed:
        gap = x @ line.seabed_normal - line.seabed_offset
        stored += 0.5 * float(np.sum(line.seabed_stiffness * np.minimum(gap, 0.0) ** 2))
    potential = -float(np.sum(line.force * x))
    return kinetic, stored, potential
