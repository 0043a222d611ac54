"""Optional dependencies in tests: skip on a developer machine, FAIL in CI.

CI installs every extra, so a missing one there is a broken install step, not a reason
to quietly test less.
"""

from __future__ import annotations

import importlib
import os
from types import ModuleType

import pytest


def in_ci() -> bool:
    return os.environ.get("CI", "").lower() == "true"


def require(module: str, install: str) -> ModuleType:
    """Import `module` or skip (locally) / fail (CI=true) with the install command."""
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        message = f"{module} is not installed ({exc}); install it with: {install}"
        if in_ci():
            pytest.fail(message, pytrace=False)
        pytest.skip(message, allow_module_level=True)
        raise  # unreachable: skip raises
