// A scene quad: the material's reference texture (mipmapped, repeating) in one of three modes.
// LUT_MODE: under a directional light a flat quad's light direction is constant, so its LUT is
// blended once per frame on the CPU; here one extra filtered fetch per channel. BRDF_MODE: the
// paper's 2D texture mapping, brightness scaled by the target-to-reference ratio. FLAT_MODE:
// the plain texture. RGB_MODE: a LUT per channel.
uniform sampler2D reference;
uniform int entries;
uniform sampler1D lut[3];
float lutAt(int channel, float v) {
    if (channel == 0) return btflutApplyLut(lut[0], entries, v);
    if (channel == 1) return btflutApplyLut(lut[1], entries, v);
    return btflutApplyLut(lut[2], entries, v);
}
uniform int unlit;        // the light is behind the quad (lut and brdf modes draw black)
uniform float brightness; // brdf mode

in vec2 uv;
out vec4 colour;

void main() {
    vec3 texel = texture(reference, uv).rgb;
#if defined(FLAT_MODE)
    colour = vec4(texel, 1.0);
#else
    if (unlit != 0) {
        colour = vec4(0.0, 0.0, 0.0, 1.0);
        return;
    }
#if defined(BRDF_MODE)
    colour = vec4(min(texel * brightness, vec3(1.0)), 1.0);
#elif defined(RGB_MODE)
    colour = vec4(lutAt(0, texel.r), lutAt(1, texel.g), lutAt(2, texel.b), 1.0);
#else
    float grey = (texel.r + texel.g + texel.b) * (1.0 / 3.0);
    colour = vec4(btflutSetGrey(texel, lutAt(0, grey)), 1.0);
#endif
#endif
}
