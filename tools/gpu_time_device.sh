#!/usr/bin/env bash
# Device half of the GPU timing (docs/gpu_timing.md): run from the repository root on the GPU
# machine, with build/gpu_carry from tools/gpu_timing.sh. Times every pack in it (pack, pack_glsl)
# into OUT/<pack>. SHARDS processes compile in parallel (the driver's compiler is single-threaded per
# context) and take turns at the GPU to time and draw the images the errors are measured on.
#
#   [BINARIES=1] [CARRY=DIR] bash tools/gpu_time_device.sh OUT [SHARDS (14)] [COMPILE_SECONDS (no limit)] [SHARD_SECONDS (no limit)]
# Leaves OUT.tgz (per pack: shard logs and records, gpu_times.json, report.md; not the images).
set -uo pipefail
cd "$(dirname "$0")/.."
out="$1"
shards="${2:-14}"
compile_seconds="${3:-1000000000}"
shard_seconds="${4:-0}"  # timeout(1): 0 = no limit
carry="${CARRY:-build/gpu_carry}"  # another pack: CARRY=build/gpu_carry_before
export LD_LIBRARY_PATH="$carry/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# Where glvnd finds no vendor on its own (the device notes): NVIDIA's EGL vendor file.
nv=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ] && [ -f "$nv" ] && export __EGL_VENDOR_LIBRARY_FILENAMES="$nv"
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader 2>/dev/null || true
mkdir -p "$out"
for pack in "$carry"/pack*/; do
  name=$(basename "$pack")
  dir="$out/$name"
  mkdir -p "$dir"
  # BINARIES=1: each program's driver binary into OUT/<pack>/binaries (NVIDIA's holds its assembly as text).
  binaries=()
  [ -n "${BINARIES:-}" ] && binaries=(--binaries "$dir/binaries")
  for ((k = 0; k < shards; ++k)); do
    timeout "$shard_seconds" "$carry/blgpu_time" "$pack" --out "$dir" --shard "$k/$shards" \
      --compile-seconds "$compile_seconds" "${binaries[@]}" 2>"$dir/shard_$k.log" &
  done
  wait
  grep -h "failed\|error\|refused\|untimed" "$dir"/shard_*.log | sort | uniq -c | head -40
  "$carry/blgpu_time" "$pack" --out "$dir" --merge
  rm -rf "$dir/images"  # the errors are in gpu_times.json; the images stay behind
done
# One archive: a device session may bring back only a few files.
tar czf "$out.tgz" -C "$out" . && rm -rf "$out"
