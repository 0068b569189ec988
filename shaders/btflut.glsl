// btflut.glsl: relight a material exported by `btflut export M.btflut -o DIR/` (docs/engines.md).
// Public shader include, GLSL 3.30 and later (no #version line: put yours first).
// Copyright the btflut authors; MIT licence (LICENSE): ship it in your game or tool.
//
// The method (van Ginneken, Koenderink & Dana, IJCV 1999): one reference texture, and per
// light direction a monotonic grey-level LUT that gives it the histogram the material has
// under that light. The LUTs of a grid of light directions are one 3D texture:
//   x: the LUT's input value, `entries` texels (LUT(k / (entries - 1)) at texel k);
//   y: grid column i, z: layer * G + grid row j (G = grid size; one layer per view direction),
// so bilinear interpolation between grid nodes and linear interpolation of the LUT are ONE
// trilinear fetch (GL_LINEAR, GL_CLAMP_TO_EDGE, no mipmaps, a 16-bit unorm format).
//
// Conventions. Directions are unit vectors in the material's tangent frame: z = surface
// normal, x = texture +u, y = texture +v (image up). The LUT acts on the reference's stored
// code values (sRGB-encoded, as in the PNG): upload the reference as a UNORM texture (not
// SRGB) and treat the result as sRGB-encoded. The result already holds the light's falloff
// and shadows of this material: scale it by the light's colour and intensity, not by N.L.

#define BTFLUT_GLSL_VERSION 5  // 2: banks with a predictor (btflutPredict, the second btflutRelight); 3: learned ones;
                               // 4: learned ones of views (the network's head of four texels); 5: a learned
                               // material's decoder specialised to it (btflut_network.glsl: btflutRelightPrediction,
                               // btflutLearnedPredictionOf)

// btflut: constants (src/core/predict/gpu_constants.h; written here when btflut is built)

// Uniform in [-1/2, 1/2) for pixel (x, y) and channel c: a fixed integer hash (btflut's
// CPU relighting uses the same one, so both agree bit for bit).
float btflutDitherOffset(uint x, uint y, uint c) {
    uint h = x * 0x8da6b343u ^ y * 0xd8163841u ^ c * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return float(h >> 8) * (1.0 / 16777216.0) - 0.5;
}

// Grey mode's colour step: an RGB value whose grey (mean of R, G, B) must become `target`
// keeps its chroma: scaled by target / grey, desaturated towards grey where a channel would
// exceed 1 (the smaller of the two factors applies), so the grey is exactly `target`.
vec3 btflutSetGrey(vec3 rgb, float target) {
    float grey = (rgb.r + rgb.g + rgb.b) * (1.0 / 3.0);
    float top = max(rgb.r, max(rgb.g, rgb.b));
    float factor = min(target / max(grey, 1e-20), (1.0 - target) / max(top - grey, 1e-20));
    return vec3(target) + (rgb - vec3(grey)) * factor;
}

// A direction's point on the Lambert equal-area disk: r = sqrt(2) sin(theta / 2) along its
// azimuth, which is xy / sqrt(1 + z). Directions below the horizon go to the rim.
vec2 btflutDiskPoint(vec3 direction) {
    vec3 d = normalize(direction);
    vec2 p = d.xy / sqrt(max(1.0 + d.z, 1e-6));
    float r = length(p);
    return r > 1.0 ? p / r : p;
}

// The 3D texture coordinate of a LUT value: LUT input `value` in [0, 1], at a disk point,
// in view layer `layer`. The grid row is clamped to the layer's texel centres, so the
// filtering never mixes two layers.
vec3 btflutLutCoordinate(sampler3D luts, vec2 disk, int layer, float value) {
    ivec3 size = textureSize(luts, 0);  // entries, G, G * layers
    float g = float(size.y);
    vec2 node = clamp((disk + 1.0) * 0.5 * (g - 1.0), 0.0, g - 1.0);  // grid (i, j), 0 .. G - 1
    return vec3((clamp(value, 0.0, 1.0) * float(size.x - 1) + 0.5) / float(size.x), (node.x + 0.5) / g,
                (float(layer) * g + node.y + 0.5) / float(size.z));
}

