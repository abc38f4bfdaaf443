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


def _one_count(no):  # noqa: ANN001, ANN202
    return 1


def _packed_count(no):  # noqa: ANN001, ANN202
    return no.shape[0] - 1


def _one_part(no, eo, o2, ko, l, n_nodes, n_o2, has_drag, clamp, offset, friction):  # noqa: ANN001, ANN202, E741
    return 0, n_nodes, 0, 0, n_o2, 0, has_drag, clamp, offset, friction[0], friction[1]


def _packed_part(no, eo, o2, ko, l, n_nodes, n_o2, has_drag, clamp, offset, friction):  # noqa: ANN001, ANN202, E741
    n0 = no[l]
    return (
        n0, no[l + 1] - n0, eo[l], o2[l], o2[l + 1], ko[l], has_drag[l], clamp[l], offset[l],
        friction[l, 0], friction[l, 1],
    )  # fmt: skip


def _one_range(no, l, n_nodes, offset):  # noqa: ANN001, ANN202, E741
    return 0, n_nodes, offset


def _packed_range(no, l, n_nodes, offset):  # noqa: ANN001, ANN202, E741
    return no[l], no[l + 1], offset[l]


def line_count(no):  # noqa: ANN001, ANN201
    """Lines in the packed arrays (1 without offsets)."""
    return (_one_count if no is None else _packed_count)(no)


def line_part(no, eo, o2, ko, l, n_nodes, n_o2, has_drag, clamp, offset, friction):  # noqa: ANN001, ANN201, E741
    """Line ``l``: its first node and node count, first element, two-off blocks
    ``q0:q1``, first law knot; its drag flag, end directions (2, 3), seabed plane offset
    [m] and friction coefficients along and across. Without offsets (``no`` None) the
    one line of ``n_nodes`` nodes and ``n_o2`` two-off blocks, its values as given."""
    part = _one_part if no is None else _packed_part
    return part(no, eo, o2, ko, l, n_nodes, n_o2, has_drag, clamp, offset, friction)


def node_range(no, l, n_nodes, offset):  # noqa: ANN001, ANN201, E741
    """Line ``l``'s nodes ``i0:i1`` and seabed plane offset [m] (without offsets: all
    ``n_nodes``, ``offset`` as given)."""
    return (_one_range if no is None else _packed_range)(no, l, n_nodes, offset)


# the compiled versions: one of the implementations above per kind of ``no``, picked at
# typing time


@overload(line_count, inline="always")
def _line_count(no):  # noqa: ANN001, ANN202
    return _one_count if isinstance(no, types.NoneType) else _packed_count


@overload(line_part, inline="always")
def _line_part(no, eo, o2, ko, l, n_nodes, n_o2, has_drag, clamp, offset, friction):  # noqa: ANN001, ANN202, E741
    return _one_part if isinstance(no, types.NoneType) else _packed_part


@overload(node_range, inline="always")
def _node_range(no, l, n_nodes, offset):  # noqa: ANN001, ANN202, E741
    return _one_range if isinstance(no, types.NoneType) else _packed_range
