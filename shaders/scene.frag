// A scene quad in one of five modes (one define each).
// LUT_MODE: banks with several view layers, whose LUT varies over the quad (banks of one view
//   layer are relit in texture space and drawn by FLAT_MODE: RelightPass, or per fragment by
//   LUT_FRAGMENT). RGB_MODE: a LUT per channel; GREY_TEXTURE: a grey reference.
// LUT_FRAGMENT: a bank of one view layer relit per fragment while the light moves: the
//   prediction (PREDICT_*: a predictor's; else the reference, filtered) and
//   the frame's LUTs (lut_common.glsl); DITHER per texel, as relight.
// BRDF_MODE: the paper's 2D texture mapping, brightness scaled by the target-to-reference ratio.
// PTM_MODE: the polynomial texture map, as RTI viewers draw it.
// FLAT_MODE: the plain texture, or a relit one. NEAREST_MODE: `reference` is the nearest measured image.
// UNLIT: the light is behind the quad (every mode but flat): black, a program of its own so
// the lit ones test nothing per fragment.
uniform sampler2D reference;
uniform float brightness; // brdf mode

in vec2 uv;
in vec2 quadPosition;
out vec4 colour;

#if defined(LUT_MODE)
// Banks with view layers, whose LUT varies over the quad: LUTs at viewGrid x viewGrid points
// on the quad and per mipmap level (MipLuts: level m's LUT gives a level-m texel the mean of
// the LUT values of its block), a 3D texture per channel: x the LUT's entries, y the grid's
// columns, z the grid's rows of level 0, then of level 1, ...
uniform sampler3D lut[3];
uniform vec2 lutCoordinate;  // (entries - 1) / entries, 0.5 / entries: texel centres for v in [0, 1]
uniform int viewGrid;
uniform int mipLevels;
uniform vec2 referenceSize;
float lutAt(int channel, float v, float level) {
    float grid = float(viewGrid);
    vec3 at = vec3(v * lutCoordinate.x + lutCoordinate.y, (quadPosition.x * (grid - 1.0) + 0.5) / grid,
                   (level * grid + quadPosition.y * (grid - 1.0) + 0.5) / (grid * float(mipLevels)));
    if (channel == 0) return textureLod(lut[0], at, 0.0).r;
    if (channel == 1) return textureLod(lut[1], at, 0.0).r;
    return textureLod(lut[2], at, 0.0).r;
}
// A texel of mip level `level` through that level's LUT.
vec3 shade(float level) {
    vec3 texel = textureLod(reference, uv, level).rgb;
#if defined(GREY_TEXTURE)
    return vec3(lutAt(0, texel.r, level));  // no chroma to keep
#elif defined(RGB_MODE)
    return vec3(lutAt(0, texel.r, level), lutAt(1, texel.g, level), lutAt(2, texel.b, level));
#else
    return btflutSetGrey(texel, lutAt(0, (texel.r + texel.g + texel.b) * (1.0 / 3.0), level));
#endif
}
#endif

#if defined(LUT_FRAGMENT)
uniform ivec2 texels;  // the reference's size: the dither and the prediction's fetches are per texel, as relight's
#endif

#if defined(PTM_MODE)
uniform sampler2D ptmLow, ptmHigh, ptmAlbedo;  // coefficients 0-2, 3-5 (bytes), RGB albedo
uniform BtflutModelFrame ptmFrame;              // the light's terms with scale and bias folded in

// The PTM as the light model it is (btflut.glsl's one predictor): six planes of one channel
// times the albedo, filtered and mipmapped as RTI viewers draw it.
vec3 ptmColour() {
    vec3 low = texture(ptmLow, uv).rgb * 255.0, high = texture(ptmHigh, uv).rgb * 255.0;
    vec4 codes[BTFLUT_MAX_LAYERS];
    for (int l = 0; l < BTFLUT_MAX_LAYERS; ++l) codes[l] = vec4(0.0);
    codes[0] = vec4(low, high.r);
    codes[1] = vec4(high.gb, 0.0, 0.0);
    return btflutModelPrediction(codes, 2, 1, ptmFrame, texture(ptmAlbedo, uv).rgb * 255.0).colour;
}
#endif

void main() {
#if defined(UNLIT)
    colour = vec4(0.0, 0.0, 0.0, 1.0);
#elif defined(LUT_FRAGMENT)
    ivec2 texel = ivec2(mod(floor(uv * vec2(texels)), vec2(texels)));
#if defined(GREY_TEXTURE)
    const bool grey = true;
#else
    const bool grey = false;
#endif
#if defined(BLEND)
    btflutPredictAt = texel;
    btflutPredictUv = uv;
    colour = vec4(btflutMatchedColour(uvec2(texel), grey), 1.0);
#else
    colour = vec4(btflutReferenceColour(texture(reference, uv).rgb, grey, uvec2(texel)), 1.0);
#endif
#elif defined(FLAT_MODE)
    colour = vec4(texture(reference, uv).rgb, 1.0);
#elif defined(PTM_MODE)
    colour = vec4(ptmColour(), 1.0);
#elif defined(NEAREST_MODE)
    colour = vec4(texture(reference, uv).rgb, 1.0);
#elif defined(BRDF_MODE)
    colour = vec4(min(texture(reference, uv).rgb * brightness, vec3(1.0)), 1.0);
#elif defined(LUT_MODE)
    // The two mip levels around the footprint, as trilinear filtering picks them, each through
    // its own LUT.
    vec2 dx = dFdx(uv * referenceSize), dy = dFdy(uv * referenceSize);
    float lod = clamp(0.5 * log2(max(dot(dx, dx), dot(dy, dy))), 0.0, float(mipLevels - 1));
    float lower = floor(lod);
    colour = vec4(mix(shade(lower), shade(min(lower + 1.0, float(mipLevels - 1))), lod - lower), 1.0);
#endif
}
