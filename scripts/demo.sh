#!/usr/bin/env bash
# Set up and run the main job: a demo episode on the built-in simulator.
set -euo pipefail
cd "$(dirname "$0")/.."
VERIGRAPH_EXTRAS="${VERIGRAPH_EXTRAS:-dev}" bash scripts/setup.sh
.venv/bin/verigraph demo "$@"
