"""Agreement and speed of the PDDL validator against VAL on classical IPC domains.

The corpus is shipped in benchmarks/data/ipc/<domain>/ (see its README.md): for each
instance `NAME.pddl`, its domain (`domain.pddl`, or `NAME.domain.pddl` where the IPC gave
one domain file per instance) and `NAME.plan`, a Fast Downward (lama-first) plan. The
benchmark runs from these files alone; `--prepare SRC` rebuilds them from a checkout of
aibasel/downward-benchmarks (and `--classical-domains SRC` from one of
AI-Planning/classical-domains, for the one domain that collection lacks); it runs Fast
Downward, so it needs the planner; the agreement run does not.

Each plan is checked as given and in nine mutations (dropped, swapped, duplicated and
truncated steps, a replaced argument, a misspelt action name, a wrong arity, an
undeclared object, the plan without its last step), deterministic per plan. For every
case VeriGraph's verdict (`validate_pddl_dict`, in process) is compared with VAL's
(`Validate -v domain problem plan`: "Plan valid" is valid; "Plan failed", "Goal not
satisfied", "Bad plan description", and the plan refused before it runs ("Bad operator
in plan", a type-checking error on a plan step, exit 255) are invalid; any other end is
"VAL error" and death by a signal is "VAL crashed": outcomes of their own, no
disagreement). A VeriGraph refusal of the domain (an unsupported feature) is counted by
the requirement it names. A structured VeriGraph error on the plan (an unknown action, a
wrong arity) is an invalid verdict, as VAL's "Bad plan description!" is. VAL is given a
renamed copy of a domain whose legal names its lexer misreads (VAL_RENAMES).

Speed, per domain: VeriGraph in process per plan (one run; both engines' code is loaded
by one untimed check first, and each domain is read again) against VAL's whole process
per plan (VAL has no library), and `verigraph validate --batch` over all cases against
VAL once per plan. A full run also rewrites data/ipc/val_verdicts.json (VAL's verdicts,
for tests/pddl/test_pddl_ipc_corpus.py). Every disagreement is listed with a
judgement (JUDGEMENTS below, written by reading the plan and the domain); one without a
judgement is marked so.

Run: python benchmarks/bench_ipc.py --val /path/to/Validate [--quick] [--out FILE]
Results: benchmarks/results/ipc.md
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

from verigraph.errors import VeriGraphError
from verigraph.pddl import validate_pddl_dict

DATA = Path(__file__).parent / "data" / "ipc"
OUT = Path(__file__).parent / "results" / "ipc.md"
ROOT = Path(__file__).parent.parent
DEFAULT_VAL = Path.home() / ".cache" / "verigraph" / "val" / "Validate"

# name in benchmarks/data/ipc -> (directory in downward-benchmarks, competition)
DOMAINS: dict[str, tuple[str, str]] = {
    "blocks": ("blocks", "IPC 2000"),
    "logistics00": ("logistics00", "IPC 2000"),
    "miconic": ("miconic", "IPC 2000"),
    "miconic-simpleadl": ("miconic-simpleadl", "IPC 2000"),
    "freecell": ("freecell", "IPC 2000"),
    "depot": ("depot", "IPC 2002"),
    "driverlog": ("driverlog", "IPC 2002"),
    "zenotravel": ("zenotravel", "IPC 2002"),
    "rovers": ("rovers", "IPC 2002"),
    "satellite": ("satellite", "IPC 2002"),
    "airport": ("airport", "IPC 2004"),
    "pipesworld-notankage": ("pipesworld-notankage", "IPC 2004"),
    "psr-small": ("psr-small", "IPC 2004"),
    "openstacks-strips": ("openstacks-strips", "IPC 2006"),
    "tpp": ("tpp", "IPC 2006"),
    "storage": ("storage", "IPC 2006"),
    "trucks-strips": ("trucks-strips", "IPC 2006"),
    "elevators": ("elevators-sat08-strips", "IPC 2008"),
    "sokoban": ("sokoban-sat08-strips", "IPC 2008"),
    "pegsol": ("pegsol-08-strips", "IPC 2008"),
    "scanalyzer": ("scanalyzer-08-strips", "IPC 2008"),
    "transport": ("transport-sat08-strips", "IPC 2008"),
    "woodworking": ("woodworking-sat08-strips", "IPC 2008"),
    "parcprinter": ("parcprinter-08-strips", "IPC 2008"),
    "nomystery": ("nomystery-sat11-strips", "IPC 2011"),
    "visitall": ("visitall-sat11-strips", "IPC 2011"),
    "barman": ("barman-sat11-strips", "IPC 2011"),
    "floortile": ("floortile-sat11-strips", "IPC 2011"),
    "parking": ("parking-sat11-strips", "IPC 2011"),
    "tidybot": ("tidybot-sat11-strips", "IPC 2011"),
    "childsnack": ("childsnack-sat14-strips", "IPC 2014"),
    "hiking": ("hiking-sat14-strips", "IPC 2014"),
    "tetris": ("tetris-sat14-strips", "IPC 2014"),
    "ged": ("ged-sat14-strips", "IPC 2014"),
    "miconic-fulladl": ("miconic-fulladl", "IPC 2000"),
    "pipesworld-tankage": ("pipesworld-tankage", "IPC 2004"),
    "airport-adl": ("airport-adl", "IPC 2004"),
    "psr-middle": ("psr-middle", "IPC 2004"),
    "psr-large": ("psr-large", "IPC 2004"),
    "optical-telegraphs": ("optical-telegraphs", "IPC 2004"),
    "philosophers": ("philosophers", "IPC 2004"),
    "openstacks": ("openstacks-sat08-strips", "IPC 2008"),
    "openstacks-adl": ("openstacks-sat08-adl", "IPC 2008"),
    "cavediving": ("cavediving-14-adl", "IPC 2014"),
    "citycar": ("citycar-sat14-adl", "IPC 2014"),
    "maintenance": ("maintenance-sat14-adl", "IPC 2014"),
    "thoughtful": ("thoughtful-sat14-strips", "IPC 2014"),
    "agricola": ("agricola-sat18-strips", "IPC 2018"),
    "caldera": ("caldera-sat18-adl", "IPC 2018"),
    "caldera-split": ("caldera-split-sat18-adl", "IPC 2018"),
    "data-network": ("data-network-sat18-strips", "IPC 2018"),
    "flashfill": ("flashfill-sat18-adl", "IPC 2018"),
    "nurikabe": ("nurikabe-sat18-adl", "IPC 2018"),
    "organic-synthesis": ("organic-synthesis-sat18-strips", "IPC 2018"),
    "organic-synthesis-split": ("organic-synthesis-split-sat18-strips", "IPC 2018"),
    "petri-net-alignment": ("petri-net-alignment-opt18-strips", "IPC 2018"),
    "settlers": ("settlers-sat18-adl", "IPC 2018"),
    "snake": ("snake-sat18-strips", "IPC 2018"),
    "spider": ("spider-sat18-strips", "IPC 2018"),
    "termes": ("termes-sat18-strips", "IPC 2018"),
    "folding": ("folding-sat23-adl", "IPC 2023"),
    # the optimal track's folder: the same domain file, smaller problems (lama-first
    # solved none of the satisficing track's smallest ones here, see PLANNING)
    "labyrinth": ("labyrinth-opt23-adl", "IPC 2023"),
    "quantum-layout": ("quantum-layout-sat23-strips", "IPC 2023"),
    "recharging-robots": ("recharging-robots-sat23-adl", "IPC 2023"),
    "ricochet-robots": ("ricochet-robots-sat23-adl", "IPC 2023"),
    "rubiks-cube": ("rubiks-cube-sat23-adl", "IPC 2023"),
    "slitherlink": ("slitherlink-sat23-adl", "IPC 2023"),
    # not in downward-benchmarks: the folder of AI-Planning/classical-domains (--prepare
    # with --classical-domains), the IPC 2008 files under their original names
    "cybersec": ("classical/cybersec", "IPC 2008"),
}
# the domains whose folder is in AI-Planning/classical-domains, not downward-benchmarks
FROM_CLASSICAL_DOMAINS = {"cybersec"}


@dataclass(frozen=True)
class Planning:
    """How --prepare plans one domain other than by default (the smallest problems by
    file size, lama-first, --time-limit), and why; an entry with only `why` gives the
    reason for the domain's folder in DOMAINS."""

    instances: tuple[str, ...] = ()     # these problems (stems), not the smallest ones
    time_limit: int | None = None       # planner seconds per instance
    translate_options: tuple[str, ...] = ()   # Fast Downward --translate-options
    why: str = ""


