// The reference image at its native size with one LUT applied: the GL twin of btflut relight,
// drawn by RelightPass (src/gl/relight_pass.h). Fragment (x, y) is image texel (x, row y),
// row 0 the image's top, as the reference is stored. Defines: RGB_MODE (a LUT per channel),
// DITHER; BLEND (and the predictor's, REGIONS) for banks with a predictor, else MAPS_REFERENCE
// (lut_common.glsl).
uniform sampler2D reference;
uniform int referenceChannels; // 1 or 3

out vec4 colour;

void main() {
    uvec2 pixel = uvec2(gl_FragCoord.xy);
#if defined(BLEND)
    btflutPredictAt = ivec2(pixel);
    colour = vec4(btflutMatchedColour(pixel, referenceChannels == 1), 1.0);
#else
    colour = vec4(btflutReferenceColour(texelFetch(reference, ivec2(pixel), 0).rgb, referenceChannels == 1, pixel), 1.0);
#endif
}
