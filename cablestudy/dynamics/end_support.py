"""The force of a line on the attachment holding its end node, where that node rests on
the seabed: one law for the single line (:mod:`.integrator`, :mod:`.time_problem`) and
the system (:mod:`.system_march`).

A held end node lumps half its element: its mass, weight and drag are the line's, so
the force of the line on the attachment is minus the support reaction ``F + M a`` of
the node (at a hanging end this is the static end tension to second order in the
element length: the element's pull plus the half element's weight). The seabed's
forces on the node (the penalty contact, the friction) are not the line's: the seabed,
not the attachment, pushes the node up and holds it back. And where the node rests on
the seabed (at or below it, within ``tolerance``), the seabed carries what presses the
node into it (the half element's weight), as it carries the laid line's in the
statics: only a normal force lifting the node off the seabed reaches the attachment.
So an anchor on the seabed feels the pull of its element (at rest the static end
tension, to the element's first order as the element tension is its midpoint's), not
its half element's weight, nor the penalty seabed it is pressed into when moved down.

Pure: arrays in, arrays out (SI units).
"""

from __future__ import annotations

from numba import njit


@njit(cache=True, nogil=True)
def seabed_support(f, x, contact, friction, stiffness, normal, offset, tolerance):  # noqa: ANN001, ANN201, PLR0913
    """Correct ``f`` (3,), minus the support reaction of a held end node at ``x`` (3,)
    (the force of the line on the attachment with the node's seabed forces in), in
    place: with no seabed (``stiffness`` 0) or the node above it by more than
    ``tolerance`` [m], unchanged; else without the node's seabed forces (``contact``
    [N] the normal force, ``friction`` (3,) the friction force on it) and with only the
    part of the normal component that lifts the node off the seabed (unit upward
    ``normal``, the plane ``normal . x = offset``)."""
    if stiffness <= 0.0:
        return
    gap = normal[0] * x[0] + normal[1] * x[1] + normal[2] * x[2] - offset
    if gap > tolerance:
        return
    fn = f[0] * normal[0] + f[1] * normal[1] + f[2] * normal[2]
    lift = max(fn - contact, 0.0)
    for c in range(3):
        f[c] += (lift - fn) * normal[c] - friction[c]
