"""Download the wheels a pylock.toml names into a directory, in parallel, each checked
against its sha256.

    python scripts/download_wheels.py pylock.toml DIRECTORY

`uv pip compile --format pylock.toml --python PYTHON` keeps, for every package, only the
wheels that install on PYTHON, so the first one listed is the one to fetch. This is what
`pip download --no-deps` does for a pinned list, in about a second instead of several
(pip fetches one package at a time and starts slowly). Used by
scripts/install_integration.sh verifiers (with the verifiers environment's Python: 3.11
or newer, so tomllib; httpx is among verifiers' own requirements, and it follows the
usual proxy and certificate variables).
"""

from __future__ import annotations

import hashlib
import sys
import tomllib
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

import httpx


def download(client: httpx.Client, wheel: dict[str, Any], directory: Path) -> None:
    """One wheel into DIRECTORY under its own file name, refused on a hash mismatch."""
    url = str(wheel["url"])
    name = url.rsplit("/", 1)[1]
    response = client.get(url)
    response.raise_for_status()
    digest = hashlib.sha256(response.content).hexdigest()
    if digest != wheel["hashes"]["sha256"]:
        raise SystemExit(f"{name}: sha256 {digest}, the lock says {wheel['hashes']['sha256']}")
    (directory / name).write_bytes(response.content)


def main(lock: str, directory: str) -> None:
    packages = tomllib.loads(Path(lock).read_text())["packages"]
    missing = [p["name"] for p in packages if not p.get("wheels")]
    if missing:
        raise SystemExit(f"no wheel for this Python: {', '.join(missing)}")
    target = Path(directory)
    target.mkdir(parents=True, exist_ok=True)
    with httpx.Client(timeout=120, follow_redirects=True) as client, \
            ThreadPoolExecutor(max_workers=8) as pool:
        for done in [pool.submit(download, client, p["wheels"][0], target)
                     for p in packages]:
            done.result()


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    main(sys.argv[1], sys.argv[2])
