"""`verigraph arm`: what the operator does to an arm outside the MCP server.

`reset --config FILE` releases the latched stop of the arm in FILE (sim and dry-run;
a real arm's reset is confirmed by the user through arm_reset); `audit-verify FILE`
checks the hash chain of an audit log (exit 1 if it is broken).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from verigraph.arm import load_arm_config
from verigraph.arm.operator import operator_reset, verify_audit_file
from verigraph.cli.exits import EXIT_NEGATIVE, EXIT_OK
from verigraph.errors import VeriGraphError


def register(sub: Any) -> None:
    p = sub.add_parser("arm", help="operator commands for an arm (reset, audit-verify)",
                       description=__doc__)
    arm_sub = p.add_subparsers(dest="arm_command", required=True, metavar="ARM_COMMAND")
    reset = arm_sub.add_parser("reset", help="release the arm's latched stop (sim, dry-run)")
    reset.add_argument("--config", type=Path, required=True, metavar="FILE",
                       help="the arm configuration the server runs with")
    reset.set_defaults(handler=run_reset)
    verify = arm_sub.add_parser("audit-verify", help="check an audit log's hash chain")
    verify.add_argument("file", type=Path, metavar="FILE")
    verify.set_defaults(handler=run_audit_verify)


def run_reset(args: argparse.Namespace) -> int:
    reason = operator_reset(load_arm_config(args.config))
    print("no stop was latched" if reason is None else
          f"stop released (it was latched: {reason}); nothing moved")
    return EXIT_OK


def run_audit_verify(args: argparse.Namespace) -> int:
    try:
        count, problems = verify_audit_file(args.file)
    except OSError as exc:
        raise VeriGraphError(f"cannot read the audit log: {exc.strerror}", field="FILE",
                             value=str(args.file), fix="give the path of an audit log") from None
    if problems:
        print(f"BROKEN: {args.file}: {len(problems)} problem(s) in {count} records",
              file=sys.stdout)
        for problem in problems[:20]:
            print(f"  {problem}")
        return EXIT_NEGATIVE
    print(f"OK: {args.file}: {count} records, hash chain intact")
    return EXIT_OK
