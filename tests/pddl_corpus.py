"""Generated STRIPS problems and plans (logistics, depots, renamed blocks worlds), with mutations.

Independent of the validator under test: valid plans are random walks chosen by
unified-planning's own simulator (an applicable action at every state), and goals are
atoms of the state the walk ends in. Mutations break plans the ways LLM plans break:
a wrong precondition (an argument swapped for another object of its type), a missing
step, a wrong goal (an atom the walk leaves false), a wrong arity, an unknown object.
"""

from __future__ import annotations

import random
import re
from pathlib import Path

import unified_planning as up
from unified_planning.engines.plan_validator import SequentialPlanValidator
from unified_planning.engines.sequential_simulator import UPSequentialSimulator
from unified_planning.io import PDDLReader
from unified_planning.shortcuts import get_environment

get_environment().credits_stream = None
PDDL_DATA = Path(__file__).parent / "data" / "pddl"
MUTATIONS = ("valid", "wrong_precondition", "missing_step", "wrong_goal", "wrong_arity",
             "unknown_object")


def logistics_problem(rng: random.Random, typed: bool, cities: int = 2, packages: int = 2
                      ) -> tuple[str, dict[str, str], list[str]]:
    """(objects text, object -> type, init atoms) of a small logistics problem."""
    types: dict[str, str] = {}
    init: list[str] = []
    for c in range(cities):
        types[f"c{c}"] = "city"
        for k in range(2):
            loc = f"l{c}-{k}"
            types[loc] = "airport" if k == 0 else "location"
            init.append(f"(in-city {loc} c{c})")
        types[f"t{c}"] = "truck"
        init.append(f"(at t{c} l{c}-{rng.randrange(2)})")
    airplanes = max(1, cities - 1)
    for a in range(airplanes):
        types[f"a{a}"] = "airplane"
        init.append(f"(at a{a} l{rng.randrange(cities)}-0)")
    for p in range(packages):
        types[f"p{p}"] = "package"
        init.append(f"(at p{p} l{rng.randrange(cities)}-{rng.randrange(2)})")
    if typed:
        init.append(f"(in-city hub c{rng.randrange(cities)})")
        objects = " ".join(f"{o} - {t}" for o, t in types.items())
    else:
        marks = {"city": "CITY", "airport": "LOCATION", "location": "LOCATION",
                 "truck": "TRUCK", "airplane": "AIRPLANE", "package": "OBJ"}
        for o, t in types.items():
            init.append(f"({marks[t]} {o})")
            if t == "airport":
                init.append(f"(AIRPORT {o})")
        objects = " ".join(types)
    return objects, types, init


def depots_problem(rng: random.Random, places: int = 2, crates: int = 3
                   ) -> tuple[str, dict[str, str], list[str]]:
    types: dict[str, str] = {}
    init: list[str] = []
    tops: dict[str, str] = {}
    for i in range(places):
        place = f"depot{i}" if i % 2 == 0 else f"distributor{i}"
        types[place] = "depot" if i % 2 == 0 else "distributor"
        types[f"pallet{i}"], types[f"hoist{i}"] = "pallet", "hoist"
        init += [f"(at pallet{i} {place})", f"(at hoist{i} {place})", f"(available hoist{i})"]
        tops[place] = f"pallet{i}"
    for t in range(max(1, places - 1)):
        types[f"truck{t}"] = "truck"
        init.append(f"(at truck{t} {rng.choice(list(tops))})")
    for c in range(crates):
        place = rng.choice(list(tops))
        types[f"crate{c}"] = "crate"
        init += [f"(at crate{c} {place})", f"(on crate{c} {tops[place]})"]
        tops[place] = f"crate{c}"
    init += [f"(clear {top})" for top in tops.values()]
    return " ".join(f"{o} - {t}" for o, t in types.items()), types, init


def problem_text(name: str, domain: str, objects: str, init: list[str], goal: list[str]) -> str:
    return (f"(define (problem {name}) (:domain {domain})\n(:objects {objects})\n(:init\n  "
            + "\n  ".join(init) + f")\n(:goal (and {' '.join(goal)})))\n")


