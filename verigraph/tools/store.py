"""Episodes: the state behind an `episode_id`, kept in a bounded, thread-safe store.

The MCP protocol has no sessions, so every stateful tool names its episode. Ids come
from `secrets.token_urlsafe` (unguessable), and each episode belongs to the caller that
opened it (docs/architecture.md: over HTTP its token, else its address; over stdio the
one peer, `local` like in-process calls): another caller's id answers exactly as an unknown one
does, so an id that leaks reads or ends nothing.

Shares (docs/server.md, "Episodes per caller"): the store holds at most `max_episodes`,
and one caller at most `share` of them (a caller over its share is refused by name, the
others are unaffected). When the store is full, expired episodes go first, then the
least recently used one idle for `reclaim_after` seconds or more, whoever owns it; only
then is a new episode refused. Each episode has its own lock so concurrent HTTP
requests on one episode serialise while other episodes proceed.
"""

from __future__ import annotations

import secrets
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from pydantic import BaseModel, Field

from verigraph.actions.execution import World
from verigraph.actions.feedback import Violation
from verigraph.actions.model import AnyAction
from verigraph.graph.dictionary import InlineDictionary
from verigraph.graph.goal import Goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState
from verigraph.tools.errors import (
    EpisodeLimitError,
    EpisodeShareError,
    EpisodeStateError,
    UnknownEpisodeError,
)
from verigraph.tools.executors import SceneCheck
from verigraph.tools.images import KeptImage

DEFAULT_K = 3
DEFAULT_THRESHOLD = 5
DEFAULT_MAX_EPISODES = 256
DEFAULT_IDLE_TIMEOUT_S = 3600.0
DEFAULT_RECLAIM_IDLE_S = 600.0  # a full store replaces episodes idle this long
LOCAL_CALLER = "local"  # in-process tool calls (CLI, environment, tests) and stdio's peer

# Set while a tool runs on an event loop thread (see `non_blocking`).
_NON_BLOCKING: ContextVar[bool] = ContextVar("verigraph_non_blocking", default=False)
# Who the running call comes from (see `calling_as`); copied into worker threads.
_CALLER: ContextVar[str] = ContextVar("verigraph_caller", default=LOCAL_CALLER)


@contextmanager
def calling_as(caller: str) -> Iterator[None]:
    """Within this block the store acts for `caller`: new episodes are its own, counted
    in its share, and only its own episodes are found. The server sets it per request."""
    if not caller:
        raise ValueError("a caller needs a name")
    token = _CALLER.set(caller)
    try:
        yield
    finally:
        _CALLER.reset(token)


def current_caller() -> str:
    return _CALLER.get()


