"""The `verigraph` command: one subcommand module per area, all calling verigraph.tools.

Exit codes: 0 success, 1 a negative verdict (plan invalid, goal missed), 2 bad input;
for `agent --transport http`: 3 no server at --url, 4 the server needs a token and none
was given, 5 the server refused the token.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from verigraph.cli import agent, bench, core, perceive, serve, sim
from verigraph.errors import VeriGraphError

# Each module defines `register(subparsers)`, in the order of the help text.
SUBCOMMAND_MODULES = (core, serve, sim, agent, bench, perceive)

EXIT_OK, EXIT_NEGATIVE, EXIT_BAD_INPUT = 0, 1, 2


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="verigraph", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for module in SUBCOMMAND_MODULES:
        module.register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
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
