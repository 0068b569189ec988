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

#define BTFLUT_GLSL_VERSION 1

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
vec3 btflutRelight(sampler3D luts, BtflutMaterial m, vec3 reference, vec3 lightTangent, uvec2 pixel) {
    vec2 disk = btflutDiskPoint(lightTangent);
    if (m.rgbLuts)
        return vec3(btflutMap(luts, m, disk, reference.r, pixel, 0), btflutMap(luts, m, disk, reference.g, pixel, 1),
                    btflutMap(luts, m, disk, reference.b, pixel, 2));
    if (m.greyReference) return vec3(btflutMap(luts, m, disk, reference.r, pixel, 0));
    float grey = (reference.r + reference.g + reference.b) * (1.0 / 3.0);
    return btflutSetGrey(reference, btflutMap(luts, m, disk, grey, pixel, 0));
}
