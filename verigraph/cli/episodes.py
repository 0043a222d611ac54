"""`verigraph episodes list|show|purge`: the operator's view of a durable episode store."""

from __future__ import annotations

import argparse
import json
import time
from datetime import UTC, datetime
from typing import Any

from verigraph.cli.exits import EXIT_OK
from verigraph.errors import VeriGraphError
from verigraph.tools.records import action_texts
from verigraph.tools.store import DEFAULT_IDLE_TIMEOUT_S
from verigraph.tools.store_backend import Backend
from verigraph.tools.store_durable import decode_record
from verigraph.tools.stores import STORE_HELP, default_store_url, open_backend, redacted


def register(sub: Any) -> None:
    p = sub.add_parser("episodes", help="list, show or purge stored episodes",
                       description="Inspect the episodes a server keeps in a durable store "
                                   "(SQLite or Redis).")
    p.add_argument("action", choices=("list", "show", "purge"))
    p.add_argument("episode_id", nargs="?", default=None,
                   help="show: the episode; purge: one episode (default: the idle ones)")
    p.add_argument("--store", default=None, metavar="URL",
                   help=f"{STORE_HELP}; default {default_store_url()}")
    p.add_argument("--idle-timeout", type=float, default=DEFAULT_IDLE_TIMEOUT_S, metavar="S",
                   help="episodes unused this long count as expired (the server's setting)")
    p.add_argument("--all", action="store_true", help="purge: every episode, idle or not")
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.set_defaults(handler=run_episodes)


def _when(seconds: float) -> str:
    return datetime.fromtimestamp(seconds, UTC).strftime("%Y-%m-%d %H:%M:%S")


def run_episodes(args: argparse.Namespace) -> int:
    url = args.store or default_store_url()
    if url.startswith("memory"):
        raise VeriGraphError("a memory store lives inside its server process",
                             field="--store", value=url, fix="give the server's sqlite:// "
                                                             "or redis:// URL")
    backend = open_backend(url)
    try:
        return _run(args, backend)
    finally:
        backend.close()


def _run(args: argparse.Namespace, backend: Backend) -> int:
    now, idle = time.time(), args.idle_timeout
    if args.action == "list":
        entries = backend.entries(now, idle)
        if args.json:
            print(json.dumps([e.__dict__ for e in entries]))
            return EXIT_OK
        print(f"{len(entries)} episode(s) in {redacted(backend.url)}")
        for e in entries:
            print(f"{e.id}  v{e.version}  created {_when(e.created_at)}  "
                  f"used {_when(e.last_used)}  {e.size} bytes  "
                  f"caller {e.owner or '(none)'}")
        return EXIT_OK
    if args.action == "show":
        if args.episode_id is None:
            raise VeriGraphError("show needs an episode id", field="episode_id", value=None,
                                 fix="verigraph episodes list, then show ID")
        text = backend.load(args.episode_id, now, idle)
        if text is None:
            raise VeriGraphError(f"no stored episode '{args.episode_id[:48]}'",
                                 field="episode_id", value=args.episode_id[:48],
                                 fix="verigraph episodes list shows the stored ids")
        record = decode_record(text)  # a damaged record: one message, exit 2
        if args.json:
            print(record.model_dump_json())
            return EXIT_OK
        state = record.state.sentences() if record.state is not None else ["(no graph yet)"]
        print(f"{record.id} v{record.version} ({record.source}, executor {record.executor})")
        print(f"k={record.k} t={record.t} tau={record.tau} calls={record.calls} "
              f"done={record.done}")
        print("graph: " + "; ".join(state))
        print("executed: " + (", ".join(action_texts(record)) or "nothing"))
        return EXIT_OK
    if args.episode_id is not None:
        gone = [args.episode_id] if backend.delete(args.episode_id) else []
    else:
        gone = backend.sweep(now, -1.0 if args.all else idle)
    print(f"purged {len(gone)} episode(s)")
    return EXIT_OK

