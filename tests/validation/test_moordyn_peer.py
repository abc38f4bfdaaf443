"""An exported MoorDyn input file runs in MoorDyn and reads into MoorPy (optional extra
`peers`), and their static fairlead forces agree with our static solution.

MoorDyn finds its initial state by running the line to rest and stops when the
fairlead tensions change by less than ``threshIC`` (relative; the exported file sets
1e-3). Its lumped-mass chain carries the half-segment weights at the end nodes, and the
force on the coupled fairlead point is the whole end force, so its discretisation
error is of order (segment length / line length)^2 ~ (1/20)^2 / 12 ~ 2e-4 for the
segment counts below (measured: 3e-4): below ``threshIC``. We therefore require agreement
to ``threshIC`` in each component, relative to the end tension.
"""

from __future__ import annotations

import contextlib
import os
import re
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from cablestudy.cli import main

PEERS = (
    "in the optional extra `peers` (pip install '.[peers]'); without it the exported file "
    "cannot be run"
)

STUDY = """
name: peer-check
environment: {fluid: water, depth: 300.0}
line:
  segments:
    - {length: 120.0, diameter: 0.08, mass_per_length: 40.0, axial_stiffness: 5.0e8}
    - {length: 100.0, diameter: 0.12, mass_per_length: 20.0, axial_stiffness: 2.0e8}
  attachments:
    - {s: 60.0, mass: 800.0, volume: 0.1}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -250.0]}
  b: {kind: fixed, position: [140.0, 0.0, -120.0]}
analysis:
  static: {method: catenary, nodes: 41, tolerance: 1.0e-12}
"""


@contextlib.contextmanager
def _quiet() -> Iterator[None]:
    saved = [os.dup(1), os.dup(2)]
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
        os.dup2(null.fileno(), 2)
        try:
            yield
        finally:
            for fd, target in zip(saved, (1, 2), strict=True):
                os.dup2(fd, target)
                os.close(fd)


def test_exported_file_runs_in_moordyn_with_our_fairlead_force(tmp_path: Path) -> None:
    moordyn = pytest.importorskip("moordyn", reason=f"MoorDyn is {PEERS}")
    study = tmp_path / "study.yaml"
    study.write_text(STUDY)
    path = tmp_path / "line.dat"
    assert main(["export", "moordyn", str(study), "--out", str(path)]) == 0
    assert main(["run", str(study), "--out", str(tmp_path), "--no-progress"]) == 0
    with xr.open_dataset(tmp_path / "peer-check.nc") as ds:
        ours = ds.force_b.values.astype(float)
    text = path.read_text()
    thresh = float(re.search(r"^(\S+)\s+threshIC", text, re.M).group(1))
    row = re.search(r"^(\d+)\s+Coupled\s+(\S+)\s+(\S+)\s+(\S+)", text, re.M)
    pid, x0 = int(row.group(1)), np.array([float(row.group(k)) for k in (2, 3, 4)])
    np.testing.assert_array_equal(x0, [140.0, 0.0, -120.0])
    with _quiet():
        system = moordyn.Create(str(path))
        moordyn.Init(system, x0, np.zeros(3))
        theirs = np.array(moordyn.GetPointForce(moordyn.GetPoint(system, pid)))
        moordyn.Close(system)
    tension = np.linalg.norm(ours)
    assert np.abs(theirs - ours).max() <= thresh * tension, (theirs, ours)


def test_moorpy_reads_the_exported_file_to_the_same_equilibrium(tmp_path: Path) -> None:
    """MoorPy (a quasi-static catenary code) reads the exported MoorDyn file, solves the
    free points' equilibrium (tolerance 1e-7 m on their positions) and finds the same
    fairlead force as ours: its catenary is exact, so the two agree to the position
    tolerance times the line's stiffness EA / L ~ 2e6 N/m, i.e. about 1e-6 of the
    tension."""
    mp = pytest.importorskip("moorpy", reason=f"MoorPy is {PEERS}")
    study = tmp_path / "study.yaml"
    study.write_text(STUDY)
    path = tmp_path / "line.dat"
    assert main(["export", "moordyn", str(study), "--out", str(path)]) == 0
    assert main(["run", str(study), "--out", str(tmp_path), "--no-progress"]) == 0
    with xr.open_dataset(tmp_path / "peer-check.nc") as ds:
        ours = ds.force_b.values.astype(float)
    with _quiet():
        system = mp.System(file=str(path))
        system.initialize()
        system.solveEquilibrium(tol=1e-7)
    fairlead = system.pointList[-1]
    np.testing.assert_array_equal(fairlead.r, [140.0, 0.0, -120.0])
    theirs = np.asarray(fairlead.getForces(), dtype=float)
    np.testing.assert_allclose(theirs, ours, atol=1e-6 * np.linalg.norm(ours))
