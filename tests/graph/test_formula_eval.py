"""Goal formulas evaluated over scenes: truth tables, every counterexample, the witnesses
of exists and the missing ones said plainly, empty kinds, states, and the name check."""

from __future__ import annotations

import itertools

import pytest

from verigraph.errors import GoalError
from verigraph.graph.dictionary import load_dictionary
from verigraph.graph.formula import parse_formula
from verigraph.graph.formula_eval import (
    LINE_CHARS,
    MAX_GROUND,
    MAX_KEPT,
    MAX_LISTED,
    Facts,
    check_names,
    evaluate,
    facts_of,
    holds,
    node_state,
)
from verigraph.graph.goal import Goal, GraphDiff, check_goal
from verigraph.graph.model import SceneGraph
from verigraph.graph.state import WorldState

pytestmark = pytest.mark.fast
NO_CUP_ON_A_PLATE = "(forall (?c - cup) (not (exists (?p - plate) (ontop ?c ?p))))"


def scene(edges: list[tuple[str, str, str]], extra: list[tuple[str, str]] = ()  # type: ignore[assignment]
          ) -> WorldState:
    """A tableware scene: a table, two plates, two cups, and `extra` (id, label) nodes."""
    nodes = [("table", "table"), ("plate_1", "plate"), ("plate_2", "plate"),
             ("cup_1", "cup"), ("cup_2", "cup"), *extra]
    return WorldState.from_graph(SceneGraph.model_validate({
        "nodes": [{"id": i, "label": label} for i, label in nodes],
        "edges": [{"source": s, "relation": r, "target": t} for s, r, t in edges],
        "dictionary": "tableware"}))


ON_TABLE = [("plate_1", "on", "table"), ("plate_2", "on", "table")]


def facts(edges: list[tuple[str, str, str]]) -> Facts:
    return facts_of(scene(ON_TABLE + edges))


def truth(text: str, edges: list[tuple[str, str, str]]) -> bool:
    return holds(parse_formula(text), facts(edges))


@pytest.mark.parametrize(("a", "b"), list(itertools.product([False, True], repeat=2)))
def test_connectives_follow_their_truth_tables(a: bool, b: bool) -> None:
    edges = [("cup_1", "on", "plate_1" if a else "table"),
             ("cup_2", "on", "plate_2" if b else "table")]
    A, B = "(ontop cup_1 plate_1)", "(ontop cup_2 plate_2)"
    assert truth(A, edges) is a and truth(B, edges) is b
    assert truth(f"(not {A})", edges) is (not a)
    assert truth(f"(and {A} {B})", edges) is (a and b)
    assert truth(f"(or {A} {B})", edges) is (a or b)
    assert truth(f"(imply {A} {B})", edges) is ((not a) or b)
    assert truth("(and)", edges) and not truth("(or)", edges)


def test_quantifiers_range_over_the_kind() -> None:
    one_on_a_plate = [("cup_1", "on", "plate_1"), ("cup_2", "on", "table")]
    both = [("cup_1", "on", "plate_1"), ("cup_2", "on", "plate_2")]
    none = [("cup_1", "on", "table"), ("cup_2", "on", "table")]
    on_some_plate = "(forall (?c - cup) (exists (?p - plate) (ontop ?c ?p)))"
    assert not truth(on_some_plate, one_on_a_plate) and truth(on_some_plate, both)
    assert truth(NO_CUP_ON_A_PLATE, none) and not truth(NO_CUP_ON_A_PLATE, one_on_a_plate)
    for n, expected in ((0, False), (1, True), (2, False)):
        assert truth(f"(forn ({n}) (?c - cup) (on ?c table))", one_on_a_plate) is expected
    assert truth("(forn (0) (?c - cup) (on ?c table))", both)
    # a kind word reads as the dictionary reads labels (here a plural)
    assert truth("(forall (?c - cups) (exists (?p - plate) (ontop ?c ?p)))", both)


