"""Build verigraph/graph/data/behavior.json, the `behavior` dictionary, from the installed
`bddl` package (BEHAVIOR-1K's knowledge base, `bddl/generated_data/`).

Run it when `bddl` changes (`pip install 'verigraph-mcp[household]'` first):

    python scripts/build_behavior_dictionary.py

Nothing downloads at run time: the JSON written here is package data, read lazily the
first time a scene or a command names the `behavior` dictionary.

Every synset of the knowledge base with at least one ability becomes one kind. Its
label is its common name (docs/worlds.md, "The behavior dictionary"):
- a hand-picked everyday word where BEHAVIOR's lemma is not one (`fridge` for
  `electric_refrigerator.n.01`, `tv` for `television_receiver.n.01`),
- else the lemma, `__` read as `_` (`disinfectant__bottle.n.01` -> `disinfectant_bottle`),
- a lemma several senses share goes to the sense the activities use most (then the
  lowest sense number), the others taking `<lemma>_n<sense>` (`bag_n04`).
The lemma and the synset stay synonyms, so `electric_refrigerator.n.01_1` reads as
`fridge` and the synset is kept for reference (`synsets` in the file).

Roles from abilities (the knowledge base has no notion of a surface or of capacity):
- movable: every kind but a `sceneObject` (furniture, appliances, floors, walls);
- surface: a `sceneObject` that is no wall, ceiling, door or window (tables, counters,
  shelves, floors, beds, chairs);
- container: `fillable` or `openable`, or a heat or cold source that is no surface (a
  toaster: what it heats goes in it);
- openable, toggleable, cookable, heatable, freezable: the ability of that name;
  heat_source: `heatSource`; cold_source: `coldSource`;
- capacity: unlimited on a fixed kind; 4 on a movable surface or container;
- room: BEHAVIOR's room types (`kitchen`, `living_room`; `bar_room` and `closet_room`
  where an object kind has the word).
"""

from __future__ import annotations

import collections
import json
import os
import re
import sys
from pathlib import Path

OUT = Path(__file__).resolve().parent.parent / "verigraph" / "graph" / "data" / "behavior.json"
MOVABLE_CAPACITY = 4
# Everyday words for kinds whose BEHAVIOR lemma is not what a person says.
COMMON_NAMES = {
    "electric_refrigerator.n.01": "fridge",
    "television_receiver.n.01": "tv",
    "deep-freeze.n.02": "freezer",
    "washer.n.03": "washing_machine",
    "clothes_dryer.n.01": "dryer",
    "microwave.n.02": "microwave",
    "stove.n.01": "stove",
    "burner.n.02": "burner",
    "countertop.n.01": "countertop",
    "straight_chair.n.01": "chair",
    "pot_plant.n.01": "potted_plant",
}
# BEHAVIOR ability -> the role it gives a kind.
ROLES_OF_ABILITIES = (("openable", "openable"), ("toggleable", "toggleable"),
                      ("cookable", "cookable"), ("heatable", "heatable"),
                      ("freezable", "freezable"), ("heatSource", "heat_source"),
                      ("coldSource", "cold_source"))
NOT_SURFACES = ("wall.n.01", "ceiling.n.01", "door.n.01", "fixed_window.n.01",
                "openable_window.n.01", "gate.n.01", "rail_fence.n.01", "mirror.n.01",
                "photograph.n.01", "switch.n.01", "showerhead.n.01", "range_hood.n.01",
                "wall_clock.n.01", "wall_nail.n.01", "display_panel.n.01",
                "grandfather_clock.n.01", "tree.n.01", "scrub.n.01", "lawn.n.01",
                "driveway.n.01")
_SENSE = re.compile(r"^(?P<lemma>.+)\.n\.(?P<sense>\d+)$")


def activity_usage(definitions: Path) -> collections.Counter[str]:
    """How many activities name each synset (to give a shared lemma to the common sense)."""
    uses: collections.Counter[str] = collections.Counter()
    for activity in sorted(definitions.iterdir()):
        problem = activity / "problem0.bddl"
        if problem.is_file():
            uses.update(set(re.findall(r"[a-z0-9_\-]+\.n\.\d+", problem.read_text().lower())))
    return uses


