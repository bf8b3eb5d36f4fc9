#!/usr/bin/env bash
# CUDA tests and GPU benchmark figures from a build made here, run on a GPU machine that has no
# SUMO and no package registry.
#
#   tools/gpu_bench.sh --bundle   on the build machine: copies the GPU binaries (criticality-bench,
#                                 the CUDA tests) and the shared libraries they need into
#                                 BUILD_DIR/gpu-bundle (a few MB; the whole build folder is too
#                                 large to carry); glibc goes into gpu-libs/glibc, used only when
#                                 the GPU machine's own glibc is older than the build's
#   BUILD_DIR=build/gpu-bundle tools/gpu_bench.sh [REPEAT]
#                                 on the GPU machine: runs the CUDA tests, then criticality-bench
#                                 (--compare on S1/S2, cuda on S1/S2 with 6 and 5 profiles, a
#                                 recorded city fleet step as one batch beside the cpu's, the
#                                 the risk kernels' variants side by side, the scaling scenes),
#                                 printing a table and a JSON line for each.
#                                 Without a usable GPU the tests skip and cuda rows are absent.
# Every command is stopped after STEP_TIMEOUT seconds (default 150), so that one hang does not
# take the whole lease; the run continues and exits non-zero.
# Environment: BUILD_DIR (default build), STEP_TIMEOUT.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
bench=$BUILD_DIR/estimator/bench/criticality-bench
tests=("$BUILD_DIR/tests/core_on_device_test" "$BUILD_DIR/tests/cuda_backend_test")
libs=$BUILD_DIR/gpu-libs
fleet=bench/fleet_step
step_timeout=${STEP_TIMEOUT:-150}

if [ "${1:-}" = "--bundle" ]; then
  out=$BUILD_DIR/gpu-bundle
  rm -rf "$out"
  mkdir -p "$out/gpu-libs/glibc" "$out/estimator/bench" "$out/tests"
  for bin in "$bench" "${tests[@]}"; do
    [ -x "$bin" ] || { echo "gpu_bench: $bin is not built (is nvcc installed? run tools/setup.sh)" >&2; exit 1; }
    cp "$bin" "$out/${bin#"$BUILD_DIR"/}"
    ldd "$bin" | awk '/=> \// {print $3} /ld-linux/ {print $1}' | while read -r lib; do
      case $(basename "$lib") in
        libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|ld-linux*) cp -L "$lib" "$out/gpu-libs/glibc/" ;;
        *) cp -L "$lib" "$out/gpu-libs/" ;;
      esac
    done
  done
  for lib in libdl.so.2 libpthread.so.0 librt.so.1; do  # what the driver's libcuda may load
    path=$(ldconfig -p | awk -v l="$lib" '$1 == l && /x86-64/ {print $NF; exit}')
    if [ -n "$path" ]; then cp -L "$path" "$out/gpu-libs/glibc/"; fi
  done
  echo "gpu_bench: bundled into $out ($(du -sh "$out" | cut -f1)); carry $out to the GPU machine" \
       "and run BUILD_DIR=$out tools/gpu_bench.sh there"
  exit 0
fi

repeat=${1:-20}
export LD_LIBRARY_PATH="$PWD/$libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
for bin in "$bench" "${tests[@]}"; do
  [ -x "$bin" ] || { echo "gpu_bench: $bin missing; build with CUDA and run 'tools/gpu_bench.sh --bundle' first" >&2; exit 1; }
done
# The binaries through the system's loader, or, where its glibc is older than the build's,
# through the bundled loader and glibc.
launch=()
if ! "$bench" --help >/dev/null 2>&1 && [ -x "$libs/glibc/ld-linux-x86-64.so.2" ]; then
  launch=("$PWD/$libs/glibc/ld-linux-x86-64.so.2" --library-path "$PWD/$libs/glibc:$PWD/$libs")
  echo "gpu_bench: the system's glibc does not run the build; using the bundled one"
fi
command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader || true

status=0
run() {  # run CMD...: the command under the step timeout; a failure marks the run failed
  local rc=0
  timeout "$step_timeout" "${launch[@]}" "$@" || rc=$?
  if [ $rc -eq 124 ]; then
    echo "gpu_bench: stopped after ${step_timeout} s: $*" >&2
  elif [ $rc -ne 0 ]; then
    echo "gpu_bench: exit $rc: $*" >&2
  fi
  [ $rc -eq 0 ] || status=1
  return 0
}
for t in "${tests[@]}"; do
  echo "== $(basename "$t")"
  run "$t" --gtest_brief=1
done
for mode in thread warp; do  # the other risk kernels (CRITICALITY_CUDA_RISK, cuda_backend.cu)
  echo "== $(basename "${tests[1]}") with CRITICALITY_CUDA_RISK=$mode"
  CRITICALITY_CUDA_RISK=$mode run "${tests[1]}" --gtest_brief=1
done

echo "== criticality-bench --compare (every backend, same scene, one process)"
for scene in S1 S2; do
  run "$bench" --compare --scene "$scene" --repeat "$repeat" --json
done
if ! why=$(timeout 60 "${launch[@]}" "$bench" --backend cuda --repeat 1 --warmup 0 2>&1 >/dev/null); then
  echo "gpu_bench: no cuda figures: ${why#criticality-bench: error: }"
  exit $status
fi
echo "== cuda backend, end to end (scene in host memory to result in host memory), after warm-up"
for scene in S1 S2; do
  for profiles in 6 5; do
    run "$bench" --backend cuda --scene "$scene" --profiles "$profiles" --repeat "$repeat" --warmup 3 --json
  done
done
echo "== a recorded city fleet step ($fleet) as one batch: cpu (all cores) and cuda, same process"
run "$bench" --fleet "$fleet" --repeat 5 --warmup 1 --json
echo "== a fleet of S1-size egos in one call (target: >= 10,000 egos/s on one H100)"
for n in 1000 10000; do
  run "$bench" --backend cuda --scene S1 --batch "$n" --repeat 5 --warmup 1 --json
done
echo "== the risk kernels side by side (CRITICALITY_CUDA_RISK: thread, default, warp), 3 rounds;"
echo "   stages with CRITICALITY_CUDA_TIMING=1 (risk kernels, and of them the rows)"
for round in 1 2 3; do
  for mode in thread default warp; do
    echo "-- round $round, risk kernels: $mode"
    risk=$mode
    [ "$mode" = default ] && risk=
    CRITICALITY_CUDA_RISK=$risk run "$bench" --backend cuda --scene S2 --repeat "$repeat" --warmup 3
    CRITICALITY_CUDA_RISK=$risk run "$bench" --fleet "$fleet" --repeat 5 --warmup 1
    CRITICALITY_CUDA_RISK=$risk CRITICALITY_CUDA_TIMING=1 run "$bench" --backend cuda --scene S2 \
      --repeat 3 --warmup 1
  done
done
echo "== scaling with the number of other vehicles (cpu and cuda)"
for n in 1 3 10 30 100; do
  for backend in cpu cuda; do
    run "$bench" --backend "$backend" --cos "$n" --repeat 5 --warmup 1 --json
  done
done
exit $status
