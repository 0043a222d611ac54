"""The separate virtual environments of the framework packages (integrations/*), for
the tests that run OpenEnv 0.10's and verifiers' own code against VeriGraph.

Their children reach loopback only: every HTTP(S) client in them that follows the proxy
variables (uv, pip, httpx, websockets, huggingface_hub) is sent to a loopback port that
refuses connections, loopback itself excepted, and uv's only index is
.tools/verifiers-wheels, the wheels of verifiers' chat-harness program that
scripts/install_integration.sh verifiers downloads at install time.
"""

from __future__ import annotations

import functools
import os
import socket
import subprocess
from pathlib import Path

import pytest

from optional import in_ci

ROOT = Path(__file__).resolve().parents[1]
OUTSIDE = ROOT / "tests" / "data"  # a working directory with no verigraph/ package in it
HARNESS_WHEELS = ROOT / ".tools" / "verifiers-wheels"
PROXY_VARIABLES = ("HTTP_PROXY", "HTTPS_PROXY", "ALL_PROXY")


def missing(message: str) -> None:
    """Skip locally, fail in CI (where scripts/test.sh builds everything)."""
    if in_ci():
        pytest.fail(message, pytrace=False)
    pytest.skip(message)


def venv_python(name: str, variable: str) -> Path:
    """`.tools/NAME-venv/bin/python` (or $VARIABLE); skip locally, fail in CI without it."""
    python = Path(os.environ.get(variable, ROOT / ".tools" / f"{name}-venv" / "bin" /
                                 "python"))
    if not python.exists():
        missing(f"no {name} environment at {python}; build it with "
                f"`bash scripts/install_integration.sh {name}`")
    return python


def harness_wheels() -> Path:
    """.tools/verifiers-wheels, the chat-harness program's wheels (skip/fail without)."""
    if not (HARNESS_WHEELS / "pylock.toml").exists():
        missing(f"no chat-harness wheels at {HARNESS_WHEELS}; download them with "
                "`bash scripts/install_integration.sh verifiers`")
    return HARNESS_WHEELS


@functools.cache
def refusing_socket() -> socket.socket:
    """A loopback socket bound for the whole session and never listening: every
    connection to its port is refused at once (no timeout; no other process can take
    the port while this cached socket holds it)."""
    sock = socket.socket()
    sock.bind(("127.0.0.1", 0))
    return sock


def offline_settings() -> dict[str, str]:
    """The variables that keep a child on loopback: proxies that refuse, loopback
    exempt, no index but the harness wheels, no Python downloads, pip without an index."""
    proxy = f"http://127.0.0.1:{refusing_socket().getsockname()[1]}"
    settings = {name: proxy for variable in PROXY_VARIABLES
                for name in (variable, variable.lower())}
    settings.update(NO_PROXY="127.0.0.1,localhost", no_proxy="127.0.0.1,localhost",
                    UV_DEFAULT_INDEX=HARNESS_WHEELS.as_uri(),
                    UV_FIND_LINKS=str(HARNESS_WHEELS), UV_PYTHON_DOWNLOADS="never",
                    PIP_NO_INDEX="1", HF_HUB_OFFLINE="1")
    return settings


def child_env(**extra: str) -> dict[str, str]:
    """This process's environment without PYTHONPATH (the child sees its own packages)
    and with `offline_settings()`: a child that tries any address but loopback fails."""
    inherited = {k: v for k, v in os.environ.items()
                 if k != "PYTHONPATH" and not k.upper().startswith(("UV_", "PIP_"))}
    return {**inherited, **offline_settings(), **extra}


def assert_reaches_loopback_only(python: Path) -> None:
    """A request to PyPI from `python` with `child_env()` is refused at once by the
    loopback proxy (PyPI itself would answer, or time out): the child is offline."""
    probe = subprocess.run(
        [str(python), "-c", "import urllib.request; "
         "urllib.request.urlopen('https://pypi.org/simple/certifi/', timeout=30)"],
        capture_output=True, text=True, timeout=60, env=child_env(), cwd=OUTSIDE)
    assert probe.returncode != 0 and "Connection refused" in probe.stderr, \
        probe.stderr[-2000:]
