#!/usr/bin/env bash
# Rebuild the viewer's single HTML file (verigraph/viewer/static/episode.html, shipped as
# package data so a pip install needs no Node) and the browser tests' minimal MCP Apps
# host page (tests/viewer_host/host.html) from viewer/. Needs Node >= 20 and npm.
set -euo pipefail
cd "$(dirname "$0")/../viewer"
npm ci --no-audit --no-fund
npm run typecheck
npm run build
