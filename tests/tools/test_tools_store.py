"""EpisodeStore: unguessable ids, bounds, idle eviction, thread safety."""

from __future__ import annotations

import re
import threading

import pytest

from verigraph.graph.builtin_scenes import cup_on_book
from verigraph.graph.state import WorldState
from verigraph.tools import EpisodeLimitError, EpisodeStore, LiveEpisode, UnknownEpisodeError
from verigraph.tools.store import WouldBlock, non_blocking

pytestmark = pytest.mark.fast


def make(episode_id: str) -> LiveEpisode:
    return LiveEpisode(id=episode_id, state=WorldState.from_graph(cup_on_book()), source="test")


def test_ids_are_long_random_and_url_safe() -> None:
    store = EpisodeStore(max_episodes=500)
    ids = {store.add(make).id for _ in range(300)}
    assert len(ids) == 300
    for eid in ids:
        assert re.fullmatch(r"ep_[A-Za-z0-9_-]{22}", eid)


def test_unknown_id_names_the_field_and_the_fix() -> None:
    store = EpisodeStore()
    with pytest.raises(UnknownEpisodeError) as err, store.use("ep_nope"):
        pass
    assert err.value.field == "episode_id"
    assert "load_scene" in (err.value.fix or "")


def test_store_is_bounded_with_a_clear_error() -> None:
    store = EpisodeStore(max_episodes=2)
    store.add(make)
    store.add(make)
    with pytest.raises(EpisodeLimitError) as err:
        store.add(make)
    assert "end_episode" in (err.value.fix or "")
    assert len(store) == 2


def test_idle_episodes_are_evicted_when_full() -> None:
    now = [0.0]
    store = EpisodeStore(max_episodes=2, idle_timeout=10, clock=lambda: now[0])
    old = store.add(make).id
    now[0] = 5
    recent = store.add(make).id
    now[0] = 12  # `old` idle for 12 s, `recent` for 7 s
    new = store.add(make).id
    assert set(store.ids()) == {recent, new}
    with pytest.raises(UnknownEpisodeError), store.use(old):
        pass


def test_using_an_episode_refreshes_it() -> None:
    now = [0.0]
    store = EpisodeStore(max_episodes=1, idle_timeout=10, clock=lambda: now[0])
    eid = store.add(make).id
    now[0] = 9
    with store.use(eid):
        pass
    now[0] = 15  # only 6 s since last use
    with pytest.raises(EpisodeLimitError):
        store.add(make)


def test_concurrent_updates_to_one_episode_are_serialised() -> None:
    store = EpisodeStore()
    eid = store.add(make).id

    def bump() -> None:
        for _ in range(2000):
            with store.use(eid) as ep:
                value = ep.calls
                ep.calls = value + 1

    threads = [threading.Thread(target=bump) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    with store.use(eid) as ep:
        assert ep.calls == 8000


def test_removed_episode_is_gone_even_for_a_waiting_caller() -> None:
    store = EpisodeStore()
    eid = store.add(make).id
    with store.use(eid) as ep:
        store.remove(ep.id)
    with pytest.raises(UnknownEpisodeError), store.use(eid):
        pass


def test_non_blocking_mode_refuses_to_wait() -> None:
    store = EpisodeStore()
    eid = store.add(make).id
    with non_blocking(), store.use(eid) as ep:  # a free episode is used directly
        assert ep.id == eid
    with store.use(eid), non_blocking(), pytest.raises(WouldBlock), store.use(eid):
        pass  # busy: refused instead of waiting
    with store.use(eid) as ep:
        ep.world = object()  # type: ignore[assignment]
    with non_blocking(), pytest.raises(WouldBlock), store.use(eid):
        pass  # a simulator may be slow: refused too
    with store.use(eid) as ep:  # normal mode still waits and works
        assert ep.world is not None
