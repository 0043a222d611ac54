"""Drive a VeriGraph OpenEnv server with the package's client, one JSON command a line.

`python -m verigraph_openenv.drive URL` reads commands from stdin
(`{"reset": {...}}`, `{"step": "move(...)"}`, `{"state": true}`) and writes one JSON
result per line: the observation, reward and done, or `{"error": ...}`. Tests and
scripts in another Python environment use it to play episodes through OpenEnv's own
client without importing OpenEnv themselves.
"""

from __future__ import annotations

import json
import sys

from verigraph_openenv.client import VeriGraphEnv
from verigraph_openenv.models import VeriGraphAction


def main() -> None:
    with VeriGraphEnv(base_url=sys.argv[1]).sync() as env:
        for line in sys.stdin:
            command = json.loads(line)
            try:
                if "reset" in command:
                    result = env.reset(**command["reset"])
                elif "step" in command:
                    result = env.step(VeriGraphAction(actions=command["step"]))
                else:
                    print(json.dumps({"state": env.state().model_dump()}), flush=True)
                    continue
            except Exception as exc:  # the server's refusal, reported to the caller
                print(json.dumps({"error": f"{type(exc).__name__}: {exc}"}), flush=True)
                continue
            print(json.dumps({"observation": result.observation.model_dump(),
                              "reward": result.reward, "done": result.done}), flush=True)


if __name__ == "__main__":
    main()
