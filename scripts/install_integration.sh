#!/usr/bin/env bash
# Build .tools/NAME-venv with the integration package integrations/NAME. Idempotent.
#
#   scripts/install_integration.sh openenv     OpenEnv 0.10 and verigraph-openenv
#   scripts/install_integration.sh verifiers   verifiers 0.4 and the verigraph-verifiers taskset
#
# Each lives in its own virtual environment because of `mcp`: OpenEnv 0.10 needs mcp below
# 2 (through fastmcp 3) and verifiers 0.4 pins mcp==2.0.0, while VeriGraph needs mcp 2.3 or
# newer; both reach VeriGraph's environment server over OpenEnv's WebSocket protocol.
# tests/env/test_openenv_current.py and test_verifiers_taskset.py find them here (or at
# $VERIGRAPH_OPENENV_PYTHON / $VERIGRAPH_VERIFIERS_PYTHON).
set -euo pipefail
cd "$(dirname "$0")/.."
NAME="${1:?usage: scripts/install_integration.sh openenv|verifiers}"
case "$NAME" in openenv|verifiers) ;; *) echo "unknown integration: $NAME (openenv or verifiers)" >&2; exit 2;; esac
PYTHON="${PYTHON:-python3}"
VENV=".tools/$NAME-venv"
if [ ! -x "$VENV/bin/python" ]; then
  mkdir -p .tools
  "$PYTHON" -m venv "$VENV"
  "$VENV/bin/python" -m pip install --quiet --upgrade pip
fi
"$VENV/bin/python" -m pip install --quiet -e "integrations/$NAME"
