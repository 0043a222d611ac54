"""The Redis backend: episodes shared by several server processes (replicas).

Each episode is a hash `verigraph:ep:<id>` (version, record JSON, timestamps, owner)
whose key expires after the idle timeout (Redis EXPIRE, refreshed on every use), a
sorted set `verigraph:episodes` indexes live ids by last use for the cap, the reclaiming
of idle episodes and the operator listing, and `verigraph:owner:<caller>` does the same
for one caller's share. Every step is one Lua script, so it is atomic on the server:
create checks the share and the cap (reclaiming an idle episode when full) and inserts,
swap is the compare-and-set on the version. Before anything is counted, create drops
every episode whose last use (its score) is older than the idle timeout, as SQLite does,
whether or not its key's TTL has run out yet (another replica's clock may differ).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

import redis

from verigraph.tools.errors import StoreError
from verigraph.tools.store_backend import Admission, Limits, StoredEpisode, redacted

PREFIX = "verigraph:"
INDEX = PREFIX + "episodes"
OWNER_PREFIX = PREFIX + "owner:"
T = TypeVar("T")

# KEYS: episode, index, owner index. ARGV: id, record, now, cap, idle ms, expiry cutoff,
# owner, share, reclaim cutoff, episode key prefix.
_CREATE = """
local expired = redis.call('ZRANGEBYSCORE', KEYS[2], '-inf', '(' .. ARGV[6])
for _, id in ipairs(expired) do
  local owner = redis.call('HGET', ARGV[10] .. id, 'owner')
  redis.call('DEL', ARGV[10] .. id)
  if owner then redis.call('ZREM', '""" + OWNER_PREFIX + """' .. owner, id) end
end
redis.call('ZREMRANGEBYSCORE', KEYS[2], '-inf', '(' .. ARGV[6])
redis.call('ZREMRANGEBYSCORE', KEYS[3], '-inf', '(' .. ARGV[6])
local held = redis.call('ZCARD', KEYS[3])
if held >= tonumber(ARGV[8]) and tonumber(ARGV[8]) < tonumber(ARGV[4]) then
  return {'share', held, ''}
end
local reclaimed = ''
if redis.call('ZCARD', KEYS[2]) >= tonumber(ARGV[4]) then
  local idle = redis.call('ZRANGEBYSCORE', KEYS[2], '-inf', ARGV[9], 'LIMIT', 0, 1)
  if #idle == 0 then return {'full', held, ''} end
  reclaimed = idle[1]
  local owner = redis.call('HGET', ARGV[10] .. reclaimed, 'owner')
  redis.call('DEL', ARGV[10] .. reclaimed)
  redis.call('ZREM', KEYS[2], reclaimed)
  if owner then redis.call('ZREM', '""" + OWNER_PREFIX + """' .. owner, reclaimed) end
end
redis.call('HSET', KEYS[1], 'v', 1, 'rec', ARGV[2], 'created', ARGV[3], 'updated', ARGV[3],
           'used', ARGV[3], 'owner', ARGV[7])
redis.call('PEXPIRE', KEYS[1], ARGV[5])
redis.call('ZADD', KEYS[2], ARGV[3], ARGV[1])
redis.call('ZADD', KEYS[3], ARGV[3], ARGV[1])
redis.call('PEXPIRE', KEYS[3], ARGV[5])
return {'created', held, reclaimed}
"""
# Refreshes an episode's place in its owner's index (stores made before owners have none).
_TOUCH_OWNER = """
local owner = redis.call('HGET', KEYS[1], 'owner')
if owner then
  redis.call('ZADD', '""" + OWNER_PREFIX + """' .. owner, ARGV[2], ARGV[1])
  redis.call('PEXPIRE', '""" + OWNER_PREFIX + """' .. owner, ARGV[3])
end
"""
_CHECK = """
local v = redis.call('HGET', KEYS[1], 'v')
if not v then
  redis.call('ZREM', KEYS[2], ARGV[1])
  return false
end
redis.call('HSET', KEYS[1], 'used', ARGV[2])
redis.call('PEXPIRE', KEYS[1], ARGV[3])
redis.call('ZADD', KEYS[2], ARGV[2], ARGV[1])
""" + _TOUCH_OWNER + """
return tonumber(v)
"""
_SWAP = """
local v = redis.call('HGET', KEYS[1], 'v')
if (not v) or tonumber(v) ~= tonumber(ARGV[2]) then return 0 end
redis.call('HSET', KEYS[1], 'v', tonumber(v) + 1, 'rec', ARGV[3], 'updated', ARGV[4],
           'used', ARGV[4])
redis.call('PEXPIRE', KEYS[1], ARGV[5])
redis.call('ZADD', KEYS[2], ARGV[4], ARGV[1])
local owner = redis.call('HGET', KEYS[1], 'owner')
if owner then
  redis.call('ZADD', '""" + OWNER_PREFIX + """' .. owner, ARGV[4], ARGV[1])
  redis.call('PEXPIRE', '""" + OWNER_PREFIX + """' .. owner, ARGV[5])