PLANNING: dict[str, Planning] = {
    "organic-synthesis": Planning(
        instances=("p06", "p07"), time_limit=300,
        why="the only two problems with the small (12 KB) per-instance domain (about "
            "20 s and 90 s); on the others, with their 71 KB domain, Fast Downward's "
            "translator runs out of 6 GB (the smallest, p01, after 80 s)"),
    "labyrinth": Planning(
        time_limit=300,
        why="the optimal track's p01 (3x3 cards) and p02 (4x4) take 3 s and 35 s; the "
            "satisficing track's problems have 5x5 cards or more, and for its p04 and p01 "
            "(the smallest file, and the one scrambled by a single rotation) lama-first "
            "found no plan in 400 s and 580 s, nor did greedy search with type-based "
            "exploration (p01, 590 s) or blind A* (p04, out of 8 GB): 1.5 million ground "
            "actions, and the FF heuristic stays on a plateau"),
    "ricochet-robots": Planning(
        time_limit=300,
        why="p01 takes about 135 s, p07 about 65 s"),
    "slitherlink": Planning(
        time_limit=120, translate_options=("--invariant-generation-max-candidates", "0"),
        why="without mutex groups the negated goal literals stay single facts; with them "
            "the translator multiplies the goal out into exponentially many conjunctions "
            "(out of 6 GB on a 5x3 grid)"),
    "petri-net-alignment": Planning(
        why="the collection has only the optimal track's folder (the domain's only track)"),
    "cybersec": Planning(
        instances=("p09",), time_limit=120,
        why="the smallest domain file (336 KB: each problem has its own grounded domain, "
            "whose translation takes about 30 s); p24 is the same problem and domain with "
            "other action costs, the others' domains are 0.6 MB and larger"),
}

