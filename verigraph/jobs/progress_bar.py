"""The live progress bar of a benchmark run (tqdm): done/total, success per group, ETA.

Episodes found in the results file count as done from the start, so a resumed run's
bar starts where the last one stopped; its rate and ETA only count this run's work.
`summary()` is what is printed at the end, and also when the run is interrupted. Any
result with a `group`, a `success` and an `error` counts (`bench plan`'s records, the
environment's rollout results).
"""

from __future__ import annotations

import sys
from collections.abc import Iterable
from typing import Protocol, TextIO

from tqdm import tqdm


class Outcome(Protocol):
    """What the bar counts of a finished job."""

    @property
    def group(self) -> str: ...

    @property
    def success(self) -> bool: ...

    @property
    def error(self) -> str | None: ...


class EpisodeProgress:
    """Counts finished episodes per group and shows them on one bar."""

    def __init__(self, total: int, resumed: Iterable[Outcome] = (), *,
                 stream: TextIO | None = None, enabled: bool = True) -> None:
        self.total = total
        self.stream = stream or sys.stderr
        self.by_group: dict[str, list[int]] = {}
        self.resumed = 0
        self.ran = 0
        self.errors = 0
        for record in resumed:
            self._count(record)
            self.resumed += 1
        tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.bar = tqdm(total=total, initial=self.resumed, file=self.stream, unit="ep",
                        desc="episodes", disable=not enabled, dynamic_ncols=True,
                        mininterval=0.2 if tty else 10.0, smoothing=0.1)
        self.bar.set_postfix_str(self.groups_text(), refresh=False)

    def _count(self, record: Outcome) -> None:
        counts = self.by_group.setdefault(record.group, [0, 0])
        counts[0] += record.success
        counts[1] += 1
        self.errors += record.error is not None

    def groups_text(self) -> str:
        return " ".join(f"{group} {ok}/{n}" for group, (ok, n) in self.by_group.items())

    def update(self, record: Outcome) -> None:
        self._count(record)
        self.ran += 1
        self.bar.set_postfix_str(self.groups_text(), refresh=False)
        self.bar.update(1)

    def close(self) -> None:
        self.bar.close()

    def summary(self, *, interrupted: bool = False, results: str | None = None) -> str:
        done = self.resumed + self.ran
        elapsed = self.bar.format_dict.get("elapsed", 0.0) or 0.0
        rate = self.ran / elapsed if elapsed > 0 else 0.0
        head = "interrupted" if interrupted else "finished"
        lines = [f"{head}: {done}/{self.total} episodes done ({self.resumed} from the results "
                 f"file, {self.ran} run now in {elapsed:.1f} s, {rate:.1f} episodes/s), "
                 f"{self.errors} with errors"]
        if self.by_group:
            lines.append("success so far: " + ", ".join(
                f"{group} {ok}/{n} ({ok / n:.0%})" for group, (ok, n) in self.by_group.items()))
        if interrupted:
            lines.append(f"rerun the same command to resume; finished episodes are in "
                         f"{results}" if results else
                         "nothing was saved: pass --results FILE.jsonl to make runs resumable")
        return "\n".join(lines)
