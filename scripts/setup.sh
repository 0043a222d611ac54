#!/usr/bin/env bash
# Create .venv (if missing) and install VeriGraph with the extras named in $VERIGRAPH_EXTRAS.
set -euo pipefail
cd "$(dirname "$0")/.."
EXTRAS="${VERIGRAPH_EXTRAS:-dev,pddl}"
PYTHON="${PYTHON:-python3}"
if [ ! -x .venv/bin/python ]; then
  "$PYTHON" -m venv .venv
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet -e ".[${EXTRAS}]"
