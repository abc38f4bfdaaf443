"""Where one line sits in the packed arrays of :func:`.assembly.assemble_lines` and
:func:`.assembly.contact_states_lines`, chosen when numba compiles them: with the
offsets given (a system: lines packed one after another) they are read from them; with
``None`` (a single line) they are the constant 0, so that the compiled one-line kernel
indexes every array by a plain count, as a kernel written for one line would (offsets
read from memory cost the single-line time step several per cent: every index must
then be checked for negative wrap-around, and the per-line values were read per node).
"""

from __future__ import annotations

from numba.core import types
from numba.extending import overload


def line_count(no):  # noqa: ANN001, ANN201
    """Lines in the packed arrays (1 without offsets)."""
    return 1 if no is None else no.shape[0] - 1


def line_part(no, eo, o2, ko, l, n_nodes, n_o2, has_drag, clamp, offset, friction):  # noqa: ANN001, ANN201, E741
    """Line ``l``: its first node and node count, first element, two-off blocks
    ``q0:q1``, first law knot; its drag flag, end directions (2, 3), seabed plane offset
    [m] and friction coefficients along and across. Without offsets (``no`` None) the
    one line of ``n_nodes`` nodes and ``n_o2`` two-off blocks, its values as given."""
    if no is None:
        return 0, n_nodes, 0, 0, n_o2, 0, has_drag, clamp, offset, friction[0], friction[1]
    n0 = no[l]
    return (
        n0, no[l + 1] - n0, eo[l], o2[l], o2[l + 1], ko[l], has_drag[l], clamp[l], offset[l],
        friction[l, 0], friction[l, 1],
    )  # fmt: skip


def node_range(no, l, n_nodes, offset):  # noqa: ANN001, ANN201, E741
    """Line ``l``'s nodes ``i0:i1`` and seabed plane offset [m] (without offsets: all
    ``n_nodes``, ``offset`` as given)."""
    if no is None:
        return 0, n_nodes, offset
    return no[l], no[l + 1], offset[l]


# the compiled versions: one implementation per kind of ``no``, picked at typing time


@overload(line_count, inline="always")
def _line_count(no):  # noqa: ANN001, ANN202
    if isinstance(no, types.NoneType):
        return lambda no: 1
    return lambda no: no.shape[0] - 1


@overload(line_part, inline="always")
def _line_part(no, eo, o2, ko, l, n_nodes, n_o2, has_drag, clamp, offset, friction):  # noqa: ANN001, ANN202, E741
    if isinstance(no, types.NoneType):

        def one(no, eo, o2, ko, l, n_nodes, n_o2, has_drag, clamp, offset, friction):  # noqa: ANN001, ANN202, E741
            return 0, n_nodes, 0, 0, n_o2, 0, has_drag, clamp, offset, friction[0], friction[1]

        return one

    def packed(no, eo, o2, ko, l, n_nodes, n_o2, has_drag, clamp, offset, friction):  # noqa: ANN001, ANN202, E741
        n0 = no[l]
        return (
            n0, no[l + 1] - n0, eo[l], o2[l], o2[l + 1], ko[l], has_drag[l], clamp[l],
            offset[l], friction[l, 0], friction[l, 1],
        )  # fmt: skip

    return packed


@overload(node_range, inline="always")
def _node_range(no, l, n_nodes, offset):  # noqa: ANN001, ANN202, E741
    if isinstance(no, types.NoneType):
        return lambda no, l, n_nodes, offset: (0, n_nodes, offset)  # noqa: E741
    return lambda no, l, n_nodes, offset: (no[l], no[l + 1], offset[l])  # noqa: E741
