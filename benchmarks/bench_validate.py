"""Validator throughput against unified-planning (and VAL, if given), measured in one run.

* 1,000-object scene x 10,000 valid moves: the core loop, `validate_plan` with its
  per-step report, text parsing, and the whole `verigraph validate --json` process;
* the same plan as PDDL 4-op blocks world (20,000 hand actions): our native validator,
  unified-planning's SequentialPlanValidator (on a slice: it is slow), and VAL's
  `Validate` on the whole file when `--val PATH` names a binary (nothing is built);
* the general STRIPS engine on the same blocks plan and on a 20,000-action typed
  logistics plan, against unified-planning (a slice) and VAL (the whole plan);
* `verigraph validate --batch` on PlanBench-sized items against one validator run per plan;
* long IPC plans in process against VAL's whole process: gripper (IPC 1998) and visitall
  (IPC 2011) walks of 100,000 steps, and the shipped nomystery plans with their large
  initial states (benchmarks/data/ipc);
* every plan of the IPC corpus as given, in process against VAL's process (the ratios
  summarised, the long plans apart);
* every case of the IPC corpus (benchmarks/data/ipc: the Fast Downward plans and their
  mutations, as bench_ipc.py makes them): the slowest in-process check (an invalid
  plan's explanation included), and `--batch` over all of them against VAL run once per
  case;
* CLI start-up on a small plan (blocks world, STRIPS logistics, `verigraph-val`);
* `--validate-only`: `validate_plan` with its per-step report (and the two PDDL engines)
  against VAL's validate-only time on the same plan: VAL's run minus its run on the empty
  plan (same domain and problem), which takes out VAL's start-up and its reading of the
  1,000-block problem; about half a minute, appended to the results file as its own
  section;
* `--grounding`: the STRIPS engine's three ways to run a plan on the same plans (the fast
  run with generated grounding functions, the fast run with the literal-by-literal
  closures only, the step-by-step run only), reports compared byte for byte; appended to
  the results file as its own section (a full run rewrites the file: run it after).

VAL: `--val PATH`, else $VERIGRAPH_VAL, else ~/.cache/verigraph/val/Validate when it
exists (docs/validator.md says how to build it: VAL's parser must be compiled with a
larger YYMAXDEPTH, or it refuses plans of more than about 10,000 steps).

Run: python benchmarks/bench_validate.py [--val /path/to/Validate] [--up-actions 300]
Results: benchmarks/results/validate.md (rates are wall clock; CPU-time rates beside them
because the machine may be shared).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import random
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from blocks_problems import DOMAIN_FILE, problem  # noqa: E402
from common import RESULTS, machine, median_time, write_table  # noqa: E402

from verigraph.actions import MoveAction, parse_plan, validate_plan  # noqa: E402
from verigraph.actions.execution import run_actions  # noqa: E402
from verigraph.graph import Edge, Node, SceneGraph, WorldState  # noqa: E402
from verigraph.pddl import validate_strips_dict  # noqa: E402
from verigraph.pddl.blocksworld import validate_blocks_dict  # noqa: E402
from verigraph.pddl.simulate import cached_strips_problem  # noqa: E402

N_OBJECTS, N_ACTIONS = 1000, 10_000
EXAMPLES = Path(__file__).parent.parent / "examples" / "scenes"
DEFAULT_VAL = Path.home() / ".cache" / "verigraph" / "val" / "Validate"


def find_val(given: str | None) -> str | None:
    path = given or os.environ.get("VERIGRAPH_VAL") or (str(DEFAULT_VAL) if DEFAULT_VAL.exists()
                                                        else None)
    return path


def run_val(val: str, domain: Path, problem_file: Path, plan_file: Path, runs: int = 5
            ) -> tuple[float, float, str]:
    """Median wall seconds and best CPU seconds (as for our in-process rows) of VAL's
    Validate on one plan (its library beside it), and the verdict it printed."""
    env = dict(os.environ, LD_LIBRARY_PATH=str(Path(val).parent))
    times, cpu, out = [], [], ""
    for _ in range(runs):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        done = subprocess.run([val, str(domain), str(problem_file), str(plan_file)],
                              capture_output=True, text=True, check=False, env=env)
        times.append(time.perf_counter() - start)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu.append(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
        out = done.stdout
    verdict = "valid" if "Plan valid" in out else "NOT VALID: " + out.strip()[-80:]
    return sorted(times)[len(times) // 2], min(cpu), verdict


def big_scene(seed: int = 0) -> SceneGraph:
    rng = random.Random(seed)
    ids = [f"b{i}" for i in range(N_OBJECTS - 1)]
    edges, tops = [], []
    for b in ids:
        if tops and rng.random() < 0.5:
            t = tops.pop(rng.randrange(len(tops)))
            edges.append(Edge(source=b, relation="on", target=t))
        else:
            edges.append(Edge(source=b, relation="on", target="table"))
        tops.append(b)
    nodes = [Node(id="table", label="table")] + [Node(id=b, label="block") for b in ids]
    return SceneGraph(nodes=nodes, edges=edges, dictionary="blocks")


def valid_random_walk(scene: SceneGraph, n: int, seed: int = 1) -> list[MoveAction]:
    """n valid moves: a clear block onto another clear block or the table."""
    rng = random.Random(seed)
    state = WorldState.from_graph(scene)
    clear = [o for o in state.objects if o != "table" and state.is_clear(o)]
    plan = []
    for _ in range(n):
        obj = rng.choice(clear)
        options = [c for c in clear if c != obj]
        below = state.support[obj][1]
        target = "table" if below != "table" and rng.random() < 0.3 else rng.choice(options)
        plan.append(MoveAction(object=obj, relation="on", target=target))
        state.set_support(obj, "on", target)
        if target != "table":
            clear.remove(target)
        if below != "table":
            clear.append(below)
    return plan


def as_pddl(scene: SceneGraph, plan: list[MoveAction]) -> tuple[str, list[str]]:
    """The scene as a 4-op problem (goal: where the plan ends) and the plan as hand actions."""
    state = WorldState.from_graph(scene)
    blocks = [o for o in state.objects if o != "table"]
    facts = ["(arm-empty)"] + [f"(clear {b})" for b in blocks if state.is_clear(b)]
    facts += [f"(on-table {b})" if state.support[b][1] == "table"
              else f"(on {b} {state.support[b][1]})" for b in blocks]
    lines = []
    for a in plan:
        below = state.support[a.object][1]
        lines.append(f"(pick-up {a.object})" if below == "table"
                     else f"(unstack {a.object} {below})")
        lines.append(f"(put-down {a.object})" if a.target == "table"
                     else f"(stack {a.object} {a.target})")
        state.set_support(a.object, "on", a.target)
    goal = [f"(on {b} {state.support[b][1]})" for b in blocks if state.support[b][1] != "table"]
    text = (f"(define (problem big)\n(:domain blocksworld-4ops)\n(:objects {' '.join(blocks)})\n"
            f"(:init {' '.join(facts)})\n(:goal (and {' '.join(goal)})))\n")
    return text, lines


CHILD_CPU: dict[str, float] = {}
CHILD_CPU_BEST: dict[str, float] = {}


def process_time(cmd: list[str], runs: int = 3) -> float:
    """Median wall time of a whole process; its median CPU time goes to CHILD_CPU[cmd]."""
    times, cpu = [], []
    for _ in range(runs):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run(cmd, capture_output=True, check=False)
        times.append(time.perf_counter() - start)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu.append(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
    CHILD_CPU[" ".join(cmd)] = sorted(cpu)[len(cpu) // 2]
    CHILD_CPU_BEST[" ".join(cmd)] = min(cpu)
    return sorted(times)[len(times) // 2]


def last_cpu(cmd: list[str]) -> float:
    return CHILD_CPU[" ".join(cmd)]


def up_validate(domain: Path, problem_file: Path, actions: list[str]) -> float:
    """Seconds unified-planning's SequentialPlanValidator takes on `actions` (parse excluded)."""
    import unified_planning as up
    from unified_planning.engines.plan_validator import SequentialPlanValidator
    from unified_planning.io import PDDLReader
    from unified_planning.shortcuts import get_environment

    get_environment().credits_stream = None
    parsed = PDDLReader().parse_problem(str(domain), str(problem_file))
    plan = up.plans.SequentialPlan([
        up.plans.ActionInstance(parsed.action(line.strip("()").split()[0]),
                                [parsed.object(a) for a in line.strip("()").split()[1:]])
        for line in actions])
    start = time.perf_counter()
    SequentialPlanValidator().validate(parsed, plan)
    return time.perf_counter() - start


