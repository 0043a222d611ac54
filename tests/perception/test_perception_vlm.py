"""The VLM path over real HTTP on loopback, against recorded responses.

`RecordedResponseServerForTests` (tests/planning_doubles.py) replays chat-completions
bodies. `RECORDED_LLAMA_CPP_*` were recorded once from a real server: llama-cpp-python
0.3.36 serving Gemma 3 270M (text-only, so it was sent the prompt without the image),
with response_format json_object_schema and this module's graph schema (max 6 nodes and
6 edges for the complete answer; no item limit and max_tokens 400 for the truncated
one). The small model's graph is poor, which is what the normalisation and the
warnings are tested on. Answers built from the true graph are marked as synthesised.
"""

from __future__ import annotations

import base64
import json
from pathlib import Path

import cv2
import numpy as np
import pytest
from planning_doubles import RecordedResponse as R
from planning_doubles import RecordedResponseServerForTests, chat_completion

from verigraph.cli import main
from verigraph.graph.dictionary import builtin_dictionary
from verigraph.llm.formats import response_format_field
from verigraph.perception.label.vlm import VlmClient, VlmConfig, VlmError, graph_schema
from verigraph.perception.metrics import score_graph
from verigraph.sim2d.generator import generate_scene

RECORDED_LLAMA_CPP_ANSWER = json.loads(
    '{"id":"chatcmpl-a45732a3-915d-4db9-a9b6-1ea10d9b6e1f","object":"chat.completion","created"'
    ':1795311362,"model":"gemma-3-270m","choices":[{"index":0,"message":{"content":"{ \\"nodes'
    '\\": [{\\"id\\": \\"desk\\", \\"label\\": \\"desk\\",\\"attrs\\": {\\"color\\": \\"white\\'
    '"}}, {\\"id\\": \\"book\\", \\"label\\": \\"book\\",\\"attrs\\": {\\"color\\": \\"white\\"'
    '}}, {\\"id\\": \\"cup\\", \\"label\\": \\"cup\\", \\"attrs\\": {\\"color\\": \\"white\\"}}'
    ', {\\"id\\": \\"plate\\", \\"label\\": \\"plate\\", \\"attrs\\": {\\"color\\": \\"white\\"'
    '}}, {\\"id\\": \\"shelf\\", \\"label\\": \\"shelf\\", \\"attrs\\": {\\"color\\": \\"white'
    '\\"}}, {\\"id\\": \\"tray\\", \\"label\\": \\"tray\\", \\"attrs\\": {\\"color\\": \\"white'
    '\\"}}] ,\\"edges\\": [{\\"source\\": \\"book\\", \\"relation\\": \\"on\\", \\"target\\": '
    '\\"desk\\" , \\"source_side\\": 1, \\"target_side\\": 2}, {\\"source\\": \\"cup\\", \\"rel'
    'ation\\": \\"on\\", \\"target\\": \\"book\\" , \\"source_side\\": 3, \\"target_side\\": 4}'
    ', {\\"source\\": \\"plate\\", \\"relation\\": \\"on\\", \\"target\\": \\"shelf\\" , \\"sou'
    'rce_side\\": 5, \\"target_side\\": 6}, {\\"source\\": \\"cup\\", \\"relation\\": \\"on\\",'
    ' \\"target\\": \\"tray\\" , \\"source_side\\": 7, \\"target_side\\": 8}, {\\"source\\": \\'
    '"plate\\", \\"relation\\": \\"on\\", \\"target\\": \\"shelf\\" , \\"source_side\\": 9, \\"'
    'target_side\\": 10}, {\\"source\\": \\"cup\\", \\"relation\\": \\"on\\", \\"target\\": \\"'
    'tray\\" , \\"source_side\\": 11, \\"target_side\\": 12}]}","role":"assistant"},"logprobs":'
    'null,"finish_reason":"stop"}],"usage":{"prompt_tokens":536,"completion_tokens":354,"total_'
    'tokens":890}}')

