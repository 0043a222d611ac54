"""An episode as a stored record: everything another process needs to continue it.

`EpisodeRecord` is the versioned, JSON-only form of an `LiveEpisode`: the scene graph, goal,
dictionary, k, t, tau, trace, executed actions, executor kind and the simulator's world
state (poses and velocities, see `sim2d.persist`), plus `extras` for small per-episode
records other features keep (any JSON value; a world keeps its own there through
`WorldExtras`, e.g. an arm's latched stop as `extras["arm_latched"]`). An LiveEpisode
field added later without a place of its own here is stored all the same, in its
pydantic JSON form (`fields`). Live things are never stored: an arm's driver connection
is opened again by whoever loads the record (`revive` hook), a lock is per process. No
secret is part of an episode, so none is stored.
"""

from __future__ import annotations

import base64
import dataclasses
import functools
import typing
from typing import Any, Literal, Protocol, runtime_checkable

import cv2
import numpy as np
from pydantic import BaseModel, ConfigDict, Field, TypeAdapter

from verigraph.actions.feedback import Violation
from verigraph.actions.model import AnyAction
from verigraph.graph.dictionary import InlineDictionary
from verigraph.graph.goal import Goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.sim2d.persist import world_from_state, world_state
from verigraph.sim2d.world import SimWorld
from verigraph.tools.executors import SceneCheck
from verigraph.tools.fields import dictionary_for
from verigraph.tools.images import KeptImage, png_base64
from verigraph.tools.store import PER_PROCESS, LiveEpisode, TraceEntry

SCHEMA_VERSION: Literal[1] = 1


@runtime_checkable
class WorldExtras(Protocol):
    """A world (an arm's) that keeps small JSON facts with its stored episode and takes
    them back when the episode is reloaded; the store never needs to know its type."""

    def extras_to_keep(self) -> dict[str, object]: ...

    def restore_extras(self, extras: dict[str, object]) -> None: ...


def world_extras(world: object) -> dict[str, object]:
    """What `world` keeps with its episode (nothing for worlds that keep nothing)."""
    return world.extras_to_keep() if isinstance(world, WorldExtras) else {}


_ACTIONS: TypeAdapter[list[AnyAction]] = TypeAdapter(list[AnyAction])


class EpisodeRecord(BaseModel):
    """One stored episode (schema version 1). `version` counts committed state changes."""

    model_config = ConfigDict(extra="forbid")

    schema_version: Literal[1] = SCHEMA_VERSION
    id: str
    version: int = Field(ge=1)
    created_at: float = Field(description="wall-clock seconds since the epoch")
    updated_at: float
    source: str
    executor: str
    k: int
    t: int
    state: SceneGraph | None
    initial_graph: SceneGraph | None
    dictionary_name: str | InlineDictionary | None
    goal: Goal | None
    instruction: str | None
    tau: int
    calls: int
    executed: list[dict[str, Any]]
    trace: list[TraceEntry]
    last_violation: Violation | None
    done: bool
    scene_check: SceneCheck | None
    world: dict[str, Any] | None = Field(description="sim2d world state, when one runs")
    goal_world: dict[str, Any] | None
    image_png: str | None = Field(description="the scene photo (base64 PNG), image episodes")
    extras: dict[str, Any] = Field(default_factory=dict)
    fields: dict[str, Any] = Field(
        default_factory=dict, description="any other LiveEpisode field, in its JSON form")


def _png(image: np.ndarray | KeptImage | None) -> str | None:
    if image is None:
        return None
    if isinstance(image, KeptImage):  # already encoded: store the same bytes
        return png_base64(image.png)
    ok, buffer = cv2.imencode(".png", image)
    return png_base64(buffer.tobytes()) if ok else None


def _image(text: str | None) -> KeptImage | None:
    if text is None:
        return None
    raw = np.frombuffer(base64.b64decode(text), dtype=np.uint8)
    decoded = cv2.imdecode(raw, cv2.IMREAD_COLOR)
    return None if decoded is None else KeptImage.of(np.asarray(decoded))


