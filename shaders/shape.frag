// A material on a curved surface: the light (and the view) in the surface's own frame at each
// fragment, and the LUT for that direction from the bank's grid (btflut.glsl's one filtered
// fetch), so highlights and shadows move across the object as they would on the material.
uniform sampler2D reference;
uniform sampler3D luts;
uniform bool pointLight;
uniform vec3 lightDirection;  // directional: towards the light, world frame
uniform vec3 lightPosition;   // point light: its position
uniform vec3 eye;
uniform int layers;
uniform vec3 layerViews[16];  // each view layer's direction in the tangent frame
uniform bool rgbLuts;
uniform bool greyReference;
uniform float inputCode;
uniform float outputCode;

in vec3 worldPosition;
in vec3 worldNormal;
in vec3 worldTangent;
in vec2 uv;
out vec4 colour;

#if defined(PREDICTOR)
// A bank with a predictor, as BlendTextures uploads it (`planes`): a light model (MODEL: its
// 8-bit planes three to a layer, its 4-bit planes six, two to a channel with the first in the
// high nibble, then its albedo), or references (one per layer, grey ones in all three
// channels; LRGB: four grey ones per layer and the albedo apart). Its weights over the light
// disk, four to a layer (lightModelWeightGrid, referenceWeightGrid); its match LUTs over the
// grid, a region's grid above the last (`luts`).
uniform sampler2DArray planes;
uniform sampler2DArray modelWeights;
#if defined(REGIONS)
uniform usampler2D labels;
#endif
#if defined(LRGB)
uniform sampler2D albedo;
#endif
uniform ivec2 texels;  // the planes' size
uniform float codes;   // codes of a predicted value: 255, or 765 for the grey of RGB

// A code's LUT at the light: its region's match LUT at disk point `disk`, the code read at the
// top of its cell, (q + 1) / (codes + 1) (Relighter::inputCode), dithered per pixel.
float matchAt(float code, int region, vec2 disk, uvec2 pixel, int channel) {
    BtflutMaterial m = BtflutMaterial(region, false, false, 1.0 / (codes + 1.0), outputCode, true);
    return btflutMap(luts, m, disk, (code + 1.0) / (codes + 1.0), pixel, channel);
}