def test_empty_kinds_exists_false_forall_true() -> None:
    edges = [("cup_1", "on", "table"), ("cup_2", "on", "table")]
    assert not truth("(exists (?b - bowl) (on ?b table))", edges)
    assert truth("(forall (?b - bowl) (on ?b table))", edges)
    assert truth("(forn (0) (?b - bowl) (on ?b table))", edges)
    assert truth("(forpairs (?b - bowl) (?c - cup) (in ?c ?b))", edges)  # 0 pairs needed
    result = evaluate(parse_formula("(exists (?b - bowl) (on ?b table))"), facts(edges))
    assert result.counterexamples == ["(exists (?b - bowl) (on ?b table)) fails: missing: "
                                      "there is no bowl in the scene"]


def test_pairs_need_a_one_to_one_matching_of_distinct_objects() -> None:
    # cup_1 fits plate_1 and plate_2, cup_2 only plate_1: a matching exists
    both_ok = [("cup_1", "on", "plate_2"), ("cup_2", "on", "plate_1")]
    assert truth("(forpairs (?c - cup) (?p - plate) (ontop ?c ?p))", both_ok)
    crowded = [("cup_1", "on", "plate_1"), ("cup_2", "on", "plate_1")]
    pairs = "(forpairs (?c - cup) (?p - plate) (ontop ?c ?p))"
    assert not truth(pairs, crowded)  # both cups on one plate: only one pair
    assert truth("(fornpairs (1) (?c - cup) (?p - plate) (ontop ?c ?p))", crowded)
    assert not truth("(fornpairs (2) (?c - cup) (?p - plate) (ontop ?c ?p))", crowded)
    result = evaluate(parse_formula(pairs), facts(crowded))
    assert result.counterexamples == [
        f"{pairs} fails: only 1 of 2 one-to-one pairs (cup with plate) hold: cup_1 with "
        "plate_1; unpaired: cup_2, plate_2"]
    # a pair is two distinct objects, even of one kind
    assert not truth("(exists (?p - plate) (forpairs (?a - plate) (?b - plate) (on ?a ?b)))",
                     crowded)


def test_every_counterexample_is_listed_with_its_part_and_objects() -> None:
    extra = [(f"cup_{i}", "cup") for i in range(3, 8)]
    where = {1: "plate_1", 3: "plate_1", 5: "plate_2", 7: "plate_2"}
    s = scene(ON_TABLE + [(f"cup_{i}", "on", where.get(i, "table")) for i in range(1, 8)],
              extra)
    result = evaluate(parse_formula(NO_CUP_ON_A_PLATE), facts_of(s))
    assert not result.satisfied and result.counterexample_count == 4
    assert result.counterexamples == [
        f"(not (exists (?p - plate) (ontop cup_{i} ?p))) fails: cup_{i} is on {where[i]}"
        for i in (1, 3, 5, 7)]
    text = check_goal(s, Goal(formula=NO_CUP_ON_A_PLATE)).summary()
    assert text.startswith("goal not reached: formula fails (4 counterexamples): ")
    assert all(f"cup_{i} is on {where[i]}" in text for i in (1, 3, 5, 7))


def test_long_lists_end_with_and_n_more() -> None:
    extra = [(f"cup_{i}", "cup") for i in range(3, 16)]
    s = scene(ON_TABLE + [(f"cup_{i}", "on", "table") for i in range(1, 16)], extra)
    result = evaluate(parse_formula("(forall (?c - cup) (ontop ?c plate_1))"), facts_of(s))
    assert result.counterexample_count == 15 and len(result.counterexamples) == 15
    lines = result.lines()
    assert len(lines) == MAX_LISTED + 1 and lines[-1] == f"... and {15 - MAX_LISTED} more"
    assert check_goal(s, Goal(formula="(forall (?c - cup) (ontop ?c plate_1))")).summary() \
        .endswith(f"; ... and {15 - MAX_LISTED} more")


def test_a_failing_exists_says_plainly_what_is_missing() -> None:
    edges = [("cup_1", "on", "table"), ("cup_2", "on", "plate_2")]
    f = "(exists (?p - plate) (ontop cup_1 ?p))"
    result = evaluate(parse_formula(f), facts(edges))
    assert result.counterexamples == [
        f"{f} fails: missing: no plate as ?p makes (ontop cup_1 ?p) hold; of the 2 "
        "plate(s): cup_1 is not on plate_1 (cup_1 is on table); cup_1 is not on plate_2 "
        "(cup_1 is on table)"]


