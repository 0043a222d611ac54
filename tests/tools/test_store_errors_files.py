"""Store failures reported for what they are: a damaged record (server and CLI alike), a
file that is not a store (left untouched), a full disk (one clear error, nothing half
saved). Real SQLite files throughout; the full disk is a small tmpfs when this user may
mount one, else SQLite's own size limit (max_page_count), which fails the same way."""

from __future__ import annotations

import logging
import multiprocessing
import os
import stat
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from mcp import Client
from mcp_helpers import structured, text, verigraph_command

from verigraph.server import build_server
from verigraph.tools import Toolbox, ToolConfig
from verigraph.tools.errors import StoreError
from verigraph.tools.store_durable import DurableStore
from verigraph.tools.store_sqlite import SqliteBackend, create_private_file
from verigraph.tools.stores import open_store


def tower(n: int) -> dict[str, object]:
    nodes = [{"id": "table", "label": "table"}] + [{"id": f"b{i}", "label": "block"}
                                                   for i in range(n - 1)]
    edges = [{"source": f"b{i}", "relation": "on", "target": f"b{i - 1}" if i else "table"}
             for i in range(n - 1)]
    return {"nodes": nodes, "edges": edges, "dictionary": "blocks"}


def episodes(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*verigraph_command(), "episodes", *args], capture_output=True,
                          text=True, timeout=60)


def damage(url: str, episode_id: str) -> None:
    """Overwrite the stored record with valid JSON of the right version but wrong fields."""
    store = open_store(url)
    assert isinstance(store, DurableStore)
    assert store.backend.swap(episode_id, 1, '{"schema_version": 1, "id": 7}', time.time(), 60)


def test_a_damaged_record_is_reported_alike_by_server_and_cli(tmp_path: Path) -> None:
    url = f"sqlite:///{tmp_path / 'episodes.db'}"
    ep = Toolbox(config=ToolConfig(store=url)).call(
        "load_scene", {"scene_id": "three_blocks"}).episode_id  # type: ignore[union-attr]
    damage(url, ep)
    with pytest.raises(StoreError) as err:
        Toolbox(config=ToolConfig(store=url)).call("get_state", {"episode_id": ep})
    message = str(err.value)
    assert "damaged" in message and "purge" in message
    assert "schema version" not in message  # the version is right; the record is not
    shown = episodes("show", ep, "--store", url)
    assert shown.returncode == 2 and shown.stdout == ""
    lines = shown.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in shown.stderr, shown.stderr
    assert "damaged" in lines[0] and "purge" in lines[0]


def test_a_file_that_is_not_a_store_is_refused_as_such_and_left_alone(tmp_path: Path) -> None:
    path = tmp_path / "episodes.db"
    content = b"root:x:0:0:root:/root:/bin/bash\n" * 200  # some other file, not SQLite
    path.write_bytes(content)
    path.chmod(0o644)
    with pytest.raises(StoreError) as err:
        open_store(f"sqlite:///{path}")
    message = str(err.value)
    assert "not a readable SQLite episode store" in message and "move that file" in message
    assert "writable" not in message and "root:x" not in message  # never the content
    assert stat.S_IMODE(path.stat().st_mode) == 0o644 and path.read_bytes() == content
    listed = episodes("list", "--store", f"sqlite:///{path}")
    assert listed.returncode == 2 and "Traceback" not in listed.stderr
    assert "not a readable SQLite episode store" in listed.stderr


@pytest.fixture()
def small_disk(tmp_path: Path) -> Iterator[Path | None]:
    """A 1 MiB tmpfs, or None when this user may not mount one."""
    mount = tmp_path / "small"
    mount.mkdir()
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=1m", "tmpfs", str(mount)],
                          capture_output=True)
    if done.returncode != 0:
        yield None
        return
    try:
        yield mount
    finally:
        subprocess.run(["umount", "-l", str(mount)], check=True)


def fill(folder: Path) -> None:
    """Write until the filesystem is full (ENOSPC). Unbuffered, so that closing the file
    has nothing left to write (a buffered remainder would raise ENOSPC again)."""
    with open(folder / "filler", "wb", buffering=0) as out:
        try:
            while True:
                out.write(b"\0" * 65536)
                os.fsync(out.fileno())
        except OSError:
            pass


@pytest.mark.anyio
async def test_a_full_disk_is_one_clear_store_error_and_saves_nothing(
        small_disk: Path | None, tmp_path: Path, caplog: pytest.LogCaptureFixture) -> None:
    folder = small_disk or tmp_path
    url = f"sqlite:///{folder / 'episodes.db'}"
    box = Toolbox(config=ToolConfig(store=url))
    big = tower(1500)  # a record of about 100 KB: needs new pages
    if small_disk is None:  # same failure (SQLITE_FULL) from SQLite's own size limit
        store = box.context.store
        assert isinstance(store, DurableStore)
        store.backend._connection().execute("PRAGMA max_page_count=8")  # type: ignore[attr-defined]
        box.call("load_scene", {"scene_id": "cup_on_book"})
        with pytest.raises(StoreError) as err:
            box.call("load_scene", {"graph": big})
        assert "is full" in str(err.value)
        return
    caplog.set_level(logging.INFO)
    async with Client(build_server(box)) as c:
        first = structured(await c.call_tool("load_scene", {"scene_id": "cup_on_book"}))[
            "episode_id"]
        fill(folder)
        refused = await c.call_tool("load_scene", {"graph": big})
        assert refused.is_error
        message = text(refused)
        assert "is full" in message and "free space" in message, message
        moved = await c.call_tool("execute_actions", {"episode_id": first,
                                                      "actions": ["move(cup, on, desk)"]})
        if moved.is_error:  # the change did not fit either: nothing of it is kept
            assert "is full" in text(moved)
            state = structured(await c.call_tool("get_state", {"episode_id": first}))
            assert state["executed"] == []
    assert "cannot rollback" not in caplog.text
    assert "Traceback" not in caplog.text


def _open_after(path: str, start: Any) -> None:
    start.wait(timeout=30)
    SqliteBackend(path).close()


def test_processes_opening_one_new_store_at_once_all_succeed(tmp_path: Path) -> None:
    """`serve --workers N` opens a new SQLite store from N processes at the same moment:
    those that lose the race to create the file use it (not "File exists")."""
    context = multiprocessing.get_context("fork")
    for attempt in range(8):
        path = tmp_path / f"new{attempt}" / "episodes.db"
        start = context.Barrier(4)
        procs = [context.Process(target=_open_after, args=(str(path), start))
                 for _ in range(4)]
        for proc in procs:
            proc.start()
        for proc in procs:
            proc.join(timeout=60)
        assert [proc.exitcode for proc in procs] == [0, 0, 0, 0], attempt
        assert stat.S_IMODE(path.stat().st_mode) == 0o600


def test_creating_a_store_file_another_process_just_created_is_not_an_error(
        tmp_path: Path) -> None:
    path = tmp_path / "episodes.db"
    create_private_file(path)
    create_private_file(path)  # what the second of two processes does
    assert stat.S_IMODE(path.stat().st_mode) == 0o600
