"""image -> scene graph: lighting, colour classes, the view's detector, the graph.

`perceive_image` returns everything a caller may want to show (warnings, timings, the
detections); `perceive` is the narrow form the tools layer calls.
"""

from __future__ import annotations

import logging
import time
from typing import Any

import numpy as np

from verigraph.graph.dictionary import (
    BUILTIN_DICTIONARIES,
    Dictionary,
    builtin_dictionary,
    load_dictionary,
)
from verigraph.graph.model import SceneGraph
from verigraph.graph.wellformed import check_well_formed
from verigraph.perception.config import PerceptionConfig
from verigraph.perception.correct.deblur import restore
from verigraph.perception.correct.noise import BLURRED, SOFT, blur_warning, denoise, sharpness
from verigraph.perception.correct.photometry import correct_colours
from verigraph.perception.correct.roll import MIN_DEGREES as ROLL_NOTE
from verigraph.perception.correct.roll import estimate_roll, unroll
from verigraph.perception.detect import colors
from verigraph.perception.detect.occlusion import (
    Occluder,
    area_occluders,
    find_occluders,
    hidden_mask,
    occluded_by,
    unexplained_areas,
)
from verigraph.perception.detect.tabletop import Detection, detect_tabletop
from verigraph.perception.detect.tangram import perceive_tangram
from verigraph.perception.imageio import as_bgr
from verigraph.perception.label.catalogue import models_by_colour
from verigraph.perception.label.labelling import ColourShapeLabeller, Labeller, Shape, shape_error
from verigraph.perception.relate.confidence import edge_name, graph_confidence, upright_doubts
from verigraph.perception.relate.graphing import assign_ids, tabletop_graph
from verigraph.perception.relate.household import household_kinds, read_household
from verigraph.perception.relate.occluded import (
    HIDDEN_REASON,
    blocked_views,
    merge_doubts,
    occlusion_doubts,
)
from verigraph.perception.relate.plausible import (
    furniture_on_objects,
    plausibility_doubts,
    unoutlined_doubts,
    wall_on_floor,
)
from verigraph.perception.relate.support import infer_supports, label_map
from verigraph.perception.result import DetectedObject, PerceptionResult
from verigraph.perception.views import FAMILY_ORDER, choose_view, family_of
from verigraph.sim2d import palette

log = logging.getLogger("verigraph.perception")

DEFAULT_CONFIG = PerceptionConfig()
DEFAULT_LABELLER = ColourShapeLabeller()
UNKNOWN_COLOURS = "have colours no dictionary object is drawn in"
UNION = "all"
HOUSEHOLD = "household"  # load_dictionary(None): the built-ins together; the family is inferred
FAMILY_MARGIN = 0.03
ILL_FORMED_PENALTY = 0.05
SHAPE_PENALTY = 0.1  # per unit of mean shape error: a red block is no mug by its outline


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
    level = sharpness(bgr)
    bgr, noisy = denoise(bgr)
    restored = restore(bgr, level, noisy=noisy) if level < BLURRED else None
    if restored is not None:
        bgr = restored.image
    blurred = blur_warning(level) if restored is None else None
    view = choose_view(bgr, d, config.view)
    if view == "tangram":
        result = perceive_tangram(bgr, d, config, labeller)
    elif d.name == UNION:
        result = _choose_family(bgr, config, labeller, level < SOFT, restored is not None)
    else:
        result = _perceive_tabletop(bgr, d, config, labeller, level < SOFT,
                                    restored is not None)
    if result.view == "tabletop":
        _add_household(result, bgr, d)
    if blurred is not None:
        result.warnings.insert(0, blurred)
    if restored is not None:
        result.restored = restored.note()
    if not result.family_reason:
        result.family_reason = (
            f"{result.family}: the dictionary given" if d.name != UNION else
            f"{result.family}: a top view of coloured pieces on a neutral table"
            if view == "tangram" else f"{result.family}: the objects seen")
    result.seconds = time.perf_counter() - start
    for w in result.warnings:
        log.warning("perception: %s", w)
    return result


