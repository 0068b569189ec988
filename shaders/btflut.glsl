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

// The prediction at a texel: what every kind shares here, each kind's own functions in its file
// (shaders/kinds/, written in at the "btflut: kinds" line below), used by engines (btflutPredict
// below: the light's weights from the sidecar and the weight grid, per fragment) and by btflut's
// own renderer (shaders/lut_common.glsl: the CPU's integers at the light, so its codes are the
// CPU's bit for bit). Sums are in 1 / BTFLUT_WEIGHT_UNIT of a code.

#define BTFLUT_MAX_LAYERS (BTFLUT_MAX_PLANES / 4)

// How a prediction's codes are matched: each channel by its LUT (colour "rgb"), its first
// channel alone (a grey prediction: codes 255), or the grey of RGB (the channels' codes summed:
// codes 765).
#define BTFLUT_MATCH_RGB 0
#define BTFLUT_MATCH_ONE 1
#define BTFLUT_MATCH_SUM 2

// A texel's prediction: `channels` in 1 / BTFLUT_WEIGHT_UNIT of a code (0 .. 255 a channel), and
// its colour in [0, 1], whose chroma a grey match keeps.
struct BtflutPrediction {
    vec3 channels;
    vec3 colour;
};

// An RGBA8 texel's stored bytes (a filtered one's nearest).
vec4 btflutBytes(vec4 texel) { return floor(texel * 255.0 + 0.5); }

// A prediction of nothing yet: a blend of references adds to it.
BtflutPrediction btflutNoPrediction() { return BtflutPrediction(vec3(0.0), vec3(0.0)); }

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

// The layer of `planes` that holds the albedo.
int btflutAlbedoLayer(BtflutPredictor p) { return p.kind == BTFLUT_KIND_MODEL ? (p.planes + 3) / 4 : p.planes; }

// A texel's codes at texture coordinate `uv`, filtered: layer l's four in codes[l] (the first
// `layers` of `planes`), as a light model and a learned model store them.
void btflutCodesAt(sampler2DArray planes, int layers, vec2 uv, out vec4 codes[BTFLUT_MAX_LAYERS]) {
    for (int l = 0; l < BTFLUT_MAX_LAYERS; ++l) codes[l] = l < layers ? texture(planes, vec3(uv, float(l))) * 255.0 : vec4(0.0);
}

// btflut: kinds (shaders/kinds/*.glsl, one file per kind; written here when btflut is built)

// The prediction at texture coordinate `uv` for a light in the tangent frame, seen from a view
// there (read by a learned model of views alone): its kind's (shaders/kinds/<kind>.glsl's
// btflut<Kind>PredictionAt).
BtflutPrediction btflutPrediction(sampler2DArray planes, sampler2DArray weights, BtflutPredictor p, vec2 uv,
                                  vec3 lightTangent, vec3 viewTangent) {
    // btflut: dispatch (a line per file of shaders/kinds/; written here when btflut is built)
    return btflutNoPrediction();
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