// What the material's sidecar (material.json) says, as the relight function needs it.
struct BtflutMaterial {
    int layer;          // view layer (0 for a fixed camera; see docs/engines.md to blend layers)
    bool rgbLuts;       // colour "rgb": one LUT per channel (texture channel c for colour c)
    bool greyReference; // the reference has one channel (use .rrr)
    float inputCode;    // "lut_input_code": one code of the LUT's input (1/765 for the grey of RGB8)
    float outputCode;   // "lut_output_code": one code of the values the LUTs map to
    bool dither;        // dither (reproduces the histogram exactly); false: the plain LUT
};

// The LUT's output for input v (channel c), dithered per pixel as btflut relights.
float btflutMap(sampler3D luts, BtflutMaterial m, vec2 disk, float v, uvec2 pixel, int c) {
    if (!m.dither) return textureLod(luts, btflutLutCoordinate(luts, disk, m.layer, v), 0.0)[c];
    float moved = v + (btflutDitherOffset(pixel.x, pixel.y, uint(c)) - 0.5) * m.inputCode;
    float value = textureLod(luts, btflutLutCoordinate(luts, disk, m.layer, moved), 0.0)[c];
    return value > 0.0 ? min(1.0, value + 0.5 * m.outputCode) : 0.0;
}

// The reference texel `reference` (its stored values) relit for a light direction in the
// tangent frame; `pixel`: the texel's integer coordinate (or the screen pixel) for the dither.
// A light at or below the horizon lights nothing: black, as btflut's renderer draws it.
vec3 btflutRelight(sampler3D luts, BtflutMaterial m, vec3 reference, vec3 lightTangent, uvec2 pixel) {
    if (lightTangent.z <= 0.0) return vec3(0.0);
    vec2 disk = btflutDiskPoint(lightTangent);
    if (m.rgbLuts)
        return vec3(btflutMap(luts, m, disk, reference.r, pixel, 0), btflutMap(luts, m, disk, reference.g, pixel, 1),
                    btflutMap(luts, m, disk, reference.b, pixel, 2));
    if (m.greyReference) return vec3(btflutMap(luts, m, disk, reference.r, pixel, 0));
    float grey = (reference.r + reference.g + reference.b) * (1.0 / 3.0);
    return btflutSetGrey(reference, btflutMap(luts, m, disk, grey, pixel, 0));
}

// ---------------------------------------------------------------------------------------------
// Version 2: banks with a predictor (material.json "kind": "model" or "references"). Per light
// a prediction of the texel (a light model's planes times the light's weights, or the
// references blended), rounded to its codes, then the LUT from the prediction's distribution
// to the material's at that light: the match LUTs over the light grid, one 3D texture as
// above, a block of G rows per region (`BtflutMaterial.layer` is the region).
//
// Textures: `planes`, a 2D array of RGBA8 images (UNORM, linear, repeat): a model's planes
// four to a layer, or one reference per layer, then the albedo if any; `weights`, a 2D array
// of RGBA32F layers over the light disk (read exactly with texelFetch; unused by ptm and
// hsh, whose weights are computed here); `labels`, R8 (nearest): each texel's region * 1/255.

// The prediction at a texel: one set of functions for every bank kind, used by engines
// (btflutPredict below: the light's weights from the sidecar and the weight grid, per fragment)
// and by btflut's own renderer (shaders/lut_common.glsl: the CPU's integers at the light, so
// its codes are the CPU's bit for bit). Sums are in 1 / BTFLUT_WEIGHT_UNIT of a code.

#define BTFLUT_MAX_LAYERS (BTFLUT_MAX_PLANES / 4)

// How a prediction's codes are matched: each channel by its LUT (colour "rgb"), its first
// channel alone (a grey prediction: codes 255), or the grey of RGB (the channels' codes summed:
// codes 765).
#define BTFLUT_MATCH_RGB 0
#define BTFLUT_MATCH_ONE 1
#define BTFLUT_MATCH_SUM 2

// A light model at one light: per layer of four planes and per channel ([layer * 3 + channel])
// the weights of the planes' codes; per channel the offset; the scale that takes the sum to the
// value times BTFLUT_WEIGHT_UNIT, floored.
struct BtflutModelFrame {
    vec4 weights[BTFLUT_MAX_LAYERS * 3];
    vec3 offset;
    float scale;
};

