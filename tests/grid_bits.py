"""The array grid against the case-by-case path: two datasets of the same study equal bit
for bit (every variable's dims and bytes, every attribute but the run's history and wall
times), as issue 20 asks of a grid and its chunks of one."""

from __future__ import annotations

import numpy as np
import xarray as xr


def same_bits(fast: xr.Dataset, slow: xr.Dataset) -> None:
    """Assert ``fast`` (the arrays) and ``slow`` (case by case) hold the same bits."""
    assert set(fast.variables) == set(slow.variables)
    for name in slow.variables:
        if name == "wall_time":
            continue
        a, b = fast[name], slow[name]
        assert a.dims == b.dims, name
        if a.dtype.kind == "f":
            assert a.values.tobytes() == b.values.tobytes(), name
        else:
            assert np.array_equal(a.values, b.values), name
    skip = {"history"}
    assert {k: v for k, v in fast.attrs.items() if k not in skip} == {
        k: v for k, v in slow.attrs.items() if k not in skip
    }