def cpu_rate(fn, n: int, runs: int = 5, before=None) -> float:  # type: ignore[no-untyped-def]
    return n / _in_process_cpu(fn, runs, before)


def _cpu(fn, before=None) -> float:  # type: ignore[no-untyped-def]
    """CPU seconds of one call; `before` (dropping a cache) runs untimed ahead of it."""
    if before is not None:
        before()
    start = time.process_time()
    fn()
    return time.process_time() - start


def _cold() -> None:
    """Drop the read problems: the next call reads its problem, as VAL does (the one it
    drops is freed here, untimed: VAL's process leaves that to the end)."""
    cached_strips_problem.cache_clear()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--val", help="path to VAL's Validate binary (optional)")
    parser.add_argument("--up-actions", type=int, default=300,
                        help="actions of the big plan given to unified-planning")
    parser.add_argument("--batch-items", type=int, default=2000)
    parser.add_argument("--ipc-only", action="store_true",
                        help="only the IPC rows (printed, no results file)")
    parser.add_argument("--validate-only", action="store_true",
                        help="only validate_plan and the PDDL engines against VAL's "
                             "validate-only time (VAL's run minus its empty-plan run; about "
                             "half a minute), appended to the results file")
    parser.add_argument("--grounding", action="store_true",
                        help="only the STRIPS engine's grounding paths compared (about "
                             "half a minute), appended to the results file")
    args = parser.parse_args()
    work = Path(tempfile.mkdtemp(prefix="bench_validate_"))
    py = [sys.executable, "-m", "verigraph"]
    if args.grounding:
        grounding_rows()
        return
    if args.validate_only:
        validate_only_rows(find_val(args.val), work)
        return
    if args.ipc_only:
        ipc_long_rows(args, work, find_val(args.val), [])
        ipc_plan_rows(args, work, find_val(args.val), [])
        ipc_corpus_rows(args, work, py, find_val(args.val), [])
        return
    scene = big_scene()
    plan = valid_random_walk(scene, N_ACTIONS)
    text = "\n".join(a.text() for a in plan)
    state = WorldState.from_graph(scene)
    rows: list[list[str]] = []

    def row(name: str, seconds: float, n: int, cpu: float | None = None,
            up_rate: float | None = None, val_time: tuple[float, float] | None = None
            ) -> None:
        """One row; `val_time` is VAL's (wall, CPU) seconds on the same plan, and the VAL
        columns are its time over ours (a scene move is two of VAL's hand actions: the
        plan, not the action, is what both validate)."""
        rate = n / seconds
        rows.append([name, f"{seconds * 1000:.1f}", f"{rate:,.0f}",
                     "-" if cpu is None else f"{cpu:,.0f}",
                     "-" if up_rate is None else f"{rate / up_rate:,.1f}x",
                     "-" if val_time is None else f"{val_time[0] / seconds:.2f}x",
                     "-" if val_time is None or cpu is None else
                     f"{val_time[1] / (n / cpu):.2f}x"])
        print(rows[-1], flush=True)

    # PDDL form of the same plan, and the peers on it
    problem_text, hand = as_pddl(scene, plan)
    (work / "big.pddl").write_text(problem_text)
    (work / "big_plan.txt").write_text("\n".join(hand) + "\n")
    domain_text = DOMAIN_FILE.read_text()
    up_seconds = up_validate(DOMAIN_FILE, work / "big.pddl", hand[:args.up_actions])
    up_rate = args.up_actions / up_seconds
    val_time: tuple[float, float] | None = None
    val = find_val(args.val)
    if val:
        val_process, val_seconds_cpu, verdict = run_val(val, DOMAIN_FILE, work / "big.pddl",
                                                        work / "big_plan.txt")
        assert verdict == "valid", verdict  # a refused plan would time nothing
        val_time = (val_process, val_seconds_cpu)
    def core() -> None:
        run = run_actions(state.copy(), plan)
        assert not run.violations and len(run.records) == N_ACTIONS

    def report() -> None:
        assert validate_plan(state, plan)["valid"]

    hand_text = "\n".join(hand)  # the plan file's text, as VAL reads it from its file

    def pddl() -> None:
        assert validate_blocks_dict(domain_text, problem_text, hand_text)["valid"]

    def pddl_strips() -> None:
        assert validate_strips_dict(domain_text, problem_text, hand_text)["valid"]

    measured = []
    for name, fn, n in [("scene: validate + apply (core loop)", core, N_ACTIONS),
                        ("scene: validate_plan with per-step report", report, N_ACTIONS),
                        ("scene: parse 10,000-line text plan",
                         lambda: parse_plan(text), N_ACTIONS),
                        ("PDDL 4-op: native validator with report (20,000 actions)", pddl,
                         len(hand)),
                        ("PDDL 4-op: general STRIPS engine with report (20,000 actions)",
                         pddl_strips, len(hand))]:
        med, _ = median_time(fn, runs=5, before=_cold)
        measured.append((name, med, n, cpu_rate(fn, n, before=_cold)))
    if val and val_time is not None:  # VAL again after our rows: the lower of its timings
        wall, cpu_s, _ = run_val(val, DOMAIN_FILE, work / "big.pddl", work / "big_plan.txt")
        val_time = (min(val_time[0], wall), min(val_time[1], cpu_s))
    for name, med, n, cpu in measured:
        row(name, med, n, cpu, up_rate, val_time)
    rows.append(["unified-planning SequentialPlanValidator (first "
                 f"{args.up_actions} hand actions)", f"{up_seconds * 1000:.1f}",
                 f"{up_rate:,.0f}", "-", "1.0x", "-", "-"])
    (work / "scene.json").write_text(scene.model_dump_json())
    (work / "plan.txt").write_text(text)
    cmd = [*py, "validate", "--scene", str(work / "scene.json"), "--plan",
           str(work / "plan.txt"), "--json"]
    seconds = process_time(cmd)
    row("process: verigraph validate --json, scene, 10,000 moves", seconds, N_ACTIONS,
        N_ACTIONS / last_cpu(cmd), up_rate=up_rate, val_time=val_time)
    cmd = [*py, "validate", "--domain", str(DOMAIN_FILE), "--problem", str(work / "big.pddl"),
           "--plan", str(work / "big_plan.txt"), "--json"]
    seconds = process_time(cmd)
    row("process: verigraph validate --json, PDDL, 20,000 actions", seconds, len(hand),
        len(hand) / last_cpu(cmd), up_rate=up_rate, val_time=val_time)
    if val and val_time is not None:
        rows.append(["process: VAL Validate, PDDL, 20,000 actions (wall: median of 5, the "
                     "lower of two timings; CPU: best of 10)",
                     f"{val_time[0] * 1000:.1f}", f"{len(hand) / val_time[0]:,.0f}",
                     f"{len(hand) / val_time[1]:,.0f}",
                     f"{len(hand) / val_time[0] / up_rate:,.1f}x", "1.00x", "1.00x"])
        (work / "empty_plan.txt").write_text("")
        _, empty_cpu, _ = run_val(val, DOMAIN_FILE, work / "big.pddl", work / "empty_plan.txt",
                                  runs=10)
        only = val_time[1] - empty_cpu  # VAL's validate-only time: its run minus start-up
        ours = {name: n / cpu for name, _, n, cpu in measured}  # CPU seconds per row
        ratios = ", ".join(f"{what} {only / ours[name]:.2f}x" for what, name in (
            ("validate_plan", "scene: validate_plan with per-step report"),
            ("native blocks", "PDDL 4-op: native validator with report (20,000 actions)"),
            ("STRIPS", "PDDL 4-op: general STRIPS engine with report (20,000 actions)")))
        rows.append([f"process: VAL Validate, the empty plan on the same problem (start-up "
                     f"and reading): {empty_cpu * 1000:.1f} ms CPU, so VAL validate-only "
                     f"{only * 1000:.1f} ms CPU; ours against it (CPU): {ratios}",
                     "-", "-", "-", "-", "-", "-"])
    logistics_rows(args, work, val, rows)
    bare_python = process_time([sys.executable, "-c", "pass"], runs=15)
    rows.append(["process: `python -c pass` (the floor for any Python command)",
                 f"{bare_python * 1000:.0f}", "-", "-", "-", "-", "-"])
    bare_cpu = CHILD_CPU_BEST[f"{sys.executable} -c pass"]
    rows[-1][3] = f"{bare_cpu * 1000:.0f} ms"
    sys.path.insert(0, str(Path(__file__).parent.parent / "tests"))
    from pddl_corpus import PDDL_DATA

    (work / "small_log.pddl").write_text(SMALL_LOGISTICS)
    (work / "small_log.plan").write_text(SMALL_LOGISTICS_PLAN)
    blocks = [str(DOMAIN_FILE), str(DOMAIN_FILE.parent / "planbench_instance.pddl"),
              str(DOMAIN_FILE.parent / "planbench_plan.txt")]
    logistics = [str(PDDL_DATA / "logistics_domain.pddl"), str(work / "small_log.pddl"),
                 str(work / "small_log.plan")]
    val_small = None
    if val:
        env = dict(os.environ, LD_LIBRARY_PATH=str(Path(val).parent))
        cpus = []
        for _ in range(15):
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            subprocess.run([val, *blocks], capture_output=True, check=False, env=env)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpus.append(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
        val_small = min(cpus)
    for what, cmd in [
            ("scene", [*py, "validate", "--scene", str(EXAMPLES / "cup_on_book.json"), "--plan",
                       str(EXAMPLES / "cup_on_book_fixed.txt")]),
            ("PDDL blocks world, native engine", [*py, "validate", "--domain", blocks[0],
                                                  "--problem", blocks[1], "--plan", blocks[2]]),
            ("PDDL logistics, STRIPS engine", [*py, "validate", "--domain", logistics[0],
                                               "--problem", logistics[1], "--plan",
                                               logistics[2]]),
            ("verigraph val, blocks world", [*py, "val", *blocks])]:
        startup = process_time(cmd, runs=15)
        ratio = startup / bare_python  # how much the CLI adds to starting Python at all
        best = CHILD_CPU_BEST[" ".join(cmd)]
        rows.append([f"process: start-up + small plan ({what}); best CPU of 15 in the CPU "
                     f"column; {ratio:.1f}x `python -c pass`"
                     + ("" if val_small is None or what == "scene" else
                        f"; VAL's Validate on the blocks plan: {val_small * 1000:.0f} ms CPU"),
                     f"{startup * 1000:.0f}", "-", f"{best * 1000:.0f} ms", "-", "-", "-"])
    batch_rows(args, work, py, rows)
    ipc_long_rows(args, work, val, rows)
    ipc_plan_rows(args, work, val, rows)
    ipc_corpus_rows(args, work, py, val, rows)
    write_table("validate", "Validator throughput against unified-planning and VAL",
                ["what", "median ms", "actions/s (wall)", "actions/s (CPU)",
                 "vs unified-planning", "vs VAL (wall)", "vs VAL (CPU)"], rows,
                notes=f"{N_ACTIONS:,} valid moves on a {N_OBJECTS:,}-object blocks scene "
                      "(as PDDL: 20,000 4-op actions). In-process rows: median of 5 runs "
                      "after a warm-up (wall), best of 5 (CPU); a PDDL row reads its "
                      "problem in every run, as VAL does (the cache is dropped untimed "
                      "before each). Ratios compare the time to validate the same plan "
                      "(wall, and CPU: best of N on both sides, steadier on a shared "
                      "machine): a scene move is two of VAL's hand actions, so the scene "
                      "rows' VAL columns are VAL's time on the plan's PDDL form over ours, "
                      "not actions per second. The VAL ratio of an in-process row compares "
                      "it with VAL's whole process on the same files (VAL has no library "
                      "form; its start-up is a few milliseconds). Load average "
                      f"at the end of the run: {os.getloadavg()[0]:.1f} on "
                      f"{os.cpu_count()} cores. VAL: "
                      + ("measured (Validate built with YYMAXDEPTH=10000000, docs/validator.md)"
                         if val
                         else "not measured (no VAL binary)") + ".")


def logistics_rows(args: argparse.Namespace, work: Path, val: str | None,
                   rows: list[list[str]]) -> None:
    """The general STRIPS engine on a long typed-logistics plan, against the peers."""
    sys.path.insert(0, str(Path(__file__).parent.parent / "tests"))
    from pddl_corpus import PDDL_DATA, logistics_walk

    domain_file = PDDL_DATA / "logistics_typed_domain.pddl"
    problem_text, plan = logistics_walk(50, 500, 20_000, seed=3)
    (work / "log.pddl").write_text(problem_text)
    (work / "log_plan.txt").write_text("\n".join(plan) + "\n")
    domain_text = domain_file.read_text()
    text = "\n".join(plan)
    up_seconds = up_validate(domain_file, work / "log.pddl", plan[:args.up_actions])
    up_rate = args.up_actions / up_seconds
    val_rate = val_cpu = None
    if val:
        val_seconds, val_seconds_cpu, verdict = run_val(val, domain_file, work / "log.pddl",
                                                        work / "log_plan.txt")
        assert verdict == "valid", verdict
        val_rate, val_cpu = len(plan) / val_seconds, len(plan) / val_seconds_cpu

    def strips() -> None:
        assert validate_strips_dict(domain_text, problem_text, text)["valid"]

    med, _ = median_time(strips, runs=5, before=_cold)
    rate = len(plan) / med
    cpu = cpu_rate(strips, len(plan), before=_cold)
    rows.append(["STRIPS logistics (typed, equality, negative precondition, constant): "
                 "general engine with report, 20,000 actions", f"{med * 1000:.1f}",
                 f"{rate:,.0f}", f"{cpu:,.0f}", f"{rate / up_rate:,.1f}x",
                 "-" if val_rate is None else f"{rate / val_rate:.2f}x",
                 "-" if val_cpu is None else f"{cpu / val_cpu:.2f}x"])
    rows.append([f"unified-planning SequentialPlanValidator, logistics (first {args.up_actions} "
                 "actions)", f"{up_seconds * 1000:.1f}", f"{up_rate:,.0f}", "-", "1.0x", "-",
                 "-"])
    if val_rate is not None and val_cpu is not None:
        rows.append(["process: VAL Validate, logistics, 20,000 actions (wall: median of 5)",
                     f"{len(plan) / val_rate * 1000:.1f}", f"{val_rate:,.0f}", f"{val_cpu:,.0f}",
                     f"{val_rate / up_rate:,.1f}x", "1.00x", "1.00x"])


def batch_rows(args: argparse.Namespace, work: Path, py: list[str],
               rows: list[list[str]]) -> None:
    """PlanBench-sized items through --batch vs one validator run per plan."""
    sys.path.insert(0, str(Path(__file__).parent.parent / "tests"))
    from blocksworld_corpus import reference_plan

    items = []
    plans: list[tuple[Path, list[str]]] = []
    for i in range(args.batch_items):
        n = 3 + i % 5
        text, _, _, start, goal = problem(n, i)
        pfile, plan_file = work / f"bp{i}.pddl", work / f"bplan{i}.txt"
        actions = reference_plan(start, goal)
        pfile.write_text(text)
        plan_file.write_text("\n".join(actions))
        plans.append((pfile, actions))
        items.append(json.dumps({"id": i, "domain": str(DOMAIN_FILE), "problem": str(pfile),
                                 "plan": str(plan_file)}))
    (work / "batch.jsonl").write_text("\n".join(items) + "\n")
    cmd = [*py, "validate", "--batch", str(work / "batch.jsonl"), "--no-progress"]
    seconds = process_time(cmd, runs=3)
    rate = args.batch_items / seconds
    k = min(100, args.batch_items)
    up_seconds = sum(up_validate(DOMAIN_FILE, p, a) for p, a in plans[:k])
    up_rate = k / up_seconds
    val_rate = val_cpu = None
    val = find_val(args.val)
    if val:
        env = dict(os.environ, LD_LIBRARY_PATH=str(Path(val).parent))
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        for i in range(k):
            subprocess.run([val, str(DOMAIN_FILE), str(work / f"bp{i}.pddl"),
                            str(work / f"bplan{i}.txt")], capture_output=True, check=False,
                           env=env)
        val_rate = k / (time.perf_counter() - start)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        val_cpu = k / (after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
    cpu = args.batch_items / last_cpu(cmd)
    rows.append([f"process: verigraph validate --batch, {args.batch_items:,} PlanBench-sized "
                 "plans (plans/s)", f"{seconds * 1000:.0f}", f"{rate:,.0f}", f"{cpu:,.0f}",
                 f"{rate / up_rate:,.1f}x", "-" if val_rate is None else f"{rate / val_rate:.1f}x",
                 "-" if val_cpu is None else f"{cpu / val_cpu:.1f}x"])
    rows.append([f"unified-planning, one validation per plan ({k} plans, parse excluded)",
                 f"{up_seconds * 1000:.0f}", f"{up_rate:,.0f}", "-", "1.0x", "-", "-"])
    if val_rate is not None and val_cpu is not None:
        rows.append([f"VAL Validate, one process per plan ({k} plans)", "-", f"{val_rate:,.0f}",
                     f"{val_cpu:,.0f}", "-", "1.0x", "1.0x"])


SMALL_LOGISTICS = """(define (problem one-truck) (:domain logistics)
  (:objects p0 t0 l0 l1 c0)
  (:init (OBJ p0) (TRUCK t0) (LOCATION l0) (LOCATION l1) (CITY c0)
         (in-city l0 c0) (in-city l1 c0) (at t0 l0) (at p0 l0))
  (:goal (and (at p0 l1))))
"""
SMALL_LOGISTICS_PLAN = "(load-truck p0 t0 l0)\n(drive-truck t0 l0 l1 c0)\n(unload-truck p0 t0 l1)\n"
GRIPPER_DOMAIN = Path(__file__).parent / "data" / "gripper" / "domain.pddl"  # IPC 1998
IPC = Path(__file__).parent / "data" / "ipc"


def gripper_walk(balls: int, steps: int, seed: int = 0) -> tuple[str, list[str]]:
    """A valid gripper plan of about `steps` steps: a ball carried to roomb and back,
    again and again, then every ball to roomb (the goal)."""
    rng = random.Random(seed)
    names = [f"ball{i}" for i in range(1, balls + 1)]
    init = ["(room rooma)", "(room roomb)", "(gripper left)", "(gripper right)",
            "(at-robby rooma)", "(free left)", "(free right)",
            *(f"(ball {b})" for b in names), *(f"(at {b} rooma)" for b in names)]
    final: list[str] = []
    for i in range(0, balls, 2):
        pair = list(zip(names[i:i + 2], ("left", "right"), strict=False))
        final += [f"(pick {b} rooma {g})" for b, g in pair] + ["(move rooma roomb)"]
        final += [f"(drop {b} roomb {g})" for b, g in pair] + ["(move roomb rooma)"]
    final.pop()
    plan: list[str] = []
    while len(plan) + 6 + len(final) <= steps:
        b = rng.choice(names)
        plan += [f"(pick {b} rooma left)", "(move rooma roomb)", f"(drop {b} roomb left)",
                 f"(pick {b} roomb left)", "(move roomb rooma)", f"(drop {b} rooma left)"]
    problem_text = (f"(define (problem gripper-walk) (:domain gripper-strips)\n(:objects rooma "
                    f"roomb left right {' '.join(names)})\n(:init {' '.join(init)})\n"
                    f"(:goal (and {' '.join(f'(at {b} roomb)' for b in names)})))\n")
    return problem_text, plan + final


def visitall_walk(n: int, steps: int, seed: int = 0) -> tuple[str, list[str]]:
    """A valid visitall plan on an n x n grid: a sweep that visits every cell (the goal),
    then a random walk, `steps` moves in all (most revisit a cell: `visited` already
    holds, so the step's edit differs from its first time)."""
    def cell(x: int, y: int) -> str:
        return f"loc-x{x}-y{y}"

    def near(x: int, y: int) -> list[tuple[int, int]]:
        return [(x + dx, y + dy) for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1))
                if 0 <= x + dx < n and 0 <= y + dy < n]

    cells = [(x, y) for x in range(n) for y in range(n)]
    init = [f"(at-robot {cell(0, 0)})", f"(visited {cell(0, 0)})"]
    init += [f"(connected {cell(*a)} {cell(*b)})" for a in cells for b in near(*a)]
    path = [(x, y) for x in range(n) for y in (range(n) if x % 2 == 0 else range(n - 1, -1, -1))]
    rng = random.Random(seed)
    while len(path) <= steps:
        path.append(rng.choice(near(*path[-1])))
    plan = [f"(move {cell(*a)} {cell(*b)})" for a, b in zip(path, path[1:], strict=False)]
    problem_text = (f"(define (problem grid-walk) (:domain grid-visit-all)\n(:objects "
                    f"{' '.join(cell(*c) for c in cells)} - place)\n(:init {' '.join(init)})\n"
                    f"(:goal (and {' '.join(f'(visited {cell(*c)})' for c in cells)})))\n")
    return problem_text, plan[:steps]