def _add_household(result: PerceptionResult, bgr: np.ndarray, d: Dictionary) -> None:
    """Household furniture, doors and switches (`relate.household`): new nodes, states
    with their confidences, doubts and a note. A render with none of them is unchanged."""
    if d.name == UNION:  # the union of the tabletop families: a household is told by
        d = builtin_dictionary(HOUSEHOLD)  # its own colours, doors and lamps
    elif not household_kinds(d):
        return
    reading = read_household(bgr, d, result.objects, result.scale)
    if reading.found or any(UNKNOWN_COLOURS in w for w in result.warnings):
        # Colours off the renderer's (white balance, gamma, a tint): read the picture
        # again after a tone map fitted to the palette and household colours together.
        colours = [*palette.COLORS.values(), *palette.HOUSEHOLD_COLORS.values(),
                   palette.DOOR, palette.LIT]
        photo = correct_colours(bgr, colours, palette.BACKGROUND,
                                [palette.BACKGROUND, palette.FLOOR])
        if photo.image is not bgr:
            again = read_household(photo.image, d, result.objects, result.scale)
            if again.sure > reading.sure:
                reading = again
    if not reading.found:
        return
    if reading.nodes and result.family != HOUSEHOLD:
        result.family = HOUSEHOLD
        result.graph.dictionary = HOUSEHOLD
        result.family_reason = ("household: household furniture is seen (" + ", ".join(
            sorted(n.id for n in reading.nodes)) + ")")
    result.graph.nodes.extend(reading.nodes)
    result.objects.extend(reading.objects)
    for node in result.graph.nodes:
        if node.id in reading.states:
            node.state = {**node.state, **reading.states[node.id]}
    result.confidence.update(reading.confidence)
    result.uncertain.extend(reading.uncertain)
    result.warnings.extend(reading.warnings)


def _perceive_tabletop(bgr: np.ndarray, d: Dictionary, config: PerceptionConfig,
                       labeller: Labeller, soft: bool = False,
                       restored: bool = False) -> PerceptionResult:
    """A side view; `soft`: the picture is blurred (thin objects are checked by shape);
    `restored`: its motion blur was undone (the detector reads white and silver
    pockets accordingly)."""
    models = models_by_colour(d)
    table = colors.colour_table(tuple(sorted(models)), tangram=False)
    photo = correct_colours(bgr, [c for i, c in enumerate(table.bgr) if i not in
                                  (colors.UNKNOWN, colors.MIXED)],
                            palette.BACKGROUND, [palette.BACKGROUND, palette.FLOOR])
    corrected = photo.image
    classes = colors.classify(corrected, table)
    notes = list(photo.notes)
    degrees = estimate_roll(classes)
    if degrees is not None and abs(degrees) >= ROLL_NOTE:
        corrected = unroll(corrected, degrees)
        classes = colors.classify(corrected, table)
        notes.append(f"the camera is rolled {degrees:+.1f} degrees (the floor line is not "
                     "level); the image was turned back before supports were read")
    colors.refine_edges(corrected, classes, table)
    occluders = find_occluders(corrected, [palette.BACKGROUND, palette.FLOOR],
                               _object_colours(table))
    hidden = hidden_mask(occluders, classes.shape)
    if hidden is not None:
        classes[hidden] = colors.UNKNOWN  # no object is read off an occluder's pixels
    scene = detect_tabletop(corrected, classes, table, models, labeller, config, occluders,
                            restored=restored)
    detections = scene.detections
    warnings = notes + list(scene.warnings)
    if not detections:
        warnings.append("no objects of the dictionary were found in the image")
    assign_ids(detections)
    labels = label_map(classes.shape, detections, scene.floor_row)
    supports = infer_supports(detections, labels, gap=config.contact_gap, scale=scene.scale)
    misread = furniture_on_objects(detections, supports)
    if misread:
        # Furniture stands on the floor: a "counter" standing on a stove is something in
        # front of the scene in a furniture colour. It is not emitted; what it touches
        # is named below as behind an area in front.
        for i in misread:
            det = detections[i]
            r = det.region
            warnings.append(
                f"a region in the {det.colour} of a {det.label} (box {r.x0}, {r.y0}, {r.x1}, "
                f"{r.y1}) stands on {supports[det.id][1]}, but a {det.label} stands on the "
                "floor: it is something in front of the scene, or a misreading, and is not "
                "reported as an object")
            occluders.append(Occluder("area", (r.x0, r.y0, r.x1, r.y1), r.mask.copy()))
        detections = [det for i, det in enumerate(detections) if i not in misread]
        assign_ids(detections)
        labels = label_map(classes.shape, detections, scene.floor_row)
        supports = infer_supports(detections, labels, gap=config.contact_gap,
                                  scale=scene.scale)
    family = family_of({det.label for det in detections}, d)
    name = family if family is not None else (d.name if d.name in BUILTIN_DICTIONARIES
                                              else None)
    graph = tabletop_graph(detections, supports, name)
    problems = check_well_formed(graph, d)
    warnings += [f"perceived graph: {p.message}" for p in problems]
    regions = [det.region for det in detections]
    leftover, explained = unexplained_areas(classes, regions, scene.floor_row,
                                            _min_unexplained(scene.scale), hidden)
    unexplained = [(r.x0, r.y0, r.x1, r.y1) for r in leftover]
    ids = [det.id for det in detections]
    areas = area_occluders(leftover, corrected)
    if unexplained:
        boxes = ", ".join(f"{b}" for b in unexplained[:4])
        near = sorted({ids[i] for hits in occluded_by(areas, regions, classes.shape)
                       for i in hits})
        warnings.append(f"{len(unexplained)} area(s) of the image are not explained by any "
                        f"detected object (boxes x0, y0, x1, y1: {boxes}); something unknown, "
                        "or an object that was missed, is there"
                        + (f"; it borders {', '.join(near)}" if near else ""))
    confidence, uncertain = graph_confidence(graph, detections, corrected, table,
                                             scene.scale, floor_row=scene.floor_row,
                                             soft=soft)
    hiding, doubts, occluded = occlusion_doubts(
        graph, ids, regions, occluders + areas, classes.shape,
        edge_name=lambda e: edge_name(e.source, e.relation, e.target))
    warnings += hiding[:len(occluders)]  # the areas' warning is the one above
    rolled = degrees is not None and abs(degrees) >= ROLL_NOTE  # its corners are filled
    floor_notes, floor_doubts = wall_on_floor(graph, detections, classes == colors.BACKGROUND,
                                              None if rolled else scene.floor_row)
    warnings += floor_notes
    merge_doubts(confidence, uncertain, doubts + floor_doubts + upright_doubts(graph, detections)
                 + plausibility_doubts(graph, detections, d, classes.shape)
                 + ([] if soft or restored else  # blur takes the outlines away
                    unoutlined_doubts(graph, detections, corrected,
                                      classes == colors.BACKGROUND)))
    objects = [DetectedObject(id=det.id, label=det.label, colour=det.colour,
                              box=(det.region.x0, det.region.y0, det.region.x1, det.region.y1),
                              score=det.score) for det in detections]
    return PerceptionResult(graph=graph, view="tabletop", family=family,
                            labeller=labeller.name, objects=objects, warnings=warnings,
                            confidence=confidence, uncertain=uncertain, scale=scene.scale,
                            explained=explained, occluded=occluded,
                            blocked=blocked_views(occluders + areas, ids, regions,
                                                  classes.shape),
                            shape_error=_shape_error(detections, scene.scale))


