"""The still-water drag fit in closed form (issue 24; cablestudy/dynamics/elliptic_fit.py,
unit tests in tests/unit/test_elliptic_drag_fit.py) from the study file to the dataset:
case8 in surge without ``linearisation.samples`` (the exact means at every node) against
``samples: 4096`` and ``samples: 32`` (the phase sums)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from cablestudy.cli import main

CONFIG = Path(__file__).parents[2] / "configs" / "system-case8-surge.yaml"


FREQUENCY = """\
  dynamic:
    excitation: {{body: body1, dof: surge, amplitude: 2.0, frequency: 0.1}}
    method: frequency
    elements: 12  # per line (not test_system_frequency's 20: its assembly is counted)
{linearisation}"""


def _case8(tmp: Path, linearisation: str) -> xr.Dataset:
    text = CONFIG.read_text()
    tmp.mkdir()
    cfg = tmp / "case8.yaml"
    cfg.write_text(text[: text.index("  dynamic:")] + FREQUENCY.format(linearisation=linearisation))
    args = ["run", str(cfg), "--out", str(tmp), "--no-cache", "--no-progress"]
    assert main([*args, "--scheduler", "synchronous"]) == 0
    return xr.load_dataset(tmp / "system-case8-surge.nc")


def test_case8_without_samples_is_the_many_phase_answer(tmp_path: Path) -> None:
    """case8 (three-dimensional legs, no current) from the study file: ``samples``
    unset (the exact means) against ``samples: 4096`` (the phase sums at their limit
    within 1e-10, previous test): the two drag iterations stop within their tolerance
    (1e-6 of the velocities) of one fixed point, so the tension amplitudes agree within
    a few times that: bar 5e-6 of the largest; against 32 phases they differ."""
    exact = _case8(tmp_path / "exact", "")
    dense = _case8(tmp_path / "dense", "    linearisation: {samples: 4096}\n")
    coarse = _case8(tmp_path / "coarse", "    linearisation: {samples: 32}\n")
    for ds in (exact, dense, coarse):
        assert np.all(ds.status.values == 0), ds.message.values
    for end in ("a", "b"):
        a, b = exact[f"tension_amplitude_{end}"].values, dense[f"tension_amplitude_{end}"].values
        np.testing.assert_allclose(a, b, rtol=0.0, atol=5e-6 * np.abs(b).max())
    a, c = exact.tension_amplitude_a.values, coarse.tension_amplitude_a.values
    assert not np.array_equal(a, c)
