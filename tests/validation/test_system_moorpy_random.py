"""Random spread moorings against NREL/MoorPy: inputs nobody on the team chose.

Each case is a body's three fairleads (held) moored by three legs at random headings in
random depths; a leg is one line or two joined at a free junction carrying a clump
(2 t, 10 t), a buoy (5 m^3) or both, of chain or wire, from 0.3 % to 25 % longer than
the straight line from anchor to fairlead: junctions hang, float, or rest on the seabed
with the leg's bottom laid. The case is written as a MoorDyn input file, which MoorPy
reads and solves (``System.solveEquilibrium``), and which cablestudy imports
(``import_model``, a system study) and runs through the command line to its netCDF.

Three oracles:
* ours balances every free point with the forces it writes (lines' end forces, the
  point's wet weight, ``point_seabed_force``): 1e-8 of the largest tension, the system
  tolerance (1e-9) with room for the sum;
* MoorPy's tensions. MoorPy gives its points a soft seabed: a point within ``zTol`` (2 m
  by default) of the seabed is held up by a force rising linearly to its wet weight at
  the seabed, so a clump resting on the rigid seabed hangs up to ``zTol`` above it in
  MoorPy with a stretch of chain lifted (7.9e-3 of the largest tension off in random
  cases); the test sets ``zTol`` to 1e-4 m. MoorPy stops on its position step and leaves
  its points a residual force r (33 N in one); a line's end force differs from the
  balanced one by about r at most (the point's stiffness is the sum of its lines'), so
  the bound is 1e-6 of the largest tension plus 2 r. Where MoorPy finds no equilibrium
  (its solver's error, or a catenary whose horizontal pull differs between its ends) only
  the first oracle applies; ours solves those;
* a line refused by name as lying slack on the seabed is longer than the way along the
  seabed and straight up to its higher end, recomputed here;
* a free point refused by name as resting on the seabed with every line lying slack from
  it (its place there is not determined by the statics) has every line slack at it in
  MoorPy's answer too, which leaves it where its iteration stops.
"""

from __future__ import annotations

from pathlib import Path

import moorpy
import numpy as np
import pytest
import xarray as xr
import yaml

from cablestudy.cli import main
from cablestudy.interchange import import_model, imported_yaml

TYPES = [
    "chain      0.1     150        8e8    -1         0      2.4    1.0    1.15    0.5",
    "wire       0.08    30         6e8    -1         0      1.2    1.0    0.008   0.0",
]


def _spread(seed: int, longer: tuple[float, float]) -> tuple[str, int]:
    """A random spread mooring as a MoorDyn file's text, and its number of lines."""
    rng = np.random.default_rng(seed)
    depth = float(rng.uniform(80, 400))
    radius = float(rng.uniform(2.0, 5.0) * depth)
    points: list[tuple] = []
    lines: list[tuple] = []
    for heading in np.radians(np.sort(rng.uniform(0, 360, 3))):
        c, s = np.cos(heading), np.sin(heading)
        fair = (20 * c, 20 * s, -float(rng.uniform(5, 15)))
        anchor = (radius * c, radius * s, -depth)
        length = float(np.hypot(radius - 20, depth + fair[2]) * rng.uniform(*longer))
        points += [("Fixed", *anchor, 0.0, 0.0), ("Fixed", *fair, 0.0, 0.0)]
        a, b = len(points) - 1, len(points)
        if rng.random() < 0.7:
            f = float(rng.uniform(0.2, 0.8))
            mass, vol = (
                float(rng.choice([0.0, 2000.0, 10000.0])),
                float(rng.choice([0.0, 0.0, 5.0])),
            )
            at = [anchor[i] + f * (fair[i] - anchor[i]) for i in range(2)]
            points.append(("Free", *at, -depth + 0.5 * f * depth, mass, vol))
            t1, t2 = rng.choice(["chain", "wire"], 2)
            lines += [(t1, a, len(points), f * length), (t2, len(points), b, (1 - f) * length)]
        else:
            lines.append((str(rng.choice(["chain", "wire"])), a, b, length))
    text = [
        "--------------------- MoorDyn Input File ------------------------------------",
        f"random spread mooring, seed {seed}",
        "----------------------- LINE TYPES ------------------------------------------",
        "TypeName   Diam    Mass/m     EA     BA/-zeta    EI    Cd     Ca     CdAx    CaAx",
        "(name)     (m)     (kg/m)     (N)    (N-s/-)    (N-m^2) (-)   (-)    (-)     (-)",
        *TYPES,
        "---------------------- POINTS --------------------------------",
        "ID  Attachment  X       Y     Z      Mass   Volume  CdA    CA",
        "(#)   (-)       (m)     (m)   (m)    (kg)   (m^3)   (m^2)  (-)",
        *(
            f"{i} {p[0]} {p[1]:.4f} {p[2]:.4f} {p[3]:.4f} {p[4]} {p[5]} 0 0"
            for i, p in enumerate(points, 1)
        ),
        "---------------------- LINES --------------------------------------",
        "ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs",
        "(#)   (name)     (#)      (#)       (m)        (-)      (-)",
        *(f"{i} {t} {a} {b} {L:.4f} 20 -" for i, (t, a, b, L) in enumerate(lines, 1)),
        "---------------------- OPTIONS -----------------------------------------",
        f"{depth:.4f}   depth",
        "1025   rho",
        "9.81   g",
        "---------------------- OUTPUTS --------------------------------------------",
        "END",
    ]
    return "\n".join(text) + "\n", len(lines)