def _in_process_cpu(fn, runs: int, before=None) -> float:  # type: ignore[no-untyped-def]
    """Best CPU seconds of `runs` calls after a warm-up (`before` untimed ahead of each)."""
    _cpu(fn, before)
    return min(_cpu(fn, before) for _ in range(runs))


def ipc_long_rows(args: argparse.Namespace, work: Path, val: str | None,
                  rows: list[list[str]]) -> None:
    """Long plans of IPC domains: `validate_pddl_dict` in process (the report built)
    against VAL's whole process on the same files; best-of-N CPU on both sides."""
    from verigraph.pddl import validate_pddl_dict

    cases: list[tuple[str, Path, str, list[str]]] = []
    problem_text, plan = gripper_walk(20, 100_000)
    cases.append(("gripper (IPC 1998), 20 balls, 100,000 steps", GRIPPER_DOMAIN,
                  problem_text, plan))
    problem_text, plan = visitall_walk(20, 100_000)
    cases.append(("visitall (IPC 2011), 20 x 20 grid, 100,000 steps",
                  IPC / "visitall" / "domain.pddl", problem_text, plan))
    for inst in sorted((IPC / "nomystery").glob("*.plan"))[-1:]:
        problem_text = inst.with_suffix(".pddl").read_text()
        facts = problem_text.count("(") - 1
        cases.append((f"nomystery (IPC 2011) {inst.stem}, Fast Downward plan, {facts:,} "
                      "parenthesised terms in the problem", IPC / "nomystery" / "domain.pddl",
                      problem_text, [ln for ln in inst.read_text().splitlines()
                                     if ln.startswith("(")]))
    for name, domain_file, problem_text, plan in cases:
        slug = name.split(" ")[0]
        (work / f"{slug}.pddl").write_text(problem_text)
        (work / f"{slug}.plan").write_text("\n".join(plan) + "\n")
        domain_text, text = domain_file.read_text(), "\n".join(plan) + "\n"

        def check(domain_text: str = domain_text, problem_text: str = problem_text,
                  text: str = text) -> None:
            assert validate_pddl_dict(domain_text, problem_text, text)["valid"]

        runs = 5 if len(plan) > 1000 else 20
        med, _ = median_time(check, runs=runs, before=_cold)
        cpu = _in_process_cpu(check, runs, before=_cold)
        val_wall = val_cpu = None
        if val:
            val_wall, val_cpu, verdict = run_val(val, domain_file, work / f"{slug}.pddl",
                                                 work / f"{slug}.plan", runs=runs)
            assert verdict == "valid", verdict
        rows.append([f"IPC long plan, in process: {name}", f"{med * 1000:.1f}",
                     f"{len(plan) / med:,.0f}", f"{len(plan) / cpu:,.0f}", "-",
                     "-" if val_wall is None else f"{val_wall / med:.2f}x",
                     "-" if val_cpu is None else f"{val_cpu / cpu:.2f}x"])
        print(rows[-1], flush=True)
        if val_wall is not None and val_cpu is not None:
            rows.append([f"process: VAL Validate, {slug} (wall: median of {runs})",
                         f"{val_wall * 1000:.1f}", f"{len(plan) / val_wall:,.0f}",
                         f"{len(plan) / val_cpu:,.0f}", "-", "1.00x", "1.00x"])


