"""Finding the Node clients the interoperability tests run: Node >= 22 and tests/interop.

Node comes from, in order: $VERIGRAPH_NODE; the Node next to the Inspector that
scripts/install_inspector.sh installed ($VERIGRAPH_INSPECTOR or .tools/bin/mcp-inspector,
whose launcher names its Node); .tools/node; `node` on PATH. Each candidate is asked
for its version, so an old system Node is never used by mistake. The npm packages come
from `bash scripts/install_interop.sh` (tests/interop/node_modules). Missing pieces skip
the tests locally and FAIL them in CI (CI=true), like tests/optional.py.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from mcp_helpers import REPO

from optional import in_ci

MIN_NODE_MAJOR = 22
INTEROP = REPO / "tests" / "interop"


def _missing(message: str) -> None:
    if in_ci():
        pytest.fail(message, pytrace=False)
    pytest.skip(message)


def _major(node: str) -> int:
    try:
        done = subprocess.run([node, "--version"], capture_output=True, text=True, timeout=20)
    except OSError:
        return 0
    match = re.match(r"v(\d+)\.", done.stdout.strip())
    return int(match.group(1)) if match else 0


def _candidates() -> list[str]:
    found: list[str] = []
    if os.environ.get("VERIGRAPH_NODE"):
        found.append(os.environ["VERIGRAPH_NODE"])
    inspector = Path(os.environ.get("VERIGRAPH_INSPECTOR")
                     or REPO / ".tools" / "bin" / "mcp-inspector")
    if inspector.is_file():
        # The launcher is `exec "<node>" "<inspector>" "$@"`: its first quoted path.
        match = re.search(r'exec "([^"]+/node)"', inspector.read_text(errors="replace"))
        if match:
            found.append(match.group(1))
    found += [str(p) for p in sorted((REPO / ".tools" / "node" / "node_modules")
                                     .glob("node-linux-*/bin/node"))]
    system = shutil.which("node")
    if system:
        found.append(system)
    return found


def node22() -> str:
    """A Node >= 22 executable, or skip (locally) / fail (CI)."""
    tried = []
    for candidate in _candidates():
        major = _major(candidate)
        if major >= MIN_NODE_MAJOR:
            return candidate
        tried.append(f"{candidate} (v{major or '?'})")
    _missing(f"Node >= {MIN_NODE_MAJOR} not found (tried: {', '.join(tried) or 'nothing'}); "
             "install it with `bash scripts/install_inspector.sh`")
    raise AssertionError("unreachable")


def interop_package(name: str) -> Path:
    """The installed npm package `name` under tests/interop, or skip / fail."""
    path = INTEROP / "node_modules" / name
    if not (path / "package.json").is_file():
        _missing(f"{name} is not installed in {INTEROP}; run `bash scripts/install_interop.sh`")
    return path
