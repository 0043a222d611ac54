#!/usr/bin/env bash
# Set up from scratch and run every check CI runs: lint, types, the test suite.
#
#   scripts/test.sh [PYTEST ARGS]          the suite without tests marked slow (CI), with
#                                          each framework's own smoke evaluation: OpenEnv
#                                          0.10 and verifiers 0.4 in their own environments
#                                          (scripts/install_integration.sh, uv from PyPI,
#                                          both in parallel: 10 s from scratch with uv's
#                                          own install, 17-33 s on a loaded machine, and
#                                          1.3-1.7 s more for the wheels of verifiers'
#                                          chat harness; their tests about 2 minutes,
#                                          offline: loopback only)
#   scripts/test.sh --fast [PYTEST ARGS]   the fast tier only: installs the core and `dev`,
#                                          no service, no server subprocess, no training
#                                          (under two minutes on two cores)
#   scripts/test.sh --slow [PYTEST ARGS]   also builds llama.cpp (7-25 min on a new
#                                          machine, cached after) and runs the slow tests
# Every run prints the 25 slowest tests (--durations=25).
set -euo pipefail
cd "$(dirname "$0")/.."
MODE=default
if [ "${1:-}" = "--slow" ] || [ "${1:-}" = "--fast" ]; then MODE="${1#--}"; shift; fi
if [ "$MODE" = fast ]; then
  VERIGRAPH_EXTRAS="${VERIGRAPH_EXTRAS:-dev}" bash scripts/setup.sh
  exec .venv/bin/pytest -m fast --durations=25 "$@"
fi
# Redis and Chromium from Debian's packages, started by the tests on loopback.
bash scripts/install_services.sh
VERIGRAPH_EXTRAS="${VERIGRAPH_EXTRAS:-test}" bash scripts/setup.sh
# OpenEnv 0.10 and verifiers 0.4 in their own environments (each pins an mcp that cannot
# sit beside VeriGraph's): tests/env/test_openenv_current.py and test_verifiers_taskset.py.
# Built in the background while the other tools install.
bash scripts/install_integration.sh openenv verifiers &
INTEGRATIONS=$!
# The official MCP Inspector (a client nobody here wrote) for the interoperability test.
bash scripts/install_inspector.sh
export VERIGRAPH_INSPECTOR="$PWD/.tools/bin/mcp-inspector"
# The official TypeScript SDK, ajv and the conformance suite (tests/interop/).
bash scripts/install_interop.sh
.venv/bin/ruff check verigraph tests benchmarks examples
.venv/bin/mypy
wait "$INTEGRATIONS"
if [ "$MODE" = slow ]; then
  # The real local LLM (llama.cpp + Gemma 3 270M) for the llm-local planner tests.
  bash scripts/install_llm.sh
  .venv/bin/pytest --durations=25 "$@"
else
  .venv/bin/pytest -m "not slow" --durations=25 "$@"
fi