def ipc_plan_rows(args: argparse.Namespace, work: Path, val: str | None,
                  rows: list[list[str]]) -> None:
    """Every plan of the IPC corpus as the planner gave it: `validate_pddl_dict` in
    process (the problem read again each run, as VAL reads it) against VAL's whole
    process, best CPU of 5 and 3; the ratios summarised, plans of 100 steps or more
    (the long ones) apart, and the lowest named."""
    from bench_ipc import load_cases

    from verigraph.pddl import validate_pddl_dict

    if not val:
        return
    env = dict(os.environ, LD_LIBRARY_PATH=str(Path(val).parent))
    ratios: list[tuple[float, str, int]] = []
    for i, c in enumerate(x for x in load_cases(quick=False) if x.mutation == "original"):
        plan_file = work / f"plan{i}.plan"
        plan_file.write_text(c.plan)
        domain_text, problem_text = c.domain_file.read_text(), c.problem_file.read_text()

        def check(d: str = domain_text, p: str = problem_text, plan: str = c.plan) -> None:
            validate_pddl_dict(d, p, plan)

        ours = _in_process_cpu(check, 5, before=_cold)
        theirs = 1e9
        for _ in range(3):
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            subprocess.run([val, str(c.domain_file), str(c.problem_file), str(plan_file)],
                           capture_output=True, check=False, env=env, timeout=120)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            theirs = min(theirs, after.ru_utime + after.ru_stime - before.ru_utime
                         - before.ru_stime)
        steps = sum(1 for line in c.plan.splitlines() if line.startswith("("))
        ratios.append((theirs / ours, f"{c.domain} {c.instance}", steps))
    for what, group in [("every plan", ratios),
                        ("plans of 100 steps or more", [r for r in ratios if r[2] >= 100])]:
        group = sorted(group)
        median = group[len(group) // 2][0]
        below = [r for r in group if r[0] < 2]
        lowest = ", ".join(f"{name} ({n} steps) {r:.2f}x" for r, name, n in group[:3])
        rows.append([f"IPC plans as given, in process vs VAL's process: {what} ({len(group)} "
                     f"plans); median ratio in the CPU column; under 2x: {len(below)}; "
                     f"lowest: {lowest}", "-", "-", "-", "-", "-", f"{median:.2f}x"])
        print(rows[-1], flush=True)


def ipc_corpus_rows(args: argparse.Namespace, work: Path, py: list[str], val: str | None,
                    rows: list[list[str]]) -> None:
    """Every IPC case (plans and mutations, bench_ipc.py's): the slowest in-process
    check, and `--batch` over all of them against VAL once per case."""
    from bench_ipc import batch_items, load_cases

    from verigraph.errors import VeriGraphError
    from verigraph.pddl import validate_pddl_dict

    cases = load_cases(quick=False)
    texts: dict[Path, str] = {}
    worst: list[tuple[float, str]] = []
    for c in cases:
        domain_text = texts.setdefault(c.domain_file, c.domain_file.read_text())
        problem_text = texts.setdefault(c.problem_file, c.problem_file.read_text())

        def check(d: str = domain_text, p: str = problem_text, plan: str = c.plan) -> None:
            with contextlib.suppress(VeriGraphError):  # a refused domain: timed all the same
                validate_pddl_dict(d, p, plan)

        check()  # the domain text is read once per batch too (cached)
        best = min(_cpu(check, _cold) for _ in range(3))  # each case reads its problem
        worst.append((best, f"{c.domain} {c.instance} {c.mutation}"))
    worst.sort(reverse=True)
    rows.append([f"IPC corpus, in process: slowest of {len(cases)} cases (plans and "
                 f"mutations, explanation included): {worst[0][1]}; next {worst[1][1]} "
                 f"({worst[1][0] * 1000:.1f} ms)", "-", "-", f"{worst[0][0] * 1000:.1f} ms",
                 "-", "-", "-"])
    print(rows[-1], flush=True)
    cmd = [*py, "validate", "--batch", str(batch_items(cases, work)), "--no-progress"]
    seconds = process_time(cmd, runs=3)
    cpu = last_cpu(cmd)
    val_seconds = val_cpu_total = None
    if val:
        env = dict(os.environ, LD_LIBRARY_PATH=str(Path(val).parent))
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        for i, c in enumerate(cases):
            subprocess.run([val, str(c.domain_file), str(c.problem_file),
                            str(work / f"case{i}.plan")], capture_output=True, check=False,
                           env=env, timeout=120)
        val_seconds = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        val_cpu_total = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    n = len(cases)
    rows.append([f"process: verigraph validate --batch, the IPC corpus ({n} cases, "
                 f"{len(texts)} files; plans/s)", f"{seconds * 1000:.0f}", f"{n / seconds:,.0f}",
                 f"{n / cpu:,.0f}", "-",
                 "-" if val_seconds is None else f"{val_seconds / seconds:.1f}x",
                 "-" if val_cpu_total is None else f"{val_cpu_total / cpu:.1f}x"])
    print(rows[-1], flush=True)
    if val_seconds is not None and val_cpu_total is not None:
        rows.append([f"VAL Validate, one process per IPC case ({n} cases)",
                     f"{val_seconds * 1000:.0f}", f"{n / val_seconds:,.0f}",
                     f"{n / val_cpu_total:,.0f}", "-", "1.0x", "1.0x"])



# ---------------------------------------------------------------- grounding paths

GROUNDING_TITLE = "## The STRIPS engine's grounding paths"
VALIDATE_ONLY_TITLE = "## validate_plan against VAL's validate-only time"


def append_section(title: str, lines: list[str]) -> None:
    """Append a section to results/validate.md, replacing an earlier one of that title
    (and keeping the sections after it)."""
    path = RESULTS / "validate.md"
    text = path.read_text("utf-8") if path.exists() else ""
    if title in text:
        start = text.index(title)
        after = text.find("\n## ", start + len(title))
        text = text[:start].rstrip("\n") + "\n" + (text[after:] if after >= 0 else "")
    path.write_text(text.rstrip("\n") + "\n\n" + "\n".join(lines) + "\n", "utf-8")
    print("\n".join(lines))


def validate_only_rows(val: str | None, work: Path, runs: int = 9) -> None:
    """`validate_plan` with its per-step report on the 10,000-move walk (parsed actions,
    and from its text), and the native blocks and STRIPS engines on its PDDL form,
    against VAL's validate-only time on that PDDL form: VAL's best CPU on the plan minus
    its best CPU on the empty plan (same domain and problem: start-up and reading the
    1,000-block problem). Best CPU of `runs` on every side, in one run."""
    from verigraph.agent.evaluation.markdown import table

    if val is None:
        raise SystemExit("--validate-only needs VAL's Validate (--val, $VERIGRAPH_VAL or "
                         f"{DEFAULT_VAL}; docs/validator.md says how to build it)")
    scene = big_scene()
    plan = valid_random_walk(scene, N_ACTIONS)
    text = "\n".join(a.text() for a in plan)
    state = WorldState.from_graph(scene)
    problem_text, hand = as_pddl(scene, plan)
    hand_text = "\n".join(hand)
    domain_text = DOMAIN_FILE.read_text()
    (work / "big.pddl").write_text(problem_text)
    (work / "big_plan.txt").write_text(hand_text + "\n")
    (work / "empty_plan.txt").write_text("")
    ours = [("validate_plan with per-step report (parsed actions)",
             lambda: validate_plan(state, plan)),
            ("validate_plan with per-step report, from the plan's text",
             lambda: validate_plan(state, text)),
            ("validate + apply alone (the core loop, no report)",
             lambda: run_actions(state.copy(), plan)),
            ("native blocks engine with report, the PDDL form (20,000 hand actions)",
             lambda: validate_blocks_dict(domain_text, problem_text, hand_text)),
            ("STRIPS engine with report, the PDDL form (20,000 hand actions)",
             lambda: validate_strips_dict(domain_text, problem_text, hand_text))]
    val_full = run_val(val, DOMAIN_FILE, work / "big.pddl", work / "big_plan.txt", runs)
    val_empty = run_val(val, DOMAIN_FILE, work / "big.pddl", work / "empty_plan.txt", runs)
    cpus = [(name, _in_process_cpu(fn, runs, before=_cold)) for name, fn in ours]
    again = run_val(val, DOMAIN_FILE, work / "big.pddl", work / "big_plan.txt", runs)
    empty_again = run_val(val, DOMAIN_FILE, work / "big.pddl", work / "empty_plan.txt", runs)
    full, empty = min(val_full[1], again[1]), min(val_empty[1], empty_again[1])
    only = full - empty
    rows = [["VAL Validate, whole process", f"{full * 1000:.1f}", "-", "-"],
            ["VAL Validate, the empty plan (start-up, reading domain and problem)",
             f"{empty * 1000:.1f}", "-", "-"],
            ["VAL validate-only (the two above subtracted)", f"{only * 1000:.1f}", "1.00x",
             "-"]]
    rows += [[name, f"{cpu * 1000:.1f}", f"{only / cpu:.2f}x", f"{full / cpu:.2f}x"]
             for name, cpu in cpus]
    load = os.getloadavg()[0]
    append_section(VALIDATE_ONLY_TITLE, [
        VALIDATE_ONLY_TITLE, "", f"Machine: {machine()}  ",
        f"Date: {time.strftime('%Y-%m-%d')}", "",
        *table(["what", "ms CPU", "vs VAL validate-only", "vs VAL's whole process"], rows),
        "", f"`python benchmarks/bench_validate.py --validate-only`. {N_ACTIONS:,} valid "
        f"moves on a {N_OBJECTS:,}-object blocks scene; VAL and the PDDL engines check its "
        "PDDL form (20,000 hand actions, the problem read in every run). Best CPU of "
        f"{runs} on every side (VAL: of two series of {runs}, before and after ours); the "
        "ratios are VAL's time over ours. Load average at the end: "
        f"{load:.1f} on {os.cpu_count()} cores."])


def grounding_rows() -> None:
    """The STRIPS engine's three ways to run a plan, on the same plans: the fast run with
    the generated grounding functions (what the engine does), the fast run with the
    literal-by-literal closures only, and the step-by-step run alone (`simulate(...,
    try_fast=False)`). Each report is compared byte for byte with the engine's; best CPU
    of 5 after a warm-up, the problem read in every run (`_cold`), the domain kept (as a
    batch or a server keeps it, with its generated functions). Appended to the results
    file, replacing an earlier such section."""
    import importlib

    from bench_ipc import load_cases

    from verigraph.agent.evaluation.markdown import table
    from verigraph.errors import VeriGraphError
    from verigraph.graph.bulk import collector_paused, promote_young_objects
    from verigraph.pddl.plans import parse_strips_plan

    simulate = importlib.import_module("verigraph.pddl.simulate")
    generated = simulate.Generated

    class Closures:  # what `_Compiled` gets instead of a generated function: none
        function = None

        def __init__(self, *args: object) -> None:
            pass

        def counted(self) -> None:
            return None

    def fast(d: str, p: str, t: str) -> dict:  # type: ignore[type-arg]
        return simulate.validate_strips_dict(d, p, t)

    def stepwise(d: str, p: str, t: str) -> dict:  # type: ignore[type-arg]
        # with the collector handled as validate_strips_dict handles it for every run
        with collector_paused(t.count("\n") + 1 + p.count("(")):
            domain = simulate.cached_strips_domain(d)
            problem = simulate.cached_strips_problem(d, p)
            report = simulate.simulate(domain, problem, parse_strips_plan(t, domain),
                                       try_fast=False)
            promote_young_objects()
        return report

    scene = big_scene()
    problem_text, hand = as_pddl(scene, valid_random_walk(scene, N_ACTIONS))
    plans = [("blocks, 1,000 blocks, 20,000 hand actions (almost every step a new ground "
              "action)", DOMAIN_FILE.read_text(), problem_text, "\n".join(hand))]
    problem_text, walk = gripper_walk(20, 20_000)
    plans.append(("gripper (IPC 1998), 20 balls, 20,000 steps", GRIPPER_DOMAIN.read_text(),
                  problem_text, "\n".join(walk) + "\n"))
    problem_text, walk = visitall_walk(20, 20_000)
    plans.append(("visitall (IPC 2011), 20 x 20 grid, 20,000 steps",
                  (IPC / "visitall" / "domain.pddl").read_text(), problem_text,
                  "\n".join(walk) + "\n"))
    problem_text, walk = gripper_walk(20, 20_000)
    plans.append(("gripper, 20,000 steps, then a failing step (explained)",
                  GRIPPER_DOMAIN.read_text(), problem_text,
                  "\n".join(walk + [walk[0]] * 2) + "\n"))
    corpus = [(c.domain_file.read_text(), c.problem_file.read_text(), c.plan)
              for c in load_cases(quick=True)]
    paths = [("fast run, generated grounding (the engine)", fast, generated),
             ("fast run, closures only", fast, Closures),
             ("step-by-step run only", stepwise, generated)]
    rows = []
    for name, d, p, t in plans:
        base = ""
        for label, run, kind in paths:
            simulate.Generated = kind
            simulate.cached_strips_domain.cache_clear()  # no function of another path
            report = json.dumps(run(d, p, t), sort_keys=True, default=list)
            base = base or report
            cpu = _in_process_cpu(lambda run=run, d=d, p=p, t=t: run(d, p, t), 5, before=_cold)
            steps = t.count("\n") + 1
            rows.append([name, label, f"{cpu * 1000:.1f}", f"{steps / cpu:,.0f}",
                         "yes" if report == base else "NO"])
            print(rows[-1], flush=True)
    base_reports: list[str] = []
    for label, run, kind in paths:
        simulate.Generated = kind
        simulate.cached_strips_domain.cache_clear()
        reports, total = [], 0.0
        for d, p, t in corpus:
            _cold()
            start = time.process_time()
            try:
                reports.append(json.dumps(run(d, p, t), sort_keys=True, default=list))
            except VeriGraphError as exc:
                reports.append(json.dumps(exc.to_dict(), default=str))
            total += time.process_time() - start
        base_reports = base_reports or reports
        rows.append([f"IPC corpus, {len(corpus)} cases (quick: each domain's first plan "
                     "and 4 mutations), one pass", label, f"{total * 1000:.1f}", "-",
                     "yes" if reports == base_reports else "NO"])
        print(rows[-1], flush=True)
    simulate.Generated = generated
    simulate.cached_strips_domain.cache_clear()
    load = os.getloadavg()[0]
    lines = [GROUNDING_TITLE, "", f"Machine: {machine()}  ",
             f"Date: {time.strftime('%Y-%m-%d')}", "",
             *table(["plan", "path", "ms CPU", "steps/s (CPU)", "same report"], rows), "",
             "`python benchmarks/bench_validate.py --grounding`. Best CPU of 5 after a "
             "warm-up; the problem read in every run, the domain (and its generated "
             "grounding functions) kept. The step-by-step run gives the same reports but is "
             "needed only where the fast run cannot go (all_errors, derived predicates, the "
             "explanation after a failing step); the generated functions pay where a plan "
             f"grounds many distinct actions. Load average at the end: {load:.1f} on "
             f"{os.cpu_count()} cores."]
    append_section(GROUNDING_TITLE, lines)


if __name__ == "__main__":
    main()
