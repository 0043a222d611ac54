"""Choosing an episode store from a URL: memory://, sqlite:///path or redis://host:port/db.

`verigraph serve` defaults to SQLite under the user's data directory
($XDG_DATA_HOME/verigraph/episodes.db, else ~/.local/share/verigraph/episodes.db), so an
episode survives a restart; the in-process Toolbox defaults to memory:// (tests and
one-off runs keep nothing on disk).
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from urllib.parse import urlsplit

from verigraph.tools.errors import StoreError
from verigraph.tools.store import (
    DEFAULT_IDLE_TIMEOUT_S,
    DEFAULT_MAX_EPISODES,
    DEFAULT_RECLAIM_IDLE_S,
    EpisodeStore,
    LiveEpisode,
)
from verigraph.tools.store_backend import Backend, redacted
from verigraph.tools.store_durable import DurableStore

STORE_HELP = ("memory://, sqlite:///path/to/episodes.db or redis://host:port/db "
              "(default for the server: sqlite under the user's data directory)")


def default_store_url() -> str:
    """SQLite in $XDG_DATA_HOME/verigraph (or ~/.local/share/verigraph)."""
    base = os.environ.get("XDG_DATA_HOME") or str(Path.home() / ".local" / "share")
    return f"sqlite:///{Path(base) / 'verigraph' / 'episodes.db'}"


def open_backend(url: str) -> Backend:
    """The backend a durable URL names; StoreError names the accepted forms."""
    scheme = urlsplit(url).scheme
    if scheme == "sqlite":
        from verigraph.tools.store_sqlite import SqliteBackend
        path = url[len("sqlite://"):]
        if not path.startswith("/") or len(path) < 2:
            raise StoreError("a SQLite store URL needs a path", field="--store", value=url,
                             fix="use sqlite:///absolute/path/episodes.db")
        return SqliteBackend(path)
    if scheme in ("redis", "rediss", "unix"):
        from verigraph.tools.store_redis import RedisBackend
        return RedisBackend(url)
    raise StoreError(f"unknown store '{url[:64]}'", field="--store", value=url[:64],
                     fix=f"use {STORE_HELP}")


def open_store(url: str, max_episodes: int = DEFAULT_MAX_EPISODES,
               idle_timeout: float = DEFAULT_IDLE_TIMEOUT_S,
               on_drop: Callable[[LiveEpisode], None] | None = None,
               share: int | None = None,
               reclaim_after: float = DEFAULT_RECLAIM_IDLE_S) -> EpisodeStore:
    """The store `url` names; `share` episodes per caller (None: the whole store)."""
    if url in ("memory://", "memory"):
        return EpisodeStore(max_episodes, idle_timeout, on_drop=on_drop, share=share,
                            reclaim_after=reclaim_after)
    return DurableStore(open_backend(url), max_episodes, idle_timeout, on_drop=on_drop,
                        share=share, reclaim_after=reclaim_after)


__all__ = ["STORE_HELP", "default_store_url", "open_backend", "open_store", "redacted"]