def _choose_family(bgr: np.ndarray, config: PerceptionConfig,
                   labeller: Labeller, soft: bool = False,
                   restored: bool = False) -> PerceptionResult:
    """Perceive with each tabletop family's dictionary and keep the one that explains
    the picture best (share of the scene its objects account for, less a penalty per
    ill-formed fact and per uncertain object, and a penalty for outlines that fit their
    labels badly); refuse (empty graph, a warning naming both) when two come within
    `FAMILY_MARGIN` of each other."""
    tried = []
    for name in FAMILY_ORDER:
        result = _perceive_tabletop(bgr, builtin_dictionary(name), config, labeller, soft,
                                    restored)
        problems = sum(w.startswith("perceived graph:") for w in result.warnings)
        problems += sum(" " not in u.item and not u.reason.startswith(HIDDEN_REASON)
                        for u in result.uncertain)  # doubtful objects (not what is hidden)
        fit = (result.explained - ILL_FORMED_PENALTY * problems
               - SHAPE_PENALTY * result.shape_error) if result.objects else 0.0
        tried.append((fit, name, result))
    tried.sort(key=lambda t: -t[0])
    (best, name, result), (second, other, _) = tried[0], tried[1]
    scores = ", ".join(f"{n} {f:.2f}" for f, n, _ in tried)
    if best - second < FAMILY_MARGIN:
        return PerceptionResult(
            graph=SceneGraph(), view="tabletop", family=None, labeller=labeller.name,
            family_reason=f"refused: {name} and {other} explain the picture about equally "
                          f"(share of the scene explained: {scores})",
            warnings=[f"the picture fits the {name} and {other} families about equally "
                      f"({scores}); give the dictionary (--family) to perceive it"])
    result.family_reason = (f"{name}: its objects explain the most of the picture "
                            f"(share of the scene explained: {scores})")
    return result


def _object_colours(table: colors.ColourTable) -> list[tuple[int, int, int]]:
    """BGR of the colour classes objects are drawn in (not wall, floor, outline)."""
    return [table.bgr[c] for c in table.object_classes]


def _shape_error(detections: list[Detection], scale: float) -> float:
    """Mean shape error of the movable objects (how well outlines fit their labels)."""
    errors = [shape_error(Shape.of(d.region), d.model, scale) for d in detections
              if not d.model.fixed]
    return float(np.mean(errors)) if errors and scale > 0 else 0.0


def _min_unexplained(scale: float) -> int:
    """Smallest unexplained area worth a warning: a square of 1.5 world units (about a
    spoon's bowl), at least 40 px."""
    return max(40, int((1.5 * scale) ** 2)) if scale > 0 else 150


def perceive(image: Any, dictionary: Dictionary | str | None = None, task: str | None = None,
             **options: Any) -> SceneGraph:
    """Scene graph of a BGR image: the entry point `verigraph.tools` looks up.

    `task` is accepted for the VLM path's signature and ignored by the detectors;
    `options` go to `perceive_image` (config, labeller). Warnings are logged.
    """
    return perceive_image(image, dictionary=dictionary, **options).graph
