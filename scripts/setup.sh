#!/usr/bin/env bash
# Installs every Debian package michi needs to build, test and benchmark (Debian 12). Skips what is installed.
set -euo pipefail
PACKAGES=(
    build-essential cmake pkg-config git
    libompl-dev ompl-demos
    libfcl-dev libccd-dev liboctomap-dev
    liburdfdom-dev liburdfdom-headers-dev
    libeigen3-dev
    libboost-dev libboost-graph-dev libboost-filesystem-dev libboost-program-options-dev libboost-serialization-dev
    libboost-system-dev
    libyaml-cpp-dev
    libpng-dev
    libassimp-dev
    libgtest-dev libgmock-dev
    libbenchmark-dev
    python3 sqlite3
    librsvg2-bin
    libtinyxml2-dev
    libcli11-dev
    clang libclang-rt-14-dev
    libjs-three chromium nodejs
    slurm-wlm
)
# the replay page inlines libjs-three's three.js; its browser test drives chromium with npm puppeteer-core. A NodeSource
# nodejs brings its own npm (and conflicts with Debian's npm package): ask for npm only when there is none
if ! command -v npm >/dev/null 2>&1; then
    PACKAGES+=(npm)
fi
missing=()
for p in "${PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    fi
done
if [[ ${#missing[@]} -eq 0 ]]; then
    echo "setup: all ${#PACKAGES[@]} packages already installed" >&2
    exit 0
fi
echo "setup: installing ${missing[*]}" >&2
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