# Classical IPC 2008-2023 domains with no case in the corpus, and why (see the README).
NOT_IN_CORPUS: dict[str, tuple[str, str]] = {}
# Tracks outside classical planning: their domains declare :durative-actions or
# :numeric-fluents, which VeriGraph refuses by name; downward-benchmarks has none of them.
OTHER_TRACKS = ("temporal tracks of IPC 2008, 2011, 2014 and 2018 (`:durative-actions`: "
                "`unsupported requirement :durative-actions`)",
                "numeric track of IPC 2023 (`:numeric-fluents` beyond action costs: "
                "`unsupported requirement :numeric-fluents`)")

# (domain, instance, mutation) -> who is right and why, written after reading the case.
JUDGEMENTS: dict[tuple[str, str, str], str] = {}
# the judged disagreements where VAL is wrong: the verdict the corpus test expects is
# VeriGraph's there (see write_verdicts)
VAL_WRONG: set[tuple[str, str, str]] = set()
VERDICTS = DATA / "val_verdicts.json"
# VAL's lexer takes some legal names for keywords and then refuses the whole domain
# ("Problem in domain definition!"); VAL is given a copy with the name changed (a
# variable renamed throughout its action: the same domain), and the report says so.
VAL_RENAMES: dict[str, list[tuple[str, str]]] = {
    "data-network": [("?after", "?post")],  # `after` is a PDDL 3 keyword for VAL's lexer
}

MUTATIONS = ("original", "drop", "swap", "duplicate", "truncate", "replace-arg",
             "misspelt-name", "wrong-arity", "undeclared-object", "no-last-step")


# ---------------------------------------------------------------- corpus preparation

def find_val(given: str | None) -> str | None:
    """VAL's Validate: --val, else $VERIGRAPH_VAL, else the cache bench_validate uses."""
    return given or os.environ.get("VERIGRAPH_VAL") or (
        str(DEFAULT_VAL) if DEFAULT_VAL.exists() else None)


def _domain_for(src: Path, problem: Path) -> Path | None:
    """The domain file of one IPC problem: a per-instance one if the folder has them."""
    stem = problem.stem
    for cand in (f"{stem}-domain.pddl", f"domain_{problem.name}", f"domain-{problem.name}",
                 f"{stem.split('-')[0]}-domain.pddl", "domain.pddl"):
        if (src / cand).exists():
            return src / cand
    return None


def _is_problem(path: Path) -> bool:
    return path.suffix == ".pddl" and "domain" not in path.name


