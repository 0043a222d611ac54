"""`verigraph serve`: the MCP server over stdio (default) or streamable HTTP."""

from __future__ import annotations

import argparse
import logging
import os
import sys
from pathlib import Path
from typing import Any

import anyio

from verigraph.cli.exits import EXIT_OK
from verigraph.errors import VeriGraphError

TOKEN_ENV = "VERIGRAPH_TOKEN"


def register(sub: Any) -> None:
    p = sub.add_parser(
        "serve", help="run the MCP server (stdio or streamable HTTP)",
        description="Serve the VeriGraph tools over MCP. stdio is for clients that start "
                    "the server themselves (Claude Desktop, Claude Code, VS Code, Cursor); "
                    "http serves stateless streamable HTTP on loopback by default.")
    p.add_argument("--transport", choices=("stdio", "http"), default="stdio")
    p.add_argument("--host", default="127.0.0.1",
                   help="HTTP bind address (default loopback; other addresses need --token)")
    p.add_argument("--port", type=int, default=8000, help="HTTP port (default 8000)")
    p.add_argument("--token", action="append", default=None, metavar="TOKEN",
                   help="require 'Authorization: Bearer TOKEN' on HTTP (default: "
                        f"${TOKEN_ENV}); repeat it to give each client its own token, so "
                        "the per-client limits tell clients on one host apart")
    p.add_argument("--allow-host", action="append", default=[], metavar="NAME",
                   help="extra Host/Origin name accepted over HTTP (repeatable)")
    p.add_argument("--max-body-mib", type=float, default=16.0,
                   help="largest request in MiB: an HTTP body or a stdio message (default 16)")
    p.add_argument("--max-connections", type=int, default=None,
                   help="open HTTP connections at once; more get 503 (default 512, or fewer "
                        "when the file-descriptor limit is low)")
    p.add_argument("--header-timeout", type=float, default=10.0, metavar="S",
                   help="HTTP: seconds a client has to send its request headers (default 10)")
    p.add_argument("--body-timeout", type=float, default=30.0, metavar="S",
                   help="HTTP: seconds a client has to send its request body (default 30)")
    p.add_argument("--keep-alive", type=float, default=75.0, metavar="S",
                   help="HTTP: seconds an idle connection stays open (default 75)")
    p.add_argument("--stream-idle", type=float, default=30.0, metavar="S",
                   help="HTTP: seconds an event stream (GET /mcp) stays open with no event "
                        "(default 30)")
    p.add_argument("--streams-per-client", type=int, default=8, metavar="N",
                   help="HTTP: event streams one client (its own token, else its address) "
                        "may hold open (default 8)")
    p.add_argument("--tool-seconds", type=float, default=30.0, metavar="S",
                   help="wall-clock budget of one heavy tool call (default 30)")
    p.add_argument("--tool-mib", type=float, default=512.0, metavar="MIB",
                   help="memory growth budget of one heavy tool call (default 512)")
    p.add_argument("--heavy-workers", type=int, default=2,
                   help="heavy tool calls running at once (default 2)")
    p.add_argument("--per-connection", "--per-client", dest="per_connection", type=int,
                   default=1, help="heavy tool calls running at once for one connection "
                                   "(default 1; the rest wait; --per-client is its old name)")
    p.add_argument("--max-episodes", type=int, default=256,
                   help="open episodes kept at once (default 256)")
    p.add_argument("--episodes-per-caller", type=int, default=None, metavar="N",
                   help="open episodes one caller may hold (its token, else its address; "
                        "default: a quarter of --max-episodes over HTTP, all of them over "
                        "stdio, whose one peer is the only caller)")
    p.add_argument("--reclaim-idle", type=float, default=600.0, metavar="S",
                   help="when the store is full, a new episode replaces the least recently "
                        "used one unused for this many seconds (default 600)")
    p.add_argument("--max-arm-episodes", type=int, default=8,
                   help="arm episodes open at once (default 8; each holds an arm world "
                        "until end_episode)")
    p.add_argument("--store", default=None, metavar="URL",
                   help="where episodes live: memory://, sqlite:///path/episodes.db or "
                        "redis://host:port/db (default: sqlite in the user's data directory, "
                        "so episodes survive a restart)")
    p.add_argument("--idle-timeout", type=float, default=3600.0, metavar="S",
                   help="drop episodes unused for this many seconds (default 3600)")
    p.add_argument("--disable-solve", action="store_true", help="turn the solve tool off")
    p.add_argument("--executor", default=None, metavar="NAME",
                   help="where episodes run unless load_scene picks another: graph "
                        "(verification only; the default), sim2d, arm:pybullet, "
                        "arm:rosbridge or arm:xarm (default with --arm-config: its arm). "
                        "Clients may pick graph, sim2d, or this server's arm; without an "
                        "arm here (or in --arm-config) no client can open an arm episode")
    p.add_argument("--arm-config", type=Path, default=None, metavar="FILE",
                   help="arm configuration (YAML or JSON): driver, host, workspace, keep-out "
                        "zones, speeds, force cap, timeouts, mode (dry-run unless the file "
                        "says sim or real)")
    p.add_argument("--workers", type=int, default=1,
                   help="HTTP: server processes sharing the port (default 1); more than 1 "
                        "needs a durable --store (sqlite or redis) and no arm")
    p.add_argument("--check-above-kib", type=float, default=64.0, metavar="KIB",
                   help="HTTP: bodies above this are parsed and checked in a child process, "
                        "off the server's event loop (default 64; 0 turns that off)")
    p.add_argument("--queued-per-client", type=int, default=8, metavar="N",
                   help="HTTP: large bodies one client may have waiting for the checking "
                        "process, per lane; one more gets 503 (default 8)")
    p.add_argument("--check-seconds", type=float, default=10.0, metavar="S",
                   help="HTTP: seconds the process that checks a large body has to answer; "
                        "later, it is killed and replaced and the caller told (default 10)")
    p.add_argument("--log-level", default="WARNING",
                   choices=("DEBUG", "INFO", "WARNING", "ERROR"), help="stderr log level")
    p.set_defaults(handler=run_serve)


