"""Single image degradations a camera brings and a renderer does not: colour casts,
tone curves, another wall, camera roll and tilt, framing, motion blur, occluders.

Each function takes and returns a BGR uint8 image and is deterministic given its
arguments (randomness comes in through an explicit numpy Generator). Geometric ones
fill uncovered corners by replicating the border, as a wider real view would show
more wall and floor.
"""

from __future__ import annotations

import cv2
import numpy as np

WALL_MATCH = 40.0  # RGB distance within which a pixel counts as (partly) wall


def hue_shift(image: np.ndarray, degrees: float) -> np.ndarray:
    """Every colour's hue turned by `degrees` (saturation and value kept)."""
    hsv = cv2.cvtColor(image, cv2.COLOR_BGR2HSV_FULL)
    shift = int(round(degrees / 360.0 * 256)) % 256
    hsv[..., 0] = ((hsv[..., 0].astype(np.int32) + shift) % 256).astype(np.uint8)
    return np.asarray(cv2.cvtColor(hsv, cv2.COLOR_HSV2BGR_FULL))


def gamma(image: np.ndarray, exponent: float) -> np.ndarray:
    """out = 255 * (in / 255) ** exponent (>1 darkens mid-tones, <1 brightens)."""
    lut = np.clip(255.0 * (np.arange(256) / 255.0) ** exponent + 0.5, 0, 255).astype(np.uint8)
    return np.asarray(cv2.LUT(image, lut))


def white_balance(image: np.ndarray, gains: tuple[float, float, float]) -> np.ndarray:
    """Per-channel gains (B, G, R): a colour cast such as a warm lamp."""
    out = image.astype(np.float32) * np.array(gains, dtype=np.float32)
    return np.clip(out + 0.5, 0, 255).astype(np.uint8)


def recolour(image: np.ndarray, old: tuple[int, int, int], new: tuple[int, int, int]
             ) -> np.ndarray:
    """Pixels of colour `old` (the wall) repainted `new`; anti-aliased edges that are
    partly `old` move partly, so outlines stay as drawn."""
    diff = image.astype(np.float32) - np.array(old, dtype=np.float32)
    weight = np.clip(1.0 - np.linalg.norm(diff, axis=2) / WALL_MATCH, 0.0, 1.0)
    shift = np.array(new, dtype=np.float32) - np.array(old, dtype=np.float32)
    out = image.astype(np.float32) + weight[..., None] * shift
    return np.clip(out + 0.5, 0, 255).astype(np.uint8)


def rotate(image: np.ndarray, degrees: float, scale: float = 1.0) -> np.ndarray:
    """Camera roll (counter-clockwise in the image for positive degrees) and zoom about
    the centre; the frame keeps its size."""
    h, w = image.shape[:2]
    m = cv2.getRotationMatrix2D((w / 2.0, h / 2.0), degrees, scale)
    return np.asarray(cv2.warpAffine(image, m, (w, h), flags=cv2.INTER_LINEAR,
                                      borderMode=cv2.BORDER_REPLICATE))


def rescale(image: np.ndarray, factor: float) -> np.ndarray:
    """The image resized by `factor` (a farther or nearer camera)."""
    h, w = image.shape[:2]
    size = (max(1, round(w * factor)), max(1, round(h * factor)))
    interp = cv2.INTER_AREA if factor < 1 else cv2.INTER_LINEAR
    return np.asarray(cv2.resize(image, size, interpolation=interp))


def content_box(image: np.ndarray, background: list[tuple[int, int, int]]
                ) -> tuple[int, int, int, int]:
    """(x0, y0, x1, y1) around every pixel of a BGR uint8 image unlike all the background
    colours (unlike: some channel differs by more than 12). In uint8 with OpenCV, a
    channel at a time: the robustness sweeps call it on every picture they degrade."""
    h, w = image.shape[:2]
    busy = np.ones((h, w), dtype=bool)
    for colour in background:
        diff = cv2.absdiff(image, np.full_like(image, colour))
        busy &= np.maximum(np.maximum(diff[..., 0], diff[..., 1]), diff[..., 2]) > 12
    rows, cols = np.flatnonzero(busy.any(axis=1)), np.flatnonzero(busy.any(axis=0))
    if len(rows) == 0:
        return 0, 0, w, h
    return int(cols[0]), int(rows[0]), int(cols[-1]) + 1, int(rows[-1]) + 1


def crop_randomly(image: np.ndarray, fraction: float, keep: tuple[int, int, int, int],
         rng: np.random.Generator) -> np.ndarray:
    """Up to `fraction` of each side cut off at random, never into the `keep` box."""
    h, w = image.shape[:2]
    x0, y0, x1, y1 = keep
    left = int(rng.uniform(0, 1) * min(fraction * w, max(0, x0 - 2)))
    right = int(rng.uniform(0, 1) * min(fraction * w, max(0, w - x1 - 2)))
    top = int(rng.uniform(0, 1) * min(fraction * h, max(0, y0 - 2)))
    bottom = int(rng.uniform(0, 1) * min(fraction * h, max(0, h - y1 - 2)))
    return image[top:h - bottom, left:w - right].copy()


def perspective(image: np.ndarray, strength: float, rng: np.random.Generator) -> np.ndarray:
    """A small camera tilt: each corner moved by up to `strength` of the frame size."""
    h, w = image.shape[:2]
    src = np.array([[0, 0], [w, 0], [w, h], [0, h]], dtype=np.float32)
    jitter = rng.uniform(-strength, strength, size=(4, 2)) * np.array([w, h])
    m = cv2.getPerspectiveTransform(src, (src + jitter).astype(np.float32))
    return np.asarray(cv2.warpPerspective(image, m, (w, h), flags=cv2.INTER_LINEAR,
                                          borderMode=cv2.BORDER_REPLICATE))


