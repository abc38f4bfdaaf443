"""What the compiled system path (:mod:`.system_fast`) packs of a system alone: each
line's pieces as the batch kernels lay them, the arrays they fill and each line's
starting-tension inputs but the chord, built once per system (a sweep's chunk and a
case's extreme poses pack the same system again). Pure: arrays in, arrays out."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .seabed import Plane, seabed_of
from .semi_analytic import make_layout
from .system_model import MooringSystem


def line_pieces(line) -> tuple[np.ndarray, ...]:  # noqa: ANN001
    """ell, EA, weight, point, bounds as the batch kernels build them for ``line``."""
    if line.length.size == 1 and line.attachment_s.size == 0:
        L = float(line.length[0])
        return (
            np.array([L]),
            np.array([float(line.axial_stiffness[0])]),
            np.array([float(line.weight[0])]),
            np.zeros((2, 3)),
            np.array([0.0, L]),
        )
    lay = make_layout(line)
    return lay.ell, lay.EA, lay.weight, lay.point, lay.bounds


@dataclass(frozen=True)
class Layout:
    """What :func:`pack` takes from a system alone (its lines' pieces as laid from A,
    the arrays they fill, each line's starting-tension inputs but the chord), built
    once per system."""

    P: np.ndarray
    poff: np.ndarray
    ell: np.ndarray  # (Ptot,)
    EA: np.ndarray
    w: np.ndarray
    bounds: np.ndarray  # (Ptot + M,)
    point: np.ndarray  # (Ptot + M, 3)
    clear: np.ndarray  # (M,)
    L: np.ndarray  # (M,)
    a: np.ndarray
    b: np.ndarray
    guess: np.ndarray  # (M, 11): _guess's inputs per line, the chord (0:3) left 0
    plane: Plane | None


_LAYOUTS: dict[int, tuple[MooringSystem, Layout]] = {}


def system_layout(system: MooringSystem) -> Layout:
    hit = _LAYOUTS.get(id(system))
    if hit is not None and hit[0] is system:
        return hit[1]
    plane = seabed_of(system.lines[0].problem.medium)
    # per line model (lines alike share one: a spread's legs, a spar's bridles): its
    # pieces, whether its loads all point down, and its starting-tension inputs but the
    # chord (the same operations on one row as pack's for a case: the same numbers)
    kinds: dict[int, tuple] = {}
    rows = []
    for ln in system.lines:
        got = kinds.get(id(ln.problem.line))
        if got is None:
            e_, ea_, w_, pt_, bd_ = pieces = line_pieces(ln.problem.line)
            down = bool(np.all(w_ >= 0.0))
            if plane is not None:
                down = down and bool(np.all(pt_ @ plane.normal <= 0.0))
            g = np.zeros((1, 11))
            g[:, 3] = bd_[-1]
            g[:, 4:7] = pt_[None].sum(axis=1)
            g[:, 6] -= np.sum(w_[None] * e_[None], axis=1)
            g[:, 7] = g[:, 3] / np.sum(e_[None] / ea_[None], axis=1)
            g[:, 8:] = pt_[0]
            got = kinds[id(ln.problem.line)] = (pieces, down, g[0])
        rows.append(got)
    fwd = [r[0] for r in rows]
    P = np.array([len(f[0]) for f in fwd])
    cat = np.concatenate
    lay = Layout(
        P=P, poff=np.concatenate(([0], np.cumsum(P))).astype(np.int64),
        ell=cat([f[0] for f in fwd]), EA=cat([f[1] for f in fwd]), w=cat([f[2] for f in fwd]),
        bounds=cat([f[4] for f in fwd]), point=cat([f[3] for f in fwd]),
        clear=np.array([r[1] for r in rows]), L=np.array([float(f[4][-1]) for f in fwd]),
        a=np.array([ln.a for ln in system.lines], dtype=np.int64),
        b=np.array([ln.b for ln in system.lines], dtype=np.int64),
        guess=np.array([r[2] for r in rows]), plane=plane,
    )  # fmt: skip
    if len(_LAYOUTS) > 16:
        _LAYOUTS.clear()
    _LAYOUTS[id(system)] = (system, lay)
    return lay
