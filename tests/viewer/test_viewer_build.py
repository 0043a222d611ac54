"""The committed viewer files are what `scripts/build_viewer.sh` builds from viewer/.

Needs Node and npm (the npm registry for `npm ci` when viewer/node_modules is missing);
the installed package itself never needs them.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
VIEWER = REPO / "viewer"
COMMITTED = {"episode.html": REPO / "verigraph" / "viewer" / "static" / "episode.html",
             "host.html": REPO / "tests" / "viewer_host" / "host.html"}


@pytest.mark.skipif(shutil.which("npm") is None or shutil.which("node") is None,
                    reason="rebuilding the viewer needs Node and npm")
def test_committed_viewer_files_are_current(tmp_path: Path) -> None:
    if not (VIEWER / "node_modules").is_dir():
        subprocess.run(["npm", "ci", "--no-audit", "--no-fund"], cwd=VIEWER, check=True,
                       capture_output=True, timeout=300)
    subprocess.run(["node", "build.mjs"], cwd=VIEWER, check=True, capture_output=True,
                   timeout=300, env={"PATH": os.environ["PATH"],
                                     "VIEWER_OUT_DIR": str(tmp_path)})
    for name, committed in COMMITTED.items():
        built = (tmp_path / name).read_text(encoding="utf-8")
        assert built == committed.read_text(encoding="utf-8"), (
            f"{committed.relative_to(REPO)} is stale: run scripts/build_viewer.sh and commit it")


def test_packaged_viewer_is_one_file_with_the_bridge_bundled() -> None:
    html = COMMITTED["episode.html"].read_text(encoding="utf-8")
    assert html.count("<script") == 1 and "<script src" not in html
    assert "ui/initialize" in html and "ui/notifications/tool-result" in html
    assert "<link" not in html  # no stylesheet or font fetched
