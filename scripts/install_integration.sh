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
# pip one after the other (26 s OpenEnv, 51 s verifiers). The wheels of verifiers' chat
# harness (harness_wheels below) add 1.3-1.7 s at a load average of 6 to 7; a second run
# with nothing changed takes about 1.4 s. uv's cache (~/.cache/uv, or $UV_CACHE_DIR) only
# holds downloads, rebuilt on demand.
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
  if [ "$1" = verifiers ]; then harness_wheels; fi
}

# verifiers' chat harness (vf-eval's `null` and `bash` harnesses) runs a PEP 723 program
# that it prepares with `uv sync --script` on first use, from PyPI. Its wheels are fetched
# here, at install time, into .tools/verifiers-wheels: the program's requirements pinned
# for this environment's Python (uv pip compile reads the program's header, taken from
# verifiers' source) and downloaded in parallel (scripts/download_wheels.py), so the tests
# prepare it from that directory alone (UV_DEFAULT_INDEX and UV_FIND_LINKS, set by
# tests/venv_helpers.py) and never reach an index. Skipped while the header is unchanged.
harness_wheels() {
  local venv=.tools/verifiers-venv wheels=.tools/verifiers-wheels
  rm -rf "$wheels.new" && mkdir -p "$wheels.new"
  # the header alone, without importing verifiers (that takes seconds)
  "$venv/bin/python" -c 'import ast, sys, sysconfig
source = open(sysconfig.get_paths()["purelib"] + sys.argv[1]).read()
[value] = [n.value.value for n in ast.parse(source).body
           if isinstance(n, ast.Assign) and getattr(n.targets[0], "id", "") == "CHAT_PROGRAM"]
print(value, end="")' /verifiers/v1/harnesses/utils/launch.py > "$wheels.new/chat_program.py"
  if cmp -s "$wheels.new/chat_program.py" "$wheels/chat_program.py" \
      && [ -f "$wheels/pylock.toml" ]; then
    rm -rf "$wheels.new"
    return
  fi
  "$UV" pip compile --quiet --no-header --format pylock.toml --python "$venv/bin/python" \
    "$wheels.new/chat_program.py" -o "$wheels.new/pylock.toml"
  "$venv/bin/python" scripts/download_wheels.py "$wheels.new/pylock.toml" "$wheels.new"
  rm -rf "$wheels" && mv "$wheels.new" "$wheels"
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