def run_serve(args: argparse.Namespace) -> int:
    logging.basicConfig(stream=sys.stderr, level=args.log_level,
                        format="%(asctime)s %(levelname)s %(name)s: %(message)s")
    from verigraph.budget import CallBudget
    from verigraph.server.app import build_server
    from verigraph.server.heavy import HeavyLimits, keep_loop_responsive
    from verigraph.tools.context import ToolConfig
    from verigraph.tools.executors import server_executor
    from verigraph.tools.stores import default_store_url, redacted

    env_token = os.environ.get(TOKEN_ENV)
    tokens = tuple(dict.fromkeys(args.token or ([env_token] if env_token else [])))
    if any(not token.strip() or token != token.strip() for token in tokens):
        raise VeriGraphError("a token is empty or has spaces around it", field="--token",
                             value=None, fix="give each --token as one word, e.g. from "
                                             "`python -c 'import secrets; print(secrets."
                                             "token_urlsafe())'`")
    if args.transport == "http" and args.host not in ("127.0.0.1", "localhost", "::1") \
            and not tokens:
        raise VeriGraphError(f"refusing to serve on {args.host} without a token",
                             field="--host", value=args.host,
                             fix=f"pass --token (or set {TOKEN_ENV}), or bind to 127.0.0.1")
    if args.max_episodes < 1 or args.max_arm_episodes < 0 or not 0 < args.max_body_mib <= 1024 \
            or args.idle_timeout <= 0:
        raise VeriGraphError("limits out of range",
                             field="--max-episodes/--max-arm-episodes/--max-body-mib/"
                                   "--idle-timeout",
                             value=None, fix="use --max-episodes >= 1, --max-arm-episodes >= 0, "
                                             "0 < --max-body-mib <= 1024 and --idle-timeout > 0")
    share = episodes_per_caller(args)
    executor, arm = server_executor(args.executor, args.arm_config)
    if arm is not None:
        from verigraph.arm.shutdown import install_stop_on_signals

        install_stop_on_signals()  # SIGTERM / SIGINT stop any motion before exit
    if arm is not None and executor.startswith("arm:"):
        logging.getLogger("verigraph.server").warning(
            "episodes run on %s in mode %s", executor, arm.config.mode)
    store = args.store or default_store_url()
    logging.getLogger("verigraph.server").info("episodes are kept in %s", redacted(store))
    config = ToolConfig(max_episodes=args.max_episodes, enable_solve=not args.disable_solve,
                        executor=executor, arm=arm, max_arm_worlds=args.max_arm_episodes,
                        store=store, idle_timeout_s=args.idle_timeout,
                        episodes_per_caller=share, reclaim_idle_s=args.reclaim_idle)
    numbers = (args.header_timeout, args.body_timeout, args.keep_alive, args.tool_seconds,
               args.tool_mib, args.heavy_workers, args.per_connection, args.stream_idle,
               args.streams_per_client)
    if min(numbers) <= 0:
        raise VeriGraphError("timeouts, budgets and worker counts must be positive",
                             field="--header-timeout/--body-timeout/--keep-alive/--stream-idle/"
                                   "--streams-per-client/"
                                   "--tool-seconds/--tool-mib/--heavy-workers/--per-connection",
                             value=None, fix="give each a positive number")
    if args.workers < 1 or args.check_seconds <= 0 or args.check_above_kib < 0 \
            or args.queued_per_client < 1:
        raise VeriGraphError("--workers, --check-seconds, --check-above-kib or "
                             "--queued-per-client out of range",
                             field="--workers/--check-seconds/--check-above-kib/"
                                   "--queued-per-client", value=None,
                             fix="use --workers >= 1, --check-seconds > 0, "
                                 "--check-above-kib >= 0 and --queued-per-client >= 1")
    if args.workers > 1:
        check_workers(args.transport, store, arm)
    heavy = HeavyLimits(workers=args.heavy_workers, per_connection=args.per_connection,
                        budget=CallBudget(wall_s=args.tool_seconds, memory_mib=args.tool_mib))
    max_bytes = int(args.max_body_mib * 1024 * 1024)
    if args.transport == "stdio":
        from verigraph.server.stdio import run_stdio

        server = build_server(config=config, log_level=args.log_level, heavy=heavy)
        keep_loop_responsive()
        anyio.run(run_stdio, server, max_bytes)
        return EXIT_OK
    from verigraph.server.http import HttpOptions, serve_http
    from verigraph.server.http.workers import listening_socket, run_workers

    options = HttpOptions(host=args.host, port=args.port, tokens=tokens,
                          max_body_bytes=max_bytes,
                          allowed_hosts=tuple(args.allow_host),
                          header_timeout_s=args.header_timeout, body_timeout_s=args.body_timeout,
                          keep_alive_s=args.keep_alive, large_call_mib=args.tool_mib,
                          large_call_deadline_s=args.check_seconds,
                          large_calls_queued=args.queued_per_client,
                          large_call_bytes=int(args.check_above_kib * 1024),
                          stream_idle_s=args.stream_idle,
                          streams_per_client=args.streams_per_client,
                          max_connections=args.max_connections or default_max_connections())

    def serve(sock: Any = None, in_flight: Any = None) -> None:
        server = build_server(config=config, log_level=args.log_level, heavy=heavy)
        keep_loop_responsive()
        serve_http(server, options, log_level=args.log_level, sock=sock, in_flight=in_flight)

    if args.workers > 1:  # each process builds its own server after the fork
        return run_workers(args.workers, listening_socket(options.host, options.port), serve)
    serve()
    return EXIT_OK


