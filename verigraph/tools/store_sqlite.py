"""The SQLite backend: one file, WAL mode, one transaction per state change.

WAL lets readers run while a writer commits; `synchronous=NORMAL` keeps every committed
transaction through a process crash (kill -9), which is what a restart needs. The file
(and its directory, when created here) is readable by its owner only (an existing file
is made so only once it opened as a store: a refused file is left as it was); SQLite gives the
-wal and -shm files the database file's permissions. Idle episodes are swept by the
store on every load_scene and `verigraph episodes purge`; an expired episode is treated
as gone at once even before the sweep. Each thread has its own connection. Every
SQLite failure (disk full, damaged file, lock held too long) is a StoreError that says
which, never a second error from the rollback.
"""

from __future__ import annotations

import os
import sqlite3
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager, suppress
from pathlib import Path

from verigraph.tools.errors import StoreError
from verigraph.tools.store_backend import Admission, Limits, StoredEpisode

# Refresh an episode's last-used time at most this often, so a read is not a write.
TOUCH_EVERY_S = 5.0

_SCHEMA = """
CREATE TABLE IF NOT EXISTS episodes (
    id TEXT PRIMARY KEY,
    version INTEGER NOT NULL,
    created_at REAL NOT NULL,
    updated_at REAL NOT NULL,
    last_used REAL NOT NULL,
    record TEXT NOT NULL
);
CREATE INDEX IF NOT EXISTS episodes_last_used ON episodes(last_used);
CREATE TABLE IF NOT EXISTS episode_owners (
    id TEXT PRIMARY KEY,
    owner TEXT NOT NULL
);
CREATE INDEX IF NOT EXISTS episode_owners_owner ON episode_owners(owner);
"""
# Owners have a table of their own, so the episodes table keeps its shape: a server of an
# earlier version on the same file (a rolling upgrade) still writes its rows, which own
# nothing. An owner row whose episode is gone (ended, expired, or deleted by such a
# server) is dropped before owners are counted.
_DROP_ORPHANS = "DELETE FROM episode_owners WHERE id NOT IN (SELECT id FROM episodes)"


def create_private_file(path: Path) -> None:
    """Create `path` (and missing parents) so that only its owner can read it.

    Several server processes (`serve --workers`) open a new store at the same moment:
    the file one of them has just created is theirs too, not an error."""
    path.parent.mkdir(parents=True, mode=0o700, exist_ok=True)
    try:
        fd = os.open(path, os.O_CREAT | os.O_EXCL | os.O_RDWR, 0o600)
    except FileExistsError:
        return
    os.close(fd)


def primary_code(exc: sqlite3.Error | OSError) -> int:
    """SQLite's primary result code of `exc` (SQLITE_BUSY, SQLITE_FULL, ...; 0 if none)."""
    return (getattr(exc, "sqlite_errorcode", 0) or 0) & 0xFF


def store_error(path: Path, exc: sqlite3.Error | OSError, doing: str) -> StoreError:
    """What went wrong with the store file, in words, with the fix that fits it (never
    the file's content)."""
    url = f"sqlite:///{path}"
    code = primary_code(exc)
    if code in (sqlite3.SQLITE_FULL,):
        return StoreError(f"the episode store {path} is full (no space left on its disk, "
                          f"or its size limit): {doing} was not saved", field="--store",
                          value=url, fix="free space on that disk, drop idle episodes with "
                                         "verigraph episodes purge, or give another --store")
    if code in (sqlite3.SQLITE_CORRUPT, sqlite3.SQLITE_NOTADB):
        return StoreError(f"{path} is not a readable SQLite episode store (the file is "
                          "damaged or of another kind)", field="--store", value=url,
                          fix="move that file aside (a new store is created in its place) "
                              "or give another path: sqlite:///path/to/episodes.db")
    if code in (sqlite3.SQLITE_BUSY, sqlite3.SQLITE_LOCKED):
        return StoreError(f"the episode store {path} stayed locked by another process: "
                          f"{doing} was not done", field="--store", value=url,
                          fix="send the call again; if it persists, check what holds the file")
    reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
    return StoreError(f"cannot use the SQLite store {path} ({doing}): {reason}",
                      field="--store", value=url,
                      fix="give a path in a folder this user can write: "
                          "sqlite:///path/to/episodes.db")


def _switch_to_wal(connection: sqlite3.Connection, patience_s: float = 30.0) -> None:
    """`PRAGMA journal_mode=WAL`, tried again while another process does the same.

    On a new file the switch needs every other connection out of the way; two processes
    switching at once (`serve --workers`) deadlock, and SQLite answers one of them
    SQLITE_BUSY at once, without its busy timeout: that one lets go and tries again."""
    give_up = time.monotonic() + patience_s
    while True:
        try:
            connection.execute("PRAGMA journal_mode=WAL")
            return
        except sqlite3.OperationalError as exc:
            if primary_code(exc) != sqlite3.SQLITE_BUSY or time.monotonic() > give_up:
                raise
            time.sleep(0.01)


