#!/usr/bin/env bash
# Set up from scratch and run every check CI runs: lint, types, the test suite.
#
#   scripts/test.sh [PYTEST ARGS]          the suite without tests marked slow (CI)
#   scripts/test.sh --slow [PYTEST ARGS]   also builds llama.cpp (7-25 min on a new
#                                          machine, cached after) and runs the slow tests
set -euo pipefail
cd "$(dirname "$0")/.."
SLOW=0
if [ "${1:-}" = "--slow" ]; then SLOW=1; shift; fi
# Redis and Chromium from Debian's packages, started by the tests on loopback.
bash scripts/install_services.sh
VERIGRAPH_EXTRAS="${VERIGRAPH_EXTRAS:-dev,pddl,arm,clip,scale,env}" bash scripts/setup.sh
# The official MCP Inspector (a client nobody here wrote) for the interoperability test.
bash scripts/install_inspector.sh
export VERIGRAPH_INSPECTOR="$PWD/.tools/bin/mcp-inspector"
# The official TypeScript SDK, ajv and the conformance suite (tests/interop/).
bash scripts/install_interop.sh
.venv/bin/ruff check verigraph tests benchmarks examples
.venv/bin/mypy
if [ "$SLOW" = 1 ]; then
  # The real local LLM (llama.cpp + Gemma 3 270M) for the llm-local planner tests.
  bash scripts/install_llm.sh
  .venv/bin/pytest "$@"
else
  .venv/bin/pytest -m "not slow" "$@"
fi
