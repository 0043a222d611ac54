"""Append-only audit log: one JSON line per command the adapter sends (or records).

Each line is flushed and synced before the command goes out, so after a crash the log
still says what the arm was last told to do.
"""

from __future__ import annotations

import os
import threading
import time
from pathlib import Path

from verigraph.arm.models import AuditRecord


class AuditLog:
    """Records in memory and, with a path, appends them to a JSON-lines file."""

    def __init__(self, path: str | Path | None = None) -> None:
        self.path = Path(path) if path is not None else None
        self._records: list[AuditRecord] = []
        self._lock = threading.Lock()
        if self.path is not None:
            self.path.parent.mkdir(parents=True, exist_ok=True)

    def record(self, record: AuditRecord) -> AuditRecord:
        with self._lock:
            record = record.model_copy(update={"seq": len(self._records) + 1,
                                               "time": time.time()})
            self._records.append(record)
            if self.path is not None:
                with self.path.open("a", encoding="utf-8") as f:
                    f.write(record.model_dump_json() + "\n")
                    f.flush()
                    os.fsync(f.fileno())
        return record

    @property
    def records(self) -> list[AuditRecord]:
        with self._lock:
            return list(self._records)
