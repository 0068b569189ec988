// ---------------------------------------------------------------------------------------------
// A learned model (material.json "kind": "learned"; docs/predictors.md): per texel N codes,
// bytes in `planes` four to a layer, value v_k = (code_k - bias_k) scale_k; and a decoder of
// two small networks of the features h (F of them: the light's 9 hsh terms of order 3, and
// for a model of views the view's 3 hsh terms of order 2 but the constant) and the values:
//   pred_c = clamp(sum_k A_ck(L) v_k + a_c(L) + r_c(v, h), 0, 1),  code_c = round(255 pred_c)
// A, a: the light network's outputs (row c (N + 1) + k is A_ck, row c (N + 1) + N is a_c);
// r: the residual network of (v, h). Both are fully connected, ELU between layers, the last
// linear. Their parameters are the `weights` texture: one RGBA32F layer, texel t at
// (t % S, t / S), S its width (LearnedModel::gpuNetwork):
//   texel 0: N, C (channels), the residual's and the light network's hidden layer counts
//   texel 1, 2: the residual's, then the light network's, hidden widths
//   texel 3: F, the features (9, or 12 with the view)
//   then the codes' scale (N values, in texels of four), their bias, the residual's layers,
//   the light network's. A layer of I inputs and O outputs: O rows of ceil(I / 4) texels
//   (output o's weights, zero-padded), then ceil(O / 4) texels of biases.

#define BTFLUT_LEARNED_VECTORS (BTFLUT_LEARNED_WIDTH / 4)

// A learned model at one light: per code layer and channel ([layer * 3 + c]) A_ck of the
// layer's four codes, a_c, and the residual's first layer at codes 0 (its bias and h's part).
struct BtflutLearnedFrame {
    vec4 basis[BTFLUT_MAX_LAYERS * 3];
    vec3 offset;
    vec4 hidden[BTFLUT_LEARNED_VECTORS];
};

vec4 btflutNetworkTexel(sampler2DArray network, int t) {
    int s = textureSize(network, 0).x;
    return texelFetch(network, ivec3(t % s, t / s, 0), 0);
}

// What the decoder's head says: N, C, hidden layer counts and widths, and the texels where
// the residual network and the light network start.
struct BtflutNetworkHead {
    int codes, channels, hidden, lightHidden, features;
    ivec4 widths, lightWidths;
    int residual, light;
};

// The texels of a layer of `inputs` and `outputs`.
int btflutLayerTexels(int inputs, int outputs) { return outputs * ((inputs + 3) / 4) + (outputs + 3) / 4; }

BtflutNetworkHead btflutNetworkHeadOf(sampler2DArray network) {
    vec4 head = btflutNetworkTexel(network, 0);
    BtflutNetworkHead d;
    d.codes = int(head.x);
    d.channels = int(head.y);
    d.hidden = int(head.z);
    d.lightHidden = int(head.w);
    d.widths = ivec4(btflutNetworkTexel(network, 1));
    d.lightWidths = ivec4(btflutNetworkTexel(network, 2));
    d.features = int(btflutNetworkTexel(network, 3).x);
    d.residual = 4 + 2 * ((d.codes + 3) / 4);
    d.light = d.residual;
    int inputs = d.codes + d.features;
    for (int k = 0; k <= BTFLUT_LEARNED_HIDDEN; ++k) {
        if (k > d.hidden) break;
        int outputs = k < d.hidden ? d.widths[k] : d.channels;
        d.light += btflutLayerTexels(inputs, outputs);
        inputs = outputs;
    }
    return d;
}

// The layer at texel `at` applied to x: W x, plus its biases (`withBias`), through the ELU
// (`hidden`; max(a, 0) + exp(min(a, 0)) - 1, as the CPU). Returns the texel after it.
int btflutLearnedLayer(sampler2DArray network, int at, int inputs, int outputs, bool withBias, bool hidden,
                       vec4 x[BTFLUT_LEARNED_VECTORS], out vec4 y[BTFLUT_LEARNED_VECTORS]) {
    int n = (inputs + 3) / 4;
    for (int k = 0; k < BTFLUT_LEARNED_VECTORS; ++k) y[k] = vec4(0.0);
    for (int o = 0; o < BTFLUT_LEARNED_WIDTH; ++o) {
        if (o >= outputs) break;
        float sum = 0.0;
        for (int t = 0; t < BTFLUT_LEARNED_VECTORS; ++t) {
            if (t >= n) break;
            sum += dot(btflutNetworkTexel(network, at + o * n + t), x[t]);
        }
        y[o / 4][o % 4] = sum;
    }
    at += outputs * n;
    for (int k = 0; k < BTFLUT_LEARNED_VECTORS; ++k) {
        if (k >= (outputs + 3) / 4) break;
        if (withBias) y[k] += btflutNetworkTexel(network, at + k);
        if (hidden) y[k] = max(y[k], 0.0) + exp(min(y[k], 0.0)) - 1.0;
    }
    return at + (outputs + 3) / 4;
}

