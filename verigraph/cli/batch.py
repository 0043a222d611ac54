"""`verigraph validate --batch FILE.jsonl`: many plans in one process.

Each input line is `{"id": ..., "domain": D, "problem": P, "plan": F}` or
`{"id": ..., "scene": S, "plan": F, "goal": G}` (goal optional; relative paths are read
from the batch file's folder). Each output line is `{"id": ..., <the --json report>}`,
or `{"id": ..., "ok": false, "error": ..., "message": ..., "field": ..., "fix": ...}`
for an item that cannot be validated; the batch always goes on. Exit 0 when every item
is valid, 1 when any is invalid or failed, 2 when the batch file itself cannot be read.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

from verigraph.cli.validating import (
    EXIT_BAD_INPUT,
    EXIT_NEGATIVE,
    EXIT_OK,
    pddl_report,
    scene_report,
)
from verigraph.errors import InputFileError, VeriGraphError

PDDL_KEYS = ("domain", "problem", "plan")
SCENE_KEYS = ("scene", "plan")


def _item_report(item: Any, base: Path, cache: dict[str, str]) -> dict[str, Any]:
    if not isinstance(item, dict):
        raise InputFileError("a batch item is a JSON object", field="item",
                             value=str(item)[:80], fix='write {"id": ..., "domain": ..., '
                             '"problem": ..., "plan": ...}')
    def path(key: str) -> Path:
        value = item.get(key)
        if not isinstance(value, str) or not value:
            raise InputFileError(f"'{key}' must be a file path", field=key, value=value,
                                 fix=f"give '{key}' as a path string")
        p = Path(value)
        return p if p.is_absolute() else base / p

    if "domain" in item or "problem" in item:
        return pddl_report(path("domain"), path("problem"), path("plan"), cache)
    if "scene" in item:
        goal = path("goal") if item.get("goal") is not None else None
        report = scene_report(path("scene"), path("plan"), goal)
        data: dict[str, Any] = report.model_dump(mode="json", exclude_none=True)
        return data
    raise InputFileError("a batch item needs domain/problem/plan or scene/plan[/goal]",
                         field="item", value=", ".join(map(str, item)),
                         fix='add "domain", "problem" and "plan", or "scene" and "plan"')


def run_batch(batch: Path, *, progress: bool = True) -> int:
    try:
        lines = batch.read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        print(f"error: batch: cannot read '{batch}': {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    base = batch.parent
    cache: dict[str, str] = {}
    all_valid = True
    out = sys.stdout
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=len(lines), unit="plan", file=sys.stderr, mininterval=0.5)
    for number, line in enumerate(lines, start=1):
        if bar is not None:
            bar.update(1)
        if not line.strip():
            continue
        item_id: Any = f"line {number}"
        try:
            try:
                item = json.loads(line)
            except json.JSONDecodeError as exc:
                raise InputFileError(f"line {number} is not JSON: {exc.msg}", field="item",
                                     value=line[:80], fix="one JSON object per line") from None
            if isinstance(item, dict) and "id" in item:
                item_id = item["id"]
            report = _item_report(item, base, cache)
            all_valid = all_valid and bool(report["valid"])
            out.write(json.dumps({"id": item_id, **report}) + "\n")
        except VeriGraphError as exc:
            all_valid = False
            out.write(json.dumps({"id": item_id, "ok": False, **exc.to_dict()}) + "\n")
    if bar is not None:
        bar.close()
    return EXIT_OK if all_valid else EXIT_NEGATIVE
