"""The registry of optional extras: a missing package names the command that installs it."""

from __future__ import annotations

import importlib.util
import tomllib
from pathlib import Path

import pytest

from verigraph import extras
from verigraph.errors import VeriGraphError
from verigraph.extras import EXTRAS, Extra, ExtraMissingError

pytestmark = pytest.mark.fast


def test_every_extra_installs_from_the_distribution() -> None:
    project = tomllib.loads((Path(__file__).parents[2] / "pyproject.toml").read_text())
    assert set(EXTRAS) == {"arm", "clip", "env", "llm", "pddl", "scale"}
    assert set(EXTRAS) <= set(project["project"]["optional-dependencies"])
    for name, extra in EXTRAS.items():
        assert extra.name == name and extra.modules
        assert extra.install == f"pip install 'verigraph-mcp[{name}]'"


def test_presence_is_what_find_spec_says() -> None:
    for name, extra in EXTRAS.items():
        absent = [m for m in extra.modules if importlib.util.find_spec(m) is None]
        assert extras.missing(name) == absent
        assert extras.installed(name) is (not absent)


def test_a_missing_package_is_an_error_with_the_install_command(
        monkeypatch: pytest.MonkeyPatch) -> None:
    # The registry entry is replaced by one whose package cannot exist, so the test
    # does not depend on what this machine has installed.
    absent = Extra("arm", ("verigraph_no_such_driver_sdk",), "a test driver")
    monkeypatch.setitem(EXTRAS, "arm", absent)
    with pytest.raises(ExtraMissingError) as err:
        extras.require("arm")
    assert isinstance(err.value, VeriGraphError)
    assert err.value.fix == "pip install 'verigraph-mcp[arm]'"
    assert err.value.value == "verigraph_no_such_driver_sdk"
    assert "verigraph_no_such_driver_sdk is not installed" in err.value.message


def test_a_module_outside_the_extra_is_a_programming_error() -> None:
    with pytest.raises(ValueError, match="not in the 'clip' extra"):
        extras.missing("clip", "pybullet")
