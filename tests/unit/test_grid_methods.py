"""Static sweeps with another method (``analytic``, ``shooting``, ``discrete``) run as
arrays: the grid's chunk builds each case's static problem from arrays (no per-case
study) and the method's solver takes each, as a case alone
(cablestudy.analyses.static_grid._solve_each). The dataset must be the case-by-case one
bit for bit; the methods agree with each other on the same cases to their accuracy."""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.analyses import static as static_analysis
from cablestudy.run.runner import run_study
from cablestudy.study import parse_study_text
from cablestudy.study.grid import expand_grid
from cablestudy.study.loader import StudyError
from tests.grid_bits import same_bits

#: a uniform wire hanging in water between fixed ends: end B's offset, the stiffness
#: and the node count swept (every method models it)
WIRE = """\
name: gm
environment: {fluid: water}
line:
  segments:
    - {length: 60.0, diameter: 0.02, weight_in_fluid: 20.0, axial_stiffness: 2.0e7}
    - {length: 40.0, diameter: 0.02, weight_in_fluid: 20.0, axial_stiffness: 2.0e7}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -10.0]}
  b: {kind: fixed, position: [90.0, 0.0, -25.0]}
analysis:
  static: {method: METHOD, nodes: 21}
sweep:
  ends.b.position.0: [80.0, 90.0, 95.0]
  analysis.static.nodes: [11, 21]
  line.segments.0.axial_stiffness: {values: [2.0e7, 5.0e6], name: ea0}
  line.segments.1.axial_stiffness: {values: [2.0e7, 5.0e6], name: ea1}
"""


@pytest.fixture(autouse=True)
def _fresh_static_cache(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(static_analysis, "_STATIC_CACHE", OrderedDict())


def _run(text: str, tmp_path: Path, name: str, *, cases: bool = False) -> xr.Dataset:
    src = parse_study_text(text, "gm.yaml")
    grid = expand_grid(src)
    assert grid.chunked and grid.arrays
    if cases:
        grid = replace(grid, chunked=False)
    return xr.load_dataset(
        run_study(src, grid, tmp_path / name, scheduler="synchronous", use_cache=False).path
    )


@pytest.mark.parametrize("method", ["analytic", "shooting", "discrete"])
def test_another_methods_sweep_runs_as_arrays_with_the_case_datasets_bits(
    tmp_path: Path, method: str
) -> None:
    text = WIRE.replace("METHOD", method)
    fast = _run(text, tmp_path, "g")
    slow = _run(text, tmp_path, "c", cases=True)
    status = slow["status"].values
    uniform = slow["ea0"].values[:, None] == slow["ea1"].values[None, :]
    if method == "analytic":
        # the closed form needs a uniform line: the others fail with the method's reason
        ok = np.broadcast_to(uniform, status.shape[2:])
        assert np.all(status[..., ok] == 0) and np.all(status[..., ~ok] != 0)
        msg = str(slow["message"].values[..., ~ok].ravel()[0])
        assert "does not support segments of different weight or axial stiffness" in msg
    else:
        assert (status == 0).all()
    assert fast.attrs["cases_fallback"] == status.size  # no batch kernel: all counted
    same_bits(fast, slow)
    # against the catenary on the same cases (the method left out)
    ref = _run(WIRE.replace("method: METHOD, ", ""), tmp_path, "r")
    ok = status == 0
    tb, tr = fast["tension_b"].values[ok], ref["tension_b"].values[ok]
    # analytic and catenary: both exact to their tolerance 1e-9 -> 1e-8 relative
    # (measured 3e-15); shooting: its ODE integration's tolerance, 1e-6 (measured
    # 1.4e-12); discrete: straight elements between the output points (10 m and 5 m
    # here), an O(h^2) error in the sag and so the tension: measured 3.7e-3 at 10 m,
    # bounded at 1e-2
    bound = {"analytic": 1e-8, "shooting": 1e-6, "discrete": 1e-2}[method]
    assert np.max(np.abs(tb - tr) / tr) <= bound, np.max(np.abs(tb - tr) / tr)


def test_a_sweep_the_analytic_method_cannot_model_is_refused_before_any_work(
    tmp_path: Path,
) -> None:
    """The support check runs per swept value for another method (the template alone
    answers only for the catenary's arrays)."""
    from cablestudy import cli

    path = tmp_path / "gm.yaml"
    path.write_text(WIRE.replace("METHOD", "analytic"))
    with pytest.raises(StudyError, match="does not support segments of different weight"):
        cli._load(str(path))
