// LUT application shared by btflut's fragment shaders (after btflut.glsl, whose dither hash
// and grey step they use): the GLSL twin of src/core/histogram/lut.h (lutInput, lutOutput) and of
// applyLuts in src/core/bank/lut_bank.cpp, bit for bit, so CPU relighting and GPU rendering agree.
// (Compiled and tested against `btflut relight` by the renderer, issue 5.)

// The LUT (a 1D texture of `entries` texels, linear filtering) at v in [0, 1]. textureLod: a
// LUT has no mipmaps, so the fetch needs no derivatives.
float btflutApplyLut(sampler1D lut, int entries, float v) {
    float position = clamp(v, 0.0, 1.0) * float(entries - 1);
    return textureLod(lut, (position + 0.5) / float(entries), 0.0).r;
}

// The frame's LUTs, as RelightPass (native.frag) and the scene's per-fragment path
// (scene.frag, LUT_FRAGMENT) apply them: MAPS_REFERENCE for banks of LUTs, BLEND for banks that
// make their LUTs; DITHER; PREDICTION_ONLY leaves the LUTs out (bench render's baseline).
uniform float outCode;  // one target code

// LUT_UNIFORMS N: the frame's LUTs as N uniform floats, [region][channel][entry] (read as an
// array, they cost llvmpipe a third of a filtered fetch per pixel); else as textures.
#if defined(LUT_UNIFORMS)
uniform float lutValues[LUT_UNIFORMS];

// LUT `lut` (region * channels + channel) of `count` entries at v: Lut::applyLut's arithmetic,
// in the same order.
float btflutUniformLut(int lut, int count, float v) {
    float position = clamp(v, 0.0, 1.0) * float(count - 1);
    int i = min(int(position), count - 2), at = lut * count + i;
    return lutValues[at] + (position - float(i)) * (lutValues[at + 1] - lutValues[at]);
}
#endif

// Banks that blend references (src/core/relight/relighter.h; defines BLEND, BLEND_PACKED for lrgb,
// BLEND_MODEL for a light model, REGIONS). The blend is exact integer arithmetic in float
// (8-bit codes times integer weights, sums below 2^24), so its code is the CPU's; the LUT
// of the texel's region is applied to it.
#if defined(BLEND)
// grey and rgb: one reference per layer (grey references in all three channels:
// BLEND_GREY_REFERENCES); lrgb: four per RGBA layer; BLEND_MODEL: the light
// model's 8-bit planes three to a layer (BLEND_MODEL_LAYERS), its 4-bit planes six to a layer
// (BLEND_MODEL_NIBBLE_LAYERS: two to a channel, the first in the high nibble), then its albedo
// (BLEND_MODEL_ALBEDO)
uniform sampler2DArray blendReferences;
#if defined(BLEND_MODEL)
// src/core/predict/light_model.h, LightModelFixed: per layer and channel, the integer weights
// of its three planes (4-bit layers: of their high, then their low nibbles); per channel the
// integer offset; the power of two to value * 4096.
#if BLEND_MODEL_LAYERS > 0
uniform vec3 blendModelWeights[BLEND_MODEL_LAYERS * BLEND_MODEL_CHANNELS];
#endif
#if BLEND_MODEL_NIBBLE_LAYERS > 0
uniform vec3 blendModelNibbleWeights[BLEND_MODEL_NIBBLE_LAYERS * BLEND_MODEL_CHANNELS * 2];
#endif
uniform vec3 blendModelOffset;
uniform float blendModelScale;
#elif defined(BLEND_PACKED)
uniform vec4 blendWeights[BLEND_LAYERS]; // per layer, the integer weights of its four references (BLEND_LAYERS: 1 to 4)
#else
uniform int blendLayer[BLEND_FETCHES];   // the references around the light (BLEND_FETCHES: min(K, 3))
uniform float blendWeight[BLEND_FETCHES]; // integers summing to 4096
#endif
uniform float blendCodes;                // codes of a blended value: 765 for the grey of RGB8, 255 for one channel
uniform sampler2D blendLuts[3];          // per channel: a LUT per region (row)
uniform int blendEntries;
uniform int blendRegions;
#if defined(REGIONS)
uniform usampler2D blendLabels;
#endif
#if defined(BLEND_PACKED)
uniform sampler2D blendAlbedo;           // lrgb: the chroma
#endif

// A reference layer's texel at btflutBlendAt (below).
vec4 btflutBlendTexel(int layer);

vec4 btflutBytes(vec4 texel) { return floor(texel * 255.0 + 0.5); }

// The blend: its colour (chroma for grey mode), and its codes (per channel for rgb, else in
// .x), integers in 0 .. blendCodes.
struct BtflutBlend {
    vec3 colour;
    vec3 codes;
};

