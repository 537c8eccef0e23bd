#!/usr/bin/env bash
# The checks a lent GPU runs (the device tool: docs/benchmarks.md, "On an NVIDIA H100"), prepared
# here so that one call does them all inside a session's few minutes of device time.
#
#   scripts/gpu-check.sh pack   here, after the build: packs the GPU tests, the benchmark and every
#                               library they load (the Vulkan validation layer included) into
#                               .gpu/pack.tar.xz, which git ignores: the device machine has no
#                               package manager, and a call carries at most 64 MiB (this is ~50).
#   scripts/gpu-check.sh run    there, from the repository root, with .gpu carried:
#                               run(command="scripts/gpu-check.sh run", carry=[".gpu"], timeout_s=540)
#                               GPU tests on Vulkan and GL, then the frames (1280x720, 96 frames,
#                               GPU timestamps) and propagation parts on both; logs and the frames'
#                               summaries go to $OUT.
#   scripts/gpu-check.sh run --quick   the same, fewer frames and kernel runs: checks the script
#                               here on Mesa before device time is spent on it.
set -euo pipefail
cd "$(dirname "$0")/.."
archive=.gpu/pack.tar.xz

packLibraries() {
    # Every library the binaries and the validation layer load, except the C runtime's own, which
    # the device's system has (a newer glibc runs binaries built against an older one).
    local skip='^(linux-vdso|ld-linux|libc\.|libm\.|libdl\.|librt\.|libpthread\.)'
    ldd "$@" | awk '/=> \//{print $3}' | sort -u | while read -r lib; do
        name=$(basename "$lib")
        [[ $name =~ $skip ]] && continue
        cp -L "$lib" "$pack/lib/$name"
    done
}

if [[ ${1:-} == pack ]]; then
    pack=$(mktemp -d)
    trap 'rm -rf "$pack"' EXIT
    mkdir -p "$pack/bin" "$pack/lib" "$pack/layers" .gpu
    grep -qx '/.gpu/' .git/info/exclude 2>/dev/null || echo '/.gpu/' >>.git/info/exclude
    for b in build/tests/lpv_gpu_tests build/tests/lpv_alloc_tests build/bench/lpv_bench; do
        [[ -x $b ]] || { echo "gpu-check: $b is not built (cmake --build build)" >&2; exit 1; }
        strip -o "$pack/bin/$(basename "$b")" "$b"
    done
    layer=$(ls /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json)
    layerLib=$(ldconfig -p | awk '/libVkLayer_khronos_validation.so /{print $NF; exit}')
    sed "s|\"library_path\": *\"[^\"]*\"|\"library_path\": \"../lib/libVkLayer_khronos_validation.so\"|" \
        "$layer" >"$pack/layers/VkLayer_khronos_validation.json"
    cp -L "$layerLib" "$pack/lib/libVkLayer_khronos_validation.so"
    packLibraries "$pack"/bin/* "$pack/lib/libVkLayer_khronos_validation.so"
    # Mesa's OSMesa brings LLVM (112 MB): compressed, everything fits a call.
    tar -C "$pack" -cf - bin lib layers | xz -6 -T2 >"$archive"
    du -h "$archive"
    exit 0
fi

[[ ${1:-} == run ]] || { sed -n '2,16p' "$0"; exit 2; }
quick=${2:-}
out=${OUT:-out/gpu-check}
mkdir -p "$out"
pack=$(mktemp -d)
trap 'rm -rf "$pack"' EXIT
xz -dc "$archive" | tar -C "$pack" -xf -
export LD_LIBRARY_PATH="$pack/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export VK_ADD_LAYER_PATH="$pack/layers"
# NVIDIA's Vulkan and EGL drivers where the device machine mounts them.
nvidia=/usr/local/nvidia/share
[[ -f $nvidia/vulkan/icd.d/nvidia_icd.json ]] && export VK_DRIVER_FILES=$nvidia/vulkan/icd.d/nvidia_icd.json
[[ -f $nvidia/glvnd/egl_vendor.d/10_nvidia.json ]] &&
    export __EGL_VENDOR_LIBRARY_FILENAMES=$nvidia/glvnd/egl_vendor.d/10_nvidia.json
command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version,clocks.sm --format=csv | tee "$out/gpu.txt"

frames=96 kernelRuns=101 testTimeout=240 tests=()
[[ $quick == --quick ]] && frames=4 kernelRuns=3 tests=(-tc='*pinned*')
status=0
# Every GPU test on the GPU's backends (validation and debug output fail a test; gl-osmesa is
# Mesa on the CPU there too).
timeout "$testTimeout" "$pack/bin/lpv_gpu_tests" --backends=vulkan,gl-egl "${tests[@]}" 2>&1 | tail -n 40 | tee "$out/gpu-tests.txt" ||
    status=1
"$pack/bin/lpv_alloc_tests" 2>&1 | tail -n 5 | tee "$out/alloc-tests.txt" || status=1
"$pack/bin/lpv_bench" --backends vulkan,gl-egl --parts frames,propagation --frames "$frames" \
    --kernel-runs "$kernelRuns" --out "$pack/frames" 2>&1 | tee "$out/bench.txt" || status=1
# The device tool brings back at most 8 files: the per-pass tables, not the traces and images.
for s in "$pack"/frames/*-profile; do
    [[ -f $s/summary.md ]] && cp "$s/summary.md" "$out/$(basename "$s").md"
done
exit $status
