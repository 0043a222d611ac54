"""The `verigraph` command: one subcommand module per area, all calling verigraph.tools.

Exit codes: 0 success, 1 a negative verdict (plan invalid, goal missed), 2 bad input;
for `agent --transport http`: 3 no server at --url, 4 the server needs a token and none
was given, 5 the server refused the token. `verigraph val` (and `verigraph-val`) answer
with VAL's statuses instead (`verigraph val -h`).

Start-up: a command imports the one module that defines it (`COMMANDS`), and that module
imports its heavy dependencies where they are used, so `verigraph validate --domain ...`
loads the PDDL engine and nothing of the server, agent, simulator or scene-graph stacks.
Only `verigraph --help` (or an unknown command) imports every subcommand module.

A closed pipe (`verigraph validate ... | head -1`, also with `2>&1`): standard output
and standard error are wrapped for the run (`PipeSafeStream`); when the reader has gone,
later output to that stream goes to the null device and the command finishes as it
would have, quietly, with its own exit status (the verdict's), never a `BrokenPipeError`
traceback.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
from collections.abc import Callable, Iterable, Sequence
from typing import Any, TextIO, cast

from verigraph.cli.exits import EXIT_BAD_INPUT, EXIT_INTERRUPTED
from verigraph.errors import VeriGraphError

# Each command -> the module whose `register(subparsers)` defines it, in the order of the
# help text. Modules are imported by name when the parser is built (an import error is an
# error, never skipped). tests/cli/test_cli_startup.py checks this table against what the
# modules register.
COMMANDS: dict[str, str] = {
    "validate": "verigraph.cli.validating", "val": "verigraph.cli.val",
    "solve": "verigraph.cli.core", "export-pddl": "verigraph.cli.core",
    "serve": "verigraph.cli.serve", "episodes": "verigraph.cli.episodes",
    "render": "verigraph.cli.sim", "demo": "verigraph.cli.sim", "agent": "verigraph.cli.agent",
    "rollouts": "verigraph.cli.rollouts", "bench": "verigraph.cli.bench",
    "perceive": "verigraph.cli.perceive", "view": "verigraph.cli.view",
    "arm": "verigraph.cli.arm",
}
SUBCOMMAND_MODULES = tuple(dict.fromkeys(COMMANDS.values()))


class PipeSafeStream:
    """`sys.stdout` (or `sys.stderr`) for one command run: a closed pipe ends the output,
    not the command.

    When a write or flush fails with BrokenPipeError (the reader quit, as `head -1` does),
    the stream's file descriptor is pointed at the null device and every later write is
    dropped, so the command completes and returns its own exit status. Anything else is
    the wrapped stream's (`encoding`, `isatty`, `buffer`, ...).
    """

    def __init__(self, stream: TextIO) -> None:
        self._stream = stream
        self.pipe_closed = False

    def write(self, text: str) -> int:
        if not self.pipe_closed:
            try:
                return self._stream.write(text)
            except BrokenPipeError:
                self._divert()
        return len(text)

    def writelines(self, lines: Iterable[str]) -> None:
        for line in lines:
            self.write(line)

    def flush(self) -> None:
        if not self.pipe_closed:
            try:
                self._stream.flush()
            except BrokenPipeError:
                self._divert()

    def _divert(self) -> None:
        """Drop all later output; the descriptor goes to the null device so that what is
        still buffered (and the interpreter's flush at exit) lands there, not on the pipe."""
        self.pipe_closed = True
        try:
            fd = self._stream.fileno()
        except (AttributeError, OSError, ValueError):
            return
        devnull = os.open(os.devnull, os.O_WRONLY)
        try:
            os.dup2(devnull, fd)
        finally:
            os.close(devnull)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream, name)


def run_guarded(command: Callable[[], int], *, process_ends: bool = False) -> int:
    """`command()` with standard output and error wrapped in PipeSafeStream (flushed
    before the wrappers are removed, so a pipe closed at the very end is caught here).
    `process_ends`: it runs the process's own command line, which ends next
    (`graph.bulk.before_exit`)."""
    out, err = sys.stdout, sys.stderr
    guards = [PipeSafeStream(s) for s in (out, err) if s is not None]  # None: no console
    if out is not None:
        sys.stdout = cast(TextIO, guards[0])
    if err is not None:
        sys.stderr = cast(TextIO, guards[-1])
    try:
        return command()
    finally:
        for guard in guards:
            guard.flush()
        sys.stdout, sys.stderr = out, err
        if process_ends:
            from verigraph.graph.bulk import before_exit

            before_exit()


def build_parser(modules: Sequence[str] = SUBCOMMAND_MODULES) -> argparse.ArgumentParser:
    # The help text is the first two paragraphs above: what the command is, exit codes.
    parser = argparse.ArgumentParser(prog="verigraph",
                                     description="\n\n".join(__doc__.split("\n\n")[:2]),
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name in modules:
        importlib.import_module(name).register(sub)
    return parser


def _dispatch(argv: list[str]) -> int:
    module = COMMANDS.get(argv[0]) if argv else None
    parser = build_parser((module,) if module else SUBCOMMAND_MODULES)
    args = parser.parse_args(argv)
    try:
        code: int = args.handler(args)
    except VeriGraphError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return int(getattr(exc, "exit_code", EXIT_BAD_INPUT))
    except KeyboardInterrupt:
        return EXIT_INTERRUPTED
    return code


def main(argv: Sequence[str] | None = None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    return run_guarded(lambda: _dispatch(args), process_ends=argv is None)


if __name__ == "__main__":
    sys.exit(main())
