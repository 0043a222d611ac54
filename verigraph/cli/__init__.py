"""The `verigraph` command: one subcommand module per area, all calling verigraph.tools.

Exit codes: 0 success, 1 a negative verdict (plan invalid, goal missed), 2 bad input.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

from verigraph.errors import VeriGraphError

# Each module defines `register(subparsers)`; a module whose optional dependencies are
# missing is skipped, so the core install still has validate/solve/export-pddl.
SUBCOMMAND_MODULES = ("verigraph.cli.core", "verigraph.cli.serve", "verigraph.cli.sim",
                      "verigraph.cli.agent", "verigraph.cli.bench", "verigraph.cli.perceive",
                      "verigraph.cli.arm")

EXIT_OK, EXIT_NEGATIVE, EXIT_BAD_INPUT = 0, 1, 2


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="verigraph", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for name in SUBCOMMAND_MODULES:
        try:
            module = importlib.import_module(name)
        except ModuleNotFoundError as exc:
            if exc.name and exc.name.startswith("verigraph"):
                continue
            raise
        module.register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        code: int = args.handler(args)
    except VeriGraphError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        return 130
    return code


if __name__ == "__main__":
    sys.exit(main())
