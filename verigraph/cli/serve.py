"""`verigraph serve`: the MCP server over stdio (default) or streamable HTTP."""

from __future__ import annotations

import argparse
import logging
import os
import sys
from pathlib import Path
from typing import Any

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
    p.add_argument("--token", default=None,
                   help=f"require 'Authorization: Bearer TOKEN' on HTTP (default: ${TOKEN_ENV})")
    p.add_argument("--allow-host", action="append", default=[], metavar="NAME",
                   help="extra Host/Origin name accepted over HTTP (repeatable)")
    p.add_argument("--max-body-mib", type=float, default=16.0,
                   help="largest HTTP request body in MiB (default 16)")
    p.add_argument("--max-episodes", type=int, default=256,
                   help="open episodes kept at once (default 256)")
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
                        "arm:rosbridge or arm:xarm (default with --arm-config: its arm)")
    p.add_argument("--arm-config", type=Path, default=None, metavar="FILE",
                   help="arm configuration (YAML or JSON): driver, host, workspace, keep-out "
                        "zones, speeds, force cap, timeouts, mode (dry-run unless the file "
                        "says sim or real)")
    p.add_argument("--log-level", default="WARNING",
                   choices=("DEBUG", "INFO", "WARNING", "ERROR"), help="stderr log level")
    p.set_defaults(handler=run_serve)


def run_serve(args: argparse.Namespace) -> int:
    logging.basicConfig(stream=sys.stderr, level=args.log_level,
                        format="%(asctime)s %(levelname)s %(name)s: %(message)s")
    from verigraph.server.app import build_server
    from verigraph.server.http import HttpOptions, serve_http
    from verigraph.tools.context import ToolConfig
    from verigraph.tools.executors import server_executor
    from verigraph.tools.stores import default_store_url, redacted

    token = args.token or os.environ.get(TOKEN_ENV) or None
    if args.transport == "http" and args.host not in ("127.0.0.1", "localhost", "::1") \
            and not token:
        raise VeriGraphError(f"refusing to serve on {args.host} without a token",
                             field="--host", value=args.host,
                             fix=f"pass --token (or set {TOKEN_ENV}), or bind to 127.0.0.1")
    if args.max_episodes < 1 or not 0 < args.max_body_mib <= 1024 or args.idle_timeout <= 0:
        raise VeriGraphError("limits out of range", field="--max-episodes/--max-body-mib",
                             value=None, fix="use --max-episodes >= 1 and 0 < --max-body-mib "
                                             "<= 1024, --idle-timeout > 0")
    executor, arm = server_executor(args.executor, args.arm_config)
    if arm is not None and executor.startswith("arm:"):
        logging.getLogger("verigraph.server").warning(
            "episodes run on %s in mode %s", executor, arm.config.mode)
    store = args.store or default_store_url()
    logging.getLogger("verigraph.server").info("episodes are kept in %s", redacted(store))
    config = ToolConfig(max_episodes=args.max_episodes, enable_solve=not args.disable_solve,
                        executor=executor, arm=arm, store=store,
                        idle_timeout_s=args.idle_timeout)
    server = build_server(config=config, log_level=args.log_level)
    if args.transport == "stdio":
        server.run("stdio")
        return 0
    options = HttpOptions(host=args.host, port=args.port, token=token,
                          max_body_bytes=int(args.max_body_mib * 1024 * 1024),
                          allowed_hosts=tuple(args.allow_host))
    serve_http(server, options, log_level=args.log_level)
    return 0