// A texel's prediction: `channels` in 1 / BTFLUT_WEIGHT_UNIT of a code (0 .. 255 a channel), and
// its colour in [0, 1], whose chroma a grey match keeps.
struct BtflutPrediction {
    vec3 channels;
    vec3 colour;
};

// An RGBA8 texel's stored bytes (a filtered one's nearest).
vec4 btflutBytes(vec4 texel) { return floor(texel * 255.0 + 0.5); }

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

// A blend of references, one at a time: `weight` (an integer, of BTFLUT_WEIGHT_UNIT) times
// the reference's texel. Start from btflutNoPrediction().
BtflutPrediction btflutNoPrediction() { return BtflutPrediction(vec3(0.0), vec3(0.0)); }
void btflutAddReference(inout BtflutPrediction p, float weight, vec4 texel) {
    p.channels += weight * btflutBytes(texel).rgb;
    p.colour += weight / float(BTFLUT_WEIGHT_UNIT) * texel.rgb;
}

// The codes a prediction is matched with (BTFLUT_MATCH_...): per channel, or in .x.
vec3 btflutCodes(BtflutPrediction p, int match) {
    const float unit = float(BTFLUT_WEIGHT_UNIT);
    if (match == BTFLUT_MATCH_RGB) return floor(p.channels / unit + 0.5);
    if (match == BTFLUT_MATCH_ONE) return vec3(floor(p.channels.r / unit + 0.5));
    return vec3(floor((p.channels.r + p.channels.g + p.channels.b) / unit + 0.5));
}

// A code's LUT input: code q read at the top of its cell, (q + 1) / (codes + 1).
float btflutCodeValue(float code, float codes) { return (code + 1.0) / (codes + 1.0); }

// The relit colour from the matched values (`matched`: per channel for BTFLUT_MATCH_RGB, else
// the grey in .x): the grey alone (`greyOutput`), or given the chroma of `chroma` (the
// prediction's colour; lrgb: the albedo's).
vec3 btflutRelitColour(vec3 matched, int match, bool greyOutput, vec3 chroma) {
    if (match == BTFLUT_MATCH_RGB) return matched;
    if (greyOutput) return vec3(matched.x);
    return btflutSetGrey(chroma, matched.x);
}

// What the sidecar's "predictor" says.
struct BtflutPredictor {
    int kind;       // BTFLUT_KIND_MODEL (a light model), BTFLUT_KIND_REFERENCES or BTFLUT_KIND_LEARNED
    int basis;      // model: BTFLUT_BASIS_PTM, _HSH (closed form), _RBF, _BLN (the weight texture)
    int order;      // hsh: 2 or 3
    int planes;     // model: its planes P; references: their count K; learned: its codes N
    int channels;   // the prediction's channels before any albedo: 1 or 3
    int albedo;     // 0 none; 1: multiplies the model's value; 2: gives the chroma after the match (lrgb)
    float scale[BTFLUT_MAX_PLANES];  // model: plane p's value = (code - bias[p]) * scale[p], code 0 .. 255
    float bias[BTFLUT_MAX_PLANES];
    int regions;    // 1, or each texel's region from `labels`
    float codes;    // codes of a prediction: 255, or 765 (the grey of RGB: three codes summed)
    bool rgbLuts;   // colour "rgb": each channel matched by its own LUT
    bool greyOutput;  // one output channel (grey in R, G and B)
    float outputCode; // "lut_output_code"
    bool dither;
};

// How its codes are matched (BTFLUT_MATCH_...).
int btflutMatchOf(BtflutPredictor p) {
    return p.rgbLuts ? BTFLUT_MATCH_RGB : p.codes == 255.0 ? BTFLUT_MATCH_ONE : BTFLUT_MATCH_SUM;
}

// Four weights of the light at disk point `disk`: layer `layer` of the weight grid, bilinear
// between the four nodes around it (node (i, j) at -1 + 2 (i, j) / (S - 1)).
vec4 btflutWeightLayer(sampler2DArray weights, vec2 disk, int layer) {
    int s = textureSize(weights, 0).x;
    vec2 node = clamp((disk + 1.0) * 0.5 * float(s - 1), 0.0, float(s - 1));
    ivec2 at = min(ivec2(node), ivec2(s - 2));
    vec2 f = node - vec2(at);
    vec4 a = texelFetch(weights, ivec3(at, layer), 0), b = texelFetch(weights, ivec3(at + ivec2(1, 0), layer), 0);
    vec4 c = texelFetch(weights, ivec3(at + ivec2(0, 1), layer), 0), d = texelFetch(weights, ivec3(at + ivec2(1, 1), layer), 0);
    return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}

