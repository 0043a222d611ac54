"""Episode stores side by side: validate_action and execute_actions over HTTP, 10 clients.

For each store (memory://, sqlite:/// in a temporary directory, redis:// on a private
redis-server) one `verigraph serve --transport http --store URL` runs; 10 concurrent
clients post tools/call requests in the exact wire form the SDK client sends:
* validate_action on one shared episode (reads: the cached episode after one version
  check per request);
* execute_actions, each client on its own episode, alternating two valid moves (each
  call is a compare-and-set write).
Reports p50/p99 per call, calls/s and errors, and the ratio to memory measured in the same
run. Target: SQLite and Redis within 2x of memory for validate_action, no errors.
Run: python benchmarks/bench_store.py [--quick]
"""

from __future__ import annotations

import argparse
import asyncio
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

import httpx2  # noqa: E402
from bench_server import (  # noqa: E402
    free_port,
    percentile,
    verigraph_command,
    wait_port,
    wire_call,
)
from common import write_table  # noqa: E402

CLIENTS = 10
MOVES = ["move(cup, desk)", "move(cup, book)"]


def start_server(store: str) -> tuple[subprocess.Popen[bytes], str]:
    port = free_port()
    proc = subprocess.Popen([*verigraph_command(), "serve", "--transport", "http", "--port",
                             str(port), "--store", store], stderr=subprocess.DEVNULL)
    wait_port(port, proc)
    return proc, f"http://127.0.0.1:{port}/mcp"


class Run:
    """Per-call times and errors of one tool under load."""

    def __init__(self) -> None:
        self.times: list[float] = []
        self.errors = 0
        self.elapsed = 0.0


async def load_scene(http: httpx2.AsyncClient, url: str) -> str:
    headers, body = wire_call("load_scene", {"scene_id": "cup_on_book"}, 1)
    reply = (await http.post(url, headers=headers, content=body)).json()
    episode: str = reply["result"]["structuredContent"]["episode_id"]
    return episode


async def measure(url: str, tool: str, calls_each: int) -> Run:
    run = Run()
    async with httpx2.AsyncClient(timeout=60) as http:
        shared = await load_scene(http, url)
        own = [await load_scene(http, url) for _ in range(CLIENTS)]

    async def client(index: int, record: bool) -> None:
        async with httpx2.AsyncClient(timeout=60) as http:
            for i in range(calls_each):
                if tool == "validate_action":
                    args = {"episode_id": shared, "action": MOVES[0]}
                else:
                    args = {"episode_id": own[index], "actions": [MOVES[i % 2]]}
                headers, body = wire_call(tool, args, i + 2)
                start = time.perf_counter()
                response = await http.post(url, headers=headers, content=body)
                took = time.perf_counter() - start
                ok = response.status_code == 200 and b'"isError":false' in response.content
                if tool == "execute_actions":
                    ok = ok and b'"ok":true' in response.content
                if record:
                    run.times.append(took)
                    run.errors += not ok

    await client(0, record=False)  # warm-up
    start = time.perf_counter()
    await asyncio.gather(*[client(i, record=True) for i in range(CLIENTS)])
    run.elapsed = time.perf_counter() - start
    return run


def summary(runs: list[Run]) -> tuple[float, float, float, int]:
    """Median p50, p99 and calls/s over rounds, and all errors."""
    return (statistics.median(percentile(r.times, 0.5) for r in runs),
            statistics.median(percentile(r.times, 0.99) for r in runs),
            statistics.median(len(r.times) / r.elapsed for r in runs),
            sum(r.errors for r in runs))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer calls (smoke test)")
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    calls_each = 20 if args.quick else 100
    rounds = 1 if args.quick else args.rounds
    redis_bin = shutil.which("redis-server")
    if redis_bin is None:
        print("redis-server is not installed: apt-get install -y redis-server")
        return 2
    rport = free_port()
    redis_proc = subprocess.Popen([redis_bin, "--port", str(rport), "--bind", "127.0.0.1",
                                   "--save", "", "--appendonly", "no"],
                                  stdout=subprocess.DEVNULL)
    tmp = tempfile.mkdtemp(prefix="verigraph-bench-store-")
    stores = {"memory": "memory://", "sqlite": f"sqlite:///{tmp}/episodes.db",
              "redis": f"redis://127.0.0.1:{rport}/0"}
    results: dict[tuple[str, str], list[Run]] = {}
    load = os.getloadavg()[0]
    servers: list[subprocess.Popen[bytes]] = []
    try:
        wait_port(rport, redis_proc)
        endpoints = {}
        for name, url in stores.items():
            proc, endpoints[name] = start_server(url)
            servers.append(proc)
        # Rounds alternate the stores, so a burst of load on the shared machine does not
        # fall on one store only; the table reports medians over the rounds.
        for _ in range(rounds):
            for tool in ("validate_action", "execute_actions"):
                for name, endpoint in endpoints.items():
                    run = asyncio.run(measure(endpoint, tool, calls_each))
                    results.setdefault((name, tool), []).append(run)
    finally:
        for proc in servers:
            proc.terminate()
            proc.wait(timeout=10)
        redis_proc.terminate()
        redis_proc.wait(timeout=10)
        shutil.rmtree(tmp, ignore_errors=True)

    rows = []
    met = True
    for tool in ("validate_action", "execute_actions"):
        base_p50 = summary(results[("memory", tool)])[0]
        for name in stores:
            p50, p99, rate, errors = summary(results[(name, tool)])
            ratio = p50 / base_p50
            target = "-"
            if tool == "validate_action" and name != "memory":
                target = "within 2x: " + ("met" if ratio <= 2 and not errors else "MISSED")
                met = met and ratio <= 2
            met = met and errors == 0
            rows.append([tool, name, f"{p50 * 1000:.2f}", f"{p99 * 1000:.2f}", f"{rate:,.0f}",
                         f"{ratio:.2f}x", str(errors), target])
    notes = (f"{CLIENTS} concurrent HTTP clients x {calls_each} calls each per tool and "
             f"round, after a warm-up; medians of {rounds} round(s) that alternate the "
             "stores; validate_action on one shared episode, execute_actions on one episode "
             "per client (every call a committed state change). Server, Redis and clients "
             f"share the machine; 1-minute load average at start: {load:.2f}. The ratio is "
             "p50 against the memory store in the same run.")
    write_table("store", "Episode stores over HTTP",
                ["tool", "store", "p50 ms", "p99 ms", "calls/s", "p50 vs memory", "errors",
                 "target"], rows, notes)
    return 0 if met else 1


if __name__ == "__main__":
    sys.exit(main())