end
return 1
"""
_DELETE = """
local owner = redis.call('HGET', KEYS[1], 'owner')
if owner then redis.call('ZREM', '""" + OWNER_PREFIX + """' .. owner, ARGV[1]) end
redis.call('ZREM', KEYS[2], ARGV[1])
return redis.call('DEL', KEYS[1])
"""


def _key(episode_id: str) -> str:
    return f"{PREFIX}ep:{episode_id}"


def _ms(seconds: float) -> int:
    return max(1, int(seconds * 1000))


class RedisBackend:
    """Episode records in a Redis database (redis://host:port/db)."""

    def __init__(self, url: str) -> None:
        self.url = url
        try:
            self.client = redis.Redis.from_url(url, decode_responses=True,
                                               socket_timeout=10, socket_connect_timeout=5)
        except ValueError as exc:
            raise StoreError(f"bad Redis URL: {exc}", field="--store", value=redacted(url),
                             fix="use redis://host:port/db, e.g. redis://127.0.0.1:6379/0"
                             ) from None
        self._create = self.client.register_script(_CREATE)
        self._check = self.client.register_script(_CHECK)
        self._swap = self.client.register_script(_SWAP)
        self._delete = self.client.register_script(_DELETE)
        self._call(self.client.ping)

    def _call(self, fn: Callable[..., T], *args: Any, **kwargs: Any) -> T:
        try:
            return fn(*args, **kwargs)
        except redis.RedisError as exc:
            shown = redacted(self.url)  # never the password
            raise StoreError(f"the Redis store at {shown} failed: {exc}", field="--store",
                             value=shown, fix="check that the Redis server is running and "
                                                 "reachable; episodes are kept there") from None

    def create(self, episode_id: str, owner: str, record: str, now: float, limits: Limits
               ) -> Admission:
        outcome, held, reclaimed = self._call(
            self._create, keys=[_key(episode_id), INDEX, OWNER_PREFIX + owner],
            args=[episode_id, record, now, limits.cap, _ms(limits.idle), now - limits.idle,
                  owner, limits.share, now - limits.reclaim_after, _key("")])
        return Admission(outcome, int(held), str(reclaimed) or None)

    def check(self, episode_id: str, now: float, idle: float) -> int | None:
        version = self._call(self._check, keys=[_key(episode_id), INDEX],
                             args=[episode_id, now, _ms(idle)])
        return None if version is None else int(version)

    def load(self, episode_id: str, now: float, idle: float) -> str | None:
        record = self._call(self.client.hget, _key(episode_id), "rec")
        return None if record is None else str(record)

    def swap(self, episode_id: str, expected: int, record: str, now: float, idle: float
             ) -> bool:
        done = self._call(self._swap, keys=[_key(episode_id), INDEX],
                          args=[episode_id, expected, record, now, _ms(idle)])
        return bool(done)

    def delete(self, episode_id: str) -> bool:
        deleted = self._call(self._delete, keys=[_key(episode_id), INDEX], args=[episode_id])
        return bool(deleted)

    def sweep(self, now: float, idle: float) -> list[str]:
        cutoff = f"({now - idle}"
        ids = [str(i) for i in self._call(self.client.zrangebyscore, INDEX, "-inf", cutoff)]
        if ids:
            owners = self._call(self._owners_of, ids)
            pipe = self.client.pipeline()
            pipe.delete(*[_key(i) for i in ids])
            pipe.zrem(INDEX, *ids)
            for episode_id, owner in zip(ids, owners, strict=True):
                if owner is not None:  # its share is free again at once (purge --all)
                    pipe.zrem(OWNER_PREFIX + str(owner), episode_id)
            self._call(pipe.execute)
        return ids

    def _owners_of(self, ids: list[str]) -> list[str | None]:
        pipe = self.client.pipeline()
        for episode_id in ids:
            pipe.hget(_key(episode_id), "owner")
        return list(pipe.execute())

    def entries(self, now: float, idle: float) -> list[StoredEpisode]:
        ids = [str(i) for i in self._call(self.client.zrangebyscore, INDEX, now - idle, "+inf")]
        pipe = self.client.pipeline()
        for episode_id in ids:
            pipe.hmget(_key(episode_id), ["v", "created", "updated", "used", "owner"])
            pipe.hstrlen(_key(episode_id), "rec")
        replies = self._call(pipe.execute) if ids else []
        out = []
        for i, episode_id in enumerate(ids):
            fields, size = replies[2 * i], replies[2 * i + 1]
            if fields[0] is None:
                continue  # expired between the two calls
            out.append(StoredEpisode(episode_id, int(fields[0]), float(fields[1]),
                                     float(fields[2]), float(fields[3]), int(size),
                                     str(fields[4] or "")))
        return sorted(out, key=lambda e: e.created_at)

    def close(self) -> None:
        self.client.close()
