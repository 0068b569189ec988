// ---------------------------------------------------------------------------------------------
// A light model (material.json "kind": "model": ptm, hsh, rbf, bln; light_model.h): per texel
// P planes of codes four to a layer of `planes` (4-bit ones as 17 n), and an albedo after them
// when it has one; the light's weights in closed form (ptm, hsh) or from the weight grid.

// A light model at one light: per layer of four planes and per channel ([layer * 3 + channel])
// the weights of the planes' codes; per channel the offset; the scale that takes the sum to the
// value times BTFLUT_WEIGHT_UNIT, floored.
struct BtflutModelFrame {
    vec4 weights[BTFLUT_MAX_LAYERS * 3];
    vec3 offset;
    float scale;
};

// A light model's prediction from its planes' codes (`codes[l]`: layer l's four, on the scale
// the frame's weights are for): the sum floored after the scale, times the albedo's bytes (or
// 255 without one), clamped.
BtflutPrediction btflutModelPrediction(vec4 codes[BTFLUT_MAX_LAYERS], int layers, int channels, BtflutModelFrame f,
                                       vec3 albedoBytes) {
    vec3 sum = f.offset;
    for (int l = 0; l < BTFLUT_MAX_LAYERS; ++l) {
        if (l >= layers) break;
        for (int c = 0; c < 3; ++c) {
            if (c >= channels) break;
            sum[c] += dot(codes[l], f.weights[l * 3 + c]);
        }
    }
    vec3 value = floor(sum * f.scale);
    if (channels == 1) value = vec3(value.x);
    BtflutPrediction p;
    p.channels = clamp(albedoBytes * value, 0.0, 255.0 * float(BTFLUT_WEIGHT_UNIT));
    p.colour = p.channels / (255.0 * float(BTFLUT_WEIGHT_UNIT));
    return p;
}

// A light model's frame at a light, from the sidecar: the weights (closed form, or the grid's
// rows: (1 + P) x channels, the offsets, then each plane's channel weights) with each plane's
// scale and bias folded in, on the planes' stored bytes.
BtflutModelFrame btflutModelFrame(sampler2DArray weights, BtflutPredictor p, vec3 lightTangent) {
    bool closed = p.basis == BTFLUT_BASIS_PTM || p.basis == BTFLUT_BASIS_HSH;
    float terms[9];
    if (closed) btflutBasisTerms(p.basis, lightTangent, terms);
    vec2 disk = btflutDiskPoint(lightTangent);
    const float unit = float(BTFLUT_WEIGHT_UNIT);
    BtflutModelFrame f;
    for (int k = 0; k < BTFLUT_MAX_LAYERS * 3; ++k) f.weights[k] = vec4(0.0);
    f.offset = vec3(0.0);
    f.scale = 1.0;
    vec4 w4 = vec4(0.0);
    int rows = (p.planes + 1) * p.channels;
    for (int k = 0; k < rows; ++k) {
        int c = k % p.channels, plane = k / p.channels - 1;
        if (!closed && k % 4 == 0) w4 = btflutWeightLayer(weights, disk, k / 4);
        float w = closed ? (plane >= 0 ? terms[plane] : 0.0) : w4[k % 4];
        if (plane < 0) {
            f.offset[c] += w * unit;
            continue;
        }
        float weight = p.scale[plane] * w * unit;  // of the plane's byte
        f.weights[(plane / 4) * 3 + c][plane % 4] = weight;
        f.offset[c] -= p.bias[plane] * weight;
    }
    return f;
}

// The prediction at texture coordinate `uv` for a light in the tangent frame (btflutPrediction;
// one view).
BtflutPrediction btflutModelPredictionAt(sampler2DArray planes, sampler2DArray weights, BtflutPredictor p, vec2 uv,
                                         vec3 lightTangent, vec3 viewTangent) {
    vec4 codes[BTFLUT_MAX_LAYERS];
    int layers = (p.planes + 3) / 4;
    btflutCodesAt(planes, layers, uv, codes);
    vec3 albedo = p.albedo == 1 ? btflutBytes(texture(planes, vec3(uv, float(layers)))).rgb : vec3(255.0);
    return btflutModelPrediction(codes, layers, p.channels, btflutModelFrame(weights, p, lightTangent), albedo);
}