BtflutBlend btflutBlend() {
    BtflutBlend b;
#if defined(BLEND_MODEL)
    vec3 value = vec3(0.0);  // each channel's value before the albedo, times 4096
    for (int c = 0; c < BLEND_MODEL_CHANNELS; ++c) {  // unrolled: constant bounds
        float sum = blendModelOffset[c];
#if BLEND_MODEL_LAYERS > 0
        for (int l = 0; l < BLEND_MODEL_LAYERS; ++l)
            sum += dot(btflutBytes(btflutBlendTexel(l)).rgb, blendModelWeights[l * BLEND_MODEL_CHANNELS + c]);
#endif
#if BLEND_MODEL_NIBBLE_LAYERS > 0
        for (int l = 0; l < BLEND_MODEL_NIBBLE_LAYERS; ++l) {
            vec3 bytes = btflutBytes(btflutBlendTexel(BLEND_MODEL_LAYERS + l)).rgb;
            vec3 high = floor(bytes / 16.0);
            int at = (l * BLEND_MODEL_CHANNELS + c) * 2;
            sum += dot(high, blendModelNibbleWeights[at]) + dot(bytes - 16.0 * high, blendModelNibbleWeights[at + 1]);
        }
#endif
        value[c] = floor(sum * blendModelScale);
    }
#if BLEND_MODEL_CHANNELS == 1
    value = vec3(value.x);
#endif
#if defined(BLEND_MODEL_ALBEDO)
    vec3 channels = clamp(btflutBytes(btflutBlendTexel(BLEND_MODEL_LAYERS + BLEND_MODEL_NIBBLE_LAYERS)).rgb * value, 0.0,
                          255.0 * 4096.0);
#else
    vec3 channels = clamp(255.0 * value, 0.0, 255.0 * 4096.0);
#endif
    b.colour = channels / (255.0 * 4096.0);
#if defined(RGB_MODE)
    b.codes = floor(channels / 4096.0 + 0.5);  // each channel matched apart
#elif BLEND_MODEL_CHANNELS == 1 && !defined(BLEND_MODEL_ALBEDO)
    b.codes = vec3(floor(channels.r / 4096.0 + 0.5));
#else
    b.codes = vec3(floor((channels.r + channels.g + channels.b) / 4096.0 + 0.5));
#endif
#elif defined(BLEND_PACKED)
    float sum = 0.0;
    for (int l = 0; l < BLEND_LAYERS; ++l) sum += dot(btflutBytes(btflutBlendTexel(l)), blendWeights[l]);  // unrolled: a constant bound
    b.codes = vec3(floor(sum / 4096.0 + 0.5));
    b.colour = vec3(b.codes.x / 255.0);
#else
    vec3 sum = vec3(0.0);
    b.colour = vec3(0.0);
    for (int k = 0; k < BLEND_FETCHES; ++k) {  // unrolled
        vec4 texel = btflutBlendTexel(blendLayer[k]);
        sum += blendWeight[k] * btflutBytes(texel).rgb;
        b.colour += blendWeight[k] / 4096.0 * texel.rgb;
    }
#if defined(RGB_MODE)
    b.codes = floor(sum / 4096.0 + 0.5);
#elif defined(BLEND_GREY_REFERENCES)
    b.codes = vec3(floor(sum.r / 4096.0 + 0.5));  // one channel (stored in all three)
#else
    b.codes = vec3(floor((sum.r + sum.g + sum.b) / 4096.0 + 0.5));  // the grey of RGB: the channel codes' sum
#endif
#endif
    return b;
}

// A code read at the top of its cell [q, q + 1) / (codes + 1) (Relighter::inputCode).
float btflutBlendValue(float code) { return (code + 1.0) / (blendCodes + 1.0); }

// The texel the blend reads (texelFetch at level 0): set by each shader's main. BLEND_FILTERED
// (the scene's per-fragment path) samples bilinearly at btflutBlendUv instead, so a magnified
// quad is smooth while the light moves, as its relit texture is once it stops: the prediction
// of filtered planes, each rounded to 8 bits; 4-bit planes, two to a byte, are fetched as they are.
ivec2 btflutBlendAt;
vec2 btflutBlendUv;

vec4 btflutBlendTexel(int layer) {
#if defined(BLEND_FILTERED)
#if defined(BLEND_MODEL) && BLEND_MODEL_NIBBLE_LAYERS > 0
    if (layer >= BLEND_MODEL_LAYERS && layer < BLEND_MODEL_LAYERS + BLEND_MODEL_NIBBLE_LAYERS)
        return texelFetch(blendReferences, ivec3(btflutBlendAt, layer), 0);
#endif
    return textureLod(blendReferences, vec3(btflutBlendUv, float(layer)), 0.0);
#else
    return texelFetch(blendReferences, ivec3(btflutBlendAt, layer), 0);
#endif
}

// A region's LUT applied to a blended code (below).
float btflutBlendMap(int channel, uint region, float code, uvec2 pixel);

