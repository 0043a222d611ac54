#!/usr/bin/env bash
# Install the clients nobody here wrote that the interoperability tests run against
# `verigraph serve`: the official TypeScript SDK, ajv, and the official conformance suite
# (versions pinned in tests/interop/package-lock.json). The conformance suite needs
# Node >= 22, which scripts/install_inspector.sh provides in .tools/.
set -euo pipefail
cd "$(dirname "$0")/../tests/interop"
npm ci --no-audit --no-fund --loglevel=error >&2
