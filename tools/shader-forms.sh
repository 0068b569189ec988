#!/usr/bin/env bash
# The shader include in other shading languages, all generated from shaders/btflut.glsl (run
# by src/gl/CMakeLists.txt at configure time; never edited by hand):
#   btflut_es.glsl      GLSL ES 3.00 (WebGL2, three.js): the same text after precision lines
#   btflut.hlsl         HLSL, shader model 5 (Unity, Unreal): glslang compiles the include
#                       inside a wrapper to SPIR-V, SPIRV-Cross writes HLSL, and the wrapper's
#                       resources and entry point are cut away, leaving structs and functions
#   btflut.gdshaderinc  Godot 4's shading language (GLSL ES-like): the same text
#
#   bash tools/shader-forms.sh shaders/btflut.glsl OUT_DIR
set -euo pipefail
source=$1
out=$2
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for tool in glslangValidator spirv-cross; do
  command -v "$tool" >/dev/null || { echo "shader-forms: $tool not found (bash tools/setup.sh installs it)" >&2; exit 1; }
done
version=$(sed -n 's/^#define BTFLUT_GLSL_VERSION \([0-9]*\).*/\1/p' "$source")

# GLSL ES 3.00: precision for the types ES gives none by default.
{
  echo "// btflut_es.glsl: btflut.glsl (version $version) for GLSL ES 3.00 (WebGL2, three.js), generated"
  echo "// from it at build time. Put \`#version 300 es\` first. Everything below the precision lines is"
  echo "// btflut.glsl unchanged: its comments and docs/engines.md describe it."
  echo "precision highp float;"
  echo "precision highp int;"
  echo "precision highp sampler3D;"
  echo "precision highp sampler2DArray;"
  echo
  cat "$source"
} > "$work/btflut_es.glsl"
# Checked as ES before it is kept: a fragment shader that calls both btflutRelight overloads.
{ echo "#version 300 es"; cat "$work/btflut_es.glsl"; cat <<'GLSL'
uniform sampler3D luts; uniform sampler2DArray planes, weights; uniform highp sampler2D labels, reference;
uniform BtflutPredictor predictor; uniform BtflutMaterial material;
in vec2 uv; in vec3 lightTangent; out vec4 colour;
void main() {
    uvec2 pixel = uvec2(gl_FragCoord.xy);
    colour = vec4(btflutRelight(luts, planes, weights, labels, predictor, uv, lightTangent, pixel) +
                  btflutRelight(luts, material, texture(reference, uv).rgb, lightTangent, pixel), 1.0);
}
GLSL
} > "$work/es.frag"
glslangValidator "$work/es.frag" > "$work/log" || { cat "$work/log" >&2; exit 1; }

# HLSL. The structs go into a uniform block as plain vectors (HLSL packs a struct's arrays
# differently from std140), so every function is reachable and none is inlined away.
{ echo "#version 450"; cat "$source"; cat <<'GLSL'
layout(binding = 0) uniform sampler3D luts;
layout(binding = 1) uniform sampler2DArray planes;
layout(binding = 2) uniform sampler2DArray weights;
layout(binding = 3) uniform sampler2D labels;
layout(binding = 4) uniform sampler2D reference;
layout(binding = 5, std140) uniform Fields { ivec4 a; ivec4 b; vec4 codes; ivec4 flags; vec4 scale[8]; vec4 bias[8]; };
layout(location = 0) in vec2 uv;
layout(location = 1) in vec3 lightTangent;
layout(location = 0) out vec4 colour;
void main() {
    BtflutPredictor p;
    p.kind = a.x; p.basis = a.y; p.order = a.z; p.planes = a.w; p.channels = b.x; p.albedo = b.y; p.regions = b.z;
    for (int k = 0; k < BTFLUT_MAX_PLANES; ++k) { p.scale[k] = scale[k / 4][k % 4]; p.bias[k] = bias[k / 4][k % 4]; }
    p.codes = codes.x; p.outputCode = codes.y; p.rgbLuts = flags.x != 0; p.greyOutput = flags.y != 0; p.dither = flags.z != 0;
    BtflutMaterial m = BtflutMaterial(b.w, flags.x != 0, flags.w != 0, codes.z, codes.y, flags.z != 0);
    uvec2 pixel = uvec2(gl_FragCoord.xy);
    colour = vec4(btflutRelight(luts, planes, weights, labels, p, uv, lightTangent, pixel) +
                  btflutRelight(luts, m, texture(reference, uv).rgb, lightTangent, pixel) +
                  btflutPredict(planes, weights, p, uv, lightTangent) / 255.0, 1.0);
}
GLSL
} > "$work/hlsl.frag"
glslangValidator -V -g "$work/hlsl.frag" -o "$work/hlsl.spv" > "$work/log" || { cat "$work/log" >&2; exit 1; }
spirv-cross "$work/hlsl.spv" --hlsl --shader-model 50 --output "$work/full.hlsl"
# Keep the structs (before the wrapper's cbuffer) and the functions (from SPIRV-Cross's
# helpers up to the wrapper's entry point).
{
  echo "// btflut.hlsl: btflut.glsl (version $version) in HLSL, shader model 5 (Unity, Unreal), generated from it"
  echo "// at build time by glslang and SPIRV-Cross (tools/shader-forms.sh). The same functions and"
  echo "// structs; each sampler is a texture and its SamplerState, passed side by side."
  echo "#ifndef BTFLUT_HLSL"
  echo "#define BTFLUT_HLSL"
  echo "#define BTFLUT_GLSL_VERSION $version"
  awk '/^cbuffer /{exit} {print}' "$work/full.hlsl"
  awk '/^static float4 gl_FragCoord;/{skip=1} skip && /^(float|int|uint|void)[0-9]* [a-zA-Z]+\(/{keep=1} /^void frag_main\(\)/{exit} keep{print}' \
    "$work/full.hlsl" | sed -E 's/\bmod\(/btflutMod(/g; s/spvTextureSize/btflutTextureSize/g'  # names of our own
  echo "#endif"
} > "$work/btflut.hlsl"
grep -q "^float3 btflutRelight(" "$work/btflut.hlsl" || { echo "shader-forms: no btflutRelight in SPIRV-Cross's HLSL" >&2; exit 1; }

# Godot 4: its language reads the include as it is; `#include "res://btflut.gdshaderinc"`.
{
  echo "// btflut.gdshaderinc: btflut.glsl (version $version) for Godot 4's shading language, generated from it at"
  echo "// build time: \`#include \"res://btflut.gdshaderinc\"\` in a spatial or canvas_item shader."
  echo
  cat "$source"
} > "$work/btflut.gdshaderinc"

for f in btflut_es.glsl btflut.hlsl btflut.gdshaderinc; do
  cmp -s "$work/$f" "$out/$f" 2>/dev/null || cp "$work/$f" "$out/$f"
done