def episodes_per_caller(args: argparse.Namespace) -> int | None:
    """One caller's share of the store: --episodes-per-caller, else a quarter of it over
    HTTP and all of it over stdio (None)."""
    from verigraph.tools.store import default_share

    if not args.reclaim_idle > 0:
        raise VeriGraphError("--reclaim-idle must be a positive number of seconds",
                             field="--reclaim-idle", value=args.reclaim_idle,
                             fix="use e.g. --reclaim-idle 600")
    share = args.episodes_per_caller
    if share is None:
        return default_share(args.max_episodes) if args.transport == "http" else None
    if not 1 <= share <= args.max_episodes:
        raise VeriGraphError(
            f"--episodes-per-caller {share} is not between 1 and --max-episodes "
            f"({args.max_episodes})", field="--episodes-per-caller", value=share,
            fix="give a share between 1 and --max-episodes")
    return share


def check_workers(transport: str, store: str, arm: Any) -> None:
    """Several server processes share episodes only through a durable store, and an arm
    world lives in one process."""
    if transport != "http":
        raise VeriGraphError("--workers needs --transport http", field="--workers",
                             value=transport, fix="drop --workers for stdio")
    if store.startswith("memory:"):
        raise VeriGraphError("--workers above 1 needs a store the processes share",
                             field="--store", value=store,
                             fix="use --store sqlite:///path/episodes.db or redis://host:port/db")
    if arm is not None:
        raise VeriGraphError("an arm is served by one process only", field="--workers",
                             value=None, fix="drop --workers (or use --workers 1) with an arm")


def default_max_connections() -> int:
    """512, or what the file-descriptor limit leaves after a margin for the server."""
    try:
        import resource

        soft = resource.getrlimit(resource.RLIMIT_NOFILE)[0]
    except (ImportError, ValueError, OSError):
        return 512
    if soft == resource.RLIM_INFINITY:
        return 512
    return max(8, min(512, soft - 64))
