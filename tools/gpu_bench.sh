#!/usr/bin/env bash
# CUDA tests and GPU benchmark figures from a build folder copied to a GPU machine that has no
# SUMO and no package registry.
#
#   tools/gpu_bench.sh --bundle   on the build machine: copies the shared libraries the GPU
#                                 binaries need (beyond libc/libm) into BUILD_DIR/gpu-libs
#   tools/gpu_bench.sh [REPEAT]   on the GPU machine: runs the CUDA tests, then criticality-bench
#                                 (--compare on S1/S2, cuda on S1/S2 with 6 and 5 profiles, the
#                                 scaling scenes) and prints JSON lines and a summary table.
#                                 Without a usable GPU the tests skip and cuda rows are absent.
# Environment: BUILD_DIR (default build).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
bench=$BUILD_DIR/estimator/bench/criticality-bench
tests=("$BUILD_DIR/tests/core_on_device_test" "$BUILD_DIR/tests/cuda_backend_test")
libs=$BUILD_DIR/gpu-libs

if [ "${1:-}" = "--bundle" ]; then
  mkdir -p "$libs"
  for bin in "$bench" "${tests[@]}"; do
    [ -x "$bin" ] || { echo "gpu_bench: $bin is not built (is nvcc installed? run tools/setup.sh)" >&2; exit 1; }
    ldd "$bin" | awk '/=> \// {print $3}' | while read -r lib; do
      case $(basename "$lib") in
        libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|ld-linux*) ;;  # every Linux has these
        *) cp -L "$lib" "$libs/" ;;
      esac
    done
  done
  echo "gpu_bench: bundled $(ls "$libs" | tr '\n' ' ')into $libs; carry $BUILD_DIR to the GPU machine"
  exit 0
fi

repeat=${1:-20}
export LD_LIBRARY_PATH="$PWD/$libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
for bin in "$bench" "${tests[@]}"; do
  [ -x "$bin" ] || { echo "gpu_bench: $bin missing; build with CUDA and run 'tools/gpu_bench.sh --bundle' first" >&2; exit 1; }
done
command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader || true

status=0
for t in "${tests[@]}"; do
  echo "== $(basename "$t")"
  "$t" --gtest_brief=1 || status=1
done

echo "== criticality-bench --compare (every backend, same scene, one process)"
for scene in S1 S2; do
  "$bench" --compare --scene "$scene" --repeat "$repeat" --json || status=1
done
if ! why=$("$bench" --backend cuda --repeat 1 --warmup 0 2>&1 >/dev/null); then
  echo "gpu_bench: no cuda figures: ${why#criticality-bench: error: }"
  exit $status
fi
echo "== cuda backend, end to end (scene in host memory to result in host memory), after warm-up"
for scene in S1 S2; do
  for profiles in 6 5; do
    "$bench" --backend cuda --scene "$scene" --profiles "$profiles" --repeat "$repeat" --warmup 3 --json | tail -n 1 || status=1
  done
done
echo "== a fleet of S1-size egos in one call (target: >= 10,000 egos/s on one H100)"
for n in 1000 10000; do
  "$bench" --backend cuda --scene S1 --batch "$n" --repeat 5 --warmup 1 --json | tail -n 1 || status=1
done
echo "== scaling with the number of other vehicles (cpu and cuda)"
for n in 1 3 10 30 100; do
  for backend in cpu cuda; do
    "$bench" --backend "$backend" --cos "$n" --repeat 5 --warmup 1 --json 2>/dev/null | tail -n 1 || true
  done
done
exit $status