def prepare(src_root: Path, per_domain: int, time_limit: int, fd: str,
            only: set[str] | None = None, tries: int = 6,
            classical_root: Path | None = None) -> None:
    """Copy the smallest problems of each domain (by file size; up to `tries` of them
    are tried when the planner fails on some), or those PLANNING names, and plan them
    with Fast Downward."""
    for name, (folder, _) in DOMAINS.items():
        if only and name not in only:
            continue
        root = classical_root if name in FROM_CLASSICAL_DOMAINS else src_root
        if root is None:
            print(f"{name}: needs --classical-domains", file=sys.stderr)
            continue
        src = root / folder
        if not src.is_dir():
            print(f"{name}: no folder {src}", file=sys.stderr)
            continue
        how = PLANNING.get(name, Planning())
        limit = how.time_limit or time_limit
        problems = sorted((p for p in src.iterdir() if _is_problem(p)),
                          key=lambda p: (p.stat().st_size, p.name))
        if how.instances:
            problems = [src / f"{inst}.pddl" for inst in how.instances]
        dest = DATA / name
        dest.mkdir(parents=True, exist_ok=True)
        done = 0
        for prob in problems[:max(tries, per_domain)]:
            if done == per_domain:
                break
            dom = _domain_for(src, prob)
            if dom is None:
                continue
            inst = prob.stem
            translate = ["--translate-options", *how.translate_options] \
                if how.translate_options else []
            with tempfile.TemporaryDirectory() as tmp:
                plan_file = Path(tmp) / "plan"
                subprocess.run([sys.executable, fd, "--plan-file", str(plan_file),
                                "--overall-time-limit", f"{limit}s", "--alias",
                                "lama-first", str(dom), str(prob), *translate],
                               capture_output=True, cwd=tmp, check=False)
                if not plan_file.exists():
                    print(f"{name}/{inst}: no plan in {limit}s", file=sys.stderr)
                    continue
                shutil.copy(prob, dest / f"{inst}.pddl")
                shared = dom.name == "domain.pddl"
                shutil.copy(dom, dest / ("domain.pddl" if shared else f"{inst}.domain.pddl"))
                shutil.copy(plan_file, dest / f"{inst}.plan")
                done += 1
                print(f"{name}/{inst}: planned", file=sys.stderr)
        _share_domain(dest)


def _share_domain(dest: Path) -> None:
    """Per-instance domain files that are all the same become one domain.pddl."""
    own = sorted(dest.glob("*.domain.pddl"))
    if len(own) > 1 and len({p.read_bytes() for p in own}) == 1:
        own[0].rename(dest / "domain.pddl")
        for p in own[1:]:
            p.unlink()


# ---------------------------------------------------------------- cases

@dataclass
class Case:
    domain: str
    instance: str
    mutation: str
    domain_file: Path
    problem_file: Path
    plan: str
    vg: str = ""            # valid | invalid | refused
    vg_detail: str = ""
    vg_seconds: float = 0.0
    val: str = ""           # valid | invalid | crashed | error
    val_detail: str = ""
    val_seconds: float = 0.0
    extra: dict[str, str] = field(default_factory=dict)


def _steps(plan_text: str) -> list[str]:
    return [ln.strip() for ln in plan_text.splitlines()
            if ln.strip() and not ln.strip().startswith(";")]


def _objects(problem_text: str, domain_text: str) -> list[str]:
    """Names of the problem's objects and the domain's constants (for replace-arg)."""
    names: list[str] = []
    for text, key in ((problem_text, ":objects"), (domain_text, ":constants")):
        m = re.search(r"\(\s*" + key + r"\b(.*?)\)", text, re.S | re.I)
        if m:
            body = re.sub(r";[^\n]*", "", m.group(1))
            toks = body.split()
            skip = False
            for t in toks:
                if skip:
                    skip = False
                    continue
                if t == "-":
                    skip = True
                    continue
                names.append(t.lower())
    return names


