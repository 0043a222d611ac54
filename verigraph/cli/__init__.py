"""The `verigraph` command: one subcommand module per area, all calling verigraph.tools.

Exit codes: 0 success, 1 a negative verdict (plan invalid, goal missed), 2 bad input;
for `agent --transport http`: 3 no server at --url, 4 the server needs a token and none
was given, 5 the server refused the token.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

from verigraph.errors import VeriGraphError

# Each module defines `register(subparsers)`, in the order of the help text. They are
# imported by name when the parser is built (an import error is an error, never skipped)
# so that a core command imports only what it needs.
SUBCOMMAND_MODULES = ("verigraph.cli.core", "verigraph.cli.serve",
                      "verigraph.cli.episodes", "verigraph.cli.sim",
                      "verigraph.cli.agent", "verigraph.cli.rollouts", "verigraph.cli.bench",
                      "verigraph.cli.perceive", "verigraph.cli.view", "verigraph.cli.arm")

# The offline verifier's commands need only verigraph.cli.core: running one of them does
# not import the server, agent or simulator stacks (start-up stays well under a second).
CORE_COMMANDS = ("validate", "solve", "export-pddl")

EXIT_OK, EXIT_NEGATIVE, EXIT_BAD_INPUT = 0, 1, 2


def build_parser(modules: Sequence[str] = SUBCOMMAND_MODULES) -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="verigraph", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name in modules:
        importlib.import_module(name).register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    core_only = bool(argv) and argv[0] in CORE_COMMANDS
    parser = build_parser(("verigraph.cli.core",) if core_only else SUBCOMMAND_MODULES)
    args = parser.parse_args(argv)
    try:
        code: int = args.handler(args)
    except VeriGraphError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return int(getattr(exc, "exit_code", EXIT_BAD_INPUT))
    except KeyboardInterrupt:
        return 130
    return code


if __name__ == "__main__":
    sys.exit(main())
