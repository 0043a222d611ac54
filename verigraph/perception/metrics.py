"""Scene-graph generation metrics of the paper's Table 1: node F1, edge F1, exact match.

A perceived graph may name a second plate `plate_2` where the truth says `plate`, so
nodes are matched by what they are (label and colour), and ids of look-alike objects
are assigned to make the most edges agree. Tangram contacts are compared up to each
piece's rotational symmetry (a square's side 0 is any of its sides), as goals are.

>>> from verigraph.graph.model import SceneGraph
>>> g = SceneGraph.model_validate({"nodes": [{"id": "t", "label": "table"},
...     {"id": "b", "label": "book"}], "edges": [{"source": "b", "relation": "on",
...     "target": "t"}]})
>>> score_graph(g, g).exact
True
"""

from __future__ import annotations

import itertools
from collections import Counter, defaultdict
from collections.abc import Iterable, Sequence

from pydantic import BaseModel, Field

from verigraph.graph.dictionary import Dictionary, load_dictionary
from verigraph.graph.model import Edge, Node, SceneGraph

EdgeKey = tuple[str, str, str, int | None, int | None]
MAX_PERMUTATIONS = 720


class GraphScore(BaseModel):
    """How one perceived graph compares with the truth."""

    node_precision: float
    node_recall: float
    node_f1: float
    edge_precision: float
    edge_recall: float
    edge_f1: float
    exact: bool
    mapping: dict[str, str] = Field(default_factory=dict,
                                    description="perceived id -> true id")


class SggSummary(BaseModel):
    """Mean scores over many images (the numbers of one table cell)."""

    images: int
    node_f1: float
    edge_f1: float
    exact: float


def node_key(node: Node) -> tuple[str, str]:
    """What a node is, regardless of its id: label and colour (if it has one)."""
    colour = node.attrs.get("color")
    return node.label, str(colour).lower() if isinstance(colour, str) else ""


def _f1(tp: int, n_pred: int, n_true: int) -> tuple[float, float, float]:
    precision = tp / n_pred if n_pred else (1.0 if n_true == 0 else 0.0)
    recall = tp / n_true if n_true else (1.0 if n_pred == 0 else 0.0)
    f1 = 2 * precision * recall / (precision + recall) if precision + recall else 0.0
    return precision, recall, f1


def _symmetries(graph: SceneGraph, dictionary: Dictionary) -> dict[str, tuple[int, int]]:
    out = {}
    for n in graph.nodes:
        label = dictionary.resolve(n.label)
        if label is None:
            continue
        props = dictionary.objects[label]
        if props.sides and props.symmetry > 1:
            out[n.id] = (props.symmetry, props.sides)
    return out


def _variants(keys: set[EdgeKey], symmetry: dict[str, tuple[int, int]]) -> Iterable[set[EdgeKey]]:
    """The edge set under every rotation of the symmetric pieces' side numbers."""
    pieces = sorted(symmetry)
    for shifts in itertools.product(*[range(symmetry[p][0]) for p in pieces]):
        shift = dict(zip(pieces, shifts, strict=True))
        out = set()
        for s, rel, t, ss, ts in keys:
            if rel == "touches":
                if s in shift and ss is not None:
                    order, sides = symmetry[s]
                    ss = (ss + shift[s] * sides // order) % sides
                if t in shift and ts is not None:
                    order, sides = symmetry[t]
                    ts = (ts + shift[t] * sides // order) % sides
                out.add(Edge(source=s, relation=rel, target=t, source_side=ss,
                             target_side=ts).key())
            else:
                out.add((s, rel, t, ss, ts))
        yield out


def _mappings(pred: SceneGraph, truth: SceneGraph) -> Iterable[dict[str, str]]:
    """Candidate id maps from perceived to true nodes with the same key."""
    pred_groups: dict[tuple[str, str], list[str]] = defaultdict(list)
    true_groups: dict[tuple[str, str], list[str]] = defaultdict(list)
    for n in pred.nodes:
        pred_groups[node_key(n)].append(n.id)
    for n in truth.nodes:
        true_groups[node_key(n)].append(n.id)
    fixed: dict[str, str] = {}
    choices: list[list[list[tuple[str, str]]]] = []
    for key, ids in pred_groups.items():
        targets = true_groups.get(key, [])
        if len(ids) == 1 and len(targets) <= 1:
            if targets:
                fixed[ids[0]] = targets[0]
            continue
        k = min(len(ids), len(targets))
        options = [list(zip(ids, perm, strict=False))
                   for perm in itertools.permutations(targets, k)][:MAX_PERMUTATIONS]
        choices.append(options or [[]])
    if not choices:
        yield fixed
        return
    for combo in itertools.islice(itertools.product(*choices), MAX_PERMUTATIONS):
        mapping = dict(fixed)
        for pairs in combo:
            mapping.update(pairs)
        yield mapping


def score_graph(pred: SceneGraph, truth: SceneGraph,
                dictionary: Dictionary | str | None = None) -> GraphScore:
    """Node F1, edge F1 and exact match of a perceived graph against the truth."""
    d = load_dictionary(dictionary if dictionary is not None else truth.dictionary)
    pred_keys = Counter(node_key(n) for n in pred.nodes)
    true_keys = Counter(node_key(n) for n in truth.nodes)
    node_tp = sum((pred_keys & true_keys).values())
    np_, nr, nf = _f1(node_tp, len(pred.nodes), len(truth.nodes))
    true_edges = truth.edge_keys()
    symmetry = _symmetries(truth, d)
    best: tuple[int, dict[str, str], set[EdgeKey]] | None = None
    for mapping in _mappings(pred, truth):
        renamed = {_rename(k, mapping) for k in pred.edge_keys()}
        for variant in _variants(renamed, symmetry):
            tp = len(variant & true_edges)
            if best is None or tp > best[0]:
                best = (tp, mapping, variant)
            if tp == len(true_edges) == len(variant):
                break
    assert best is not None
    edge_tp, mapping, renamed_edges = best
    ep, er, ef = _f1(edge_tp, len(pred.edges), len(true_edges))
    exact = (pred_keys == true_keys and renamed_edges == true_edges
             and len(pred.edges) == len(truth.edges))
    return GraphScore(node_precision=np_, node_recall=nr, node_f1=nf, edge_precision=ep,
                      edge_recall=er, edge_f1=ef, exact=exact, mapping=mapping)


def _rename(key: EdgeKey, mapping: dict[str, str]) -> EdgeKey:
    s, rel, t, ss, ts = key
    edge = Edge(source=mapping.get(s, f"?{s}"), relation=rel, target=mapping.get(t, f"?{t}"),
                source_side=ss, target_side=ts)
    return edge.key()


def summarise(scores: Sequence[GraphScore]) -> SggSummary:
    """Means over images (each image weighs the same, as in the paper's table)."""
    n = len(scores)
    if n == 0:
        return SggSummary(images=0, node_f1=0.0, edge_f1=0.0, exact=0.0)
    return SggSummary(images=n, node_f1=sum(s.node_f1 for s in scores) / n,
                      edge_f1=sum(s.edge_f1 for s in scores) / n,
                      exact=sum(s.exact for s in scores) / n)
