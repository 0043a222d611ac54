"""Optional-dependency guard for the arm tests: skip locally, fail loudly in CI.

The arm drivers need the `arm` extra (pybullet, roslibpy, xarm-python-sdk,
websockets). A developer without it gets skipped tests with the install command; CI
(CI=true) must have it, so there a missing package is a failure, not a silent skip.
"""

from __future__ import annotations

import importlib
import os
from types import ModuleType

from verigraph.extras import EXTRAS

INSTALL = EXTRAS["arm"].install


def require(module: str) -> ModuleType:
    """Import `module` for a test module, or skip (locally) / fail (CI) with the fix."""
    import pytest

    try:
        return importlib.import_module(module)
    except ImportError as exc:
        message = f"the arm tests need '{module}' ({exc}); install it with: {INSTALL}"
        if os.environ.get("CI", "").lower() in ("true", "1", "yes"):
            pytest.fail(message, pytrace=False)
        pytest.skip(message, allow_module_level=True)
