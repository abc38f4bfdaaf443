"""The closed-form piece increments (cablestudy.statics.pieces) against direct
quadrature of dr/ds = T (1/EA + 1/|T|), T = T0 - q s, and finite differences."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from cablestudy.statics.pieces import piece_integrals


def _quadrature(T0: np.ndarray, q: np.ndarray, ell: float, EA: float) -> tuple[np.ndarray, float]:
    def tension(s: float) -> np.ndarray:
        return T0 - q * s

    # split the quadrature where the load-parallel tension component changes sign
    w = float(np.linalg.norm(q))
    crossing = -(T0 @ (-q / w)) / w if w > 0.0 else -1.0
    points = [crossing] if 0.0 < crossing < ell else None

    dr = np.array(
        [
            quad(
                lambda s, k=k: (tension(s) * (1.0 / EA + 1.0 / np.linalg.norm(tension(s))))[k],
                0.0,
                ell,
                epsabs=1e-14,
                epsrel=1e-13,
                limit=200,
                points=points,
            )[0]
            for k in range(3)
        ]
    )
    energy = quad(
        lambda s: np.linalg.norm(tension(s)) + tension(s) @ tension(s) / (2.0 * EA),
        0.0,
        ell,
        epsabs=1e-14,
        epsrel=1e-13,
        limit=200,
        points=points,
    )[0]
    return dr, energy


CASES = [
    # T0 [N], q [N/m], length [m], EA [N]
    ((100.0, 0.0, -50.0), (0.0, 0.0, -3.0), 40.0, 1e5),  # ordinary sagging piece
    ((100.0, 20.0, 80.0), (0.0, 0.0, -3.0), 40.0, 1e5),  # V keeps its sign
    ((1.0, 0.0, -60.0), (0.0, 0.0, -3.0), 40.0, 1e5),  # nearly vertical, V changes sign
    ((100.0, 0.0, -50.0), (0.0, 0.0, 3.0), 40.0, 1e5),  # buoyant
    ((100.0, 30.0, -50.0), (1e-9, 0.0, -1e-9), 40.0, 1e5),  # nearly weightless
    ((100.0, 30.0, -50.0), (0.0, 0.0, 0.0), 40.0, 1e5),  # weightless: straight
    ((10.0, -30.0, 5.0), (4.0, -2.0, -3.0), 25.0, 1e4),  # oblique load (weight + drag)
    ((2e5, 0.0, 1e3), (0.0, 0.0, -30.0), 10.0, 1e6),  # taut, stretched
]


@pytest.mark.parametrize(("T0", "q", "ell", "EA"), CASES)
def test_increment_and_energy_match_quadrature(T0, q, ell, EA) -> None:  # noqa: ANN001
    T0, q = np.array(T0), np.array(q)
    dr, jac, energy = piece_integrals(T0, q, np.array(ell), np.array(EA))
    dr_q, energy_q = _quadrature(T0, q, ell, EA)
    # quad is asked for 1e-13 relative; the closed forms are exact to round-off
    assert np.max(np.abs(dr - dr_q)) <= 1e-11 * ell
    assert abs(energy - energy_q) <= 1e-11 * abs(energy_q)


@pytest.mark.parametrize(("T0", "q", "ell", "EA"), CASES)
def test_jacobian_is_the_symmetric_derivative_of_the_increment(T0, q, ell, EA) -> None:  # noqa: ANN001
    T0, q = np.array(T0), np.array(q)
    _, jac, _ = piece_integrals(T0, q, np.array(ell), np.array(EA))
    h = 1e-6 * np.linalg.norm(T0)
    fd = np.empty((3, 3))
    grad = np.empty(3)
    for k in range(3):
        d = np.zeros(3)
        d[k] = h
        plus = piece_integrals(T0 + d, q, np.array(ell), np.array(EA))
        minus = piece_integrals(T0 - d, q, np.array(ell), np.array(EA))
        fd[:, k] = (plus[0] - minus[0]) / (2 * h)
        grad[k] = (plus[2] - minus[2]) / (2 * h)
    # central differences: truncation ~ h^2 |d3r|, round-off ~ eps |dr| / h -> ~1e-7 relative
    assert np.max(np.abs(jac - fd)) <= 1e-6 * np.max(np.abs(jac))
    assert np.allclose(jac, np.swapaxes(jac, -1, -2), rtol=0, atol=1e-14 * np.max(np.abs(jac)))
    assert np.min(np.linalg.eigvalsh(jac)) > 0.0  # flexibility is positive definite
    dr, _, _ = piece_integrals(T0, q, np.array(ell), np.array(EA))
    assert np.max(np.abs(grad - dr)) <= 1e-6 * ell  # energy gradient = increment


def test_vectorised_over_pieces_and_zero_length() -> None:
    T0 = np.array([[100.0, 0.0, -50.0], [3.0, 4.0, 0.0]])
    q = np.array([[0.0, 0.0, -3.0], [0.0, 0.0, -3.0]])
    dr, jac, energy = piece_integrals(T0, q, np.array([40.0, 0.0]), np.array([1e5, 1e5]))
    single, _, _ = piece_integrals(T0[0], q[0], np.array(40.0), np.array(1e5))
    assert np.array_equal(dr[0], single)
    assert np.all(dr[1] == 0.0) and energy[1] == 0.0 and np.all(jac[1] == 0.0)


def test_vertical_hanging_piece_with_zero_horizontal_tension() -> None:
    # H = 0 and V from -60 to +60 N: a folded vertical line; reach 0, rise
    # int V/|V| ds = 0 plus elastic part (V0 l + w l^2 / 2) / EA = 0
    dr, jac, _ = piece_integrals(
        np.array([0.0, 0.0, -60.0]), np.array([0.0, 0.0, -3.0]), np.array(40.0), np.array(1e5)
    )
    assert np.all(np.isfinite(dr)) and np.all(np.isfinite(jac))
    assert np.max(np.abs(dr)) <= 1e-13
    # d z / d V0 = l / EA + H^2 int(1/|T|^3) -> l/EA + 2 / w as H -> 0 (fold)
    assert jac[2, 2] == pytest.approx(40.0 / 1e5 + 2.0 / 3.0, rel=1e-12)
