"""`validate --batch` goes on past hostile lines, and every output line is strict JSON."""

from __future__ import annotations

import json
import math
import shutil
import subprocess
import sys

from blocksworld_corpus import DATA
from pddl_corpus import PDDL_DATA


def strict(line: str):
    return json.loads(line, parse_constant=lambda name: (_ for _ in ()).throw(ValueError(name)))


def test_hostile_lines_get_error_lines_and_the_batch_goes_on(tmp_path):
    for name in ("planbench_domain.pddl", "planbench_instance.pddl", "planbench_plan.txt"):
        shutil.copy(DATA / name, tmp_path / name)
    shutil.copy(PDDL_DATA / "logistics_typed_domain.pddl", tmp_path / "log.pddl")
    (tmp_path / "deep.pddl").write_text("(define (domain x)\n" + "(" * 100_000 + ")" * 100_000)
    good = {"domain": "planbench_domain.pddl", "problem": "planbench_instance.pddl",
            "plan": "planbench_plan.txt"}
    lines = [
        "[" * 100_000 + "]" * 100_000,                      # nested brackets
        '{"id": ' + "9" * 5000 + ', "domain": "x"}',       # 5,000-digit integer
        '{"id": NaN, "domain": "x"}',                       # not JSON numbers
        '{"id": Infinity}',
        json.dumps({"id": 10 ** 30, **good}),               # id beyond 64 bits
        json.dumps({"id": {"nested": [1, 2]}, **good}),     # id that is not a scalar
        json.dumps({"id": "deep", **good, "domain": "deep.pddl"}),
        json.dumps({"id": "engine", **good, "engine": "quantum"}),
        json.dumps({"id": "strips", **good, "domain": "log.pddl"}),  # problem is not logistics
        json.dumps({"id": "ok", **good}),
        json.dumps({"id": 7, **good, "plan": "planbench_domain.pddl"}),
    ]
    (tmp_path / "b.jsonl").write_text("\n".join(lines) + "\n")
    r = subprocess.run([sys.executable, "-m", "verigraph", "validate", "--batch",
                        str(tmp_path / "b.jsonl"), "--no-progress", "--planbench"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 1 and "Traceback" not in r.stderr
    out = [strict(line) for line in r.stdout.splitlines()]
    assert [o["id"] for o in out] == ["line 1", "line 2", "line 3", "line 4", "line 5", "line 6",
                                      "deep", "engine", "strips", "ok", 7]
    by = {o["id"]: o for o in out}
    assert "nests too deep" in by["line 1"]["message"]
    assert "strict JSON" in by["line 2"]["message"] and "NaN" in by["line 3"]["message"]
    assert by["line 5"]["field"] == by["line 6"]["field"] == "id"
    assert "deep on line 2" in by["deep"]["message"]
    assert by["engine"]["field"] == "engine"
    assert by["strips"]["ok"] is False and by["strips"]["error"] == "PddlInputError"
    assert by["ok"]["valid"] and by["ok"]["planbench"] == {"valid": True, "message":
                                                          "The above plan is valid."}
    # A plan file that holds no plan (here the domain) is invalid at its first line.
    assert by[7]["valid"] is False and by[7]["planbench"]["valid"] is False
    assert by[7]["violations"][0]["step"] == 1
    assert all(not (isinstance(v, float) and not math.isfinite(v)) for o in out for v in o.values())


def test_a_batch_of_only_valid_items_exits_zero(tmp_path):
    item = {"domain": str(DATA / "planbench_domain.pddl"),
            "problem": str(DATA / "planbench_instance.pddl"),
            "plan": str(DATA / "planbench_plan.txt")}
    (tmp_path / "b.jsonl").write_text("\n".join(json.dumps({"id": i, **item}) for i in range(3)))
    r = subprocess.run([sys.executable, "-m", "verigraph", "validate", "--batch",
                        str(tmp_path / "b.jsonl"), "--no-progress"], capture_output=True,
                       text=True, timeout=120)
    assert r.returncode == 0 and len(r.stdout.splitlines()) == 3
