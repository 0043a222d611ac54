"""Dependencies point one way: no module imports a package of its own or a higher layer.

The layers are written down once, in the table of docs/architecture.md; this test reads
that table and walks every module under verigraph/ with `ast`, function-level imports
included, so a cycle cannot hide inside a function.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

pytestmark = pytest.mark.fast

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "verigraph"
DOC = ROOT / "docs" / "architecture.md"
ROW = re.compile(r"^\|\s*(\d+(?:\.\d+)?)\s*\|([^|]*)\|")


def layer_table() -> dict[str, float]:
    """Package name -> layer, from the rows `| n | `a`, `b` | ... |` of the doc (a layer
    may be written 2.5, to place a package between two others without renumbering)."""
    layers: dict[str, float] = {}
    for line in DOC.read_text("utf-8").splitlines():
        match = ROW.match(line)
        if match:
            for name in re.findall(r"`([^`]+)`", match.group(2)):
                assert name not in layers, f"{name} is listed twice in {DOC.name}"
                layers[name] = float(match.group(1))
    return layers


def package_of(module: str) -> str:
    """`verigraph.tools.loading` -> `tools`; the root package itself is `verigraph`."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "verigraph"


def module_name(path: Path) -> str:
    rel = path.relative_to(ROOT).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def imported_modules(tree: ast.AST, module: str, is_package: bool) -> list[tuple[int, str]]:
    """(line, module) of every verigraph import anywhere in the tree."""
    found: list[tuple[int, str]] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = module.split(".")
                anchor = anchor[:len(anchor) - node.level + (1 if is_package else 0)]
                base = ".".join(anchor + ([base] if base else []))
            if base == "verigraph":  # `from verigraph import tools` names a package
                found += [(node.lineno, f"verigraph.{a.name}")
                          if (PACKAGE / a.name).exists() or (PACKAGE / f"{a.name}.py").exists()
                          else (node.lineno, "verigraph") for a in node.names]
            else:
                found.append((node.lineno, base))
    return [(line, name) for line, name in found
            if name == "verigraph" or name.startswith("verigraph.")]


def violations(source: str, module: str, layers: dict[str, float], *,
               is_package: bool = False) -> list[str]:
    """Every import in `source` (the text of `module`) that breaks the layer rule."""
    own = package_of(module)
    out = []
    for line, target in imported_modules(ast.parse(source), module, is_package):
        other = package_of(target)
        if other == own:
            continue
        if other not in layers:
            out.append(f"{module}:{line} imports {target}, whose package '{other}' has no layer")
        elif layers[other] >= layers[own]:
            out.append(f"{module}:{line} (layer {layers[own]}, {own}) imports {target} "
                       f"(layer {layers[other]}, {other})")
    return out


def test_the_doc_places_every_package() -> None:
    layers = layer_table()
    assert layers["errors"] == 0 and layers["__main__"] == max(layers.values())
    packages = {p.name for p in PACKAGE.iterdir()
                if p.is_dir() and (p / "__init__.py").exists()}
    modules = {p.stem for p in PACKAGE.glob("*.py") if p.stem != "__init__"}
    missing = sorted((packages | modules | {"verigraph"}) - set(layers))
    assert not missing, f"add these to the layer table of {DOC.relative_to(ROOT)}: {missing}"


def test_no_module_imports_its_own_or_a_higher_layer() -> None:
    layers = layer_table()
    found: list[str] = []
    for path in sorted(PACKAGE.rglob("*.py")):
        found += violations(path.read_text("utf-8"), module_name(path), layers,
                            is_package=path.name == "__init__.py")
    assert not found, "imports against the layers:\n" + "\n".join(found)


def test_the_environment_imports_nothing_of_the_agent() -> None:
    """As in Gymnasium an agent uses an environment, never the other way round: what
    both need (planners, the prompt and parser, the task suites, the job engine) sits
    below both, so no module under verigraph/env names verigraph.agent."""
    found = []
    for path in sorted((PACKAGE / "env").rglob("*.py")):
        module = module_name(path)
        found += [f"{module}:{line} imports {target}" for line, target in imported_modules(
            ast.parse(path.read_text("utf-8")), module, path.name == "__init__.py")
            if package_of(target) == "agent"]
    assert not found, "the environment imports the agent:\n" + "\n".join(found)
    layers = layer_table()
    assert layers["env"] < layers["agent"]
    assert max(layers["planning"], layers["tasks"], layers["jobs"]) < layers["env"]


@pytest.mark.parametrize(("module", "source", "bad"), [
    ("verigraph.perception.vlm", "from verigraph.agent.http import X\n", True),
    ("verigraph.perception.vlm",
     "def f():\n    from verigraph.tools import prompting\n", True),  # hidden in a function
    ("verigraph.sim2d.render", "import verigraph.solver.search\n", True),  # same layer
    ("verigraph.graph.model", "from verigraph import tools\n", True),
    ("verigraph.server.app", "from verigraph import __version__\n", False),
    ("verigraph.tools.loading", "from verigraph.sim2d import world_for_graph\n", False),
    ("verigraph.tools.loading", "from .store import LiveEpisode\n", False),
    ("verigraph.graph.io", "from ..tools import store\n", True),
    ("verigraph.env.rollout", "def f():\n    from verigraph.agent.loop import run_episode\n",
     True),
    ("verigraph.agent.loop", "from verigraph.env.rollout import run_rollout\n", False),
])
def test_the_check_catches_an_upward_import(module: str, source: str, bad: bool) -> None:
    assert bool(violations(source, module, layer_table())) is bad
