"""The audit log, the arm's safety record: one hash-chained JSON line per event.

Every command is logged twice: its intent before it is sent, its outcome after. Every
refusal, confirmation (approved, declined, cancelled, timed out, not asked), stop and
reset is logged too, in every mode, with the episode id, the process id, the client
that asked and the question shown to the human.

Each line is written under an exclusive `flock` on the file and synced before the
call returns, so `seq` is unique and increasing per file across processes, and each
record carries the hash of the previous record (`prev`) and its own (`hash`, SHA-256
of its canonical JSON without `hash`). `verify_audit_file` recomputes the chain: any
changed byte is found; a removed tail is not (nothing after it to disagree), so keep a
copy of the last hash elsewhere if truncation matters.
"""

from __future__ import annotations

import fcntl
import hashlib
import json
import os
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from pathlib import Path
from typing import Any

from verigraph.arm.errors import ArmError
from verigraph.arm.models import AuditRecord

GENESIS = "0" * 64
_TAIL_CHUNK = 4096


class AuditWriteError(ArmError):
    """The audit log could not be written: the arm is stopped and latched."""


_IDENTITY: ContextVar[dict[str, str] | None] = ContextVar("verigraph_arm_audit_identity",
                                                          default=None)


@contextmanager
def audit_scope(**identity: str | None) -> Iterator[None]:
    """Tag every record written in this context (episode_id, client) with `identity`.

    The server opens one scope per tool call; context variables follow the call into
    its worker thread, like the confirmation hook.
    """
    token = _IDENTITY.set({k: v for k, v in identity.items() if v is not None})
    try:
        yield
    finally:
        _IDENTITY.reset(token)


def canonical(data: dict[str, Any]) -> str:
    return json.dumps(data, sort_keys=True, separators=(",", ":"), ensure_ascii=False)


def record_hash(data: dict[str, Any]) -> str:
    """SHA-256 of a record's canonical JSON without its own `hash`."""
    body = {k: v for k, v in data.items() if k != "hash"}
    return hashlib.sha256(canonical(body).encode("utf-8")).hexdigest()


class AuditLog:
    """Records in memory and, with a path, appends them to a hash-chained JSON-lines file."""

    def __init__(self, path: str | Path | None = None) -> None:
        self.path = Path(path) if path is not None else None
        self._records: list[AuditRecord] = []
        self._lock = threading.Lock()
        self._last = (0, GENESIS)  # seq and hash of the last record (memory-only logs)
        if self.path is not None:
            self.path.parent.mkdir(parents=True, exist_ok=True)

    def record(self, record: AuditRecord) -> AuditRecord:
        """Append `record` (seq, time, pid, identity, chain filled in); raises
        AuditWriteError if the file cannot be written."""
        identity = _IDENTITY.get() or {}
        fields = {"time": time.time(), "pid": os.getpid(),
                  **{k: v for k, v in identity.items() if getattr(record, k, None) is None}}
        with self._lock:
            if self.path is None:
                seq, prev = self._last
                record = _sealed(record, fields, seq + 1, prev)
                self._last = (record.seq, record.hash or GENESIS)
            else:
                try:
                    record = self._append(record, fields)
                except OSError as exc:
                    raise AuditWriteError(
                        f"cannot write the audit log {self.path}: {exc.strerror or exc}",
                        field="audit_log", value=str(self.path),
                        fix="free disk space or fix the file's permissions, then reset "
                            "the arm") from None
            self._records.append(record)
        return record

    def _append(self, record: AuditRecord, fields: dict[str, Any]) -> AuditRecord:
        assert self.path is not None
        fd = os.open(self.path, os.O_RDWR | os.O_CREAT | os.O_APPEND, 0o640)
        with os.fdopen(fd, "r+b") as f:
            fcntl.flock(f, fcntl.LOCK_EX)
            try:
                seq, prev = _tail(f)
                record = _sealed(record, fields, seq + 1, prev)
                f.write((canonical(record.model_dump(mode="json")) + "\n").encode("utf-8"))
                f.flush()
                os.fsync(f.fileno())
            finally:
                fcntl.flock(f, fcntl.LOCK_UN)
        return record

    @property
    def records(self) -> list[AuditRecord]:
        """The records this process wrote through this log, in order."""
        with self._lock:
            return list(self._records)


def _sealed(record: AuditRecord, fields: dict[str, Any], seq: int, prev: str) -> AuditRecord:
    data = record.model_dump(mode="json") | fields | {"seq": seq, "prev": prev, "hash": None}
    data["hash"] = record_hash(data)
    return AuditRecord.model_validate(data)


def _tail(f: Any) -> tuple[int, str]:
    """(seq, hash) of the file's last record; a damaged last line chains to its bytes."""
    end = f.seek(0, os.SEEK_END)
    if end == 0:
        return 0, GENESIS
    pos, data = end, b""
    while pos > 0 and data.count(b"\n") < 2:
        step = min(_TAIL_CHUNK, pos)
        pos -= step
        f.seek(pos)
        data = f.read(step) + data
    last = data.rstrip(b"\n").rsplit(b"\n", 1)[-1]
    try:
        parsed = json.loads(last)
        return int(parsed["seq"]), str(parsed["hash"])
    except (ValueError, KeyError, TypeError):
        f.seek(0)
        count = sum(1 for _ in f)
        return count, hashlib.sha256(last).hexdigest()


def verify_audit_file(path: str | Path) -> tuple[int, list[str]]:
    """Check every line's hash, its link to the previous one and its seq.

    Returns the number of records and the problems found (empty: the chain holds).
    """
    problems: list[str] = []
    prev, seq, count = GENESIS, 0, 0
    with open(path, "rb") as f:
        for number, raw in enumerate(f, start=1):
            count = number
            try:
                data = json.loads(raw)
                if not isinstance(data, dict):
                    raise ValueError("not a JSON object")
            except ValueError as exc:
                problems.append(f"line {number}: not a JSON record ({exc})")
                prev = hashlib.sha256(raw.rstrip(b"\n")).hexdigest()
                seq += 1
                continue
            if data.get("hash") != record_hash(data):
                problems.append(f"line {number}: the record's hash does not match its content")
            if data.get("prev") != prev:
                problems.append(f"line {number}: prev does not match the hash of line "
                                f"{number - 1}" if number > 1 else
                                f"line {number}: the first record does not start the chain")
            if data.get("seq") != seq + 1:
                problems.append(f"line {number}: seq {data.get('seq')} where {seq + 1} "
                                "was expected")
            prev = str(data.get("hash"))
            seq = data["seq"] if isinstance(data.get("seq"), int) else seq + 1
    return count, problems
