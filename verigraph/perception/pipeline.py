"""image -> scene graph: lighting, colour classes, the view's detector, the graph.

`perceive_image` returns everything a caller may want to show (warnings, timings, the
detections); `perceive` is the narrow form the tools layer calls.
"""

from __future__ import annotations

import logging
import time
from typing import Any

import numpy as np

from verigraph.graph.dictionary import BUILTIN_DICTIONARIES, Dictionary, load_dictionary
from verigraph.graph.model import SceneGraph
from verigraph.graph.wellformed import check_well_formed
from verigraph.perception import colors, lighting
from verigraph.perception.catalogue import models_by_colour
from verigraph.perception.config import PerceptionConfig
from verigraph.perception.graphing import assign_ids, tabletop_graph
from verigraph.perception.imageio import as_bgr
from verigraph.perception.labelling import ColourShapeLabeller, Labeller
from verigraph.perception.noise import denoise
from verigraph.perception.result import DetectedObject, PerceptionResult
from verigraph.perception.support import infer_supports, label_map
from verigraph.perception.tabletop import detect_tabletop
from verigraph.perception.tangram import perceive_tangram
from verigraph.perception.views import choose_view, family_of
from verigraph.sim2d import palette

log = logging.getLogger("verigraph.perception")

DEFAULT_CONFIG = PerceptionConfig()
DEFAULT_LABELLER = ColourShapeLabeller()
CAVITY_FLOOR_TOLERANCE = 0.5  # world units, as in sim2d.readback


def perceive_image(image: Any, *, dictionary: Dictionary | str | None = None,
                   config: PerceptionConfig | None = None,
                   labeller: Labeller | None = None) -> PerceptionResult:
    """Perceive a BGR image (array) as a scene graph over the dictionary D."""
    start = time.perf_counter()
    config = config or DEFAULT_CONFIG
    labeller = labeller or DEFAULT_LABELLER
    bgr = as_bgr(image, config.limits)
    d = load_dictionary(dictionary) if not isinstance(dictionary, Dictionary) else dictionary
    if min(bgr.shape[:2]) < config.limits.min_side:
        result = PerceptionResult(
            graph=SceneGraph(dictionary=d.name if d.name in BUILTIN_DICTIONARIES else None),
            view=config.view, family=None, labeller=labeller.name, warnings=[
                f"the image is {bgr.shape[1]}x{bgr.shape[0]} pixels, too small to find "
                f"objects in (ImageLimits.min_side is {config.limits.min_side}); "
                "the graph is empty"])
        result.seconds = time.perf_counter() - start
        return result
    bgr = denoise(bgr)
    view = choose_view(bgr, d, config.view)
    if view == "tangram":
        result = perceive_tangram(bgr, d, config, labeller)
    else:
        result = _perceive_tabletop(bgr, d, config, labeller)
    result.seconds = time.perf_counter() - start
    for w in result.warnings:
        log.warning("perception: %s", w)
    return result


def _perceive_tabletop(bgr: np.ndarray, d: Dictionary, config: PerceptionConfig,
                       labeller: Labeller) -> PerceptionResult:
    models = models_by_colour(d)
    gain = lighting.estimate_gain(bgr, [palette.BACKGROUND, palette.FLOOR])
    corrected = lighting.correct(bgr, gain)
    table = colors.colour_table(tuple(sorted(models)), tangram=False)
    classes = colors.classify(corrected, table)
    colors.refine_edges(corrected, classes, table)
    scene = detect_tabletop(corrected, classes, table, models, labeller, config)
    detections = scene.detections
    warnings = list(scene.warnings)
    if not detections:
        warnings.append("no objects of the dictionary were found in the image")
    assign_ids(detections)
    labels = label_map(classes.shape, detections, scene.floor_row)
    supports = infer_supports(detections, labels, gap=config.contact_gap,
                              cavity_tolerance=CAVITY_FLOOR_TOLERANCE * scene.scale + 1.0)
    family = family_of({det.label for det in detections}, d)
    name = family if family is not None else (d.name if d.name in BUILTIN_DICTIONARIES
                                              else None)
    graph = tabletop_graph(detections, supports, name)
    problems = check_well_formed(graph, d)
    warnings += [f"perceived graph: {p.message}" for p in problems]
    objects = [DetectedObject(id=det.id, label=det.label, colour=det.colour,
                              box=(det.region.x0, det.region.y0, det.region.x1, det.region.y1),
                              score=det.score) for det in detections]
    return PerceptionResult(graph=graph, view="tabletop", family=family,
                            labeller=labeller.name, objects=objects, warnings=warnings,
                            scale=scene.scale)


def perceive(image: Any, dictionary: Dictionary | str | None = None, task: str | None = None,
             **options: Any) -> SceneGraph:
    """Scene graph of a BGR image: the entry point `verigraph.tools` looks up.

    `task` is accepted for the VLM path's signature and ignored by the detectors;
    `options` go to `perceive_image` (config, labeller). Warnings are logged.
    """
    return perceive_image(image, dictionary=dictionary, **options).graph
