"""``cablestudy compile`` warms every kernel signature a run uses (issue 20, item 4: a
user's first study should not compile at run time without saying so).

numba compiles a kernel once per signature (argument types, including each array's
layout: a C-ordered and an F-ordered array are two signatures). In a fresh interpreter
the compile step's warm-ups run (:data:`cablestudy.kernels._WARM`, every kind), then a
few representative studies through ``cablestudy run`` in the same process (synchronous
scheduler): a kernel signature those runs add to any numba dispatcher of the package is
one a user's first run compiles although ``cablestudy compile`` ran, and fails the test
with its name and types. (Main had one: the batch statics' arc lengths from
``np.linspace(..., axis=1)`` are F-ordered, a second signature of
``_fast.solve_cases`` compiled by the first study with a towed end B.)
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
#: quick configs reaching the batch statics (towed end, anchored on the seabed, a
#: current), the time and frequency domains, a system's statics and time domain (and its
#: frequency domain, made from the last in the test)
CONFIGS = (
    "cable-break-catenary",
    "tutorial-towed-cable",
    "mooring-span-sweep",
    "vaz-patel-turning-current",
    "umbilical-frequency-tension-30kg",
    "system-case8-surge",
)
#: a chain anchored on a sloped seabed in a current (the general solver's drag
#: iteration with seabed contact) and still (the contact kernel), swept as arrays
SEABED = """\
name: NAME
environment:
  fluid: water
  depth: 30.0
  seabed: {slope_deg: 5.0, friction: 0.3}
CURRENTline:
  segments:
    - {length: 200.0, diameter: 0.15, mass_per_length: 141.0, axial_stiffness: 6.0e+8}
ends:
  a: {kind: fixed, position: [0.0, 0.0, -30.0]}
  b: {kind: fixed, position: [0.0, 190.0, -15.0]}
sweep:
  ends.b.position.0: [-5.0, 5.0]
"""
_CHILD = textwrap.dedent(
    """
    import contextlib, io, json, sys, tempfile
    from numba.core.registry import CPUDispatcher
    from cablestudy import kernels
    from cablestudy.cli import main

    def signatures():
        out = {}
        for name, mod in list(sys.modules.items()):
            if name.startswith("cablestudy"):
                for obj in list(vars(mod).values()):
                    if isinstance(obj, CPUDispatcher):
                        key = f"{obj.py_func.__module__}.{obj.py_func.__qualname__}"
                        out.setdefault(key, set()).update(map(str, obj.signatures))
        return out

    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        for kind in kernels.KINDS:
            kernels._WARM[kind]()
        warm = signatures()
        codes = [
            main(["run", path, "--out", tempfile.mkdtemp(), "--no-cache", "--no-progress",
                  "--scheduler", "synchronous"])
            for path in sys.argv[1:]
        ]
    new = {k: sorted(v - warm.get(k, set())) for k, v in signatures().items()}
    print(json.dumps({"codes": codes, "new": {k: v for k, v in new.items() if v}}))
    """
)


def test_runs_compile_no_signature_the_compile_step_missed(tmp_path: Path) -> None:
    paths = [str(ROOT / "configs" / f"{name}.yaml") for name in CONFIGS]
    current = "  current:\n    - {z: 0.0, speed: 0.5, heading_deg: 60.0}\n"
    for name, text in (("calm", ""), ("current", current)):
        path = tmp_path / f"{name}.yaml"
        path.write_text(SEABED.replace("NAME", name).replace("CURRENT", text))
        paths.append(str(path))
    system = (ROOT / "configs" / "system-case8-surge.yaml").read_text()
    fd = tmp_path / "system-frequency.yaml"
    fd.write_text(
        system.replace("    points_per_period: 128\n", "    method: frequency\n")
        + "sweep:\n  analysis.dynamic.excitation.frequency: [0.05, 0.1]\n"
    )
    paths.append(str(fd))
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    done = subprocess.run(
        [sys.executable, "-c", _CHILD, *paths],
        capture_output=True,
        text=True,
        env=env,
        cwd=tmp_path,
        check=True,
    )
    got = json.loads(done.stdout.strip().splitlines()[-1])
    assert got["codes"] == [0] * len(paths)
    assert got["new"] == {}, "compiled at run time, not by cablestudy compile:\n" + "\n".join(
        f"{k}: {s}" for k, v in got["new"].items() for s in v
    )
