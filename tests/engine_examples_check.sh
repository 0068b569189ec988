#!/usr/bin/env bash
# The engine examples as far as a machine without Unity or Godot 4 can check them.
# Unity (examples/unity/): every C# file parsed by Mono's compiler; the importer's plain-C# part
# (BtflutTexels.cs) compiled and run under Mono on a real export, its decoded PNGs and half
# floats compared with Python's; the shader's HLSL program compiled by glslang's HLSL front end
# (UnityCG.cginc's two functions stubbed). Godot 4 (examples/godot/): the spatial shader with the
# include, as GLSL (its hints and built-ins mapped), compiled by glslang; the GDScript is not run.
#
#   bash tests/engine_examples_check.sh BTFLUT MATERIAL SHADERS   (a dataset; SHADERS: the built includes)
set -euo pipefail
btflut=$1
material=$2
shaders=$3
here=$(cd "$(dirname "$0")" && pwd)
unity=$here/../examples/unity
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

for file in "$unity"/Runtime/*.cs "$unity"/Editor/*.cs; do
  mcs --parse "$file" >"$work/log" 2>&1 || { cat "$work/log"; echo "unity_check: $file does not parse"; exit 1; }
done

"$btflut" bake "$material" --predictor hsh2 -o "$work/m.btflut" -q  # a model: planes to read
"$btflut" export "$work/m.btflut" -o "$work/export/" -q
mcs -nologo -warnaserror -out:"$work/check.exe" "$unity/Runtime/BtflutTexels.cs" "$here/unity/TexelsCheck.cs"
mkdir "$work/out"
mono "$work/check.exe" "$work/export" "$work/out" >"$work/said"
grep -q "x.png: not a PNG file" "$work/said"
/usr/bin/python3 - "$work/export" "$work/out" <<'PY'
import sys, numpy as np
from PIL import Image
export, out = sys.argv[1], sys.argv[2]
luts = np.array(Image.open(export + "/luts.png")).astype(np.uint16)
decoded = np.fromfile(out + "/luts.u16", dtype="<u2").reshape(luts.shape)
assert (decoded == luts).all(), "luts.png decoded differently"
halves = np.fromfile(out + "/luts.f16", dtype="<f2").reshape(luts.shape).astype(np.float64)
assert np.abs(halves - luts / 65535.0).max() <= 2.0 ** -11, "half floats off by more than half an ulp"
plane = np.array(Image.open(export + "/planes-0.png").convert("RGBA"))
rows = np.fromfile(out + "/planes-0.rgba", dtype=np.uint8).reshape(plane.shape)
assert (rows == plane[::-1]).all(), "planes-0.png: not its rows bottom first"
print("unity_check: luts.png %dx%d and planes-0.png decoded as Python does" % (luts.shape[1], luts.shape[0]))
PY

# The shader's program: HLSLPROGRAM .. ENDHLSL, UnityCG.cginc's two functions stubbed.
{
  echo 'float4x4 unity_MatrixMVP; float4 UnityObjectToClipPos(float4 p) { return mul(unity_MatrixMVP, p); }'
  echo 'float3 GammaToLinearSpace(float3 c) { return pow(c, 2.2); }'
  sed -n '/HLSLPROGRAM/,/ENDHLSL/p' "$unity/BtflutRelit.shader" | sed '1d;$d' | grep -v '#include "UnityCG.cginc"' | grep -v '#pragma'
} >"$work/relit.hlsl"
glslangValidator -D -V -S frag -e frag -I"$shaders" "$work/relit.hlsl" -o "$work/relit.spv" \
  >"$work/log" || { cat "$work/log"; exit 1; }
# A learned material's own shader, as BtflutImporter writes it: its decoder at the marker line.
"$btflut" bake "$material" --predictor neural4 --budget 1s -o "$work/n.btflut" -q
"$btflut" export "$work/n.btflut" -o "$work/learned/" -q
grep -q '^ *// btflut: network$' "$unity/BtflutRelit.shader"
sed 's|^ *// btflut: network$|#include "btflut_network.hlsl"|' "$work/relit.hlsl" >"$work/learned.hlsl"
grep -q 'btflut_network.hlsl' "$work/learned.hlsl"
glslangValidator -D -V -S frag -e frag -I"$shaders" -I"$work/learned" "$work/learned.hlsl" -o "$work/learned.spv" \
  >"$work/log" || { cat "$work/log"; exit 1; }
echo "unity_check: the C# parses, BtflutTexels runs, BtflutRelit.shader's program compiles, with a learned decoder too"

# Godot: shader_type and render_mode dropped, the include inlined, uniform hints stripped,
# fragment() as main() with UV, FRAGCOORD and ALBEDO declared.
# The same with a learned material's decoder where btflut_material.gd puts it.
godot=$here/../examples/godot
for network in "" "$work/learned/btflut_network.gdshaderinc"; do
  {
    printf '#version 450\nlayout(location = 0) in vec2 UV;\nvec3 ALBEDO;\n#define FRAGCOORD gl_FragCoord\n'
    while IFS= read -r line; do
      case "$line" in
        shader_type*|render_mode*) ;;
        '#include "res://btflut.gdshaderinc"') cat "$shaders"/btflut.gdshaderinc ;;
        '// btflut: network') [ -z "$network" ] || cat "$network" ;;
        *) printf '%s\n' "$line" ;;
      esac
    done <"$godot/btflut_relit.gdshader"
  } | sed -e 's/^\(uniform [^:=;]*\) : [^;=]*/\1/' -e 's/^void fragment()/void main()/' >"$work/relit.frag"
  [ -z "$network" ] || grep -q 'btflutNetworkValue' "$work/relit.frag"
  glslangValidator -S frag "$work/relit.frag" >"$work/log" || { cat "$work/log"; exit 1; }
done
grep -q 'res://btflut_relit.gdshader' "$godot/btflut_material.gd"
grep -q 'path="res://btflut_material.gd"' "$godot/relit.tscn"
echo "godot_check: btflut_relit.gdshader compiles with the include, and with a learned decoder"
