"""Every parser regex reads hostile text in linear time.

A regex runs in C holding the interpreter, so neither the per-call watchdog nor another
client gets a turn while it backtracks: a pattern quadratic in a run of spaces
(`move` + 30,000 spaces + `x`) froze a server for seconds. Each row below is a pattern,
how the code calls it, and texts built to make a backtracking pattern retry a run at
every split; 4x the text must cost under 9x the time (quadratic is 16x). Best of five
with the collector paused, as in test_parser.py, and no wall-clock threshold; both sizes
are past the first-level cache, where the cost per character changes.
"""

from __future__ import annotations

import gc
import re
import time
from collections.abc import Callable

import pytest

from blocksworld_corpus import DATA
from verigraph.actions.parser import _CALL, _NAME, _NUMBERING, _PLAIN_MOVE, parse_plan
from verigraph.budget import BudgetExceeded, CallBudget, run_within
from verigraph.errors import PlanParseError
from verigraph.graph import Edge, Node, SceneGraph, dictionary
from verigraph.graph.translator import read_instruction
from verigraph.pddl import plans as pddl_plans
from verigraph.pddl import syntax
from verigraph.pddl import validate as pddl_validate
from verigraph.pddl.blocksworld import plans as blocks_plans
from verigraph.pddl.blocksworld.domain import recognise_domain
from verigraph.perception.label import vlm
from verigraph.planning import parsing
from verigraph.planning.parsing import ParseFailure, parse_answer
from verigraph.tools import goals

pytestmark = pytest.mark.fast

SMALL = 20_000  # characters of the run; the large text has 4x


def _cost(fn: Callable[[str], object], text: str) -> float:
    """Best of five single calls, the collector paused: a busy machine adds noise, and a
    loop of calls on a long text times the allocator as much as the pattern."""
    best = float("inf")
    for _ in range(5):
        gc.disable()
        try:
            start = time.perf_counter()
            fn(text)
            best = min(best, time.perf_counter() - start)
        finally:
            gc.enable()
    return best


def assert_linear(fn: Callable[[str], object], build: Callable[[int], str]) -> None:
    t_small, t_large = _cost(fn, build(SMALL)), _cost(fn, build(4 * SMALL))
    assert t_large < 9 * max(t_small, 1e-6), (t_small, t_large)


def _sub(p: re.Pattern[str]) -> Callable[[str], object]:
    return lambda s: p.sub("", s)


def _all(*patterns: re.Pattern[str]) -> Callable[[str], object]:
    """The matches `findall` finds, counted as they are found: a list of 100,000 tokens
    would time the allocator (its cost per object grows with the heap), not the pattern.
    (Patterns that only take one token at a time, such as syntax._TOKEN, cannot backtrack
    and are left out: a match object per character times the same allocator effects.)"""
    return lambda s: [sum(1 for _ in p.finditer(s)) for p in patterns]


