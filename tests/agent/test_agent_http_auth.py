"""`verigraph agent --transport http` tells no server, no token and a wrong token apart,
and the server refuses without inviting OAuth; `GET /healthz` answers without a token."""

from __future__ import annotations

import subprocess
import sys

import httpx2
import pytest
from mcp_helpers import JSON_HEADERS, free_port, http_server, rpc

from verigraph import __version__

TOKEN = "agent-auth-token"


def agent(url: str, *extra: str) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in __import__("os").environ.items() if k != "VERIGRAPH_TOKEN"}
    return subprocess.run([sys.executable, "-m", "verigraph", "agent", "--scene", "cup_on_book",
                           "--planner", "oracle", "--transport", "http", "--url", url, *extra],
                          capture_output=True, text=True, timeout=120, env=env)


@pytest.fixture(scope="module")
def url() -> object:
    with http_server(token=TOKEN) as server:
        yield server.url


def test_no_server_is_its_own_error() -> None:
    done = agent(f"http://127.0.0.1:{free_port()}/mcp")
    assert done.returncode == 3, done.stderr
    assert "no MCP server answers" in done.stderr and "verigraph serve" in done.stderr
    assert "TaskGroup" not in done.stderr


def test_a_wrong_path_says_so(url: str) -> None:
    done = agent(url.removesuffix("/mcp") + "/nope", "--token", TOKEN)
    assert done.returncode == 3, done.stderr
    assert "no MCP endpoint there (HTTP 404)" in done.stderr


def test_missing_token_is_its_own_error(url: str) -> None:
    done = agent(url)
    assert done.returncode == 4, done.stderr
    assert "needs a bearer token" in done.stderr and "no token was sent" in done.stderr
    assert "--token" in done.stderr and "TaskGroup" not in done.stderr


def test_wrong_token_is_its_own_error(url: str) -> None:
    done = agent(url, "--token", "not-the-token")
    assert done.returncode == 5, done.stderr
    assert "refused the token" in done.stderr and "does not match" in done.stderr
    assert "not-the-token" not in done.stderr  # the secret is not echoed


def test_right_token_plays_the_episode(url: str) -> None:
    done = agent(url, "--token", TOKEN)
    assert done.returncode == 0, done.stderr


def test_refusals_carry_the_reason_and_no_oauth_challenge(url: str) -> None:
    for headers, reason in (({}, "missing_token"),
                            ({"Authorization": "Bearer wrong"}, "wrong_token"),
                            ({"Authorization": TOKEN}, "wrong_token")):
        response = httpx2.post(url, headers={**JSON_HEADERS, **headers}, content=rpc("ping"))
        assert response.status_code == 403
        assert "www-authenticate" not in response.headers
        error = response.json()["error"]
        assert error["data"]["reason"] == reason and "--token" in error["message"]


def test_healthz_answers_without_token_or_body(url: str) -> None:
    health = url.removesuffix("/mcp") + "/healthz"
    response = httpx2.get(health, timeout=10)
    assert response.status_code == 200
    assert response.json() == {"status": "ok", "name": "verigraph", "version": __version__}
    assert httpx2.post(health, timeout=10).status_code == 405
    assert httpx2.get(url, timeout=10).status_code == 403  # the MCP endpoint stays guarded
