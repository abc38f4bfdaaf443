"""`make bench` without the optional `peers` extra: every peer is skipped with a message,
never an error. MoorPy and MoorDyn are hidden by putting None into sys.modules (then
`import moorpy` raises ImportError, exactly as when the package is absent)."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

BENCH = Path(__file__).resolve().parents[2] / "benchmarks"


def _load(name: str) -> ModuleType:
    spec = importlib.util.spec_from_file_location(name, BENCH / f"{name}.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture
def no_peers(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in ("moorpy", "moorpy.Catenary", "moordyn"):
        monkeypatch.setitem(sys.modules, name, None)
    monkeypatch.syspath_prepend(str(BENCH))
    monkeypatch.delitem(sys.modules, "peers", raising=False)


def test_static_catenary_benchmark_skips_moorpy(no_peers: None, tmp_path: Path) -> None:
    from cablestudy.bench import run_benchmarks

    text = run_benchmarks(tmp_path, quick=True, only=["wp_static_catenary"])
    assert "MoorPy not installed" in text
    assert (tmp_path / "static_catenary.nc").exists()
    assert (tmp_path / "static_catenary.png").exists()


def test_drag_and_dynamic_peers_are_skipped_with_a_message(no_peers: None) -> None:
    from cablestudy.bench import WorkPrecision

    drag = _load("wp_static_drag")
    wp = WorkPrecision(name="x", title="x", error_name="e")
    drag.moorpy_fig8(wp, None, 1)  # returns before touching the reference
    assert not wp.curves and "MoorPy not installed" in wp.notes[0]

    dyn = _load("wp_dynamic_moustafa")
    wp = WorkPrecision(name="y", title="y", error_name="e")
    dyn.moordyn(wp, 0.5, 0.05, lambda t: float(np.max(t)), True)
    assert not wp.curves and "MoorDyn not installed" in wp.notes[0]
    # and the summary table of a benchmark without a peer has no ratio, no error
    c = wp.curve("ours")
    c.add("a", 1.0, 1e-3)
    assert wp.summary_rows()[0].endswith("|  |")
