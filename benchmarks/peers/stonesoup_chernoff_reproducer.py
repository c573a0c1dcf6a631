"""Stone Soup's ChernoffUpdater: its innovation covariance pairs the weights the other way round.

Standalone (numpy and Stone Soup only; nothing from fusion-book). Run in a side environment:

    python -m venv /tmp/peers && /tmp/peers/bin/pip install stonesoup
    /tmp/peers/bin/python benchmarks/peers/stonesoup_chernoff_reproducer.py

For the measurement (a, A) and the prediction (b, B), ChernoffUpdater.update fuses with the
measurement's weight omega: D = (omega A^-1 + (1 - omega) B^-1)^-1. The normaliser of that update,
Z(a) = integral of N(x; a, A)^omega N(x; b, B)^(1 - omega) dx, is a Gaussian in the innovation a - b
with covariance V = A/omega + B/(1 - omega). predict_measurement returns A/(1 - omega) + B/omega instead.
This script computes V three ways (closed form; minus the inverse Hessian of log Z of Stone Soup's own
update, by finite differences in a; the corrected updater below) and prints them beside Stone Soup's.
"""

from __future__ import annotations

import numpy as np
import stonesoup
from stonesoup.models.measurement.linear import LinearGaussian
from stonesoup.types.detection import GaussianDetection
from stonesoup.types.hypothesis import SingleHypothesis
from stonesoup.types.prediction import GaussianStatePrediction
from stonesoup.updater.chernoff import ChernoffUpdater

A = np.array([[2.0, 0.3], [0.3, 1.0]])    # measurement covariance (also the model's noise covariance)
B = np.array([[1.0, -0.2], [-0.2, 3.0]])  # prediction covariance
a = np.array([1.0, 2.0])                  # measurement mean
b = np.array([0.5, -1.0])                 # prediction mean
MODEL = LinearGaussian(ndim_state=2, mapping=(0, 1), noise_covar=A)


def stonesoup_update(updater: ChernoffUpdater, meas: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Stone Soup's posterior (d, D) for the measurement mean ``meas``."""
    pred = GaussianStatePrediction(b[:, None], B)
    det = GaussianDetection(meas[:, None], A, measurement_model=MODEL)
    post = updater.update(SingleHypothesis(pred, det))
    return np.asarray(post.state_vector, float).ravel(), np.asarray(post.covar, float)


def log_normaliser(meas: np.ndarray, w: float, d: np.ndarray, D: np.ndarray) -> float:
    """log of the integral of N(x; meas, A)^w N(x; b, B)^(1-w), written with the update's own (d, D).

    N(x; m, P)^w = (2 pi)^(-w n/2) |P|^(-w/2) exp(-w/2 (x-m)' P^-1 (x-m)); completing the square with
    D^-1 = w A^-1 + (1-w) B^-1 and D^-1 d = w A^-1 meas + (1-w) B^-1 b leaves a Gaussian integral.
    """
    Ai, Bi, Di = np.linalg.inv(A), np.linalg.inv(B), np.linalg.inv(D)
    quad = w * meas @ Ai @ meas + (1 - w) * b @ Bi @ b - d @ Di @ d
    logdets = w * np.linalg.slogdet(2 * np.pi * A)[1] + (1 - w) * np.linalg.slogdet(2 * np.pi * B)[1]
    return 0.5 * (np.linalg.slogdet(2 * np.pi * D)[1] - logdets - quad)


def curvature_covariance(w: float, h: float = 1e-3) -> np.ndarray:
    """-(d2 log Z / d a2)^-1 from Stone Soup's own update (central differences; log Z is quadratic in a)."""
    up = ChernoffUpdater(measurement_model=MODEL, omega=w)

    def f(m: np.ndarray) -> float:
        d, D = stonesoup_update(up, m)
        return log_normaliser(m, w, d, D)

    n = a.size
    H = np.empty((n, n))
    E = np.eye(n) * h
    for i in range(n):
        for j in range(n):
            H[i, j] = (f(a + E[i] + E[j]) - f(a + E[i] - E[j]) - f(a - E[i] + E[j]) + f(a - E[i] - E[j])) / (4 * h * h)
    return np.linalg.inv(-(H + H.T) / 2)


class PatchedChernoffUpdater(ChernoffUpdater):
    """The proposed fix: the measurement's weight omega divides the measurement's covariance."""

    def predict_measurement(self, predicted_state, measurement_model=None, measurement_noise=True, **kwargs):
        mp = super().predict_measurement(predicted_state, measurement_model, measurement_noise=False, **kwargs)
        if measurement_noise:
            measurement_model = self._check_measurement_model(measurement_model)
            mp.covar = measurement_model.noise_covar / self.omega + predicted_state.covar / (1 - self.omega)
        return mp


def rel(x: np.ndarray, y: np.ndarray) -> float:
    return float(np.linalg.norm(x - y) / np.linalg.norm(y))


def main() -> None:
    np.set_printoptions(precision=6, suppress=True)
    print(f"stonesoup {stonesoup.__version__}, numpy {np.__version__}")
    print(f"measurement a = {a}, A =\n{A}\nprediction  b = {b}, B =\n{B}\n")
    pred = GaussianStatePrediction(b[:, None], B)
    for w in (0.2, 0.5, 0.8):
        up = ChernoffUpdater(measurement_model=MODEL, omega=w)
        actual = np.asarray(up.predict_measurement(pred, measurement_model=MODEL).covar, float)
        expected = A / w + B / (1 - w)
        curv = curvature_covariance(w)
        fixed = np.asarray(PatchedChernoffUpdater(measurement_model=MODEL, omega=w)
                           .predict_measurement(pred, measurement_model=MODEL).covar, float)
        d, D = stonesoup_update(up, a)
        Di = w * np.linalg.inv(A) + (1 - w) * np.linalg.inv(B)
        print(f"omega = {w} (weight of the measurement in update(): D^-1 = omega A^-1 + (1-omega) B^-1; "
              f"Stone Soup's D matches to {rel(np.linalg.inv(D), Di):.1e})")
        print(f"  actual   predict_measurement().covar = A/(1-w) + B/w:\n{actual}")
        print(f"  expected A/w + B/(1-w):\n{expected}")
        print(f"  -(Hessian of log Z of its own update)^-1 (finite differences):\n{curv}")
        print(f"  relative difference actual vs expected  ||.||_F = {rel(actual, expected):.3f}")
        print(f"  relative difference curvature vs expected       = {rel(curv, expected):.1e}")
        print(f"  relative difference patched vs expected         = {rel(fixed, expected):.1e}\n")


if __name__ == "__main__":
    main()
