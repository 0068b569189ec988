// The viewer's last step, per window pixel: image A, or B where the compare shows it (right of
// the wipe line, or inside the lens), then exposure and gamma. Built in variants (#define
// WIPE or LENS, TONE) so that each does only its own work; without any of them the viewer
// copies A with a blit instead.
uniform sampler2D imageA;
uniform sampler2D imageB;
uniform float wipeX;      // WIPE: window pixels
uniform vec2 lensCentre;  // LENS: window pixels, origin bottom left
uniform float lensRadius;
uniform sampler1D tone;   // TONE: 256 entries, code k / 255 -> its toned value (present.cpp)

out vec4 colour;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
#if defined(WIPE)
    vec3 c = gl_FragCoord.x >= wipeX ? texelFetch(imageB, p, 0).rgb : texelFetch(imageA, p, 0).rgb;
#elif defined(LENS)
    vec3 c = distance(gl_FragCoord.xy, lensCentre) <= lensRadius ? texelFetch(imageB, p, 0).rgb : texelFetch(imageA, p, 0).rgb;
#else
    vec3 c = texelFetch(imageA, p, 0).rgb;
#endif
#ifdef TONE
    ivec3 code = ivec3(c * 255.0 + 0.5);  // the composite is 8-bit: a table of 256 is exact
    c = vec3(texelFetch(tone, code.r, 0).r, texelFetch(tone, code.g, 0).r, texelFetch(tone, code.b, 0).r);
#endif
    colour = vec4(c, 1.0);
}
