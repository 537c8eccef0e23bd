#!/usr/bin/env bash
# Builds the libFuzzer harnesses (clang, ASan + UBSan; build dir build-asan, shared with the
# sanitizer test build) and runs each from its seeds: the built-in configs and platform profiles,
# and the glTF scenes in bench/scenes (and a .glb packed from one, fuzz/seeds/).
#   fuzz/run.sh [--time SECONDS | --runs N] [--no-build] [config gltf glb]
# Default: 60 seconds, all three side by side. A finding stops that fuzzer and leaves the input as
# build-asan/fuzz/<name>/crash-* (or leak-*, timeout-*); the script then exits 1.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${LPV_ASAN_BUILD_DIR:-$root/build-asan}
limit=(-max_total_time=60)
do_build=1
names=()
while [ $# -gt 0 ]; do
  case "$1" in
  --time) limit=(-max_total_time="$2"); shift 2 ;;
  --runs) limit=(-runs="$2"); shift 2 ;;
  --no-build) do_build=0; shift ;;
  config | gltf | glb) names+=("$1"); shift ;;
  *) echo "usage: $0 [--time SECONDS | --runs N] [--no-build] [config gltf glb]" >&2; exit 2 ;;
  esac
done
[ ${#names[@]} -gt 0 ] || names=(config gltf glb)

if [ $do_build -eq 1 ]; then
  CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DLPV_WERROR=ON -DLPV_FUZZ=ON >/dev/null
  cmake --build "$build" --parallel "$(nproc)" --target lpv_fuzzers
fi

# Mesa is not used by the loaders; ASan's leak check stays on (a leak is a finding).
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# The fuzzers run side by side (a machine's cores shared between them), each from its seeds.
run_one() {
  local name=$1 work=$build/fuzz/$1 seeds
  local corpus=$work/corpus log=$work/last-run.log
  mkdir -p "$corpus"
  case "$name" in
  config) seeds=("$root"/game/lpv_game.toml "$root"/gi/presets/console.toml "$root"/platforms/profiles/*.toml) ;;
  gltf) seeds=("$root"/bench/scenes/*.gltf "$root"/fuzz/seeds/*.gltf) ;;
  glb) seeds=("$root"/fuzz/seeds/*.glb) ;;
  esac
  cp "${seeds[@]}" "$corpus/"
  # -max_len: the largest seed (a glTF scene is ~16 KB) and room to grow.
  (cd "$work" && "$build/fuzz/lpv_fuzz_$name" "${limit[@]}" -max_len=32768 -timeout=30 -rss_limit_mb=4096 \
    -print_final_stats=1 "$corpus" >"$log" 2>&1)
}
pids=()
for name in "${names[@]}"; do
  echo "fuzz: $name (${limit[*]}), log $build/fuzz/$name/last-run.log"
  run_one "$name" &
  pids+=($!)
done
status=0
for i in "${!names[@]}"; do
  name=${names[$i]}
  log=$build/fuzz/$name/last-run.log
  if wait "${pids[$i]}"; then
    echo "fuzz: $name: $(grep -E '^(Done|stat::new_units_added)' "$log" | tr '\n' ' ')"
  else
    status=1
    echo "fuzz: $name FOUND a problem:" >&2
    tail -n 60 "$log" >&2
  fi
done
exit $status
