"""Colour constancy: undo a camera's colour cast and tone curve, and a repainted wall,
before pixels are classified.

Everything in a render is drawn in known colours (the palette), so the image itself is
the colour chart. A per-channel tone map `true = exp(b) * observed ** a` (a gain, which
is white balance and exposure, and an exponent, which is the gamma curve) is fitted to
the flat areas of the image: each area is paired with the palette colour it is closest
to under the current map, the map is refitted on those pairs (one vote per colour, so a
large wall does not outvote the objects), outlying pairs are dropped, and the loop
repeats until the pairing stops changing. Known surfaces (wall, floor, furniture,
outlines) take part like any other colour; a surface that disagrees with the rest (a
wall painted another colour) is an outlier and does not bend the map.

The wall is then checked on its own: when the area at the top border has another hue
than the palette's background, it is repainted with the background colour (it is the
background whatever its colour), and a note says so.

What the map cannot undo (a hue rotation, a colour no palette entry explains) shows as
a large residual: the mean CIELab distance of flat pixels to their nearest palette
colour, which perception reports as a reason for doubt.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

from verigraph.perception.detect.colors import lab

FLAT_RANGE = 10  # grey levels between the darkest and brightest of a 3x3 window
MAX_SAMPLES = 2500
MATCH_DELTA_E = 30.0  # a flat area this far from every palette colour votes for none
MIN_SHARE = 0.002  # a colour needs this share of the flat samples to vote
OUTLIER_LOG = 0.08  # |log residual| beyond this drops a pair in the second pass
EXPONENT_RANGE = (0.45, 2.2)
GAIN_RANGE = (0.5, 2.0)
ITERATIONS = 4
WALL_CHROMA = 8.0  # CIELab a*b* distance that says "another hue", not "dimmer"
WALL_MATCH = 40.0
WALL_NEAR = 12  # grey levels: samples this close to the wall's colour are the wall
LOW = 6.0  # observed values are clipped here before logarithms
BETTER_BY = 0.2  # CIELab residual a tone map must gain over the best so far to replace it


@dataclass(frozen=True, slots=True)
class ToneMap:
    """Per-channel (B, G, R) exponent and log-gain: true = exp(b) * observed ** a,
    on values scaled to 0-1. Identity: a = 1, b = 0."""

    a: tuple[float, float, float] = (1.0, 1.0, 1.0)
    b: tuple[float, float, float] = (0.0, 0.0, 0.0)
    colours: int = 0  # palette colours the fit rests on
    residual: float = 0.0  # mean CIELab distance of flat pixels to the palette, after

    @property
    def is_identity(self) -> bool:
        return (max(abs(x - 1) for x in self.a) < 0.02
                and max(abs(x) for x in self.b) < 0.02)

    def lut(self) -> np.ndarray:
        """256x1x3 lookup table for cv2.LUT."""
        levels = np.maximum(np.arange(256, dtype=np.float64), LOW) / 255.0
        out = np.stack([np.exp(b) * levels ** a for a, b in zip(self.a, self.b, strict=True)],
                       axis=1)
        return np.clip(out * 255.0 + 0.5, 0, 255).astype(np.uint8).reshape(256, 1, 3)

    def apply(self, image: np.ndarray) -> np.ndarray:
        if self.is_identity:
            return image
        return np.asarray(cv2.LUT(image, self.lut()))


def flat_samples(image: np.ndarray, seed: int = 0) -> np.ndarray:
    """BGR pixels (n, 3) from the insides of uniform areas (not outlines or blur edges),
    read on every second row and column (a fill's inside is many pixels wide)."""
    stride = 2 if min(image.shape[:2]) >= 64 else 1
    grey = np.ascontiguousarray(cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)[::stride, ::stride])
    k = np.ones((3, 3), np.uint8)
    flat = cv2.subtract(cv2.dilate(grey, k), cv2.erode(grey, k)) <= FLAT_RANGE
    # Positions first, pixels last: only the chosen few are gathered from the image.
    where = np.flatnonzero(flat)
    if len(where) > MAX_SAMPLES:
        step = len(where) / MAX_SAMPLES
        offset = np.random.default_rng(seed).uniform(0, step)
        where = where[(offset + np.arange(MAX_SAMPLES) * step).astype(np.int64)]
    rows, cols = np.divmod(where, flat.shape[1])
    return np.asarray(image[rows * stride, cols * stride])


