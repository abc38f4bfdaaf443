"""Running the peer codes on our cases (optional extra `peers`: MoorPy, MoorDyn).

Nothing here is copied from the peers; we only call their public Python interfaces.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np


def have(module: str) -> bool:
    try:
        __import__(module)
    except ImportError:
        return False
    return True


@contextlib.contextmanager
def quiet_stdout() -> Iterator[None]:
    """Silence a C library's console output (file descriptors 1 and 2)."""
    saved = [os.dup(1), os.dup(2)]
    with open(os.devnull, "w") as null:
        os.dup2(null.fileno(), 1)
        os.dup2(null.fileno(), 2)
        try:
            yield
        finally:
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            for fd in saved:
                os.close(fd)


@dataclass(frozen=True)
class CableCase:
    """A single line between a fixed end A (origin) and a moved end B."""

    length: float  # [m]
    span: float  # [m] horizontal, along x
    rise: float  # [m] z_B - z_A
    diameter: float  # [m]
    mass: float  # [kg/m]
    axial_stiffness: float  # [N]
    density: float  # [kg/m^3] of the fluid
    drag_normal: float = 1.2
    drag_tangential: float = 0.01
    added_mass_normal: float = 1.0
    depth: float = 1000.0


@dataclass
class PeerDynamicResult:
    tension_max: float
    tension_min: float
    wall_time: float  # [s] time stepping only
    init_time: float  # [s] initial-state (static/dynamic relaxation) time


def moordyn_harmonic(
    case: CableCase,
    *,
    amplitude: float,
    frequency: float,
    segments: int,
    dt: float,
    periods: int = 8,
    window: int = 2,
    ramp_periods: float = 1.0,
    samples_per_period: int = 200,
) -> PeerDynamicResult:
    """MoorDyn with end B moved harmonically along x, ``amplitude * r(t) * sin(2 pi f t)``
    with the ramp ``r = (1 - cos(pi t / t_r)) / 2`` over ``ramp_periods`` periods (the
    ramp of cablestudy's dynamics); max/min tension at end B over the last ``window``
    periods, sampled ``samples_per_period`` times a period."""
    text = f"""--------------------- MoorDyn Input File ------------------------------------
cablestudy benchmark
----------------------- LINE TYPES ------------------------------------------
TypeName   Diam    Mass/m     EA     BA/-zeta    EI    Cd     Ca     CdAx    CaAx
(name)     (m)     (kg/m)     (N)    (N-s/-)    (N-m^2) (-)   (-)    (-)     (-)
cable {case.diameter} {case.mass} {case.axial_stiffness} -0.8 0.0 \
{case.drag_normal} {case.added_mass_normal} {case.drag_tangential} 0.0
---------------------- POINTS --------------------------------
ID     Attachment  X        Y     Z       Mass   Volume  CdA    Ca
(#)    (-)         (m)      (m)   (m)     (kg)   (m^3)   (m^2)  (-)
1      Fixed       0.0      0.0   -1.0    0      0       0      0
2      Coupled     {case.span}   0.0   {-1.0 + case.rise}     0      0       0      0
---------------------- LINES --------------------------------------
ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)  (name)     (#)      (#)      (m)       (-)      (-)
1    cable      1        2        {case.length}   {segments}       -
---------------------- OPTIONS -----------------------------------------
{dt}  dtM
{case.depth}  WtrDpth
{case.density}  WtrDnsty
5.0       ICDfac
0.0001    ICthresh
20        TmaxIC
0         writeLog
----------------------------OUTPUTS--------------------------------------------
FairTen1
------------------------- need this line --------------------------------------
"""
    return moordyn_prescribed(
        text,
        x0=np.array([case.span, 0.0, -1.0 + case.rise]),
        direction=np.array([1.0, 0.0, 0.0]),
        amplitude=amplitude,
        frequency=frequency,
        periods=periods,
        window=window,
        ramp_periods=ramp_periods,
        samples_per_period=samples_per_period,
    )


def moordyn_prescribed(
    text: str,
    *,
    x0: np.ndarray,
    direction: np.ndarray,
    amplitude: float,
    frequency: float,
    periods: int,
    window: int,
    ramp_periods: float,
    samples_per_period: int,
    extra_files: dict[str, str] | None = None,
) -> PeerDynamicResult:
    """Run the MoorDyn input file ``text`` (one ``Coupled`` point, at ``x0`` [m]) with that
    point moved ``amplitude * r(t) * sin(2 pi f t)`` [m] along the unit vector
    ``direction``, ``r = (1 - cos(pi t / t_r)) / 2`` over ``ramp_periods`` periods (the
    ramp of cablestudy's dynamics); the motion and its velocity are handed to MoorDyn
    ``samples_per_period`` times a period. Returns the maximum and minimum magnitude of
    the force on the coupled point over the last ``window`` periods [N], the time
    stepping's and the initial state's wall times [s]. ``extra_files`` (name -> text)
    are written beside the input file."""
    import moordyn

    direction = np.asarray(direction, dtype=float)
    x0 = np.asarray(x0, dtype=float)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "line.txt"
        path.write_text(text)
        for name, body in (extra_files or {}).items():
            (Path(tmp) / name).write_text(body)
        with quiet_stdout():
            t0 = time.perf_counter()
            system = moordyn.Create(str(path))
            moordyn.Init(system, x0, np.zeros(3))
            t1 = time.perf_counter()
            omega = 2.0 * np.pi * frequency
            period = 1.0 / frequency
            dt_out = period / samples_per_period
            n = int(round(periods * period / dt_out))
            t = 0.0
            tension = np.empty(n)
            t_r = ramp_periods * period
            for i in range(n):
                tn = t + dt_out
                if tn < t_r:
                    ramp = 0.5 * (1.0 - np.cos(np.pi * tn / t_r))
                    dramp = 0.5 * np.pi / t_r * np.sin(np.pi * tn / t_r)
                else:
                    ramp, dramp = 1.0, 0.0
                sin, cos = np.sin(omega * tn), np.cos(omega * tn)
                xx = x0 + ramp * amplitude * sin * direction
                vv = amplitude * (ramp * omega * cos + dramp * sin) * direction
                force = moordyn.Step(system, xx, vv, t, dt_out)
                tension[i] = float(np.linalg.norm(force))
                t = tn
            t2 = time.perf_counter()
            moordyn.Close(system)
    last = tension[-int(round(window * period / dt_out)) :]
    return PeerDynamicResult(float(last.max()), float(last.min()), t2 - t1, t1 - t0)
