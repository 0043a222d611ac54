"""Tangram detector (top view): seven coloured pieces, their sides and their contacts.

Each piece colour is one piece. Its pixels give a convex outline, which
`cv2.approxPolyN` reduces to the piece's number of corners; the corners are ordered
clockwise from the canonical vertex, the exact piece model is fitted onto them, and
every pair of facing, collinear, overlapping sides becomes a `touches` edge with both
side indices.
"""

from __future__ import annotations

import math

import cv2
import numpy as np

from verigraph.graph.dictionary import Dictionary
from verigraph.graph.model import Edge, Node, SceneGraph
from verigraph.perception.config import PerceptionConfig
from verigraph.perception.correct.photometry import correct_colours
from verigraph.perception.detect import colors
from verigraph.perception.detect.occlusion import TOUCH, find_occluders, hidden_mask
from verigraph.perception.detect.regions import Region, colour_fragments
from verigraph.perception.detect.tangram_hidden import complete_piece, drawn_offset
from verigraph.perception.detect.tangram_sides import (
    PlacedPiece,
    borderline,
    canonical_start,
    clockwise,
    contact_share,
    contacts,
    fit_model,
    to_world,
)
from verigraph.perception.label.catalogue import ObjectModel
from verigraph.perception.label.labelling import Labeller
from verigraph.perception.relate.occluded import blocked_views, merge_doubts, occlusion_doubts
from verigraph.perception.result import (
    CONFIDENT,
    DetectedObject,
    PerceptionResult,
    Uncertain,
    add_edge_confidence,
)
from verigraph.sim2d import palette
from verigraph.sim2d.tangram_geometry import piece_model, signed_area

MAX_FIT_ERROR = 0.35  # RMS corner error (world units) before a shape is called odd
MIN_PIECE_PIXELS = 60  # a small triangle covers several hundred pixels even at 320x240
MIN_FILL = 0.8  # share of a piece's outline its colour must fill
REJECT_FIT_ERROR = 1.0  # beyond this the region is not that piece at all (e.g. noise)
# Pieces drawn early lose half an outline along edges later pieces share, so their
# areas understate the scale; the upper part of the distribution is the honest one.
SCALE_PERCENTILE = 80
GAP_SAMPLES = 7
# Two sharply fitted pieces (both within SHARP_FIT units of their exact shape) whose
# facing sides lie more than HIDDEN_GAP apart leave a gap, even where the outlines
# fill it: on sharp pictures touching sides measure at most ~0.17 units apart (the
# later piece's outline eats into the earlier one), a quarter-unit gap ~0.22 or more.
SHARP_FIT = 0.08
HIDDEN_GAP = 0.195
# A contact made by aligning two sides (the align action puts their midpoints together)
# covers the shorter side wholly: measured, at least 0.94 of it on 3,300 clean figures.
# Sides that merely run side by side across a gap the outlines fill (a small triangle
# or the square sliding past a neighbour) overlap by part of their length only.
FULL_CONTACT = 0.92
PARTIAL = 0.4  # confidence of a contact that covers only part of the shorter side


def piece_models(dictionary: Dictionary) -> list[ObjectModel]:
    """The tangram pieces of a dictionary as labeller candidates."""
    out = []
    for label, props in sorted(dictionary.objects.items()):
        if props.sides is None or not props.color:
            continue
        try:
            model = piece_model(label)
        except KeyError:
            continue
        xs, ys = [x for x, _ in model], [y for _, y in model]
        perimeter = sum(math.dist(model[i], model[(i + 1) % len(model)])
                        for i in range(len(model)))
        out.append(ObjectModel(label=label, colour=props.color.strip().lower(),
                               fixed=False, width=max(xs) - min(xs), height=max(ys) - min(ys),
                               area=abs(signed_area(model)), perimeter=perimeter,
                               container=False, surface=False, own_colour=True))
    return out


def _largest_per_colour(fragments: list[Region]) -> dict[int, Region]:
    best: dict[int, Region] = {}
    for r in fragments:
        if r.cls not in best or r.area > best[r.cls].area:
            best[r.cls] = r
    return best


