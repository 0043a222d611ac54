"""A sim2d world as plain JSON data, and back: how a world outlives its process.

The state is every body's shape, pose and velocity (plus whether it is in the world or
held by the arm), so a world rebuilt in another process renders byte-identically and
continues from the same poses. Floats survive JSON exactly (Python writes the shortest
repr that reads back to the same double). Nothing is pickled: a record read from a
shared store is data, never code.
"""

from __future__ import annotations

from typing import Any

import pymunk

from verigraph.graph.dictionary import Dictionary, InlineDictionary, ObjectProperties
from verigraph.graph.model import Node
from verigraph.sim2d import physics
from verigraph.sim2d.bodies import BodySpec
from verigraph.sim2d.physics import BodyPose
from verigraph.sim2d.scene import TabletopScene, Thing
from verigraph.sim2d.tabletop import TabletopWorld
from verigraph.sim2d.tangram import TangramWorld
from verigraph.sim2d.tangram_geometry import TPose
from verigraph.sim2d.world import SimWorld

FORMAT = 1


def _motion(body: pymunk.Body) -> dict[str, float]:
    return {"x": float(body.position.x), "y": float(body.position.y),
            "angle": float(body.angle), "vx": float(body.velocity.x),
            "vy": float(body.velocity.y), "spin": float(body.angular_velocity)}


def _spec(spec: BodySpec) -> dict[str, Any]:
    return {"label": spec.label, "kind": spec.kind, "width": spec.width,
            "height": spec.height, "parts": [[list(p) for p in part] for part in spec.parts],
            "top": spec.top, "cavity": list(spec.cavity) if spec.cavity else None,
            "wall": spec.wall}


def _spec_from(data: dict[str, Any]) -> BodySpec:
    cavity = data["cavity"]
    return BodySpec(label=data["label"], kind=data["kind"], width=data["width"],
                    height=data["height"],
                    parts=tuple(tuple((float(x), float(y)) for x, y in part)
                                for part in data["parts"]),
                    top=data["top"], cavity=(cavity[0], cavity[1], cavity[2], cavity[3])
                    if cavity else None, wall=data["wall"])


def _reference(name: str | InlineDictionary | None) -> Any:
    """How a world's graphs name their dictionary, as JSON (a client's own: its object)."""
    return name.model_dump(mode="json") if isinstance(name, InlineDictionary) else name


def _reference_from(data: Any) -> str | InlineDictionary | None:
    return InlineDictionary.model_validate(data) if isinstance(data, dict) else data


def world_state(world: SimWorld) -> dict[str, Any]:
    """Everything needed to rebuild `world` exactly (JSON-ready)."""
    nodes = [n.model_dump(mode="json") for n in world.nodes]
    if isinstance(world, TangramWorld):
        return {"format": FORMAT, "kind": "tangram", "nodes": nodes, "labels": world.labels,
                "dictionary_name": _reference(world.dictionary_name),
                "bodies": {p: _motion(b) for p, b in world.bodies.items()}}
    if isinstance(world, TabletopWorld):
        things = [{"id": t.id, "label": t.label, "props": t.props.model_dump(mode="json"),
                   "spec": _spec(t.spec), "fixed": t.fixed,
                   "present": t.body.space is not None, **_motion(t.body)}
                  for t in world.scene.things.values()]
        return {"format": FORMAT, "kind": "tabletop", "nodes": nodes, "things": things,
                "dictionary": world.dictionary.model_dump(mode="json"),
                "dictionary_name": _reference(world.dictionary_name)}
    raise TypeError(f"no persistent form for {type(world).__name__}")


def _set_velocity(body: pymunk.Body, m: dict[str, float]) -> None:
    if body.body_type != pymunk.Body.STATIC:
        body.velocity = (m["vx"], m["vy"])
        body.angular_velocity = m["spin"]


def world_from_state(data: dict[str, Any]) -> SimWorld:
    """The world `world_state` described, with the same poses and velocities."""
    if data.get("format") != FORMAT:
        raise ValueError(f"unknown sim2d state format {data.get('format')!r}")
    nodes = [Node.model_validate(n) for n in data["nodes"]]
    if data["kind"] == "tangram":
        bodies = data["bodies"]
        world = TangramWorld(nodes, data["labels"],
                             {p: TPose(m["x"], m["y"], m["angle"]) for p, m in bodies.items()},
                             _reference_from(data["dictionary_name"]))
        for piece, m in bodies.items():
            _set_velocity(world.bodies[piece], m)
        return world
    scene = TabletopScene()
    for t in data["things"]:
        spec = _spec_from(t["spec"])
        body = physics.make_body(spec, BodyPose(t["x"], t["y"], t["angle"]), fixed=t["fixed"])
        _set_velocity(body, t)
        scene.add(Thing(t["id"], t["label"], ObjectProperties.model_validate(t["props"]),
                        spec, body, t["fixed"]), in_space=t["present"])
    return TabletopWorld(scene, nodes, Dictionary.model_validate(data["dictionary"]),
                         _reference_from(data["dictionary_name"]))