def sense_number(synset: str) -> int:
    match = _SENSE.match(synset)
    return int(match["sense"]) if match else 0


def labels_of(synsets: list[str], uses: collections.Counter[str]) -> dict[str, str]:
    """synset -> label, one label per synset and no label twice."""
    by_lemma: dict[str, list[str]] = collections.defaultdict(list)
    for synset in synsets:
        match = _SENSE.match(synset)
        lemma = match["lemma"] if match else synset
        by_lemma[lemma.replace("__", "_").replace("-", "_").lower()].append(synset)
    labels: dict[str, str] = {}
    for lemma, senses in by_lemma.items():
        senses.sort(key=lambda s: (-uses[s], sense_number(s), s))
        for i, synset in enumerate(senses):
            if i == 0:
                labels[synset] = lemma
            else:
                sense = _SENSE.match(synset)
                labels[synset] = f"{lemma}_n{sense['sense'] if sense else i}"
    taken = set(labels.values())
    for synset, name in COMMON_NAMES.items():
        if synset in labels and (name == labels[synset] or name not in taken):
            taken.discard(labels[synset])
            labels[synset] = name
            taken.add(name)
    assert len(set(labels.values())) == len(labels), "a label names two synsets"
    return labels


def build(generated: Path, definitions: Path) -> dict[str, object]:
    annots = json.loads((generated / "propagated_annots_canonical.json").read_text())
    synsets = sorted(s for s, abilities in annots.items() if abilities)
    uses = activity_usage(definitions)
    labels = labels_of(synsets, uses)
    objects: dict[str, dict[str, object]] = {}
    for synset in synsets:
        abilities = annots[synset]
        label = labels[synset]
        fixed = "sceneObject" in abilities
        surface = fixed and synset not in NOT_SURFACES
        container = "fillable" in abilities or "openable" in abilities or (
            not surface and ("heatSource" in abilities or "coldSource" in abilities))
        entry: dict[str, object] = {}
        sense = _SENSE.match(synset)
        lemma = sense["lemma"] if sense else synset
        entry["synonyms"] = [w for w in dict.fromkeys((lemma, synset)) if w != label]
        if fixed:
            entry["movable"] = False
        if surface:
            entry["surface"] = True
        if container:
            entry["container"] = True
        if (surface or container) and not fixed:
            entry["capacity"] = MOVABLE_CAPACITY
        for ability, role in ROLES_OF_ABILITIES:
            if ability in abilities:
                entry[role] = True
        objects[label] = entry
    # BEHAVIOR's room types as room kinds (furniture stands `inroom` them); a room type
    # whose word an object kind has (`bar`, `closet`) is the kind `<type>_room`.
    with (generated / "allowed_room_types.csv").open() as rows:
        room_types = [line.strip() for line in rows.readlines()[1:] if line.strip()]
    for room in room_types:
        objects[room if room not in objects else f"{room}_room"] = {"movable": False,
                                                                   "room": True}
    return {
        "name": "behavior",
        "relations": ["on", "in", "under", "nextto", "inroom"],
        "objects": dict(sorted(objects.items())),
        "synsets": {labels[s]: s for s in synsets},
    }


def main() -> int:
    try:
        import bddl.config
    except ImportError:
        print("bddl is not installed: pip install 'verigraph-mcp[household]'", file=sys.stderr)
        return 2
    root = Path(os.path.dirname(bddl.config.__file__))
    data = build(root / "generated_data", Path(bddl.config.ACTIVITY_CONFIGS_PATH))
    OUT.write_text(json.dumps(data, separators=(",", ":"), sort_keys=False) + "\n")
    counts = collections.Counter(k for e in data["objects"].values()  # type: ignore[attr-defined]
                                 for k, v in e.items() if v is True)
    print(f"wrote {OUT} ({len(data['objects'])} kinds; {dict(counts)})")  # type: ignore[arg-type]
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