def piece_outline(region: Region, sides: int) -> np.ndarray | None:
    """Convex polygon with `sides` corners around a region, in pixel coordinates."""
    pts = region.points().astype(np.float32)
    if len(pts) < sides:
        return None
    hull = cv2.convexHull(pts)
    if len(hull) < sides:  # a sliver (what an occluder left of a piece) has too few corners
        return None
    poly = cv2.approxPolyN(hull, sides, epsilon_percentage=-1, ensure_convex=True)
    poly = np.asarray(poly, dtype=np.float64).reshape(-1, 2)
    if len(poly) != sides:
        return None
    return poly + 0.5  # pixel centres -> pixel area


def perceive_tangram(image: np.ndarray, dictionary: Dictionary, config: PerceptionConfig,
                     labeller: Labeller) -> PerceptionResult:
    """What a top-view tangram image shows."""
    warnings: list[str] = []
    models = piece_models(dictionary)
    if not models:
        raise ValueError("the dictionary has no tangram pieces with known shapes")
    colour_names = tuple(sorted({m.colour for m in models}))
    table = colors.colour_table(colour_names, tangram=True)
    photo = correct_colours(image, [c for i, c in enumerate(table.bgr)
                                    if i not in (colors.UNKNOWN, colors.MIXED, colors.FLOOR)],
                            palette.TANGRAM_BACKGROUND, [palette.TANGRAM_BACKGROUND])
    corrected = photo.image
    warnings += photo.notes
    classes = colors.classify(corrected, table)
    occluders = find_occluders(corrected, [palette.TANGRAM_BACKGROUND],
                               [table.bgr[c] for c in table.object_classes])
    hidden = hidden_mask(occluders, classes.shape)
    if hidden is not None:
        classes[hidden] = colors.UNKNOWN  # no piece is read off an occluder's pixels
    fragments = colour_fragments(corrected, classes, table, min_core=config.min_core_pixels)
    pieces = _largest_per_colour(fragments)
    cut: set[int] = set()  # colours of pieces partly under an occluder
    if hidden is not None:
        pieces, cut = _parts_around(fragments, pieces, hidden)
    found: list[tuple[ObjectModel, np.ndarray]] = []
    pending: list[tuple[ObjectModel, Region]] = []  # pieces to complete under an occluder
    regions = [pieces[c] for c in sorted(pieces)]
    colours = [table.names[c] for c in sorted(pieces)]
    labels = labeller.label(corrected, regions, colours, models, 0.0)
    objects: dict[str, DetectedObject] = {}
    seen: dict[str, Region] = {}
    for region, colour, (model, score) in zip(regions, colours, labels, strict=True):
        if model.label in objects:
            warnings.append(f"two regions look like {model.label}; kept the first")
            continue
        objects[model.label] = DetectedObject(id=model.label, label=model.label,
                                              colour=model.colour,
                                              box=(region.x0, region.y0, region.x1, region.y1),
                                              score=score)
        seen[model.label] = region
        if region.cls in cut and region.area >= MIN_PIECE_PIXELS:
            pending.append((model, region))
            continue
        poly, drop = _outline_of(region, model, colour, warnings)
        if drop:
            objects.pop(model.label, None)
        if poly is not None:
            found.append((model, poly))
    scale = _scale(found)
    if scale <= 0 and pending:  # every piece is cut: what shows of them gives the scale
        shown = [(model, piece_outline(region, len(piece_model(model.label))))
                 for model, region in pending]
        scale = _scale([(model, poly) for model, poly in shown if poly is not None])
    placed: dict[str, PlacedPiece] = {}
    for model, poly in found:
        if scale <= 0:
            break
        piece = _place(model, poly, scale, warnings)
        if piece is None:
            objects.pop(model.label, None)
        else:
            placed[model.label] = piece
    # The drawn fill's sides lie a little in or out of the model's at this scale (the
    # outlines): pieces in full view show how far, for the cut ones that cannot.
    inset = drawn_offset([(_pixels(placed[m.label], scale), seen[m.label].mask,
                           (seen[m.label].x0, seen[m.label].y0))
                          for m, _ in found if m.label in placed]) if pending else 0.0
    completed: list[str] = []  # pieces whose hidden sides were read from what shows ...
    settled: list[str] = []  # ... where no other placement explains it as well
    for model, region in pending:
        assert hidden is not None  # a piece is pending only where an occluder cuts it
        completion = complete_piece(model.label, _full_mask(region, classes.shape), hidden,
                                    scale, inset)
        if completion is not None:
            poly = completion.corners
        else:
            poly, drop = _outline_of(region, model, table.names[region.cls], warnings)
            if drop:
                objects.pop(model.label, None)
        if poly is None:
            continue
        piece = _place(model, poly, scale, warnings)
        if piece is None:
            objects.pop(model.label, None)
            continue
        placed[model.label] = piece
        if completion is not None:
            completed.append(model.label)
            if completion.settled:
                settled.append(model.label)
    ids = sorted(placed)
    edges = []
    unsure: list[str] = []
    partial: list[Uncertain] = []
    tolerances = {"max_angle": math.radians(config.side_angle_degrees),
                  "max_distance": config.side_distance, "min_overlap": config.side_overlap}
    for i, a in enumerate(ids):
        for b in ids[i + 1:]:
            # A completed piece's hidden sides are inferred, not seen sharply: the hidden
            # gap test, which needs both pieces' sides where they sit, does not apply.
            whole = a not in completed and b not in completed
            touching = [pair for pair in contacts(placed[a], placed[b], **tolerances)
                        if not gap_visible(classes, scale, placed[a], placed[b], pair)
                        and not (whole and hidden_gap(placed[a], placed[b], pair))]
            for sa, sb in touching:
                edges.append(Edge(source=a, relation="touches", target=b, source_side=sa,
                                  target_side=sb))
                share = contact_share(placed[a], placed[b], (sa, sb))
                if share < FULL_CONTACT:
                    partial.append(Uncertain(
                        item=f"{a} touches {b} ({sa}, {sb})", confidence=PARTIAL,
                        reason=f"the sides meet along {share:.0%} of the shorter one only: "
                               "sides aligned to touch meet along all of it; these may run "
                               "side by side across a gap the outlines hide"))
            for sa in range(len(placed[a].vertices)):
                for sb in range(len(placed[b].vertices)):
                    if borderline(placed[a], placed[b], (sa, sb), **tolerances):
                        unsure.append(f"{a} touches {b} ({sa}, {sb})")
    nodes = [Node(id=p, label=p, attrs={"color": objects[p].colour}) for p in ids]
    if not nodes:
        warnings.append("no tangram pieces were found in the image")
    graph = SceneGraph(nodes=nodes, edges=edges, dictionary="tangram").canonical()
    confidence, uncertain = _confidence(graph, placed, objects)
    uncertain += [Uncertain(item=name, confidence=0.4, reason="the sides lie near the "
                            "limit of touching; the picture cannot tell whether they touch")
                  for name in unsure]
    merge_doubts(confidence, uncertain, partial)
    occluded: list[str] = []
    if occluders:
        # Pieces rejected for their shape are named too: the occluder may be why.
        hiding, doubts, occluded = occlusion_doubts(
            graph, list(seen), list(seen.values()), occluders, classes.shape,
            edge_name=_contact_name, supports=False, completed=settled)
        warnings += hiding
        missing = sorted(set(m.label for m in models) - set(placed))
        if missing:
            warnings.append(f"not seen: {', '.join(missing)}; they may be behind what is in "
                            "front of the table")
            # A piece wholly behind the occluder touches nothing seen: it is named too.
            occluded = sorted(set(occluded) | set(missing))
        merge_doubts(confidence, uncertain, doubts)
    return PerceptionResult(graph=graph, view="tangram", family="tangram",
                            labeller=labeller.name, objects=[objects[p] for p in ids],
                            warnings=warnings, scale=scale, confidence=confidence,
                            uncertain=uncertain, occluded=occluded,
                            blocked=blocked_views(occluders, list(seen), list(seen.values()),
                                                  classes.shape))


