"""The frames' lighting and noise kernel (soccer_env.sensors.images.photometry_kernels)
against the OpenCV and numpy operations it replaces, to the bit."""

import math

import numpy as np
import pytest

pytest.importorskip("cv2", reason="the reference uses OpenCV (the 'pixels' extra)")

import cv2

from soccer_env.sensors.images.common import Photometry


def _reference(ph: Photometry, img: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """The photometry as OpenCV's multiply and numpy's add computed it."""
    z = float(rng.standard_normal())
    a_u, phi_u = rng.random(2).tolist()
    oy, ox = rng.integers(0, (ph.height + 1, ph.width + 1)).tolist()
    out = img
    if ph.gain_sigma > 0.0 or ph.gradient > 0.0:
        gain = min(2.0, max(0.3, 1.0 + ph.gain_sigma * z))
        a = ph.gradient * a_u
        phi = 2.0 * math.pi * phi_u
        gx, gy = gain * a * math.cos(phi), gain * a * math.sin(phi)
        xn = np.linspace(-1.0, 1.0, ph.width, dtype=np.float32)
        yn = np.linspace(-1.0, 1.0, ph.height, dtype=np.float32)
        ramp = (gain + gx * xn)[None, :] + (gy * yn)[:, None]
        dtype = cv2.CV_16S if ph.noise_sigma > 0.0 else cv2.CV_8U
        out = cv2.multiply(img, cv2.merge([ramp, ramp, ramp]), dtype=dtype)
    if ph.noise_sigma > 0.0:
        bank = np.rint(ph.noise_sigma * np.random.default_rng(0x5EED).standard_normal(
            (2 * ph.height, 2 * ph.width, 3), dtype=np.float32)).astype(np.int16)
        out = np.add(out, bank[oy:oy + ph.height, ox:ox + ph.width], dtype=np.int16)
        np.clip(out, 0, 255, out=out)
        out = out.astype(np.uint8)
    return out


@pytest.mark.parametrize("gain_sigma, gradient, noise_sigma",
                         [(0.1, 0.2, 3.0), (0.0, 0.0, 4.0), (0.2, 0.3, 0.0), (0.5, 0.5, 8.0)])
def test_photometry_equals_opencv_and_numpy(gain_sigma, gradient, noise_sigma):
    ph = Photometry(96, 64, gain_sigma, gradient, noise_sigma)
    images = np.random.default_rng(3)
    for seed in range(8):
        img = images.integers(0, 256, (64, 96, 3), dtype=np.uint8)
        img[:20] = 250  # saturates under a gain above 1
        got = ph.apply(img, np.random.default_rng(seed))
        want = _reference(ph, img, np.random.default_rng(seed))
        assert got.dtype == np.uint8 and np.array_equal(got, want)
