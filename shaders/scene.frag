// A scene quad in one of five modes (one define each). BLEND (with LUT_MODE): a bank that blends
// references and matches regions (lut_common.glsl).
// LUT_MODE: under a directional light a flat quad's light direction is constant, so its LUT
//   is blended once per frame on the CPU; here one extra filtered fetch per channel. With
//   VIEW_GRID (banks with several view layers) the LUT is a 3D texture over a grid of points
//   on the quad, so the view direction varies per fragment. RGB_MODE: a LUT per channel.
// BRDF_MODE: the paper's 2D texture mapping, brightness scaled by the target-to-reference ratio.
// PTM_MODE: the polynomial texture map, as RTI viewers draw it.
// FLAT_MODE: the plain texture. NEAREST_MODE: `reference` is the nearest measured image.
// UNLIT: the light is behind the quad (every mode but flat): black, a program of its own so
// the lit ones test nothing per fragment.
uniform sampler2D reference;
uniform float brightness; // brdf mode

in vec2 uv;
in vec2 quadPosition;
out vec4 colour;

#if defined(LUT_MODE)
// The LUT's texel centres for v in [0, 1] (v comes from a unorm texture): (entries - 1) /
// entries and 0.5 / entries, set per draw, so a fragment does one multiply-add, no division.
uniform vec2 lutCoordinate;
#if defined(VIEW_GRID)
uniform sampler3D lut[3];
uniform int viewGrid;
float lutAt(int channel, float v) {
    vec3 at = vec3(v * lutCoordinate.x + lutCoordinate.y, (quadPosition * float(viewGrid - 1) + 0.5) / float(viewGrid));
    if (channel == 0) return textureLod(lut[0], at, 0.0).r;
    if (channel == 1) return textureLod(lut[1], at, 0.0).r;
    return textureLod(lut[2], at, 0.0).r;
}
#else
uniform sampler1D lut[3];
float lutAt(int channel, float v) {
    float at = v * lutCoordinate.x + lutCoordinate.y;
    if (channel == 0) return textureLod(lut[0], at, 0.0).r;
    if (channel == 1) return textureLod(lut[1], at, 0.0).r;
    return textureLod(lut[2], at, 0.0).r;
}
#endif
#endif

#if defined(BLEND)
uniform sampler2D blendAlbedo;  // lrgb
uniform ivec2 labelSize;
vec4 btflutBlendTexel(int layer) { return texture(blendReferences, vec3(uv, float(layer))); }
#endif

#if defined(PTM_MODE)
uniform sampler2D ptmLow, ptmHigh, ptmAlbedo;  // coefficients 0-2, 3-5 (bytes), RGB albedo
uniform vec3 ptmWeightsLow, ptmWeightsHigh;    // the light's terms with scale and bias folded in
uniform float ptmOffset;
#endif

void main() {
#if defined(UNLIT)
    colour = vec4(0.0, 0.0, 0.0, 1.0);
#elif defined(FLAT_MODE)
    colour = vec4(texture(reference, uv).rgb, 1.0);
#elif defined(PTM_MODE)
    float luminance = dot(texture(ptmLow, uv).rgb, ptmWeightsLow) + dot(texture(ptmHigh, uv).rgb, ptmWeightsHigh) +
                      ptmOffset;
    colour = vec4(clamp(texture(ptmAlbedo, uv).rgb * luminance, 0.0, 1.0), 1.0);
#elif defined(NEAREST_MODE)
    colour = vec4(texture(reference, uv).rgb, 1.0);
#elif defined(BRDF_MODE)
    colour = vec4(min(texture(reference, uv).rgb * brightness, vec3(1.0)), 1.0);
#elif defined(BLEND)
    // A bank that blends references: the blend, rounded to its codes, through its region's LUT.
#if defined(REGIONS)
    uint region = texelFetch(blendLabels, ivec2(mod(floor(uv * vec2(labelSize)), vec2(labelSize))), 0).r;
#else
    uint region = 0u;
#endif
    BtflutBlend blend = btflutBlend();
#if defined(RGB_MODE)
    colour = vec4(btflutBlendLut(0, region, btflutBlendValue(blend.codes.r)), btflutBlendLut(1, region, btflutBlendValue(blend.codes.g)),
                  btflutBlendLut(2, region, btflutBlendValue(blend.codes.b)), 1.0);
#elif defined(BLEND_PACKED)
    colour = vec4(btflutSetGrey(texture(blendAlbedo, uv).rgb, btflutBlendLut(0, region, btflutBlendValue(blend.codes.x))), 1.0);
#else
    colour = vec4(btflutSetGrey(blend.colour, btflutBlendLut(0, region, btflutBlendValue(blend.codes.x))), 1.0);
#endif
#elif defined(GREY_TEXTURE)
    colour = vec4(vec3(lutAt(0, texture(reference, uv).r)), 1.0);  // no chroma to keep
#elif defined(RGB_MODE)
    vec3 texel = texture(reference, uv).rgb;
    colour = vec4(lutAt(0, texel.r), lutAt(1, texel.g), lutAt(2, texel.b), 1.0);
#else
    vec3 texel = texture(reference, uv).rgb;
    float grey = (texel.r + texel.g + texel.b) * (1.0 / 3.0);
    colour = vec4(btflutSetGrey(texel, lutAt(0, grey)), 1.0);
#endif
}
