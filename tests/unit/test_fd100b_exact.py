"""The shortcuts of issue 24's speed work give what they replace, bit for bit: the
largest modulus found with ``abs`` taken only near the running maximum
(:func:`cablestudy.dynamics.system_fd_kernel._larger`), and a chunk's output stacked
when every record has it whole (:func:`cablestudy.analyses.grid_chunk.records_chunk`)
against the values placed one record at a time."""

from __future__ import annotations

import numpy as np

from cablestudy.analyses.grid_chunk import records_chunk
from cablestudy.analyses.variables import OUTPUTS, CaseRecord
from cablestudy.dynamics.system_fd_kernel import _larger


def test_largest_modulus_is_that_of_every_abs() -> None:
    """Moduli that tie to the last bits (the same number turned by a few ulps, a few
    ulps larger or smaller), tiny, huge and zero ones: the maximum of ``abs`` over all of
    them, equal to the bit (no tolerance: the shortcut must not change a case's
    convergence test or residual)."""
    rng = np.random.default_rng(24)
    for trial in range(200):
        n = int(rng.integers(1, 60))
        z = (rng.standard_normal(n) + 1j * rng.standard_normal(n)) * 10.0 ** rng.integers(-8, 8)
        if trial % 3 == 0:  # near ties: one modulus, the angle turned
            r = abs(z[0]) * (1.0 + rng.integers(-3, 4, n) * np.finfo(float).eps)
            z = r * np.exp(1j * rng.uniform(0.0, 2.0 * np.pi, n))
        if trial % 7 == 0:
            z[rng.integers(0, n)] = 0.0
        top = top2 = 0.0
        for v in z:
            top, top2 = _larger(top, top2, complex(v))
        assert top == max(0.0, *(abs(complex(v)) for v in z)), trial


def _placed(records: list[CaseRecord], name: str) -> np.ndarray:
    """The output ``name`` of ``records`` placed record by record (the general path)."""
    spec = OUTPUTS[name]
    shape = np.shape(records[0].data[name])
    arr = np.full((len(records), *shape), np.nan, dtype=spec.dtype)
    for i, r in enumerate(records):
        arr[(i, *(slice(0, k) for k in np.shape(r.data[name])))] = r.data[name]
    return arr


def test_stacked_outputs_equal_placed_ones() -> None:
    """Records that all hold an output whole, of one dtype or of mixed dtypes (an int
    and a float value cast to the output's float): the chunk's array is the one placed
    record by record, dtype and bits."""
    rng = np.random.default_rng(7)
    name = "tension"  # float, on s; kept for a case of status 0
    dims = OUTPUTS[name].dims
    shape = tuple(3 for _ in dims)
    for mixed in (False, True):
        records = []
        for i in range(5):
            value = rng.standard_normal(shape)
            if mixed and i % 2:
                value = np.asarray(rng.integers(-5, 5, shape), dtype=np.int64)
            records.append(CaseRecord(f"h{i}", (i,), 0, "", 0.0, {name: value}))
        got = records_chunk(records).data[name]
        want = _placed(records, name)
        assert got.dtype == want.dtype
        assert got.tobytes() == want.tobytes()
