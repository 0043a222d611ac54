#!/usr/bin/env bash
# Build .tools/NAME-venv with the integration package integrations/NAME, for each NAME
# given, in parallel. Idempotent.
#
#   scripts/install_integration.sh openenv            OpenEnv 0.10 and verigraph-openenv
#   scripts/install_integration.sh verifiers          verifiers 0.4 and the verigraph-verifiers taskset
#   scripts/install_integration.sh openenv verifiers  both at once (what scripts/test.sh runs)
#
# Each lives in its own virtual environment because of `mcp`: OpenEnv 0.10 needs mcp below
# 2 (through fastmcp 3) and verifiers 0.4 pins mcp==2.0.0, while VeriGraph needs mcp 2.3 or
# newer; both reach VeriGraph's environment server over OpenEnv's WebSocket protocol.
# tests/env/test_openenv_current.py and test_verifiers_taskset.py find them here (or at
# $VERIGRAPH_OPENENV_PYTHON / $VERIGRAPH_VERIFIERS_PYTHON).
#
# The installer is uv (from PyPI: the one on PATH, else a copy installed with pip into
# .tools/uv-venv), which resolves and downloads in parallel: both environments from
# scratch take about 6 s on the idle 2-core development machine with an empty uv cache
# (4 s more to install uv; 17-33 s in all under a load average of 6), against 77 s with
# pip one after the other (26 s OpenEnv, 51 s verifiers). uv's cache
# (~/.cache/uv, or $UV_CACHE_DIR) only holds downloads, rebuilt on demand.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -gt 0 ] || { echo "usage: scripts/install_integration.sh openenv|verifiers ..." >&2; exit 2; }
for NAME in "$@"; do
  case "$NAME" in openenv|verifiers) ;;
    *) echo "unknown integration: $NAME (openenv or verifiers)" >&2; exit 2;; esac
done
PYTHON="${PYTHON:-python3}"
mkdir -p .tools
UV="${UV:-$(command -v uv || true)}"
if [ -z "$UV" ]; then
  if [ ! -x .tools/uv-venv/bin/uv ]; then
    "$PYTHON" -m venv .tools/uv-venv
    .tools/uv-venv/bin/python -m pip install --quiet uv
  fi
  UV=.tools/uv-venv/bin/uv
fi

install() {
  local venv=".tools/$1-venv"
  if [ ! -x "$venv/bin/python" ]; then
    "$UV" venv --quiet --python "$PYTHON" "$venv"
  fi
  "$UV" pip install --quiet --python "$venv/bin/python" -e "integrations/$1"
}

pids=()
for NAME in "$@"; do
  install "$NAME" &
  pids+=("$!")
done
status=0
for pid in "${pids[@]}"; do
  wait "$pid" || status=1
done
exit "$status"
