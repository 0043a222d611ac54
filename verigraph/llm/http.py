"""JSON over HTTP with retries: the transport of every model client (planners, VLM).

Transient failures (connection errors, timeouts, 408, 409, 425, 429, 5xx and
Anthropic's 529 "overloaded") are retried with exponential backoff and jitter,
honouring `Retry-After`; anything else fails at once with an error that names the
endpoint, the status and the body's message, because retrying a 400 or a 401 only
wastes time. Uses `httpx2`, the HTTP client the MCP SDK ships with.
"""

from __future__ import annotations

import json
import random
import time
from collections.abc import Callable, Mapping
from typing import Any

import httpx2

from verigraph.errors import VeriGraphError

RETRY_STATUS = frozenset({408, 409, 425, 429, 500, 502, 503, 504, 529})


class LLMEndpointError(VeriGraphError):
    """The model endpoint failed in a way retrying cannot fix (or retries ran out)."""


def _message(response: httpx2.Response) -> str:
    try:
        body = response.json()
    except (ValueError, UnicodeDecodeError):
        return response.text[:300]
    if isinstance(body, dict):
        err = body.get("error", body)
        if isinstance(err, dict):
            return str(err.get("message") or err)[:300]
        return str(err)[:300]
    return str(body)[:300]


def _retry_after(response: httpx2.Response) -> float | None:
    value = response.headers.get("retry-after")
    if value is None:
        return None
    try:
        return max(0.0, float(value))
    except ValueError:
        return None


class JsonHttpClient:
    """POST JSON, get JSON back; retries transient failures `retries` times."""

    def __init__(self, base_url: str, *, headers: Mapping[str, str] | None = None,
                 timeout: float = 120.0, retries: int = 4, backoff: float = 0.5,
                 max_backoff: float = 20.0, sleep: Callable[[float], None] = time.sleep,
                 seed: int | None = None) -> None:
        if not base_url.startswith(("http://", "https://")):
            raise VeriGraphError(f"not an HTTP URL: {base_url!r}", field="base_url",
                                 value=base_url, fix="give e.g. http://127.0.0.1:8080/v1")
        self.base_url = base_url.rstrip("/")
        self.retries = retries
        self.backoff = backoff
        self.max_backoff = max_backoff
        self.sleep = sleep
        self.attempts = 0
        self._jitter = random.Random(seed)
        self._client = httpx2.Client(headers=dict(headers or {}),
                                     timeout=httpx2.Timeout(timeout, connect=10.0))

    def _delay(self, attempt: int, hint: float | None) -> float:
        if hint is not None:
            return min(hint, self.max_backoff)
        base = min(self.backoff * (2 ** attempt), self.max_backoff)
        return base * (0.5 + self._jitter.random() / 2)

    def post(self, path: str, payload: Mapping[str, Any]) -> dict[str, Any]:
        """POST `payload` to base_url + path and return the decoded JSON object."""
        url = f"{self.base_url}/{path.lstrip('/')}"
        last: str = "no attempt made"
        for attempt in range(self.retries + 1):
            self.attempts += 1
            hint: float | None = None
            try:
                response = self._client.post(url, json=dict(payload))
            except (httpx2.TransportError, httpx2.TimeoutException) as exc:
                last = f"{type(exc).__name__}: {exc}"
            else:
                if response.status_code < 300:
                    try:
                        data = response.json()
                    except (ValueError, UnicodeDecodeError):
                        last = f"HTTP {response.status_code} with a body that is not JSON: " \
                               f"{response.text[:200]!r}"
                    else:
                        if isinstance(data, dict):
                            return data
                        last = f"expected a JSON object, got {json.dumps(data)[:200]}"
                    # A garbled 2xx body is treated as transient (proxies do this).
                elif response.status_code in RETRY_STATUS:
                    last = f"HTTP {response.status_code}: {_message(response)}"
                    hint = _retry_after(response)
                else:
                    raise LLMEndpointError(
                        f"{url} answered HTTP {response.status_code}: {_message(response)}",
                        field="base_url/model/api key", value=response.status_code,
                        fix="check the model name, the API key and the request options "
                            "(e.g. --response-format) for this endpoint")
            if attempt < self.retries:
                self.sleep(self._delay(attempt, hint))
        raise LLMEndpointError(f"{url} failed after {self.retries + 1} attempt(s): {last}",
                               field="base_url", value=url,
                               fix="check that the server is running and reachable, or raise "
                                   "--retries / --timeout")

    def close(self) -> None:
        self._client.close()
