"""The stop latch of one physical arm (driver + connection target), not of one episode.

A stop must outlive whatever asked for the motion: ending the episode, loading a new
scene or restarting the server must not give an unlatched arm. With an audit log the
latch is a small JSON file next to it (`<audit_log>.latch`), shared by every process
that drives that arm and read on every check, so an operator's reset from the command
line (`verigraph arm reset --config F`) is seen by a running server. Without an audit
log (dry-run and sim only: real mode requires one) the latch lives in this process.

Writes replace the file atomically under an exclusive lock on `<file>.lock`; reads
take no lock. If the file cannot be written the latch still holds in memory, so a
failure to persist never unlatches an arm.
"""

from __future__ import annotations

import fcntl
import json
import os
import threading
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from verigraph.arm.config import ArmConfig

DAMAGED = "*"  # the entry an unreadable latch file reads as: latched, for every arm
_MEMORY: dict[str, dict[str, Any]] = {}
_MEMORY_LOCK = threading.Lock()


def arm_key(config: ArmConfig) -> str:
    """The physical (or simulated) arm a config drives: driver and connection target."""
    target = config.host or "local"
    if config.driver == "rosbridge":
        target = f"{target}:{config.rosbridge.port}"
    return f"{config.driver}@{target}"


def latch_path(config: ArmConfig) -> Path | None:
    """Where the latch of `config`'s arm is persisted (None: in this process only)."""
    if config.audit_log is None:
        return None
    return config.audit_log.with_name(config.audit_log.name + ".latch")


class ArmLatch:
    """Set, read and clear the latched stop of one arm."""

    def __init__(self, key: str, path: Path | None) -> None:
        self.key = key
        self.path = path
        self._local: dict[str, Any] | None = None  # set but not (yet) persisted
        self._lock = threading.Lock()

    @classmethod
    def for_config(cls, config: ArmConfig) -> ArmLatch:
        return cls(arm_key(config), latch_path(config))

    # -- reading ---------------------------------------------------------------------------
    def state(self) -> dict[str, Any] | None:
        """The latch record (reason, time, pid) or None when the arm is not latched."""
        local = self._local
        if local is not None:
            return local
        if self.path is None:
            with _MEMORY_LOCK:
                return _MEMORY.get(self.key)
        latches = _read(self.path)
        return latches.get(self.key) or latches.get(DAMAGED)

    def reason(self) -> str | None:
        state = self.state()
        return None if state is None else str(state.get("reason", "stop latched"))

    # -- writing ---------------------------------------------------------------------------
    def set(self, reason: str) -> None:
        """Latch with `reason` unless already latched (the first reason is kept)."""
        record = {"reason": reason, "time": time.time(), "pid": os.getpid()}
        with self._lock:
            if self.state() is not None:
                return
            self._local = record  # holds even if the file cannot be written
        if self.path is None:
            with _MEMORY_LOCK:
                _MEMORY.setdefault(self.key, record)
            self._local = None
            return
        try:
            with _locked(self.path):
                latches = _read(self.path)
                latches.setdefault(self.key, record)
                _write(self.path, latches)
        except OSError:
            return  # the in-memory latch stays set: fail safe
        self._local = None

    def clear(self) -> None:
        """Release the latch (a reset: the caller checked who may do it)."""
        with self._lock:
            if self.path is None:
                with _MEMORY_LOCK:
                    _MEMORY.pop(self.key, None)
            else:
                with _locked(self.path):
                    latches = _read(self.path)
                    latches.pop(self.key, None)
                    latches.pop(DAMAGED, None)
                    _write(self.path, latches)
            self._local = None


def _read(path: Path) -> dict[str, Any]:
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        return {}
    except (OSError, ValueError):
        # An unreadable or damaged latch file must not read as "not latched".
        return {DAMAGED: {"reason": f"the latch file {path} cannot be read"}}
    return data if isinstance(data, dict) else {}


def _write(path: Path, latches: dict[str, Any]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + f".{os.getpid()}.tmp")
    with tmp.open("w", encoding="utf-8") as f:
        json.dump(latches, f)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


@contextmanager
def _locked(path: Path) -> Any:
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path.with_name(path.name + ".lock"), "a") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)
