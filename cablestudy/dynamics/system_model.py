"""The time-domain model of a mooring system: every line's lumped-mass model
(:mod:`.model`) packed one after another, the free points that join them, and the
driven points (fixed, on a prescribed body, or moved on their own).

:func:`pack` lays the lines' arrays end to end for the compiled kernels
(:mod:`.system_kernels`, :mod:`.system_march`); :func:`body_motion` packs the motion of
the bodies and points into the slots of :func:`.excitation.motion_at` (a system's slots).

Pure: arrays in, arrays out (SI units).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .discrete_line import DiscreteLine
from .excitation import TableMotion, table_args


@dataclass(frozen=True, kw_only=True)
class FreePoints:
    """The free points of a system: mass [kg] (structural plus added, isotropic),
    constant force [N] (P, 3) (weight, buoyancy, applied) and drag ``1/2 rho C_D A``
    [kg/m] (P,)."""

    mass: np.ndarray
    force: np.ndarray
    drag: np.ndarray


@dataclass(frozen=True, kw_only=True)
class Drives:
    """The driven (held) points: ``body`` (D,) index of the body carrying each (-1:
    none), ``slot`` (D,) its own motion's slot (-1: none), ``offset`` (D, 3) in the
    body frame, ``static`` (D, 3) its static position [m]; ``body_base`` (B, 6) the
    bodies' static positions and ``body_R0`` (B, 3, 3) their static rotations."""

    body: np.ndarray
    slot: np.ndarray
    offset: np.ndarray
    static: np.ndarray
    body_base: np.ndarray
    body_R0: np.ndarray


@dataclass(frozen=True, kw_only=True)
class SlotMotion:
    """Harmonics and tables of the motion slots (slot 2b: body b's translation, 2b + 1
    its rotation angles roll, pitch, yaw; 2B + q: point q's own motion), each along a
    unit direction, and the ramp [s]."""

    slot: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    direction: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    amplitude: np.ndarray = field(default_factory=lambda: np.zeros(0))
    frequency: np.ndarray = field(default_factory=lambda: np.zeros(0))
    phase: np.ndarray = field(default_factory=lambda: np.zeros(0))
    tables: tuple[tuple[int, TableMotion], ...] = ()
    ramp_time: float = 0.0

    def kernel_args(self) -> tuple:
        return (
            np.asarray(self.slot, dtype=np.int64),
            np.asarray(self.direction, dtype=float).reshape(-1, 3),
            np.asarray(self.amplitude, dtype=float),
            np.asarray(self.frequency, dtype=float),
            np.asarray(self.phase, dtype=float),
            float(self.ramp_time),
            *table_args([s for s, _ in self.tables], [t for _, t in self.tables]),
        )


@dataclass(frozen=True, kw_only=True)
class PackedSystem:
    """The packed arrays ``S`` of the kernels and the index maps: ``no`` / ``eo``
    (L + 1,) the lines' first node and element; held ends ``he_*`` (line, end, node,
    drive, body); ``end_point`` (L, 2) the free point at each line end (-1: held)."""

    lines: tuple[DiscreteLine, ...]
    S: tuple
    no: np.ndarray
    eo: np.ndarray
    end_point: np.ndarray
    he_line: np.ndarray
    he_end: np.ndarray
    he_node: np.ndarray
    he_drive: np.ndarray
    he_body: np.ndarray
    frac: np.ndarray
    n_points: int

    @property
    def n_nodes(self) -> int:
        return int(self.no[-1])

    @property
    def n_elements(self) -> int:
        return int(self.eo[-1])

    @property
    def lmin(self) -> float:
        return float(min(ln.rest_length.min() for ln in self.lines))


