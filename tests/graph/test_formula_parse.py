"""Goal formulas in BDDL's syntax: every grammar rule, every error (position and fix),
and hostile inputs that stay linear and bounded."""

from __future__ import annotations

import time

import pytest

from verigraph.errors import GoalError
from verigraph.graph import formula as formula_module
from verigraph.graph.formula import (
    MAX_DEPTH,
    MAX_FORMULA_CHARS,
    MAX_PARTS,
    Atom,
    Imply,
    Junction,
    Not,
    Pairs,
    Param,
    Quantified,
    constants,
    parse_formula,
    show,
)
from verigraph.graph.goal import looks_like_formula

pytestmark = pytest.mark.fast
NO_CUP_ON_A_PLATE = "(forall (?c - cup) (not (exists (?p - plate) (ontop ?c ?p))))"


def test_atoms_read_bddl_and_scene_names_of_each_relation() -> None:
    assert parse_formula("(ontop cup plate)") == Atom("ontop", "on", ("cup", "plate"))
    assert parse_formula("(on cup plate)") == Atom("on", "on", ("cup", "plate"))
    assert parse_formula("(inside lid pot)").relation == "in"
    assert parse_formula("(in lid pot)").relation == "in"
    for name in ("under", "nextto", "inroom"):
        assert parse_formula(f"({name} a b)") == Atom(name, name, ("a", "b"))
    assert parse_formula("(open fridge)") == Atom("open", "open", ("fridge",))
    assert parse_formula("(toggled_on stove)") == Atom("toggled_on", "toggled_on", ("stove",))
    assert parse_formula("(ONTOP a b)").relation == "on"  # case of the head is free


def test_connectives() -> None:
    a, b = Atom("on", "on", ("a", "t")), Atom("on", "on", ("b", "t"))
    assert parse_formula("(and (on a t) (on b t))") == Junction("and", (a, b))
    assert parse_formula("(or (on a t) (on b t))") == Junction("or", (a, b))
    assert parse_formula("(and)") == Junction("and", ())
    assert parse_formula("(not (on a t))") == Not(a)
    assert parse_formula("(imply (on a t) (on b t))") == Imply(a, b)


def test_quantifiers_bind_variables_over_kinds() -> None:
    f = parse_formula(NO_CUP_ON_A_PLATE)
    assert f == Quantified("forall", Param("?c", "cup"), Not(Quantified(
        "exists", Param("?p", "plate"), Atom("ontop", "on", ("?c", "?p")))))
    # several variables in one list read as nested quantifiers
    assert parse_formula("(exists (?c - cup ?p - plate) (on ?c ?p))") == Quantified(
        "exists", Param("?c", "cup"), Quantified("exists", Param("?p", "plate"),
                                                 Atom("on", "on", ("?c", "?p"))))
    assert parse_formula("(forn (2) (?c - cup) (on ?c t))") == Quantified(
        "forn", Param("?c", "cup"), Atom("on", "on", ("?c", "t")), 2)
    assert parse_formula("(forpairs (?l - lid) (?p - pot) (inside ?l ?p))") == Pairs(
        "forpairs", Param("?l", "lid"), Param("?p", "pot"), Atom("inside", "in", ("?l", "?p")))
    assert parse_formula("(fornpairs (3) (?l - lid) (?p - pot) (inside ?l ?p))").count == 3


def test_bddl_sections_synsets_and_comments() -> None:
    text = """(:goal ; the activity's goal
        (forall (?c - cup.n.01) (ontop ?c table.n.02_1)))"""
    f = parse_formula(text)
    assert f == Quantified("forall", Param("?c", "cup"), Atom("ontop", "on",
                                                              ("?c", "table.n.02_1")))
    assert constants(f) == ({"table.n.02_1"}, {"cup"})


def test_an_unbound_question_mark_name_is_an_object_as_in_bddl() -> None:
    f = parse_formula("(forall (?boot.n.01 - boot.n.01) (ontop ?boot.n.01 ?floor.n.01_2))")
    assert f == Quantified("forall", Param("?boot.n.01", "boot"),
                           Atom("ontop", "on", ("?boot.n.01", "floor.n.01_2")))
    assert constants(parse_formula("(on ?x b)")) == ({"x", "b"}, set())


def test_show_writes_the_formula_back_with_objects_filled_in() -> None:
    f = parse_formula(NO_CUP_ON_A_PLATE)
    assert show(f) == NO_CUP_ON_A_PLATE
    assert isinstance(f, Quantified)
    assert show(f.body, {"?c": "cup_1"}) == "(not (exists (?p - plate) (ontop cup_1 ?p)))"
    assert show(parse_formula("(fornpairs (1) (?l - lid) (?p - pot) (in ?l ?p))")) == \
        "(fornpairs (1) (?l - lid) (?p - pot) (in ?l ?p))"
    assert parse_formula(show(f)) == f


