"""The single-line contact states (compiled apart, offsets 0: cablestudy.dynamics.
line_offsets) are those of the packed lines, state for state: the two compiled cases
of contact_states_lines must not drift apart (the assembly's two cases are compared in
test_system_assembly.py)."""

from __future__ import annotations

import numpy as np

from cablestudy.dynamics.assembly import contact_states, contact_states_lines


def test_one_line_contact_states_are_the_packed_lines_states() -> None:
    rng = np.random.default_rng(3)
    sizes = (6, 9, 4)
    no = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    n = int(no[-1])
    normal = np.array([0.0, 0.0, 1.0])
    offset = np.array([-30.0, -29.5, -31.0])
    # nodes a few cm either side of each line's plane, moving both ways: touching,
    # lifting and pulled-off nodes; one node without seabed, one held at state 3
    x = rng.standard_normal((n, 3))
    x[:, 2] = np.repeat(offset, sizes) + 0.05 * rng.standard_normal(n)
    v = 0.3 * rng.standard_normal((n, 3))
    stiffness = np.full(n, 2e5)
    stiffness[2] = 0.0
    damping = np.full(n, 5e3)
    for fix in (False, True):
        state = rng.integers(0, 3, size=(n, 3)).astype(np.int64)
        state[5, 2] = 3
        flips = rng.integers(0, 2, size=n).astype(np.int64)
        packed_state, packed_flips = state.copy(), flips.copy()
        changed = contact_states_lines(
            no, x, v, normal, offset, stiffness, damping, packed_state, fix, packed_flips
        )
        any_changed = False
        for k in range(len(sizes)):
            part = slice(no[k], no[k + 1])
            own_state, own_flips = state[part].copy(), flips[part].copy()
            any_changed |= contact_states(
                x[part], v[part], normal, offset[k], stiffness[part], damping[part],
                own_state, fix, own_flips,
            )  # fmt: skip
            assert np.array_equal(own_state, packed_state[part]), (fix, k)
            assert np.array_equal(own_flips, packed_flips[part]), (fix, k)
        assert changed == any_changed
        # the case exercises both states
        assert np.any(packed_state[:, 2] == 1) and np.any(packed_state[:, 2] == 2)