// A learned model's frame at a light seen from a view (both in the tangent frame; a model of
// one view ignores the view), from its decoder alone (engines, per fragment; btflut's own
// renderer gets the same numbers from the CPU: LearnedModel::lightFrame).
BtflutLearnedFrame btflutLearnedFrameAt(sampler2DArray network, vec3 lightTangent, vec3 viewTangent) {
    BtflutNetworkHead d = btflutNetworkHeadOf(network);
    float h[12], t[9];
    btflutBasisTerms(BTFLUT_BASIS_HSH, lightTangent, t);
    for (int k = 0; k < 9; ++k) h[k] = t[k];
    btflutBasisTerms(BTFLUT_BASIS_HSH, viewTangent, t);  // its order-2 terms 1..3, as LearnedModel::featuresAt
    for (int k = 0; k < 3; ++k) h[9 + k] = t[1 + k];
    vec4 x[BTFLUT_LEARNED_VECTORS], y[BTFLUT_LEARNED_VECTORS];
    for (int k = 0; k < BTFLUT_LEARNED_VECTORS; ++k) x[k] = vec4(0.0);
    for (int k = 0; k < 12; ++k)
        if (k < d.features) x[k / 4][k % 4] = h[k];
    int at = d.light, inputs = d.features, outputs = d.features;
    for (int k = 0; k <= BTFLUT_LEARNED_HIDDEN; ++k) {
        if (k > d.lightHidden) break;
        outputs = k < d.lightHidden ? d.lightWidths[k] : d.channels * (d.codes + 1);
        at = btflutLearnedLayer(network, at, inputs, outputs, true, k < d.lightHidden, x, y);
        for (int j = 0; j < BTFLUT_LEARNED_VECTORS; ++j) x[j] = y[j];
        inputs = outputs;
    }
    BtflutLearnedFrame f;
    for (int k = 0; k < BTFLUT_MAX_LAYERS * 3; ++k) f.basis[k] = vec4(0.0);
    f.offset = vec3(0.0);
    for (int c = 0; c < 3; ++c) {
        if (c >= d.channels) break;
        for (int k = 0; k <= BTFLUT_MAX_PLANES; ++k) {
            if (k > d.codes) break;
            int row = c * (d.codes + 1) + k;
            if (k == d.codes) f.offset[c] = x[row / 4][row % 4];
            else f.basis[(k / 4) * 3 + c][k % 4] = x[row / 4][row % 4];
        }
    }
    for (int k = 0; k < BTFLUT_LEARNED_VECTORS; ++k) x[k] = vec4(0.0);
    for (int k = 0; k < 12; ++k)
        if (k < d.features) x[(d.codes + k) / 4][(d.codes + k) % 4] = h[k];
    btflutLearnedLayer(network, d.residual, d.codes + d.features, d.widths[0], true, false, x, f.hidden);
    return f;
}
BtflutLearnedFrame btflutLearnedFrameAt(sampler2DArray network, vec3 lightTangent) {
    return btflutLearnedFrameAt(network, lightTangent, vec3(0.0, 0.0, 1.0));
}

// A learned model's prediction from its value per channel in [0, 1] (a grey model's in all three):
// each channel rounded to its code, as the CPU (LearnedPredictor).
BtflutPrediction btflutLearnedPredictionOf(vec3 value) {
    vec3 code = floor(value * 255.0 + 0.5);
    BtflutPrediction p;
    p.channels = code * float(BTFLUT_WEIGHT_UNIT);
    p.colour = code / 255.0;
    return p;
}

// A learned model's prediction from a texel's code bytes (`codes[l]`: layer l's four) at a
// frame: each channel's value rounded to its code, as the CPU (LearnedPredictor).
BtflutPrediction btflutLearnedPrediction(sampler2DArray network, vec4 codes[BTFLUT_MAX_LAYERS], BtflutLearnedFrame f) {
    BtflutNetworkHead d = btflutNetworkHeadOf(network);
    int layers = (d.codes + 3) / 4;
    vec4 x[BTFLUT_LEARNED_VECTORS], y[BTFLUT_LEARNED_VECTORS];
    for (int k = 0; k < BTFLUT_LEARNED_VECTORS; ++k) x[k] = vec4(0.0);
    vec3 value = f.offset;
    for (int l = 0; l < BTFLUT_MAX_LAYERS; ++l) {
        if (l >= layers) break;
        x[l] = (codes[l] - btflutNetworkTexel(network, 4 + layers + l)) * btflutNetworkTexel(network, 4 + l);
        for (int c = 0; c < 3; ++c) {
            if (c >= d.channels) break;
            value[c] += dot(f.basis[l * 3 + c], x[l]);
        }
    }
    int at = btflutLearnedLayer(network, d.residual, d.codes + d.features, d.widths[0], false, false, x, y);
    for (int k = 0; k < BTFLUT_LEARNED_VECTORS; ++k) {
        vec4 a = y[k] + f.hidden[k];
        x[k] = max(a, 0.0) + exp(min(a, 0.0)) - 1.0;
    }
    for (int k = 1; k <= BTFLUT_LEARNED_HIDDEN; ++k) {
        if (k > d.hidden) break;
        bool last = k == d.hidden;
        at = btflutLearnedLayer(network, at, d.widths[k - 1], last ? d.channels : d.widths[k], true, !last, x, y);
        for (int j = 0; j < BTFLUT_LEARNED_VECTORS; ++j) x[j] = y[j];
    }
    value = clamp(value + x[0].xyz, 0.0, 1.0);
    return btflutLearnedPredictionOf(d.channels == 1 ? vec3(value.x) : value);
}

// The prediction at texture coordinate `uv` for a light in the tangent frame seen from a view
// there (btflutPrediction): the frame from the decoder per fragment.
BtflutPrediction btflutLearnedPredictionAt(sampler2DArray planes, sampler2DArray weights, BtflutPredictor p, vec2 uv,
                                           vec3 lightTangent, vec3 viewTangent) {
    vec4 codes[BTFLUT_MAX_LAYERS];
    btflutCodesAt(planes, (p.planes + 3) / 4, uv, codes);
    return btflutLearnedPrediction(weights, codes, btflutLearnedFrameAt(weights, lightTangent, viewTangent));
}
