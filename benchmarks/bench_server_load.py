"""Load and fault suite for `verigraph serve` on loopback (bounded in count and time).

Reports, into benchmarks/results/server_load.md:
* validate_action calls/s and p50/p99 with 10 and 50 concurrent HTTP clients;
* a light client's validate_action p99 alone and while a heavy client posts
  5,000-block graphs with 1,000-action plans (validate_plan) back to back;
* the light client beside the heavy and the hostile client on `--workers 2`, with and
  without the child process that checks large bodies (`--only workers`);
* a 280 KB load_scene's latency while another client posts 15 MB bodies from 4
  connections back to back, and while another client keeps 8 bodies of 3.9 MB in flight
  (beside the call alone and the call from that client's own address; `--only fair`
  measures just these rows);
* server RSS per open episode of each kind (built-in scene, sim2d, image, arm) and
  after 10 rounds of open/end on an arm server;
* loading the 100,000-block tower (library) and a 5,000-block tower (load_scene);
* a token client's p99 beside 1,000 half-open connections, and another client's beside
  one holding 600 event streams (bench_admission; `--only admission`);
* seconds from SIGTERM to exit with heavy calls in flight.

Run: python benchmarks/bench_server_load.py [--quick]
"""

from __future__ import annotations

import argparse
import asyncio
import base64
import json
import multiprocessing
import os
import signal
import statistics
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).parent))

import cv2  # noqa: E402
import httpx2  # noqa: E402
import numpy as np  # noqa: E402
from bench_admission import admission_rows  # noqa: E402
from bench_load import tower  # noqa: E402
from bench_server import light_latencies, percentile, start_http, wire_call  # noqa: E402
from common import RESULTS, write_table  # noqa: E402

from verigraph.graph import WorldState  # noqa: E402
from verigraph.graph.io import scene_from_json  # noqa: E402


def children_checking(pid: int) -> list[int]:
    """The server's children that check large bodies (verigraph.server.http.argument_process)."""
    children = Path(f"/proc/{pid}/task/{pid}/children").read_text().split()
    return [int(c) for c in children if b"spawn_main" in Path(f"/proc/{c}/cmdline").read_bytes()]


def rss_mib(pid: int) -> float:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return float("nan")


async def call(http: httpx2.AsyncClient, url: str, name: str, arguments: dict[str, Any]
               ) -> dict[str, Any]:
    headers, body = wire_call(name, arguments, 1)
    reply = (await http.post(url, headers=headers, content=body, timeout=120)).json()
    result = reply["result"]
    assert not result.get("isError"), str(result)[:300]
    return result.get("structuredContent") or {}


async def concurrency(url: str, clients: int, calls_each: int) -> tuple[float, list[float]]:
    async with httpx2.AsyncClient() as http:
        episode = (await call(http, url, "load_scene", {"scene_id": "cup_on_book"}))[
            "episode_id"]
    start = time.perf_counter()
    runs = await asyncio.gather(*[light_latencies(url, episode, calls_each)
                                  for _ in range(clients)])
    elapsed = time.perf_counter() - start
    flat = [t for r in runs for t in r]
    return len(flat) / elapsed, flat


def heavy_arguments(n: int = 5000) -> dict[str, Any]:
    plan = [f"move(b{i}, on, table)" for i in range(n - 2, n - 1002, -1)]
    return {"graph": tower(n), "plan": plan}


def hostile_arguments(nodes: int = 300_000) -> dict[str, Any]:
    """An 11 MB graph of small nodes, far beyond the node limit: refused, after parsing."""
    graph = {"nodes": [{"id": f"n{i}", "label": "block"} for i in range(nodes)], "edges": []}
    return {"graph": graph, "plan": "done"}


def heavy_client(url: str, kind: str, stop: Any, done: Any) -> None:
    """Large calls back to back until `stop` is set: validate_plan on a 5,000-block tower
    ("plan"), or a graph far beyond the limits ("hostile"). Its own process, as a real
    second client would be (its JSON work must not slow the light client's measurements)."""
    arguments = heavy_arguments() if kind == "plan" else hostile_arguments()
    headers, body = wire_call("validate_plan", arguments, 1)
    with httpx2.Client(headers=headers, timeout=120) as http:
        while not stop.is_set():
            reply = http.post(url, content=body).json()
            if kind == "plan":
                assert reply["result"]["structuredContent"]["valid"], str(reply)[:300]
            else:  # refused: as an argument error, or as too large to parse
                assert reply.get("error") or reply["result"]["isError"], str(reply)[:300]
            done.value += 1


