"""What a durable episode store needs from its backend (SQLite, Redis): versioned records.

Every method is one atomic step on the shared store; `DurableStore` (store_durable)
builds the episode store's contract on top.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal, Protocol
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
    owner: str = ""  # the caller that opened it ("": stored before episodes had owners)


@dataclass(frozen=True)
class Admission:
    """What `Backend.create` did: `created`, or refused because the owner holds its
    `share` or the store is full; `held` is the owner's live episodes before it, and
    `reclaimed` the idle episode dropped to make room (if one was)."""

    outcome: Literal["created", "share", "full"]
    held: int
    reclaimed: str | None = None


@dataclass(frozen=True)
class Limits:
    """The store's shape for `Backend.create` (see tools.store): `cap` live episodes in
    all, `share` per owner, expired after `idle` s unused, reclaimable (the least
    recently used first) after `reclaim_after` s unused when the store is full."""

    cap: int
    share: int
    idle: float
    reclaim_after: float


class Backend(Protocol):
    """Versioned records by id; every method is one atomic step on the shared store."""

    url: str

    def create(self, episode_id: str, owner: str, record: str, now: float, limits: Limits
               ) -> Admission:
        """Insert version 1 for `owner` within `limits`: expired episodes are dropped
        first; an owner holding its share is refused; a full store drops its least
        recently used episode idle for `reclaim_after`, else refuses."""

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
