"""Agreement with VAL on PlanBench's own instances: same verdict and same failing step.

For each PlanBench domain that is classical STRIPS (Mystery Blocksworld, depots,
logistics) and each of its instances, a valid plan is made by a random walk (an
applicable grounding found by the STRIPS engine's bounded search at every step) and
then broken three ways (a dropped step, two steps swapped, all steps shuffled). Every
plan goes to VAL's `Validate -v` and to `validate_pddl_dict`; a row counts the plans and
how many got the same verdict and, for an inexecutable plan, the same failing step.
Instances are read from a PlanBench checkout given on the command line; nothing is
downloaded.

Run: python benchmarks/bench_planbench_agreement.py --planbench PATH/plan-bench/instances
     [--val PATH/Validate] [--instances 120]
Results: benchmarks/results/validate_planbench.md
"""

from __future__ import annotations

import argparse
import os
import random
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from bench_validate import find_val  # noqa: E402
from common import write_table  # noqa: E402

from verigraph.pddl import read_domain, read_problem, validate_pddl_dict  # noqa: E402
from verigraph.pddl.model import Domain, Problem  # noqa: E402
from verigraph.pddl.simulate import complete_binding  # noqa: E402

DOMAINS = {"Mystery Blocksworld": "blocksworld/mystery", "depots": "depots",
           "logistics": "logistics"}
MUTATIONS = ("valid walk", "dropped step", "swapped steps", "shuffled")
_FAILED_AT = re.compile(r"has an unsatisfied precondition at time (\d+)")


def walk(domain: Domain, problem: Problem, rng: random.Random, length: int) -> list[str]:
    """A valid plan: at each step a random schema with an applicable grounding."""
    state = set(problem.init)
    plan: list[str] = []
    for _ in range(length):
        names = list(domain.schemas)
        rng.shuffle(names)
        for name in names:
            schema = domain.schemas[name]
            for kind in set(schema.types):
                rng.shuffle(problem.of_type(domain, kind))
            binding = complete_binding(domain, problem, schema, [None] * len(schema.params),
                                       state)
            if binding is None:
                continue
            dels = {schema.ground(lit, binding) for lit in schema.delete}
            adds = {schema.ground(lit, binding) for lit in schema.add}
            state = (state - dels) | adds
            plan.append("(" + " ".join((name, *binding)) + ")")
            break
        else:
            break
    return plan


def mutate(plan: list[str], kind: str, rng: random.Random) -> list[str]:
    plan = list(plan)
    if kind == "dropped step" and plan:
        del plan[rng.randrange(len(plan))]
    elif kind == "swapped steps" and len(plan) > 1:
        i = rng.randrange(len(plan) - 1)
        plan[i], plan[i + 1] = plan[i + 1], plan[i]
    elif kind == "shuffled":
        rng.shuffle(plan)
    return plan


def val_verdict(val: str, domain: Path, problem: Path, plan: Path) -> tuple[object, int | None]:
    env = dict(os.environ, LD_LIBRARY_PATH=str(Path(val).parent))
    out = subprocess.run([val, "-v", str(domain), str(problem), str(plan)], capture_output=True,
                         text=True, check=False, env=env).stdout
    if "Plan valid" in out:
        return True, None
    failed = _FAILED_AT.search(out)
    if failed:
        return False, int(failed.group(1))
    if "Goal not satisfied" in out:
        return False, None
    return "unreadable", None


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--planbench", required=True,
                        help="PlanBench's plan-bench/instances folder")
    parser.add_argument("--val", help="VAL's Validate (default as in bench_validate.py)")
    parser.add_argument("--instances", type=int, default=120)
    args = parser.parse_args()
    val = find_val(args.val)
    if val is None:
        sys.exit("no VAL binary: give --val (docs/validator.md says how to build it)")
    work = Path(tempfile.mkdtemp(prefix="bench_planbench_"))
    rows: list[list[str]] = []
    for title, folder in DOMAINS.items():
        base = Path(args.planbench) / folder
        domain_file = base / "generated_domain.pddl"
        domain_text = domain_file.read_text()
        domain = read_domain(domain_text)
        rng = random.Random(1)
        plans = same = invalid = executable = 0
        engines: set[str] = set()
        ours_seconds = 0.0
        for i in range(1, args.instances + 1):
            instance = base / "generated_basic" / f"instance-{i}.pddl"
            if not instance.exists():
                continue
            problem_text = instance.read_text()
            plan = walk(domain, read_problem(problem_text, domain), rng, rng.randint(3, 12))
            for kind in MUTATIONS:
                trial = mutate(plan, kind, rng)
                (work / "plan.txt").write_text("\n".join(trial) + "\n")
                theirs = val_verdict(val, domain_file, instance, work / "plan.txt")
                start = time.perf_counter()
                report = validate_pddl_dict(domain_text, problem_text, "\n".join(trial))
                ours_seconds += time.perf_counter() - start
                v = report["violations"]
                ours = (report["valid"], v[0]["step"] if v else None)
                engines.add(report["engine"])
                plans += 1
                same += ours == theirs
                invalid += not report["valid"]
                executable += report["plan_valid"]
        rows.append([title, ", ".join(sorted(engines)), f"{plans:,}", f"{executable:,}",
                     f"{invalid:,}",
                     f"{same:,} ({100 * same / max(plans, 1):.1f}%)",
                     f"{1000 * ours_seconds / max(plans, 1):.2f}"])
        print(rows[-1], flush=True)
    write_table("validate_planbench", "Agreement with VAL on PlanBench's own instances",
                ["domain", "engine", "plans", "executable", "invalid",
                 "same verdict and failing step",
                 "ms per plan (ours, in process)"], rows,
                notes=f"Instances 1-{args.instances} of each domain's generated_basic set; "
                      "per instance one random-walk plan and its " + ", ".join(MUTATIONS[1:])
                      + " variants (the walks rarely reach PlanBench's goals, so most "
                      "executable plans are judged on the goal). VAL: Validate -v, verdict "
                      "and the time of the unsatisfied precondition.")


if __name__ == "__main__":
    main()
