"""What a person reads off the operator's view: the scene's pixels, never its messages.

The AR layers' labels are drawn by WebGL, not the page's text, so they are read as a person reads
them: from a screenshot of the scene, beside the bar they belong to (the label sits left of its
bar), with Tesseract OCR. Where things are, as a person sees them: the bowl by its yellow, the
target circle by its black ring on the table. A scripted participant (issue 44) is to decide its
moves from these alone.

Needs Tesseract (Debian: ``apt-get install tesseract-ocr``) and pytesseract (the ``test`` extra).
"""

from __future__ import annotations

import re
import shutil
from dataclasses import dataclass

import cv2
import numpy as np
from numpy.typing import NDArray

from arteleop.ar_features.layers.colors import DISTANCE_RGB, GRIP_RGB
from arteleop.errors import ArteleopError

OCR_SCALE = 3
"""The labels' text is about 12 px high: Tesseract reads it best three times larger."""
INK = 140
"""A label's text is darker than this (0-255), its white box and the grey table lighter."""
DOMINANCE = 35
"""A pixel is of a bar's hue where its strongest channel beats the others by this (0-255): the
bars are shaded and translucent, their exact colour is nowhere on the screen."""
LABEL_WIDTH_PX = 110
"""Room left of a bar for its label (CSS px): "grip 100 %" at the labels' size."""
LABEL_HEIGHT_PX = 24


class ScreenReadingError(ArteleopError):
    """Tesseract is missing: the scripted participant cannot read."""


def require_tesseract() -> None:
    """Skip the calling test without Tesseract; fail it under CI, which installs it."""
    from tests.helpers import unavailable

    if shutil.which("tesseract") is None:
        unavailable(
            ScreenReadingError(
                "Tesseract is not installed: install it with 'apt-get install tesseract-ocr'."
            )
        )


def of_hue(rgb: NDArray[np.uint8], hue_rgb: tuple[int, int, int]) -> NDArray[np.bool_]:
    """Mask of the pixels whose strongest channel is ``hue_rgb``'s, beating the others by
    :data:`DOMINANCE` (the AR cues' green, blue, and the gizmo's)."""
    c = rgb.astype(np.int16)
    k = int(np.argmax(hue_rgb))
    return c[..., k] - np.max(np.delete(c, k, axis=-1), axis=-1) > DOMINANCE


def _components(mask: NDArray[np.uint8]) -> list[tuple[int, int, int, int, int]]:
    """Connected components of ``mask``: (x, y, width, height, area) in px."""
    n, _, stats, _ = cv2.connectedComponentsWithStats(mask)
    return [tuple(int(v) for v in stats[i]) for i in range(1, n)]  # type: ignore[misc]


def bar_box(rgb: NDArray[np.uint8], hue_rgb: tuple[int, int, int]) -> tuple[int, ...] | None:
    """The bar of ``hue_rgb``: the widest flat component of its hue (x, y, width, height in px),
    or None if none is drawn (the target mesh, of the same green, is not flat)."""
    parts = _components(of_hue(rgb, hue_rgb).astype(np.uint8))
    flat = [b for b in parts if b[2] > 3 * b[3] and b[3] >= 3]
    return max(flat, key=lambda b: b[2])[:4] if flat else None


def ocr_line(rgb: NDArray[np.uint8]) -> str:
    """One line of dark text in ``rgb`` (a label and what lies around it), spaces dropped;
    empty where there is no text."""
    import pytesseract

    c = rgb.astype(np.int16)
    gray = cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY)
    gray[c.max(axis=-1) - c.min(axis=-1) > 60] = 255  # a cue's colour (the beam) is no text
    ys, xs = np.nonzero(gray < INK)
    if ys.size == 0:
        return ""
    text = gray[max(ys.min() - 2, 0) : ys.max() + 3, max(xs.min() - 2, 0) : xs.max() + 3]
    big = cv2.resize(text, None, fx=OCR_SCALE, fy=OCR_SCALE, interpolation=cv2.INTER_CUBIC)
    big = np.where(big < INK, 0, 255).astype(np.uint8)
    big = cv2.copyMakeBorder(big, 20, 20, 20, 20, cv2.BORDER_CONSTANT, value=255)
    config = "--psm 7 -c tessedit_char_whitelist=0123456789gimpr%"
    return re.sub(r"\s", "", pytesseract.image_to_string(big, config=config))


def label_left_of(rgb: NDArray[np.uint8], box: tuple[int, ...]) -> str:
    """The text of the label drawn left of the bar in ``box``."""
    x, y, _, h = box
    top = max(y + h // 2 - LABEL_HEIGHT_PX // 2, 0)
    return ocr_line(rgb[top : top + LABEL_HEIGHT_PX, max(x - LABEL_WIDTH_PX, 0) : max(x - 1, 1)])


def distance_mm(rgb: NDArray[np.uint8]) -> int | None:
    """The distance bar's label, "N mm"; None where no bar is drawn or its label is not read."""
    box = bar_box(rgb, DISTANCE_RGB)
    found = box and re.fullmatch(r"(\d+)mm", label_left_of(rgb, box))
    return int(found.group(1)) if found else None


def grip_percent(rgb: NDArray[np.uint8]) -> int | None:
    """The grip bar's label, "grip N %"; None where no bar is drawn or its label is not read."""
    box = bar_box(rgb, GRIP_RGB)
    found = box and re.fullmatch(r"grip(\d+)%", label_left_of(rgb, box))
    return int(found.group(1)) if found else None


@dataclass(frozen=True)
class Spot:
    """Where something is seen in the scene (CSS px from its top-left corner)."""

    x_px: float
    y_px: float


def bowl_spot(rgb: NDArray[np.uint8]) -> Spot | None:
    """The bowl: the middle of its yellow (red and green over blue); None if not seen."""
    c = rgb.astype(np.int16)
    yellow = (np.minimum(c[..., 0], c[..., 1]) - c[..., 2] > 80).astype(np.uint8)
    parts = [b for b in _components(yellow) if b[4] > 200]
    if not parts:
        return None
    x, y, w, h, _ = max(parts, key=lambda b: b[4])
    return Spot(x + w / 2, y + h / 2)


def target_spot(rgb: NDArray[np.uint8]) -> Spot | None:
    """The target circle on the table: the largest black ring (its middle empty); None if not
    seen. The depth aids' ring, near-black too, is smaller and hangs from its line."""
    black = (rgb.max(axis=-1) < 60).astype(np.uint8)
    rings = [
        b
        for b in _components(black)
        if b[2] > 40 and 0.5 < b[2] / b[3] < 3 and b[4] < 0.4 * b[2] * b[3]
    ]
    if not rings:
        return None
    x, y, w, h, _ = max(rings, key=lambda b: b[2])
    return Spot(x + w / 2, y + h / 2)
