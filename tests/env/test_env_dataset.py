"""Task datasets: hash-checked splits that never share a task, JSONL, difficulty knobs,
prompts without the ground-truth goal of language tasks, and a datasets.Dataset export."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from optional import require

require("gymnasium", "pip install 'verigraph-mcp[env]'")

from verigraph.env import (  # noqa: E402
    Task,
    VeriGraphEnv,
    build_tasks,
    check_disjoint,
    read_jsonl,
    select,
    split_tasks,
    write_jsonl,
)
from verigraph.env.dataset import (  # noqa: E402
    FAMILY_GROUPS,
    SUITE_PER_GROUP,
    split_of,
    suite_tasks,
)
from verigraph.env.export import prompt_rows, to_hf_dataset  # noqa: E402
from verigraph.errors import VeriGraphError  # noqa: E402
from verigraph.graph.model import SceneGraph  # noqa: E402
from verigraph.tasks.task import SUITE_VERSION, content_hash  # noqa: E402


@pytest.mark.parametrize("family", ["blocks", "kitchen", "tangram"])
def test_train_and_test_never_share_a_task(family: str) -> None:
    pool = suite_tasks(family)
    train, test = split_tasks(pool, "train"), split_tasks(pool, "test")
    assert train and test and len(train) + len(test) == len(pool)
    check_disjoint(train, test)
    assert not {t.content_hash for t in train} & {t.content_hash for t in test}
    # a split is a property of the task: a pool from another seed agrees on shared tasks
    other = build_tasks(family, 10, seed=1)
    where = {t.content_hash: split_of(t.content_hash) for t in pool}
    assert all(where[t.content_hash] == split_of(t.content_hash)
               for t in other if t.content_hash in where)
    assert all(split_of(t.content_hash) == ("test" if int(t.content_hash[:12], 16) < 0.2 * 16 ** 12
                             else "train") for t in other)
    # and the environment of each split holds exactly that split
    assert VeriGraphEnv(family, split="test").tasks == test
    assert VeriGraphEnv(family, split="train").tasks == train


def test_check_disjoint_catches_a_shared_task_even_under_another_id() -> None:
    pool = build_tasks("tangram", 10)
    copy = pool[0].model_copy(update={"task_id": "renamed/0/0"})
    with pytest.raises(VeriGraphError) as err:
        check_disjoint(pool[1:] + [copy], [pool[0]])
    assert err.value.field == "split" and "content hash" in (err.value.fix or "")


def test_the_hash_ignores_order_and_ids_but_not_the_scene() -> None:
    task = build_tasks("blocks", 5)[0]
    graph = SceneGraph.model_validate(task.load["graph"])
    shuffled = SceneGraph(nodes=graph.nodes[::-1], edges=graph.edges[::-1],
                          dictionary=graph.dictionary)
    load = {"graph": shuffled.model_dump(mode="json", exclude_none=True)}
    assert content_hash(load, task.set_goal) == task.content_hash
    moved = shuffled.model_copy(update={"edges": shuffled.edges[1:]})
    assert content_hash({"graph": moved.model_dump(mode="json")}, task.set_goal) \
        != task.content_hash


def test_jsonl_round_trip_and_a_tampered_line_is_refused(tmp_path: Path) -> None:
    pool = build_tasks("blocks", 6)
    path = tmp_path / "blocks.jsonl"
    assert write_jsonl(pool, path) == len(pool)
    assert read_jsonl(path) == pool
    lines = path.read_text().splitlines()
    row = json.loads(lines[2])
    row["optimal_length"] = 99  # metadata only: still the same task
    row["load"]["graph"]["edges"] = row["load"]["graph"]["edges"][1:]  # the scene: not
    lines[2] = json.dumps(row)
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(VeriGraphError) as err:
        read_jsonl(path)
    assert err.value.field == "line 3" and "content_hash" in err.value.message
    path.write_text(lines[0] + "\n{\"task_id\": 1}\n")
    with pytest.raises(VeriGraphError) as err:
        read_jsonl(path)
    assert err.value.field == "line 2"
    with pytest.raises(VeriGraphError) as err:
        VeriGraphEnv(tasks=str(tmp_path / "missing.jsonl"))
    assert err.value.field == "path"


def test_difficulty_knobs_select_by_length_objects_family_and_group() -> None:
    pool = build_tasks("blocks", 20)
    hard = select(pool, min_optimal=6)
    assert hard and all(t.optimal_length >= 6 for t in hard)
    small = select(pool, max_objects=5, groups=["stacking"])
    assert small and all(t.objects <= 5 and t.group == "stacking" for t in small)
    assert select(pool, family="kitchen") == []
    assert {t.group for t in pool} == {"stacking", "language", "ref_image_blocks"}
    assert {t.family for t in build_tasks("kitchen", 5)} == {"kitchen"}
    env = VeriGraphEnv(tasks=hard)
    assert all(env.reset(seed=s)[1]["optimal_length"] >= 6 for s in range(5))
    env.close()
    with pytest.raises(VeriGraphError):
        build_tasks("warehouse")


def test_no_language_prompt_shows_its_ground_truth_goal() -> None:
    records = [t for t in build_tasks("blocks", 40) if t.group == "language"]
    assert len(records) >= 30 and all(not t.show_goal_graph for t in records)
    env = VeriGraphEnv(tasks=records)
    checked = 0
    for record in records:
        obs, info = env.reset(options={"task": record})
        assert record.set_goal is not None and record.instruction
        goal = SceneGraph.model_validate(record.set_goal["graph"])
        start = set(SceneGraph.model_validate(record.load["graph"]).sentences())
        hidden = [s for s in goal.sentences() if s not in start]  # what the goal adds
        assert hidden, record.task_id
        goal_section = obs.split("## Goal", 1)[1].split("## Actions", 1)[0]
        assert goal_section.strip() == f"Instruction: {record.instruction}"
        for sentence in hidden:
            assert sentence not in obs, (record.task_id, sentence)
        # after a step the prompt still hides it
        obs, *_ = env.step("move(no_such_object, on, table)")
        assert not any(sentence in obs for sentence in hidden)
        checked += 1
    assert checked == len(records)
    env.close()


def test_rows_and_a_datasets_dataset_carry_the_prompt_and_the_task() -> None:
    datasets = require("datasets", "pip install datasets")
    pool = build_tasks("tangram", 8)
    rows = prompt_rows(pool)
    assert [r["task_id"] for r in rows] == [t.task_id for t in pool]
    assert all(r["prompt"][0]["content"].startswith("You are planning") for r in rows)
    assert {r["split"] for r in rows} <= {"train", "test"}
    assert Task.model_validate_json(rows[0]["info"]) == pool[0]
    ds = to_hf_dataset(pool)
    assert isinstance(ds, datasets.Dataset) and ds.num_rows == len(pool)
    assert ds[3]["optimal_length"] == pool[3].optimal_length
    assert ds[3]["prompt"] == rows[3]["prompt"]


def test_a_task_given_directly_is_checked_against_its_hash_too() -> None:
    task = build_tasks("kitchen", 3)[0]
    edited = task.model_dump()
    edited["set_goal"] = {**edited["set_goal"], "instruction": "anything"}
    env = VeriGraphEnv(tasks=[task])
    with pytest.raises(VeriGraphError) as err:
        env.reset(options={"task": edited})
    assert err.value.field == "tasks[0]" and "content_hash" in err.value.message
    with pytest.raises(VeriGraphError) as err:
        VeriGraphEnv(tasks=[{"task_id": "x"}])
    assert err.value.field == "tasks[0]"
    assert env.reset(options={"task": task.model_dump()})[1]["task_id"] == task.task_id
    env.close()


@pytest.mark.parametrize("family", ["blocks", "kitchen", "tangram"])
def test_the_bundled_suites_are_whole_versioned_and_hash_checked(family: str) -> None:
    bundled = suite_tasks(family)  # read_jsonl recomputes every content hash
    groups = FAMILY_GROUPS[family]  # type: ignore[index]
    assert {t.group for t in bundled} == set(groups)
    assert all(t.suite_version == SUITE_VERSION and t.family == family for t in bundled)
    assert len({t.content_hash for t in bundled}) == len(bundled)
    for group in groups:  # SUITE_PER_GROUP draws per group, repeated draws kept once
        drawn = [t for t in bundled if t.group == group]
        assert 0.8 * SUITE_PER_GROUP <= len(drawn) <= SUITE_PER_GROUP
    env = VeriGraphEnv(family)
    assert env.tasks == split_tasks(bundled, "train")
    env.close()
