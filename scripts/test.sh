#!/usr/bin/env bash
# Set up from scratch and run every check CI runs: lint, types, the test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
VERIGRAPH_EXTRAS="${VERIGRAPH_EXTRAS:-dev,pddl,arm,clip}" bash scripts/setup.sh
# Evaluation at scale: Ray for `bench plan --ray`, matplotlib for `bench report --plot`.
.venv/bin/python -m pip install --quiet -e ".[scale]"
# The real local LLM (llama.cpp + Gemma 3 270M) for the llm-local planner tests.
bash scripts/install_llm.sh
# The official MCP Inspector (a client nobody here wrote) for the interoperability test.
bash scripts/install_inspector.sh
export VERIGRAPH_INSPECTOR="$PWD/.tools/bin/mcp-inspector"
.venv/bin/ruff check verigraph tests benchmarks examples
.venv/bin/mypy
.venv/bin/pytest "$@"