class SqliteBackend:
    """Episode records in one SQLite table."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path).expanduser()
        self.url = f"sqlite:///{self.path}"
        existed = self.path.exists()
        try:
            if not existed:
                create_private_file(self.path)
            connection = self._connection()
            # The write lock first: in WAL mode a read that turns into a write after
            # another process wrote (two workers creating the table) fails at once
            # instead of waiting for the lock.
            connection.executescript(f"BEGIN IMMEDIATE;{_SCHEMA}COMMIT;")
            if existed:
                os.chmod(self.path, 0o600)  # only once it is known to be a store
        except (OSError, sqlite3.Error) as exc:
            self.close()
            raise store_error(self.path, exc, "opening it") from None

    @contextmanager
    def _guard(self, doing: str) -> Iterator[None]:
        """sqlite3 errors as StoreError: the client hears what failed, once."""
        try:
            yield
        except sqlite3.Error as exc:
            raise store_error(self.path, exc, doing) from None

    _local = threading.local()

    def _connection(self) -> sqlite3.Connection:
        cache: dict[str, sqlite3.Connection] = self._local.__dict__.setdefault("c", {})
        connection = cache.get(str(self.path))
        if connection is None:
            connection = sqlite3.connect(self.path, isolation_level=None, timeout=30.0,
                                         check_same_thread=False)
            _switch_to_wal(connection)
            connection.execute("PRAGMA synchronous=NORMAL")
            connection.execute("PRAGMA busy_timeout=30000")
            cache[str(self.path)] = connection
        return connection

    def create(self, episode_id: str, owner: str, record: str, now: float, limits: Limits
               ) -> Admission:
        with self._guard("the new episode"):
            db = self._connection()
            db.execute("BEGIN IMMEDIATE")
            try:
                db.execute("DELETE FROM episodes WHERE last_used < ?", (now - limits.idle,))
                db.execute(_DROP_ORPHANS)
                (held,) = db.execute("SELECT count(*) FROM episode_owners WHERE owner = ?",
                                     (owner,)).fetchone()
                if held >= limits.share < limits.cap:
                    db.execute("COMMIT")
                    return Admission("share", held)
                (count,) = db.execute("SELECT count(*) FROM episodes").fetchone()
                reclaimed = None
                if count >= limits.cap:
                    row = db.execute("SELECT id FROM episodes WHERE last_used <= ? "
                                     "ORDER BY last_used LIMIT 1",
                                     (now - limits.reclaim_after,)).fetchone()
                    if row is None:
                        db.execute("COMMIT")
                        return Admission("full", held)
                    reclaimed = str(row[0])
                    db.execute("DELETE FROM episodes WHERE id = ?", (reclaimed,))
                    db.execute("DELETE FROM episode_owners WHERE id = ?", (reclaimed,))
                db.execute("INSERT INTO episodes (id, version, created_at, updated_at, "
                           "last_used, record) VALUES (?, 1, ?, ?, ?, ?)",
                           (episode_id, now, now, now, record))
                db.execute("INSERT INTO episode_owners (id, owner) VALUES (?, ?)",
                           (episode_id, owner))
                db.execute("COMMIT")
                return Admission("created", held, reclaimed)
            except BaseException:
                if db.in_transaction:  # SQLite may have rolled back already (disk full)
                    db.execute("ROLLBACK")
                raise

    def check(self, episode_id: str, now: float, idle: float) -> int | None:
        with self._guard("reading the episode"):
            db = self._connection()
            row = db.execute("SELECT version, last_used FROM episodes WHERE id = ?",
                             (episode_id,)).fetchone()
            if row is None or row[1] < now - idle:
                return None
            if now - row[1] > min(TOUCH_EVERY_S, idle / 10):
                with suppress(sqlite3.OperationalError):  # a missed touch costs nothing
                    db.execute("UPDATE episodes SET last_used = max(last_used, ?) "
                               "WHERE id = ?", (now, episode_id))
            return int(row[0])

    def load(self, episode_id: str, now: float, idle: float) -> str | None:
        with self._guard("reading the episode"):
            row = self._connection().execute(
                "SELECT record FROM episodes WHERE id = ? AND last_used >= ?",
                (episode_id, now - idle)).fetchone()
        return None if row is None else str(row[0])

    def swap(self, episode_id: str, expected: int, record: str, now: float, idle: float
             ) -> bool:
        with self._guard("the episode's change"):
            cursor = self._connection().execute(
                "UPDATE episodes SET version = version + 1, record = ?, updated_at = ?, "
                "last_used = ? WHERE id = ? AND version = ?",
                (record, now, now, episode_id, expected))
        return cursor.rowcount == 1

    def delete(self, episode_id: str) -> bool:
        with self._guard("ending the episode"):
            db = self._connection()
            cursor = db.execute("DELETE FROM episodes WHERE id = ?", (episode_id,))
            db.execute("DELETE FROM episode_owners WHERE id = ?", (episode_id,))
        return cursor.rowcount == 1

    def sweep(self, now: float, idle: float) -> list[str]:
        with self._guard("dropping idle episodes"):
            db = self._connection()
            rows = db.execute("DELETE FROM episodes WHERE last_used < ? RETURNING id",
                              (now - idle,)).fetchall()
            db.execute(_DROP_ORPHANS)
        return [str(r[0]) for r in rows]

    def entries(self, now: float, idle: float) -> list[StoredEpisode]:
        with self._guard("listing the episodes"):
            rows = self._connection().execute(
                "SELECT e.id, version, created_at, updated_at, last_used, length(record), "
                "coalesce(o.owner, '') FROM episodes e LEFT JOIN episode_owners o "
                "ON o.id = e.id WHERE last_used >= ? ORDER BY created_at",
                (now - idle,)).fetchall()
        return [StoredEpisode(*row) for row in rows]

    def close(self) -> None:
        cache = self._local.__dict__.get("c", {})
        connection = cache.pop(str(self.path), None)
        if connection is not None:
            connection.close()