async def light_under_heavy(url: str, light_calls: int, heavy: str | None
                            ) -> tuple[list[float], int]:
    async with httpx2.AsyncClient() as http:
        episode = (await call(http, url, "load_scene", {"scene_id": "cup_on_book"}))[
            "episode_id"]
    if heavy is None:
        return await light_latencies(url, episode, light_calls), 0
    spawn = multiprocessing.get_context("spawn")
    stop, done = spawn.Event(), spawn.Value("i", 0)
    process = spawn.Process(target=heavy_client, args=(url, heavy, stop, done))
    process.start()
    while done.value == 0:  # the heavy client is under way
        await asyncio.sleep(0.05)
    times = await light_latencies(url, episode, light_calls)
    stop.set()
    process.join(timeout=120)
    assert process.exitcode == 0, "the heavy client failed"
    return times, done.value


WORKER_SETUPS = {
    "2 worker processes": ["--workers", "2"],
    "2 worker processes, no checking process": ["--workers", "2", "--check-above-kib", "0"],
}


async def light_beside_hostile_on_one_process(url: str, pid: int, light_calls: int
                                              ) -> tuple[list[float], int]:
    """The light client's latencies when its connection and the hostile client's were
    both accepted by the same worker process (the other is stopped while they connect,
    then resumed): what a keep-alive connection that lands beside a hostile one gets."""
    children = [int(c) for c in Path(f"/proc/{pid}/task/{pid}/children").read_text().split()]
    spawn = multiprocessing.get_context("spawn")
    stop, done = spawn.Event(), spawn.Value("i", 0)
    os.kill(children[1], signal.SIGSTOP)
    resumed = False
    try:
        async with httpx2.AsyncClient() as http:
            episode = (await call(http, url, "load_scene", {"scene_id": "cup_on_book"}))[
                "episode_id"]
        process = spawn.Process(target=heavy_client, args=(url, "hostile", stop, done))
        process.start()
        while done.value == 0:
            await asyncio.sleep(0.05)
        headers, body = wire_call("validate_action", {"episode_id": episode,
                                                      "action": "move(cup, on, desk)"}, 2)
        async with httpx2.AsyncClient(headers=headers) as http:
            assert (await http.post(url, content=body)).status_code == 200  # connected
            os.kill(children[1], signal.SIGCONT)
            resumed = True
            times = []
            for _ in range(light_calls):
                start = time.perf_counter()
                response = await http.post(url, content=body)
                times.append(time.perf_counter() - start)
                assert response.status_code == 200
        stop.set()
        process.join(timeout=120)
    finally:
        if not resumed:
            os.kill(children[1], signal.SIGCONT)
    return times, done.value


async def worker_rows(quick: bool) -> list[list[str]]:
    """The light client beside a heavy and a hostile client on `verigraph serve --workers
    2` (one socket, one SQLite store): with the in-process protections, and without the
    child process that checks large bodies (the SDK parses every body on the loop of
    the process that accepted the connection)."""
    rows: list[list[str]] = []
    light = 50 if quick else 1000
    with tempfile.TemporaryDirectory() as tmp:
        for n, (label, extra) in enumerate(WORKER_SETUPS.items()):
            proc, url = start_http([*extra, "--store", f"sqlite:///{tmp}/episodes{n}.db"])
            try:
                alone, _ = await light_under_heavy(url, light, None)
                loaded, heavy_calls = await light_under_heavy(url, light, "plan")
                hostile, hostile_calls = await light_under_heavy(url, light, "hostile")
                shared, shared_calls = await light_beside_hostile_on_one_process(
                    url, proc.pid, light)
            finally:
                proc.terminate()
                proc.wait(timeout=20)
            rows += [[f"{label}: light client alone", "-", ms(alone, 0.5), ms(alone, 0.99),
                      f"{light} calls"],
                     [f"{label}: light client while a heavy client runs", "-",
                      ms(loaded, 0.5), ms(loaded, 0.99),
                      f"{light} calls; heavy: {heavy_calls} validate_plan meanwhile"],
                     [f"{label}: light client while a hostile client runs", "-",
                      ms(hostile, 0.5), ms(hostile, 0.99),
                      f"{light} calls; hostile: {hostile_calls} 11 MB bodies meanwhile"],
                     [f"{label}: same, both connections on one process", "-",
                      ms(shared, 0.5), ms(shared, 0.99),
                      f"{light} calls; hostile: {shared_calls} 11 MB bodies meanwhile"]]
    return rows