RECORDED_LLAMA_CPP_TRUNCATED = json.loads(
    '{"id":"chatcmpl-c89e75dd-a978-4302-8105-47624e4378ed","object":"chat.completion","created"'
    ':1795311241,"model":"gemma-3-270m","choices":[{"index":0,"message":{"content":"{ \\"nodes'
    '\\": [{\\"id\\": \\"desk\\", \\"label\\": \\"desk\\",\\"attrs\\": {\\"color\\": \\"white\\'
    '"}}, {\\"id\\": \\"book\\", \\"label\\": \\"book\\",\\"attrs\\": {\\"color\\": \\"white\\"'
    '}}, {\\"id\\": \\"cup\\", \\"label\\": \\"cup\\", \\"attrs\\": {\\"color\\": \\"white\\"}}'
    ', {\\"id\\": \\"plate\\", \\"label\\": \\"plate\\", \\"attrs\\": {\\"color\\": \\"white\\"'
    '}}, {\\"id\\": \\"shelf\\", \\"label\\": \\"shelf\\", \\"attrs\\": {\\"color\\": \\"white'
    '\\"}}, {\\"id\\": \\"tray\\", \\"label\\": \\"tray\\", \\"attrs\\": {\\"color\\": \\"white'
    '\\"}}, {\\"id\\": \\"spoon\\", \\"label\\": \\"spoon\\", \\"attrs\\": {\\"color\\": \\"whi'
    'te\\"}}, {\\"id\\": \\"table\\", \\"label\\": \\"table\\", \\"attrs\\": {\\"color\\": \\"w'
    'hite\\"}}, {\\"id\\": \\"shelf\\", \\"label\\": \\"shelf\\", \\"attrs\\": {\\"color\\": \\'
    '"white\\"}}, {\\"id\\": \\"plate\\", \\"label\\": \\"plate\\", \\"attrs\\": {\\"color\\": '
    '\\"white\\"}}, {\\"id\\": \\"tray\\", \\"label\\": \\"tray\\", \\"attrs\\": {\\"color\\": '
    '\\"white\\"}}, {\\"id\\": \\"cup\\", \\"label\\": \\"cup\\", \\"attrs\\": {\\"color\\": \\'
    '"white\\"}}, {\\"id\\": \\"book\\", \\"label\\": \\"book\\", \\"attrs\\": {\\"color\\": \\'
    '"white\\"}}, {\\"id\\": \\"plate\\", \\"label\\": \\"plate\\", \\"attrs\\": {\\"color\\": '
    '\\"white\\"}}, {\\"id\\": \\"shelf\\", \\"label\\": \\"shelf\\", \\"attrs\\": {\\"color\\"'
    ': \\"white\\"}}, {\\"id\\": \\"tray\\", \\"label\\": \\"tray\\", \\"attrs\\": {\\"color\\"'
    ': \\"white\\"}}, {\\"id\\": \\"cup\\", \\"label\\": \\"cup\\", \\"attrs\\": {\\"color\\": '
    '\\"white\\"}}, {\\"id\\": \\"book\\", \\"label\\": \\"book\\", \\"attrs\\": {\\"color\\": '
    '\\"white\\"}},","role":"assistant"},"logprobs":null,"finish_reason":"length"}],"usage":{"p'
    'rompt_tokens":536,"completion_tokens":400,"total_tokens":936}}')


@pytest.fixture(scope="module")
def scene() -> tuple[np.ndarray, object]:
    s = generate_scene("tableware", 3)
    return s.world.render(640, 480), s.graph


def synthesised_answer(graph: object) -> dict:
    """An answer as a perfect model would write it (synthesised from the truth)."""
    data = graph.model_dump(exclude={"dictionary"})  # type: ignore[attr-defined]
    for node in data["nodes"]:
        node["attrs"] = {"color": node["attrs"].get("color")}
    return chat_completion(json.dumps(data))


def client(url: str, **config: object) -> VlmClient:
    return VlmClient(VlmConfig(base_url=url + "/v1", model="recorded", retries=1, **config))


def test_request_carries_the_prompt_the_image_and_the_schema(scene: tuple) -> None:
    image, truth = scene
    with RecordedResponseServerForTests([R(synthesised_answer(truth))]) as server:
        result = client(server.url).perceive(image, "tableware", task="put the cup away")
    assert score_graph(result.graph, truth, "tableware").exact
    assert result.view == "vlm" and result.graph.dictionary == "tableware"
    sent = server.requests[0]
    assert sent.path == "/v1/chat/completions"
    text, picture = sent.body["messages"][0]["content"]
    assert "on, in" in text["text"] and "put the cup away" in text["text"]
    assert "- cup: movable, container" in text["text"]  # the dictionary D
    url = picture["image_url"]["url"]
    assert url.startswith("data:image/png;base64,")
    decoded = cv2.imdecode(np.frombuffer(base64.b64decode(url.split(",", 1)[1]), np.uint8),
                           cv2.IMREAD_COLOR)
    assert np.array_equal(decoded, image)
    fmt = sent.body["response_format"]
    assert fmt["type"] == "json_schema" and fmt["json_schema"]["strict"] is True
    labels = fmt["json_schema"]["schema"]["properties"]["nodes"]["items"]["properties"]
    assert "cup" in labels["label"]["enum"] and "teacup" in labels["label"]["enum"]


