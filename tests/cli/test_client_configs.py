"""Every client config, `server.json` and the docs launch this project, not a namesake.

The PyPI name `verigraph` belongs to an unrelated project with its own `verigraph`
console script, so a config that says `uvx --from verigraph ...` would run that one. Each
stdio config here must install the distribution named in pyproject.toml and run a console
script that distribution declares; the test then runs that command from the local build
(this virtual environment) and lists the tools over a real stdio client.
"""

from __future__ import annotations

import json
import re
import shutil
import sys
import tomllib
from importlib import metadata
from pathlib import Path
from typing import Any

import anyio
import pytest
from mcp import Client, StdioServerParameters, stdio_client

REPO = Path(__file__).resolve().parents[2]
CONFIGS = sorted((REPO / "examples" / "clients").glob("*.json"))
PYPROJECT = tomllib.loads((REPO / "pyproject.toml").read_text())
DISTRIBUTION = PYPROJECT["project"]["name"]
SCRIPTS = PYPROJECT["project"]["scripts"]


def stdio_servers(config: dict[str, Any]) -> list[dict[str, Any]]:
    """The stdio server entries of a client config (Claude, Cursor and VS Code shapes)."""
    servers = config.get("mcpServers") or config.get("servers") or {}
    return [s for s in servers.values() if "command" in s]


def package_and_script(entry: dict[str, Any]) -> tuple[str, list[str]]:
    """(package spec, command after it) of a `uvx --from PKG CMD ...` or `pipx run --spec` entry."""
    command, args = entry["command"], list(entry["args"])
    if command == "uvx":
        assert args[0] == "--from", f"uvx without --from runs whatever owns the name: {args}"
        return args[1], args[2:]
    if command == "pipx":
        assert args[:2] == ["run", "--spec"], args
        return args[2], args[3:]
    raise AssertionError(f"unexpected launcher {command!r}; configs use uvx or pipx")


def test_the_distribution_name_is_ours() -> None:
    assert DISTRIBUTION == "verigraph-mcp"
    assert "verigraph" in SCRIPTS
    installed = metadata.distribution(DISTRIBUTION)
    assert any(ep.name == "verigraph" for ep in installed.entry_points
               if ep.group == "console_scripts")


@pytest.mark.parametrize("path", CONFIGS, ids=lambda p: p.name)
def test_config_installs_this_distribution(path: Path) -> None:
    entries = stdio_servers(json.loads(path.read_text()))
    assert entries, f"{path.name} has no stdio server"
    for entry in entries:
        package, command = package_and_script(entry)
        assert package == DISTRIBUTION, f"{path.name} installs {package!r}"
        assert command[0] in SCRIPTS, f"{path.name} runs {command[0]!r}, not our script"


def test_server_json_and_docs_name_this_distribution() -> None:
    server = json.loads((REPO / "server.json").read_text())
    assert [p["identifier"] for p in server["packages"]] == [DISTRIBUTION]
    readme = (REPO / "README.md").read_text()
    assert f"mcp-name: {server['name']}" in readme
    for doc in [REPO / "README.md", *sorted((REPO / "docs").glob("*.md"))]:
        text = doc.read_text()
        wrong = re.findall(r"(?:--from|--spec|pip install)\s+['\"]?(verigraph)(?![-\w])", text)
        assert not wrong, f"{doc.name} installs the unrelated `verigraph` package"


async def list_tools_over_stdio(command: list[str]) -> list[str]:
    params = StdioServerParameters(command=command[0], args=command[1:])
    async with Client(stdio_client(params)) as client:
        return [tool.name for tool in (await client.list_tools()).tools]


@pytest.mark.parametrize("path", CONFIGS, ids=lambda p: p.name)
def test_config_command_lists_tools_from_the_local_build(path: Path) -> None:
    """The config's command, with the local build's console script in place of `uvx`."""
    for entry in stdio_servers(json.loads(path.read_text())):
        _, command = package_and_script(entry)
        script = shutil.which(command[0], path=str(Path(sys.executable).parent))
        assert script, f"console script {command[0]!r} is not installed next to {sys.executable}"
        names = anyio.run(list_tools_over_stdio, [script, *command[1:]])
        assert {"load_scene", "validate_action", "execute_actions"} <= set(names)
