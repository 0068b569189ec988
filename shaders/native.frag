// The reference image at its native size with one LUT applied: the GL twin of btflut relight,
// drawn by RelightPass (src/gl/relight_pass.h). Fragment (x, y) is image texel (x, row y),
// row 0 the image's top, as the reference is stored. Defines: RGB_MODE (a LUT per channel),
// DITHER; BLEND (and BLEND_PACKED, REGIONS) for banks that blend references (lut_common.glsl).
uniform sampler2D reference;
uniform sampler1D lut[3];      // grey mode uses lut[0]
uniform int entries;
uniform int referenceChannels; // 1 or 3
uniform float inCode;          // one input code of the value a LUT maps
uniform float outCode;         // one target code

out vec4 colour;

float mapValue(int channel, float v, uvec2 pixel) {
#ifdef DITHER
    if (channel == 0) return btflutApplyLutDithered(lut[0], entries, v, pixel, 0u, inCode, outCode);
    if (channel == 1) return btflutApplyLutDithered(lut[1], entries, v, pixel, 1u, inCode, outCode);
    return btflutApplyLutDithered(lut[2], entries, v, pixel, 2u, inCode, outCode);
#else
    if (channel == 0) return btflutApplyLut(lut[0], entries, v);
    if (channel == 1) return btflutApplyLut(lut[1], entries, v);
    return btflutApplyLut(lut[2], entries, v);
#endif
}

#if defined(BLEND)
uniform sampler2D blendAlbedo;  // lrgb
vec4 btflutBlendTexel(int layer) {
    return texelFetch(blendReferences, ivec3(ivec2(gl_FragCoord.xy), layer), 0);
}
float blendMap(int channel, uint region, float code, uvec2 pixel) {
#ifdef DITHER
    return btflutBlendLutDithered(channel, region, btflutBlendValue(code), pixel, outCode);
#else
    return btflutBlendLut(channel, region, btflutBlendValue(code));
#endif
}
#endif

void main() {
    uvec2 pixel = uvec2(gl_FragCoord.xy);
#if defined(BLEND)
#if defined(REGIONS)
    uint region = texelFetch(blendLabels, ivec2(pixel), 0).r;
#else
    uint region = 0u;
#endif
    BtflutBlend blend = btflutBlend();
#if defined(RGB_MODE)
    colour = vec4(blendMap(0, region, blend.codes.r, pixel), blendMap(1, region, blend.codes.g, pixel),
                  blendMap(2, region, blend.codes.b, pixel), 1.0);
#elif defined(BLEND_PACKED)
    colour = vec4(btflutSetGrey(texelFetch(blendAlbedo, ivec2(pixel), 0).rgb, blendMap(0, region, blend.codes.x, pixel)), 1.0);
#else
    if (referenceChannels == 1) {
        colour = vec4(vec3(blendMap(0, region, blend.codes.x, pixel)), 1.0);
        return;
    }
    colour = vec4(btflutSetGrey(blend.colour, blendMap(0, region, blend.codes.x, pixel)), 1.0);
#endif
    return;
#endif
    vec3 texel = texelFetch(reference, ivec2(pixel), 0).rgb;
    if (referenceChannels == 1) {
        colour = vec4(vec3(mapValue(0, texel.r, pixel)), 1.0);
        return;
    }
#ifdef RGB_MODE
    colour = vec4(mapValue(0, texel.r, pixel), mapValue(1, texel.g, pixel), mapValue(2, texel.b, pixel), 1.0);
#else
    float grey = (texel.r + texel.g + texel.b) * (1.0 / 3.0);
    colour = vec4(btflutSetGrey(texel, mapValue(0, grey, pixel)), 1.0);
#endif
}