def test_recorded_llama_cpp_answer_is_normalised_and_its_problems_listed(scene: tuple
                                                                         ) -> None:
    image, _ = scene
    with RecordedResponseServerForTests([R(RECORDED_LLAMA_CPP_ANSWER)]) as server:
        result = client(server.url, response_format="json_object_schema").perceive(
            image, "tableware")
    assert server.requests[0].body["response_format"]["type"] == "json_object"
    graph = result.graph
    assert ("cup", "on", "book", None, None) in graph.edge_keys()
    assert all(e.source_side is None for e in graph.edges)  # sides dropped, noted
    assert any("dropped the side numbers" in w for w in result.warnings)
    assert any("[multiple_supports] 'cup'" in w for w in result.warnings)
    assert any("[missing_support] movable object 'tray'" in w for w in result.warnings)


def test_recorded_truncated_answer_is_a_clear_error(scene: tuple) -> None:
    image, _ = scene
    with RecordedResponseServerForTests([R(RECORDED_LLAMA_CPP_TRUNCATED)]) as server, \
            pytest.raises(VlmError, match="cut off") as err:
        client(server.url).perceive(image, "tableware")
    assert "max_nodes" in (err.value.fix or "")


@pytest.mark.parametrize("body,message", [
    (chat_completion("I see a cup on a book."), "not JSON"),
    (chat_completion(json.dumps({"objects": []})), "not a scene graph"),
    ({"choices": []}, "no choices"),
    (chat_completion(""), "no text"),
])
def test_bad_answers_are_vlm_errors(scene: tuple, body: dict, message: str) -> None:
    image, _ = scene
    with RecordedResponseServerForTests([R(body)]) as server, \
            pytest.raises(VlmError, match=message):
        client(server.url).perceive(image, "tableware")


def test_synonyms_and_fenced_json_are_accepted(scene: tuple) -> None:
    image, _ = scene
    content = ("```json\n" + json.dumps({
        "nodes": [{"id": "Desk", "label": "writing desk", "attrs": {"color": None}},
                  {"id": "mug", "label": "coffee mug", "attrs": {"color": "red"}}],
        "edges": [{"source": "mug", "relation": "on top of", "target": "Desk",
                   "source_side": None, "target_side": None}]}) + "\n```")
    with RecordedResponseServerForTests([R(chat_completion(content))]) as server:
        result = client(server.url, response_format="none").perceive(image, "tableware")
    assert "response_format" not in server.requests[0].body
    assert result.graph.sentences() == ["mug on desk"]
    assert {n.id: n.label for n in result.graph.nodes} == {"desk": "desk", "mug": "mug"}


def test_transient_errors_are_retried(scene: tuple) -> None:
    image, truth = scene
    with RecordedResponseServerForTests([R({"error": {"message": "busy"}}, status=503),
                                         R(synthesised_answer(truth))]) as server:
        result = client(server.url).perceive(image, "tableware")
    assert len(server.requests) == 2 and result.graph.edge_keys() == truth.edge_keys()


def test_schema_dialects_and_limits() -> None:
    schema = graph_schema(builtin_dictionary("tangram"), max_nodes=7, max_edges=20)
    assert schema["properties"]["nodes"]["maxItems"] == 7
    edge = schema["properties"]["edges"]["items"]
    assert edge["properties"]["relation"]["enum"] == ["touches"]
    assert set(edge["required"]) == set(edge["properties"])  # strict mode: all required
    assert response_format_field("json_object_schema", schema) == {"type": "json_object",
                                                                   "schema": schema}
    assert response_format_field("none", schema) is None
    strict = response_format_field("json_schema", schema, "scene_graph")
    assert strict is not None and strict["json_schema"]["name"] == "scene_graph"


def test_config_from_env(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("VERIGRAPH_VLM_MODEL", "llava")
    monkeypatch.setenv("OPENAI_BASE_URL", "http://127.0.0.1:1/v1")
    config = VlmConfig.from_env()
    assert config.model == "llava" and config.base_url == "http://127.0.0.1:1/v1"
    monkeypatch.delenv("VERIGRAPH_VLM_MODEL")
    monkeypatch.delenv("OPENAI_MODEL", raising=False)
    with pytest.raises(VlmError, match="no vision model"):
        VlmConfig.from_env()


def test_cli_vlm_route(scene: tuple, tmp_path: Path, capsys: pytest.CaptureFixture[str]
                       ) -> None:
    image, truth = scene
    path = tmp_path / "t.png"
    path.write_bytes(cv2.imencode(".png", image)[1].tobytes())
    with RecordedResponseServerForTests([R(synthesised_answer(truth))]) as server:
        code = main(["perceive", str(path), "--family", "tableware", "--vlm-model", "m",
                     "--vlm-base-url", server.url + "/v1"])
    assert code == 0
    out = capsys.readouterr().out
    assert out.startswith("# vlm view") and all(s in out for s in truth.sentences())
