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
# openenv-core (the env extra's old name for OpenEnv) and openenv install the same
# `openenv` module: drop the old one first so its files do not linger under the new one
if .venv/bin/python -m pip show --quiet openenv-core >/dev/null 2>&1; then
  .venv/bin/python -m pip uninstall --quiet --yes openenv-core
fi
.venv/bin/python -m pip install --quiet -e ".[${EXTRAS}]"
