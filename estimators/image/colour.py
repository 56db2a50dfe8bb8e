"""Colour operations of the image trackers: Li et al.'s (2010) colour look-up table and motion
image, Yu et al.'s (2010) hue histogram and back-projection.

Images are ``(H, W, 3)`` ``uint8`` arrays in RGB order. These wrap OpenCV's colour conversions,
histograms and back-projections (the ``pixels`` extra), the one part of :mod:`estimators`
that needs more than numpy; nothing else imports them, so the rest of the package works
without OpenCV.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from .meanshift import RegionImage

try:
    import cv2
except ImportError as err:  # pragma: no cover - depends on the installation
    raise ImportError("estimators.image.colour needs OpenCV; install it with: "
                      "pip install 'soccer-env[pixels]'") from err

__all__ = ["RGB", "ColourTable", "hue_histogram", "back_project", "frame_difference", "grey",
           "difference_image"]

#: A colour ``(r, g, b)``, each 0-255.
RGB = tuple[int, int, int]


def _valid_hue(hsv: np.ndarray, min_saturation: int, min_value: int) -> np.ndarray:
    return cv2.inRange(hsv, (0, min_saturation, min_value), (180, 255, 255))


def hue_histogram(image_patch: np.ndarray, bins: int = 16, mask: np.ndarray | None = None,
                  min_saturation: int = 60, min_value: int = 32) -> np.ndarray:
    """Hue histogram ``(bins,)`` float32 of an RGB patch, scaled to a maximum of 1 (Yu et
    al.'s 2010 target model). Pixels darker than ``min_value`` or less saturated than
    ``min_saturation`` (0-255; OpenCV's CamShift sample uses 60 and 32) have no reliable hue
    and are left out, as are those where ``mask`` (uint8, same size) is 0."""
    if image_patch.ndim != 3 or image_patch.shape[2] != 3 or image_patch.dtype != np.uint8:
        raise ValueError(f"image_patch must be an (h, w, 3) uint8 RGB array, got "
                         f"{image_patch.shape} {image_patch.dtype}")
    if not (isinstance(bins, int) and 1 <= bins <= 180):
        raise ValueError(f"bins must be an integer in [1, 180], got {bins!r}")
    hsv = cv2.cvtColor(image_patch, cv2.COLOR_RGB2HSV)
    valid = _valid_hue(hsv, min_saturation, min_value)
    if mask is not None:
        valid = cv2.bitwise_and(valid, np.asarray(mask, np.uint8))
    hist = cv2.calcHist([hsv], [0], valid, [bins], [0, 180]).reshape(-1)
    peak = float(hist.max())
    return (hist / peak if peak > 0 else hist).astype(np.float32)


def back_project(image: np.ndarray, histogram: np.ndarray, min_saturation: int = 60,
                 min_value: int = 32) -> np.ndarray:
    """Back-projection of a :func:`hue_histogram` on an RGB image: float32 ``(H, W)`` in
    [0, 1], each pixel the histogram's value at its hue (0 where its hue is unreliable, as in
    :func:`hue_histogram`)."""
    hist = np.asarray(histogram, np.float32).reshape(-1)
    if hist.size < 1 or hist.size > 180:
        raise ValueError(f"histogram must have 1-180 bins, got {hist.size}")
    hsv = cv2.cvtColor(image, cv2.COLOR_RGB2HSV)
    scaled = np.clip(hist, 0.0, 1.0) * 255.0
    bp = cv2.calcBackProject([hsv], [0], scaled, [0, 180], scale=1)
    bp = cv2.bitwise_and(bp, _valid_hue(hsv, min_saturation, min_value))
    return bp.astype(np.float32) * (1.0 / 255.0)


def frame_difference(prev: np.ndarray, cur: np.ndarray) -> np.ndarray:
    """Absolute grey-level difference of two RGB (or grey) uint8 frames, float32 in [0, 1]
    (Li et al.'s 2010 motion image)."""
    if prev.shape != cur.shape:
        raise ValueError(f"frames must have the same shape, got {prev.shape} and {cur.shape}")
    return _difference(grey(prev), grey(cur))


def _difference(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``|a - b| / 255`` of grey uint8 images, float32."""
    return cv2.absdiff(a, b).astype(np.float32) * (1.0 / 255.0)


def grey(image: np.ndarray) -> np.ndarray:
    """The grey levels (uint8) of an RGB uint8 frame, as :func:`frame_difference` takes
    them (a grey frame is returned as it is)."""
    return cv2.cvtColor(image, cv2.COLOR_RGB2GRAY) if image.ndim == 3 else image


def difference_image(prev: np.ndarray, cur: np.ndarray, reuse: RegionImage | None = None
                     ) -> RegionImage:
    """:func:`frame_difference` of two grey uint8 frames (:func:`grey`) as a
    :class:`~estimators.image.meanshift.RegionImage`, computed box by box where the trackers
    read it (a box's pixels are the whole difference's: it is per pixel); with ``reuse`` (a
    region image of the same shape that nothing reads any more, e.g. the previous frame's),
    that one :meth:`~estimators.image.meanshift.RegionImage.refill`-ed."""
    if prev.shape != cur.shape or prev.ndim != 2:
        raise ValueError(f"frames must be grey images of one shape, got {prev.shape} and "
                         f"{cur.shape}")

    def fill(x0: int, y0: int, x1: int, y1: int) -> np.ndarray:
        return _difference(prev[y0:y1, x0:x1], cur[y0:y1, x0:x1])

    return _region(cur.shape, fill, reuse)


def _region(shape: tuple[int, ...], fill, reuse: RegionImage | None) -> RegionImage:
    """A :class:`~estimators.image.meanshift.RegionImage` of ``shape`` and ``fill``: ``reuse``
    refilled when it has that shape, else a new one."""
    if reuse is not None and reuse.shape == (int(shape[0]), int(shape[1])):
        return reuse.refill(fill)
    return RegionImage(shape, fill)


def _rgb(image: np.ndarray) -> np.ndarray:
    """``image``, checked to be an ``(H, W, 3)`` uint8 RGB array."""
    if image.ndim != 3 or image.shape[2] != 3 or image.dtype != np.uint8:
        raise ValueError(f"image must be an (H, W, 3) uint8 RGB array, got {image.shape} "
                         f"{image.dtype}")
    return image


def _look_up(image: np.ndarray, hist: np.ndarray) -> np.ndarray:
    """The class probabilities of an RGB uint8 image from a quantised RGB table ``hist``
    (0-255): float32 in [0, 1]."""
    bp = cv2.calcBackProject([image], [0, 1, 2], hist, [0, 256, 0, 256, 0, 256], scale=1)
    return bp.astype(np.float32) * (1.0 / 255.0)


class ColourTable:
    """A colour look-up table (Li et al.'s 2010, built offline): quantised RGB -> class
    probabilities.

    The RGB cube is cut into ``2**bits`` levels per channel. For each cell centre ``x`` and
    class ``c`` of nominal colour ``n_c``, ``d_c`` is the distance from ``x`` to the nearest
    colour ``g n_c`` (saturated at 255) with the lighting gain ``g`` in ``gain_range``, and
    ``w_c = exp(-d_c^2 / (2 tolerance^2))``; the probability of class ``c`` is ``w_c /
    max(1, sum_k w_k)``: near 1 at a nominal colour (under any gain of the range), shared where
    classes overlap, near 0 far from every class (lines, robot bodies).

    Args:
        colours: class name -> nominal RGB (the classes, in this order), e.g. the overhead
            camera's :func:`soccer_env.sensors.images.overhead_colour_classes`.
        aliases: other names of classes (``{"ball": "orange"}``) accepted by
            :meth:`probability`.
        tolerance: distance scale [grey levels].
        gain_range: lighting gains the table must cover.
        bits: quantisation (1-8 bits per channel).
    """

    def __init__(self, colours: Mapping[str, RGB], tolerance: float = 30.0,
                 gain_range: tuple[float, float] = (0.75, 1.25), bits: int = 5,
                 aliases: Mapping[str, str] | None = None) -> None:
        if not colours:
            raise ValueError("colours must name at least one class")
        if not (math.isfinite(tolerance) and tolerance > 0.0):
            raise ValueError(f"tolerance must be > 0 grey levels, got {tolerance!r}")
        g0, g1 = gain_range
        if not (0.0 < g0 <= g1 <= 10.0):
            raise ValueError(f"gain_range must be (low, high) with 0 < low <= high <= 10, got "
                             f"{gain_range!r}")
        if not (isinstance(bits, int) and 1 <= bits <= 8):
            raise ValueError(f"bits must be an integer in [1, 8], got {bits!r}")
        self.classes = tuple(colours)
        self.aliases = dict(aliases or {})
        self.colours = {k: tuple(int(c) for c in v) for k, v in colours.items()}
        self.tolerance, self.gain_range, self.bits = float(tolerance), (g0, g1), bits
        n = 1 << bits
        step = 256.0 / n
        centres = (np.arange(n) + 0.5) * step
        grid = np.stack(np.meshgrid(centres, centres, centres, indexing="ij"), axis=-1)
        cells = grid.reshape(-1, 3)
        gains = np.linspace(g0, g1, 17)
        weights = []
        for name in self.classes:
            ref = np.minimum(gains[:, None] * np.array(self.colours[name], float), 255.0)
            d2 = ((cells[:, None, :] - ref[None, :, :]) ** 2).sum(axis=2).min(axis=1)
            weights.append(np.exp(-0.5 * d2 / self.tolerance**2))
        w = np.stack(weights)
        p = w / np.maximum(1.0, w.sum(axis=0))
        #: ``(C, n, n, n)`` float32 probabilities, indexed by class then R, G, B level.
        self.table = p.reshape(len(self.classes), n, n, n).astype(np.float32)
        self._hists = self._histograms()

    def _histograms(self) -> list:
        # cv2.Mat(..., wrap_channels=False): a 3-D histogram, not a 2-D image of 32 channels.
        return [cv2.Mat(np.ascontiguousarray(t * 255.0), wrap_channels=False)
                for t in self.table]

    def __getstate__(self) -> dict:
        # A pickled cv2.Mat comes back as a plain 3-D array that OpenCV reads as an image of
        # many channels: the histograms are rebuilt from the table instead.
        return {k: v for k, v in self.__dict__.items() if k != "_hists"}

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state)
        self._hists = self._histograms()

    def _index(self, cls: str) -> int:
        name = self.aliases.get(cls, cls)
        if name not in self.classes:
            raise ValueError(f"unknown colour class {cls!r}; known: {list(self.classes)}")
        return self.classes.index(name)

    def lookup(self, rgb: Sequence[int]) -> dict[str, float]:
        """Class probabilities of one RGB colour."""
        s = 8 - self.bits
        r, g, b = (int(c) >> s for c in rgb)
        return {c: float(self.table[k, r, g, b]) for k, c in enumerate(self.classes)}

    def probability(self, image: np.ndarray, cls: str) -> np.ndarray:
        """Probability image of class ``cls`` (``"ball"`` means ``"orange"``) for an RGB uint8
        image: float32 ``(H, W)`` in [0, 1] (Li et al.'s 2010 colour image)."""
        return _look_up(_rgb(image), self._hists[self._index(cls)])

    def region_image(self, image: np.ndarray, cls: str, reuse: RegionImage | None = None
                     ) -> RegionImage:
        """:meth:`probability` of ``image`` as a :class:`~estimators.image.meanshift.
        RegionImage`: computed box by box where the trackers read it (a box's pixels are
        the whole image's: the look-up is per pixel); with ``reuse`` (a region image of the
        same shape that nothing reads any more, e.g. the previous frame's), that one
        :meth:`~estimators.image.meanshift.RegionImage.refill`-ed."""
        hist = self._hists[self._index(cls)]
        image = _rgb(image)

        def fill(x0: int, y0: int, x1: int, y1: int) -> np.ndarray:
            return _look_up(np.ascontiguousarray(image[y0:y1, x0:x1]), hist)

        return _region(image.shape[:2], fill, reuse)

    def classify(self, image: np.ndarray, threshold: float = 0.5) -> np.ndarray:
        """Most probable class index per pixel (``int8``), -1 where no class reaches
        ``threshold``."""
        probs = np.stack([self.probability(image, c) for c in self.classes])
        best = probs.argmax(axis=0).astype(np.int8)
        best[probs.max(axis=0) < threshold] = -1
        return best