def motion_blur(image: np.ndarray, length: int, degrees: float) -> np.ndarray:
    """A straight camera shake of `length` pixels at an angle."""
    if length <= 1:
        return image
    kernel = np.zeros((length, length), np.float32)
    kernel[length // 2, :] = 1.0
    m = cv2.getRotationMatrix2D((length / 2 - 0.5, length / 2 - 0.5), degrees, 1.0)
    turned = np.asarray(cv2.warpAffine(kernel, m, (length, length)), dtype=np.float32)
    kernel = turned / np.float32(max(float(turned.sum()), 1e-6))
    return np.asarray(cv2.filter2D(image, -1, kernel, borderType=cv2.BORDER_REPLICATE))


def occlude(image: np.ndarray, width_fraction: float, keep: tuple[int, int, int, int],
            rng: np.random.Generator, colour: tuple[int, int, int] = (118, 118, 118)
            ) -> np.ndarray:
    """A vertical bar (an arm, a pole) of the given share of the width in front of the
    scene, somewhere across the content box, drawn from the top to the bottom."""
    h, w = image.shape[:2]
    bar = max(2, int(round(width_fraction * w)))
    x0, _, x1, _ = keep
    left = int(rng.uniform(x0, max(x0 + 1, x1 - bar)))
    out = image.copy()
    out[:, left:left + bar] = colour
    cv2.line(out, (left, 0), (left, h), (25, 25, 25), 1)
    cv2.line(out, (left + bar - 1, 0), (left + bar - 1, h), (25, 25, 25), 1)
    return out


def occlude_bar(image: np.ndarray, width_fraction: float, keep: tuple[int, int, int, int],
                rng: np.random.Generator, *, degrees: float = 0.0, at: float | None = None,
                colour: tuple[int, int, int] = (118, 118, 118)) -> np.ndarray:
    """A straight bar (an arm reaching in) of the given share of the width, tilted
    `degrees` from vertical (90 = horizontal), crossing the content box at `at` (0-1
    along its width, or its height for a bar nearer horizontal; None = at random),
    drawn across the whole frame with dark edges."""
    h, w = image.shape[:2]
    bar = max(2, int(round(width_fraction * w)))
    x0, y0, x1, y1 = keep
    share = float(rng.uniform(0, 1)) if at is None else float(at)
    t = np.radians(degrees)
    if abs(degrees) <= 45:  # nearer vertical: placed along x, through the box's middle row
        centre = (x0 + share * (x1 - x0), (y0 + y1) / 2)
    else:
        centre = ((x0 + x1) / 2, y0 + share * (y1 - y0))
    along = np.array([np.sin(t), np.cos(t)])  # direction of the bar's length
    across = np.array([along[1], -along[0]]) * bar / 2
    reach = along * (h + w)
    c = np.array(centre)
    corners = np.array([c - reach - across, c + reach - across, c + reach + across,
                        c - reach + across])
    out = image.copy()
    cv2.fillConvexPoly(out, np.round(corners).astype(np.int32), colour, cv2.LINE_AA)
    for a, b in ((corners[0], corners[1]), (corners[3], corners[2])):
        cv2.line(out, tuple(int(v) for v in np.round(a)), tuple(int(v) for v in np.round(b)),
                 (25, 25, 25), 1, cv2.LINE_AA)
    return out


def occlude_blob(image: np.ndarray, radius_fraction: float, keep: tuple[int, int, int, int],
                 rng: np.random.Generator, colour: tuple[int, int, int] = (118, 118, 118)
                 ) -> np.ndarray:
    """A grey blob (a hand, a passing object) of radius `radius_fraction` of the content
    box's height, an irregular ellipse centred somewhere inside the box."""
    x0, y0, x1, y1 = keep
    radius = max(3.0, radius_fraction * (y1 - y0))
    cx, cy = rng.uniform(x0, x1), rng.uniform(y0 + 0.3 * (y1 - y0), y1)
    angles = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    radii = radius * rng.uniform(0.75, 1.25, size=len(angles))
    points = np.stack([cx + radii * np.cos(angles), cy + 0.8 * radii * np.sin(angles)], axis=1)
    out = image.copy()
    hull = cv2.convexHull(np.round(points).astype(np.int32))
    cv2.fillConvexPoly(out, hull, colour, cv2.LINE_AA)
    cv2.polylines(out, [hull], True, (25, 25, 25), 1, cv2.LINE_AA)
    return out


def occlude_pole(image: np.ndarray, width_fraction: float, length_fraction: float,
                 keep: tuple[int, int, int, int], rng: np.random.Generator,
                 colour: tuple[int, int, int] = (118, 118, 118), at: float | None = None
                 ) -> np.ndarray:
    """A plain vertical bar hanging from the top edge in front of the scene (a pole, a
    cable, an arm link): `width_fraction` of the image width wide, reaching
    `length_fraction` of the image height down (1 = to the bottom edge), with no outline
    (anti-aliased sides only), somewhere across the content box (`at`: 0-1 along its
    width; None = at random)."""
    h, w = image.shape[:2]
    bar = max(2.0, width_fraction * w)
    x0, _, x1, _ = keep
    share = float(rng.uniform(0, 1)) if at is None else float(at)
    left = x0 + share * max(1.0, x1 - x0 - bar)
    bottom = max(1.0, min(1.0, length_fraction) * h)
    out = image.copy()
    shift = 4  # sub-pixel corners: a pole's sides fall anywhere between pixels
    corners = np.array([[left, -1.0], [left + bar, -1.0], [left + bar, bottom],
                        [left, bottom]]) * (1 << shift)
    cv2.fillConvexPoly(out, np.round(corners).astype(np.int32), colour, cv2.LINE_AA,
                       shift)
    return out
