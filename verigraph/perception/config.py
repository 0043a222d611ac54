"""Settings of the perception pipeline: input limits and geometric tolerances.

One pydantic model so that the CLI, the tools layer and tests share the same defaults
and the same validation; every limit is configurable because a robot camera and a
640x480 render need different ones.
"""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

ViewKind = Literal["auto", "tabletop", "tangram"]


class ImageLimits(BaseModel):
    """What an input image may be; checked from the file header before decoding."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    max_bytes: int = Field(default=32 * 1024 * 1024, ge=1,
                           description="largest encoded file accepted")
    max_pixels: int = Field(default=40_000_000, ge=1,
                            description="largest width*height decoded (decompression bombs)")
    max_side: int = Field(default=16384, ge=1, description="longest side in pixels")
    min_side: int = Field(default=32, ge=1, description="shortest side worth perceiving; "
                                                        "smaller images give an empty graph "
                                                        "with a warning")


class PerceptionConfig(BaseModel):
    """Tolerances of the detectors (pixels unless named in world units)."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    limits: ImageLimits = Field(default_factory=ImageLimits)
    view: ViewKind = Field(default="auto", description="tabletop (side view), tangram "
                                                       "(top view) or auto")
    min_core_pixels: int = Field(default=6, ge=1,
                                 description="a region needs this many pixels after a "
                                             "one-pixel erosion to count")
    contact_gap: int = Field(default=9, ge=1, description="largest vertical gap between two "
                                                          "fills that still counts as resting "
                                                          "(two outlines are about 3 px)")
    min_visible_fraction: float = Field(default=0.12, gt=0, le=1,
                                        description="smallest share of an object's expected "
                                                    "area that must show to report it")
    side_angle_degrees: float = Field(default=6.0, gt=0, le=45,
                                      description="tangram: largest angle between touching "
                                                  "sides")
    side_distance: float = Field(default=0.3, gt=0,
                                 description="tangram: largest offset between touching "
                                             "sides, in world units (a small triangle's "
                                             "leg is 4)")
    side_overlap: float = Field(default=0.25, gt=0, le=1,
                                description="tangram: shared length as a fraction of the "
                                            "shorter side")
