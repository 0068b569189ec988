// btflut's own renderer (after btflut.glsl, whose predictor, dither hash and grey step it uses):
// the GLSL twin of src/core/histogram/lut.h (lutInput, lutOutput) and of applyLuts in
// src/core/bank/lut_bank.cpp, and btflut.glsl's predictor driven by the CPU's integers at the
// light, bit for bit, so CPU relighting and GPU rendering agree. (Compiled and tested against
// `btflut relight` by the renderer, issue 5.)

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

// Banks with a predictor (src/core/predict/predictor.h; defines BLEND, the predictor's own
// from Predictor::shaderDefines, REGIONS): btflut.glsl's prediction (btflutModelPrediction,
// btflutAddReference) of the CPU's integers at the light. The arithmetic is exact in float
// (8-bit codes times integer weights, sums below 2^24), so its codes are the CPU's; the LUT of
// the texel's region is applied to them.
#if defined(BLEND)
// The predictor's planes as engines get them (Predictor::planes): RGBA8 layers, a light
// model's planes four to a layer (its 4-bit codes n as 17 n), or one reference to a layer (a
// grey one in R, G and B); then the albedo at PREDICT_ALBEDO_LAYER (PREDICT_MODEL_ALBEDO: it
// multiplies the model's value; PREDICT_ALBEDO_CHROMA: lrgb's chroma after the match).
uniform sampler2DArray predictPlanes;
#if defined(PREDICT_LEARNED)
uniform BtflutLearnedFrame predictLearned;  // LearnedModel::lightFrame: the decoder's part at the light
#if !defined(BTFLUT_NETWORK)
uniform sampler2DArray predictNetwork;  // the decoder's texture, for a network past a shader's constants
#endif
#elif defined(PREDICT_MODEL)
uniform BtflutModelFrame predictModel;  // LightModelFixed: the weights of the codes n of 4-bit planes
#else
uniform int blendLayer[PREDICT_FETCHES];   // the references around the light (PREDICT_FETCHES: min(K, 3))
uniform float blendWeight[PREDICT_FETCHES]; // integers summing to BTFLUT_WEIGHT_UNIT
#endif
uniform float predictCodes;                // codes of a blended value: 765 for the grey of RGB8, 255 for one channel
uniform sampler2D matchLuts[3];          // per channel: a LUT per region (row)
uniform int matchEntries;
uniform int matchRegions;
#if defined(REGIONS)
uniform usampler2D predictLabels;
#endif

// How the prediction's codes are matched: PREDICT_MATCH, from the predictor's codes as
// btflutMatchOf has it for engines (PredictionTextures::upload), whatever its kind.
const int btflutPredictMatch = PREDICT_MATCH;

// The texel the prediction reads (texelFetch at level predictLevel of the planes' mipmaps: the
// relight pass's level, 0 unless it relights a minified texture's level alone): set by each
// shader's main. PREDICT_FILTERED (the scene's per-fragment path) samples bilinearly at btflutPredictUv instead,
// so a magnified quad is smooth while the light moves, as its relit texture is once it stops:
// the prediction of filtered planes, each rounded to 8 bits (4-bit planes fetched as they are).
ivec2 btflutPredictAt;
vec2 btflutPredictUv;
uniform int predictLevel;

vec4 btflutPlaneTexel(int layer) {
#if defined(PREDICT_FILTERED)
    return textureLod(predictPlanes, vec3(btflutPredictUv, float(layer)), 0.0);
#else
    return texelFetch(predictPlanes, ivec3(btflutPredictAt, layer), predictLevel);
#endif
}

#if defined(PREDICT_MODEL)
// Layer `layer`'s four plane codes: bytes, and a 4-bit plane's n from its 17 n (exact: a
// multiple of 17 divided by 17). The filtered path fetches 4-bit planes as they are.
vec4 btflutPlaneCodes(int layer) {
    vec4 nibble = vec4(greaterThanEqual(vec4(float(4 * layer)) + vec4(0.0, 1.0, 2.0, 3.0), vec4(PREDICT_MODEL_WIDE)));
    vec4 bytes = btflutBytes(btflutPlaneTexel(layer));
#if defined(PREDICT_FILTERED)
    if (any(greaterThan(nibble, vec4(0.0))))
        bytes = mix(bytes, btflutBytes(texelFetch(predictPlanes, ivec3(btflutPredictAt, layer), 0)), nibble);
#endif
    return bytes / (1.0 + 16.0 * nibble);
}
#endif

