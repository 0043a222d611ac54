"""What perception returns: the graph plus what the detector noticed on the way."""

from __future__ import annotations

from pydantic import BaseModel, Field

from verigraph.graph.model import SceneGraph


class DetectedObject(BaseModel):
    """One object found in the image, with where it is (pixels)."""

    id: str
    label: str
    colour: str
    box: tuple[int, int, int, int] = Field(description="x0, y0, x1, y1 (x1, y1 exclusive)")
    score: float = Field(ge=0.0, le=1.0, description="the labeller's confidence")


class PerceptionResult(BaseModel):
    """A perceived scene graph with what the detector noticed along the way."""

    graph: SceneGraph
    view: str = Field(description="tabletop (side view) or tangram (top view)")
    family: str | None = Field(description="built-in dictionary the objects belong to")
    labeller: str
    objects: list[DetectedObject] = Field(default_factory=list)
    warnings: list[str] = Field(default_factory=list)
    scale: float = Field(default=0.0, description="pixels per world unit (0 = unknown)")
    seconds: float = 0.0
