"""What a person reads off the operator's view: the scene's pixels, never its messages.

The AR layers' labels are drawn by WebGL, not the page's text, so they are read as a person reads
them: from a screenshot of the scene, each white box of dark text, with Tesseract OCR; what it
says tells which label it is. Where things are, as a person sees them: the bowl by its yellow, the
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

from arteleop.errors import ArteleopError

OCR_SCALE = (3, 4)
"""The labels' text is about 12 px high: Tesseract reads it best three times larger, and a line
read there without a digit is read again four times larger (a lone "0" in "grip 0 %" was
dropped at three)."""
INK = 140
"""A label's text is darker than this (0-255) at its strokes' middle, its white box and the grey
table lighter."""
DOMINANCE = 35
"""A pixel is of a cue's hue where its strongest channel beats the others by this (0-255): the
bars are shaded and translucent, their exact colour is nowhere on the screen."""
LINE_MIN_HEIGHT_PX = 8
LINE_MAX_HEIGHT_PX = 24
LINE_MAX_WIDTH_PX = 160
"""A label's line of text is this tall and wide (CSS px): "0 mm" to "height 1000 mm" at the
labels' size; the target circle's ring is taller."""
LETTERS = "eghimprt%"
"""What the labels hold besides digits: "mm", "grip N %", "height"."""


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


def gizmo_red(rgb: NDArray[np.uint8]) -> NDArray[np.bool_]:
    """Mask of the gizmo's red handle: a pink the cloud's shaded red never reaches (the
    software-WebGL notice's orange has less blue than green)."""
    c = rgb.astype(np.int16)
    return (c[..., 0] - np.max(c[..., 1:], axis=-1) > 120) & (c[..., 2] > c[..., 1])


@dataclass(frozen=True)
class Spot:
    """Where something is seen in the scene (CSS px from its top-left corner)."""

    x_px: float
    y_px: float


@dataclass(frozen=True)
class Box(Spot):
    """Something seen: its middle, and its width and height (CSS px)."""

    width_px: float
    height_px: float


def _components(mask: NDArray[np.uint8]) -> list[tuple[int, int, int, int, int]]:
    """Connected components of ``mask``: (x, y, width, height, area) in px."""
    n, _, stats, _ = cv2.connectedComponentsWithStats(mask)
    return [tuple(int(v) for v in stats[i]) for i in range(1, n)]  # type: ignore[misc]


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
    config = f"--psm 7 -c tessedit_char_whitelist=0123456789{LETTERS}"
    read = ""
    for scale in OCR_SCALE:
        big = cv2.resize(text, None, fx=scale, fy=scale, interpolation=cv2.INTER_CUBIC)
        # Otsu's split between ink and box: a fixed one lost a thin "0" or "i" of the grey text.
        _, big = cv2.threshold(big, 0, 255, cv2.THRESH_BINARY + cv2.THRESH_OTSU)
        big = cv2.copyMakeBorder(big, 20, 20, 20, 20, cv2.BORDER_CONSTANT, value=255)
        read = re.sub(r"\s", "", pytesseract.image_to_string(big, config=config))
        if re.search(r"\d", read):
            break
    return read


def label_lines(rgb: NDArray[np.uint8]) -> list[tuple[int, int, int, int]]:
    """Where lines of the labels' text may be (x, y, width, height in px): runs of dark grey
    ink of a line's height, as a person finds them, wherever their bars are (a bar inside the
    bowl's cloud is hidden by it, its label is not; the beam may cross a label)."""
    c = rgb.astype(np.int16)
    ink = (c.max(axis=-1) < INK) & (c.max(axis=-1) - c.min(axis=-1) <= 40)
    # Closed along the rows, a line's glyphs and the spaces between its words are one.
    words = cv2.morphologyEx(ink.astype(np.uint8), cv2.MORPH_CLOSE, np.ones((1, 9), np.uint8))
    return [
        (max(x - 3, 0), max(y - 3, 0), w + 6, h + 6)
        for x, y, w, h, _ in _components(words)
        if LINE_MIN_HEIGHT_PX <= h <= LINE_MAX_HEIGHT_PX and 2 * h <= w <= LINE_MAX_WIDTH_PX
    ]


def find_label(rgb: NDArray[np.uint8], pattern: str) -> tuple[int, Box] | None:
    """The number of the first label whose text (spaces dropped) is ``pattern``, a regular
    expression with one group of digits, and where its line of text is; None where none reads
    so."""
    for x, y, w, h in label_lines(rgb):
        found = re.fullmatch(pattern, ocr_line(rgb[y : y + h, x : x + w]))
        if found:
            return int(found.group(1)), Box(x + w / 2, y + h / 2, w, h)
    return None


def read_label(rgb: NDArray[np.uint8], pattern: str) -> int | None:
    """The number of :func:`find_label`'s label."""
    found = find_label(rgb, pattern)
    return None if found is None else found[0]


DISTANCE = r"(\d+)mm"
"""The distance bar's label, "N mm"."""


def distance_mm(rgb: NDArray[np.uint8]) -> int | None:
    """The distance bar's label, "N mm"; None where it is not drawn or not read."""
    return read_label(rgb, DISTANCE)


def grip_percent(rgb: NDArray[np.uint8]) -> int | None:
    """The grip bar's label, "grip N %"; None where it is not drawn or not read."""
    return read_label(rgb, r"grip(\d+)%")


def height_mm(rgb: NDArray[np.uint8]) -> int | None:
    """The depth aids' label, "height N mm"; None where it is not drawn or not read."""
    return read_label(rgb, r"height(\d+)mm")


def bowl_box(rgb: NDArray[np.uint8]) -> Box | None:
    """The bowl: its largest yellow part (red and green over blue); None if not seen."""
    c = rgb.astype(np.int16)
    yellow = (np.minimum(c[..., 0], c[..., 1]) - c[..., 2] > 80).astype(np.uint8)
    return _largest([b for b in _components(yellow) if b[4] > 200], by=4)


def bowl_spot(rgb: NDArray[np.uint8]) -> Spot | None:
    """The middle of :func:`bowl_box`."""
    return _middle(bowl_box(rgb))


RING_SHARE_MIN = 0.8
"""A black part is a ring if this share of its pixels lies near the ellipse its box holds: the
target circle's 0.97, the depth aids' small ring with the line it hangs from 0.45 (together as
wide as the target circle, read for it once in a clean CI run)."""


_CLOSE_GAPS = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (7, 7))


