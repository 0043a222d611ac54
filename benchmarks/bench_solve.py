"""Solver benchmark: VeriGraph's solver against Fast Downward (LAMA, seq-opt-lmcut) and
pyperplan on the same random IPC-2000-sized blocks-world problems, in the same run.

Peers plan on the 4-op PDDL (pick-up/put-down/stack/unstack); VeriGraph plans moves on
the scene graph. A move is exactly one grasp + one release, so our 4-op length is twice
the number of moves (and an optimal 4-op plan is twice an optimal move plan). Each peer
runs in its own process with a wall-clock limit (pyperplan has no timeout of its own).
Run: python benchmarks/bench_solve.py [--sizes 4 8 12 20 30 50] [--seeds 1] [--timeout 20]
"""

from __future__ import annotations

import argparse
import multiprocessing as mp
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).parent))

from blocks_problems import DOMAIN_FILE, problem  # noqa: E402
from common import write_table  # noqa: E402

from verigraph.actions import validate_plan  # noqa: E402
from verigraph.solver import solve  # noqa: E402

PEERS = {"FD lama-first": ("fast-downward", {}), "FD seq-opt-lmcut": ("fast-downward-opt", {}),
         "pyperplan": ("pyperplan", {})}


def _peer_worker(engine: str, params: dict[str, Any], problem_file: str, out: Any) -> None:
    import os
    import warnings

    os.chdir(Path(problem_file).parent)  # Fast Downward writes output.sas into the cwd
    from unified_planning.io import PDDLReader
    from unified_planning.shortcuts import OneshotPlanner, get_environment

    warnings.simplefilter("ignore")
    get_environment().credits_stream = None
    parsed = PDDLReader().parse_problem(str(DOMAIN_FILE), problem_file)
    start = time.perf_counter()
    with OneshotPlanner(name=engine, params=params) as planner:
        result = planner.solve(parsed)
    length = len(result.plan.actions) if result.plan is not None else None
    out.put((length, time.perf_counter() - start))


def run_peer(engine: str, params: dict[str, Any], problem_file: str, timeout: float
             ) -> tuple[int | None, float | None]:
    """(4-op plan length or None, seconds or None on timeout/failure)."""
    queue: Any = mp.Queue()
    proc = mp.Process(target=_peer_worker, args=(engine, params, problem_file, queue))
    start = time.perf_counter()
    proc.start()
    proc.join(timeout)
    if proc.is_alive():
        proc.terminate()
        proc.join()
        return None, None
    if queue.empty():
        return None, time.perf_counter() - start
    return queue.get()  # type: ignore[no-any-return]


def fmt(length: int | None, seconds: float | None) -> str:
    if length is None:
        return "timeout" if seconds is None else "failed"
    return f"{length} in {seconds:.2f} s"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[4, 8, 12, 16, 20, 30, 40, 50])
    parser.add_argument("--seeds", type=int, default=1)
    parser.add_argument("--timeout", type=float, default=20.0, help="seconds per peer run")
    parser.add_argument("--peers", nargs="*", default=list(PEERS), choices=list(PEERS))
    args = parser.parse_args()
    rows = []
    workdir = Path(tempfile.mkdtemp(prefix="bench_solve_"))
    for n in args.sizes:
        for seed in range(args.seeds):
            text, start, goal, _, _ = problem(n, 1000 * n + seed)
            pfile = workdir / f"p{n}_{seed}.pddl"
            pfile.write_text(text)
            t0 = time.perf_counter()
            anytime = solve(start, goal, anytime=True)
            t_any = time.perf_counter() - t0
            assert anytime.reachable and validate_plan(start, anytime.plan, goal)["valid"]
            t0 = time.perf_counter()
            optimal = solve(start, goal, time_limit=args.timeout)
            t_opt = time.perf_counter() - t0
            ours_any = (f"{2 * len(anytime.plan)} in {t_any:.2f} s"
                        + ("" if anytime.optimal else f" (>= {2 * (anytime.lower_bound or 0)})")
                        + f"; first plan {anytime.first_plan_s or 0:.2f} s")
            ours_opt = (f"{2 * len(optimal.plan)} in {t_opt:.2f} s" if optimal.reachable
                        else "budget")
            row = [f"{n}", f"{seed}", ours_any, ours_opt]
            for name in args.peers:
                engine, params = PEERS[name]
                row.append(fmt(*run_peer(engine, params, str(pfile), args.timeout)))
            print(" | ".join(row), flush=True)
            rows.append(row)
    header = ["blocks", "seed", "VeriGraph anytime (default 5 s budget)",
              f"VeriGraph optimal ({args.timeout:g} s budget)", *args.peers]
    write_table("solve", "Solver against Fast Downward and pyperplan (4-op plan length, time)",
                header, rows,
                notes="Random start and goal towers (IPC-2000 style). Lengths are 4-op "
                      "actions: VeriGraph's moves x 2. '(>= B)' is the lower bound the "
                      "anytime solver proved; 'timeout' = no plan within the peer's "
                      f"{args.timeout:g} s limit (own process; killed). Times are wall "
                      "clock, including each peer's PDDL parsing and grounding.")


if __name__ == "__main__":
    main()
