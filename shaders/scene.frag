// A scene quad: the material's reference texture (mipmapped, repeating) with the quad's LUT.
// Under a directional light a flat quad's light direction is constant, so its LUT is blended
// once per frame on the CPU: one extra filtered fetch per channel here.
// Defines: LUT_MODE (else plain texture), RGB_MODE, UNLIT (light behind the quad).
uniform sampler2D reference;
uniform sampler1D lut[3];
uniform int entries;

in vec2 uv;
out vec4 colour;

void main() {
    vec3 texel = texture(reference, uv).rgb;
#if defined(UNLIT)
    colour = vec4(0.0, 0.0, 0.0, 1.0);
#elif !defined(LUT_MODE)
    colour = vec4(texel, 1.0);
#elif defined(RGB_MODE)
    colour = vec4(btflutApplyLut(lut[0], entries, texel.r), btflutApplyLut(lut[1], entries, texel.g),
                  btflutApplyLut(lut[2], entries, texel.b), 1.0);
#else
    float grey = (texel.r + texel.g + texel.b) * (1.0 / 3.0);
    colour = vec4(btflutSetGrey(texel, btflutApplyLut(lut[0], entries, grey)), 1.0);
#endif
}