def oracle(tmp: Path, domain: str, problem: str, plan: list[str]
           ) -> tuple[bool | str, int | None]:
    """(valid, first failing step) from unified-planning's SequentialPlanValidator, the
    reference the agreement tests compare with, or ("refused", step) when it cannot build
    the plan's step (wrong arity, unknown object)."""
    (tmp / "d.pddl").write_text(domain)
    (tmp / "p.pddl").write_text(problem)
    parsed = PDDLReader().parse_problem(str(tmp / "d.pddl"), str(tmp / "p.pddl"))
    actions = []
    for step, line in enumerate(plan, start=1):
        name, *args = line.strip("()").split()
        try:
            actions.append(up.plans.ActionInstance(parsed.action(name),
                                                   [parsed.object(a) for a in args]))
        except Exception:  # noqa: BLE001 - the oracle refuses to build this step
            return "refused", step
    result = SequentialPlanValidator().validate(parsed, up.plans.SequentialPlan(actions))
    step = len(result.trace) if result.inapplicable_action is not None else None
    return result.status.name == "VALID", step


def _atom_text(fluent) -> str:  # type: ignore[no-untyped-def]
    args = [str(a) for a in fluent.args]
    return "(" + " ".join([fluent.fluent().name, *args]) + ")"


def random_walk(domain_file: Path, problem: str, tmp: Path, length: int, rng: random.Random,
                walker: tuple[Path, str] | None = None
                ) -> tuple[list[str], list[str], list[str]]:
    """(plan lines, atoms true at the end, atoms false at the end that were true once),
    chosen by unified-planning's simulator, action names and objects lower-cased.

    `walker` (domain file, problem text) chooses the actions on an equivalent typed
    encoding when the simulator cannot ground the domain itself (its grounder fails on
    PlanBench's untyped logistics); the walk is replayed on the real domain, and stops
    at the first step that domain cannot apply.
    """
    (tmp / "walk.pddl").write_text(problem)
    parsed = PDDLReader().parse_problem(str(domain_file), str(tmp / "walk.pddl"))
    if walker is not None:
        lines, _, _ = random_walk(walker[0], walker[1], tmp, length, rng)
    plan: list[str] = []
    seen: set[str] = set()
    with UPSequentialSimulator(parsed) as sim:
        state = sim.get_initial_state()
        for k in range(length):
            if walker is None:
                options = list(sim.get_applicable_actions(state))
                if not options:
                    break
                action, params = options[rng.randrange(len(options))]
            else:
                if k >= len(lines):
                    break
                name, *args = lines[k].strip("()").split()
                if not parsed.has_action(name) or not all(parsed.has_object(a) for a in args):
                    break
                action, params = parsed.action(name), tuple(parsed.object(a) for a in args)
                if not sim.is_applicable(state, action, params):
                    break
            state = sim.apply(state, action, params)
            assert state is not None
            plan.append("(" + " ".join([action.name, *(str(p) for p in params)]).lower() + ")")
            seen.update(_true_atoms(parsed, state))
        true_now = _true_atoms(parsed, state)
    return plan, sorted(true_now), sorted(seen - true_now)


def _true_atoms(parsed, state) -> set[str]:  # type: ignore[no-untyped-def]
    from itertools import product

    out: set[str] = set()
    for fluent in parsed.fluents:
        if not fluent.type.is_bool_type():
            continue
        domains = [list(parsed.objects(p.type)) for p in fluent.signature]
        for combo in product(*domains):
            expr = fluent(*combo)
            if state.get_value(expr).bool_constant_value():
                out.add(_atom_text(expr).lower())
    return out


def mutate(plan: list[str], kind: str, types: dict[str, str], rng: random.Random
           ) -> list[str] | None:
    """The plan broken one way (goals are mutated by the caller), or None if impossible."""
    plan = list(plan)
    if kind in ("valid", "wrong_goal"):
        return plan
    if not plan:
        return None
    i = rng.randrange(len(plan))
    name, *args = plan[i].strip("()").split()
    if kind == "missing_step":
        del plan[i]
    elif kind == "wrong_arity":
        plan[i] = "(" + " ".join([name, *args[:-1]]) + ")"
    elif kind == "unknown_object":
        args[rng.randrange(len(args))] = "zz9"
        plan[i] = "(" + " ".join([name, *args]) + ")"
    elif kind == "wrong_precondition":
        k = rng.randrange(len(args))
        same = [o for o, t in types.items() if t == types.get(args[k]) and o != args[k]]
        if not same:
            return None
        args[k] = rng.choice(same)
        plan[i] = "(" + " ".join([name, *args]) + ")"
    return plan