def mutate(steps: list[str], objects: list[str], kind: str, rng: random.Random
           ) -> list[str] | None:
    """One mutation of a plan's steps; None when the plan is too short for it."""
    s = list(steps)
    n = len(s)
    parts = [x.strip("()").split() for x in s]
    if kind == "original":
        return s
    if kind == "drop":
        if n < 2:
            return None
        del s[rng.randrange(n - 1)]   # not the last step (no-last-step is its own case)
        return s
    if kind == "swap":
        pairs = [i for i in range(n - 1) if s[i] != s[i + 1]]
        if not pairs:
            return None
        i = rng.choice(pairs)
        s[i], s[i + 1] = s[i + 1], s[i]
        return s
    if kind == "duplicate":
        if not s:
            return None
        i = rng.randrange(n)
        s.insert(i, s[i])
        return s
    if kind == "truncate":
        return s[: n // 2] if n >= 2 else None
    if kind == "no-last-step":
        return s[:-1] if n >= 1 else None
    with_args = [i for i in range(n) if len(parts[i]) > 1]
    if not with_args and kind == "misspelt-name":
        with_args = list(range(n))   # a grounded domain: no action takes an argument
    if not with_args:
        return None
    i = rng.choice(with_args)
    name, args = parts[i][0], parts[i][1:]
    if kind == "replace-arg":
        j = rng.randrange(len(args))
        others = [o for o in objects if o != args[j].lower()]
        if not others:
            return None
        args[j] = rng.choice(others)
    elif kind == "misspelt-name":
        name = name[:-1] + ("x" if name[-1] != "x" else "y")
    elif kind == "wrong-arity":
        args = args[:-1]
    elif kind == "undeclared-object":
        args[rng.randrange(len(args))] = "undeclared-object-7"
    s[i] = "(" + " ".join([name, *args]) + ")"
    return s


def load_cases(quick: bool) -> list[Case]:
    cases = []
    for name in sorted(p.name for p in DATA.iterdir() if p.is_dir()):
        folder = DATA / name
        plans = sorted(folder.glob("*.plan"))
        if quick:
            plans = plans[:1]
        for plan_file in plans:
            inst = plan_file.stem
            dom = folder / f"{inst}.domain.pddl"
            dom = dom if dom.exists() else folder / "domain.pddl"
            prob = folder / f"{inst}.pddl"
            steps = _steps(plan_file.read_text())
            objects = _objects(prob.read_text(), dom.read_text())
            for kind in (MUTATIONS[:4] if quick else MUTATIONS):
                rng = random.Random(f"{name}/{inst}/{kind}")
                mutated = mutate(steps, objects, kind, rng)
                if mutated is not None:
                    cases.append(Case(name, inst, kind, dom, prob, "\n".join(mutated) + "\n"))
    return cases


# ---------------------------------------------------------------- verdicts

def verigraph_verdict(case: Case, domain_text: str, problem_text: str) -> None:
    start = time.perf_counter()
    try:
        report = validate_pddl_dict(domain_text, problem_text, case.plan)
    except VeriGraphError as exc:
        case.vg_seconds = time.perf_counter() - start
        kind = type(exc).__name__
        if kind in ("UnsupportedRequirementError", "UnsupportedDomainError") or \
                "unsupported" in exc.message.lower():
            case.vg, case.vg_detail = "refused", f"{exc.value}: {exc.message[:160]}"
        elif kind in ("PddlInputError", "PddlSyntaxError") and exc.field in (
                "domain", "problem") or str(exc.field).startswith(("domain", "problem")):
            case.vg, case.vg_detail = "refused", f"{kind} {exc.field}: {exc.message[:160]}"
        else:
            case.vg, case.vg_detail = "invalid", f"{kind}: {exc.message[:160]}"
        return
    case.vg_seconds = time.perf_counter() - start
    case.vg = "valid" if report.get("valid") else "invalid"
    if not report.get("valid"):
        viol = report.get("violations") or []
        if viol:
            v = viol[0]
            case.vg_detail = f"step {v.get('step')}: {str(v.get('message'))[:200]}"
        else:
            case.vg_detail = "goal: " + json.dumps(report.get("goal_diff"))[:200]


def warm_up(cases: list[Case]) -> None:
    """Load both engines' code before timing (a one-off import, not a per-plan cost):
    one untimed check of a blocks-world case and of another, then the domain caches are
    emptied so the timed runs read each domain again."""
    from verigraph.pddl.blocksworld.domain import cached_domain
    from verigraph.pddl.simulate import cached_strips_domain

    for want_blocks in (True, False):
        for c in cases:
            if (c.domain == "blocks") == want_blocks:
                verigraph_verdict(Case(**{**c.__dict__, "extra": {}}),
                                  c.domain_file.read_text(), c.problem_file.read_text())
                break
    cached_domain.cache_clear()
    cached_strips_domain.cache_clear()


def val_verdict(case: Case, val: str, tmp: Path) -> None:
    plan_file = tmp / "plan.txt"
    plan_file.write_text(case.plan)
    domain_file = case.domain_file
    if case.domain in VAL_RENAMES:
        text = domain_file.read_text()
        for old, new in VAL_RENAMES[case.domain]:
            text = re.sub(re.escape(old) + r"(?![\w-])", new, text)
        domain_file = tmp / "renamed-domain.pddl"
        domain_file.write_text(text)
    env = dict(os.environ, LD_LIBRARY_PATH=str(Path(val).parent))
    start = time.perf_counter()
    try:
        done = subprocess.run([val, "-v", str(domain_file), str(case.problem_file),
                               str(plan_file)], capture_output=True, text=True,
                              errors="replace", check=False, env=env, timeout=60)
    except subprocess.TimeoutExpired:
        case.val_seconds = time.perf_counter() - start
        case.val, case.val_detail = "crashed", "timeout 60 s"
        return
    case.val_seconds = time.perf_counter() - start
    out = done.stdout + done.stderr
    if done.returncode < 0:
        case.val, case.val_detail = "crashed", f"signal {-done.returncode}"
        return
    key = [ln.strip() for ln in out.splitlines()
           if re.search(r"Plan valid|Plan failed|Goal not satisfied|Bad plan|Plan invalid|"
                        r"Error|Unsatisfied precondition|Plan Repair", ln)]
    case.val_detail = f"exit {done.returncode}: " + " | ".join(key[:3])[:240]
    if "Plan valid" in out and "Plan failed" not in out:
        case.val = "valid"
    elif re.search(r"Plan failed|Goal not satisfied|Bad plan|Plan invalid", out):
        case.val = "invalid"
    elif re.search(r"Bad operator in plan|Checking plan:.*Error in type-checking", out, re.S):
        # VAL refuses the plan before running it (exit 255): an unknown action name, or
        # an object the problem does not declare. The plan is not valid for VAL.
        case.val = "invalid"
        case.val_detail += " (plan refused before execution)"
    else:
        case.val = "error"
        case.val_detail += " | " + out.strip()[-200:].replace("\n", " ")


def batch_items(cases: list[Case], tmp: Path) -> Path:
    """The cases as a `verigraph validate --batch` file in `tmp` (item i's plan in
    `tmp/case{i}.plan`, id i)."""
    lines = []
    for i, c in enumerate(cases):
        plan = tmp / f"case{i}.plan"
        plan.write_text(c.plan)
        lines.append(json.dumps({"id": i, "domain": str(c.domain_file),
                                 "problem": str(c.problem_file), "plan": str(plan)}))
    items = tmp / "items.jsonl"
    items.write_text("\n".join(lines) + "\n")
    return items


def batch_time(cases: list[Case], tmp: Path) -> tuple[float, int, int]:
    """Whole-process `verigraph validate --batch` over all cases: seconds, items, lines."""
    items = batch_items(cases, tmp)
    exe = Path(sys.executable).parent / "verigraph"
    cmd = [str(exe) if exe.exists() else "verigraph", "validate", "--batch", str(items),
           "--no-progress"]
    start = time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True, check=False)
    seconds = time.perf_counter() - start
    out = [ln for ln in done.stdout.splitlines() if ln.strip()]
    # the batch must give the library's verdicts
    for ln in out:
        rec = json.loads(ln)
        if not isinstance(rec.get("id"), int):
            continue
        c = cases[rec["id"]]
        got = "valid" if rec.get("valid") else ("error" if rec.get("ok") is False
                                                else "invalid")
        c.extra["batch"] = got
    return seconds, len(cases), len(out)


