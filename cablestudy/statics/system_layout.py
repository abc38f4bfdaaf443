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

    fwd: list
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
    M = len(system.lines)
    plane = seabed_of(system.lines[0].problem.medium)
    fwd = [line_pieces(ln.problem.line) for ln in system.lines]
    P = np.array([len(f[0]) for f in fwd])
    poff = np.concatenate(([0], np.cumsum(P))).astype(np.int64)
    Ptot = int(poff[-1])
    ell, EA, w = np.empty((1, Ptot)), np.empty((1, Ptot)), np.empty((1, Ptot))
    bounds, point = np.empty((1, Ptot + M)), np.empty((1, Ptot + M, 3))
    clear = np.zeros(M, dtype=bool)
    for m, (e_, ea_, w_, pt_, bd_) in enumerate(fwd):
        o, ob, p = poff[m], poff[m] + m, P[m]
        ell[:, o : o + p] = e_
        EA[:, o : o + p] = ea_
        w[:, o : o + p] = w_
        bounds[:, ob : ob + p + 1] = bd_
        point[:, ob : ob + p + 1] = pt_
        down = bool(np.all(w_ >= 0.0))
        if plane is not None:
            down = down and bool(np.all(pt_ @ plane.normal <= 0.0))
        clear[m] = down
    # each line's starting-tension inputs as pack computes them for a case (the same
    # operations on one row: the same numbers), the chord filled per case
    guess = np.zeros((1, M, 11))
    for m in range(M):
        o, ob, p = poff[m], poff[m] + m, P[m]
        guess[:, m, 3] = bounds[:, ob + p]
        guess[:, m, 4:7] = point[:, ob : ob + p + 1].sum(axis=1)
        guess[:, m, 6] -= np.sum(w[:, o : o + p] * ell[:, o : o + p], axis=1)
        guess[:, m, 7] = guess[:, m, 3] / np.sum(ell[:, o : o + p] / EA[:, o : o + p], axis=1)
        guess[:, m, 8:] = point[:, ob]
    lay = Layout(
        fwd=fwd, P=P, poff=poff, ell=ell[0], EA=EA[0], w=w[0], bounds=bounds[0],
        point=point[0], clear=clear, L=np.array([float(f[4][-1]) for f in fwd]),
        a=np.array([ln.a for ln in system.lines], dtype=np.int64),
        b=np.array([ln.b for ln in system.lines], dtype=np.int64),
        guess=guess[0], plane=plane,
    )  # fmt: skip
    if len(_LAYOUTS) > 16:
        _LAYOUTS.clear()
    _LAYOUTS[id(system)] = (system, lay)
    return lay