def blocks_renaming(rng: random.Random) -> dict[str, str]:
    """A random renaming of PlanBench's blocks-world names: predicates, actions, parameters,
    objects; some are PDDL keywords or prefixes of one another."""
    pool = ["at", "over", "start", "end", "all", "goal", "init", "either", "define", "and-2",
            "on", "on-table", "on-table-2", "o", "oo", "ontable", "clear", "x-1", "tricky_name",
            "pick", "pick-up-2", "stack", "unstack", "province", "craves", "harmony"]
    pool += ["".join(rng.choice("abcdefghijklmnopqrstuvwxyz") for _ in range(rng.randint(4, 12)))
             for _ in range(20)]
    rng.shuffle(pool)
    names = iter(dict.fromkeys(pool))
    renaming = {w: next(names) for w in ("on", "on-table", "clear", "arm-empty", "holding",
                                         "pick-up", "put-down", "stack", "unstack")}
    renaming.update({f"?{w}": f"?{next(names)}" for w in ("x", "ob", "underob")})
    return renaming


def rename(text: str, renaming: dict[str, str]) -> str:
    """Replace whole PDDL tokens (names between spaces and parentheses)."""
    return re.sub(r"[^\s()]+", lambda m: renaming.get(m.group(0).lower(), m.group(0)), text)


def logistics_walk(cities: int, packages: int, steps: int, seed: int = 0
                   ) -> tuple[str, list[str]]:
    """(problem text, valid plan) for the typed logistics domain, for benchmarks: trucks
    drive between the locations of their city, loading the packages they find and
    unloading them elsewhere; the goal is where the walk leaves the first packages.
    Bookkeeping is its own (a dict per package), not the validator under test."""
    rng = random.Random(seed)
    where = {f"p{i}": f"l{rng.randrange(cities)}-{rng.randrange(3)}" for i in range(packages)}
    truck_at = {f"t{c}": f"l{c}-0" for c in range(cities)}
    load: dict[str, list[str]] = {t: [] for t in truck_at}
    plan: list[str] = []
    while len(plan) < steps:
        c = rng.randrange(cities)
        t = f"t{c}"
        here = truck_at[t]
        waiting = [p for p, loc in where.items() if loc == here]
        if load[t] and rng.random() < 0.5:
            p = load[t].pop()
            where[p] = here
            plan.append(f"(unload-truck {p} {t} {here})")
        elif waiting and rng.random() < 0.7:
            p = rng.choice(waiting)
            where[p] = t
            load[t].append(p)
            plan.append(f"(load-truck {p} {t} {here})")
        else:
            to = f"l{c}-{rng.choice([k for k in range(3) if f'l{c}-{k}' != here])}"
            truck_at[t] = to
            plan.append(f"(drive-truck {t} {here} {to} c{c})")
    types = {f"c{c}": "city" for c in range(cities)}
    init = []
    for c in range(cities):
        for k in range(3):
            types[f"l{c}-{k}"] = "airport" if k == 0 else "location"
            init.append(f"(in-city l{c}-{k} c{c})")
        types[f"t{c}"] = "truck"
        init.append(f"(at t{c} l{c}-0)")
    types["a0"] = "airplane"
    init += ["(at a0 l0-0)", "(in-city hub c0)"]
    rng2 = random.Random(seed)
    for i in range(packages):
        types[f"p{i}"] = "package"
        init.append(f"(at p{i} l{rng2.randrange(cities)}-{rng2.randrange(3)})")
    goal = [f"(at {p} {loc})" if loc.startswith("l") else f"(in {p} {loc})"
            for p, loc in list(where.items())[:20]]
    objects = " ".join(f"{o} - {t}" for o, t in types.items())
    return problem_text("walk", "logistics-typed", objects, init, goal), plan
