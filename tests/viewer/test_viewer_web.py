"""`verigraph view` over real HTTP: the token, loopback-only Host names, body limit, clear
errors for bad input, and the CSP on every response; `validate --html` errors."""

from __future__ import annotations

import subprocess
from collections.abc import Iterator
from pathlib import Path

import httpx2
import pytest
from mcp_helpers import free_port, verigraph_command

TOKEN = "view-token-123"


@pytest.fixture(scope="module")
def base_url() -> Iterator[str]:
    port = free_port()
    proc = subprocess.Popen([*verigraph_command(), "view", "--port", str(port), "--token",
                             TOKEN], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()
        assert line.startswith("VeriGraph viewer: http://127.0.0.1:"), proc.stderr
        yield f"http://127.0.0.1:{port}/"
    finally:
        proc.terminate()
        proc.wait(timeout=10)


def post(url: str, body: object, token: str | None = TOKEN, **kw: object) -> httpx2.Response:
    headers = {"Authorization": f"Bearer {token}"} if token else {}
    return httpx2.post(url + "api/view", json=body, headers=headers, timeout=60, **kw)


def test_page_is_served_with_a_strict_policy(base_url: str) -> None:
    page = httpx2.get(base_url)
    assert page.status_code == 200 and 'name="verigraph-mode" content="page"' in page.text
    csp = page.headers["content-security-policy"]
    assert "default-src 'none'" in csp and "connect-src 'self'" in csp
    assert TOKEN not in page.text  # the token only travels in the URL fragment


def test_api_needs_the_token(base_url: str) -> None:
    for token in (None, "wrong"):
        answer = post(base_url, {"scene": "cup_on_book", "plan": "done"}, token=token)
        assert answer.status_code == 401 and "#token=" in answer.json()["error"]


def test_foreign_host_names_are_refused(base_url: str) -> None:
    answer = httpx2.get(base_url, headers={"Host": "attacker.example"})
    assert answer.status_code == 400


def test_a_plan_is_checked_with_the_tool_functions(base_url: str) -> None:
    scene = ("nodes:\n- {id: table, label: table}\n- {id: red, label: block}\n"
             "- {id: blue, label: block}\nedges:\n- {source: red, relation: 'on', target: table}\n"
             "- {source: blue, relation: 'on', target: red}\n")
    answer = post(base_url, {"scene": scene, "plan": "move(red, on, table)",
                             "goal": "single_stack"})
    assert answer.status_code == 200, answer.text
    view = answer.json()
    assert [s["ok"] for s in view["steps"]] == [False]
    assert view["steps"][0]["violation"]["constraint"] in ("object_not_clear", "already_there")
    assert view["initial_render"].startswith("data:image/png;base64,")


@pytest.mark.parametrize(("body", "field", "words"), [
    ({"scene": "", "plan": "done"}, "scene", "scene is empty"),
    ({"scene": "cup_on_book", "plan": ""}, "plan", "plan is empty"),
    ({"scene": "{nodes: [", "plan": "done"}, "scene", "invalid YAML"),
    ({"scene": "cup_on_book", "plan": "fly(cup)"}, "plan", "fly"),
    ({"scene": "cup_on_book", "plan": "done", "goal": "{graph: 3}"}, "goal", "goal"),
    ({"scene": 5, "plan": "done"}, "scene", "must be text"),
    (["not", "an", "object"], "body", "object"),
])
def test_bad_input_names_the_field(base_url: str, body: object, field: str,
                                   words: str) -> None:
    answer = post(base_url, body)
    assert answer.status_code == 400
    error = answer.json()
    assert words in error["error"] and str(error["field"]).startswith(field), error


def test_large_bodies_are_refused_before_reading(base_url: str) -> None:
    answer = post(base_url, {"scene": "x" * (9 * 1024 * 1024), "plan": "done"})
    assert answer.status_code == 413


def test_validate_html_to_a_missing_folder_is_a_clear_error(tmp_path: Path) -> None:
    from verigraph.graph.builtin_scenes import cup_on_book
    from verigraph.graph.io import save_graph

    save_graph(cup_on_book(), tmp_path / "scene.json")
    (tmp_path / "plan.txt").write_text("move(cup, on, desk)\n")
    done = subprocess.run([*verigraph_command(), "validate", "--scene",
                           str(tmp_path / "scene.json"), "--plan", str(tmp_path / "plan.txt"),
                           "--html", str(tmp_path / "missing" / "r.html")],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2
    assert "--html" in done.stderr and "existing, writable folder" in done.stderr


def test_a_busy_port_is_a_clear_error() -> None:
    import socket

    with socket.socket() as busy:
        busy.bind(("127.0.0.1", 0))
        busy.listen()
        port = busy.getsockname()[1]
        done = subprocess.run([*verigraph_command(), "view", "--port", str(port)],
                              capture_output=True, text=True, timeout=60)
    assert done.returncode == 2
    assert "--port" in done.stderr and "--port 0" in done.stderr
