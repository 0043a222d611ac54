"""The package root's public API is loaded on first use, and is the same API as before."""

from __future__ import annotations

import subprocess
import sys

import pytest

pytestmark = pytest.mark.fast


def python(code: str) -> str:
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, r.stderr
    return r.stdout


def test_every_public_name_resolves_to_its_package_object():
    import verigraph
    from verigraph import actions, errors, graph

    homes = {"VeriGraphError": errors, "Goal": graph, "SceneGraph": graph,
             "WorldState": graph}
    assert sorted(verigraph.__all__) == sorted([
        "AlignAction", "Goal", "MoveAction", "SceneGraph", "ValidationReport",
        "VeriGraphError", "Violation", "WorldState", "execute_until_violation",
        "parse_plan", "validate_plan"])
    for name in verigraph.__all__:
        assert getattr(verigraph, name) is getattr(homes.get(name, actions), name), name
    assert set(verigraph.__all__) <= set(dir(verigraph))
    from verigraph import validate_plan

    assert validate_plan is actions.validate_plan


def test_import_verigraph_loads_nothing_heavy_until_a_name_is_used():
    out = python("import sys, verigraph\n"
                 "print(sorted(m for m in sys.modules if m.startswith(('verigraph', "
                 "'pydantic', 'networkx', 'yaml', 'numpy'))))\n"
                 "verigraph.SceneGraph\n"
                 "print('pydantic' in sys.modules, 'verigraph.graph' in sys.modules)")
    first, second = out.splitlines()
    assert first == "['verigraph']"
    assert second == "True True"


def test_unknown_names_and_subpackages():
    import verigraph

    with pytest.raises(AttributeError, match="nope"):
        _ = verigraph.nope
    # `from verigraph import <subpackage>` still imports the subpackage.
    out = python("from verigraph import prompts, extras; print(prompts.__name__, "
                 "extras.__name__)")
    assert out.split() == ["verigraph.prompts", "verigraph.extras"]
    assert verigraph.__version__ == "0.1.0"
