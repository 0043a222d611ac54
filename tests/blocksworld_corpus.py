"""Generated PlanBench-style blocks-world problems and 4-op plans, with mutations.

Independent of the validator: states are plain dicts, plans are built by the textbook
strategy (everything to the table, then goal towers bottom-up) and then broken in
the ways LLM plans break.
"""

from __future__ import annotations

import random
from pathlib import Path

DATA = Path(__file__).parent / "data" / "blocksworld"
DOMAINS = {"planbench": ("on-table", "arm-empty"), "ipc2000": ("ontable", "handempty"),
           "typed": ("ontable", "handempty")}
LETTERS = "abcdefghijkl"
MUTATIONS = ("valid", "covered_block", "wrong_source", "missing_release", "no_op_pair",
             "swapped_steps", "dropped_step")


def random_state(blocks: list[str], rng: random.Random) -> dict[str, str | None]:
    """block -> block below (None = table)."""
    order = blocks[:]
    rng.shuffle(order)
    below: dict[str, str | None] = {}
    tops: list[str] = []
    for b in order:
        if tops and rng.random() < 0.6:
            t = tops.pop(rng.randrange(len(tops)))
            below[b] = t
        else:
            below[b] = None
        tops.append(b)
    return below


def problem_text(name: str, below: dict[str, str | None], goal: dict[str, str | None],
                 spelling: str) -> str:
    ontable, handempty = DOMAINS[spelling]
    covered = {v for v in below.values() if v}
    facts = [f"({handempty})"]
    facts += [f"(clear {b})" for b in below if b not in covered]
    facts += [f"(on {b} {v})" if v else f"({ontable} {b})" for b, v in below.items()]
    goals = [f"(on {b} {v})" for b, v in goal.items() if v]
    objects = " ".join(below) + (" - block" if spelling == "typed" else "")
    return (f"(define (problem {name})\n(:domain d)(:objects {objects})\n(:init\n"
            + "\n".join(facts) + f")\n(:goal\n(and\n{' '.join(goals)}))\n)\n")


def reference_plan(below: dict[str, str | None], goal: dict[str, str | None]) -> list[str]:
    """A valid 4-op plan: unstack every tower to the table, then build goal towers."""
    state = dict(below)
    plan: list[str] = []
    above = {v: b for b, v in state.items() if v}
    # unstack from the top of each tower
    for base in [b for b, v in state.items() if v is None]:
        tower = [base]
        while tower[-1] in above:
            tower.append(above[tower[-1]])
        for top, under in zip(reversed(tower[1:]), reversed(tower[:-1]), strict=True):
            plan += [f"(unstack {top} {under})", f"(put-down {top})"]
    def depth(b: str) -> int:
        d, cur = 0, goal.get(b)
        while cur:
            d, cur = d + 1, goal.get(cur)
        return d
    for b in sorted((b for b, v in goal.items() if v), key=depth):
        plan += [f"(pick-up {b})", f"(stack {b} {goal[b]})"]
    return plan


def mutate(plan: list[str], below: dict[str, str | None], kind: str,
           rng: random.Random) -> list[str] | None:
    """The plan broken one way, or None when this plan has no place for that mutation."""
    plan = list(plan)
    if kind == "valid":
        return plan
    if kind == "covered_block":
        covered = [v for v in below.values() if v]
        if not covered:
            return None
        x = rng.choice(covered)
        under = below[x]
        return [f"(unstack {x} {under})" if under else f"(pick-up {x})", *plan]
    if kind == "wrong_source":
        grasps = [i for i, a in enumerate(plan) if a.startswith(("(unstack", "(pick-up"))]
        if not grasps:
            return None
        i = rng.choice(grasps)
        x = plan[i].split()[1].rstrip(")")
        if plan[i].startswith("(unstack"):
            plan[i] = f"(pick-up {x})"
        else:
            others = [b for b in below if b != x]
            plan[i] = f"(unstack {x} {rng.choice(others)})"
        return plan
    if kind == "missing_release":
        releases = [i for i, a in enumerate(plan) if a.startswith(("(put-down", "(stack"))]
        if not releases:
            return None
        del plan[rng.choice(releases)]
        return plan
    if kind == "no_op_pair":
        clear_on_table = [b for b, v in below.items() if v is None and b not in below.values()]
        if not clear_on_table:
            return None
        x = rng.choice(clear_on_table)
        return [f"(pick-up {x})", f"(put-down {x})", *plan]
    if kind == "swapped_steps":
        if len(plan) < 2:
            return None
        i = rng.randrange(len(plan) - 1)
        plan[i], plan[i + 1] = plan[i + 1], plan[i]
        return plan
    if kind == "dropped_step":
        if not plan:
            return None
        del plan[rng.randrange(len(plan))]
        return plan
    raise ValueError(kind)


def generate(n_cases: int, seed: int = 0, sizes: tuple[int, int] = (3, 7)):
    """(spelling, problem text, plan lines, mutation kind) for many random problems."""
    rng = random.Random(seed)
    for case in range(n_cases):
        n = rng.randint(*sizes)
        blocks = list(LETTERS[:n])
        below = random_state(blocks, rng)
        goal = random_state(blocks, rng)
        spelling = list(DOMAINS)[case % len(DOMAINS)]
        kind = MUTATIONS[case % len(MUTATIONS)]
        plan = mutate(reference_plan(below, goal), below, kind, rng)
        if plan is None:
            continue
        yield spelling, problem_text(f"p{case}", below, goal, spelling), plan, kind


def domain_text(spelling: str) -> str:
    return (DATA / f"{spelling}_domain.pddl").read_text()
