#!/usr/bin/env bash
# Per program of a blgpu_time --binaries folder (BINARIES=1 bash tools/gpu_time_device.sh OUT): the
# local memory NVIDIA's compiler gave the fragment program ("TEMP lmem0[N]": N four-float slots per
# invocation) and the length of its assembly. NVIDIA's program binary holds that assembly as text
# (!!NVfp5.0); other drivers' binaries print "-". Large lmem is what made the bumps programs slow
# (docs/gpu_timing.md, stop 28): every inlined piece table got its own slots.
#
#   bash tools/gpu_binary_stats.sh DIR [GPU_TIMES_JSON]   (sorted by lmem; with the JSON, ns/px beside)
set -euo pipefail
dir="$1"
times="${2:-}"
[ -d "$dir" ] || { echo "gpu_binary_stats.sh: $dir: no such folder" >&2; exit 2; }
# ns/px per "<scene>__<label>", read from the JSON once.
declare -A ns_of=()
if [ -n "$times" ]; then
  while read -r key ns; do ns_of["$key"]="$ns"; done < <(python3 -c 'import json,sys
for p in json.load(open(sys.argv[1]))["programs"]: print("%s__%s %.3f" % (p["scene"], p["label"], p["gpu_ns_per_pixel"]))' "$times")
fi
printf '%-40s %8s %8s %10s\n' program lmem lines "ns/px"
for f in "$dir"/*.bin; do
  name="$(basename "$f" .bin)"
  asm="$(strings -n 3 "$f" | awk '/^!!NVfp5.0/{p=1} p')"
  if [ -z "$asm" ]; then lmem="-" lines="-"; else
    lmem="$(sed -n 's/^TEMP lmem0\[\([0-9]*\)\];.*/\1/p' <<<"$asm" | head -1)"
    lmem="${lmem:-0}"
    lines="$(wc -l <<<"$asm")"
  fi
  printf '%-40s %8s %8s %10s\n' "$name" "$lmem" "$lines" "${ns_of[$name]:--}"
done | sort -k2,2nr