// The closed-form weights of ptm (Malzbender's u^2, v^2, uv, u, v, 1) and hsh (hemispherical
// harmonics of order 2 or 3, Gautron et al. 2004), for a light at or above the horizon.
void btflutBasisTerms(int basis, vec3 light, out float t[9]) {
    vec3 l = normalize(light);
    if (l.z < 0.0) l = normalize(vec3(l.xy, 0.0));  // below the horizon: the horizon's
    for (int k = 0; k < 9; ++k) t[k] = 0.0;
    if (basis == BTFLUT_BASIS_PTM) {
        t[0] = l.x * l.x; t[1] = l.y * l.y; t[2] = l.x * l.y; t[3] = l.x; t[4] = l.y; t[5] = 1.0;
        return;
    }
    const float pi = 3.14159265358979;
    float c = l.z, s = sqrt(max(0.0, c - c * c)), r = length(l.xy);
    vec2 azimuth = r > 0.0 ? l.xy / r : vec2(1.0, 0.0);  // cos phi, sin phi
    t[0] = 1.0 / sqrt(2.0 * pi);
    t[1] = sqrt(6.0 / pi) * azimuth.x * s;
    t[2] = sqrt(3.0 / (2.0 * pi)) * (2.0 * c - 1.0);
    t[3] = sqrt(6.0 / pi) * azimuth.y * s;
    t[4] = sqrt(30.0 / pi) * (azimuth.x * azimuth.x - azimuth.y * azimuth.y) * (c * c - c);
    t[5] = sqrt(30.0 / pi) * azimuth.x * (2.0 * c - 1.0) * s;
    t[6] = sqrt(5.0 / (2.0 * pi)) * (1.0 - 6.0 * c + 6.0 * c * c);
    t[7] = sqrt(30.0 / pi) * azimuth.y * (2.0 * c - 1.0) * s;
    t[8] = sqrt(30.0 / pi) * 2.0 * azimuth.x * azimuth.y * (c * c - c);
}

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

// The layer of `planes` that holds the albedo.
int btflutAlbedoLayer(BtflutPredictor p) { return p.kind == BTFLUT_KIND_MODEL ? (p.planes + 3) / 4 : p.planes; }

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

// The prediction at texture coordinate `uv` for a light in the tangent frame, seen from a view
// there (read by a learned model of views alone).
BtflutPrediction btflutPrediction(sampler2DArray planes, sampler2DArray weights, BtflutPredictor p, vec2 uv,
                                  vec3 lightTangent, vec3 viewTangent) {
    BtflutPrediction prediction = btflutNoPrediction();
    if (p.kind == BTFLUT_KIND_REFERENCES) {  // references: one weight each, to 1 / BTFLUT_WEIGHT_UNIT as btflut's CPU
        vec2 disk = btflutDiskPoint(lightTangent);
        vec4 w4 = vec4(0.0);
        for (int k = 0; k < p.planes; ++k) {
            if (k % 4 == 0) w4 = btflutWeightLayer(weights, disk, k / 4);
            float w = floor(w4[k % 4] * float(BTFLUT_WEIGHT_UNIT) + 0.5);
            if (w != 0.0) btflutAddReference(prediction, w, texture(planes, vec3(uv, float(k))));
        }
        return prediction;
    }
    vec4 codes[BTFLUT_MAX_LAYERS];
    int layers = (p.planes + 3) / 4;
    for (int l = 0; l < BTFLUT_MAX_LAYERS; ++l) codes[l] = l < layers ? texture(planes, vec3(uv, float(l))) * 255.0 : vec4(0.0);
    if (p.kind == BTFLUT_KIND_LEARNED)
        return btflutLearnedPrediction(weights, codes, btflutLearnedFrameAt(weights, lightTangent, viewTangent));
    vec3 albedo = p.albedo == 1 ? btflutBytes(texture(planes, vec3(uv, float(layers)))).rgb : vec3(255.0);
    return btflutModelPrediction(codes, layers, p.channels, btflutModelFrame(weights, p, lightTangent), albedo);
}
BtflutPrediction btflutPrediction(sampler2DArray planes, sampler2DArray weights, BtflutPredictor p, vec2 uv,
                                  vec3 lightTangent) {
    return btflutPrediction(planes, weights, p, uv, lightTangent, vec3(0.0, 0.0, 1.0));
}

