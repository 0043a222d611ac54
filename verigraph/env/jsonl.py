"""JSON Lines of pydantic models: the one reader and writer of the env's files.

Task datasets (verigraph.env.dataset) and trajectories (verigraph.env.trajectory) are
both one model per line. Reading them the same way means the same errors for the same
faults: a file that cannot be read, or a line that does not validate, is a
`VeriGraphError` naming the file, the line and the field, never a traceback.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import TypeVar

from pydantic import BaseModel, ValidationError

from verigraph.errors import VeriGraphError

ModelT = TypeVar("ModelT", bound=BaseModel)


def read_models(path: str | Path, model: type[ModelT], *, what: str, fix: str
                ) -> list[tuple[int, ModelT]]:
    """(line number, model) of every non-blank line; `what` names the file in errors
    ("task file"), `fix` says which file to pass instead."""
    source = Path(path)
    try:
        data = source.read_bytes()
    except OSError as exc:
        raise VeriGraphError(f"cannot read the {what} {source}: {exc.strerror}",
                             field="path", value=str(source), fix=fix) from None
    return parse_models(decode(data, source=str(source), what=what, fix=fix), model,
                        source=str(source), fix=fix)


def decode(data: bytes, *, source: str, what: str, fix: str) -> str:
    """`data` as UTF-8 text; a byte that is not UTF-8 is an error naming the file, the
    line and the byte (these files are written as UTF-8 JSON, so it is damage)."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        column = exc.start - (data.rfind(b"\n", 0, exc.start) + 1) + 1
        bad = data[exc.start:exc.end]
        raise VeriGraphError(f"{source}:{line}: the {what} is not UTF-8 text (byte "
                             f"0x{bad[0]:02x} at column {column})", field=f"line {line}",
                             value=bad.hex(), fix=fix) from None


def parse_models(text: str, model: type[ModelT], *, source: str, fix: str
                 ) -> list[tuple[int, ModelT]]:
    """`read_models` on text already read (`source` names it in errors)."""
    out = []
    # "\n" alone ends a line: a JSON string may hold U+2028 or U+0085 unescaped, which
    # str.splitlines would take for line ends.
    for number, line in enumerate(text.split("\n"), 1):
        if not line.strip():
            continue
        try:
            out.append((number, model.model_validate_json(line)))
        except ValidationError as exc:
            err = exc.errors()[0]
            where = ".".join(str(p) for p in err["loc"]) or "line"
            raise VeriGraphError(f"{source}:{number}: {where}: {err['msg']}",
                                 field=f"line {number}", value=where, fix=fix) from None
    return out


def write_models(models: Iterable[BaseModel], path: str | Path, *, append: bool,
                 exclude_none: bool) -> int:
    """One model per line (appended, or replacing the file); returns how many."""
    count = 0
    with Path(path).open("a" if append else "w", encoding="utf-8") as out:
        for model in models:
            out.write(model.model_dump_json(exclude_none=exclude_none) + "\n")
            count += 1
    return count
