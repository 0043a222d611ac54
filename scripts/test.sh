#!/usr/bin/env bash
# Set up from scratch and run every check CI runs: lint, types, the test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
VERIGRAPH_EXTRAS="${VERIGRAPH_EXTRAS:-dev,pddl,arm}" bash scripts/setup.sh
.venv/bin/ruff check verigraph tests benchmarks examples
.venv/bin/mypy
.venv/bin/pytest "$@"