def _place(model: ObjectModel, poly: np.ndarray, scale: float, warnings: list[str]
           ) -> PlacedPiece | None:
    """The piece's exact model fitted onto an outline's corners (pixels), or None when
    the outline is too far from the piece's shape (`REJECT_FIT_ERROR`; with a warning)."""
    corners = clockwise(to_world(poly, scale))
    start, flipped = canonical_start(model.label, corners)
    corners = np.roll(corners, -start, axis=0)
    piece = fit_model(model.label, corners)
    if flipped:
        warnings.append(f"{model.label} looks mirrored; tangram pieces are never flipped")
    if piece.fit_error > REJECT_FIT_ERROR:
        warnings.append(f"the {model.colour} region is not a {model.label} "
                        f"({piece.fit_error:.2f} units off its shape); ignored")
        return None
    if piece.fit_error > MAX_FIT_ERROR:
        warnings.append(f"{model.label} fits its shape poorly "
                        f"({piece.fit_error:.2f} units off)")
    return piece


def _pixels(piece: PlacedPiece, scale: float) -> np.ndarray:
    """A placed piece's corners in pixels (x right, y down)."""
    out = np.array(piece.vertices, dtype=np.float64) * scale
    out[:, 1] *= -1
    return out


def _outline_of(region: Region, model: ObjectModel, colour: str, warnings: list[str]
                ) -> tuple[np.ndarray | None, bool]:
    """The polygon a piece's region outlines (None when it does not look like the
    piece, with a warning), and whether the region is no piece at all (too small, or
    not solid)."""
    poly = piece_outline(region, len(piece_model(model.label)))
    if poly is None:
        warnings.append(f"the {colour} region does not look like a {model.label}")
        return None, False
    if region.area < MIN_PIECE_PIXELS:
        warnings.append(f"the {colour} region is too small for a piece "
                        f"({region.area} px); ignored")
        return None, True
    filled = region.area / max(abs(float(cv2.contourArea(poly.astype(np.float32)))), 1.0)
    if filled < MIN_FILL:
        # A piece is a solid polygon; scattered specks of its colour (noise, texture)
        # are not, however well their outline happens to fit.
        warnings.append(f"the {colour} region is not solid ({filled:.0%} filled); ignored")
        return None, True
    return poly, False


