"""Inputs a clumsy user or an attacker gives the environment: unreadable actions, bad reset
options, damaged bytes in its files, edited task fields, and resumes under other
settings. Each is a malformed step or a clear error, never a traceback or a wrong run."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from optional import require

require("gymnasium", "pip install 'verigraph-mcp[env]'")

from verigraph.env import VeriGraphEnv, build_tasks, read_jsonl, write_jsonl  # noqa: E402
from verigraph.env.dataset import load_tasks  # noqa: E402
from verigraph.env.rollout import RolloutJob, run_rollouts  # noqa: E402
from verigraph.env.trajectory import TrajectoryFile, read_lines, replay  # noqa: E402
from verigraph.errors import VeriGraphError  # noqa: E402

DEEP = "[" * 1000 + "]" * 1000
LONG_NUMBER = '{"actions": [' + "9" * 4301 + "]}"


def test_unreadable_actions_are_malformed_steps_and_the_counter_stays_true() -> None:
    tasks = build_tasks("blocks", 2)
    env = VeriGraphEnv(tasks=tasks, rubric={"refusal": 0.25}, threshold=10)
    env.reset(options={"task": 0})
    answers = [DEEP, LONG_NUMBER, '{"actions": [' + "[" * 990 + "]" * 990 + "]}",
               "{" * 5000]
    for number, answer in enumerate(answers, 1):
        _, reward, terminated, truncated, info = env.step(answer)
        assert info["verdict"] == "malformed", answer[:20]
        assert reward == -0.25 and not terminated and not truncated
        assert info["step"] == env.steps == number and info["tau"] == number
        assert "write it as" in (info["feedback"] or "")
    assert "nests too deeply" in env.step(DEEP)[4]["feedback"]
    # a number too long to read (4,301 digits) does not fit the 4,096-character space
    assert "more than the 4,096 an action may hold" in env.step(LONG_NUMBER)[4]["feedback"]
    # the episode goes on: a readable action is still executed
    _, _, _, _, info = env.step("move(no_such_object, on, table)")
    assert info["verdict"] == "violation" and info["step"] == len(answers) + 3
    env.close()


def test_an_action_past_the_action_space_is_refused_unread() -> None:
    """20 KB of `move` + spaces took 2.2 s to parse; the action space holds 4,096
    characters, so a longer answer is a malformed step naming the limit, at once."""
    env = VeriGraphEnv(tasks=build_tasks("blocks", 1), rubric={"refusal": 0.25})
    env.reset(options={"task": 0})
    assert env.action_space.max_length == 4096
    for answer in ("move" + " " * 20_000 + "x", "move(a, on, b)\n" * 300, "x" * 4097):
        _, reward, terminated, _, info = env.step(answer)
        assert info["verdict"] == "malformed" and reward == -0.25 and not terminated
        assert f"the answer is {len(answer):,} characters, more than the 4,096" in info["feedback"]
    _, _, _, _, info = env.step("move" + " " * 4000 + "x")  # inside the space: read
    assert info["verdict"] == "malformed" and "could not read the answer" in info["feedback"]
    assert env.steps == 4
    env.close()


def test_bad_reset_options_are_clear_errors_and_change_nothing() -> None:
    tasks = build_tasks("blocks", 2)
    env = VeriGraphEnv(tasks=tasks)
    env.reset(options={"task": 1})
    env.step("move(no_such_object, on, table)")
    before = (env.task, env.steps, env.episode_id, env.observation)
    for options, value in (("abc", "'abc'"), (["task"], "['task']"), ({"taks": 0}, "taks")):
        with pytest.raises(VeriGraphError) as err:
            env.reset(options=options)  # type: ignore[arg-type]
        assert err.value.field == "options" and err.value.value == value
        assert err.value.fix
    assert (env.task, env.steps, env.episode_id, env.observation) == before
    assert env.step("move(no_such_object, on, table)")[4]["step"] == 2  # still running
    env.close()


def test_a_byte_that_is_not_utf8_names_the_file_and_line(tmp_path: Path) -> None:
    tasks = build_tasks("tangram", 2)
    path = tmp_path / "tasks.jsonl"
    write_jsonl(tasks, path)
    data = path.read_bytes().split(b"\n")
    data[1] = data[1][:10] + b"\xff" + data[1][10:]
    path.write_bytes(b"\n".join(data))
    with pytest.raises(VeriGraphError) as err:
        read_jsonl(path)
    assert err.value.field == "line 2" and f"{path}:2" in err.value.message
    assert "0xff" in err.value.message and "column 11" in err.value.message
    with pytest.raises(VeriGraphError):
        VeriGraphEnv(tasks=str(path))
    run = tmp_path / "run.jsonl"
    run_rollouts([RolloutJob(task_id=tasks[0].task_id)], {"tasks": tasks}, trajectories=run)
    count = run.read_bytes().count(b"\n")
    run.write_bytes(run.read_bytes() + b'{"kind": "reset\xff"}\n')
    for read in (lambda: read_lines(run), lambda: TrajectoryFile(run).complete()):
        with pytest.raises(VeriGraphError) as err:
            read()
        assert err.value.field == f"line {count + 1}" and str(run) in err.value.message


def test_every_field_that_reaches_a_prompt_or_a_score_is_hash_checked(tmp_path: Path
                                                                      ) -> None:
    language = next(t for t in build_tasks("blocks", 10) if t.group == "language")
    assert not language.show_goal_graph
    for field, value in (("show_goal_graph", True), ("optimal_length", 1),
                         ("instruction", "put every block on the table"),
                         ("objects", 99), ("kind", "other"), ("record_hash", "0" * 64)):
        row = language.model_dump()
        row[field] = value
        path = tmp_path / f"{field}.jsonl"
        path.write_text(json.dumps(row) + "\n")
        with pytest.raises(VeriGraphError) as err:
            read_jsonl(path)
        assert "record_hash" in err.value.message and err.value.field == "line 1", field
        with pytest.raises(VeriGraphError) as err:
            load_tasks([row])
        assert "record_hash" in err.value.message, field
    # a record handed to reset() is checked too, and so is a trajectory's reset line
    env = VeriGraphEnv(tasks=[language])
    shown = language.model_copy(update={"show_goal_graph": True})
    with pytest.raises(VeriGraphError) as err:
        env.reset(options={"task": shown})
    assert "record_hash" in err.value.message
    run = tmp_path / "run.jsonl"
    run_rollouts([RolloutJob(task_id=language.task_id, policy="refuse")],
                 {"tasks": [language], "threshold": 1}, trajectories=run)
    lines = run.read_text().splitlines()
    row = json.loads(lines[0])
    row["task"]["show_goal_graph"] = True
    run.write_text("\n".join([json.dumps(row), *lines[1:]]) + "\n")
    with pytest.raises(VeriGraphError) as err:
        replay(read_lines(run), env)
    assert "record_hash" in err.value.message
    env.close()
    renamed = language.model_copy(update={"task_id": "renamed/0/0"})
    assert load_tasks([renamed]) == [renamed]  # the id is not part of the task
    broken = {**language.model_dump(), "load": {"graph": {"nodes": 1, "edges": []}}}
    with pytest.raises(VeriGraphError) as err:
        load_tasks([broken])
    assert "cannot be read" in err.value.message


def test_a_resume_under_other_settings_is_refused_and_the_file_kept(tmp_path: Path) -> None:
    tasks = build_tasks("blocks", 2)[:2]
    jobs = [RolloutJob(task_id=t.task_id) for t in tasks]
    path = tmp_path / "run.jsonl"
    short = run_rollouts(jobs, {"tasks": tasks, "max_steps": 1}, trajectories=path)
    assert not any(r.success for r in short)
    written = path.read_bytes()
    for kwargs, named in (({"tasks": tasks}, "max_steps 1 (now 40)"),
                          ({"tasks": tasks, "max_steps": 1, "k": 1}, "k 3 (now 1)"),
                          ({"tasks": tasks, "max_steps": 1, "threshold": 2}, "threshold"),
                          ({"tasks": tasks, "max_steps": 1, "feedback": "none"}, "feedback"),
                          ({"tasks": tasks, "max_steps": 1, "rubric": {"refusal": 1.0}},
                           "rubric")):
        with pytest.raises(VeriGraphError) as err:
            run_rollouts(jobs, kwargs, trajectories=path)
        assert named in err.value.message and err.value.field == "trajectories"
        assert "new trajectory file" in (err.value.fix or "")
        assert path.read_bytes() == written  # nothing cut, nothing appended
    same = run_rollouts(jobs, {"tasks": tasks, "max_steps": 1}, trajectories=path)
    assert [r.worker for r in same] == [None, None]  # the same settings resume as before
    fresh = run_rollouts(jobs, {"tasks": tasks})
    assert all(r.success for r in fresh)  # what the refused resume would have hidden
    # a task of the same id whose record changed is not the task the file played
    edited = tasks[0].model_copy(update={"optimal_length": tasks[0].optimal_length + 1})
    edited = edited.model_copy(update={"record_hash": edited.expected_record_hash()})
    with pytest.raises(VeriGraphError) as err:
        run_rollouts(jobs, {"tasks": [edited, tasks[1]], "max_steps": 1}, trajectories=path)
    assert tasks[0].task_id in err.value.message and "record hash" in err.value.message
    # a file whose reset lines lack their settings cannot be checked, so it is refused
    bare = tmp_path / "bare.jsonl"
    rows = [json.loads(line) for line in written.decode().splitlines()]
    bare.write_text("".join(json.dumps({k: v for k, v in row.items() if k != "settings"})
                            + "\n" for row in rows))
    with pytest.raises(VeriGraphError) as err:
        run_rollouts(jobs, {"tasks": tasks, "max_steps": 1}, trajectories=bare)
    assert "without its settings" in err.value.message
    # and a replay under other settings says so
    env = VeriGraphEnv(tasks=tasks)
    report = replay(read_lines(path), env)
    assert any("max_steps 1 (now 40)" in m for m in report.mismatches)
    env.close()


def test_noise_levels_that_print_alike_are_different_episodes() -> None:
    a = RolloutJob(task_id="t", policy="noisy", noise=0.3)
    b = RolloutJob(task_id="t", policy="noisy", noise=0.30000001)
    assert a.episode() == "t#noisy~0.3:0@0" and a.episode() != b.episode()