// The texel's relit colour: grey keeps the blend's chroma (lrgb: the albedo's), rgb matches
// each channel; `greyReference`: the bank's references have one channel.
vec3 btflutBlendColour(uvec2 pixel, bool greyReference) {
#if defined(REGIONS)
    uint region = texelFetch(blendLabels, btflutBlendAt, 0).r;
#else
    uint region = 0u;
#endif
    BtflutBlend blend = btflutBlend();
#if defined(RGB_MODE)
    return vec3(btflutBlendMap(0, region, blend.codes.r, pixel), btflutBlendMap(1, region, blend.codes.g, pixel),
                btflutBlendMap(2, region, blend.codes.b, pixel));
#elif defined(BLEND_PACKED)
    return btflutSetGrey(texelFetch(blendAlbedo, btflutBlendAt, 0).rgb, btflutBlendMap(0, region, blend.codes.x, pixel));
#else
    if (greyReference) return vec3(btflutBlendMap(0, region, blend.codes.x, pixel));
    return btflutSetGrey(blend.colour, btflutBlendMap(0, region, blend.codes.x, pixel));
#endif
}

// The LUT of a region at v in [0, 1] (linear between entries, as Lut::applyLut).
float btflutBlendLut(int channel, uint region, float v) {
#if defined(LUT_UNIFORMS) && defined(RGB_MODE)
    return btflutUniformLut(int(region) * 3 + channel, blendEntries, v);
#elif defined(LUT_UNIFORMS)
    return btflutUniformLut(int(region), blendEntries, v);
#endif
    vec2 at = vec2((clamp(v, 0.0, 1.0) * float(blendEntries - 1) + 0.5) / float(blendEntries),
                   (float(region) + 0.5) / float(blendRegions));
    if (channel == 0) return textureLod(blendLuts[0], at, 0.0).r;
    if (channel == 1) return textureLod(blendLuts[1], at, 0.0).r;
    return textureLod(blendLuts[2], at, 0.0).r;
}

// The same, dithered as btflutMapValue (code: 1 / (blendCodes + 1)).
float btflutBlendLutDithered(int channel, uint region, float v, uvec2 pixel, float outCode) {
    float moved = v + (btflutDitherOffset(pixel.x, pixel.y, uint(channel)) - 0.5) / (blendCodes + 1.0);
    float value = btflutBlendLut(channel, region, moved);
    return value > 0.0 ? min(1.0, value + 0.5 * outCode) : 0.0;
}

float btflutBlendMap(int channel, uint region, float code, uvec2 pixel) {
#if defined(PREDICTION_ONLY)
    return code / blendCodes;  // bench render's baseline: the predictor as an RTI viewer draws it
#elif defined(DITHER)
    return btflutBlendLutDithered(channel, region, btflutBlendValue(code), pixel, outCode);
#else
    return btflutBlendLut(channel, region, btflutBlendValue(code));
#endif
}
#endif  // BLEND

#if defined(MAPS_REFERENCE)
// Banks of LUTs: the frame's LUT per channel (grey mode uses the first), from uniforms
// (LUT_UNIFORMS) or 1D textures.
uniform int entries;
uniform float inCode;  // one input code of the value a LUT maps
#if defined(LUT_UNIFORMS)
float btflutLutAt(int channel, float v) { return btflutUniformLut(channel, entries, v); }
#else
uniform sampler1D lut[3];

float btflutLutAt(int channel, float v) {
    if (channel == 0) return btflutApplyLut(lut[0], entries, v);
    if (channel == 1) return btflutApplyLut(lut[1], entries, v);
    return btflutApplyLut(lut[2], entries, v);
}
#endif

// A channel's LUT applied to v, dithered per `pixel` (DITHER): the input moved within its
// code's cell [v - code, v), the output raised half a target code (code 0 stays black).
float btflutMapValue(int channel, float v, uvec2 pixel) {
#if defined(PREDICTION_ONLY)
    return v;
#elif defined(DITHER)
    float value = btflutLutAt(channel, v + (btflutDitherOffset(pixel.x, pixel.y, uint(channel)) - 0.5) * inCode);
    return value > 0.0 ? min(1.0, value + 0.5 * outCode) : 0.0;
#else
    return btflutLutAt(channel, v);
#endif
}

// A reference texel (its stored values) through the LUTs: grey keeps its chroma, rgb maps each
// channel.
vec3 btflutReferenceColour(vec3 texel, bool greyReference, uvec2 pixel) {
    if (greyReference) return vec3(btflutMapValue(0, texel.r, pixel));
#if defined(RGB_MODE)
    return vec3(btflutMapValue(0, texel.r, pixel), btflutMapValue(1, texel.g, pixel), btflutMapValue(2, texel.b, pixel));
#else
    return btflutSetGrey(texel, btflutMapValue(0, (texel.r + texel.g + texel.b) * (1.0 / 3.0), pixel));
#endif
}
#endif