// The texel's prediction.
BtflutPrediction btflutPredict() {
#if defined(PREDICT_LEARNED)
    vec4 codes[BTFLUT_MAX_LAYERS];
    for (int l = 0; l < BTFLUT_MAX_LAYERS; ++l) codes[l] = l < PREDICT_LEARNED_LAYERS ? btflutBytes(btflutPlaneTexel(l)) : vec4(0.0);
#if defined(BTFLUT_NETWORK)  // the decoder specialised to the model (Predictor::shaderSource)
    return btflutLearnedPredictionOf(btflutNetworkValue(codes, predictLearned));
#else
    return btflutLearnedPrediction(predictNetwork, codes, predictLearned);
#endif
#elif defined(PREDICT_MODEL)
    vec4 codes[BTFLUT_MAX_LAYERS];
    for (int l = 0; l < BTFLUT_MAX_LAYERS; ++l) codes[l] = l < PREDICT_MODEL_LAYERS ? btflutPlaneCodes(l) : vec4(0.0);
#if defined(PREDICT_MODEL_ALBEDO)
    vec3 albedo = btflutBytes(btflutPlaneTexel(PREDICT_ALBEDO_LAYER)).rgb;
#else
    vec3 albedo = vec3(255.0);
#endif
    return btflutModelPrediction(codes, PREDICT_MODEL_LAYERS, PREDICT_MODEL_CHANNELS, predictModel, albedo);
#else
    BtflutPrediction p = btflutNoPrediction();
    for (int k = 0; k < PREDICT_FETCHES; ++k) btflutAddReference(p, blendWeight[k], btflutPlaneTexel(blendLayer[k]));
    return p;
#endif
}

// A region's LUT applied to a blended code (below).
float btflutMatchCode(int channel, uint region, float code, uvec2 pixel);

// The texel's relit colour: grey keeps the prediction's chroma (lrgb: the albedo's), rgb matches
// each channel; `greyReference`: the bank's references have one channel.
vec3 btflutMatchedColour(uvec2 pixel, bool greyReference) {
#if defined(REGIONS)
    uint region = texelFetch(predictLabels, btflutPredictAt, 0).r;
#else
    uint region = 0u;
#endif
    BtflutPrediction prediction = btflutPredict();
    vec3 q = btflutCodes(prediction, btflutPredictMatch);
    vec3 matched = vec3(btflutMatchCode(0, region, q.x, pixel));
#if defined(RGB_MODE)
    matched = vec3(matched.x, btflutMatchCode(1, region, q.y, pixel), btflutMatchCode(2, region, q.z, pixel));
#endif
#if defined(PREDICT_ALBEDO_CHROMA)
    return btflutRelitColour(matched, btflutPredictMatch, false,
                             texelFetch(predictPlanes, ivec3(btflutPredictAt, PREDICT_ALBEDO_LAYER), predictLevel).rgb);
#else
    return btflutRelitColour(matched, btflutPredictMatch, greyReference, prediction.colour);
#endif
}

// The LUT of a region at v in [0, 1] (linear between entries, as Lut::applyLut).
float btflutMatchLut(int channel, uint region, float v) {
#if defined(LUT_UNIFORMS) && defined(RGB_MODE)
    return btflutUniformLut(int(region) * 3 + channel, matchEntries, v);
#elif defined(LUT_UNIFORMS)
    return btflutUniformLut(int(region), matchEntries, v);
#endif
    vec2 at = vec2((clamp(v, 0.0, 1.0) * float(matchEntries - 1) + 0.5) / float(matchEntries),
                   (float(region) + 0.5) / float(matchRegions));
    if (channel == 0) return textureLod(matchLuts[0], at, 0.0).r;
    if (channel == 1) return textureLod(matchLuts[1], at, 0.0).r;
    return textureLod(matchLuts[2], at, 0.0).r;
}

// The same, dithered as btflutMapValue (code: 1 / (predictCodes + 1)).
float btflutMatchLutDithered(int channel, uint region, float v, uvec2 pixel, float outCode) {
    float moved = v + (btflutDitherOffset(pixel.x, pixel.y, uint(channel)) - 0.5) / (predictCodes + 1.0);
    float value = btflutMatchLut(channel, region, moved);
    return value > 0.0 ? min(1.0, value + 0.5 * outCode) : 0.0;
}

float btflutMatchCode(int channel, uint region, float code, uvec2 pixel) {
#if defined(PREDICTION_ONLY)
    return code / predictCodes;  // bench render's baseline: the predictor as an RTI viewer draws it
#elif defined(DITHER)
    return btflutMatchLutDithered(channel, region, btflutCodeValue(code, predictCodes), pixel, outCode);
#else
    return btflutMatchLut(channel, region, btflutCodeValue(code, predictCodes));
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
