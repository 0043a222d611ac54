#!/usr/bin/env bash
# Build .tools/openenv-venv: OpenEnv 0.10 with the verigraph-openenv package
# (integrations/openenv). Idempotent.
#
# OpenEnv 0.10 needs mcp below 2 (through fastmcp 3) and VeriGraph needs mcp 2.3 or newer,
# so the OpenEnv server lives in its own virtual environment and reaches VeriGraph's
# environment server over OpenEnv's WebSocket protocol. tests/env/test_openenv_current.py
# finds it here (or at $VERIGRAPH_OPENENV_PYTHON).
set -euo pipefail
cd "$(dirname "$0")/.."
PYTHON="${PYTHON:-python3}"
VENV=.tools/openenv-venv
if [ ! -x "$VENV/bin/python" ]; then
  mkdir -p .tools
  "$PYTHON" -m venv "$VENV"
  "$VENV/bin/python" -m pip install --quiet --upgrade pip
fi
"$VENV/bin/python" -m pip install --quiet -e integrations/openenv
