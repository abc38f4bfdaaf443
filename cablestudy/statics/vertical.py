"""A line between two fixed ends on one vertical: the catenary's degenerate case.

Pure: arrays in, arrays out (SI units, no I/O).

With both ends on one vertical (no horizontal offset) and still water, the horizontal
tension is zero and the elastic catenary's parametrisation (the slope V / H) breaks
down: the end-force Newton has no direction to go. The shape is then one of two,
both in closed form for a line of linear segments (EA constant per segment) with
positive weight in the fluid:

* **taut**: the line hanging from the upper end does not reach the lower one; it is a
  vertical bar pulled down at the lower end with T_low >= 0, the tension growing by the
  weight above: T(s) = T_low + W(s) (W the weight between s and the lower end) and the
  ends' distance D = sum over segments of l (1 + T_mid / EA) (T linear in s within a
  segment, so the midpoint tension gives the exact stretch); linear in T_low;
* **folded**: the line is longer than that; it hangs down from both ends to a fold
  where its tension is zero (a catenary of zero width), both legs vertical. With s* the
  fold's arc length from A, each leg's tension is the weight below it on that leg, and
  s* solves z_A - z_B = l_A(s*) - l_B(s*), l the legs' stretched lengths (increasing in
  s*: bisection to round-off).

Not covered here (left to the general solver): a current, attachments, a nonlinear
axial law, a segment of zero or negative weight, a fold below the seabed, ends not on
one vertical.
"""

from __future__ import annotations

import numpy as np

from .base import StaticProblem, StaticResult

_Z = np.array([0.0, 0.0, 1.0])


def _stretched(
    bounds: np.ndarray,
    w: np.ndarray,
    ea: np.ndarray,
    s0: float,
    s1: float,
    t0: float = 0.0,
    *,
    up: bool = False,
) -> float:
    """Stretched length of [s0, s1] hanging with tension t0 at its lower end, growing by
    the weight towards its upper end: s0 (``up`` False) or s1 (``up`` True: t0 at s0);
    sum l (1 + T_mid / EA) over the pieces, marched from the lower end."""
    total, t = 0.0, t0
    for k in range(len(w)) if up else range(len(w) - 1, -1, -1):
        a, b = max(bounds[k], s0), min(bounds[k + 1], s1)
        if b <= a:
            continue
        ell = b - a
        total += ell * (1.0 + (t + 0.5 * w[k] * ell) / ea[k])
        t += w[k] * ell
    return total


def solve_vertical(problem: StaticProblem, s: np.ndarray) -> StaticResult | None:
    """The closed-form shape of a line whose fixed ends are on one vertical (module
    doc), sampled at ``s`` [m]; None where it does not apply."""
    a, b, line, med = problem.end_a, problem.end_b, problem.line, problem.medium
    if a.kind != "fixed" or b.kind != "fixed" or a.position is None or b.position is None:
        return None
    ra, rb = np.asarray(a.position, dtype=float), np.asarray(b.position, dtype=float)
    L = line.total_length
    if float(np.hypot(*(ra[:2] - rb[:2]))) > 1e-12 * max(L, 1.0) or ra[2] == rb[2]:
        return None
    if med.has_current or line.attachment_s.size or line.is_nonlinear:
        return None
    w = np.asarray(line.weight, dtype=float)
    ea = np.asarray(line.axial_stiffness, dtype=float)
    if np.any(w <= 0.0) or np.any(~np.isfinite(ea)) or np.any(ea <= 0.0):
        return None
    bounds = line.segment_ends
    dz = float(ra[2] - rb[2])  # A above B when positive

    def g(fold: float) -> float:  # z_A - z_B with the fold at s = fold
        return _stretched(bounds, w, ea, 0.0, fold) - _stretched(bounds, w, ea, fold, L, up=True)

    weight = np.concatenate(([0.0], np.cumsum(w * np.diff(bounds))))  # W(0, s) at bounds

    def W(s_: np.ndarray) -> np.ndarray:
        return np.interp(s_, bounds, weight)

    total = float(weight[-1])
    if g(0.0) < dz < g(L):  # folded: bisection on the fold's arc length
        lo, hi = 0.0, L
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if g(mid) < dz:
                lo = mid
            else:
                hi = mid
            if hi - lo <= 4.0 * np.finfo(float).eps * L:
                break
        fold = 0.5 * (lo + hi)
        t_a, t_b = float(W(np.array(fold))), total - float(W(np.array(fold)))
        z_fold = ra[2] - _stretched(bounds, w, ea, 0.0, fold, 0.0)
        force_a, force_b = -t_a * _Z, -t_b * _Z
        tension = np.abs(t_a - W(s))
        z = np.array(
            [
                ra[2] - _stretched(bounds, w, ea, 0.0, si, t_a - float(W(np.array(si))))
                if si <= fold
                else z_fold + _stretched(bounds, w, ea, fold, si, up=True)
                for si in s
            ]
        )
    else:  # taut: pulled down at the lower end with T_low >= 0
        upper_is_a = dz > 0.0
        d = abs(dz)
        # D = sum l (1 + (T_low + W_below_mid) / EA): linear in T_low
        base = (
            _stretched(bounds, w, ea, 0.0, L, 0.0)
            if upper_is_a
            else _stretched(bounds, w, ea, 0.0, L, up=True)
        )
        compliance = float(np.sum(np.diff(bounds) / ea))
        t_low = (d - base) / compliance
        if t_low < 0.0:
            return None  # round-off at the boundary of the two shapes: leave it
        if upper_is_a:
            t_of_s = t_low + (total - W(s))
            force_a, force_b = -(t_low + total) * _Z, t_low * _Z
            z = np.array(
                [
                    ra[2]
                    - _stretched(bounds, w, ea, 0.0, si, float(t_low + total - W(np.array(si))))
                    for si in s
                ]
            )
        else:
            t_of_s = t_low + W(s)
            force_a, force_b = t_low * _Z, -(t_low + total) * _Z
            z = np.array(
                [
                    ra[2]
                    + (
                        _stretched(bounds, w, ea, 0.0, si, up=True)
                        + t_low * float(np.sum(np.diff(np.clip(bounds, 0.0, si)) / ea))
                    )
                    for si in s
                ]
            )
        tension = np.asarray(t_of_s, dtype=float)
    if med.depth is not None:
        ground = float(med.seabed_z(np.array(ra[0]), np.array(ra[1])))
        if float(np.min(z)) < ground:
            return None  # the fold reaches the seabed: not this shape
    position = np.column_stack((np.full(s.size, ra[0]), np.full(s.size, ra[1]), z))
    position[0], position[-1] = ra, rb
    return StaticResult(
        s=s,
        position=position,
        tension=tension,
        force_a=force_a,
        force_b=force_b,
        laid_length=0.0,
    )
