#!/usr/bin/env bash
# package.example: a game builds against the installed package and draws what the sample game draws.
# Installs this build into a staging prefix and moves it (the package must be relocatable), builds
# examples/ against it with find_package (only the installed headers on its include path), runs it
# headless on Vulkan, and compares its screenshot with lpv_game's for the same scene, config, size
# and frame count.
#   package_test.sh BUILD_DIR SOURCE_DIR LPV_GAME LPV_PNG_COMPARE WORK_DIR
set -euo pipefail
build=$1 source=$2 game=$3 compare=$4 work=$5
rm -rf "$work"
mkdir -p "$work"

cmake --install "$build" --prefix "$work/staging" >"$work/install.log"
mv "$work/staging" "$work/prefix"
prefix=$work/prefix
for dir in include/rhi include/platforms include/engine include/gi lib/cmake/LpvEngine share/LpvEngine/presets; do
  [[ -d $prefix/$dir ]] || { echo "not installed: $dir" >&2; exit 1; }
done

cmake -S "$source/examples" -B "$work/example" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
  "-DCMAKE_CXX_FLAGS=-Wall -Wextra -Wpedantic -Werror" >"$work/configure.log" ||
  { cat "$work/configure.log"; exit 1; }
cmake --build "$work/example"
# The example sees the engine through the package only: no include folder of the tree or its build.
includes=$(grep -oE -- '(-I|-isystem )[^ "]+' "$work/example/compile_commands.json" | sed -E 's/^(-I|-isystem )//')
echo "example include folders: $(echo $includes)"
for dir in $includes; do
  case $dir in
  "$prefix"/* | /usr/*) ;;
  *) echo "the example's include path has $dir, outside the package and the system" >&2; exit 1 ;;
  esac
done

scene=$source/bench/scenes/cornell-sun.gltf
size=(--set render.width=128 --set render.height=128)
"$work/example/minimal_game" "$scene" --backend vulkan --frames 3 --screenshot "$work/example.png" "${size[@]}" \
  | tee "$work/example.txt"
# Its summary is the profiler's, with the GI's passes in it.
grep -q '^GI total (every GI pass' "$work/example.txt" || { echo "no GI total in the summary" >&2; exit 1; }
grep -qE '^  lookup ' "$work/example.txt" || { echo "no gi/lookup pass in the summary" >&2; exit 1; }

"$game" --scene "$scene" --config "$source/examples/minimal_game.toml" --headless --backend vulkan --frames 3 \
  --screenshot "$work/game.png" "${size[@]}" >"$work/game.txt" 2>&1 || { cat "$work/game.txt"; exit 1; }
# Both drew the same frames with the same device: equal but for rounding (3 of 255, 0.5% of pixels).
"$compare" "$work/example.png" "$work/game.png" 3 0.005
