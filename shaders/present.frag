// The viewer's last step, per window pixel: image A, or B where the compare shows it (right of
// the wipe line, or inside the lens), then exposure and gamma. Built in variants (#define
// WIPE or LENS, TONE) so that each does only its own work; without any of them the viewer
// copies A with a blit instead.
uniform sampler2D imageA;
uniform sampler2D imageB;
uniform float wipeX;      // WIPE: window pixels
uniform vec2 lensCentre;  // LENS: window pixels, origin bottom left
uniform float lensRadius;
uniform float exposure;   // TONE: stops, applied in linear light
uniform float gamma;      // TONE: display gamma on top of sRGB (1 = none)

out vec4 colour;

vec3 srgbToLinear(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}
vec3 linearToSrgb(vec3 c) {
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

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
    c = pow(linearToSrgb(clamp(srgbToLinear(c) * exp2(exposure), 0.0, 1.0)), vec3(1.0 / gamma));
#endif
    colour = vec4(c, 1.0);
}
