"""`verigraph rollouts`: environment rollouts of a task suite, serially or on Ray.

The command-line face of `verigraph.env.rollout.run_rollouts` (docs/env.md): the
tasks of a bundled suite (`--family`, one split) or of a task file (`--tasks`), each
run `--samples` times by one of the project's policies, through the evaluation engine
that runs `bench plan` (serial, or `--ray local|auto|HOST:PORT`). With
`--trajectories FILE` every finished episode is written there as JSONL (one line per
step) and a rerun of the same command resumes (a rerun with other --k, --threshold or
--max-steps, or other tasks under the same ids, is refused: exit 2, the file kept); the
progress bar is `bench plan`'s. It
prints pass@1 and pass^k (every sample of a task succeeded) over the tasks run, the
mean return, and the failed rollouts by kind; `--json` prints the same as one object.
The exit code is 0 whatever the policy achieved (a run's outcome is not a verdict),
2 for bad input.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections import Counter
from typing import Any, get_args

from verigraph.cli.exits import EXIT_OK
from verigraph.errors import VeriGraphError

# verigraph.env's PolicyName and FAMILIES, written out so that building the parser does
# not import the env extra (tests/cli/test_cli_rollouts.py checks they stay equal).
POLICIES = ("oracle", "noisy", "greedy", "refuse")
FAMILIES = ("blocks", "kitchen", "tangram", "household", "behavior")


def register(sub: Any) -> None:
    from verigraph.planning.iteration import DEFAULT_K, DEFAULT_THRESHOLD

    p = sub.add_parser("rollouts", help="run environment rollouts of a task suite "
                                        "(pass@1, pass^k, trajectories as JSONL)",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    source = p.add_mutually_exclusive_group()
    source.add_argument("--family", choices=FAMILIES, default="blocks",
                        help="a bundled task suite (default blocks)")
    source.add_argument("--tasks", metavar="FILE.jsonl", help="a task file (one task per line, "
                                                              "as verigraph.env writes them)")
    p.add_argument("--split", choices=("train", "test", "all"), default="test",
                   help="which tasks of the suite or file (by content hash; default test)")
    p.add_argument("--limit", type=int, metavar="N", help="the first N tasks only")
    p.add_argument("--policy", choices=POLICIES, default="noisy",
                   help="oracle (reads the privileged goal: the ceiling), noisy, greedy, or "
                        "refuse (an action the verifier always refuses); default noisy")
    p.add_argument("--samples", type=int, default=1, metavar="K",
                   help="rollouts per task, policy seeds 0..K-1 (pass^k needs K > 1)")
    p.add_argument("--noise", type=float, default=0.3, help="the noisy policy's error rate")
    p.add_argument("--seed", type=int, default=0, help="every episode's reset seed")
    p.add_argument("--k", type=int, default=DEFAULT_K,
                   help=f"actions per step at most (default {DEFAULT_K})")
    p.add_argument("--threshold", "-t", type=int, default=DEFAULT_THRESHOLD,
                   help="the error threshold: failed steps in a row before an episode is "
                        f"truncated (default {DEFAULT_THRESHOLD})")
    p.add_argument("--max-steps", type=int, default=40, help="steps before truncation")
    p.add_argument("--ray", metavar="ADDRESS", help="run on Ray: local (this machine's "
                                                    "cores), auto, HOST:PORT or ray://HOST:10001")
    p.add_argument("--workers", type=int, metavar="N", help="rollouts at once on Ray")
    p.add_argument("--trajectories", metavar="FILE.jsonl",
                   help="write every episode there as it ends; rerun to resume")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--json", action="store_true", help="the summary as one JSON object")
    p.set_defaults(handler=run_rollouts_command)


def _check(args: argparse.Namespace) -> None:
    for name, value, low in (("--samples", args.samples, 1), ("--limit", args.limit, 1),
                             ("--workers", args.workers, 1)):
        if value is not None and value < low:
            raise VeriGraphError(f"must be at least {low}", field=name, value=value,
                                 fix=f"give {name} {low} or more")
    if not 0.0 <= args.noise <= 1.0:
        raise VeriGraphError("must be between 0 and 1", field="--noise",
                             value=args.noise, fix="use e.g. --noise 0.3")


def run_rollouts_command(args: argparse.Namespace) -> int:
    _check(args)
    # Loaded here, not at import: `verigraph --help` must not need the env extra.
    from verigraph.env import dataset
    from verigraph.env.rollout import RolloutJob, pass_rates, run_rollouts

    records = (dataset.load_tasks(args.tasks) if args.tasks
               else dataset.suite_tasks(args.family))
    if args.split in get_args(dataset.Split):
        records = dataset.split_tasks(records, args.split)
    records = records[:args.limit] if args.limit else records
    if not records:
        raise VeriGraphError(f"no task in the {args.split} split", field="--split",
                             value=args.split, fix="use --split all, or another suite")
    jobs = [RolloutJob(task_id=r.task_id, seed=args.seed, policy=args.policy,
                       policy_seed=sample, noise=args.noise)
            for r in records for sample in range(args.samples)]
    env_kwargs = {"tasks": records, "k": args.k, "threshold": args.threshold,
                  "max_steps": args.max_steps}
    results = run_rollouts(jobs, env_kwargs, ray=args.ray, workers=args.workers,
                           trajectories=args.trajectories, progress=not args.no_progress)
    rates = pass_rates(results)  # a rollout that failed to run counts as failed
    errors = Counter(r.error_kind for r in results if r.error_kind is not None)
    summary = {"tasks": len(records), "samples": args.samples, "rollouts": len(results),
               "policy": args.policy, "pass@1": rates["pass@1"], "pass^k": rates["pass^k"],
               "mean_return": sum(r.episode_return for r in results) / len(results),
               "mean_steps": sum(r.steps for r in results) / len(results),
               "errors": dict(errors), "trajectories": args.trajectories}
    if args.json:
        print(json.dumps(summary))
        return EXIT_OK
    print(f"{summary['rollouts']} rollouts of {summary['tasks']} tasks ({args.policy}, "
          f"{args.samples} per task): pass@1 {rates['pass@1']:.3f}, "
          f"pass^{args.samples} {rates['pass^k']:.3f}, mean return "
          f"{summary['mean_return']:.3f}, mean steps {summary['mean_steps']:.1f}")
    if errors:
        print("failed to run: " + ", ".join(f"{n} {kind}" for kind, n in errors.items()),
              file=sys.stderr)
    if args.trajectories:
        print(f"trajectories: {args.trajectories} (rerun the same command to resume)")
    return EXIT_OK