def target_ring(rgb: NDArray[np.uint8]) -> Box | None:
    """The target circle on the table: the largest black ring (its middle empty); None if not
    seen."""
    black = (rgb.max(axis=-1) < 60).astype(np.uint8)
    # The cloud's points leave gaps in the drawn circle, which broke it in two parts.
    black = cv2.morphologyEx(black, cv2.MORPH_CLOSE, _CLOSE_GAPS)
    n, labels, stats, _ = cv2.connectedComponentsWithStats(black)
    rings = []
    for i in range(1, n):
        x, y, w, h, area = (int(v) for v in stats[i])
        if w > 40 and 0.5 < w / h < 3 and area < 0.4 * w * h:
            ys, xs = np.nonzero(labels[y : y + h, x : x + w] == i)
            r = np.hypot((xs + 0.5) / (w / 2) - 1, (ys + 0.5) / (h / 2) - 1)
            if np.mean((r > 0.7) & (r < 1.15)) >= RING_SHARE_MIN:
                rings.append((x, y, w, h, area))
    return _largest(rings, by=2)


def target_mesh_box(rgb: NDArray[np.uint8]) -> Box | None:
    """The task layer's bowl at the target: its largest green part about as wide as tall (the
    distance bar is long and thin, the gizmo's handles small); None where it is not drawn."""
    green = of_hue(rgb, (0, 255, 0)).astype(np.uint8)
    return _largest(
        [b for b in _components(green) if b[2] > 40 and 0.5 < b[2] / b[3] < 2 and b[4] > 500],
        by=4,
    )


def target_box(rgb: NDArray[np.uint8]) -> Box | None:
    """Where the bowl must go, as the page shows it: the task layer's bowl where it is drawn
    (over the target circle, which it hides), else the target circle."""
    return target_mesh_box(rgb) or target_ring(rgb)


def target_spot(rgb: NDArray[np.uint8]) -> Spot | None:
    """Where :func:`target_ring` is seen."""
    return _middle(target_ring(rgb))


def _largest(parts: list[tuple[int, int, int, int, int]], by: int) -> Box | None:
    """The part (x, y, width, height, area) largest in its entry ``by``; None if none."""
    if not parts:
        return None
    x, y, w, h, _ = max(parts, key=lambda b: b[by])
    return Box(x + w / 2, y + h / 2, w, h)


def _middle(box: Box | None) -> Spot | None:
    return None if box is None else Spot(box.x_px, box.y_px)


