"""Mooring system dynamics on MoorPy's case8 (issue 24): the spar with three bridled
polyester legs surged 2 m at 0.1 Hz (``configs/system-case8-surge.yaml``), run at
several meshes (elements per line x time steps a period) in one process.

For each mesh: CPU time of the whole case (system statics, the model's discrete
equilibrium, the time domain) and of the time domain alone (the statics and the model
shared, as in a sweep of the motion), steps, Newton iterations, and the largest
difference of the lines' end extremes (tension_max_a/min_a/max_b/min_b) from our finest
mesh (80 x 256), relative to the largest tension; with MoorDyn's reference
(``tests/data/moordyn_system_refs/case8_surge.json``, branch ``sysref``) also the
largest difference from it, relative to each value. Run:
``python benchmarks/wp_system_dynamics_case8.py [MESH ...]`` (MESH as ``20x128``).
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

from cablestudy import system_dynamic_cases as sdc
from cablestudy.cases import expand_cases
from cablestudy.config import parse_study_text
from cablestudy.system_cases import evaluate_system_case

ROOT = Path(__file__).parents[1]
CONFIG = ROOT / "configs" / "system-case8-surge.yaml"
REFS = ROOT / "tests" / "data" / "moordyn_system_refs" / "case8_surge.json"
KEYS = ("tension_max_a", "tension_min_a", "tension_max_b", "tension_min_b")
MESHES = ("80x256", "4x32", "5x128", "10x64", "10x128", "20x128", "40x128", "20x32", "20x64")


def run(mesh: str, repeats: int = 3) -> tuple[dict, float, float]:
    """(outputs, CPU s of the whole case, CPU s of the time domain alone)."""
    elements, steps = mesh.split("x")
    text = CONFIG.read_text().replace("elements: 20", f"elements: {elements}")
    text = text.replace("points_per_period: 128", f"points_per_period: {steps}")
    (_, [case]) = expand_cases(parse_study_text(text, "case8.yaml"))
    whole, alone = [], []
    rec = None
    for _ in range(repeats):
        sdc._MODEL_CACHE.clear()
        sdc._STATIC_CACHE.clear()
        t = time.process_time()
        rec = evaluate_system_case(case)
        whole.append(time.process_time() - t)
        t = time.process_time()
        rec = evaluate_system_case(case)
        alone.append(time.process_time() - t)
    assert rec is not None and rec.status == 0, rec.message if rec else ""
    return rec.data, min(whole), min(alone)


def main(meshes: list[str]) -> None:
    ref = json.loads(REFS.read_text())["reference"] if REFS.is_file() else None
    run("2x16", repeats=1)  # kernels loaded
    finest, _, _ = run(meshes[0], repeats=1)
    big = float(np.max(finest["tension_max_b"]))
    print("mesh | CPU case [s] | CPU dynamics [s] | steps | Newton | vs finest | vs MoorDyn")
    for mesh in meshes:
        data, whole, alone = run(mesh)
        own = max(float(np.max(np.abs(data[k] - finest[k]))) for k in KEYS) / big
        md = (
            max(float(np.max(np.abs(data[k] / np.asarray(ref[k]) - 1.0))) for k in KEYS)
            if ref
            else float("nan")
        )
        print(
            f"{mesh} | {whole:.3f} | {alone:.3f} | {int(data['dynamic_steps'])} | "
            f"{int(data['newton_iterations'])} | {own:.2e} | {md:.2e}",
            flush=True,
        )


if __name__ == "__main__":
    main(sys.argv[1:] or list(MESHES))