def _parts_around(fragments: list[Region], pieces: dict[int, Region], hidden: np.ndarray
                  ) -> tuple[dict[int, Region], set[int]]:
    """The pieces with every part of their colour that meets an occluder (`hidden`)
    joined to them (each colour is one piece, so parts of it on both sides of a bar
    are that piece), and the colours of the pieces an occluder meets."""
    near = cv2.dilate(hidden.view(np.uint8), np.ones((2 * TOUCH + 1,) * 2, np.uint8))
    out = dict(pieces)
    cut: set[int] = set()
    for part in fragments:
        if not np.any(near[part.y0:part.y1, part.x0:part.x1][part.mask]):
            continue
        cut.add(part.cls)
        if part is not pieces.get(part.cls):
            out[part.cls] = out[part.cls].merged(part)
    return out, cut


def _full_mask(region: Region, shape: tuple[int, int]) -> np.ndarray:
    out = np.zeros(shape, bool)
    out[region.y0:region.y1, region.x0:region.x1] = region.mask
    return out


def _contact_name(e: Edge) -> str:
    return f"{e.source} touches {e.target} ({e.source_side}, {e.target_side})"


def _confidence(graph: SceneGraph, placed: dict[str, PlacedPiece],
                objects: dict[str, DetectedObject]) -> tuple[dict[str, float], list[Uncertain]]:
    """A piece is as sure as its labelling and its shape fit (falling to 0 at the
    rejection error); a contact as its less sure piece."""
    confidence: dict[str, float] = {}
    uncertain: list[Uncertain] = []
    for label, piece in placed.items():
        fit = max(0.0, 1.0 - max(0.0, piece.fit_error - MAX_FIT_ERROR / 2) / REJECT_FIT_ERROR)
        value = round(min(objects[label].score, fit), 3)
        confidence[label] = value
        if value < CONFIDENT:
            uncertain.append(Uncertain(item=label, confidence=value,
                                       reason=f"its outline is {piece.fit_error:.2f} units "
                                              "off the piece's shape"))
    add_edge_confidence(graph, confidence, uncertain, _contact_name, "pieces")
    return confidence, uncertain


