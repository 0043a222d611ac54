"""`verigraph validate --batch FILE.jsonl`: many plans in one process.

Each input line is `{"id": ..., "domain": D, "problem": P, "plan": F}` or
`{"id": ..., "scene": S, "plan": F, "goal": G}` (goal optional; relative paths are read
from the batch file's folder). Each output line is `{"id": ..., <the --json report>}`,
or `{"id": ..., "ok": false, "error": ..., "message": ..., "field": ..., "fix": ...}`
for an item that cannot be validated; the batch always goes on. A plan with a line that
is no action of the domain (wrong arity, `(no plan possible)`, `(1) (op a)`) can be
validated: its report is an invalid plan failing at that step, as VAL and PlanBench count
it; only files that cannot be read, or a domain or problem that cannot be used, are error
lines. Exit 0 when every item is valid, 1 when any is invalid or failed, 2 when the batch
file itself cannot be read.

Every output line is strict JSON whatever the input line held: a line nested too deep,
an integer too long to read, `NaN`/`Infinity`, a line that is not UTF-8, or an id that is
not a short string or a 64-bit integer gets an error line (id `"line N"`) and the batch
goes on. The file is read a line at a time, so memory stays bounded whatever its size (a
FIFO or an endless generator works): a line over MAX_LINE_BYTES gets an error line and
the rest of it is read and dropped in chunks; a line still unended after
MAX_SKIPPED_BYTES (`/dev/zero`) gets an error line and stops the batch (exit 2). PDDL items may
name `"engine"` (auto, blocksworld, strips; default `--engine`); `--planbench` adds
PlanBench task 3's verdict to every PDDL item's report.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any

from verigraph.cli.exits import EXIT_BAD_INPUT, EXIT_NEGATIVE, EXIT_OK
from verigraph.cli.validating import pddl_item_report, scene_report
from verigraph.errors import InputFileError, VeriGraphError
from verigraph.graph.bulk import LARGE_GRAPH_ITEMS, collector_paused

PDDL_KEYS = ("domain", "problem", "plan")
SCENE_KEYS = ("scene", "plan")
MAX_LINE_BYTES = 1 << 20  # an item is a few paths; a longer line is refused unread
MAX_SKIPPED_BYTES = 64 << 20  # an over-long line read (and dropped) this far stops the batch
MAX_ID_CHARS = 200
INT64 = 1 << 63


def _reject_constant(name: str) -> Any:
    raise ValueError(f"{name} is not a JSON number")


class _Stop(InputFileError):
    """A line that does not end within MAX_SKIPPED_BYTES: the batch stops after its error."""


def _lines(stream: IO[bytes]) -> Iterator[tuple[int, str | InputFileError]]:
    """(line number, text) per line of `stream`, or an error for a line that is too long
    or not UTF-8; at most MAX_LINE_BYTES + 1 bytes of the file are held at once."""
    number = 0
    while raw := stream.readline(MAX_LINE_BYTES + 1):
        number += 1
        if len(raw) > MAX_LINE_BYTES and not raw.endswith(b"\n"):
            fix = (f"keep batch lines under {MAX_LINE_BYTES:,} bytes (an item names files; "
                   "it does not hold them)")
            read = len(raw)
            while not raw.endswith(b"\n"):  # the rest of the line, dropped a chunk at a time
                raw = stream.readline(MAX_LINE_BYTES)
                read += len(raw)
                if not raw:
                    break
                if read > MAX_SKIPPED_BYTES:
                    yield number, _Stop(f"line {number} runs past {MAX_SKIPPED_BYTES:,} bytes "
                                        "without a line end; the batch stops here",
                                        field="item", value=None, fix=fix)
                    return
            yield number, InputFileError(f"line {number} is {read:,} bytes long, more than "
                                         f"{MAX_LINE_BYTES:,}", field="item", value=None, fix=fix)
            continue
        try:
            yield number, raw.decode("utf-8").rstrip("\r\n")
        except UnicodeDecodeError as exc:
            yield number, InputFileError(f"line {number} is not UTF-8 text (byte {exc.start})",
                                         field="item", value=None,
                                         fix="write the batch file as UTF-8 JSON lines")


def _count_lines(batch: Path) -> int | None:
    """Lines of a regular file (for the progress bar), read in chunks; None otherwise."""
    if not batch.is_file():
        return None
    count, last = 0, b"\n"
    with batch.open("rb") as stream:
        while chunk := stream.read(1 << 20):
            count += chunk.count(b"\n")
            last = chunk[-1:]
    return count + (last != b"\n")


def _read_item(line: str, number: int) -> Any:
    """The JSON value of one line, or InputFileError saying why it is not one."""
    try:
        return json.loads(line, parse_constant=_reject_constant)
    except json.JSONDecodeError as exc:
        raise InputFileError(f"line {number} is not JSON: {exc.msg}", field="item",
                             value=None, fix="one JSON object per line") from None
    except RecursionError:
        raise InputFileError(f"line {number} nests too deep to read", field="item",
                             value=None, fix="write one flat JSON object per line") from None
    except ValueError as exc:  # NaN/Infinity, or an integer beyond Python's digit limit
        raise InputFileError(f"line {number} is not strict JSON: {str(exc)[:120]}",
                             field="item", value=None,
                             fix="use finite numbers of at most 18 digits") from None


def _item_id(item: Any, number: int) -> Any:
    """The item's id when it is a short string or a 64-bit integer, else InputFileError."""
    if not isinstance(item, dict) or "id" not in item:
        return f"line {number}"
    value = item["id"]
    if isinstance(value, str) and len(value) <= MAX_ID_CHARS:
        return value
    if isinstance(value, int) and not isinstance(value, bool) and -INT64 <= value < INT64:
        return value
    raise InputFileError("'id' must be a string of at most 200 characters or a 64-bit "
                         "integer", field="id", value=None,
                         fix='give "id" as a short string or an integer')