def test_a_satisfied_exists_names_its_witnesses() -> None:
    edges = [("cup_1", "on", "plate_2"), ("cup_2", "on", "plate_2")]
    f = "(forall (?c - cup) (exists (?p - plate) (ontop ?c ?p)))"
    result = evaluate(parse_formula(f), facts(edges))
    assert result.satisfied and result.witness_count == 2
    assert result.witnesses == [
        "(exists (?p - plate) (ontop cup_1 ?p)) holds with ?p = plate_2",
        "(exists (?p - plate) (ontop cup_2 ?p)) holds with ?p = plate_2"]
    diff = check_goal(scene(ON_TABLE + edges), Goal(formula=f))
    assert diff.satisfied and diff.formula_detail == result.witnesses
    assert diff.summary() == "goal reached; " + "; ".join(result.witnesses)


def test_a_failing_formula_still_names_the_witnesses_of_its_parts_that_hold() -> None:
    edges = [("cup_1", "on", "plate_2"), ("cup_2", "on", "table")]
    f = "(forall (?c - cup) (exists (?p - plate) (ontop ?c ?p)))"
    result = evaluate(parse_formula(f), facts(edges))
    assert not result.satisfied and result.counterexample_count == 1
    assert result.witnesses == ["(exists (?p - plate) (ontop cup_1 ?p)) holds with ?p = plate_2"]
    assert result.kept() == result.counterexamples  # a diff carries the counterexamples


def test_negations_implications_and_counts_explain_themselves() -> None:
    edges = [("cup_1", "on", "plate_1"), ("cup_2", "on", "table")]
    cases = {
        "(imply (ontop cup_1 plate_1) (ontop cup_2 plate_2))":
            "cup_1 is on plate_1, but cup_2 is not on plate_2 (cup_2 is on table)",
        "(or (ontop cup_1 table) (ontop cup_2 plate_1))":
            "none holds: cup_1 is not on table (cup_1 is on plate_1) / cup_2 is not on "
            "plate_1 (cup_2 is on table)",
        "(forn (2) (?c - cup) (ontop ?c table))":
            "1 cup(s) satisfy it (cup_2); exactly 2 wanted",
        "(not (forall (?c - cup) (or (on ?c table) (on ?c plate_1))))":
            "every cup (cup_1, cup_2) satisfies it",
    }
    for text, why in cases.items():
        result = evaluate(parse_formula(text), facts(edges))
        assert result.counterexamples == [f"{text} fails: {why}"], text


def household() -> WorldState:
    """A kitchen with node states and rooms: an open fridge with the milk, a stove that is
    off, a lamp with no state (off by default), a box under the counter, a pot next to the
    sink, and a bedroom with nothing in it."""
    nodes = [("kitchen", "kitchen", {}), ("bedroom", "bedroom", {}),
             ("counter", "counter", {}), ("fridge", "fridge", {"open": True}),
             ("stove", "stove", {"toggled_on": False}), ("sink", "sink", {}),
             ("lamp", "lamp", {}), ("milk", "milk", {}), ("box", "box", {}),
             ("pot", "pot", {})]
    edges = [("counter", "inroom", "kitchen"), ("fridge", "inroom", "kitchen"),
             ("stove", "inroom", "kitchen"), ("sink", "inroom", "kitchen"),
             ("lamp", "on", "counter"), ("milk", "in", "fridge"), ("box", "under", "counter"),
             ("pot", "nextto", "sink")]
    return WorldState.from_graph(SceneGraph.model_validate({
        "nodes": [{"id": i, "label": label, **({"state": st} if st else {})}
                  for i, label, st in nodes],
        "edges": [{"source": s, "relation": r, "target": t} for s, r, t in edges],
        "dictionary": "household"}))