def pack(
    lines: list[DiscreteLine],
    end_point: np.ndarray,
    end_drive: np.ndarray,
    points: FreePoints,
    drive_body: np.ndarray,
) -> PackedSystem:
    """Pack ``lines`` (their ends held, or on the free point ``end_point[l, end]``
    >= 0; a held end driven by ``end_drive[l, end]``, the drive on body
    ``drive_body[drive]`` or -1)."""
    L = len(lines)
    nn = np.array([ln.n_nodes for ln in lines])
    no = np.concatenate(([0], np.cumsum(nn))).astype(np.int64)
    eo = np.concatenate(([0], np.cumsum(nn - 1))).astype(np.int64)
    o2 = np.concatenate(([0], np.cumsum(np.maximum(nn - 2, 0)))).astype(np.int64)
    ko = np.concatenate(([0], np.cumsum([ln.law_knots.shape[0] for ln in lines]))).astype(np.int64)
    cat = np.concatenate
    end_point = np.asarray(end_point, dtype=np.int64).reshape(L, 2)
    held = cat([ln.held for ln in lines]).astype(np.bool_)
    junction = np.zeros(no[-1], dtype=np.bool_)
    for l in range(L):  # noqa: E741
        for end in range(2):
            node = no[l] if end == 0 else no[l + 1] - 1
            if end_point[l, end] >= 0:
                held[node] = False
                junction[node] = True
            else:
                held[node] = True
    n_p = int(np.asarray(points.mass).size)
    p_nodes: list[list[int]] = [[] for _ in range(n_p)]
    for l in range(L):  # noqa: E741
        for end in range(2):
            p = int(end_point[l, end])
            if p >= 0:
                p_nodes[p].append(int(no[l] if end == 0 else no[l + 1] - 1))
    if any(not nodes for nodes in p_nodes):
        raise ValueError("every free point must be on a line")
    p_off = np.concatenate(([0], np.cumsum([len(n) for n in p_nodes]))).astype(np.int64)
    # a point's contact damper is the one node's it is (2 zeta sqrt(k m), the point's
    # mass in m): its end nodes' dampers scaled to share it as their springs do
    c_sb = cat([ln.seabed_damping for ln in lines])
    k_sb = cat([ln.seabed_stiffness for ln in lines])
    inertia = cat([ln.mass + ln.added_mass_normal + ln.body_added_mass for ln in lines])
    for p, nodes in enumerate(p_nodes):
        k, m = k_sb[nodes], inertia[nodes]
        if k.sum() > 0.0 and m.min() > 0.0:  # (a massless line's damper stays 0)
            c_sb[nodes] *= np.sqrt(k * (m.sum() + points.mass[p]) / (k.sum() * m))
    first = lines[0]
    S = (
        no,
        eo,
        o2,
        ko,
        cat([ln.rest_length for ln in lines]),
        cat([ln.axial_stiffness for ln in lines]),
        cat([ln.internal_damping for ln in lines]),
        cat([ln.force for ln in lines]),
        cat([ln.drag_normal for ln in lines]),
        cat([ln.drag_tangential for ln in lines]),
        cat([ln.added_mass_normal for ln in lines]),
        cat([ln.added_mass_tangential for ln in lines]),
        cat([ln.mass for ln in lines]),
        first.current_z,
        first.current_velocity,
        np.array([ln.has_drag for ln in lines], dtype=np.bool_),
        cat([ln.bending for ln in lines]),
        np.array([ln.clamp_direction for ln in lines], dtype=float).reshape(L, 2, 3),
        cat([ln.transverse_damping for ln in lines]),
        cat([ln.body_added_mass for ln in lines]),
        cat([ln.body_drag for ln in lines]),
        held,
        np.asarray(first.seabed_normal, dtype=float),
        np.array([ln.seabed_offset for ln in lines], dtype=float),
        k_sb,
        c_sb,
        np.array([ln.friction for ln in lines], dtype=float).reshape(L, 2),
        cat([ln.law_code for ln in lines]).astype(np.int64),
        cat([ln.law_params for ln in lines]).reshape(-1, 5),
        cat([ln.law_knots for ln in lines]).reshape(-1, 3),
        cat([ln.law_start for ln in lines]).astype(np.int64),
        cat([ln.law_count for ln in lines]).astype(np.int64),
        cat([ln.broken for ln in lines]).astype(np.bool_),
        np.array([ln.has_bending for ln in lines], dtype=np.bool_),
        end_point,
        np.asarray(points.mass, dtype=float).reshape(n_p),
        np.asarray(points.force, dtype=float).reshape(n_p, 3),
        np.asarray(points.drag, dtype=float).reshape(n_p),
        np.array([i for nodes in p_nodes for i in nodes], dtype=np.int64),
        p_off,
        junction,
    )
    he = [
        (l, end)
        for l in range(L)  # noqa: E741
        for end in range(2)
        if end_point[l, end] < 0
    ]
    end_drive = np.asarray(end_drive, dtype=np.int64).reshape(L, 2)
    drive_body = np.asarray(drive_body, dtype=np.int64)
    return PackedSystem(
        lines=tuple(lines),
        S=S,
        no=no,
        eo=eo,
        end_point=end_point,
        he_line=np.array([l for l, _ in he], dtype=np.int64),
        he_end=np.array([e for _, e in he], dtype=np.int64),
        he_node=np.array([no[l] if e == 0 else no[l + 1] - 1 for l, e in he], dtype=np.int64),
        he_drive=np.array([end_drive[l, e] for l, e in he], dtype=np.int64),
        he_body=np.array([drive_body[end_drive[l, e]] for l, e in he], dtype=np.int64),
        frac=cat([ln.s / ln.s[-1] for ln in lines]),
        n_points=n_p,
    )


def work_arrays(packed: PackedSystem, x: np.ndarray, v: np.ndarray) -> tuple:
    """The kernels' work tuple ``W`` for the packed system (state arrays ``x``, ``v``
    the Newton iterates are read from for the points' drag)."""
    N = packed.n_nodes
    E = packed.n_elements
    Q = int(packed.S[2][-1])
    nmax = int(np.max(np.diff(packed.no)))
    P = packed.n_points
    return (
        np.zeros((N, 3)),
        np.zeros((N, 3, 3)),
        np.zeros((E, 3, 3)),
        np.zeros((Q, 3, 3)),
        np.zeros((N, 3, 3)),
        np.zeros((E, 3, 3)),
        np.zeros((N, 3, 3)),
        np.zeros(E),
        np.zeros(E),
        np.zeros(E, dtype=np.bool_),
        np.zeros(N),
        np.zeros((N, 3)),
        np.zeros((N, 3), dtype=np.int64),
        np.zeros((N, 2)),
        np.zeros((N, 3, 3)),
        np.zeros((E, 3, 3)),
        np.zeros((Q, 3, 3)),
        np.zeros((3 * nmax, 17)),
        np.zeros((2, 3, N, 3)),
        np.zeros((3 * P, 3 * P)),
        np.zeros(3 * P),
        np.zeros(nmax, dtype=np.bool_),
        v,
        x,
        np.zeros((E, 3)),
        np.zeros(E),
        np.zeros((2, 2, 3, 3)),
        np.zeros(3),
    )