def _error_line(item_id: Any, exc: BaseException) -> str:
    if isinstance(exc, VeriGraphError):
        body = exc.to_dict()
    else:
        body = {"error": "InternalError", "message": f"{type(exc).__name__}: {str(exc)[:200]}",
                "field": None, "value": None,
                "fix": "report this item; the batch went on without it"}
    value = body.get("value")
    if isinstance(value, float) and value != value or isinstance(value, str | int) \
            and len(str(value)) > 200:
        body["value"] = str(value)[:80]
    try:
        return json.dumps({"id": item_id, "ok": False, **body}, allow_nan=False)
    except (ValueError, TypeError, RecursionError):
        return json.dumps({"id": item_id, "ok": False, "error": body["error"],
                           "message": str(body["message"])[:200]})


def _item_report(item: Any, base: Path, cache: dict[str, str], planbench: bool,
                 engine_default: str) -> dict[str, Any]:
    if not isinstance(item, dict):
        raise InputFileError("a batch item is a JSON object", field="item",
                             value=str(item)[:80], fix='write {"id": ..., "domain": ..., '
                             '"problem": ..., "plan": ...}')
    def path(key: str) -> Path:
        value = item.get(key)
        if not isinstance(value, str) or not value:
            raise InputFileError(f"'{key}' must be a file path", field=key,
                                 value=str(value)[:80], fix=f"give '{key}' as a path string")
        p = Path(value)
        return p if p.is_absolute() else base / p

    if "domain" in item or "problem" in item:
        engine = item.get("engine", engine_default)
        if engine not in ("auto", "blocksworld", "strips"):
            raise InputFileError("'engine' is auto, blocksworld or strips", field="engine",
                                 value=str(engine)[:80], fix='drop "engine" or give "auto"')
        return pddl_item_report(path("domain"), path("problem"), path("plan"), cache,
                           engine=str(engine), planbench=planbench)
    if "scene" in item:
        goal = path("goal") if item.get("goal") is not None else None
        return scene_report(path("scene"), path("plan"), goal)
    raise InputFileError("a batch item needs domain/problem/plan or scene/plan[/goal]",
                         field="item", value=", ".join(map(str, item))[:80],
                         fix='add "domain", "problem" and "plan", or "scene" and "plan"')


def run_batch(batch: Path, *, progress: bool = True, planbench: bool = False,
              engine: str = "auto") -> int:
    try:
        stream = batch.open("rb")
        total = _count_lines(batch) if progress else None
    except OSError as exc:
        print(f"error: batch: cannot read '{batch}': {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    base = batch.parent
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=total, unit="plan", file=sys.stderr, mininterval=0.5)
    try:
        all_valid, stopped = _run_lines(stream, base, planbench, engine, bar)
    except OSError as exc:  # the file stopped being readable part way (a device error)
        print(f"error: batch: cannot read '{batch}' on: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    finally:
        stream.close()
        if bar is not None:
            bar.close()
    if stopped:
        return EXIT_BAD_INPUT
    return EXIT_OK if all_valid else EXIT_NEGATIVE


def _run_lines(stream: IO[bytes], base: Path, planbench: bool, engine: str,
               bar: Any) -> tuple[bool, bool]:
    """Each line's report or error line to stdout; (every item valid, stopped early)."""
    cache: dict[str, str] = {}
    all_valid = True
    stopped = False
    out = sys.stdout
    for number, line in _lines(stream):
        if bar is not None:
            bar.update(1)
        if isinstance(line, str) and not line.strip():
            continue
        item_id: Any = f"line {number}"
        try:
            # an item's report is acyclic: the cyclic collector waits until it is
            # written and dropped (one young collection per item, not one per 700 objects)
            with collector_paused(LARGE_GRAPH_ITEMS):
                if isinstance(line, InputFileError):
                    raise line
                item = _read_item(line, number)
                item_id = _item_id(item, number)
                report = _item_report(item, base, cache, planbench, engine)
                all_valid = all_valid and bool(report["valid"])
                out.write(json.dumps({"id": item_id, **report}, allow_nan=False,
                                     check_circular=False) + "\n")
                del report
        except Exception as exc:  # noqa: BLE001 - one item never ends the batch
            all_valid = False
            stopped = isinstance(exc, _Stop)
            out.write(_error_line(item_id, exc) + "\n")
    return all_valid, stopped
