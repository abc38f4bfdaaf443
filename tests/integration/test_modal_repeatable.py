"""The modal analysis is repeatable: the same study gives the same bits run after run
(ARPACK from a fixed start vector, not its own random one, whose generator state carries
over between calls), and every mode shape follows one sign convention
(cablestudy.dynamics.modal.normalise_modes), YAML -> netCDF through the command line."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp
import xarray as xr
from scipy.sparse.linalg import eigsh

from cablestudy.cli import main
from cablestudy.dynamics.modal import BANDED_LIMIT, SIGN_TIE, normalise_modes

#: a shallow level cable in water (symmetric about its middle: its antisymmetric modes
#: have two equal extremes, mirror images, the ties of the sign convention); 200
#: elements, 10 modes: ARPACK's path (more than BANDED_LIMIT unknowns, fewer than half
#: wanted); 201 static nodes, so the output points are the modal model's nodes
STUDY = """\
name: modes
environment: {fluid: water}
line:
  segments:
    - {length: 100.2, diameter: 0.05, mass_per_length: 8.0, axial_stiffness: 1.0e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -10.0]}
  b: {kind: fixed, position: [100.0, 0.0, -10.0]}
analysis:
  static: {method: analytic, nodes: 201}
  modal: {modes: 10, elements: 200}
sweep:
  line.segments.0.added_mass_normal: [0.0, 1.0]
"""


def _run(tmp_path: Path, scheduler: str = "synchronous") -> xr.Dataset:
    tmp_path.mkdir(parents=True, exist_ok=True)
    cfg = tmp_path / "modes.yaml"
    cfg.write_text(STUDY)
    args = ["run", str(cfg), "--out", str(tmp_path), "--no-cache", "--scheduler", scheduler]
    assert main(args) == 0
    return xr.load_dataset(tmp_path / "modes.nc")


def _stir_arpack() -> None:
    """A call of ARPACK with its own random start, as any other modal case of the process
    makes: it moves the generator ARPACK draws its start vectors from."""
    A = sp.diags([np.arange(1.0, 201.0)], [0], format="csc")
    eigsh(A, k=3, sigma=0.0, which="LM")


def test_two_runs_give_the_same_bits(tmp_path: Path) -> None:
    first = _run(tmp_path / "one")
    _stir_arpack()
    second = _run(tmp_path / "two")
    assert (first["status"] == 0).all()
    dof = int(first["modal_dof"].max())
    assert dof > BANDED_LIMIT and 2 * 10 < dof  # ARPACK's path, where it went wrong
    for name in first.variables:
        if name == "wall_time":
            continue
        a, b = first[name].values, second[name].values
        assert a.dtype == b.dtype and a.tobytes() == b.tobytes(), name
    # and on threads (chunks of cases at the same time): the same bits again
    threads = _run(tmp_path / "threads", "threads")
    for name in ("natural_frequency", "mode_shape"):
        assert first[name].values.tobytes() == threads[name].values.tobytes(), name


def test_the_sign_convention_holds_on_every_mode(tmp_path: Path) -> None:
    ds = _run(tmp_path)
    assert "signed so that its largest component is positive" in ds["mode_shape"].attrs["long_name"]
    shapes = ds["mode_shape"].transpose(..., "mode", "s", "component").values
    tied = 0
    for U in shapes.reshape(-1, *shapes.shape[-2:]):
        mag = np.linalg.norm(U, axis=-1)
        # scaled: the largest nodal displacement is 1 m (to the division's round-off)
        assert mag.max() == pytest.approx(1.0, rel=1e-14)
        nodes = np.flatnonzero(mag >= (1.0 - SIGN_TIE) * mag.max())
        tied += nodes.size > 1
        size = np.abs(U[nodes[0]])
        comp = int(np.flatnonzero(size >= (1.0 - SIGN_TIE) * size.max())[0])
        assert U[nodes[0], comp] > 0.0
    # the symmetric line's antisymmetric modes tie two mirror nodes: the rule was needed
    assert tied >= 2


def test_the_convention_does_not_flip_with_round_off() -> None:
    """Two mirror extremes differing by round-off either way (as two solves of the same
    model may give them): the largest-node rule alone would flip the sign; the tie rule
    keeps it, and a shape and its negative normalise to the same."""
    s = np.linspace(0.0, 1.0, 41)
    shape = np.zeros((1, s.size, 3))
    shape[0, :, 2] = np.sin(2.0 * np.pi * s)  # antisymmetric: extremes +1 and -1
    out = []
    for eps in (1e-13, -1e-13):
        U = shape.copy()
        U[0, 30, 2] *= 1.0 + eps  # the trough at s = 0.75, just larger or just smaller
        out.append(normalise_modes(U))
        out.append(normalise_modes(-U))
    for U in out:
        assert U[0, 10, 2] == pytest.approx(1.0, rel=1e-12)  # the crest at s = 0.25, first
        assert np.allclose(U, out[0], rtol=0.0, atol=1e-12)
