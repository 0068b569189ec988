// The viewer's last step, per window pixel: image A, or B where the compare shows it (right of
// the wipe line, or inside the lens), then exposure and gamma. With exposure 0 and gamma 1
// the pixel is A's (or B's) unchanged, so screenshots equal the renders.
uniform sampler2D imageA;
uniform sampler2D imageB;
uniform int compareMode;  // 0: A only, 1: wipe (B right of wipeX), 2: lens (B within lensRadius of lensCentre)
uniform float wipeX;      // window pixels
uniform vec2 lensCentre;  // window pixels, origin bottom left
uniform float lensRadius;
uniform float exposure;   // stops, applied in linear light
uniform float gamma;      // display gamma on top of sRGB: 1 = none

out vec4 colour;

vec3 srgbToLinear(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}
vec3 linearToSrgb(vec3 c) {
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    bool showB = compareMode == 1 ? gl_FragCoord.x >= wipeX
               : compareMode == 2 ? distance(gl_FragCoord.xy, lensCentre) <= lensRadius : false;
    vec3 c = showB ? texelFetch(imageB, p, 0).rgb : texelFetch(imageA, p, 0).rgb;
    if (exposure != 0.0) c = linearToSrgb(clamp(srgbToLinear(c) * exp2(exposure), 0.0, 1.0));
    if (gamma != 1.0) c = pow(c, vec3(1.0 / gamma));
    colour = vec4(c, 1.0);
}
