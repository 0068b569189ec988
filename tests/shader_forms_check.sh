#!/usr/bin/env bash
# The include's generated forms (tools/shader-forms.sh) compiled as engines include them:
# btflut.hlsl in a Unity- or Unreal-style pixel shader through glslang's HLSL front end, and
# btflut_es.glsl in a WebGL2 fragment shader. Both call every public function.
#
#   bash tests/shader_forms_check.sh BUILD/src/gl/shaders
set -euo pipefail
forms=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat >"$work/unity.hlsl" <<'HLSL'
#include "btflut.hlsl"
Texture3D<float4> _Luts; SamplerState sampler_Luts;
Texture2D<float4> _Reference; SamplerState sampler_Reference;
Texture2DArray<float4> _Planes; SamplerState sampler_Planes;
Texture2DArray<float4> _Weights; SamplerState sampler_Weights;
Texture2D<float4> _Labels; SamplerState sampler_Labels;
cbuffer Material { float3 _LightTangent; int _Kind; float4 _Codes; float4 _Scale[8]; float4 _Bias[8]; };
float4 main(float2 uv : TEXCOORD0, float4 position : SV_Position) : SV_Target {
    uint2 pixel = uint2(position.xy);
    if (_Kind == 0) {
        BtflutMaterial m;
        m.layer = 0; m.rgbLuts = false; m.greyReference = true; m.inputCode = _Codes.x; m.outputCode = _Codes.y; m.dither = true;
        float3 reference = _Reference.Sample(sampler_Reference, uv).rgb;
        return float4(btflutRelight(_Luts, sampler_Luts, m, reference, _LightTangent, pixel), 1.0);
    }
    BtflutPredictor p;
    p.kind = _Kind; p.basis = 1; p.order = 2; p.planes = 4; p.channels = 1; p.albedo = 0; p.regions = 1;
    for (int k = 0; k < 32; ++k) { p.scale[k] = _Scale[k / 4][k % 4]; p.bias[k] = _Bias[k / 4][k % 4]; }
    p.codes = 255.0; p.rgbLuts = false; p.greyOutput = true; p.outputCode = _Codes.y; p.dither = true;
    float3 predicted = btflutPredict(_Planes, sampler_Planes, _Weights, sampler_Weights, p, uv, _LightTangent);
    return float4(predicted / 255.0 + btflutRelight(_Luts, sampler_Luts, _Planes, sampler_Planes, _Weights, sampler_Weights,
                                                    _Labels, sampler_Labels, p, uv, _LightTangent, pixel), 1.0);
}
HLSL
glslangValidator -D -V -S frag -e main -I"$forms" "$work/unity.hlsl" -o "$work/unity.spv" >"$work/log" || { cat "$work/log"; exit 1; }

{ echo "#version 300 es"; cat "$forms/btflut_es.glsl"; cat <<'GLSL'
uniform sampler3D luts;
uniform sampler2DArray planes, weights;
uniform highp sampler2D labels, reference;
uniform BtflutMaterial material;
uniform BtflutPredictor predictor;
uniform vec3 lightTangent;
in vec2 uv;
out vec4 colour;
void main() {
    uvec2 pixel = uvec2(gl_FragCoord.xy);
    colour = vec4(btflutRelight(luts, planes, weights, labels, predictor, uv, lightTangent, pixel) +
                  btflutRelight(luts, material, texture(reference, uv).rgb, lightTangent, pixel) +
                  btflutPredict(planes, weights, predictor, uv, lightTangent) / 255.0, 1.0);
}
GLSL
} >"$work/webgl.frag"
glslangValidator "$work/webgl.frag" >"$work/log" || { cat "$work/log"; exit 1; }
# The generated forms carry the include they came from.
for f in btflut_es.glsl btflut.hlsl btflut.gdshaderinc; do
  grep -q "BTFLUT_GLSL_VERSION $(sed -n 's/^#define BTFLUT_GLSL_VERSION \([0-9]*\).*/\1/p' "$(dirname "$0")/../shaders/btflut.glsl")" "$forms/$f"
done
# The C++ side's idea of the include's version (what sidecars of learned models ask for).
glsl_version=$(sed -n 's/^#define BTFLUT_GLSL_VERSION \([0-9]*\).*/\1/p' "$(dirname "$0")/../shaders/btflut.glsl")
grep -q "kShaderIncludeVersion = $glsl_version;" "$(dirname "$0")/../src/core/predict/predictor.h" ||
  { echo "shader forms: kShaderIncludeVersion (predictor.h) is not BTFLUT_GLSL_VERSION $glsl_version" >&2; exit 1; }
echo "shader forms: btflut.hlsl builds in an HLSL pixel shader, btflut_es.glsl in a GLSL ES 3.00 one"
