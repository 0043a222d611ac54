"""The separate virtual environments of the framework packages (integrations/*), for
the tests that run OpenEnv 0.10's and verifiers' own code against VeriGraph."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from optional import in_ci

ROOT = Path(__file__).resolve().parents[1]
OUTSIDE = ROOT / "tests" / "data"  # a working directory with no verigraph/ package in it


def venv_python(name: str, variable: str) -> Path:
    """`.tools/NAME-venv/bin/python` (or $VARIABLE); skip locally, fail in CI without it."""
    python = Path(os.environ.get(variable, ROOT / ".tools" / f"{name}-venv" / "bin" /
                                 "python"))
    if not python.exists():
        message = (f"no {name} environment at {python}; build it with "
                   f"`bash scripts/install_integration.sh {name}`")
        if in_ci():
            pytest.fail(message, pytrace=False)
        pytest.skip(message)
    return python


def child_env(**extra: str) -> dict[str, str]:
    """This process's environment without PYTHONPATH: the child sees its own packages."""
    return {**{k: v for k, v in os.environ.items() if k != "PYTHONPATH"}, **extra}
