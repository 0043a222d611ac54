"""`SimWorld`: what every simulated world offers on top of the executor's `World` protocol.

`perform` and `observe` are the `World` contract (`verigraph.actions.execution`); a sim
world also renders itself, executes actions without the validator (`perform_unverified`,
so the consequences of a bad action show), and copies itself for what-if runs.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import Literal

import numpy as np

from verigraph.actions.feedback import Violation
from verigraph.actions.model import AlignAction, MoveAction
from verigraph.graph.model import Node, SceneGraph

WorldKind = Literal["tabletop", "tangram"]


class SimWorld(ABC):
    """A seeded, deterministic 2-D world that carries out actions and reports its graph."""

    kind: WorldKind
    nodes: list[Node]  # the scene's objects, as given (ids, labels, attrs)

    @abstractmethod
    def perform(self, action: MoveAction | AlignAction) -> Violation | None:
        """Carry out a validated action; a Violation means the world refused and nothing
        moved (tangram `overlap`, or no free placement on the target)."""

    @abstractmethod
    def observe(self) -> SceneGraph:
        """The scene graph read from the world's geometry (never from bookkeeping)."""

    @abstractmethod
    def perform_unverified(self, action: MoveAction | AlignAction) -> SceneGraph:
        """Carry out an action without any symbolic check and return the observed graph.

        The arm grasps only the named object: whatever rested on it is left behind and
        falls. Raises SimError only when the arm physically cannot act (unknown ids, a
        fixed object)."""

    @abstractmethod
    def render(self, width: int | None = None, height: int | None = None, *,
               labels: bool = False) -> np.ndarray:
        """BGR uint8 image of the current state (a pure function of the state). A side
        not given follows the scene's shape; with neither, the world picks a size that
        shows its thinnest parts (see `sim2d.render.frame_size`)."""

    @abstractmethod
    def copy(self) -> SimWorld:
        """An independent world in the same state."""