def default_share(max_episodes: int) -> int:
    """A quarter of the store (at least one): four busy callers fill it, a fifth finds
    room once one of them ends or idles an episode."""
    return max(1, max_episodes // 4)


class WouldBlock(Exception):  # noqa: N818 - a signal, not an error
    """Raised in non-blocking mode instead of waiting for a lock or a simulator.

    Nothing has changed when it is raised (episodes are only touched under the lock),
    so the caller can simply run the same call again on a worker thread.
    """


@contextmanager
def non_blocking() -> Iterator[None]:
    """Within this block `EpisodeStore.use` never waits: it raises WouldBlock instead.

    The MCP server runs fast tools directly on its event loop (no thread hop); this
    keeps one busy episode from stalling every other client.
    """
    token = _NON_BLOCKING.set(True)
    try:
        yield
    finally:
        _NON_BLOCKING.reset(token)


class TraceEntry(BaseModel):
    """One execute_actions call, as Algorithm 1 sees an iteration."""

    call: int = Field(description="1-based index of the execute_actions call")
    proposed: list[str] = Field(description="actions proposed in this call (text form)")
    executed: list[str] = Field(description="the valid prefix that was applied")
    violation: Violation | None = None
    done: bool = Field(default=False, description="the end token was among the actions")
    tau: int = Field(description="consecutive failed calls after this one")
    goal_satisfied: bool | None = None


MAX_REQUEST_RECORDS = 32


@dataclass
class RequestRecords:
    """request_id -> (proposed actions, result as JSON) of applied execute_actions calls.

    Plain, JSON-serialisable data (a durable store saves `records` with the episode),
    bounded to the MAX_REQUEST_RECORDS most recent: a retry comes soon after its call.
    """

    records: dict[str, dict[str, Any]] = field(default_factory=dict)

    def result(self, request_id: str, proposed: list[str]) -> dict[str, Any] | None:
        """The recorded result of `request_id`, or None if it has not been applied."""
        record = self.records.get(request_id)
        if record is None:
            return None
        if record["proposed"] != proposed:
            raise EpisodeStateError(
                f"request_id '{request_id}' was already used for other actions "
                f"({'; '.join(record['proposed'])[:200]})", field="request_id",
                value=request_id, fix="use a new request_id for each new call, and the same "
                                      "one only to retry the identical call")
        return dict(record["result"])

    def record(self, request_id: str, proposed: list[str], result: dict[str, Any]) -> None:
        self.records[request_id] = {"proposed": proposed, "result": result}
        while len(self.records) > MAX_REQUEST_RECORDS:
            del self.records[next(iter(self.records))]


# Fields that belong to this process only: not counted as changes, never stored.
PER_PROCESS = frozenset({"lock", "last_used"})


@dataclass(eq=False)
class LiveEpisode:
    """Mutable state of one planning episode; only touched while its lock is held."""

    id: str
    state: WorldState | None
    source: str
    k: int = DEFAULT_K
    t: int = DEFAULT_THRESHOLD
    goal: Goal | None = None
    instruction: str | None = None
    world: World | None = None
    executor: str = "graph"  # graph, sim2d or arm:<driver>
    scene_check: SceneCheck | None = None  # arm episodes: observed scene vs graph at start
    goal_world: Any = None  # a simulator world in the goal state, for rendering it
    image: np.ndarray | KeptImage | None = None  # kept encoded (see __post_init__)
    initial_graph: SceneGraph | None = None
    dictionary_name: str | InlineDictionary | None = None  # the one load_scene was given
    tau: int = 0
    calls: int = 0
    executed: list[AnyAction] = field(default_factory=list)
    trace: list[TraceEntry] = field(default_factory=list)
    last_violation: Violation | None = None
    done: bool = False
    requests: RequestRecords = field(default_factory=RequestRecords)
    extras: dict[str, Any] = field(default_factory=dict)  # small JSON records, persisted
    initial_world: dict[str, Any] | None = None  # sim2d world as loaded (JSON): for replays
    owner: str = ""  # the caller that opened it ("": stored before episodes had owners)
    lock: threading.Lock = field(default_factory=threading.Lock, repr=False)
    last_used: float = 0.0

    def __post_init__(self) -> None:
        if isinstance(self.image, np.ndarray):
            self.image = KeptImage.of(self.image)  # perception is done: keep it small

    def __setattr__(self, name: str, value: Any) -> None:
        # Durable stores write an episode back only when it changed: every assignment
        # counts (in-place edits of a list or of `extras` call `mark_changed`).
        object.__setattr__(self, name, value)
        if name not in PER_PROCESS:
            self.__dict__["changes"] = self.__dict__.get("changes", 0) + 1

    @property
    def changes(self) -> int:
        """Assignments so far; a store compares it before and after a tool call."""
        return int(self.__dict__.get("changes", 0))

    def mark_changed(self) -> None:
        """Record an in-place change (e.g. to `extras`) so that durable stores save it."""
        self.__dict__["changes"] = self.changes + 1

    @property
    def threshold_reached(self) -> bool:
        return self.tau >= self.t

    def require_state(self) -> WorldState:
        """The current graph, or an error while the episode still waits for one."""
        if self.state is None:
            raise EpisodeStateError(
                "this episode has no scene graph yet (it was loaded from an image)",
                field="episode_id", value=self.id,
                fix="call get_scene_image, describe the image as a scene graph and send it "
                    "with submit_scene_graph(episode_id, graph)")
        return self.state


def owned(owner: str) -> bool:
    """Whether the current caller may use an episode of `owner` (its own; one stored
    before episodes had owners is anyone's who holds its id, as it was then)."""
    return owner in ("", _CALLER.get())


def new_episode_id() -> str:
    """128 random bits, URL-safe: usable in resource URIs and impossible to guess."""
    return "ep_" + secrets.token_urlsafe(16)


class EpisodeStore:
    """In-memory episodes by id, bounded, safe to use from many threads at once."""

    # Whether reaching an episode may wait on I/O (a database or a network): then tool
    # calls go straight to a worker thread instead of trying the event loop first.
    blocking_io = False

    def __init__(self, max_episodes: int = DEFAULT_MAX_EPISODES,
                 idle_timeout: float = DEFAULT_IDLE_TIMEOUT_S,
                 clock: Callable[[], float] = time.monotonic,
                 on_drop: Callable[[LiveEpisode], None] | None = None,
                 share: int | None = None,
                 reclaim_after: float = DEFAULT_RECLAIM_IDLE_S) -> None:
        if max_episodes < 1:
            raise ValueError("max_episodes must be at least 1")
        if share is not None and not 1 <= share <= max_episodes:
            raise ValueError("share must be between 1 and max_episodes")
        if not reclaim_after > 0:
            raise ValueError("reclaim_after must be positive")
        self.max_episodes = max_episodes
        self.share = max_episodes if share is None else share  # None: one caller, all of it
        self.idle_timeout = idle_timeout
        self.reclaim_after = reclaim_after
        self._clock = clock
        self._on_drop = on_drop  # releases what an ended or evicted episode holds (an arm)
        self._episodes: dict[str, LiveEpisode] = {}
        self._lock = threading.Lock()

    def __len__(self) -> int:
        with self._lock:
            return len(self._episodes)

    def ids(self) -> list[str]:
        with self._lock:
            return list(self._episodes)

    def share_error(self, caller: str, held: int) -> EpisodeShareError:
        """The refusal of a caller holding its share: names the share and every way out."""
        return EpisodeShareError(
            f"this caller ({caller}) already holds {held} open episode(s), its share of "
            f"the server's {self.max_episodes} (--episodes-per-caller {self.share}); other "
            "callers are not affected", field="load_scene", value=held,
            fix="call end_episode on episodes you no longer need, wait until idle ones are "
                f"dropped ({self.idle_timeout:.0f} s unused), or start the server with a "
                "larger --episodes-per-caller")

    def full_error(self, held: int) -> EpisodeLimitError:
        return EpisodeLimitError(
            f"the server already holds {self.max_episodes} open episodes, none of them idle "
            f"for {self.reclaim_after:.0f} s (which a new episode would replace)",
            field="load_scene", value=held,
            fix="call end_episode on episodes you no longer need (idle episodes are "
                f"dropped after {self.idle_timeout:.0f} s), or start the server with a "
                "larger --max-episodes")

    def add(self, make: Callable[[str], LiveEpisode]) -> LiveEpisode:
        """Insert the episode `make(new_id)` builds, owned by the current caller.

        Refused when the caller holds its share; when the store is full, expired
        episodes are dropped and then the least recently used one idle for
        `reclaim_after` seconds (see the module docstring), else refused."""
        caller = current_caller()
        now = self._clock()
        dropped: list[LiveEpisode] = []
        try:
            with self._lock:
                dropped = self._drop_expired(now)
                held = sum(1 for ep in self._episodes.values() if ep.owner == caller)
                if held >= self.share < self.max_episodes:  # one share of all: "full"
                    raise self.share_error(caller, held)
                if len(self._episodes) >= self.max_episodes:
                    dropped += self._reclaim(now)
                if len(self._episodes) >= self.max_episodes:
                    raise self.full_error(held)
                episode_id = new_episode_id()
                while episode_id in self._episodes:  # pragma: no cover - 2**-128
                    episode_id = new_episode_id()
                episode = make(episode_id)
                episode.owner = caller
                episode.last_used = now
                self._episodes[episode_id] = episode
                return episode
        finally:
            for ep in dropped:
                self._dropped(ep)

    def _drop_expired(self, now: float) -> list[LiveEpisode]:
        """Forget the episodes idle longer than idle_timeout (the store's lock is held;
        the caller releases what they hold)."""
        gone = [ep for ep in self._episodes.values()
                if now - ep.last_used > self.idle_timeout and not ep.lock.locked()]
        for ep in gone:
            del self._episodes[ep.id]
        return gone

    def _reclaim(self, now: float) -> list[LiveEpisode]:
        """Forget the least recently used episode idle for `reclaim_after` or more, if
        there is one (the store's lock is held)."""
        idle = [ep for ep in self._episodes.values()
                if now - ep.last_used >= self.reclaim_after and not ep.lock.locked()]
        if not idle:
            return []
        oldest = min(idle, key=lambda ep: ep.last_used)
        del self._episodes[oldest.id]
        return [oldest]

    def evict_idle(self) -> None:
        """Drop episodes unused for longer than idle_timeout (and release their arms)."""
        with self._lock:
            stale = self._drop_expired(self._clock())
        for ep in stale:
            self._dropped(ep)

    def _dropped(self, episode: LiveEpisode) -> None:
        if self._on_drop is not None:
            self._on_drop(episode)

    def _get(self, episode_id: Any) -> LiveEpisode:
        if not isinstance(episode_id, str):
            raise UnknownEpisodeError(repr(episode_id))
        with self._lock:
            episode = self._episodes.get(episode_id)
        if episode is None or not owned(episode.owner):
            raise UnknownEpisodeError(episode_id)  # another caller's: as if there were none
        return episode

    def peek(self, episode_id: str) -> LiveEpisode:
        """The episode without taking its lock: only for calls that must not wait for a
        running one (arm_stop, arm_status), and that touch only thread-safe parts."""
        return self._get(episode_id)

    @contextmanager
    def use(self, episode_id: str) -> Iterator[LiveEpisode]:
        """Hold the episode's lock for the duration of one tool call.

        In `non_blocking` mode, an episode that is busy or has a (slow) simulator or
        arm raises WouldBlock instead of waiting.
        """
        episode = self._get(episode_id)
        if _NON_BLOCKING.get():
            slow = episode.world is not None or episode.executor != "graph"
            if slow or not episode.lock.acquire(blocking=False):
                raise WouldBlock(episode_id)
        else:
            episode.lock.acquire()
        try:
            # It may have been ended while we waited for the lock.
            with self._lock:
                if self._episodes.get(episode_id) is not episode:
                    raise UnknownEpisodeError(episode_id)
            episode.last_used = self._clock()
            yield episode
        finally:
            episode.lock.release()

    def remove(self, episode_id: str) -> None:
        """Forget an episode and release its arm (the caller holds its lock, see `use`)."""
        with self._lock:
            episode = self._episodes.pop(episode_id, None)
        if episode is not None:
            self._dropped(episode)

    def close(self) -> None:
        """Release the store's connections (nothing to release in memory)."""