FLOOD_NODES = 420_000  # about 15 MB of small nodes: refused by the checker, after parsing
FLOOD_CONNECTIONS = 4
FAIR_BLOCKS = 3000  # a 3,000-block tower: a 280 KB load_scene


def post_back_to_back(url: str, stop: Any, done: Any, nodes: int = FLOOD_NODES,
                      address: str | None = None) -> None:
    """One connection posting a graph of `nodes` small nodes (refused as too large, after
    the checker parsed it) again and again until `stop`, from `address` if given."""
    graph = {"nodes": [{"id": f"n{i}", "label": "block"} for i in range(nodes)],
             "edges": []}
    headers, body = wire_call("validate_plan", {"graph": graph, "plan": "done"}, 1)
    transport = httpx2.HTTPTransport(local_address=address) if address else None
    with httpx2.Client(transport=transport, headers=headers, timeout=120) as http:
        while not stop.is_set():
            reply = http.post(url, content=body)
            assert reply.status_code in (200, 413, 503), reply.text[:300]
            with done.get_lock():
                done.value += 1


def flooding_client(url: str, stop: Any, done: Any) -> None:
    """One client posting 15 MB bodies from FLOOD_CONNECTIONS connections at once, each
    back to back until `stop` is set (its own process, threads for the connections)."""
    threads = [threading.Thread(target=post_back_to_back, args=(url, stop, done))
               for _ in range(FLOOD_CONNECTIONS)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()


async def large_beside_floods(url: str, calls: int) -> tuple[list[float], int, int]:
    """Latencies of a 280 KB load_scene while one client floods the server with 15 MB
    bodies from 4 connections; also the body size and how many floods were answered."""
    headers, body = wire_call("load_scene", {"graph": tower(FAIR_BLOCKS)}, 3)
    async with httpx2.AsyncClient(headers=headers, timeout=120) as http:
        await http.post(url, content=body)  # warm-up: starts what checks large bodies
    spawn = multiprocessing.get_context("spawn")
    stop, done = spawn.Event(), spawn.Value("i", 0)
    process = spawn.Process(target=flooding_client, args=(url, stop, done))
    process.start()
    times = []
    try:
        while done.value < FLOOD_CONNECTIONS:  # every connection has had a body answered
            await asyncio.sleep(0.05)
        async with httpx2.AsyncClient(headers=headers, timeout=120) as http:
            for _ in range(calls):
                start = time.perf_counter()
                reply = (await http.post(url, content=body)).json()
                times.append(time.perf_counter() - start)
                assert not reply["result"].get("isError"), str(reply)[:300]
    finally:
        stop.set()
        process.join(timeout=120)
    return times, len(body), done.value


FAIR_ROW = "280 KB load_scene beside 4 connections posting 15 MB bodies"


async def fair_row(quick: bool) -> list[str]:
    proc, url = start_http()
    try:
        calls = 5 if quick else 20
        times, size, floods = await large_beside_floods(url, calls)
    finally:
        proc.terminate()
        proc.wait(timeout=10)
    return [FAIR_ROW, "-", ms(times, 0.5), ms(times, 0.99),
            f"max {max(times) * 1000:.0f} ms of {calls} calls ({size // 1024} KB each); "
            f"{floods} floods of 15 MB answered meanwhile; target < 1,500 ms"]


BURST_NODES = 110_000  # about 3.9 MB: the same checking child as a 280 KB call (<= 4 MiB)
BURST_BODIES = 8
FLOODER, OTHER = "127.0.0.1", "127.0.0.2"  # two clients: the server tells them by address


def bursting_client(url: str, stop: Any, done: Any) -> None:
    """One client with BURST_BODIES large bodies in flight at all times: a connection
    each, every one posting again as soon as it is answered (its own process)."""
    threads = [threading.Thread(target=post_back_to_back,
                                args=(url, stop, done, BURST_NODES, FLOODER))
               for _ in range(BURST_BODIES)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()


async def timed_calls(url: str, address: str, calls: int) -> tuple[list[float], int]:
    """Seconds until each of `calls` 280 KB load_scene calls from `address` is answered
    (a 503 for a full queue is retried at once and counted; the time includes it)."""
    headers, body = wire_call("load_scene", {"graph": tower(FAIR_BLOCKS)}, 3)
    transport = httpx2.AsyncHTTPTransport(local_address=address)
    times, refused = [], 0
    async with httpx2.AsyncClient(transport=transport, headers=headers, timeout=120) as http:
        for _ in range(calls):
            start = time.perf_counter()
            while (response := await http.post(url, content=body)).status_code == 503:
                refused += 1
            times.append(time.perf_counter() - start)
            assert not response.json()["result"].get("isError"), response.text[:300]
    return times, refused


async def beside_burst(url: str, address: str, calls: int) -> tuple[list[float], int, int]:
    """`timed_calls` from `address` while the bursting client keeps 8 bodies in flight;
    also how many of its bodies were answered meanwhile."""
    spawn = multiprocessing.get_context("spawn")
    stop, done = spawn.Event(), spawn.Value("i", 0)
    process = spawn.Process(target=bursting_client, args=(url, stop, done))
    process.start()
    try:
        while done.value < BURST_BODIES:  # the burst is under way on every connection
            await asyncio.sleep(0.05)
        before = done.value
        times, refused = await timed_calls(url, address, calls)
        answered = done.value - before
    finally:
        stop.set()
        process.join(timeout=120)
    return times, refused, answered


BURST_ROWS = ("280 KB load_scene alone", "280 KB load_scene beside one client's 8 large bodies",
              "280 KB load_scene from that client's own address")


async def burst_rows(quick: bool) -> list[list[str]]:
    """Another client's 280 KB call while one client keeps 8 bodies of 3.9 MB in flight
    (all for the child that checks bodies up to 4 MiB, as the 280 KB one is), beside two
    peers measured on the same server in the same run: the call alone, and the call
    from the bursting client's own address (one client to the server, so its bodies
    come first in arrival order)."""
    calls = 5 if quick else 20
    proc, url = start_http()
    try:
        await timed_calls(url, OTHER, 1)  # warm-up: starts the checking child
        alone, _ = await timed_calls(url, OTHER, calls)
        other, other_refused, other_burst = await beside_burst(url, OTHER, calls)
        same, same_refused, same_burst = await beside_burst(url, FLOODER, calls)
    finally:
        proc.terminate()
        proc.wait(timeout=10)
    def versus_alone(times: list[float]) -> str:
        return f"{percentile(times, 0.5) / percentile(alone, 0.5):.1f}x"

    return [
        [BURST_ROWS[0], "-", ms(alone, 0.5), ms(alone, 0.99),
         f"max {max(alone) * 1000:.0f} ms of {calls} calls; the peer of the next two rows"],
        [f"{BURST_ROWS[1]} (another address)", "-", ms(other, 0.5), ms(other, 0.99),
         f"max {max(other) * 1000:.0f} ms of {calls} calls, p50 {versus_alone(other)} alone; "
         f"{other_burst} bodies of 3.9 MB answered meanwhile; {other_refused} refused; "
         "target < 1,500 ms"],
        [f"{BURST_ROWS[2]} (one client: arrival order)", "-", ms(same, 0.5), ms(same, 0.99),
         f"max {max(same) * 1000:.0f} ms of {calls} calls, p50 {versus_alone(same)} alone; "
         f"{same_burst} bodies answered meanwhile; {same_refused} times refused with 503 "
         "(8 bodies per client may wait) and sent again"],
    ]


def jpeg_b64(width: int = 1600, height: int = 1200) -> str:
    image = np.full((height, width, 3), 180, dtype=np.uint8)
    ok, buf = cv2.imencode(".jpg", image)
    assert ok
    return base64.b64encode(buf.tobytes()).decode()


async def rss_per_episode(url: str, pid: int, kind: str, arguments: dict[str, Any],
                          count: int) -> float:
    async with httpx2.AsyncClient() as http:
        await call(http, url, "load_scene", arguments)  # warm caches and imports
        before = rss_mib(pid)
        ids = [(await call(http, url, "load_scene", arguments))["episode_id"]
               for _ in range(count)]
        after = rss_mib(pid)
        for episode in ids:
            await call(http, url, "end_episode", {"episode_id": episode})
    return (after - before) / count


async def open_end_rounds(url: str, pid: int, arguments: dict[str, Any], rounds: int
                          ) -> tuple[float, float, float]:
    async with httpx2.AsyncClient() as http:
        first = (await call(http, url, "load_scene", arguments))["episode_id"]
        await call(http, url, "end_episode", {"episode_id": first})
        start = rss_mib(pid)
        peak = start
        for _ in range(rounds):
            episode = (await call(http, url, "load_scene", arguments))["episode_id"]
            peak = max(peak, rss_mib(pid))
            await call(http, url, "end_episode", {"episode_id": episode})
        return start, peak, rss_mib(pid)


async def sigterm_exit(in_flight: int) -> float:
    proc, url = start_http()
    arguments = heavy_arguments()

    async def heavy() -> None:
        try:
            async with httpx2.AsyncClient() as http:
                headers, body = wire_call("validate_plan", arguments, 1)
                await http.post(url, headers=headers, content=body, timeout=60)
        except httpx2.HTTPError:
            pass  # the server went away: expected

    tasks = [asyncio.create_task(heavy()) for _ in range(in_flight)]
    await asyncio.sleep(1.0)  # requests sent and running
    start = time.perf_counter()
    proc.send_signal(signal.SIGTERM)
    while proc.poll() is None:
        await asyncio.sleep(0.01)
    elapsed = time.perf_counter() - start
    await asyncio.gather(*tasks)
    return elapsed


def tower_load_s(n: int) -> float:
    text = json.dumps(tower(n))
    start = time.perf_counter()
    WorldState.from_graph(scene_from_json(text))
    return time.perf_counter() - start


def ms(values: list[float], q: float) -> str:
    return f"{percentile(values, q) * 1000:.1f}"


ARM_ROWS = ("RSS per open episode: arm:pybullet", "RSS over 10 open/end rounds, arm:pybullet")


async def arm_rows(quick: bool) -> list[list[str]]:
    """RSS of an arm server (dry-run Panda): per open episode, and over 10 open/end
    rounds after a warm-up round (what end_episode fails to release shows as growth)."""
    rows: list[list[str]] = []
    arm_proc, arm_url = start_http(["--executor", "arm:pybullet"])
    try:
        arm = {"scene_id": "three_blocks", "executor": "arm:pybullet"}
        per = await rss_per_episode(arm_url, arm_proc.pid, "arm", arm, 2 if quick else 4)
        rows.append([f"{ARM_ROWS[0]} (dry-run)", "-", "-", "-", f"{per:.1f} MiB"])
        start, peak, end = await open_end_rounds(arm_url, arm_proc.pid, arm, 10)
        rows.append([ARM_ROWS[1], "-", "-", "-",
                     f"{start:.0f} -> {end:.0f} MiB (peak {peak:.0f}): "
                     f"{end - start:+.0f} MiB"])
    finally:
        arm_proc.terminate()
        arm_proc.wait(timeout=10)
    return rows


TOWER_ROW = "load + check the 100,000-block tower (library)"


def tower_row() -> list[str]:
    return [TOWER_ROW, "-", f"{tower_load_s(100_000) * 1000:.0f}", "-", "parse, check, index"]


async def some_rows(parts: list[str], quick: bool) -> list[list[str]]:
    rows = await arm_rows(quick) if "arm" in parts else []
    rows += [await fair_row(quick), *await burst_rows(quick)] if "fair" in parts else []
    rows += await worker_rows(quick) if "workers" in parts else []
    rows += await admission_rows(quick) if "admission" in parts else []
    return rows + ([tower_row()] if "tower" in parts else [])


def replace_rows(path: Path, rows: list[list[str]], parts: list[str], load: float) -> str:
    """The stored table with only the rows of `parts` measured again (and said so)."""
    note = "Measured again on "
    lines = [line for line in path.read_text().rstrip("\n").splitlines()
             if not line.startswith(note)]
    while lines and not lines[-1]:
        lines.pop()
    fresh = {row[0].split(" (")[0]: "| " + " | ".join(row) + " |" for row in rows}
    out = [next((text for name, text in fresh.items() if line.startswith(f"| {name}")), line)
           for line in lines]
    last_row = max(i for i, line in enumerate(out) if line.startswith("|"))
    missing = [text for name, text in fresh.items()
               if not any(line.startswith(f"| {name}") for line in lines)]
    out[last_row + 1:last_row + 1] = missing  # rows the stored table does not have yet
    out += ["", f"{note}{time.strftime('%Y-%m-%d %H:%M', time.gmtime())} UTC with "
                f"`--only {' '.join(parts)}`: those rows (1-minute load average {load:.2f})."]
    return "\n".join(out) + "\n"


async def run(quick: bool) -> list[list[str]]:
    rows: list[list[str]] = []
    proc, url = start_http()
    try:
        for clients in (10, 50):
            calls_each = (20 if quick else 100) if clients == 10 else (4 if quick else 20)
            rate, flat = await concurrency(url, clients, calls_each)
            rows.append([f"validate_action, {clients} concurrent clients", f"{rate:,.0f}",
                         ms(flat, 0.5), ms(flat, 0.99), f"{len(flat)} calls"])
        light = 50 if quick else 1000
        alone, _ = await light_under_heavy(url, light, None)
        loaded, heavy_calls = await light_under_heavy(url, light, "plan")
        hostile, hostile_calls = await light_under_heavy(url, light, "hostile")
        rows.append(["light client alone: validate_action", "-", ms(alone, 0.5),
                     ms(alone, 0.99), f"{light} calls"])
        rows.append(["light client while a heavy client runs", "-", ms(loaded, 0.5),
                     ms(loaded, 0.99), f"{light} calls; heavy: {heavy_calls} validate_plan "
                     "(5,000 blocks, 1,000 actions) meanwhile; p99 ratio "
                     f"{percentile(loaded, 0.99) / percentile(alone, 0.99):.1f}x"])
        rows.append(["light client while a hostile client runs", "-", ms(hostile, 0.5),
                     ms(hostile, 0.99), f"{light} calls; hostile: {hostile_calls} "
                     "validate_plan with 300,000 nodes (11 MB, refused) meanwhile"])
        checkers = children_checking(proc.pid)
        rows.append(["RSS of the process that checks large bodies", "-", "-", "-",
                     f"{sum(rss_mib(pid) for pid in checkers):.0f} MiB "
                     f"({len(checkers)} process)"])
        count = 5 if quick else 20
        kinds = {"built-in scene": {"scene_id": "cup_on_book"},
                 "sim2d": {"scene_id": "three_blocks", "simulate": True},
                 "image (1600x1200 JPEG)": {"image": jpeg_b64(), "dictionary": "kitchen"}}
        for kind, arguments in kinds.items():
            per = await rss_per_episode(url, proc.pid, kind, arguments, count)
            rows.append([f"RSS per open episode: {kind}", "-", "-", "-",
                         f"{per:.2f} MiB ({count} episodes)"])
        async with httpx2.AsyncClient() as http:
            start = time.perf_counter()
            await call(http, url, "validate_plan", {"graph": tower(5000), "plan": "done"})
            rows.append(["5,000-block tower: validate_plan round trip", "-",
                         f"{(time.perf_counter() - start) * 1000:.0f}", "-",
                         "the largest graph a request may carry"])
    finally:
        proc.terminate()
        proc.wait(timeout=10)
    rows.append(await fair_row(quick))
    rows += await burst_rows(quick)
    rows += await worker_rows(quick)
    rows += await admission_rows(quick)
    rows += await arm_rows(quick)
    rows.append(tower_row())
    exits = [await sigterm_exit(4) for _ in range(1 if quick else 3)]
    rows.append(["SIGTERM to exit, 4 heavy calls in flight", "-",
                 f"{statistics.median(exits) * 1000:.0f}", "-",
                 f"max {max(exits) * 1000:.0f} ms of {len(exits)} runs"])
    return rows


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer calls (smoke test)")
    parser.add_argument("--only", nargs="+", choices=["admission", "arm", "fair", "tower",
                                                        "workers"],
                        help="measure only these rows (the arm server's RSS, the large call "
                             "beside floods, the tower load, --workers 2, a client beside "
                             "half-open connections or event streams) and update them "
                             "in the stored table")
    args = parser.parse_args()
    load = os.getloadavg()[0]
    if args.only:
        path = RESULTS / "server_load.md"
        text = replace_rows(path, asyncio.run(some_rows(args.only, args.quick)), args.only,
                            load)
        path.write_text(text)
        print(text)
        return 0
    rows = asyncio.run(run(args.quick))
    notes = ("All clients and servers on loopback on the same machine; the heavy client is "
             "a process of its own. Light calls run on the event loop; heavy calls (large "
             "graphs or plans, images, simulator, search, arms) on at most 2 worker threads, "
             "1 per client connection, each within its wall-clock and memory budget; bodies "
             "over 64 KiB are parsed and checked in a child process (one for bodies up "
             "to 4 MiB, one for larger ones, each taking bodies round-robin over "
             "clients and answering within 10 s), and large "
             "results serialised on worker threads (verigraph.server.http.offload). The worker "
             "rows run `verigraph serve --workers 2` on one SQLite store. 1-minute load "
             "average at start: "
             f"{load:.2f} (other jobs share the 2 cores; absolute times are inflated by it).")
    write_table("server_load", "MCP server under load and faults",
                ["what", "calls/s", "p50 ms", "p99 ms", "notes"], rows, notes)
    return 0


if __name__ == "__main__":
    sys.exit(main())
