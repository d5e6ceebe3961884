#!/usr/bin/env bash
# Installs the Debian 12 packages seqc builds and tests with, when any is missing.
# Everything comes from apt; nothing is downloaded from anywhere else.
set -euo pipefail

packages=(
  g++ cmake ninja-build pkg-config
  libyaml-cpp-dev libcli11-dev libfmt-dev libsqlite3-dev libgtest-dev libgmock-dev libhidapi-dev
  libsndfile1-dev libpulse-dev pulseaudio pulseaudio-utils
  nlohmann-json3-dev libcpp-httplib-dev
  python3 python3-yaml python3-jsonschema python3-mir-eval
  dpkg-dev file groff-base zsh fish pre-commit git
  chromium python3-pil eslint
  neovim libltc-dev
)
# clang builds the libFuzzer targets; optional, installed when available.
optional=(clang libclang-rt-dev)

missing=()
for p in "${packages[@]}" "${optional[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
# Node and npm run the language server's test client (vscode-jsonrpc from npm). A machine with
# its own Node (one that ships npm) keeps it: Debian's npm would ask to replace it.
if ! command -v npm >/dev/null 2>&1; then
  packages+=(nodejs npm)
  missing+=(nodejs npm)
fi
if ((${#missing[@]} == 0)); then
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  sudo="sudo"
fi
echo "seqc: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
$sudo apt-get install -y -qq --no-install-recommends "${optional[@]}" >/dev/null 2>&1 ||
  echo "seqc: clang not available; fuzz targets will not be built" >&2
