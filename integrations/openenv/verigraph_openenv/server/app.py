"""The OpenEnv 0.10 app: `uvicorn verigraph_openenv.server.app:app --port 8000`.

Each session gets a `VeriGraphProxyEnvironment` connected to the VeriGraph environment
server at `VERIGRAPH_URL`; `VERIGRAPH_MAX_SESSIONS` (default 64) sessions at once.
"""

from __future__ import annotations

import argparse
import os

from openenv.core.env_server import create_app
from openenv.core.env_server.types import ConcurrencyConfig

from verigraph_openenv.models import VeriGraphAction, VeriGraphObservation
from verigraph_openenv.server.environment import VeriGraphProxyEnvironment

app = create_app(VeriGraphProxyEnvironment, VeriGraphAction, VeriGraphObservation,
                 env_name="verigraph",
                 concurrency_config=ConcurrencyConfig(
                     max_concurrent_envs=int(os.environ.get("VERIGRAPH_MAX_SESSIONS", "64")),
                     session_timeout=600.0))


def main() -> None:
    import uvicorn

    parser = argparse.ArgumentParser(description="VeriGraph OpenEnv server")
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, default=8000)
    args = parser.parse_args()
    uvicorn.run(app, host=args.host, port=args.port)


if __name__ == "__main__":
    main()