# ---------------------------------------------------------------- report

def machine() -> str:
    model = "unknown"
    try:
        for ln in Path("/proc/cpuinfo").read_text().splitlines():
            if ln.startswith("model name"):
                model = ln.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    load = " ".join(f"{x:.2f}" for x in os.getloadavg())
    return (f"nproc {os.cpu_count()}, {model}, load average {load}, "
            f"Python {platform.python_version()}")


def agree(c: Case) -> bool:
    return c.vg == c.val


def render(cases: list[Case], batch: tuple[float, int, int] | None, val: str,
           machine_before: str, machine_after: str) -> str:
    home = str(Path.home())
    shown = "~" + val[len(home):] if val.startswith(home + os.sep) else val
    out = ["# VeriGraph's PDDL validator against VAL on IPC domains", "",
           "Generated by `benchmarks/bench_ipc.py` (see its docstring for the method). "
           "Corpus: `benchmarks/data/ipc/` (README.md there names the source). "
           f"VAL: `{shown}` (KCL-Planning/VAL built from source with "
           "`-DYYMAXDEPTH=10000000`, as `docs/validator.md` gives it).", "",
           f"Machine at start: {machine_before}.  ",
           f"Machine at end: {machine_after}.", "",
           "## Agreement", "",
           "| domain | IPC | plans | cases | agree | disagree | VeriGraph refused | "
           "VAL crashed | VAL error |",
           "|---|---|---|---|---|---|---|---|---|"]
    tot: Counter[str] = Counter()
    by_domain: dict[str, list[Case]] = {}
    for c in cases:
        by_domain.setdefault(c.domain, []).append(c)
    for name, cs in by_domain.items():
        refused = [c for c in cs if c.vg == "refused"]
        crashed = [c for c in cs if c.val == "crashed" and c.vg != "refused"]
        error = [c for c in cs if c.val == "error" and c.vg != "refused"]
        judged = [c for c in cs if c.vg != "refused" and c.val in ("valid", "invalid")]
        ag = sum(agree(c) for c in judged)
        reasons = sorted({c.vg_detail.split(":")[0] for c in refused})
        row = Counter(cases=len(cs), agree=ag, disagree=len(judged) - ag,
                      refused=len(refused), crashed=len(crashed), error=len(error),
                      plans=len({c.instance for c in cs}))
        tot.update(row)
        out.append(f"| {name} | {DOMAINS.get(name, ('', '?'))[1]} | {row['plans']} | "
                   f"{row['cases']} | {ag} | {row['disagree']} | {len(refused)}"
                   f"{' (' + ', '.join(reasons) + ')' if reasons else ''} | "
                   f"{len(crashed)} | {len(error)} |")
    out.append(f"| **all** | | {tot['plans']} | {tot['cases']} | {tot['agree']} | "
               f"{tot['disagree']} | {tot['refused']} | {tot['crashed']} | {tot['error']} |")
    vg_counts = Counter(c.vg for c in cases)
    val_counts = Counter(c.val for c in cases)
    out += ["", f"Verdicts: VeriGraph {dict(vg_counts)}; VAL {dict(val_counts)}.", ""]
    if batch is not None:
        mism = [c for c in cases if c.extra.get("batch") not in (None, c.vg)
                and not (c.vg == "refused" and c.extra.get("batch") == "error")]
        out.append(f"`--batch` gave the library's verdict on {len(cases) - len(mism)} of "
                   f"{len(cases)} cases ({batch[2]} output lines).")
        for c in mism[:20]:
            out.append(f"- batch differs: {c.domain}/{c.instance}/{c.mutation}: library "
                       f"{c.vg}, batch {c.extra.get('batch')}")
        out.append("")
    out += ["## Disagreements", ""]
    dis = [c for c in cases if c.vg != "refused" and c.val in ("valid", "invalid")
           and not agree(c)]
    if not dis:
        out.append("None.")
    for c in dis:
        j = JUDGEMENTS.get((c.domain, c.instance, c.mutation), "NOT JUDGED")
        out += [f"### {c.domain} / {c.instance} / {c.mutation}", "",
                f"- VeriGraph: **{c.vg}** ({c.vg_detail})",
                f"- VAL: **{c.val}** ({c.val_detail})",
                f"- Judgement: {j}", ""]
    out.append("")
    for name, renames in VAL_RENAMES.items():
        if name in by_domain:
            shown = ", ".join(f"`{a}` -> `{b}`" for a, b in renames)
            out.append(f"VAL is given {name} with {shown} renamed: its lexer reads the name "
                       "as a keyword and refuses the unchanged domain (\"Problem in domain "
                       "definition!\"), though it is legal PDDL; VeriGraph reads the "
                       "original.")
            out.append("")
    out += ["## VAL crashes and errors", ""]
    bad = [c for c in cases if c.val in ("crashed", "error")]
    kinds = Counter((c.mutation, c.val, c.val_detail[:60]) for c in bad)
    if not bad:
        out.append("None.")
    for (mut, v, d), n in sorted(kinds.items()):
        out.append(f"- {n} x {mut}: {v} ({d})")
    out += ["", "## Domains not in the corpus", ""]
    for name, (ipc, why) in sorted(NOT_IN_CORPUS.items()):
        out.append(f"- {name} ({ipc}): {why}")
    out += [f"- {t}" for t in OTHER_TRACKS]
    out += ["", "## Instances and planning other than the default", "",
            "By default a domain's two smallest problems (by file size) of its "
            "downward-benchmarks folder (for a domain of the IPCs since 2008, the "
            "satisficing track's), planned by `lama-first` within `--time-limit`. "
            "Otherwise:", ""]
    for name, (folder, _) in DOMAINS.items():
        how = PLANNING.get(name)
        source = ("AI-Planning/classical-domains" if name in FROM_CLASSICAL_DOMAINS
                  else "downward-benchmarks")
        if how is None and "-opt" not in folder:
            continue
        parts = [f"`{folder}` of {source}"]
        if how is not None:
            if how.instances:
                parts.append("problems " + ", ".join(how.instances))
            if how.time_limit:
                parts.append(f"time limit {how.time_limit} s")
            if how.translate_options:
                parts.append("`--translate-options " + " ".join(how.translate_options)
                             + "`")
        why = f": {how.why}" if how is not None and how.why else ""
        out.append(f"- {name}: {'; '.join(parts)}{why}")
    out += ["", "## VeriGraph refusals", ""]
    ref = Counter((c.domain, c.vg_detail[:200]) for c in cases if c.vg == "refused")
    if not ref:
        out.append("None.")
    for (d, why), n in sorted(ref.items()):
        out.append(f"- {d} ({n} cases): {why}")
    out += ["", "## Speed", "",
            "Per case, one run each: VeriGraph `validate_pddl_dict` in process against "
            "VAL's whole `Validate -v` process (VAL has no library form; its start-up is a "
            "few milliseconds). Cases VeriGraph refused are left out.", "",
            "| domain | cases | mean plan steps | VeriGraph in process, ms/plan | "
            "VAL process, ms/plan | VAL / VeriGraph |", "|---|---|---|---|---|---|"]
    sv = sl = 0.0
    nn = 0
    for name, cs in by_domain.items():
        ok = [c for c in cs if c.vg != "refused" and c.val != "crashed"]
        if not ok:
            out.append(f"| {name} | 0 | | | | |")
            continue
        vg_s = sum(c.vg_seconds for c in ok)
        val_s = sum(c.val_seconds for c in ok)
        steps = sum(len(_steps(c.plan)) for c in ok) / len(ok)
        sv, sl, nn = sv + vg_s, sl + val_s, nn + len(ok)
        out.append(f"| {name} | {len(ok)} | {steps:.0f} | {1000 * vg_s / len(ok):.2f} | "
                   f"{1000 * val_s / len(ok):.2f} | {val_s / vg_s:.1f}x |")
    if nn:
        out.append(f"| **all** | {nn} | | {1000 * sv / nn:.2f} | {1000 * sl / nn:.2f} | "
                   f"{sl / sv:.1f}x |")
    if batch is not None:
        allval = sum(c.val_seconds for c in cases)
        out += ["", f"`verigraph validate --batch` over all {batch[1]} cases (one process, "
                f"refused domains included): {batch[0]:.2f} s = {batch[1] / batch[0]:.0f} "
                f"plans/s; VAL one process per plan: {allval:.2f} s = "
                f"{len(cases) / allval:.0f} plans/s; ratio {allval / batch[0]:.2f}x."]
    return "\n".join(out) + "\n"