def _scale(found: list[tuple[ObjectModel, np.ndarray]]) -> float:
    """Pixels per world unit: the median over pieces of sqrt(pixel area / model area)."""
    ratios = [math.sqrt(abs(float(cv2.contourArea(poly.astype(np.float32)))) / m.area)
              for m, poly in found if m.area > 0]
    return float(np.percentile(ratios, SCALE_PERCENTILE)) if ratios else 0.0


def gap_visible(classes: np.ndarray, scale: float, a: PlacedPiece, b: PlacedPiece,
                sides: tuple[int, int]) -> bool:
    """Whether the table shows between two sides the fit calls touching: most points
    halfway between them are background. Touching pieces share one outline there; a
    gap of a quarter unit leaves table between two outlines, which the fitted models
    (placed within a few tenths of a unit) cannot tell from a contact."""
    i, j = sides
    p0, p1 = np.array(a.vertices[i]), np.array(a.vertices[(i + 1) % len(a.vertices)])
    q0, q1 = np.array(b.vertices[j]), np.array(b.vertices[(j + 1) % len(b.vertices)])
    direction = (p1 - p0) / max(float(np.linalg.norm(p1 - p0)), 1e-9)
    ts = sorted([0.0, float(np.linalg.norm(p1 - p0)), float((q0 - p0) @ direction),
                 float((q1 - p0) @ direction)])[1:3]  # the overlap along side i
    h, w = classes.shape
    hits = total = 0
    for t in np.linspace(ts[0], ts[1], GAP_SAMPLES + 2)[1:-1]:
        on_p = p0 + t * direction
        on_q = q0 + ((on_p - q0) @ (q1 - q0)) / max(float((q1 - q0) @ (q1 - q0)), 1e-9) \
            * (q1 - q0)
        mid = (on_p + on_q) / 2 * scale
        x, y = int(round(mid[0] - 0.5)), int(round(-mid[1] - 0.5))
        if 0 <= x < w and 0 <= y < h:
            total += 1
            hits += int(classes[y, x] == colors.BACKGROUND)
    return total > 0 and hits > total / 2


def hidden_gap(a: PlacedPiece, b: PlacedPiece, sides: tuple[int, int]) -> bool:
    """Whether a pair of sides the tolerances call touching is a gap hidden under the
    outlines: both pieces fit their shapes sharply and the sides lie farther apart
    than touching sides of sharp pieces measure (see HIDDEN_GAP). A gap of a quarter
    unit is about 3 px at the default scale, which the two pieces' drawn outlines fill
    completely: the seam between the colours is as wide as a shared outline and no
    table shows (`gap_visible` cannot see it); only where the fitted pieces sit does.
    Pieces that fit poorly (blur, noise, perspective) keep the wide tolerance: their
    touching sides can measure that far apart too. The contact stays `borderline`,
    so the result still asks for confirmation."""
    if max(a.fit_error, b.fit_error) > SHARP_FIT:
        return False
    i, j = sides
    p0, p1 = np.array(a.vertices[i]), np.array(a.vertices[(i + 1) % len(a.vertices)])
    direction = (p1 - p0) / max(float(np.linalg.norm(p1 - p0)), 1e-9)
    normal = np.array([-direction[1], direction[0]])
    ends = (np.array(b.vertices[j]), np.array(b.vertices[(j + 1) % len(b.vertices)]))
    return min(abs(float((q - p0) @ normal)) for q in ends) > HIDDEN_GAP