def _black(rgb: NDArray[np.uint8]) -> NDArray[np.uint8]:
    """The near-black pixels: the markers on the table."""
    return (rgb.max(axis=-1) < 60).astype(np.uint8)


_CLOSE_MARKER_GAPS = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (9, 9))
"""The pointing markers' gaps closed: a cross 0.4 m off, its arms drawn by fewer points, came
apart at the 7 px the target circle's gaps take (its broken arm, empty at its box's middle, was
taken for the circle)."""


def _marker(rgb: NDArray[np.uint8], fill: tuple[float, float], middle: bool) -> Spot | None:
    """The largest black part on the table about as wide as tall, at least 20 px, filling
    between ``fill``'s shares of its box, black at its middle or not (``middle``)."""
    black = cv2.morphologyEx(_black(rgb), cv2.MORPH_CLOSE, _CLOSE_MARKER_GAPS)
    n, labels, stats, _ = cv2.connectedComponentsWithStats(black)
    found = []
    for i in range(1, n):
        x, y, w, h, area = (int(v) for v in stats[i])
        if w >= 20 and h >= 20 and 0.5 < w / h < 2 and fill[0] < area / (w * h) < fill[1]:
            cx, cy = x + w // 2, y + h // 2
            if (np.mean(labels[cy - 3 : cy + 4, cx - 3 : cx + 4] == i) >= 0.8) == middle:
                found.append((x, y, w, h, area))
    return _middle(_largest(found, by=4))


CROSS_FILL = 0.45
"""The start cross fills at most this share of its box (0.26-0.33 seen); a pointing target's
circle, its line a quarter of its diameter wide, more (0.49-0.55), and at most 0.7."""


def cross_spot(rgb: NDArray[np.uint8]) -> Spot | None:
    """The start cross on the table: sparse, black where its arms cross; None if not seen."""
    return _marker(rgb, (0.0, CROSS_FILL), middle=True)


def circle_spot(rgb: NDArray[np.uint8]) -> Spot | None:
    """A pointing target's circle, its line a quarter of its diameter wide (thicker than the
    pick-and-place target's, :func:`target_ring`): empty at its middle; None if not seen."""
    return _marker(rgb, (CROSS_FILL, 0.7), middle=False)


MAGENTA_RED_BLUE = 70
"""The depth aids' magenta has its red and blue within this of each other (0-255): blended into
the grey table or a black mark at its edges, it keeps that; the gizmo's pink-red handle,
(249, 45, 104), does not."""


def aids_hue(rgb: NDArray[np.uint8]) -> NDArray[np.bool_]:
    """Mask of the depth aids' magenta: red and blue both over green by :data:`DOMINANCE`, and
    alike (:data:`MAGENTA_RED_BLUE`)."""
    r, g, b = (rgb[..., k].astype(np.int16) for k in range(3))
    return (np.minimum(r, b) - g > DOMINANCE) & (np.abs(r - b) < MAGENTA_RED_BLUE)


FOOT_RADIUS_PX = (5, 14)
"""The depth aids' ring's radius in the scene at 1280x800 (px)."""
FOOT_SEEN_SHARE = 0.5
"""A circle is the ring if this share of its rim is of the aids' hue: the gripper's fingers,
held low, hide part of it."""


def foot_spot(rgb: NDArray[np.uint8]) -> Spot | None:
    """The middle of the depth aids' ring on the table, under the gripper: the circle of its
    size its hue draws (the drop line, which ends at its middle, draws none); None if not seen."""
    mask = aids_hue(rgb).astype(np.uint8)
    found = cv2.HoughCircles(cv2.GaussianBlur(255 * mask, (5, 5), 1.5), cv2.HOUGH_GRADIENT,
                             dp=1, minDist=100, param1=100, param2=12,
                             minRadius=FOOT_RADIUS_PX[0], maxRadius=FOOT_RADIUS_PX[1])  # fmt: skip
    if found is None:
        return None
    x, y, r = found[0][0]
    near = cv2.dilate(mask, np.ones((5, 5), np.uint8))
    angles = np.linspace(0.0, 2 * np.pi, 48, endpoint=False)
    u = np.clip(np.round(x + r * np.cos(angles)).astype(int), 0, mask.shape[1] - 1)
    v = np.clip(np.round(y + r * np.sin(angles)).astype(int), 0, mask.shape[0] - 1)
    return Spot(float(x), float(y)) if near[v, u].mean() >= FOOT_SEEN_SHARE else None
