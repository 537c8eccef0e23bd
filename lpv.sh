#!/usr/bin/env bash
# The project's entry point for people and CI.
#   ./lpv.sh run    install missing packages, build, render 12 frames of the default scene with GI (game/lpv_game.toml)
#                   to out/screenshot.png and its profile report to out/profile/
#   ./lpv.sh test   install missing packages, build with warnings as errors, run every test (ctest)
#   ./lpv.sh bench  install missing packages, build, print the benchmark figures per backend
# Extra arguments after `run` go to the game, e.g. ./lpv.sh run --backend gl
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
cmd=${1:-run}
shift || true
build=${LPV_BUILD_DIR:-$root/build}

"$root/scripts/install-deps.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLPV_WERROR=ON >/dev/null
cmake --build "$build" --parallel "$(nproc)"

case "$cmd" in
run)
  # The sample game's config (GI on) first: the caller's --config and --set apply after it. Twelve
  # frames around the orbit: the first compiles the pipelines and makes the resources (warm-up,
  # left out of the report), the other eleven give the steady-state median; --frames overrides.
  mkdir -p "$root/out"
  "$build/game/lpv_game" --config "$root/game/lpv_game.toml" --screenshot "$root/out/screenshot.png" \
    --profile-out "$root/out/profile" --frames 12 --camera-path orbit "$@"
  ;;
test)
  cd "$build"
  # As many suites at once as cores: the longest (gi.gpu.vulkan, about 2 minutes) then overlaps
  # the others (320 s of tests one at a time on a 2-core machine, about 200 s two at a time).
  ctest --output-on-failure --timeout 900 --parallel "$(nproc)" "$@"
  ;;
bench)
  "$build/bench/lpv_rhi_bench" "$@"
  ;;
*)
  echo "usage: $0 run|test|bench [args...]" >&2
  exit 2
  ;;
esac
