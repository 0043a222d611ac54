#!/usr/bin/env bash
# Build .tools/verifiers-venv: verifiers 0.4 with the verigraph-verifiers taskset
# (integrations/verifiers). Idempotent.
#
# verifiers 0.4 pins mcp==2.0.0 and VeriGraph needs mcp 2.3 or newer, so the taskset
# lives in its own virtual environment and plays episodes on VeriGraph's environment
# server over OpenEnv's WebSocket protocol. tests/env/test_verifiers_taskset.py finds it
# here (or at $VERIGRAPH_VERIFIERS_PYTHON).
set -euo pipefail
cd "$(dirname "$0")/.."
PYTHON="${PYTHON:-python3}"
VENV=.tools/verifiers-venv
if [ ! -x "$VENV/bin/python" ]; then
  mkdir -p .tools
  "$PYTHON" -m venv "$VENV"
  "$VENV/bin/python" -m pip install --quiet --upgrade pip
fi
"$VENV/bin/python" -m pip install --quiet -e integrations/verifiers