def test_states_read_through_one_accessor_and_default_to_false() -> None:
    state = household()
    assert node_state(state, "fridge") == {"open": True}
    assert node_state(state, "lamp") == {}  # no state set: off
    f = facts_of(state)
    assert holds(parse_formula("(open fridge)"), f)
    assert not holds(parse_formula("(toggled_on stove)"), f)
    assert not holds(parse_formula("(toggled_on lamp)"), f)
    assert holds(parse_formula("(not (exists (?x - stove) (toggled_on ?x)))"), f)
    result = evaluate(parse_formula("(and (toggled_on stove) (toggled_on lamp) (open box))"),
                      f)
    assert result.counterexamples == [
        "(toggled_on stove) fails: stove is off",
        "(toggled_on lamp) fails: lamp is off (no state given: that is the default)",
        "(open box) fails: box is closed (no state given: that is the default)"]
    state.set_state("lamp", "toggled_on", True)  # what toggle_on(lamp) leaves behind
    assert holds(parse_formula("(toggled_on lamp)"), facts_of(state))


def test_relations_are_read_by_name_rooms_follow_placements() -> None:
    f = facts_of(household())
    for text, expected in [("(under box counter)", True), ("(under counter box)", False),
                           ("(nextto pot sink)", True), ("(nextto sink pot)", True),
                           ("(nextto pot counter)", False),
                           ("(inroom counter kitchen)", True),
                           ("(inroom milk kitchen)", True),  # in the fridge, in the kitchen
                           ("(inroom pot kitchen)", True),  # next to the sink
                           ("(inroom milk bedroom)", False),
                           ("(forall (?r - room) (exists (?x - counter) (inroom ?x ?r)))",
                            False),  # the bedroom has no counter
                           ("(exists (?r - room) (inroom lamp ?r))", True)]:
        assert holds(parse_formula(text), f) is expected, text
    result = evaluate(parse_formula("(inroom milk bedroom)"), f)
    assert result.counterexamples == [
        "(inroom milk bedroom) fails: milk is not in room bedroom (milk is in fridge)"]


def test_inside_reads_where_an_object_is_and_ontop_its_direct_support() -> None:
    """`inside` holds anywhere within the container, down the placements (as BEHAVIOR's
    Inside); `ontop` only of the direct support (its OnTop needs contact)."""
    f = facts_of(WorldState.from_graph(SceneGraph.model_validate({
        "nodes": [{"id": i, "label": label} for i, label in [
            ("kitchen", "kitchen"), ("fridge", "fridge"), ("counter", "counter"),
            ("plate", "plate"), ("cheese", "cheese"), ("bowl", "bowl"), ("cup", "cup"),
            ("milk", "milk"), ("butter", "butter")]],
        "edges": [{"source": s, "relation": r, "target": t} for s, r, t in [
            ("fridge", "inroom", "kitchen"), ("counter", "inroom", "kitchen"),
            ("plate", "in", "fridge"), ("cheese", "on", "plate"), ("bowl", "on", "plate"),
            ("cup", "in", "bowl"), ("milk", "nextto", "plate"),
            ("butter", "on", "counter")]],
        "dictionary": "household"})))
    for text, expected in [("(inside cheese fridge)", True),  # on a plate in the fridge
                           ("(ontop cheese plate)", True), ("(ontop cheese fridge)", False),
                           ("(inside cup fridge)", True),  # in a bowl on a plate in it
                           ("(inside cup bowl)", True), ("(inside cup plate)", False),
                           ("(ontop cup plate)", False), ("(inside bowl fridge)", True),
                           ("(inside milk fridge)", True),  # beside the plate in it
                           ("(inside butter fridge)", False), ("(inside fridge fridge)", False),
                           ("(forall (?c - cup) (not (inside ?c fridge)))", False)]:
        assert holds(parse_formula(text), f) is expected, text
    assert evaluate(parse_formula("(forall (?c - cup) (not (inside ?c fridge)))"),
                    f).counterexamples == ["(not (inside cup fridge)) fails: cup is in fridge"]


