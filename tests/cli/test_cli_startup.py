"""Start-up: a command imports the module that defines it and what that module uses.

`verigraph validate --domain D --problem P --plan F` must stay well under 0.1 s (see
docs/validator.md, Start-up): it may load the PDDL engine, and nothing of the server,
agent, simulator, solver or perception stacks, nor pydantic, networkx or the scene-graph
models. Each case runs in a fresh interpreter and reads `sys.modules` after the command.
"""

from __future__ import annotations

import argparse
import importlib
import json
import subprocess
import sys
from pathlib import Path

import pytest

from verigraph.cli import COMMANDS, SUBCOMMAND_MODULES, build_parser

pytestmark = pytest.mark.fast

DATA = Path(__file__).parents[1] / "data"
BLOCKS = [str(DATA / "blocksworld" / n) for n in ("planbench_domain.pddl",
                                                  "planbench_instance.pddl",
                                                  "planbench_plan.pddl")]
# Never needed to check a PDDL plan: other areas' stacks and their libraries.
OTHER_STACKS = ("verigraph.tools", "verigraph.server", "verigraph.agent", "verigraph.sim2d",
                "verigraph.solver", "verigraph.perception", "verigraph.viewer", "verigraph.env",
                "verigraph.arm", "verigraph.llm", "mcp", "anyio", "numpy", "cv2", "pymunk",
                "httpx", "starlette", "uvicorn", "redis", "tqdm", "networkx")
# The scene-graph path: pydantic models, YAML dictionaries.
SCENE_STACK = ("pydantic", "yaml", "verigraph.graph.model", "verigraph.graph.dictionary",
               "verigraph.graph.state", "verigraph.actions.report", "verigraph.actions.feedback")
LOGISTICS_PROBLEM = """(define (problem one-truck) (:domain logistics)
  (:objects p0 t0 l0 l1 c0)
  (:init (OBJ p0) (TRUCK t0) (LOCATION l0) (LOCATION l1) (CITY c0)
         (in-city l0 c0) (in-city l1 c0) (at t0 l0) (at p0 l0))
  (:goal (and (at p0 l1))))
"""
LOGISTICS_PLAN = "(load-truck p0 t0 l0)\n(drive-truck t0 l0 l1 c0)\n(unload-truck p0 t0 l1)\n"


def modules_after(args: list[str], cwd: Path | None = None) -> tuple[int, list[str]]:
    """(exit status, sorted sys.modules) after `verigraph ARGS` in a fresh interpreter."""
    code = ("import contextlib, io, json, sys\n"
            "from verigraph.cli import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            f"    status = main({args!r})\n"
            "print(json.dumps([status, sorted(sys.modules)]))\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       cwd=cwd, timeout=120)
    assert r.returncode == 0, r.stderr
    status, modules = json.loads(r.stdout)
    return status, modules


def loaded(modules: list[str], prefixes: tuple[str, ...]) -> list[str]:
    return [m for m in modules if any(m == p or m.startswith(p + ".") for p in prefixes)]


def test_the_command_table_is_what_the_modules_register():
    registered: dict[str, str] = {}
    for name in SUBCOMMAND_MODULES:
        sub = argparse.ArgumentParser().add_subparsers()
        importlib.import_module(name).register(sub)
        registered.update(dict.fromkeys(sub.choices, name))
    assert registered == COMMANDS
    full = build_parser()
    choices = next(a for a in full._actions if isinstance(a, argparse._SubParsersAction))
    assert list(choices.choices) == list(COMMANDS)


@pytest.mark.parametrize("command", ["validate", "val"])
def test_a_pddl_check_loads_no_other_stack(command):
    args = (["validate", "--domain", BLOCKS[0], "--problem", BLOCKS[1], "--plan", BLOCKS[2]]
            if command == "validate" else ["val", *BLOCKS])
    status, modules = modules_after(args)
    assert status == 0
    assert loaded(modules, OTHER_STACKS) == []
    cli = [m for m in modules if m.startswith("verigraph.cli")]
    assert cli == sorted({"verigraph.cli", COMMANDS[command]}
                         | {"verigraph.cli.validating", "verigraph.cli.exits"})


def test_a_strips_check_loads_no_pydantic_and_no_scene_graph(tmp_path):
    (tmp_path / "p.pddl").write_text(LOGISTICS_PROBLEM)
    (tmp_path / "plan.txt").write_text(LOGISTICS_PLAN)
    status, modules = modules_after(["validate", "--domain",
                                     str(DATA / "pddl" / "logistics_domain.pddl"),
                                     "--problem", "p.pddl", "--plan", "plan.txt"], tmp_path)
    assert status == 0
    assert loaded(modules, OTHER_STACKS + SCENE_STACK) == []


@pytest.mark.parametrize("command", ["validate", "val"])
def test_a_blocks_world_check_loads_no_pydantic_and_no_scene_graph(command):
    """The native blocks-world engine runs on plain dicts: the scene-graph models (and
    pydantic) load only when a caller asks for a `ValidationReport`."""
    args = (["validate", "--domain", BLOCKS[0], "--problem", BLOCKS[1], "--plan", BLOCKS[2]]
            if command == "validate" else ["val", *BLOCKS])
    status, modules = modules_after(args)
    assert status == 0
    assert "verigraph.pddl.blocksworld.validate" in modules  # the native engine judged it
    assert loaded(modules, OTHER_STACKS + SCENE_STACK) == []


def test_the_exit_table_names_every_status_and_no_command_module_defines_its_own() -> None:
    from verigraph.cli import exits
    from verigraph.errors import MissingTokenError, ServerUnreachableError, TokenRejectedError

    names = [n for n in vars(exits) if n.startswith("EXIT_") or n == "MAX_FAILED_STATUS"]
    table = exits.__doc__ or ""
    assert names and all(f" {n} " in table for n in names), names
    for error in (ServerUnreachableError, MissingTokenError, TokenRejectedError):
        assert error.__name__ in table and str(error.exit_code) in table
    for module in sorted(set(SUBCOMMAND_MODULES) | {"verigraph.cli"}):
        source = Path(importlib.import_module(module).__file__ or "").read_text()
        assert "\nEXIT_" not in source and "\nMAX_FAILED_STATUS" not in source, module
