#!/usr/bin/env bash
# Installs the Debian packages the project needs (only those missing), then configures and
# builds Release into build/. Idempotent: a second run installs nothing and rebuilds only
# what changed. CUDA targets are built when nvcc is found, skipped cleanly otherwise.
#
# Environment: BUILD_DIR (default build), BUILD_TYPE (default Release), JOBS (default nproc),
#              CRIT_NO_APT=1 to never call apt-get (fails with a list of what is missing).
set -euo pipefail
cd "$(dirname "$0")/.."

BUILD_DIR=${BUILD_DIR:-build}
BUILD_TYPE=${BUILD_TYPE:-Release}
JOBS=${JOBS:-$(nproc)}

packages=(cmake g++ make libeigen3-dev libhwy-dev libboost-program-options-dev libgtest-dev libsqlite3-dev
          sqlite3 sumo sumo-tools libfcl-dev libboost-dev libyaml-cpp-dev nlohmann-json3-dev
          python3-matplotlib chromium)  # chromium: the campaign report's browser test
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "${CRIT_NO_APT:-0}" = 1 ]; then
    echo "setup: missing Debian packages: ${missing[*]} (install them or unset CRIT_NO_APT)" >&2
    exit 1
  fi
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

cuda_args=()
if command -v nvcc >/dev/null 2>&1; then
  cuda_args=(-DCMAKE_CUDA_COMPILER="$(command -v nvcc)")
elif [ -x /usr/local/cuda/bin/nvcc ]; then
  cuda_args=(-DCMAKE_CUDA_COMPILER=/usr/local/cuda/bin/nvcc)
else
  echo "setup: no nvcc found; CUDA targets are skipped"
fi

cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE="$BUILD_TYPE" "${cuda_args[@]}" >/dev/null
cmake --build "$BUILD_DIR" -j "$JOBS"
echo "setup: built into $BUILD_DIR/"
