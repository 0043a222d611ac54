"""Episodes that outlive the process: a local cache in front of a shared backend.

`DurableStore` keeps the in-memory store's contract (ids, limits, idle eviction, one
lock per episode within a process) and adds a backend (SQLite or Redis) that holds the
`EpisodeRecord` of every episode under a version number. Each tool call:

1. asks the backend for the episode's version (one cheap round trip, which also
   refreshes its idle TTL) and reuses the cached, already decoded episode when that
   version is the one it holds, else loads and decodes the record;
2. runs the tool on the episode under the process-local lock;
3. if the call changed the episode, writes the new record with a compare-and-set on
   the version. When another process committed first, nothing is written and
   `StaleEpisodeError` makes the tool host run the call again on the new state, so
   concurrent calls from several replicas serialise: no move is lost or applied twice.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

from pydantic import ValidationError

from verigraph.tools.errors import (
    StaleEpisodeError,
    StoreError,
    UnknownEpisodeError,
)
from verigraph.tools.records import (
    SCHEMA_VERSION,
    EpisodeRecord,
    fill_episode,
    from_record,
    to_record,
    world_extras,
)
from verigraph.tools.store import (
    _NON_BLOCKING,
    DEFAULT_IDLE_TIMEOUT_S,
    DEFAULT_MAX_EPISODES,
    DEFAULT_RECLAIM_IDLE_S,
    EpisodeStore,
    LiveEpisode,
    WouldBlock,
    current_caller,
    new_episode_id,
    owned,
)
from verigraph.tools.store_backend import Backend, Limits

Revive = Callable[[LiveEpisode], None]


def _note_world_extras(episode: LiveEpisode) -> None:
    """Keep what the world keeps with the episode (an arm's stop latches without a
    commit), so a process that reloads the episode restores it (latches again)."""
    kept = world_extras(episode.world)
    if any(episode.extras.get(key, False) != value for key, value in kept.items()):
        episode.extras.update(kept)
        episode.mark_changed()


def decode_record(text: str) -> EpisodeRecord:
    """The stored record; one this version cannot read is a StoreError that says why
    (another schema version, or a damaged record) and never quotes the record."""
    try:
        return EpisodeRecord.model_validate_json(text)
    except ValidationError as exc:
        found = re.search(r'"schema_version":\s*(\d{1,9})\b', text[:4096])
        first = exc.errors()[0]
        where = ".".join(str(p) for p in first["loc"]) or "the record"
        if found is not None and int(found.group(1)) != SCHEMA_VERSION:
            raise StoreError(
                f"a stored episode was written with schema version {found.group(1)}; this "
                f"server reads version {SCHEMA_VERSION}", field="episode_id", value=None,
                fix="run the server version that wrote it, or drop the episode with "
                    "verigraph episodes purge ID") from None
        raise StoreError(
            f"a stored episode is damaged and cannot be read: {exc.error_count()} "
            f"problem(s), the first at {where[:80]} ({first['type']})", field="episode_id",
            value=None, fix="drop the episode with verigraph episodes purge ID and start a "
                            "new one with load_scene") from None


def _stale(episode_id: str) -> StaleEpisodeError:
    return StaleEpisodeError("the episode changed in another process during this call",
                             field="episode_id", value=episode_id,
                             fix="nothing was applied; send the call again")


class DurableStore(EpisodeStore):
    """An EpisodeStore whose episodes live in a backend shared by processes."""

    blocking_io = True

    def __init__(self, backend: Backend, max_episodes: int = DEFAULT_MAX_EPISODES,
                 idle_timeout: float = DEFAULT_IDLE_TIMEOUT_S,
                 clock: Callable[[], float] = time.time,
                 on_drop: Callable[[LiveEpisode], None] | None = None,
                 share: int | None = None,
                 reclaim_after: float = DEFAULT_RECLAIM_IDLE_S) -> None:
        super().__init__(max_episodes, idle_timeout, clock, on_drop, share, reclaim_after)
        self.backend = backend
        self.revive: Revive | None = None  # reconnects an arm episode's driver on load
        self._versions: dict[str, int] = {}
        self._created: dict[str, float] = {}

    def __len__(self) -> int:
        return len(self.backend.entries(self._clock(), self.idle_timeout))

    def ids(self) -> list[str]:
        return [e.id for e in self.backend.entries(self._clock(), self.idle_timeout)]

    def add(self, make: Callable[[str], LiveEpisode]) -> LiveEpisode:
        if _NON_BLOCKING.get():
            raise WouldBlock("load_scene")
        now = self._clock()
        caller = current_caller()
        episode = make(new_episode_id())
        episode.owner = caller
        episode.last_used = now
        record = to_record(episode, version=1, created_at=now, updated_at=now)
        admission = self.backend.create(
            episode.id, caller, record.model_dump_json(), now,
            Limits(self.max_episodes, self.share, self.idle_timeout, self.reclaim_after))
        if admission.outcome == "share":
            raise self.share_error(caller, admission.held)
        if admission.outcome == "full":
            raise self.full_error(admission.held)
        if admission.reclaimed is not None:
            self._forget(admission.reclaimed)  # a cached copy here: release its arm
        with self._lock:
            self._episodes[episode.id] = episode
            self._versions[episode.id] = 1
            self._created[episode.id] = now
        return episode

    def evict_idle(self) -> None:
        """Let the backend drop idle episodes; forget cached ones idle here as long."""
        now = self._clock()
        self.backend.sweep(now, self.idle_timeout)
        with self._lock:
            stale = [ep for ep in self._episodes.values()
                     if now - ep.last_used > self.idle_timeout and not ep.lock.locked()]
        for ep in stale:
            self._forget(ep.id)

    def _forget(self, episode_id: str) -> None:
        """Drop the cached copy (not the stored record); a later call reloads it."""
        with self._lock:
            episode = self._episodes.pop(episode_id, None)
            self._versions.pop(episode_id, None)
            self._created.pop(episode_id, None)
        if episode is not None:
            self._dropped(episode)

    def _get(self, episode_id: Any) -> LiveEpisode:
        if not isinstance(episode_id, str):
            raise UnknownEpisodeError(repr(episode_id))
        with self._lock:
            cached = self._episodes.get(episode_id)
        if cached is not None:
            if not owned(cached.owner):
                raise UnknownEpisodeError(episode_id)  # another caller's: as if none
            return cached
        text = self.backend.load(episode_id, self._clock(), self.idle_timeout)
        if text is None:
            raise UnknownEpisodeError(episode_id)
        record = decode_record(text)
        episode = from_record(record)
        if not owned(episode.owner):  # refused before an arm is reconnected for it
            raise UnknownEpisodeError(episode_id)
        if self.revive is not None:
            self.revive(episode)
        with self._lock:
            cached = self._episodes.get(episode_id)
            if cached is None:
                self._episodes[episode_id] = episode
                self._versions[episode_id] = record.version
                self._created[episode_id] = record.created_at
                return episode
        self._dropped(episode)  # another thread loaded it first
        if not owned(cached.owner):
            raise UnknownEpisodeError(episode_id)
        return cached

    def _refresh(self, episode: LiveEpisode, now: float) -> int:
        """Make the cached episode the stored one; its current version."""
        with self._lock:
            if self._episodes.get(episode.id) is not episode:
                # Ended, or this copy was dropped while we waited: the tool host runs the
                # call again, which loads the stored episode (or reports it gone).
                raise _stale(episode.id)
            cached = self._versions[episode.id]
        version = self.backend.check(episode.id, now, self.idle_timeout)
        if version is None:
            self._forget(episode.id)
            raise UnknownEpisodeError(episode.id)
        if version != cached:
            text = self.backend.load(episode.id, now, self.idle_timeout)
            if text is None:
                self._forget(episode.id)
                raise UnknownEpisodeError(episode.id)
            record = decode_record(text)
            live_arm = episode.world if episode.executor.startswith("arm:") else None
            fill_episode(episode, record)
            if live_arm is not None:
                object.__setattr__(episode, "world", live_arm)  # keep the connection
            elif self.revive is not None:
                self.revive(episode)
            version = record.version
            with self._lock:
                self._versions[episode.id] = version
        return version

    @contextmanager
    def use(self, episode_id: str) -> Iterator[LiveEpisode]:
        """One tool call on the stored episode; its changes are committed at the end."""
        if _NON_BLOCKING.get():
            raise WouldBlock(episode_id)  # the backend is I/O: run on a worker thread
        episode = self._get(episode_id)
        with episode.lock:
            now = self._clock()
            version = self._refresh(episode, now)
            episode.last_used = now
            before = episode.changes
            try:
                yield episode
            except BaseException:
                if episode.changes != before:
                    self._forget(episode_id)  # half-changed: reload the stored state
                raise
            _note_world_extras(episode)
            if episode.changes == before or episode_id not in self._episodes:
                return  # read only, or ended (remove() deleted the record)
            record = to_record(episode, version=version + 1,
                               created_at=self._created.get(episode_id, now), updated_at=now)
            try:
                swapped = self.backend.swap(episode_id, version, record.model_dump_json(),
                                            now, self.idle_timeout)
            except StoreError:
                self._forget(episode_id)  # not saved: the next call reloads the stored state
                raise
            if not swapped:
                self._forget(episode_id)
                raise _stale(episode_id)
            with self._lock:
                self._versions[episode_id] = version + 1

    def remove(self, episode_id: str) -> None:
        with self._lock:
            episode = self._episodes.pop(episode_id, None)
            self._versions.pop(episode_id, None)
            self._created.pop(episode_id, None)
        self.backend.delete(episode_id)
        if episode is not None:
            self._dropped(episode)

    def close(self) -> None:
        self.backend.close()


__all__ = ["DurableStore", "decode_record"]