SPACES = " \t"
# (pattern, how the code calls it, texts as functions of a run length n)
PATTERNS: dict[str, tuple[Callable[[str], object], list[Callable[[int], str]]]] = {
    "parser._CALL": (_CALL.match, [
        lambda n: "move" + " " * n + "x", lambda n: "move(" + ") " * (n // 2) + "x",
        lambda n: "move(" + "x" * n, lambda n: "done" + " " * n + "(" + " " * n]),
    "parser._NUMBERING": (_NUMBERING.match, [
        lambda n: " " * n + "x", lambda n: "1" * n + "x", lambda n: " 1." + " " * n]),
    "parser._NAME": (_NAME.match, [lambda n: "a" * n + " ", lambda n: "a." * (n // 2) + "("]),
    "parser._PLAIN_MOVE": (_all(_PLAIN_MOVE), [
        lambda n: "move(a," + " " * n + "x", lambda n: "move" + " " * n + "x",
        lambda n: "move(a, on," + "\t" * n + "b" + " " * n + "x",
        lambda n: "move(a, b)\n" * (n // 11) + "x", lambda n: " " * n + "move(a,b)x"]),
    "syntax.STEP_PREFIX": (_sub(syntax.STEP_PREFIX), [
        lambda n: " " * n + "x", lambda n: "1" * n + "x", lambda n: "1." + "1" * n + "x",
        lambda n: "1" + " " * n + "x"]),
    "syntax.DURATION": (_sub(syntax.DURATION), [
        lambda n: "a" + " " * n + "x", lambda n: "[" + "1" * n, lambda n: "[1]" + " " * n + "x",
        lambda n: "a [1]" * (n // 5) + "x", lambda n: " [" * (n // 2)]),
    "blocksworld._VERBS": (blocks_plans._VERBS.match, [lambda n: "pick" + "_" * n + "x"]),
    "syntax._INNERMOST": (_all(syntax._INNERMOST), [
        lambda n: "(" * n, lambda n: "( " * (n // 2) + "x", lambda n: ";" + " " * n,
        lambda n: "(a" + " b" * (n // 2)]),
    "pddl plan lines": (_all(pddl_plans._PLAIN_LINE, pddl_plans._INNER_ACTION), [
        lambda n: "(a" + " b" * (n // 2) + " ", lambda n: "(a)" + " " * n + "x",
        lambda n: "( " * (n // 2) + "x", lambda n: "(a" + " " * n + ")"]),
    "pddl sections": (_all(pddl_validate._SECTION, pddl_validate._REQUIREMENTS,
                           pddl_validate._STRAY), [
        lambda n: "(" + " " * n + "x", lambda n: ")" + " " * n + "a" * n + " " * n + "x",
        lambda n: "(:requirements" + " :a" * (n // 3), lambda n: ") a" * (n // 3)]),
    "planning._FENCE": (parsing._FENCE.search, [
        lambda n: "```" + " " * n + "x", lambda n: "```json" + "\n" * n + "{",
        lambda n: "``" + " `" * (n // 2)]),
    "vlm._FENCE": (_sub(vlm._FENCE), [
        lambda n: "{" + " " * n + "x", lambda n: "```" + " " * n + "x",
        lambda n: "x" + " \n" * (n // 2) + "``", lambda n: "```" * (n // 3) + " "]),
    "goals._EDGE_TEXT": (goals._EDGE_TEXT.fullmatch, [
        lambda n: "cup" + " " * n + "x", lambda n: "cup on table" + " " * n + "x",
        lambda n: "cup" + " ," * (n // 2), lambda n: "move(" + " " * n + "cup on",
        lambda n: "cup , on" + " " * n + ", table x"]),
    "dictionary": (lambda s: (dictionary._SEPARATORS.sub("_", s),
                              dictionary._NUMBER_SUFFIX.search(s)), [
        lambda n: " -" * (n // 2) + "x", lambda n: "_" + "1" * n + "x", lambda n: "_1" * n]),
}


@pytest.mark.parametrize("name", sorted(PATTERNS))
def test_each_parser_regex_reads_hostile_text_in_linear_time(name: str) -> None:
    fn, builders = PATTERNS[name]
    for build in builders:
        assert_linear(fn, build)


BLOCKS_DOMAIN = recognise_domain((DATA / "planbench_domain.pddl").read_text())


def _blocks(text: str) -> object:
    try:
        return blocks_plans.parse_blocks_plan(text, BLOCKS_DOMAIN, {"a", "b"})
    except PlanParseError as exc:
        return exc


def _scene_plan(text: str) -> object:
    try:
        return parse_plan(text)
    except PlanParseError as exc:
        return exc


def _answer(text: str) -> object:
    try:
        return parse_answer(text)
    except ParseFailure as exc:
        return exc


@pytest.mark.parametrize("fn,build", [
    (_scene_plan, lambda n: "move" + " " * n + "x"),          # 30,000 spaces: 5.9 s before
    (_scene_plan, lambda n: "1." + " " * n + "move(a, b)" + " " * n + "x"),
    (_scene_plan, lambda n: '["move' + " " * n + 'x"]'),     # a JSON plan's text action
    (_blocks, lambda n: "unstack a" + " " * n + "b"),         # 20,000 spaces: 3.5 s before
    (_blocks, lambda n: "stack a" + " " * n + "on" + " " * n + "x"),
    (_blocks, lambda n: "unstack " + "a " * (n // 2) + "b"),
    (_blocks, lambda n: "1: (pick-up a)" + " " * n + "[1" + " " * n + "x"),
    (_blocks, lambda n: "pick up a" + " " * n + "."),
    (_answer, lambda n: "```json" + " " * n + "x"),
    (_answer, lambda n: "move" + " " * n + "x"),
], ids=lambda v: "" if callable(v) else str(v))
def test_the_plan_readers_take_hostile_lines_in_linear_time(fn, build) -> None:
    assert_linear(fn, build)
    assert fn(build(10)) is not None


def test_blocks_sentences_still_read_with_any_spacing() -> None:
    steps = blocks_plans.parse_blocks_plan(
        "unstack  the red block\tfrom on top of   the blue block\n"
        "put   down the red   block\nstack a  on\t top of b", BLOCKS_DOMAIN, set())
    assert [(s.role, s.args) for s in steps] == [("unstack", ("a", "b")),
                                                ("put-down", ("a",)),
                                                ("stack", ("a", "b"))]


def test_an_instruction_is_read_in_linear_time() -> None:
    graph = SceneGraph(nodes=[Node(id="table", label="table"), Node(id="a", label="block"),
                              Node(id="b", label="block")],
                       edges=[Edge(source="a", relation="on", target="table"),
                              Edge(source="b", relation="on", target="table")],
                       dictionary="blocks")
    assert read_instruction("put a on b", graph).edges == [Edge(source="a", relation="on",
                                                                target="b")]
    assert_linear(lambda s: read_instruction(s, graph), lambda n: "a" + " " * n + "x")
    assert_linear(lambda s: read_instruction(s, graph), lambda n: "put a" + " " * n + "on b")
    # "A on B with C on it" is read only within a clause's length (its pattern is cubic)
    assert_linear(lambda s: read_instruction(s, graph), lambda n: "a on b with " * (n // 12))
    reading = read_instruction("the a " + "on " * 1_000, graph)
    assert "at most 400 characters" in reading.not_understood[0][1]


@pytest.mark.parametrize("plan,why", [
    ("[" * 100_000, "nests too deeply"),
    ('{"actions": [' + '{"a": ' * 3_000 + "1" + "}" * 3_000 + "]}", "nests too deeply"),
    ("[" + "9" * 5_000 + "]", "holds a number too long to read"),
])
def test_a_json_plan_python_will_not_hold_is_a_parse_error(plan: str, why: str) -> None:
    with pytest.raises(PlanParseError) as err:  # was a RecursionError or ValueError
        parse_plan(plan)
    assert err.value.message == f"the JSON plan {why}" and err.value.line == 1
    assert len(err.value.text) <= 80


def test_a_long_plan_stops_at_its_call_budget() -> None:
    """The line-by-line reader is a Python loop that checks the call's budget: a plan of
    300,000 commented lines (seconds to read) stops at a 0.05 s budget."""
    plan = "move(a, b)  # c\n" * 300_000
    with pytest.raises(BudgetExceeded, match="longer than its 0.05 s budget"):
        run_within(CallBudget(wall_s=0.05), "validate_plan", lambda: parse_plan(plan))
