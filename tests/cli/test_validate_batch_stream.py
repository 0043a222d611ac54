"""`validate --batch` reads its file a line at a time: memory stays bounded by the line
limit whatever the file holds (an endless device, a FIFO, an over-long line)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
from pathlib import Path

from blocksworld_corpus import DATA
from verigraph.cli.batch import MAX_LINE_BYTES, MAX_SKIPPED_BYTES

CAP_BYTES = 1 << 30  # address space of the CLI under test: far below what reading all takes
GOOD = {"domain": str(DATA / "planbench_domain.pddl"),
        "problem": str(DATA / "planbench_instance.pddl"),
        "plan": str(DATA / "planbench_plan.txt")}


def capped_batch(path: str | Path) -> subprocess.CompletedProcess[str]:
    """`verigraph validate --batch PATH` with its address space capped at CAP_BYTES."""
    code = ("import resource, sys\n"
            f"resource.setrlimit(resource.RLIMIT_AS, ({CAP_BYTES}, {CAP_BYTES}))\n"
            "from verigraph.cli import main\n"
            f"sys.exit(main(['validate', '--batch', {str(path)!r}, '--no-progress']))\n")
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120)


def test_an_endless_line_stops_the_batch_with_an_error_line_in_bounded_memory() -> None:
    r = capped_batch("/dev/zero")  # one line that never ends; reading it all took 7.6 GB
    assert r.returncode == 2 and "Traceback" not in r.stderr and "MemoryError" not in r.stderr
    [line] = [json.loads(x) for x in r.stdout.splitlines()]
    assert line["id"] == "line 1" and line["ok"] is False and line["field"] == "item"
    assert f"{MAX_SKIPPED_BYTES:,} bytes without a line end" in line["message"]
    assert "stops" in line["message"] and line["fix"]


def test_an_over_long_line_gets_an_error_line_and_the_batch_goes_on(tmp_path: Path) -> None:
    long_line = '{"id": "' + "x" * (3 * MAX_LINE_BYTES) + '"}'
    (tmp_path / "b.jsonl").write_bytes(
        "\n".join([json.dumps({"id": "first", **GOOD}), long_line,
                   json.dumps({"id": "after", **GOOD})]).encode()
        + b"\n\xff\xfe not utf-8\n" + json.dumps({"id": "last", **GOOD}).encode())
    r = capped_batch(tmp_path / "b.jsonl")
    assert r.returncode == 1 and "Traceback" not in r.stderr
    out = [json.loads(x) for x in r.stdout.splitlines()]
    assert [o["id"] for o in out] == ["first", "line 2", "after", "line 4", "last"]
    assert out[0]["valid"] and out[2]["valid"] and out[4]["valid"]
    assert f"more than {MAX_LINE_BYTES:,}" in out[1]["message"]
    assert f"{len(long_line) + 1:,} bytes" in out[1]["message"]  # the whole line, newline too
    assert "not UTF-8" in out[3]["message"]


def test_a_line_at_the_limit_is_read() -> None:
    from verigraph.cli.batch import _lines

    class Chunks:  # a stream that hands out what readline asks for, as a file does
        def __init__(self, data: bytes) -> None:
            self.data, self.at = data, 0

        def readline(self, limit: int) -> bytes:
            end = self.data.find(b"\n", self.at, self.at + limit)
            stop = min(self.at + limit, len(self.data)) if end < 0 else end + 1
            out, self.at = self.data[self.at:stop], stop
            return out

    exact = b"a" * MAX_LINE_BYTES
    lines = list(_lines(Chunks(exact + b"\n" + exact + b"b\nc")))  # type: ignore[arg-type]
    assert lines[0] == (1, exact.decode())
    assert lines[1][0] == 2 and "more than" in str(lines[1][1])
    assert lines[2] == (3, "c")


def test_a_fifo_is_read_as_it_is_written(tmp_path: Path) -> None:
    """Items written to a FIFO one after another (an endless producer works the same way)."""
    fifo = tmp_path / "items"
    os.mkfifo(fifo)

    def produce() -> None:
        with fifo.open("w") as f:
            for i in range(3):
                f.write(json.dumps({"id": i, **GOOD}) + "\n")
                f.flush()

    writer = threading.Thread(target=produce)
    writer.start()
    r = capped_batch(fifo)
    writer.join(timeout=60)
    assert r.returncode == 0, r.stderr
    assert [json.loads(x)["id"] for x in r.stdout.splitlines()] == [0, 1, 2]
