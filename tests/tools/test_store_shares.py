"""Per-caller shares of every episode store (memory://, sqlite:///, redis:// on a real
server): a caller holding its share is refused by name and the others are not; a full
store replaces its least recently used idle episode; one caller's ids reach nothing for
another; and two tool hosts on one durable store count a caller's episodes together."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from pathlib import Path

import pytest
from store_helpers import redis_url  # noqa: F401 - the session fixture

from verigraph.tools import (
    EpisodeLimitError,
    EpisodeShareError,
    LiveEpisode,
    Toolbox,
    ToolConfig,
    UnknownEpisodeError,
    calling_as,
)
from verigraph.tools.store import EpisodeStore
from verigraph.tools.store_durable import DurableStore
from verigraph.tools.stores import open_backend


class Clock:
    """Wall-clock seconds that a test moves on by hand (near the real time, so a Redis
    key's real TTL never runs out within the test)."""

    def __init__(self) -> None:
        self.now = time.time()

    def __call__(self) -> float:
        return self.now


def store_for(url: str, clock: Callable[[], float], cap: int, share: int,
              reclaim_after: float = 600.0) -> EpisodeStore:
    if url == "memory://":
        return EpisodeStore(cap, 3600.0, clock=clock, share=share, reclaim_after=reclaim_after)
    return DurableStore(open_backend(url), cap, 3600.0, clock=clock, share=share,
                        reclaim_after=reclaim_after)


def add(store: EpisodeStore, caller: str) -> str:
    with calling_as(caller):
        return store.add(lambda eid: LiveEpisode(id=eid, state=None, source="test")).id


def touch(store: EpisodeStore, caller: str, episode_id: str) -> None:
    with calling_as(caller), store.use(episode_id) as episode:
        episode.calls += 1  # a change: the durable stores write it back


def test_a_caller_at_its_share_is_refused_by_name_and_the_others_are_not(
        store_url: str) -> None:
    store = store_for(store_url, Clock(), cap=6, share=2)
    mine = [add(store, "token aaa"), add(store, "token aaa")]
    with pytest.raises(EpisodeShareError) as err:
        add(store, "token aaa")
    assert "token aaa" in err.value.message and "--episodes-per-caller 2" in err.value.message
    assert err.value.field == "load_scene" and err.value.value == 2
    assert "end_episode" in (err.value.fix or "") and "--episodes-per-caller" in (
        err.value.fix or "")
    assert isinstance(err.value, EpisodeLimitError)  # an older client's handler still fits
    others = [add(store, "token bbb"), add(store, "address 10.0.0.7")]
    assert len(set(store.ids())) == 4 and set(mine + others) == set(store.ids())
    with calling_as("token aaa"), store.use(mine[0]):
        store.remove(mine[0])  # end_episode gives the slot back
    add(store, "token aaa")


def test_a_full_store_replaces_its_least_recently_used_idle_episode(store_url: str) -> None:
    clock = Clock()
    store = store_for(store_url, clock, cap=3, share=3, reclaim_after=600)
    oldest, older = add(store, "token aaa"), add(store, "token aaa")
    clock.now += 1
    busy = add(store, "token bbb")
    with pytest.raises(EpisodeLimitError) as err:  # full, and nothing idle long enough
        add(store, "token ccc")
    assert not isinstance(err.value, EpisodeShareError)
    assert "600 s" in err.value.message and "--max-episodes" in (err.value.fix or "")
    clock.now += 700
    touch(store, "token aaa", oldest)  # used again: now the most recent
    touch(store, "token bbb", busy)
    newcomer = add(store, "token ccc")  # `older` has been idle 700 s: it gives way
    assert set(store.ids()) == {oldest, busy, newcomer}
    with calling_as("token aaa"), pytest.raises(UnknownEpisodeError):
        touch(store, "token aaa", older)
    with pytest.raises(EpisodeLimitError):  # the rest were used within 600 s
        add(store, "token ddd")


def test_expired_episodes_do_not_count_against_a_share(store_url: str) -> None:
    clock = Clock()
    store = store_for(store_url, clock, cap=4, share=1)
    first = add(store, "token aaa")
    clock.now += 3601  # past the idle timeout
    second = add(store, "token aaa")
    assert store.ids() == [second]
    with calling_as("token aaa"), pytest.raises(UnknownEpisodeError):
        touch(store, "token aaa", first)


def test_one_callers_ids_reach_nothing_for_another(store_url: str) -> None:
    store = store_for(store_url, Clock(), cap=4, share=4)
    theirs = add(store, "token aaa")
    with calling_as("token bbb"):
        for reach in (store.peek, lambda i: store.use(i).__enter__()):
            with pytest.raises(UnknownEpisodeError) as err:
                reach(theirs)
            assert err.value.message == UnknownEpisodeError(theirs).message
    touch(store, "token aaa", theirs)  # still the owner's, unchanged by the attempts
    with calling_as("token aaa"), store.use(theirs) as episode:
        assert episode.calls == 1 and episode.owner == "token aaa"


def test_the_toolbox_acts_as_the_local_caller_with_the_whole_store() -> None:
    box = Toolbox(config=ToolConfig(max_episodes=3))
    for _ in range(3):
        box.call("load_scene", {"scene_id": "three_blocks"})
    with pytest.raises(EpisodeLimitError) as err:
        box.call("load_scene", {"scene_id": "three_blocks"})
    assert not isinstance(err.value, EpisodeShareError)  # one caller: no share below it


@pytest.mark.parametrize("kind", ["sqlite", "redis"])
def test_two_tool_hosts_count_a_callers_episodes_together(
        kind: str, tmp_path: Path, request: pytest.FixtureRequest) -> None:
    if kind == "sqlite":
        url = f"sqlite:///{tmp_path}/episodes.db"
    else:
        url = request.getfixturevalue("redis_url")
        import redis
        redis.Redis.from_url(url).flushdb()
    hosts = [store_for(url, time.time, cap=64, share=5) for _ in range(2)]
    admitted: list[str] = []
    refused: list[Exception] = []
    start = threading.Barrier(8)

    def opener(store: EpisodeStore) -> None:
        start.wait()
        for _ in range(3):
            try:
                admitted.append(add(store, "token aaa"))
            except EpisodeShareError as exc:
                refused.append(exc)

    threads = [threading.Thread(target=opener, args=(hosts[i % 2],)) for i in range(8)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert len(admitted) == 5 and len(refused) == 24 - 5  # atomic in the shared store
    assert len(hosts[0]) == 5


def test_a_store_an_earlier_version_writes_keeps_working_beside_owners(
        tmp_path: Path) -> None:
    import sqlite3

    donor = DurableStore(open_backend(f"sqlite:///{tmp_path / 'donor.db'}"), 8, 3600.0)
    with sqlite3.connect(tmp_path / "donor.db") as db:  # a record as an earlier one wrote it
        record = db.execute("SELECT record FROM episodes WHERE id = ?",
                            (add(donor, "local"),)).fetchone()[0]
    record = record.replace('"owner":"local"', '"owner":""')
    assert '"owner":""' in record
    path = tmp_path / "old.db"
    old_shape = ("CREATE TABLE episodes (id TEXT PRIMARY KEY, version INTEGER NOT NULL, "
                 "created_at REAL NOT NULL, updated_at REAL NOT NULL, last_used REAL NOT "
                 "NULL, record TEXT NOT NULL)")
    old_insert = "INSERT INTO episodes VALUES (?, 1, ?, ?, ?, ?)"  # its own statement
    with sqlite3.connect(path) as db:
        db.execute(old_shape)
        db.execute(old_insert, ("ep_old", time.time(), time.time(), time.time(),
                                record.replace(json_id(record), "ep_old")))
    store = DurableStore(open_backend(f"sqlite:///{path}"), 8, 3600.0, share=2)
    touch(store, "token zzz", "ep_old")  # no owner then: whoever holds the id, as before
    with sqlite3.connect(path) as db:  # an earlier version still writes beside this one
        db.execute(old_insert, ("ep_old2", time.time(), time.time(), time.time(),
                                record.replace(json_id(record), "ep_old2")))
    add(store, "token zzz")
    add(store, "token zzz")
    with pytest.raises(EpisodeShareError):  # the earlier episodes count for no caller
        add(store, "token zzz")
    assert {"ep_old", "ep_old2"} <= set(store.ids())


def json_id(record: str) -> str:
    import json

    return str(json.loads(record)["id"])


@pytest.fixture(params=["sqlite", "redis"])
def durable_url(request: pytest.FixtureRequest, tmp_path: Path) -> str:
    if request.param == "sqlite":
        return f"sqlite:///{tmp_path}/episodes.db"
    url: str = request.getfixturevalue("redis_url")
    import redis
    redis.Redis.from_url(url).flushdb()
    return url


def test_purging_every_episode_frees_every_share(durable_url: str) -> None:
    store_url = durable_url  # memory:// has no operator purge: it ends with its process
    store = store_for(store_url, Clock(), cap=8, share=2)
    add(store, "token aaa")
    add(store, "token aaa")
    assert open_backend(store_url).sweep(time.time(), -1.0)  # verigraph episodes purge --all
    add(store, "token aaa")  # counted from nothing again
    add(store, "token aaa")


def test_the_operator_listing_names_each_episodes_caller(durable_url: str) -> None:
    store = store_for(durable_url, Clock(), cap=8, share=4)
    mine, theirs = add(store, "token aaa"), add(store, "address 10.0.0.7")
    entries = open_backend(durable_url).entries(time.time(), 3600.0)
    assert {e.id: e.owner for e in entries} == {mine: "token aaa", theirs: "address 10.0.0.7"}
