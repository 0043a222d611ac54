"""`verigraph view`: the plan viewer as a local web page (loopback only, with a token)."""

from __future__ import annotations

import argparse
import os
import secrets
import socket
from typing import Any

from verigraph.cli.exits import EXIT_OK

TOKEN_ENV = "VERIGRAPH_TOKEN"


def register(sub: Any) -> None:
    p = sub.add_parser("view", help="open the plan viewer as a local web page",
                       description="Serve the viewer on 127.0.0.1: paste or drop a scene "
                                   "(JSON/YAML or a built-in id), a plan and an optional "
                                   "goal, and see the per-step report with drawings. Open "
                                   "the printed URL (it carries the access token).")
    p.add_argument("--port", type=int, default=8765, help="port on 127.0.0.1 (default 8765; "
                                                          "0 picks a free one)")
    p.add_argument("--token", default=None,
                   help=f"access token (default: ${TOKEN_ENV}, else a random one)")
    p.set_defaults(handler=run_view)


def run_view(args: argparse.Namespace) -> int:
    import anyio
    import uvicorn

    from verigraph.errors import VeriGraphError
    from verigraph.tools.registry import Toolbox
    from verigraph.viewer.web import viewer_app

    token = args.token or os.environ.get(TOKEN_ENV) or secrets.token_urlsafe(24)
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    try:
        sock.bind(("127.0.0.1", args.port))
    except OSError as exc:
        sock.close()
        raise VeriGraphError(f"cannot listen on 127.0.0.1:{args.port}: {exc.strerror}",
                             field="--port", value=args.port,
                             fix="pick another port, or --port 0 for a free one") from None
    port = sock.getsockname()[1]
    sock.listen(128)  # connections queue from now on, so the printed URL works at once
    app = viewer_app(Toolbox().context, token)
    config = uvicorn.Config(app, log_level="warning", access_log=False, lifespan="off")
    print(f"VeriGraph viewer: http://127.0.0.1:{port}/#token={token}", flush=True)
    anyio.run(uvicorn.Server(config).serve, [sock])
    return EXIT_OK
