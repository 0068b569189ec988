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

#define BTFLUT_GLSL_VERSION 2  // 2: banks with a predictor (btflutPredict, the second btflutRelight)

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

// What the sidecar's "predictor" says.
struct BtflutPredictor {
    int kind;       // BTFLUT_KIND_MODEL (a light model) or BTFLUT_KIND_REFERENCES
    int basis;      // model: BTFLUT_BASIS_PTM, _HSH (closed form), _RBF, _BLN (the weight texture)
    int order;      // hsh: 2 or 3
    int planes;     // model: its planes P; references: their count K
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

// The prediction at texture coordinate `uv` for a light in the tangent frame, in codes (0 ..
// 255 a channel, not yet rounded): what btflut's CPU relighting rounds before its match LUT.
vec3 btflutPredict(sampler2DArray planes, sampler2DArray weights, BtflutPredictor p, vec2 uv, vec3 lightTangent) {
    vec2 disk = btflutDiskPoint(lightTangent);
    vec3 value = vec3(0.0);
    vec4 w4 = vec4(0.0);
    if (p.kind == BTFLUT_KIND_REFERENCES) {  // references: one weight each
        for (int k = 0; k < p.planes; ++k) {
            if (k % 4 == 0) w4 = btflutWeightLayer(weights, disk, k / 4);
            float w = floor(w4[k % 4] * float(BTFLUT_WEIGHT_UNIT) + 0.5) / float(BTFLUT_WEIGHT_UNIT);  // as btflut's CPU
            if (w != 0.0) value += w * texture(planes, vec3(uv, float(k))).rgb;
        }
        return 255.0 * value;
    }
    // A light model: rows (1 + P) x channels, the offsets, then each plane's channel weights.
    bool closed = p.basis == BTFLUT_BASIS_PTM || p.basis == BTFLUT_BASIS_HSH;
    float terms[9];
    if (closed) btflutBasisTerms(p.basis, lightTangent, terms);
    int rows = (p.planes + 1) * p.channels;
    vec4 codes = vec4(0.0);
    float v = 0.0;
    for (int k = 0; k < rows; ++k) {
        int c = k % p.channels, plane = k / p.channels - 1;
        if (!closed && k % 4 == 0) w4 = btflutWeightLayer(weights, disk, k / 4);
        float w = closed ? (plane >= 0 ? terms[plane] : 0.0) : w4[k % 4];
        if (plane < 0) {
            value[c] = w;
            continue;
        }
        if (c == 0) {
            if (plane % 4 == 0) codes = texture(planes, vec3(uv, float(plane / 4))) * 255.0;
            v = (codes[plane % 4] - p.bias[plane]) * p.scale[plane];
        }
        value[c] += v * w;
    }
    // btflut rounds as here: the value down to 1 / BTFLUT_WEIGHT_UNIT, times the albedo's byte (or 255), to
    // the nearest code; so CPU and GPU codes agree but where float sums sit on a step.
    value = floor((p.channels == 1 ? vec3(value.x) : value) * float(BTFLUT_WEIGHT_UNIT)) / float(BTFLUT_WEIGHT_UNIT);
    vec3 bytes = p.albedo == 1 ? floor(texture(planes, vec3(uv, float(btflutAlbedoLayer(p)))).rgb * 255.0 + 0.5) : vec3(255.0);
    return clamp(bytes * value, 0.0, 255.0);
}

// A predicted code's value through its region's match LUT at the light, dithered per pixel.
// Code q is read at (q + 1) / (codes + 1), the top of its cell, as btflut relights.
float btflutMatch(sampler3D luts, BtflutPredictor p, vec2 disk, int region, float code, uvec2 pixel, int channel) {
    BtflutMaterial m = BtflutMaterial(region, false, false, 1.0 / (p.codes + 1.0), p.outputCode, p.dither);
    return btflutMap(luts, m, disk, (code + 1.0) / (p.codes + 1.0), pixel, channel);
}

// A bank with a predictor relit at `uv` for a light in the tangent frame; `pixel` for the dither.
// A light at or below the horizon: black.
vec3 btflutRelight(sampler3D luts, sampler2DArray planes, sampler2DArray weights, sampler2D labels, BtflutPredictor p,
                   vec2 uv, vec3 lightTangent, uvec2 pixel) {
    if (lightTangent.z <= 0.0) return vec3(0.0);
    vec2 disk = btflutDiskPoint(lightTangent);
    int region = 0;
    if (p.regions > 1) {
        ivec2 size = textureSize(labels, 0);
        region = int(texelFetch(labels, ivec2(mod(floor(uv * vec2(size)), vec2(size))), 0).r * 255.0 + 0.5);
    }
    vec3 predicted = btflutPredict(planes, weights, p, uv, lightTangent);
    if (p.rgbLuts) {
        vec3 q = floor(predicted + 0.5);
        return vec3(btflutMatch(luts, p, disk, region, q.r, pixel, 0), btflutMatch(luts, p, disk, region, q.g, pixel, 1),
                    btflutMatch(luts, p, disk, region, q.b, pixel, 2));
    }
    float q = p.codes == 255.0 ? floor(predicted.r + 0.5) : floor(predicted.r + predicted.g + predicted.b + 0.5);
    float grey = btflutMatch(luts, p, disk, region, q, pixel, 0);
    if (p.albedo == 2) return btflutSetGrey(texture(planes, vec3(uv, float(btflutAlbedoLayer(p)))).rgb, grey);
    if (p.greyOutput) return vec3(grey);
    return btflutSetGrey(predicted / 255.0, grey);
}
