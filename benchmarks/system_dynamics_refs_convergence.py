"""Mesh convergence of the system time domain on each MoorDyn reference of
``tests/data/moordyn_system_refs`` (issue 24): for each mesh (elements per line x steps
a period), the largest difference of the lines' end extremes from the first (finest)
mesh and from MoorDyn's reference, each relative to the extreme itself, and the CPU
time of the case. The tables in the docstring of
``tests/validation/test_system_dynamics_moordyn.py`` and in docs/guide/systems.md.
Run: ``PYTHONPATH=$PWD python benchmarks/system_dynamics_refs_convergence.py NAME MESH...``
(NAME as ``lines_surge``, MESH as ``80x128``, the finest first)."""

from __future__ import annotations

import json
import sys
import time

import numpy as np

from cablestudy.analyses.system import evaluate_system_case
from cablestudy.study import parse_study_text
from cablestudy.study.grid import expand_cases
from tests.validation.test_system_dynamics_moordyn import KEYS, REFS, study_text


def main(name: str, meshes: list[str]) -> None:
    ref = json.loads((REFS / f"{name}.json").read_text())["reference"]
    finest = None
    print("mesh | vs finest | vs MoorDyn | CPU [s] | steps")
    for mesh in meshes:
        elements, steps = (int(v) for v in mesh.split("x"))
        (_, [case]) = expand_cases(parse_study_text(study_text(name, elements, steps), "x"))
        t = time.process_time()
        rec = evaluate_system_case(case)
        cpu = time.process_time() - t
        if rec.status != 0:
            print(f"{mesh} | status {rec.status}: {rec.message}")
            continue
        data = {k: np.asarray(rec.data[k], dtype=float) for k in KEYS}
        finest = finest or data
        own = max(float(np.max(np.abs(data[k] / finest[k] - 1.0))) for k in KEYS)
        md = max(float(np.max(np.abs(data[k] / np.asarray(ref[k]) - 1.0))) for k in KEYS)
        print(f"{mesh} | {own:.1e} | {md:.1e} | {cpu:.2f} | {int(rec.data['dynamic_steps'])}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
