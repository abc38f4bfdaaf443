"""``method: auto`` for a system: the time domain chosen before the frequency domain is
built where the quasi-static shape change of a line over the motion's amplitude already
exceeds the geometric limit by :data:`~cablestudy.dynamics.system_prejudge.MARGIN`
(the physics and the margin: :mod:`cablestudy.dynamics.system_prejudge`).

The quasi-static states are the system's statics solved again by the compiled system
Newton (:mod:`cablestudy.statics.system_fast`, both extremes in one call, each verified
as a static case is) with the body moved by plus and minus the amplitude, the free
points starting from the static state. Decided only for one harmonic motion of a
degree of freedom of a prescribed body, a system the compiled path solved statically
(method catenary, no fallback), and on the lines hanging free of the seabed in all
three states; anything else (or a quasi-static state the compiled path does not
settle and verify) leaves the decision to the frequency domain's own checks."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..study.system_dynamics import BODY_DOFS, BodyHarmonic


def quasi_static_reason(case: Any, system: Any, static: Any, limit: float) -> str:
    """Why the time domain runs, decided before the frequency domain ('' when this check
    does not decide: the frequency domain and its checks then run)."""
    from ..dynamics.system_prejudge import MARGIN

    got = quasi_static_ratios(case, system, static) if limit > 0.0 else None
    if got is None:
        return ""
    ratio, judged = got
    over = np.flatnonzero(judged & (ratio > MARGIN * limit))
    if not over.size:
        return ""
    m = int(over[0])
    e = case.study.analysis.dynamic.excitations[0]
    return (
        f"line {list(case.study.lines)[m]!r}: large motion: amplitude/sag {ratio[m]:.3g} > "
        f"{limit:g} quasi-static (its shape with the body at -+ {e.amplitude:g} in {e.dof} "
        f"against its static shape, over its sag: above {MARGIN:g} x the limit, decided "
        "before the frequency domain)"
    )


def extreme_poses(case: Any, body_position: np.ndarray) -> np.ndarray | None:
    """The bodies' poses (2, m, 6) at the motion's extremes (``body_position`` plus and
    minus the amplitude in the moved degree of freedom) where this check applies to the
    case's motion and static method (module docstring), else None."""
    study = case.study
    dyn = study.analysis.dynamic
    if dyn is None or dyn.method != "auto" or study.analysis.static.method != "catenary":
        return None
    if len(dyn.excitations) != 1 or not isinstance(dyn.excitations[0], BodyHarmonic):
        return None
    e = dyn.excitations[0]
    poses = np.repeat(np.asarray(body_position, dtype=float)[None], 2, axis=0)
    b, k = list(study.bodies).index(e.body), BODY_DOFS.index(e.dof)
    poses[0, b, k] += e.amplitude
    poses[1, b, k] -= e.amplitude
    return poses


def quasi_static_ratios(
    case: Any, system: Any, static: Any
) -> tuple[np.ndarray, np.ndarray] | None:
    """Per line the quasi-static shape change over its sag
    (:func:`~cablestudy.dynamics.system_prejudge.shape_change_ratios`) and whether the
    line is judged by it (hanging free of the seabed in the three states), or None
    where this check does not apply (module docstring). The extreme states are those
    the static solve found with the system's (``static.extra``, asked by
    :func:`cablestudy.analyses.system._statics`) when they are of these poses, else
    solved here."""
    from ..dynamics.system_prejudge import shape_change_ratios
    from ..statics.system_fast import hanging_shapes, ineligible, pack, point_positions_many

    if getattr(static, "fallback", "") or static.body_position is None:
        return None
    poses = extreme_poses(case, static.body_position)
    if poses is None or ineligible(system):
        return None
    s = np.array([r.s for r in static.lines])
    shape = np.array([r.position for r in static.lines])
    static_laid = np.array([r.laid_length for r in static.lines]) > 0.0
    extra = getattr(static, "extra", None)
    if extra is not None and np.array_equal(extra["poses"], poses):
        if shape.shape != extra["position"].shape[1:]:
            return None
        judged = ~static_laid & ~np.any(extra["anchored"], axis=0)
        judged &= ~np.any(extra["laid_length"] > 0.0, axis=0)
        return shape_change_ratios(s, shape, extra["position"]), judged
    base = np.repeat(np.asarray(static.point_position, dtype=float)[None], 2, axis=0)
    pos = point_positions_many(system, poses, None, base)
    pk, why = pack(system, pos)
    if pk is None or any(why):
        return None
    if shape.shape[1] != pk.n_nodes:
        return None
    # the lines hanging free of the seabed (no laid length, not anchored on it)
    lines = np.flatnonzero(~static_laid & ~np.any(pk.anchored, axis=0))
    if not lines.size:
        return None
    try:
        got = hanging_shapes(pk, lines)
    except np.linalg.LinAlgError:
        return None
    if got is None:
        return None
    moved, good = got
    judged = np.zeros(len(static.lines), dtype=bool)
    judged[lines] = np.all(good, axis=0)
    ratio = np.full(len(static.lines), np.nan)
    ratio[lines] = shape_change_ratios(s[lines], shape[lines], moved)
    return ratio, judged