def _ours_balance(ds, study: dict, rho_g: float) -> float:  # noqa: ANN001
    """The largest net force on a free point from our dataset: its lines' end forces,
    its own wet weight and the seabed's force, over the largest tension."""
    fa, fb = ds.force_a.values, ds.force_b.values
    names = [str(n) for n in ds.point.values]
    net = ds.point_seabed_force.values.copy()
    for j, name in enumerate(names):
        p = study["points"][name]
        net[j, 2] += rho_g * p.get("volume", 0.0) - 9.81 * p.get("mass", 0.0)
    for i, line in enumerate(study["lines"].values()):
        for end, f in (("a", fa[i]), ("b", fb[i])):
            if line[end] in names:
                net[names.index(line[end])] += f
    return float(np.max(np.abs(net))) / float(np.max(np.abs(np.concatenate([fa, fb]))))


@pytest.mark.parametrize("seed", range(3))
def test_random_taut_spread_matches_moorpy(tmp_path: Path, seed: int) -> None:
    check_spread(tmp_path, seed, (1.003, 1.03))


def check_spread(tmp_path: Path, seed: int, longer: tuple) -> None:
    """One random spread mooring through MoorPy and ours (the module's oracles); the
    slack family runs from its own file (test_system_moorpy_random_slack.py), so that
    the test workers share the two."""
    text, n_lines = _spread(seed, longer)
    path = tmp_path / f"spread{seed}.dat"
    path.write_text(text)
    ms = moorpy.System(file=str(path))
    for p in ms.pointList:
        p.zTol = 1e-4  # a rigid seabed for MoorPy's points (module docstring)
    ms.initialize()
    try:
        ms.solveEquilibrium(tol=1e-8)
        theirs = np.array([[ln.TA, ln.TB] for ln in ms.lineList])
        residual = max(np.max(np.abs(p.getForces())) for p in ms.pointList if p.type == 0)
        # in still water a line's horizontal pull is the same at both ends: where one of
        # MoorPy's catenaries breaks that (a slack line beside a float: 62 MN at one end,
        # 0 at the other), its equilibrium is not one
        if max(np.max(np.abs(ln.fA[:2] + ln.fB[:2])) for ln in ms.lineList) > 1e-6 * theirs.max():
            residual = np.inf
    except moorpy.helpers.SolveError:
        theirs, residual = None, np.inf

    study = yaml.safe_load(imported_yaml(import_model(text, path.name, name=f"s{seed}"), path.name))
    study["analysis"] = {"static": {"nodes": 21}}
    name = study["name"]
    (tmp_path / f"{name}.yaml").write_text(yaml.safe_dump(study, sort_keys=False))
    args = ["run", str(tmp_path / f"{name}.yaml"), "--out", str(tmp_path), "--no-cache"]
    main([*args, "--no-progress", "--scheduler", "synchronous"])
    ds = xr.load_dataset(tmp_path / f"{name}.nc")
    if int(ds.status) == 4 and "lies slack on the seabed" in str(ds.message.values):
        # refused by name: the line is longer than the way along the seabed and up
        i = int(str(ds.message.values).split(":")[0].split()[-1]) - 1
        line = list(study["lines"].values())[i]
        a, b = (np.array(study["points"][line[e]]["position"]) for e in "ab")
        low, high = (a, b) if a[2] < b[2] else (b, a)
        way = np.hypot(*(high - low)[:2]) + high[2] - low[2]
        assert line["segments"][0]["length"] > way
        return
    message = str(ds.message.values)
    if int(ds.status) == 4 and "with every line lying slack from it" in message:
        # refused by name: no line pulls the point where it rests; MoorPy, which leaves
        # such a point where its iteration stops, has every line slack at it too
        point = ms.pointList[int(message.split("free point point")[-1].split()[0]) - 1]
        ends = [
            ms.lineList[n - 1].TB if b else ms.lineList[n - 1].TA
            for n, b in zip(point.attached, point.attachedEndB, strict=True)
        ]
        assert max(ends) <= 1e-6 * theirs.max()
        return
    assert int(ds.status) == 0, message
    # ours balances every free point (the lines' end forces as written, the point's
    # wet weight, the seabed's force): the system tolerance, 1e-9 of the largest tension
    assert _ours_balance(ds, study, 1025.0 * 9.81) <= 1e-8
    fa = ds.force_a.values.reshape(n_lines, 3)
    fb = ds.force_b.values.reshape(n_lines, 3)
    mine = np.stack([np.linalg.norm(fa, axis=-1), np.linalg.norm(fb, axis=-1)], -1)
    if theirs is None or residual > 1e-3 * np.max(mine):
        return  # MoorPy found no equilibrium: ours balances (above)
    # MoorPy stops on its position step, its points left with a residual force r; a
    # line's end force then differs from the balanced one by at most about r
    assert np.max(np.abs(mine - theirs)) <= 1e-6 * np.max(mine) + 2.0 * residual