// The relit colour at `uv` for a light at disk point `disk`: the prediction (planes sampled
// bilinearly; 4-bit planes decoded per texel, then weighted), each channel's code through its
// region's match LUT there.
vec3 relightPredictor(vec2 disk, uvec2 pixel) {
    vec2 at = (disk + 1.0) * 0.5;  // the weight grid's texture coordinate: node centres at the edges
    at = (at * float(textureSize(modelWeights, 0).x - 1) + 0.5) / vec2(textureSize(modelWeights, 0).xy);
    vec4 w[WEIGHT_LAYERS];
    for (int k = 0; k < WEIGHT_LAYERS; ++k) w[k] = textureLod(modelWeights, vec3(at, float(k)), 0.0);
    ivec2 texel = ivec2(mod(floor(uv * vec2(texels)), vec2(texels)));
#if defined(REGIONS)
    int region = int(texelFetch(labels, texel, 0).r);
#else
    int region = 0;
#endif
#if defined(MODEL)
    vec2 position = uv * vec2(texels) - 0.5;  // bilinear filtering's texel corner and fractions
    ivec2 corner = ivec2(floor(position));
    vec2 f = position - floor(position);
    vec3 value = vec3(0.0);
    for (int c = 0; c < MODEL_CHANNELS; ++c) {
        int o = MODEL_PLANES * MODEL_CHANNELS + c;
        value[c] = w[o / 4][o % 4];
    }
    for (int p = 0; p < MODEL_PLANES; ++p) {
        float code;
        if (p < MODEL_WIDE) {
            code = textureLod(planes, vec3(uv, float(p / 3)), 0.0)[p % 3] * 255.0;
        } else {  // two to a byte: each of the four texels around decoded, then weighted bilinearly
            int q = p - MODEL_WIDE;
            code = 0.0;
            for (int k = 0; k < 4; ++k) {
                ivec2 at = ivec2(mod(vec2(corner + ivec2(k % 2, k / 2)), vec2(texels)));
                float byte = floor(texelFetch(planes, ivec3(at, BLEND_MODEL_LAYERS + q / 6), 0)[(q % 6) / 2] * 255.0 + 0.5);
                float high = floor(byte / 16.0);
                code += (k % 2 == 0 ? 1.0 - f.x : f.x) * (k / 2 == 0 ? 1.0 - f.y : f.y) * (q % 2 == 0 ? high : byte - 16.0 * high);
            }
        }
        for (int c = 0; c < MODEL_CHANNELS; ++c) {
            int k = p * MODEL_CHANNELS + c;
            value[c] += code * w[k / 4][k % 4];
        }
    }
#if MODEL_CHANNELS == 1
    value = vec3(value.x);
#endif
#if defined(MODEL_ALBEDO)
    vec3 albedoBytes = textureLod(planes, vec3(uv, float(BLEND_MODEL_LAYERS + BLEND_MODEL_NIBBLE_LAYERS)), 0.0).rgb * 255.0;
    vec3 channels = clamp(albedoBytes * value, 0.0, 255.0);
#else
    vec3 channels = clamp(255.0 * value, 0.0, 255.0);
#endif
#elif defined(LRGB)
    float grey = 0.0;  // one grey prediction from the references four to a layer
    for (int k = 0; k < REFERENCE_COUNT; ++k) grey += w[k / 4][k % 4] * textureLod(planes, vec3(uv, float(k / 4)), 0.0)[k % 4];
    return btflutSetGrey(textureLod(albedo, uv, 0.0).rgb, matchAt(floor(grey * 255.0 + 0.5), region, disk, pixel, 0));
#else
    vec3 channels = vec3(0.0);
    for (int k = 0; k < REFERENCE_COUNT; ++k) channels += w[k / 4][k % 4] * textureLod(planes, vec3(uv, float(k)), 0.0).rgb;
    channels *= 255.0;
#endif
#if !defined(LRGB)
#if defined(RGB_MODE)
    vec3 q = floor(channels + 0.5);
    return vec3(matchAt(q.r, region, disk, pixel, 0), matchAt(q.g, region, disk, pixel, 1), matchAt(q.b, region, disk, pixel, 2));
#else
#if defined(GREY_REFERENCES)
    float q = floor(channels.r + 0.5);
#else
    float q = codes == 255.0 ? floor(channels.r + 0.5) : floor(channels.r + channels.g + channels.b + 0.5);
#endif
    float grey = matchAt(q, region, disk, pixel, 0);
    if (greyReference) return vec3(grey);
    return btflutSetGrey(channels / 255.0, grey);
#endif
#endif
}
#endif

void main() {
    vec3 n = normalize(worldNormal);
    vec3 t = normalize(worldTangent - n * dot(n, worldTangent));
    vec3 b = cross(n, t);  // image up
    vec3 l = pointLight ? normalize(lightPosition - worldPosition) : normalize(lightDirection);
    vec3 lightTangent = vec3(dot(l, t), dot(l, b), dot(l, n));
    if (lightTangent.z <= 0.0) {  // the light is behind this surface point
        colour = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
    // The view layer nearest the view direction (banks of one layer: layer 0).
    vec3 v = normalize(eye - worldPosition);
    vec3 viewTangent = vec3(dot(v, t), dot(v, b), dot(v, n));
    int layer = 0;
    float best = -2.0;
    for (int k = 0; k < layers; ++k) {
        float c = dot(viewTangent, layerViews[k]);
        if (c > best) {
            best = c;
            layer = k;
        }
    }
#if defined(PREDICTOR)
    colour = vec4(relightPredictor(btflutDiskPoint(lightTangent), uvec2(gl_FragCoord.xy)), 1.0);
    return;
#endif
    BtflutMaterial m = BtflutMaterial(layer, rgbLuts, greyReference, inputCode, outputCode, true);
    vec3 texel = texture(reference, uv).rgb;
    colour = vec4(btflutRelight(luts, m, texel, lightTangent, uvec2(gl_FragCoord.xy)), 1.0);
}
