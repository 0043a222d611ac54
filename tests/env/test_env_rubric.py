"""The reward rubric on hand-made cases, and on real episodes through the environment."""

from __future__ import annotations

import pytest

from optional import require

require("gymnasium", "pip install 'verigraph-mcp[env]'")

from verigraph.env import Rubric, StepOutcome, VeriGraphEnv, score  # noqa: E402
from verigraph.env.rollout import REFUSED_ACTION, make_policy  # noqa: E402
from verigraph.errors import VeriGraphError  # noqa: E402


def outcome(verdict: str = "clean", before: int | None = 4, after: int | None = 4,
            start: int | None = 4, success: bool = False, moves: int = 0,
            optimal: int | None = 4) -> StepOutcome:
    return StepOutcome(verdict=verdict, distance_before=before,  # type: ignore[arg-type]
                       distance_after=after, distance_start=start, success=success,
                       moves=moves, optimal_length=optimal)


def test_the_default_rubric_pays_one_on_success_and_nothing_else() -> None:
    rubric = Rubric()
    assert score(rubric, outcome(success=True, after=0, moves=9)) == (1.0, {"success": 1.0})
    assert score(rubric, outcome(before=4, after=2)) == (0.0, {})
    assert score(rubric, outcome(verdict="violation")) == (0.0, {})


def test_each_shaping_term_on_hand_made_cases() -> None:
    rubric = Rubric(success=1.0, progress=0.5, refusal=0.1, efficiency=0.2)
    # two of four goal edges fixed in one step: 0.5 * 2 / 4
    assert score(rubric, outcome(before=4, after=2)) == (0.25, {"progress": 0.25})
    # undoing a move pays it back
    assert score(rubric, outcome(before=2, after=3)) == (-0.125, {"progress": -0.125})
    # a refused action: penalty only (the graph did not change)
    assert score(rubric, outcome(verdict="violation")) == (-0.1, {"refusal": -0.1})
    assert score(rubric, outcome(verdict="malformed"))[1] == {"refusal": -0.1}
    assert score(rubric, outcome(verdict="premature_done"))[1] == {"refusal": -0.1}
    # success in 5 moves when 4 were optimal, last step fixed the last edge
    total, terms = score(rubric, outcome(before=1, after=0, success=True, moves=5))
    assert terms == {"success": 1.0, "efficiency": pytest.approx(0.2 * 4 / 5),
                     "progress": 0.125}
    assert total == pytest.approx(1.0 + 0.16 + 0.125)
    # an optimal episode gets the whole efficiency weight, never more
    assert score(rubric, outcome(before=1, after=0, success=True, moves=3))[1][
        "efficiency"] == 0.2
    # no goal distance known: no progress term
    assert score(rubric, outcome(before=None, after=None, start=None)) == (0.0, {})


def test_rewards_in_a_real_episode_follow_the_rubric() -> None:
    rubric = Rubric(progress=1.0, refusal=0.25, efficiency=0.5)
    env = VeriGraphEnv("blocks", k=1, rubric=rubric)
    task = next(t for t in env.tasks if t.optimal_length >= 3)
    _, info = env.reset(options={"task": task.task_id})
    start = info["goal_distance"]
    _, reward, _, _, info = env.step(REFUSED_ACTION)
    assert reward == -0.25 and info["reward_terms"] == {"refusal": -0.25}
    oracle = make_policy("oracle")
    total, progress = -0.25, 0.0
    terminated = truncated = False
    while not (terminated or truncated):
        before = info["goal_distance"]
        _, reward, terminated, truncated, info = env.step(oracle(env, "", info))
        total += reward
        progress += info["reward_terms"].get("progress", 0.0)
        assert info["reward_terms"].get("progress", 0.0) == pytest.approx(
            (before - info["goal_distance"]) / start)
    assert terminated and info["success"]
    # progress telescopes to the whole weight; the solver's plan is optimal
    assert progress == pytest.approx(1.0)
    assert info["reward_terms"]["success"] == 1.0
    assert info["reward_terms"]["efficiency"] == 0.5
    assert info["episode_return"] == pytest.approx(total) == pytest.approx(-0.25 + 1 + 1 + 0.5)
    env.close()


def test_a_bad_rubric_weight_is_refused() -> None:
    with pytest.raises(ValueError, match="greater than or equal to 0"):
        Rubric(refusal=-1.0)
    with pytest.raises(VeriGraphError) as err:
        VeriGraphEnv("tangram", rubric={"bonus": 1.0})
    assert err.value.field == "rubric" and "bonus" in err.value.message
    with pytest.raises(VeriGraphError) as err:
        VeriGraphEnv("tangram", rubric={"refusal": -0.5})
    assert err.value.field == "rubric" and "refusal" in err.value.message
    with pytest.raises(VeriGraphError) as err:
        VeriGraphEnv("tangram", feedback="verbose")  # type: ignore[arg-type]
    assert err.value.field == "feedback"
