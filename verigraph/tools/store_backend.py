"""What a durable episode store needs from its backend (SQLite, Redis): versioned records.

Every method is one atomic step on the shared store; `DurableStore` (store_durable)
builds the episode store's contract on top.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol
from urllib.parse import urlsplit


@dataclass(frozen=True)
class StoredEpisode:
    """What an operator sees of a stored episode without decoding it."""

    id: str
    version: int
    created_at: float
    updated_at: float
    last_used: float
    size: int


class Backend(Protocol):
    """Versioned records by id; every method is one atomic step on the shared store."""

    url: str

    def create(self, episode_id: str, record: str, now: float, cap: int, idle: float
               ) -> bool:
        """Insert version 1 unless `cap` live episodes exist (expired ones are dropped)."""

    def check(self, episode_id: str, now: float, idle: float) -> int | None:
        """The live version (refreshing the idle timer), or None when gone/expired."""

    def load(self, episode_id: str, now: float, idle: float) -> str | None:
        """The record JSON of a live episode, or None."""

    def swap(self, episode_id: str, expected: int, record: str, now: float, idle: float
             ) -> bool:
        """Store `record` as version expected+1 if the version is still `expected`."""

    def delete(self, episode_id: str) -> bool: ...

    def sweep(self, now: float, idle: float) -> list[str]:
        """Drop episodes idle for longer than `idle`; the ids dropped."""

    def entries(self, now: float, idle: float) -> list[StoredEpisode]: ...

    def close(self) -> None: ...


def redacted(url: str) -> str:
    """The URL without a password, for logs, listings and error messages."""
    parts = urlsplit(url)
    if parts.password is None:
        return url
    return url.replace(f":{parts.password}@", ":***@", 1)
