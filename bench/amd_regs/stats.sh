#!/bin/sh
# bench/amd_regs/stats.sh: register proxy for a shade kernel without a GPU.
# Assembles KERNEL as the host does (gpu/program.h, with DEFINES), turns it
# into Vulkan SPIR-V (glslang, relaxed rules) and compiles it with Mesa's
# RADV/ACO on a null navi21 device, printing VGPRs, spills, code size and
# waves per SIMD. AMD's allocator is not NVIDIA's: compare kernels with
# each other, not with a GPU's occupancy.
#   needs: mesa-vulkan-drivers glslang-tools spirv-tools libvulkan-dev, a
#   built tree (libcavalry.a)
#   usage: bench/amd_regs/stats.sh GLSL_TREE KERNEL DEFINES...
#   e.g.   bench/amd_regs/stats.sh $PWD trace/shade.comp CV_SHADE_BIN=2 CV_NO_ENV
set -eu
here=$(cd "$(dirname "$0")" && pwd)
top=$(cd "$here/../.." && pwd)
tree=$1; k=$2; shift 2
w=${TMPDIR:-/tmp}/amd_regs.$$
mkdir -p "$w"
trap 'rm -rf "$w"' EXIT
cc -std=c11 -Wall -Wextra -I"$top/src" -I"$top" "$here/assemble.c" "$top/libcavalry.a" -lEGL -lepoxy -lOpenColorIO \
    -lOpenEXR-3_1 -lOpenEXRUtil-3_1 -lOpenEXRCore-3_1 -lIex-3_1 -lIlmThread-3_1 -lImath-3_1 -lOSMesa -lpng16 \
    -lstb -lyaml -lm -lstdc++ -lpthread -o "$w/assemble"
cc -std=c11 -Wall -Wextra "$here/vkstats.c" -lvulkan -o "$w/vkstats"
CAVALRY_DATA_DIR=$tree "$w/assemble" "$k" "$@" > "$w/k.comp"
# GL-only forms Vulkan GLSL refuses: #line with file numbers, the size
# checks' stray semicolons, `sampler` as a name
grep -v "^#line" "$w/k.comp" | perl -0pe 's/\nCV_CHECK_SIZE\([^;]*\);//g; s/\bsampler\b/sampler_/g' > "$w/vk.comp"
glslangValidator -S comp -V -R --amb --aml -o "$w/k.spv" "$w/vk.comp" > /dev/null
spirv-dis "$w/k.spv" -o "$w/k.spvasm"
python3 "$here/remap.py" "$w/k.spvasm" "$w/r.spvasm" "$w/layout"
spirv-as --target-env vulkan1.0 "$w/r.spvasm" -o "$w/r.spv"
RADV_FORCE_FAMILY=navi21 VK_ICD_FILENAMES=/usr/share/vulkan/icd.d/radeon_icd.x86_64.json \
    "$w/vkstats" "$w/r.spv" "$w/layout" 2>/dev/null |
    grep -E "^(VGPRs|Spilled [VS]GPRs|Scratch size|Code size|Subgroups per SIMD|Instructions):" |
    tr '\n' ' '
echo