def _nearest(samples: np.ndarray, palette_lab: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Nearest palette colour (index, CIELab distance) of each uint8 BGR sample. A
    render's flat areas hold a few dozen distinct colours among thousands of samples,
    so the distances are computed once per distinct colour."""
    pixels = samples.astype(np.int32)
    keys = (pixels[:, 0] << 16) | (pixels[:, 1] << 8) | pixels[:, 2]
    _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    d = np.linalg.norm(lab(samples[first])[:, None, :] - palette_lab[None, :, :], axis=2)
    best = np.argmin(d, axis=1)
    return best[inverse], d[np.arange(len(best)), best][inverse]


def _fit(observed: np.ndarray, target: np.ndarray, keep: np.ndarray, min_pairs: int = 3
         ) -> tuple[np.ndarray, np.ndarray]:
    """Per-channel least squares of log(target) = a * log(observed) + b."""
    lo = np.log(np.maximum(observed[keep], LOW) / 255.0)
    lt = np.log(np.maximum(target[keep], LOW) / 255.0)
    a, b = np.ones(3), np.zeros(3)
    for c in range(3):
        x, y = lo[:, c], lt[:, c]
        if len(x) >= min_pairs and float(np.ptp(x)) > 0.3:
            design = np.stack([x, np.ones_like(x)], axis=1)
            (a[c], b[c]), *_ = np.linalg.lstsq(design, y, rcond=None)
        else:  # too little spread to tell an exponent from a gain: gain only
            b[c] = float(np.median(y - x)) if len(x) else 0.0
    return a, b


def estimate_tone(image: np.ndarray, palette_bgr: list[tuple[int, int, int]],
                  anchors: list[tuple[np.ndarray, tuple[int, int, int]]] | None = None,
                  wall: tuple[int, int, int] | None = None,
                  samples: np.ndarray | None = None) -> ToneMap:
    """The tone map that best brings the image's flat colours onto the palette.

    The pairing loop starts from the identity and, when `anchors` are given (observed
    colours of known surfaces: the wall at the top border, the floor at the bottom),
    also from the map those surfaces alone imply; the start that ends closest to the
    palette wins (a strong curve moves the floor next to the grey counter, where a
    start from the identity would pair them). `samples` are the image's
    `flat_samples`, when the caller has them already.
    """
    samples = flat_samples(image) if samples is None else samples
    palette = np.array(palette_bgr, dtype=np.float64)
    palette_lab = lab(palette.astype(np.uint8))
    if len(samples) < 50:
        return ToneMap()
    judged = samples
    if wall is not None:
        away = np.abs(samples.astype(np.int32) - np.array(wall)).max(axis=1) > WALL_NEAR
        judged = samples[away] if np.count_nonzero(away) >= 50 else samples

    def judge(tone: ToneMap) -> ToneMap:
        corrected = tone.apply(judged.reshape(-1, 1, 3)).reshape(-1, 3)
        _, dist = _nearest(corrected, palette_lab)
        return ToneMap(tone.a, tone.b, tone.colours, float(np.mean(np.minimum(dist, 60.0))))

    # The identity is judged first; a candidate must beat the best by BETTER_BY, and
    # residuals are never negative, so an image already on the palette (a clean
    # render) keeps the identity without any fit.
    best = judge(ToneMap())
    if best.residual <= BETTER_BY:
        return best
    starts = [ToneMap()]
    if anchors:
        obs = np.array([a for a, _ in anchors], dtype=np.float64)
        tgt = np.array([t for _, t in anchors], dtype=np.float64)
        a, b = _fit(obs, tgt, np.ones(len(obs), dtype=bool), min_pairs=2)
        if _plausible(a, b):
            starts.append(ToneMap(_triple(a), _triple(b)))
    for start in starts[1:]:
        tone = judge(start)
        if tone.residual < best.residual - BETTER_BY:
            best = tone
    for start in starts:
        tone = judge(_refine(start, samples, palette, palette_lab))
        if tone.residual < best.residual - BETTER_BY:
            best = tone
    return best


def _triple(x: np.ndarray) -> tuple[float, float, float]:
    return float(x[0]), float(x[1]), float(x[2])


def _plausible(a: np.ndarray, b: np.ndarray) -> bool:
    return bool(np.all((a >= EXPONENT_RANGE[0]) & (a <= EXPONENT_RANGE[1]))
                and np.all((np.exp(b) >= GAIN_RANGE[0]) & (np.exp(b) <= GAIN_RANGE[1])
                           | (np.abs(a - 1) > 0.05)))


def _group_medians(samples: np.ndarray, groups: np.ndarray, count: int, at_least: float
                   ) -> tuple[np.ndarray, np.ndarray]:
    """The groups (0..count-1) with at least `at_least` uint8 samples, and the
    per-channel median of each, from one sort per channel instead of a mask and a
    median per group (the values are integers, so the medians are exact)."""
    sizes = np.bincount(groups, minlength=count)
    voters = np.flatnonzero(sizes >= at_least)
    if len(voters) == 0:
        return voters, np.zeros((0, 3))
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])[voters]
    lower = starts + (sizes[voters] - 1) // 2
    upper = starts + sizes[voters] // 2
    medians = np.empty((len(voters), 3))
    for ch in range(3):
        ordered = np.sort(groups.astype(np.int64) * 256 + samples[:, ch])  # by group, value
        values = (ordered % 256).astype(np.float64)
        medians[:, ch] = (values[lower] + values[upper]) / 2
    return voters, medians


def _refine(tone: ToneMap, samples: np.ndarray, palette: np.ndarray,
            palette_lab: np.ndarray) -> ToneMap:
    """Pair flat colours with palette colours under the map, refit, repeat."""
    for _ in range(ITERATIONS):
        corrected = tone.apply(samples.reshape(-1, 1, 3)).reshape(-1, 3)
        best, dist = _nearest(corrected, palette_lab)
        ok = dist < MATCH_DELTA_E
        voters, obs = _group_medians(samples[ok], best[ok], len(palette),
                                     max(8, MIN_SHARE * len(samples)))
        if len(voters) < 2:
            break
        tgt = palette[voters]
        keep = np.ones(len(obs), dtype=bool)
        a, b = _fit(obs, tgt, keep)
        residual = np.abs(np.log(np.maximum(obs, LOW) / 255.0) * a + b
                          - np.log(np.maximum(tgt, LOW) / 255.0)).max(axis=1)
        keep = residual < max(OUTLIER_LOG, float(np.median(residual)) * 3)
        if keep.sum() >= 2:
            a, b = _fit(obs, tgt, keep)
        if not _plausible(a, b):
            break
        new = ToneMap(_triple(a), _triple(b), int(keep.sum()))
        done = np.allclose(new.a, tone.a, atol=0.005) and np.allclose(new.b, tone.b,
                                                                      atol=0.005)
        tone = new
        if done:
            break
    return tone


def wall_colour(image: np.ndarray, band: float = 0.04, bottom: bool = False
                ) -> tuple[int, int, int] | None:
    """Median colour of the flat pixels along the top border (the wall or the table),
    or along the bottom border (the floor)."""
    rows = max(2, int(round(band * image.shape[0])))
    top = flat_samples(np.ascontiguousarray(image[-rows:] if bottom else image[:rows]))
    if len(top) < 20:
        return None
    med = np.median(top.astype(np.float64), axis=0)
    return int(med[0]), int(med[1]), int(med[2])


def repaint_wall(image: np.ndarray, background: tuple[int, int, int]
                 ) -> tuple[np.ndarray, tuple[int, int, int] | None]:
    """The image with a wall of another hue repainted as the palette's background.

    Returns the image (unchanged when the wall has the background's hue, perhaps
    dimmer: that is lighting, undone later) and the wall colour found, if repainted.
    """
    return repaint_measured_wall(image, background, wall_colour(image))


def repaint_measured_wall(image: np.ndarray, background: tuple[int, int, int],
                          wall: tuple[int, int, int] | None
                          ) -> tuple[np.ndarray, tuple[int, int, int] | None]:
    """`repaint_wall` with the wall's colour (`wall_colour(image)`) already measured."""
    if wall is None:
        return image, None
    wall_lab, background_lab = lab(np.array([wall, background], dtype=np.uint8))
    if float(np.linalg.norm(wall_lab[1:] - background_lab[1:])) < WALL_CHROMA:
        return image, None
    diff = image.astype(np.float32) - np.array(wall, dtype=np.float32)
    weight = np.clip(1.0 - np.linalg.norm(diff, axis=2) / WALL_MATCH, 0.0, 1.0)
    weight = np.clip(2.0 * weight, 0.0, 1.0)  # the wall itself all the way, edges partly
    shift = np.array(background, dtype=np.float32) - np.array(wall, dtype=np.float32)
    out = np.clip(image.astype(np.float32) + weight[..., None] * shift + 0.5, 0, 255)
    return out.astype(np.uint8), wall


def palette_fit(image: np.ndarray, palette_bgr: list[tuple[int, int, int]],
                samples: np.ndarray | None = None) -> float:
    """How well an image's flat colours match the palette, one vote per colour: the
    mean over matched palette colours of their samples' median CIELab distance, plus a
    penalty for the share of samples no palette colour explains. Lower is better.
    `samples` are the image's `flat_samples`, when the caller has them already."""
    samples = flat_samples(image) if samples is None else samples
    if len(samples) < 50:
        return 0.0
    best, dist = _nearest(samples, lab(np.array(palette_bgr, dtype=np.uint8)))
    ok = dist < MATCH_DELTA_E
    medians = [float(np.median(dist[ok & (best == c)])) for c in range(len(palette_bgr))
               if np.count_nonzero(ok & (best == c)) >= max(8, MIN_SHARE * len(samples))]
    if not medians:
        return MATCH_DELTA_E
    return float(np.mean(medians)) + MATCH_DELTA_E * float(1 - ok.mean())