def _sim(world: Any) -> dict[str, Any] | None:
    return world_state(world) if isinstance(world, SimWorld) else None


def to_record(episode: LiveEpisode, *, version: int, created_at: float, updated_at: float
              ) -> EpisodeRecord:
    """The record of `episode` as it is now (the caller holds its lock)."""
    state = episode.state
    extras = dict(episode.extras)
    extras.update(world_extras(episode.world))  # as it is now, see store_durable
    return EpisodeRecord(
        id=episode.id, version=version, created_at=created_at, updated_at=updated_at,
        source=episode.source, executor=episode.executor, k=episode.k, t=episode.t,
        state=state.to_graph() if state is not None else None,
        initial_graph=episode.initial_graph, dictionary_name=episode.dictionary_name,
        goal=episode.goal, instruction=episode.instruction, tau=episode.tau,
        calls=episode.calls, executed=_ACTIONS.dump_python(episode.executed, mode="json"),
        trace=list(episode.trace), last_violation=episode.last_violation, done=episode.done,
        scene_check=episode.scene_check, world=_sim(episode.world),
        goal_world=_sim(episode.goal_world), image_png=_png(episode.image),
        extras=extras, fields=_other_fields(episode))


# LiveEpisode fields with their own place in the record (PER_PROCESS ones have none).
EXPLICIT = frozenset({
    "id", "state", "source", "k", "t", "goal", "instruction", "world", "executor",
    "scene_check", "goal_world", "image", "initial_graph", "dictionary_name", "tau", "calls",
    "executed", "trace", "last_violation", "done", "extras"})


@functools.cache
def _adapters() -> dict[str, TypeAdapter[Any]]:
    """A JSON adapter for every other LiveEpisode field (one added later is stored too)."""
    hints = typing.get_type_hints(LiveEpisode)
    return {f.name: TypeAdapter(hints[f.name]) for f in dataclasses.fields(LiveEpisode)
            if f.name not in EXPLICIT | PER_PROCESS}


def _other_fields(episode: LiveEpisode) -> dict[str, Any]:
    return {name: adapter.dump_python(getattr(episode, name), mode="json")
            for name, adapter in _adapters().items()}


def restore_state(graph: SceneGraph | None) -> WorldState | None:
    if graph is None:
        return None
    return WorldState.from_graph(graph, dictionary_for(graph.dictionary), partial=True)


def fill_episode(episode: LiveEpisode, record: EpisodeRecord) -> None:
    """Overwrite `episode` (same object, same lock) with the record's state.

    The world is rebuilt from the stored poses for sim2d; an arm episode's world is left
    for the caller's revive hook (it reconnects the driver).
    """
    values: dict[str, Any] = {
        "state": restore_state(record.state), "source": record.source, "k": record.k,
        "t": record.t, "goal": record.goal, "instruction": record.instruction,
        "executor": record.executor, "scene_check": record.scene_check,
        "world": world_from_state(record.world) if record.world is not None else None,
        "goal_world": world_from_state(record.goal_world)
        if record.goal_world is not None else None,
        "image": _image(record.image_png), "initial_graph": record.initial_graph,
        "dictionary_name": record.dictionary_name, "tau": record.tau, "calls": record.calls,
        "executed": _ACTIONS.validate_python(record.executed), "trace": list(record.trace),
        "last_violation": record.last_violation, "done": record.done,
        "extras": dict(record.extras)}
    for name, value in values.items():
        object.__setattr__(episode, name, value)
    for name, data in record.fields.items():
        adapter = _adapters().get(name)
        if adapter is not None:
            object.__setattr__(episode, name, adapter.validate_python(data))


def from_record(record: EpisodeRecord) -> LiveEpisode:
    episode = LiveEpisode(id=record.id, state=None, source=record.source)
    fill_episode(episode, record)
    return episode


def action_texts(record: EpisodeRecord) -> list[str]:
    """The executed actions in text form, e.g. for the operator's listing."""
    return [a.text() for a in _ACTIONS.validate_python(record.executed)]
