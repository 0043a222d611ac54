"""What perception returns: the graph plus what the detector noticed on the way."""

from __future__ import annotations

from pydantic import BaseModel, Field

from verigraph.graph.model import SceneGraph


class PerceptionResult(BaseModel):
    """A perceived scene graph with what the detector noticed along the way."""

    graph: SceneGraph
    view: str = Field(description="tabletop (side view) or tangram (top view)")
    family: str | None = Field(description="built-in dictionary the objects belong to")
    labeller: str
    warnings: list[str] = Field(default_factory=list)
    scale: float = Field(default=0.0, description="pixels per world unit (0 = unknown)")
    seconds: float = 0.0
