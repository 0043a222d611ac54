"""Simulator pictures of every step of a simulated episode, and red frames around objects.

A sim2d world is seeded and deterministic, and `sim2d.persist` rebuilds one exactly, so
an episode keeps only its world as it was loaded (`LiveEpisode.initial_world`, 2-7 KiB of
JSON) and the viewer replays the executed actions on a rebuilt copy, rendering after
each. Keeping a PNG per executed step instead would cost about 10 KiB per step in every
episode (and in every durable record), viewed or not; the replay costs CPU only when
someone looks (a few ms per step) and never touches the live episode: it runs on its
own world, outside the episode's lock.

At most MAX_SIMULATED_STEPS steps get a picture (the size of the answer). Should a
replayed action fail where the live one succeeded (a deterministic world does not, but a
record written by another version might), the pictures stop there and later steps show
only the graph drawing.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import cv2
import numpy as np

from verigraph.actions.model import AnyAction, DoneAction, StateAction
from verigraph.errors import VeriGraphError
from verigraph.sim2d.persist import world_from_state
from verigraph.sim2d.render import encode_png, tabletop_boxes, tangram_boxes
from verigraph.sim2d.tabletop import TabletopWorld
from verigraph.sim2d.tangram import TangramWorld
from verigraph.sim2d.world import SimWorld
from verigraph.tools.drawing import OUTLINE_COLOR

MAX_SIMULATED_STEPS = 100
FRAME_WIDTH = 640  # the height follows the scene's shape, as in render_scene
Box = tuple[int, int, int, int]


def boxes(world: object, width: int | None = None, height: int | None = None
          ) -> dict[str, Box]:
    """Pixel boxes of the objects in the world's render of that size (none for others)."""
    if isinstance(world, TabletopWorld):
        return tabletop_boxes(world, width, height)
    if isinstance(world, TangramWorld):
        return tangram_boxes(world, width, height)
    return {}


def outline(image: np.ndarray, frames: dict[str, Box], ids: Sequence[str]) -> np.ndarray:
    """`image` with a red frame around each of `ids` that has a box (drawn in place)."""
    for x0, y0, x1, y1 in (frames[i] for i in ids if i in frames):
        cv2.rectangle(image, (x0 - 4, y0 - 4), (x1 + 4, y1 + 4), OUTLINE_COLOR, 3, cv2.LINE_AA)
    return image


def _picture(world: SimWorld, ids: Sequence[str]) -> bytes:
    image = np.ascontiguousarray(world.render(width=FRAME_WIDTH), dtype=np.uint8)
    if ids:
        outline(image, boxes(world, FRAME_WIDTH), ids)
    return encode_png(image)


def step_frames(initial_world: dict[str, Any], executed: Sequence[AnyAction],
                outlined: Sequence[Sequence[str]]) -> tuple[bytes, list[bytes]]:
    """The initial scene's picture, and one picture per step (`outlined[i]`: the objects
    to frame in step i's). Step i < len(executed) shows the world after `executed[i]`; a
    step past them (the refused action) shows the world as the refusal left it, since
    nothing moves when an action is refused. Fewer pictures than steps when capped or
    when the replay fails."""
    world = world_from_state(initial_world)
    initial = _picture(world, ())
    frames: list[bytes] = []
    for index, ids in enumerate(outlined[:MAX_SIMULATED_STEPS]):
        if index < len(executed):
            action = executed[index]
            if isinstance(action, DoneAction | StateAction):
                break  # a state change is not drawn (the 2D simulator has no doors)
            try:
                refused = world.perform(action)
            except VeriGraphError:
                break
            if refused is not None:
                break
        elif index > len(executed):
            break
        frames.append(_picture(world, ids))
    return initial, frames
