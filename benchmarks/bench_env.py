"""The Gymnasium environment's throughput: steps in process and over MCP, rollouts on Ray.

1. Steps per second of `VeriGraphEnv` in process (the tool functions the MCP server
   wraps, no transport), with the oracle policy (the reference solver plans every step)
   and with a policy whose every action is refused (the verifier's cheapest answer),
   against the agent loop (`verigraph.agent.run_episode`, Algorithm 1 with the oracle
   planner) on the same tasks: one environment step is one loop iteration.
2. The same oracle episodes with the environment's tools over MCP stdio (a real
   `verigraph serve` child and the official SDK client).
3. Rollouts per second of noisy-planner episodes through the evaluation engine's one
   dispatch (`run_rollouts` -> `engine.run_on_workers`, the serial and Ray paths of
   `bench plan`): serial in this process, serial writing every episode to a trajectory
   file as it ends (the resumable results file), and on a local Ray with this machine's
   cores (`ray="local"`); worker start-up is timed apart. The trajectories of the runs
   are compared line by line.

Run: `verigraph bench env [--episodes 400] [--mcp-episodes 20]`; writes results/env.md.
About a minute on 2 cores.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from common import write_table  # noqa: E402

from verigraph.agent import LoopConfig, McpTools, run_episode  # noqa: E402
from verigraph.env import VeriGraphEnv, build_tasks  # noqa: E402
from verigraph.env.dataset import Task  # noqa: E402
from verigraph.env.rollout import RolloutJob, make_policy, run_rollout, run_rollouts  # noqa: E402
from verigraph.planning import InProcessTools, make_planner  # noqa: E402


def pool() -> list[Task]:
    return [*build_tasks("blocks", 10), *build_tasks("kitchen", 6), *build_tasks("tangram", 10)]


def env_steps(env: VeriGraphEnv, policy_name: str, tasks: list[Task], rounds: int
              ) -> tuple[int, float, float]:
    """(steps, wall seconds, CPU seconds) of whole episodes of every task, `rounds` times."""
    steps = 0
    wall, cpu = time.perf_counter(), time.process_time()
    for r in range(rounds):
        policy = make_policy(policy_name, seed=r)
        for task in tasks:
            steps += run_rollout(env, policy, RolloutJob(task_id=task.task_id, seed=r)).steps
    return steps, time.perf_counter() - wall, time.process_time() - cpu


def loop_iterations(tasks: list[Task], rounds: int) -> tuple[int, float, float]:
    tools = InProcessTools()
    planner = make_planner("oracle")
    iterations = 0
    wall, cpu = time.perf_counter(), time.process_time()
    for _ in range(rounds):
        for task in tasks:
            iterations += len(run_episode(tools, planner, task.spec, LoopConfig()).iterations)
    return iterations, time.perf_counter() - wall, time.process_time() - cpu


def main(argv: list[str]) -> int:
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--rounds", type=int, default=3, help="passes over the task pool (part 1)")
    p.add_argument("--mcp-episodes", type=int, default=20, help="oracle episodes over MCP")
    p.add_argument("--episodes", type=int, default=400, help="noisy rollouts (part 3)")
    args = p.parse_args(argv)
    tasks = pool()
    rows: list[list[str]] = []

    env = VeriGraphEnv(tasks=tasks)
    env_steps(env, "oracle", tasks[:5], 1)  # warm-up (imports, caches)
    loop_iterations(tasks[:5], 1)
    # Interleaved rounds, so that load from other jobs falls on every variant alike.
    totals = {"oracle": [0, 0.0, 0.0], "refuse": [0, 0.0, 0.0], "loop": [0, 0.0, 0.0]}
    for _ in range(args.rounds):
        for name in totals:
            got = loop_iterations(tasks, 1) if name == "loop" else env_steps(env, name, tasks, 1)
            totals[name] = [a + b for a, b in zip(totals[name], got, strict=True)]
    env.close()
    oracle, refused, loop = (tuple(totals[n]) for n in ("oracle", "refuse", "loop"))

    def row(what: str, measured: tuple[float, ...], peer: tuple[float, ...] | None) -> None:
        rate, cpu_rate = measured[0] / measured[1], measured[0] / measured[2]
        ratio = "" if peer is None else \
            f"{rate / (peer[0] / peer[1]):.2f}x wall, {cpu_rate / (peer[0] / peer[2]):.2f}x CPU"
        rows.append([what, f"{measured[0]:.0f}", f"{rate:,.0f}", f"{cpu_rate:,.0f}", ratio])

    row("env step, in process, oracle policy", oracle, loop)
    row("env step, in process, refused actions", refused, loop)
    row("peer: agent loop iteration (run_episode, oracle), in process", loop, None)

    mcp_tasks = tasks[: args.mcp_episodes]
    tools = McpTools.stdio()
    try:
        remote = VeriGraphEnv(tasks=tasks, tools=tools)
        env_steps(remote, "oracle", mcp_tasks[:2], 1)
        over_mcp = env_steps(remote, "oracle", mcp_tasks, 1)
        remote.close()
    finally:
        tools.close()
    local = VeriGraphEnv(tasks=tasks)
    same = env_steps(local, "oracle", mcp_tasks, 1)
    local.close()
    row("env step over MCP stdio, oracle policy (vs the same episodes in process)",
        over_mcp, same)

    jobs = [RolloutJob(task_id=tasks[i % len(tasks)].task_id, seed=i, policy="noisy",
                       policy_seed=i) for i in range(args.episodes)]
    kwargs = {"tasks": tasks}
    timings = {}
    results = {}
    runs = {"serial": (None, None), "serial, trajectory file": (None, "file"),
            f"ray (local, {os.cpu_count()} workers)": ("local", None)}
    with tempfile.TemporaryDirectory() as scratch:
        for name, (address, sink) in runs.items():
            started = time.perf_counter()
            ready = [started]
            path = Path(scratch) / "trajectories.jsonl" if sink else None
            results[name] = run_rollouts(jobs, kwargs, ray=address, trajectories=path,
                                         on_ready=lambda marks=ready: marks.append(
                                             time.perf_counter()))
            end = time.perf_counter()
            timings[name] = (end - ready[-1], ready[-1] - started)
    identical = all([r.lines for r in got] == [r.lines for r in results["serial"]]
                    for got in results.values())
    serial_rate = args.episodes / timings["serial"][0]
    steps = sum(r.steps for r in results["serial"])
    for name in runs:
        run_s, start_s = timings[name]
        rate = args.episodes / run_s
        rows.append([f"rollouts, noisy policy, {name}", f"{args.episodes} ({steps} steps)",
                     f"{rate:,.1f} rollouts/s", f"start-up {start_s:.1f} s",
                     f"{rate / serial_rate:.2f}x" if name != "serial" else ""])
    notes = (f"Rates are per wall-clock second (CPU column: per CPU second of this process; "
             f"for the MCP row the server child's CPU is not counted). Peers were measured "
             f"in the same run; the rollout rows all go through the evaluation engine's dispatch, "
             f"the ratio is to the serial row. Trajectories of every rollout run "
             f"identical: {identical}. "
             f"Tasks: {len(tasks)} (blocks, kitchen, tangram suites), {args.rounds} rounds "
             f"in part 1. Load average at the end: {os.getloadavg()[0]:.1f} on "
             f"{os.cpu_count()} cores (other jobs share them; Ray needs free cores to "
             f"gain).")
    write_table("env", "Gymnasium environment: steps and rollouts per second",
                ["what", "count", "per second (wall)", "per CPU second", "ratio to peer"],
                rows, notes)
    return 0 if identical else 1


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