def test_text_starting_with_a_parenthesis_is_a_formula() -> None:
    assert looks_like_formula("  (on a b)") and not looks_like_formula("cup on plate")
    assert looks_like_formula("; a comment\n  ; another\n(on a b)")
    assert not looks_like_formula("; a comment only")


@pytest.mark.parametrize(("text", "at", "words", "fix"), [
    ("", 1, "empty", "write one"),
    ("cup on plate", 1, "expected '('", "a formula starts with '('"),
    ("(and (on a b)", 14, "1 parenthesis(es) open", "close it with )"),
    ("(on a b))", 9, "a ')' closes nothing", "remove it"),
    ("(on a b) (on c d)", 10, "text after the end", "join several with (and"),
    ("(sliced egg)", 2, "'sliced' is not a connective", "ontop"),
    ("(on a)", 2, "takes 2 term(s), got 1", "(on cup plate)"),
    ("(open a b)", 2, "takes 1 term(s), got 2", "(open fridge)"),
    ("(forall (?c cup) (on ?c t))", 13, "expected '-', found 'cup'", "(?c - kind)"),
    ("(forall (c - cup) (on c t))", 10, "'c' is not a variable", "starts with '?'"),
    ("(forall (?c - cup) (exists (?c - plate) (on ?c t)))", 29, "already bound",
     "another name"),
    ("(forn (two) (?c - cup) (on ?c t))", 8, "not a whole number", "(2)"),
    ("(forn (2) (?c - cup ?d - cup) (on ?c t))", 21, "expected ')'", "one variable here"),
    ("(on a! b)", 5, "not an object id or a variable", "scene id"),
    ("((on a b))", 2, "expected a connective", "(and ...)"),
    ("(forall (?c - cup) (on ?c t)", 29, "parenthesis(es) open", "close it"),
])
def test_every_error_names_the_character_and_the_fix(text: str, at: int, words: str,
                                                      fix: str) -> None:
    with pytest.raises(GoalError) as err:
        parse_formula(text)
    assert err.value.field == "formula"
    assert err.value.message.startswith(f"character {at}:"), err.value.message
    assert words in err.value.message
    assert err.value.fix is not None and fix in err.value.fix


def test_size_depth_and_parts_are_bounded() -> None:
    with pytest.raises(GoalError, match=f"more than {MAX_FORMULA_CHARS}"):
        parse_formula("(and " + "(on a b) " * 3000 + ")")
    with pytest.raises(GoalError, match=f"nested deeper than {MAX_DEPTH}"):
        parse_formula("(not " * (MAX_DEPTH + 1) + "(on a b)" + ")" * (MAX_DEPTH + 1))
    parse_formula("(not " * (MAX_DEPTH - 1) + "(on a b)" + ")" * (MAX_DEPTH - 1))
    with pytest.raises(GoalError, match=f"more than {MAX_PARTS} parts"):
        parse_formula("(and" + " (on a b)" * MAX_PARTS + ")")


@pytest.mark.parametrize("hostile", [
    "(" * 19_000,
    ")" * 19_000,
    "(and" + " (on a b" * 2000,
    "(not " * 4000,
    "(on " + "a" * 19_000 + " b)",
    "(forall (?c - cup) " + "?c " * 6000 + ")",
    "(and " + "(on a b) " * 1999 + "(nope x))",
    "(and " + ";" * 19_000,
])
def test_hostile_inputs_fail_fast_with_a_structured_error(hostile: str) -> None:
    started = time.perf_counter()
    with pytest.raises(GoalError):
        parse_formula(hostile)
    assert time.perf_counter() - started < 5  # milliseconds in fact; generous on a busy machine


@pytest.mark.parametrize("text", [
    "(and " + " ".join(f"(on a{i} b{i})" for i in range(900)) + ")",
    "(not " * 30 + "(on a b)" + ")" * 30,
    "(forall (?c - cup) (or " + " ".join(f"(on ?c p{i})" for i in range(900)) + "))",
])
def test_parsing_reads_each_token_once(text: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """Linear by construction: every token is taken once and looked at a bounded number
    of times (counted, not timed, so a busy machine cannot make it flaky)."""
    calls = {"take": 0, "peek": 0}
    take, peek = formula_module._Parser.take, formula_module._Parser.peek

    def counted_take(self: formula_module._Parser) -> object:
        calls["take"] += 1
        return take(self)

    def counted_peek(self: formula_module._Parser) -> object:
        calls["peek"] += 1
        return peek(self)

    monkeypatch.setattr(formula_module._Parser, "take", counted_take)
    monkeypatch.setattr(formula_module._Parser, "peek", counted_peek)
    parse_formula.cache_clear()
    parse_formula(text)
    tokens = len(formula_module._tokens(text))
    assert calls["take"] <= tokens
    assert calls["peek"] <= 3 * tokens
