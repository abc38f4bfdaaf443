"""Work precision of the static catenary: the Fig. 4 steel catenary of the dodaran-park
seed (L = 100 m, 2.466 kg/m in air, EA = 6.283e7 N, B at (92.5, -8.6) m from A).

Reference: Irvine's two closure equations solved with mpmath at 40 significant digits
(independent of the float code). Error: largest end-force component error relative to
the end tension. Peer: MoorPy's catenary (optional extra `peers`) at several Tol.
"""

from __future__ import annotations

import numpy as np

from cablestudy.bench import WorkPrecision, median_time

L, MASS, G, EA = 100.0, 2.466, 9.80665, 6.283e7
SPAN, RISE = 92.5, -8.6
W = MASS * G  # air buoyancy ignored in the reference and in every method alike


def reference() -> np.ndarray:
    """(H, V_A, V_B) from Irvine's equations at 40 digits."""
    import mpmath as mp

    mp.mp.dps = 40
    l, h, Lm, w, ea = (mp.mpf(v) for v in (SPAN, RISE, L, W, EA))

    def eqs(H, VA):  # noqa: ANN001, ANN202
        VB = VA + w * Lm
        x = H * Lm / ea + H / w * (mp.asinh(VB / H) - mp.asinh(VA / H))
        z = (VA * Lm + w * Lm**2 / 2) / ea + (mp.sqrt(H**2 + VB**2) - mp.sqrt(H**2 + VA**2)) / w
        return [x - l, z - h]

    H, VA = mp.findroot(eqs, (mp.mpf(1600), mp.mpf(-1300)))
    return np.array([float(H), float(VA), float(VA + w * Lm)])


def run(quick: bool = False) -> WorkPrecision:
    from cablestudy.statics.elastic_catenary import solve_between

    ref = reference()
    tension = float(np.hypot(ref[0], ref[1]))
    wp = WorkPrecision(
        name="static_catenary",
        title="Static catenary (dodaran Fig. 4): end-force error vs time",
        error_name="max end-force error / end tension [-]",
    )
    s = np.linspace(0.0, L, 101)
    repeats = 3 if quick else 7

    def err_of(fa: np.ndarray, fb: np.ndarray) -> float:
        got = np.array([np.hypot(fa[0], fa[1]), fa[2], -fb[2]])
        return float(np.max(np.abs(got - ref)) / tension)

    c = wp.curve("cablestudy analytic (Irvine, Newton)")
    for tol in (1e-4, 1e-8, 1e-12):
        r = solve_between((0, 0, 0), (SPAN, 0, RISE), L, W, EA, s, tolerance=tol)
        c.add(f"tol={tol:g}", median_time(
            lambda tol=tol: solve_between((0, 0, 0), (SPAN, 0, RISE), L, W, EA, s,
                                          tolerance=tol), repeats=repeats),
            err_of(r.force_a, r.force_b))
    try:
        from moorpy.Catenary import catenary
    except ImportError:
        wp.notes.append("MoorPy not installed (pip install '.[peers]'): peer skipped")
        return wp
    p = wp.curve("MoorPy catenary", peer=True)
    for tol in (1e-4, 1e-6, 1e-9):
        fAH, fAV, fBH, fBV, _ = catenary(SPAN, RISE, L, EA, W, CB=-1e3, Tol=tol, MaxIter=200)
        # MoorPy returns (fAH, fAV, fBH, fBV) of the line's end forces, positive up:
        # in our tension-vector terms (H, V_A, V_B) = (fAH, fAV, -fBV)
        err = float(np.max(np.abs(np.array([fAH, fAV, -fBV]) - ref)) / tension)
        p.add(f"Tol={tol:g}", median_time(
            lambda tol=tol: catenary(SPAN, RISE, L, EA, W, CB=-1e3, Tol=tol, MaxIter=200),
            repeats=repeats), err)
    return wp
