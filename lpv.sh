#!/usr/bin/env bash
# The project's entry point for people and CI.
#   ./lpv.sh run    install missing packages, build, render 24 frames at 320x180 once around the default scene
#                   with GI (game/lpv_game.toml), the last to out/screenshot.png, the report to out/profile/
#   ./lpv.sh test   install missing packages, build with warnings as errors, run every test (ctest);
#                   then, given no ctest arguments, the CPU suites and game.cli built with ASan + UBSan
#                   (clang, build-asan/) and a minute of each fuzzer (fuzz/run.sh): any report fails
#   ./lpv.sh bench  install missing packages, build, print the benchmark figures per backend
# Extra arguments after `run` go to the game, e.g. ./lpv.sh run --backend gl
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
cmd=${1:-run}
shift || true
build=${LPV_BUILD_DIR:-$root/build}

"$root/scripts/install-deps.sh"
# Optimised, with line tables for backtraces (-g1): full debug information takes longer to build,
# and a debugging session configures a build of its own.
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DLPV_WERROR=ON >/dev/null
cmake --build "$build" --parallel "$(nproc)"

case "$cmd" in
run)
  # The sample game's config (GI on) first; the caller's arguments come after these and win. 24
  # frames once around the scene, ending at its own camera (the screenshot): the first compiles the
  # pipelines and makes the resources (warm-up, left out of the report), the other 23 give the
  # steady-state median. At 320x180 because on a software driver a 1280x720 frame's cost is mostly
  # its pixels; the times, and what larger frames cost: docs/benchmarks.md#the-quick-start-run.
  mkdir -p "$root/out"
  "$build/game/lpv_game" --config "$root/game/lpv_game.toml" --screenshot "$root/out/screenshot.png" \
    --profile-out "$root/out/profile" --frames 24 --camera-path orbit --width 320 --height 180 "$@"
  ;;
test)
  cd "$build"
  # As many suites at once as cores: the longest (gi.gpu.vulkan, about 2 minutes) then overlaps
  # the others (320 s of tests one at a time on a 2-core machine, about 200 s two at a time).
  ctest --output-on-failure --timeout 900 --parallel "$(nproc)" "$@"
  # Arguments pick some tests (-R ...): the sanitizer stage is for the whole run.
  [ $# -eq 0 ] || exit 0
  # The suites without a device, and the game's command line, under ASan + UBSan: any report
  # fails the run (no recovery). The one leak LeakSanitizer finds is Mesa's (tests/lsan.supp).
  asan=${LPV_ASAN_BUILD_DIR:-$root/build-asan}
  CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$asan" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DLPV_WERROR=ON -DLPV_FUZZ=ON >/dev/null
  cmake --build "$asan" --parallel "$(nproc)" \
    --target lpv_engine_tests lpv_gi_tests lpv_reference_tests lpv_cli_tests lpv_keep_modules_loaded lpv_fuzzers
  cd "$asan"
  # Reports go to files too: one from a program a test runs (game.cli runs the game) fails the
  # stage even where the test does not look at its exit code.
  reports=$asan/sanitizer-reports
  rm -rf "$reports" && mkdir -p "$reports"
  status=0
  LD_PRELOAD=$asan/tests/liblpv_keep_modules_loaded.so ASAN_OPTIONS=detect_leaks=1:log_path=$reports/asan \
    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:log_path=$reports/ubsan \
    LSAN_OPTIONS=suppressions=$root/tests/lsan.supp:print_suppressions=0 \
    ctest --output-on-failure --timeout 900 --parallel "$(nproc)" \
    -R '^(engine\.config|gi\.reference|reference\.pathtracer|game\.cli\..*)$' || status=1
  if [ -n "$(ls -A "$reports")" ]; then
    echo "sanitizers: reports in $reports:" >&2
    cat "$reports"/* >&2
    status=1
  fi
  [ $status -eq 0 ] || exit 1
  # A minute of each fuzzer from its seeds (fuzz/run.sh; longer runs: fuzz/run.sh --runs 1000000).
  "$root/fuzz/run.sh" --no-build --time 60
  ;;
bench)
  "$build/bench/lpv_rhi_bench" "$@"
  ;;
*)
  echo "usage: $0 run|test|bench [args...]" >&2
  exit 2
  ;;
esac
