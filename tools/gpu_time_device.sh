#!/usr/bin/env bash
# Device half of the GPU timing (docs/gpu_timing.md): run from the repository root on the GPU
# machine, with build/gpu_carry from tools/gpu_timing.sh. SHARDS processes compile in parallel
# (the driver's compiler is single-threaded per context) and take turns at the GPU to time.
#
#   [BINARIES=1] [CARRY=DIR] bash tools/gpu_time_device.sh OUT [SHARDS (14)] [COMPILE_SECONDS (no limit)] [SHARD_SECONDS (no limit)]
# Leaves OUT.tgz (shard logs and records, gpu_times.json, report.md).
set -uo pipefail
cd "$(dirname "$0")/.."
out="$1"
shards="${2:-14}"
compile_seconds="${3:-1000000000}"
shard_seconds="${4:-0}"  # timeout(1): 0 = no limit
carry="${CARRY:-build/gpu_carry}"  # another pack: CARRY=build/gpu_carry_before
# BINARIES=1: each program's driver binary into OUT/binaries (NVIDIA's holds its assembly as text).
binaries=()
[ -n "${BINARIES:-}" ] && binaries=(--binaries "$out/binaries")
export LD_LIBRARY_PATH="$carry/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv,noheader 2>/dev/null || true
mkdir -p "$out"
for ((k = 0; k < shards; ++k)); do
  timeout "$shard_seconds" "$carry/blgpu_time" "$carry/pack" --out "$out" --shard "$k/$shards" --compile-seconds "$compile_seconds" \
    "${binaries[@]}" 2>"$out/shard_$k.log" &
done
wait
grep -h "failed\|error\|refused\|untimed" "$out"/shard_*.log | sort | uniq -c | head -40
"$carry/blgpu_time" "$carry/pack" --out "$out" --merge
# One archive: a device session may bring back only a few files.
tar czf "$out.tgz" -C "$out" . && rm -rf "$out"