def write_verdicts(cases: list[Case]) -> None:
    """Record every case's expected verdict for tests/pddl/test_pddl_ipc_corpus.py,
    which checks VeriGraph against them without VAL: VAL's verdict where it gave one
    (VeriGraph's where the judgement says VAL is wrong), "invalid" where VAL crashed on a
    step of the wrong arity (such a step is no action of the domain, in any validator)."""
    out: dict[str, dict[str, str]] = {}
    for c in cases:
        key = (c.domain, c.instance, c.mutation)
        if c.val in ("valid", "invalid"):
            expected = c.vg if key in VAL_WRONG else c.val
        elif c.val == "crashed" and c.mutation == "wrong-arity":
            expected = "invalid"
        else:
            continue
        out["/".join(key)] = {"val": c.val, "expected": expected}
    VERDICTS.write_text(json.dumps(out, indent=0, sort_keys=True) + "\n")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--val", help="VAL's Validate binary (else $VERIGRAPH_VAL, "
                    "else ~/.cache/verigraph/val/Validate)")
    ap.add_argument("--out", type=Path, default=OUT, help="results file (markdown)")
    ap.add_argument("--quick", action="store_true",
                    help="one plan per domain, four mutations, no --batch run")
    ap.add_argument("--prepare", type=Path, metavar="SRC",
                    help="rebuild benchmarks/data/ipc from a downward-benchmarks checkout")
    ap.add_argument("--per-domain", type=int, default=2)
    ap.add_argument("--only", help="with --prepare: comma-separated domain names")
    ap.add_argument("--tries", type=int, default=6,
                    help="with --prepare: smallest problems tried per domain")
    ap.add_argument("--time-limit", type=int, default=30, help="planner seconds per instance")
    ap.add_argument("--fast-downward", help="path of fast-downward.py (for --prepare)")
    ap.add_argument("--classical-domains", type=Path, metavar="SRC",
                    help="with --prepare: a checkout of AI-Planning/classical-domains, for "
                    "the domains DOMAINS takes from it")
    args = ap.parse_args()
    if args.prepare:
        fd = args.fast_downward
        if fd is None:
            import up_fast_downward

            fd = str(Path(up_fast_downward.__file__).parent / "downward" / "fast-downward.py")
        prepare(args.prepare, args.per_domain, args.time_limit, fd,
                set(args.only.split(",")) if args.only else None, args.tries,
                args.classical_domains)
        return
    val = find_val(args.val)
    if val is None or not Path(val).exists():
        sys.exit("VAL's Validate binary is needed: --val PATH (docs/validator.md says how "
                 "to build it)")
    before = machine()
    cases = load_cases(args.quick)
    texts: dict[Path, str] = {}
    with tempfile.TemporaryDirectory() as tmpname:
        tmp = Path(tmpname)
        warm_up(cases)
        for c in cases:
            for p in (c.domain_file, c.problem_file):
                texts.setdefault(p, p.read_text())
            verigraph_verdict(c, texts[c.domain_file], texts[c.problem_file])
            val_verdict(c, val, tmp)
        batch = None if args.quick else batch_time(cases, tmp)
    after = machine()
    if not args.quick:
        write_verdicts(cases)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(render(cases, batch, val, before, after))
    print(args.out.read_text())


if __name__ == "__main__":
    main()