def test_objects_placed_next_to_one_object_stand_next_to_each_other() -> None:
    state = household()  # the pot next to the sink
    state.set_support("box", "nextto", "sink")
    state.set_support("milk", "nextto", "pot")
    f = facts_of(state)
    for text, expected in [("(nextto box pot)", True), ("(nextto pot box)", True),
                           ("(nextto box sink)", True), ("(nextto milk pot)", True),
                           ("(nextto pot milk)", True),
                           ("(nextto milk sink)", False),  # beside the pot, not the sink
                           ("(nextto milk box)", False),  # next to different objects
                           ("(nextto box box)", False), ("(nextto sink sink)", False),
                           ("(and (nextto box pot) (nextto pot sink) (nextto box sink))",
                            True)]:  # three pairwise: two beside the third
        assert holds(parse_formula(text), f) is expected, text
    state.set_support("box", "under", "counter")  # moved away: no longer side by side
    assert not holds(parse_formula("(nextto box pot)"), facts_of(state))


def test_names_are_checked_against_the_scene_all_at_once() -> None:
    f = facts([("cup_1", "on", "table"), ("cup_2", "on", "table")])
    check_names(parse_formula("(forall (?b - bowl) (ontop ?b plate_1))"), f)  # a known kind
    with pytest.raises(GoalError) as err:
        check_names(parse_formula("(and (ontop cupp_1 plate_1) (forall (?x - cupz) "
                                  "(on ?x table)))"), f)
    assert err.value.message == (
        "the formula names what the scene does not have: object 'cupp_1' (did you mean "
        "cup_1?); kind 'cupz', known neither to the dictionary nor as a label of the scene "
        "(did you mean cup?)")
    assert err.value.fix is not None and "cup, plate, table" in err.value.fix
    with pytest.raises(GoalError, match=r"object 'q' \(a \?variable must be bound"):
        check_names(parse_formula("(forall (?c - cup) (ontop ?q table))"), f)


def test_formulas_that_ground_too_large_are_refused() -> None:
    extra = [(f"cup_{i}", "cup") for i in range(3, 61)]
    s = scene(ON_TABLE + [(f"cup_{i}", "on", "table") for i in range(1, 61)], extra)
    nested = "(forall (?a - cup) (forall (?b - cup) (forall (?c - cup) (on ?a table))))"
    assert MAX_GROUND < 60 ** 3
    with pytest.raises(GoalError, match="expands to 216000 instances"):
        check_names(parse_formula(nested), facts_of(s))


def test_goal_parse_reads_text_and_json_formulas() -> None:
    assert Goal.parse(NO_CUP_ON_A_PLATE).formula == NO_CUP_ON_A_PLATE
    assert Goal.parse({"formula": NO_CUP_ON_A_PLATE}).formula == NO_CUP_ON_A_PLATE
    with pytest.raises(GoalError, match="character 2:"):
        Goal.parse("(onn a b)")
    with pytest.raises(ValueError, match="character 2:"):
        Goal.model_validate({"formula": "(onn a b)"})


def test_a_thousand_counterexamples_are_kept_and_every_one_counted() -> None:
    cups = {f"cup_{i}": "cup" for i in range(1100)}
    f = Facts({**cups, "table": "table"}, [("on", c, "table") for c in cups], {},
              load_dictionary(None).resolve)
    result = evaluate(parse_formula("(forall (?c - cup) (inside ?c table))"), f)
    assert result.counterexample_count == 1100 and len(result.counterexamples) == MAX_KEPT
    diff = GraphDiff(satisfied=False, formula_detail=result.kept())
    assert diff.formula_detail[-1] == f"... and {1100 - MAX_KEPT} more"
    assert diff.formula_count() == 1100
    assert diff.summary().startswith("goal not reached: formula fails (1100 counterexamples)")
    assert diff.summary().endswith(f"; ... and {1100 - MAX_LISTED} more")


def test_each_line_is_bounded() -> None:
    cups = {f"cup_{i}": "cup" for i in range(40)}
    f = Facts({**cups, "table": "table", "tray": "tray"},
              [("on", c, "table") for c in cups], {}, load_dictionary(None).resolve)
    text = "(exists (?c - cup) (or (inside ?c tray) (ontop ?c tray) (under ?c tray)))"
    result = evaluate(parse_formula(text), f)
    assert result.counterexample_count == 1
    line = result.counterexamples[0]
    assert len(line) == LINE_CHARS and line.endswith("...")
    assert line.startswith(f"{text} fails: missing: no cup as ?c makes")
