"""BEHAVIOR-1K's activities as installed by the `bddl` package (the `household` extra).

The activity definitions are read from the installed package, never downloaded: each
activity is a folder `bddl/activity_definitions/<activity>/problem0.bddl`. The package
is located with `find_spec` and not imported (importing it loads its simulator
back-end classes; only its files are needed here).
"""

from __future__ import annotations

import importlib.util
from functools import cache
from pathlib import Path

from verigraph.errors import VeriGraphError
from verigraph.extras import require

MAX_PROBLEM_BYTES = 262_144


@cache
def definitions_dir() -> Path:
    """`bddl/activity_definitions` of the installed package (ExtraMissingError without it)."""
    require("household", "bddl")
    spec = importlib.util.find_spec("bddl")
    assert spec is not None and spec.submodule_search_locations is not None
    return Path(next(iter(spec.submodule_search_locations))) / "activity_definitions"


@cache
def activities() -> tuple[str, ...]:
    """Every activity name, sorted (1,016 in bddl 3.6.0)."""
    root = definitions_dir()
    return tuple(sorted(d.name for d in root.iterdir() if (d / "problem0.bddl").is_file()))


def activity_text(name: str) -> str:
    """The BDDL problem of one activity, or a VeriGraphError naming the nearest names."""
    path = definitions_dir() / name / "problem0.bddl"
    if "/" in name or "\\" in name or name.startswith(".") or not path.is_file():
        import difflib

        near = difflib.get_close_matches(name, activities(), n=3, cutoff=0.6)
        raise VeriGraphError(f"no BEHAVIOR activity named '{name[:80]}'", field="activity",
                             value=name[:80],
                             fix=f"use an activity name such as {', '.join(near)}" if near else
                                 "give a .bddl file, or an activity name from "
                                 "bddl/activity_definitions (verigraph bench behavior lists "
                                 "them)")
    return path.read_text()


def problem_text(activity_or_file: str) -> tuple[str, str]:
    """(activity name, BDDL text) of an activity name or a .bddl file path."""
    path = Path(activity_or_file)
    if path.suffix == ".bddl" or path.is_file():
        if not path.is_file():
            raise VeriGraphError(f"no file {activity_or_file[:120]}", field="activity",
                                 value=activity_or_file[:120],
                                 fix="give an existing .bddl file or an activity name")
        if path.stat().st_size > MAX_PROBLEM_BYTES:
            raise VeriGraphError(f"{activity_or_file[:120]} is over {MAX_PROBLEM_BYTES} bytes",
                                 field="activity", value=activity_or_file[:120],
                                 fix="give one BDDL problem")
        try:
            text = path.read_text()
        except UnicodeDecodeError:
            raise VeriGraphError(f"{activity_or_file[:120]} is not text", field="activity",
                                 value=activity_or_file[:120],
                                 fix="give a BDDL problem file") from None
        name = path.parent.name if path.name.startswith("problem") else path.stem
        return name, text
    return activity_or_file, activity_text(activity_or_file)
