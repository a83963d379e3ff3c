"""The one time scheme: generalized-alpha and its Bossak case, checked on one oscillator.

For M a + K u = 0 the scheme's step maps (u, v dt, a dt^2) linearly; the spectral radius of that
amplification matrix as omega dt -> infinity is the damping rho_inf each constructor promises
(Chung and Hulbert 1993, J. Appl. Mech. 60, 371-375, eqs. 25-27; Wood, Bossak and Zienkiewicz
1980, Int. J. Numer. Meth. Eng. 15, 1562-1566), and at small omega dt the phase error is
second order.
"""

import numpy as np
import pytest

from shtaerman.fem.stepper import TimeScheme


def _amplification(scheme: TimeScheme, omega_dt: float) -> np.ndarray:
    """The matrix A with (u, v dt, a dt^2)_{n+1} = A (u, v dt, a dt^2)_n for a'' = -omega^2 u."""
    am, af, beta, gamma = scheme.alpha_m, scheme.alpha_f, scheme.beta, scheme.gamma
    w2 = omega_dt**2
    # rows: equation of motion at the alpha points, Newmark's u and v updates
    left = np.array([[(1 - af) * w2, 0.0, 1 - am], [1.0, 0.0, -beta], [0.0, 1.0, -gamma]])
    right = np.array([[-af * w2, 0.0, -am], [1.0, 1.0, 0.5 - beta], [0.0, 1.0, 1 - gamma]])
    return np.linalg.solve(left, right)


def _spectral_radius(matrix: np.ndarray) -> float:
    return float(np.max(np.abs(np.linalg.eigvals(matrix))))


@pytest.mark.parametrize("rho", [0.0, 0.5, 0.9, 1.0])
@pytest.mark.parametrize("make", [TimeScheme.generalized_alpha, TimeScheme.bossak])
def test_high_frequencies_are_damped_to_the_asked_spectral_radius(make, rho):
    radius = _spectral_radius(_amplification(make(rho, 1.0), 1e6))
    # the limit omega dt -> inf is reached to O(1/(omega dt)^2) = 1e-12; at rho = 0 the root
    # is a defective triple one, whose eigenvalues move by the cube root of that, 1e-4
    assert radius == pytest.approx(rho, abs=2e-4)


@pytest.mark.parametrize("make", [TimeScheme.generalized_alpha, TimeScheme.bossak])
def test_the_schemes_are_second_order(make):
    errors = []
    for omega_dt in (0.02, 0.01):
        eigenvalues = np.linalg.eigvals(_amplification(make(0.8, 1.0), omega_dt))
        principal = eigenvalues[np.argmax(np.abs(eigenvalues.imag))]
        errors.append(abs(np.angle(principal) - omega_dt))  # phase error per step
    # the relative phase error is O(omega dt^2): per step O(omega dt^3), ratio 8 on halving
    assert errors[0] / errors[1] == pytest.approx(8.0, rel=0.05)


def test_bossak_at_rho_one_is_the_trapezoidal_rule():
    newmark, bossak = TimeScheme.generalized_alpha(None, 0.1), TimeScheme.bossak(1.0, 0.1)
    assert bossak == newmark  # exact: alpha_m = 0, beta = 1/4, gamma = 1/2 in binary
