"""A rendered frame's lighting and noise as one compiled pass over its pixels
(:func:`light_and_noise`), which :class:`~soccer_env.sensors.images.common.Photometry`
calls for every camera image.

Per pixel and channel ``v`` (``uint8``): the lit value ``round(v * ramp)`` with
``ramp = (gain + gx x_n) + gy y_n`` in float32 (the product rounded to float32, then to the
nearest integer, half to even), saturated to ``int16`` when noise follows, else to
``0..255``; then the noise sample of the bank window added and the sum saturated to
``0..255``.

Bit for bit with what it replaces (OpenCV's ``multiply`` of the image by the three-channel
float32 ramp into ``CV_16S`` or ``CV_8U``, numpy's ``int16`` add of the noise window and its
clip to ``0..255``): OpenCV converts the ``uint8`` pixel to float32, multiplies in float32
and rounds half to even (``cvRound``), as the kernel does. Why a kernel: those were six
passes over a 640 x 480 x 3 image (the ramp's outer sum, its three-channel merge, the
product, the add, the clip, the cast), each writing a full intermediate image, at about a
quarter of a pixels step.
"""

from __future__ import annotations

import numpy as np

from estimators.compiled import kernel

__all__ = ["light_and_noise"]


#: ``1.5 * 2**23`` (float32): adding and subtracting it rounds a float32 of magnitude below
#: ``2**22`` to the nearest integer, half to even (``cvRound``), in vector registers.
_ROUND = np.float32(12582912.0)
#: The saturation bounds (float32): int16's, and a grey level's.
_INT16_MIN, _INT16_MAX = np.float32(-32768.0), np.float32(32767.0)
_ZERO, _FULL = np.float32(0.0), np.float32(255.0)


@kernel
def light_and_noise(img: np.ndarray, row: np.ndarray, column: np.ndarray, lit: bool,
                    bank: np.ndarray, oy: int, ox: int, noisy: bool, out: np.ndarray
                    ) -> None:
    """Light and noise a frame into ``out``, both ``(H, 3 W)`` ``uint8`` (the ``(H, W, 3)``
    image's rows; channel ``c`` of column ``x`` at ``3 x + c``).

    Args:
        img: the rendered frame.
        row: ``(3 W,)`` float32, ``gain + gx x_n`` per column and channel (the ramp's part
            along x).
        column: ``(H,)`` float32, ``gy y_n`` per row: the ramp is ``row[j] + column[y]``.
        lit: apply the ramp (else the pixels pass as they are).
        bank: ``(rows, 3 columns)`` ``int16`` noise samples, at least ``(oy + H,
            3 (ox + W))``.
        oy: the bank window's first row.
        ox: the bank window's first column (pixels).
        noisy: add the bank window (else no noise: ``bank`` is not read).
        out: where the frame goes.
    """
    # In float32 throughout: every value is an integer below 2**24 after the rounding, so
    # the saturations and the noise's sum are exact (and run in vector registers).
    h, w3 = img.shape[0], img.shape[1]
    j0 = 3 * ox
    for y in range(h):
        cy = column[y]
        src, dst = img[y], out[y]
        if lit and noisy:
            noise = bank[oy + y, j0:j0 + w3]
            for j in range(w3):
                v = ((np.float32(src[j]) * (row[j] + cy)) + _ROUND) - _ROUND
                v = min(max(v, _INT16_MIN), _INT16_MAX) + np.float32(noise[j])
                dst[j] = np.uint8(min(max(v, _ZERO), _FULL))
        elif lit:
            for j in range(w3):
                v = ((np.float32(src[j]) * (row[j] + cy)) + _ROUND) - _ROUND
                dst[j] = np.uint8(min(max(v, _ZERO), _FULL))
        elif noisy:
            noise = bank[oy + y, j0:j0 + w3]
            for j in range(w3):
                v = np.float32(src[j]) + np.float32(noise[j])
                dst[j] = np.uint8(min(max(v, _ZERO), _FULL))
        else:  # a loop, not a slice assignment, which costs seconds to compile
            for j in range(w3):
                dst[j] = src[j]