// The same in codes (0 .. 255 a channel, not yet rounded): what btflut's CPU relighting rounds
// before its match LUT, and what an RTI viewer shows.
vec3 btflutPredict(sampler2DArray planes, sampler2DArray weights, BtflutPredictor p, vec2 uv, vec3 lightTangent) {
    return btflutPrediction(planes, weights, p, uv, lightTangent).channels / float(BTFLUT_WEIGHT_UNIT);
}

// A predicted code's value through its region's match LUT at the light, dithered per pixel.
float btflutMatch(sampler3D luts, BtflutPredictor p, vec2 disk, int region, float code, uvec2 pixel, int channel) {
    BtflutMaterial m = BtflutMaterial(region, false, false, 1.0 / (p.codes + 1.0), p.outputCode, p.dither);
    return btflutMap(luts, m, disk, btflutCodeValue(code, p.codes), pixel, channel);
}

// A bank with a predictor relit from a texel's prediction, made by the caller (btflutPrediction,
// or a learned material's decoder specialised to it: btflut_network.glsl, which `export` writes,
// btflutNetworkPrediction at a frame computed once per light change or per fragment); `pixel`
// for the dither. A learned model of views: matched by the LUTs of view layer `layer`
// (material.json "views"; the LUT texture's blocks are layer * regions + region). A light at or
// below the horizon: black.
vec3 btflutRelightPrediction(sampler3D luts, sampler2DArray planes, sampler2D labels, BtflutPredictor p, vec2 uv,
                             vec3 lightTangent, int layer, uvec2 pixel, BtflutPrediction predicted) {
    if (lightTangent.z <= 0.0) return vec3(0.0);
    vec2 disk = btflutDiskPoint(lightTangent);
    int region = 0;
    if (p.regions > 1) {
        ivec2 size = textureSize(labels, 0);
        region = int(texelFetch(labels, ivec2(mod(floor(uv * vec2(size)), vec2(size))), 0).r * 255.0 + 0.5);
    }
    region += layer * p.regions;
    int match = btflutMatchOf(p);
    vec3 q = btflutCodes(predicted, match);
    vec3 matched = vec3(btflutMatch(luts, p, disk, region, q.x, pixel, 0));
    if (match == BTFLUT_MATCH_RGB)
        matched = vec3(matched.x, btflutMatch(luts, p, disk, region, q.y, pixel, 1), btflutMatch(luts, p, disk, region, q.z, pixel, 2));
    if (p.albedo == 2) return btflutRelitColour(matched, match, false, texture(planes, vec3(uv, float(btflutAlbedoLayer(p)))).rgb);
    return btflutRelitColour(matched, match, p.greyOutput, predicted.colour);
}

// The same predicted here at `uv` for a light in the tangent frame (a learned model of views:
// seen from `viewTangent`).
vec3 btflutRelight(sampler3D luts, sampler2DArray planes, sampler2DArray weights, sampler2D labels, BtflutPredictor p,
                   vec2 uv, vec3 lightTangent, vec3 viewTangent, int layer, uvec2 pixel) {
    if (lightTangent.z <= 0.0) return vec3(0.0);
    return btflutRelightPrediction(luts, planes, labels, p, uv, lightTangent, layer, pixel,
                                   btflutPrediction(planes, weights, p, uv, lightTangent, viewTangent));
}

vec3 btflutRelight(sampler3D luts, sampler2DArray planes, sampler2DArray weights, sampler2D labels, BtflutPredictor p,
                   vec2 uv, vec3 lightTangent, uvec2 pixel) {
    return btflutRelight(luts, planes, weights, labels, p, uv, lightTangent, vec3(0.0, 0.0, 1.0), 0, pixel);
}
