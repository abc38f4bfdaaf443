"""Issue 20, item 1: where no batch kernel takes a case, the general solver solves it, and
the run's summary and the dataset's attributes (``cases_fallback``, ``fallback_reasons``)
say how many cases did so and why -- for every study, not only a static sweep. YAML ->
netCDF through the command line, on a study with a modal analysis (its cases are
evaluated as case records) and the same static sweep alone (run as a grid)."""

from __future__ import annotations

from pathlib import Path

import pytest
import xarray as xr

from cablestudy.cli import main

#: a 550 m wire hanging free between an anchor 190 m down and a fairlead 10 m down, at
#: two horizontal distances (both taut, clear of the seabed)
WIRE = """\
name: NAME
environment: {fluid: water, depth: 200.0}
line:
  segments:
    - {length: 550.0, diameter: 0.076, mass_per_length: 24.0, axial_stiffness: 3.3e8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -190.0]}
  b: {kind: fixed, position: [520.0, 0.0, -10.0]}
analysis:
  static: {method: METHOD, nodes: 21}MODAL
sweep:
  ends.b.position.0: {values: [520.0, 525.0], name: distance}
"""


def _run(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], method: str, modal: bool
) -> tuple[xr.Dataset, str]:
    name = f"wire-{method}-{'modal' if modal else 'static'}"
    cfg = tmp_path / f"{name}.yaml"
    text = WIRE.replace("NAME", name).replace("METHOD", method)
    cfg.write_text(text.replace("MODAL", "\n  modal: {modes: 3}" if modal else ""))
    out = tmp_path / "out"
    code = main(["run", str(cfg), "--out", str(out), "--scheduler", "synchronous"])
    printed = capsys.readouterr().out
    assert code == 0
    return xr.load_dataset(out / f"{name}.nc"), printed


@pytest.mark.parametrize("modal", [True, False], ids=["modal-case-records", "static-grid"])
def test_cases_no_kernel_takes_are_counted_with_why(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], modal: bool
) -> None:
    """Method shooting has no batch kernel: both cases go to the general solver, and the
    dataset and the summary say so, whichever path the study's analyses take. Method
    catenary on the same free-hanging lines: the compiled kernels settle both (a line
    clear of the seabed is what they solve), so none is counted."""
    ds, printed = _run(tmp_path, capsys, "shooting", modal)
    assert int((ds["status"] == 0).sum()) == 2
    if modal:
        assert "natural_frequency" in ds and int((ds["modal_status"] == 0).sum()) == 2
    assert ds.attrs["cases_fallback"] == 2
    assert ds.attrs["fallback_reasons"] == "2 x method 'shooting' has no batch kernel"
    assert (
        "2 cases solved by the general solver (no batch kernel took them): "
        "2 x method 'shooting' has no batch kernel"
    ) in printed
    ds, printed = _run(tmp_path, capsys, "catenary", modal)
    assert int((ds["status"] == 0).sum()) == 2
    assert ds.attrs["cases_fallback"] == 0 and ds.attrs["fallback_reasons"] == ""
    assert "general solver" not in printed
