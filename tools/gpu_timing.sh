#!/usr/bin/env bash
# Host half of the GPU timing (docs/gpu_timing.md): packs a tuned suite's GLSL (blgpu_pack) and, by
# default, the tuned users' patterns (docs/tuning/glsl), the timing tool and the GL loader libraries
# it links (glvnd's libEGL/libOpenGL/libGLdispatch, which a GPU machine with only the vendor driver
# may lack) into one folder, build/gpu_carry (pack/ and pack_glsl/). On the GPU machine, from the
# repository root: bash tools/gpu_time_device.sh OUT (times every pack in it).
#
#   [ONLY=SUBSTR] [PACK_ARGS='--baselines plain,msaa16 --fronts 3'] [GLSL_SUITE=docs/tuning/glsl | GLSL_SUITE=]
#     bash tools/gpu_timing.sh [SUITE_DIR | - (no suite pack)] [TILE (10)]
set -euo pipefail
cd "$(dirname "$0")/.."
suite="${1:-docs/tuning/suite}"
tile="${2:-10}"
glsl_suite="${GLSL_SUITE-docs/tuning/glsl}"
cmake --build build --target blgpu_pack blgpu_time >/dev/null
rm -rf build/gpu_carry
mkdir -p build/gpu_carry/lib
if [ "$suite" != "-" ]; then  # "-": the patterns only
  build/bin/blgpu_pack --suite "$suite" --scenes scenes/suite --out build/gpu_carry/pack --tile "$tile" ${ONLY:+--only "$ONLY"} ${PACK_ARGS:-}
fi
if [ -n "$glsl_suite" ]; then
  build/bin/blgpu_pack --suite "$glsl_suite" --scenes scenes/glsl --out build/gpu_carry/pack_glsl --tile "$tile" \
    ${ONLY:+--only "$ONLY"} ${PACK_ARGS:-}
fi
cp build/bin/blgpu_time build/gpu_carry/
for lib in libEGL.so.1 libOpenGL.so.0 libGLdispatch.so.0; do
  path="$(ldd build/bin/blgpu_time | awk -v l="$lib" '$1 == l { print $3 }')"
  [ -n "$path" ] || { echo "gpu_timing.sh: blgpu_time does not link $lib" >&2; exit 1; }
  cp -L "$path" build/gpu_carry/lib/
done
du -sh build/gpu_carry
