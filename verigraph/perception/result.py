"""What perception returns: the graph plus what the detector noticed on the way, with a
confidence per node and edge and the items it is unsure of."""

from __future__ import annotations

from collections.abc import Callable

from pydantic import BaseModel, Field

from verigraph.graph.model import Edge, SceneGraph

CONFIDENT = 0.5  # items below this confidence are listed as uncertain


class DetectedObject(BaseModel):
    """One object found in the image, with where it is (pixels)."""

    id: str
    label: str
    colour: str
    box: tuple[int, int, int, int] = Field(description="x0, y0, x1, y1 (x1, y1 exclusive)")
    score: float = Field(ge=0.0, le=1.0, description="the labeller's confidence")


class Uncertain(BaseModel):
    """A node or edge perception is unsure of, and why."""

    item: str = Field(description="node id, or an edge as 'source relation target'")
    confidence: float = Field(ge=0.0, le=1.0)
    reason: str


def add_edge_confidence(graph: SceneGraph, confidence: dict[str, float],
                        uncertain: list[Uncertain], name: Callable[[Edge], str],
                        parts: str) -> None:
    """Each edge of `graph` is as sure as the less sure of its two ends (their values in
    `confidence`), entered under `name(edge)`; those below CONFIDENT join `uncertain`."""
    for edge in graph.edges:
        item = name(edge)
        value = min(confidence.get(edge.source, 1.0), confidence.get(edge.target, 1.0))
        confidence[item] = value
        if value < CONFIDENT:
            uncertain.append(Uncertain(item=item, confidence=value,
                                       reason=f"one of its {parts} is uncertain"))


class Blocked(BaseModel):
    """Where the view is blocked by something in front of the scene, and what it may
    hide: the graph is incomplete there, and relations through it are uncertain."""

    kind: str = Field(description="band (across the frame), pole (a bar reaching in "
                                  "from the top or a side edge), blob, or area (no "
                                  "detected object explains it)")
    box: tuple[int, int, int, int] = Field(description="x0, y0, x1, y1 (x1, y1 exclusive)")
    touches: list[str] = Field(default_factory=list, description="ids of the objects it "
                               "hides part of or cuts; any object wholly behind it is not "
                               "seen")


class PerceptionResult(BaseModel):
    """A perceived scene graph with what the detector noticed along the way.

    `confidence` holds a value in [0, 1] for every node id and every edge (written
    'source relation target'); `uncertain` lists those below `CONFIDENT` with the
    reason. A result with warnings or uncertain items is a proposal to confirm, not a
    fact (`confident` is False).
    """

    graph: SceneGraph
    view: str = Field(description="tabletop (side view) or tangram (top view)")
    family: str | None = Field(description="built-in dictionary the objects belong to")
    family_reason: str = Field(default="", description="why this family was chosen")
    labeller: str
    objects: list[DetectedObject] = Field(default_factory=list)
    warnings: list[str] = Field(default_factory=list)
    confidence: dict[str, float] = Field(default_factory=dict)
    uncertain: list[Uncertain] = Field(default_factory=list)
    scale: float = Field(default=0.0, description="pixels per world unit (0 = unknown)")
    explained: float = Field(default=1.0, description="share of the scene (not wall or "
                                                      "floor) the detected objects explain")
    shape_error: float = Field(default=0.0, description="mean shape error of the movable "
                                                        "objects (0 = as drawn)")
    occluded: list[str] = Field(default_factory=list, description="ids of objects "
                                "something in front of the scene hides part of")
    blocked: list[Blocked] = Field(default_factory=list, description="where something "
                                   "in front blocks the view, and what it touches")
    restored: str = Field(default="", description="what was undone before detection (a "
                                                  "motion blur), when it could be")
    seconds: float = 0.0

    @property
    def confident(self) -> bool:
        """No warnings and nothing uncertain: the graph can be taken as perceived."""
        return not self.warnings and not self.uncertain
