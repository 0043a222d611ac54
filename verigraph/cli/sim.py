"""`verigraph render` and `verigraph demo`: the 2-D simulator from the command line.

Scene ids: a built-in scene (cup_on_book, three_blocks, kitchen_pan), a generated
scene FAMILY:SEED[:N] (blocks, kitchen, tableware, tangram; e.g. kitchen:7), or a
scene graph file (.json/.yaml).
"""

from __future__ import annotations

import argparse
import re
from pathlib import Path
from typing import Any

import cv2
import numpy as np

from verigraph.cli.exits import EXIT_NEGATIVE, EXIT_OK
from verigraph.errors import InputFileError, VeriGraphError

GENERATED = re.compile(r"^(?P<family>[a-z_]+):(?P<seed>\d+)(?::(?P<n>\d+))?$")
DEMO_SCENES = ("cup_on_book", "kitchen_pan")


def register(sub: Any) -> None:
    r = sub.add_parser("render", help="draw a simulated scene to a PNG",
                       description="Render a scene in the 2-D simulator. " + __doc__.split(
                           "\n\n", 1)[1].replace("\n", " "))
    r.add_argument("--scene", required=True, help="built-in id, FAMILY:SEED[:N] or a file")
    r.add_argument("--out", required=True, help="PNG file to write")
    r.add_argument("--goal", action="store_true",
                   help="draw the scene's goal instead (built-in or generated scenes)")
    r.add_argument("--width", type=int, default=None,
                   help="image width (default: the scene's own shape at 8 px per world "
                        "unit for tabletops, 640 for tangram)")
    r.add_argument("--height", type=int, default=None,
                   help="image height (default: follows the scene's shape; tangram 480)")
    r.add_argument("--seed", type=int, default=0, help="layout seed for built-in and file "
                                                       "scenes; also seeds the degradations")
    r.add_argument("--labels", action="store_true", help="write object ids (tangram: side "
                                                         "indices) on the image")
    degrade = r.add_argument_group("degradations (perception tests)")
    degrade.add_argument("--noise", type=float, default=0.0, help="Gaussian noise sigma, 0-255")
    degrade.add_argument("--blur", type=float, default=0.0, help="Gaussian blur sigma, pixels")
    degrade.add_argument("--lighting", type=float, default=0.0,
                         help="uneven lighting strength, 0-1")
    degrade.add_argument("--jpeg", type=int, default=None, help="JPEG quality 1-100")
    r.set_defaults(handler=run_render)

    d = sub.add_parser("demo", help="verifier + simulator end to end: a plan with a mistake, "
                                    "the feedback, the corrected plan executed in sim2d")
    d.add_argument("--out", default="out/demo", help="directory for the images (default "
                                                     "out/demo)")
    d.add_argument("--scene", choices=DEMO_SCENES, default="cup_on_book")
    d.add_argument("--width", type=int, default=None, help="image width (default: the "
                                                             "scene's own shape)")
    d.add_argument("--height", type=int, default=None, help="image height (default: follows "
                                                             "the scene's shape)")
    d.set_defaults(handler=run_demo)


# -- render ---------------------------------------------------------------------------------
def load_world(scene_id: str, seed: int = 0, *, goal: bool = False) -> Any:
    """The SimWorld for a scene id (or, with goal=True, for its goal)."""
    from verigraph.graph.builtin_scenes import BUILTIN_GOALS, BUILTIN_SCENES
    from verigraph.graph.io import load_scene
    from verigraph.sim2d import generate_scene, world_for_graph

    match = GENERATED.match(scene_id)
    if match:
        n = int(match["n"]) if match["n"] else None
        generated = generate_scene(match["family"], int(match["seed"]), n)
        return generated.goal_world if goal else generated.world
    if scene_id in BUILTIN_SCENES:
        if not goal:
            return world_for_graph(BUILTIN_SCENES[scene_id](), seed)
        target = BUILTIN_GOALS.get(scene_id)
        graph = target().graph if target is not None else None
        if graph is None:
            raise VeriGraphError(f"built-in scene '{scene_id}' has no goal graph to draw",
                                 field="scene", value=scene_id,
                                 fix="drop --goal, or use a scene with a goal graph "
                                     "(cup_on_book, or a generated FAMILY:SEED)")
        return world_for_graph(graph, seed)
    if Path(scene_id).suffix.lower() in (".json", ".yaml", ".yml"):
        if goal:
            raise VeriGraphError("--goal needs a built-in or generated scene", field="goal",
                                 value=scene_id, fix="render the goal file as --scene instead")
        return world_for_graph(load_scene(scene_id), seed)
    raise InputFileError(f"unknown scene '{scene_id}'", field="scene", value=scene_id,
                         fix="use a built-in id (" + ", ".join(sorted(BUILTIN_SCENES)) +
                             "), FAMILY:SEED such as kitchen:7, or a .json/.yaml scene file")


def write_png(path: Path, image: np.ndarray) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    if not cv2.imwrite(str(path), image):
        raise InputFileError(f"cannot write '{path}'", field="out", value=str(path),
                             fix="give a writable path ending in .png")


def check_render_size(width: int | None, height: int | None) -> None:
    """Each side given must be 16..4000 pixels (a side left out follows the scene)."""
    for name, value in (("width", width), ("height", height)):
        if value is not None and not 16 <= value <= 4000:
            raise VeriGraphError("image size out of range", field=name, value=value,
                                 fix="use 16..4000 pixels per side, or leave it out")


def run_render(args: argparse.Namespace) -> int:
    from verigraph.sim2d import Degradation, degrade

    check_render_size(args.width, args.height)
    world = load_world(args.scene, args.seed, goal=args.goal)
    image = world.render(args.width, args.height, labels=args.labels)
    spec = Degradation(noise=args.noise, blur=args.blur, lighting=args.lighting,
                       jpeg=args.jpeg)
    image = degrade(image, spec, seed=args.seed)
    out = Path(args.out)
    write_png(out, image)
    print(f"{out}: {args.scene}{' (goal)' if args.goal else ''}, "
          f"{image.shape[1]}x{image.shape[0]}; "
          + "; ".join(world.observe().sentences()))
    return EXIT_OK


# -- demo -----------------------------------------------------------------------------------
def run_demo(args: argparse.Namespace) -> int:
    from verigraph.sim2d.demo import play_demo

    check_render_size(args.width, args.height)
    return EXIT_OK if play_demo(args.scene, Path(args.out), args.width, args.height) else \
        EXIT_NEGATIVE
