"""One step before classification: the image's colours brought back to the palette.

Order: the global tone map (colour cast, exposure, gamma; `constancy`), a wall of
another hue repainted as background, then the smooth lighting gain of `lighting` (kept
only when it brings the colours closer to the palette than leaving them alone: a wall
painted darker looks like dim light on the wall, and the floor, the furniture and the
objects then say there is none). What is left over is the palette residual, reported
so that a badly matched image is flagged rather than trusted.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from verigraph.perception.correct import constancy, lighting
from verigraph.sim2d import palette

RESIDUAL_DOUBT = 9.0  # mean palette distance (CIELab) beyond which colours are doubtful


@dataclass(slots=True)
class Photometry:
    """The corrected image and what was done to it."""

    image: np.ndarray
    tone: constancy.ToneMap
    gain: lighting.GainField
    wall: tuple[int, int, int] | None
    residual: float
    notes: list[str] = field(default_factory=list)

    @property
    def doubtful(self) -> bool:
        return self.residual > RESIDUAL_DOUBT


def correct_colours(image: np.ndarray, palette_bgr: list[tuple[int, int, int]],
                    background: tuple[int, int, int],
                    references: list[tuple[int, int, int]]) -> Photometry:
    """Tone map, wall repaint and lighting gain, each kept only if it helps."""
    anchors = []
    top = constancy.wall_colour(image)
    if top is not None:
        anchors.append((np.array(top, dtype=np.float64), background))
    floor = constancy.wall_colour(image, bottom=True)
    if floor is not None and palette.FLOOR in references:
        anchors.append((np.array(floor, dtype=np.float64), palette.FLOOR))
    samples = constancy.flat_samples(image)  # reused below while the image is unchanged
    tone = constancy.estimate_tone(image, palette_bgr, anchors, top, samples)
    toned = tone.apply(image)
    repainted, wall = (constancy.repaint_measured_wall(toned, background, top)
                       if toned is image else constancy.repaint_wall(toned, background))
    gain = lighting.estimate_gain(repainted, references)
    lit = lighting.correct(repainted, gain)
    residual = constancy.palette_fit(lit, palette_bgr, samples if lit is image else None)
    if lit is not repainted:
        unlit = constancy.palette_fit(repainted, palette_bgr,
                                      samples if repainted is image else None)
        if unlit < residual:
            gain, lit, residual = lighting.GainField(), repainted, unlit
    notes = []
    if wall is not None:
        notes.append(f"the wall's colour {wall} (BGR) is not the renderer's; it was taken "
                     "as background")
    if residual > RESIDUAL_DOUBT:
        notes.append(f"colours match the dictionary's palette poorly (mean CIELab distance "
                     f"{residual:.1f} after correction); labels may be wrong")
    return Photometry(image=lit, tone=tone, gain=gain, wall=wall, residual=residual,
                      notes=notes)
