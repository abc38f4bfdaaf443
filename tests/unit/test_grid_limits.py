"""Break conditions on static sweeps run as arrays (cablestudy.analyses.static_grid_limits):
a line with a ``failure`` condition, its limit swept with the fairlead's offset; and a
law's checked strain range (``max_strain`` on a linear law). The dataset must be the
case-by-case one bit for bit; a case is broken (status 10, results kept) exactly where
its tension passes its limit."""

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
from tests.grid_bits import same_bits

#: a chain-wire-chain mooring leg anchored on the seabed with a clump; the whole line's
#: break limit MBL / SF swept (MBL) with the fairlead's offset
BREAK = """\
name: gb
environment: {fluid: water, depth: 200.0, seabed: {friction: 0.5}}
line:
  segments:
    - {length: 450.0, diameter: 0.137, weight_in_fluid: 981.0, axial_stiffness: 4.9e8}
    - {length: 350.0, diameter: 0.076, weight_in_fluid: 240.0, axial_stiffness: 5.2e8}
    - {length: 100.0, diameter: 0.137, weight_in_fluid: 981.0, axial_stiffness: 4.9e8}
  attachments:
    - {s: 600.0, mass: 5000.0}
  failure: {minimum_breaking_load: 6.0e5, safety_factor: 1.5}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -200.0]}
  b: {kind: fixed, position: [820.0, 0.0, -20.0]}
analysis:
  static: {nodes: 31}
sweep:
  line.failure.minimum_breaking_load: [3.0e5, 6.0e5, 1.2e6]
  ends.b.position.0: {start: 800.0, stop: 860.0, num: 7, name: fairlead_x}
"""
#: the wire's linear law checked to a strain range it passes at the longest offsets
#: (a case past it fails, as a non-linear law's would)
LAW = (
    BREAK.replace(
        "axial_stiffness: 5.2e8}", "axial: {law: linear, stiffness: 5.2e8, max_strain: 1.0e-3}}"
    )
    .replace("  failure: {minimum_breaking_load: 6.0e5, safety_factor: 1.5}\n", "")
    .replace(
        "  line.failure.minimum_breaking_load: [3.0e5, 6.0e5, 1.2e6]\n",
        "  line.segments.1.length: [340.0, 350.0]\n",
    )
)


@pytest.fixture(autouse=True)
def _fresh_static_cache(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(static_analysis, "_STATIC_CACHE", OrderedDict())


@pytest.mark.parametrize("text", [BREAK, LAW], ids=["break", "law-range"])
def test_break_limits_run_as_arrays_with_the_case_datasets_bits(tmp_path: Path, text: str) -> None:
    src = parse_study_text(text, "gb.yaml")
    grid = expand_grid(src)
    assert grid.chunked and grid.arrays
    fast = xr.load_dataset(
        run_study(src, grid, tmp_path / "g", scheduler="synchronous", use_cache=False).path
    )
    slow = xr.load_dataset(
        run_study(
            src, replace(grid, chunked=False), tmp_path / "c", scheduler="synchronous",
            use_cache=False,
        ).path
    )  # fmt: skip
    status = slow["status"].values
    if text is BREAK:
        # broken exactly where the largest tension passes MBL / SF: on this hanging leg
        # the tension grows towards the fairlead (each piece's weight adds to it), so
        # its largest is tension_b (the limit is the whole line's)
        limit = slow["minimum_breaking_load"] / 1.5
        broken = (slow["tension_b"] > limit).values
        assert broken.any() and not broken.all()
        assert np.array_equal(status == 10, broken)
        assert np.all(status[~broken] == 0)
        kept = slow["tension_b"].values[broken]
        assert np.isfinite(kept).all()  # a broken case keeps its results
        assert fast.attrs["cases_broken"] == int(broken.sum())
    else:
        # failed where the wire's strain T / EA passes 1e-3 somewhere, solved elsewhere
        assert (status == 0).any() and (status != 0).any()
        assert "max_strain" in str(slow["message"].values[status != 0][0])
    same_bits(fast, slow)


#: a chain of a catalogue line type hanging in water: its nominal size and its length
#: swept (validation derives its diameter, mass and stiffness from the size, so each
#: combination's line is validated as a whole study once)
CHAIN = """\
name: gt
environment: {fluid: water}
line:
  segments:
    - {length: 120.0, line_type: {material: chain_studless, nominal_diameter: 0.076}}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -100.0]}
  b: {kind: fixed, position: [60.0, 0.0, -10.0]}
analysis:
  static: {nodes: 25}
sweep:
  line.segments.0.line_type.nominal_diameter: [0.064, 0.076, 0.095]
  line.segments.0.length: [115.0, 125.0]
  ends.b.position.0: [50.0, 70.0]
"""


def test_a_catalogue_size_sweep_runs_as_arrays_with_the_case_datasets_bits(
    tmp_path: Path,
) -> None:
    from cablestudy.study.grid_lines import line_studies
    from cablestudy.study.problem import line_model

    src = parse_study_text(CHAIN, "gt.yaml")
    grid = expand_grid(src)
    assert grid.chunked and grid.arrays
    assert "line.segments.0.line_type.nominal_diameter" in grid.whole
    fast = xr.load_dataset(
        run_study(src, grid, tmp_path / "g", scheduler="synchronous", use_cache=False).path
    )
    slow = xr.load_dataset(
        run_study(
            src, replace(grid, chunked=False), tmp_path / "c", scheduler="synchronous",
            use_cache=False,
        ).path
    )  # fmt: skip
    assert (slow["status"] == 0).all()
    same_bits(fast, slow)
    # the line hangs free: its supports carry its whole weight in water, w(d) L, w from
    # the catalogue size's line (heavier for a larger size), to the solver's tolerance
    # (1e-9 of the forces)
    weights = [float(line_model(s).weight[0]) for s in line_studies(grid)]
    w = np.array(weights).reshape(3, 2)  # (size, length)
    assert np.all(np.diff(w[:, 0]) > 0.0)
    fz = (fast["force_a"] + fast["force_b"]).sel(component="z").values  # (size, length, x)
    carried = -fz
    length = np.array([115.0, 125.0])
    expected = (w * length[None, :])[..., None]
    assert np.max(np.abs(carried - expected) / expected) <= 1e-8
