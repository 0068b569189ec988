// `btflut bench decoder`'s shaders of one learned decoder, drawn side by side in one context
// (src/apps/cli/bench_decoder.cpp), after btflut.glsl (its BtflutLearnedFrame):
// PLAIN: the network as a plain shader, written as one would by hand (issue 46's reference):
//   the weights in a uniform block as vec4 columns, loops of constant bounds (the sizes are
//   #defines), the ELU as btflut writes it, the light folded into the first layer's bias.
// BTFLUT: btflut's decoder as engines call it (btflutNetworkValue of the source specialised to
//   the model, learned_shader.h, which the program holds after the include).
// FLAT: one fetch of the codes' first layer (what a flat texture costs).
// TEXTURE_SPACE reads the codes at the pixel's texel (texelFetch, as a relight pass); else they
// are sampled bilinearly at `uv` (as a quad drawn per fragment). Each writes the prediction.
uniform sampler2DArray planes;     // the codes' bytes, four to an RGBA8 layer
uniform BtflutLearnedFrame frame;  // the light's part (LearnedModel::lightFrame)
uniform vec2 frameSize;            // the target's pixels
uniform float uvScale;             // texture repeats across the target (per fragment)
out vec4 colour;

vec4 codesAt(int layer) {
#if defined(TEXTURE_SPACE)
    return texelFetch(planes, ivec3(ivec2(gl_FragCoord.xy), layer), 0) * 255.0;
#else
    return textureLod(planes, vec3(gl_FragCoord.xy / frameSize * uvScale, float(layer)), 0.0) * 255.0;
#endif
}

#if defined(PLAIN)
// The network's sizes: CODES (LAYERS of four), CHANNELS (1 or 3), two hidden layers WIDTH1 and
// WIDTH2 (padded to fours with zero weights).
#define G1 ((WIDTH1 + 3) / 4)
#define G2 ((WIDTH2 + 3) / 4)
layout(std140) uniform PlainNetwork {
    vec4 codeScale[LAYERS];
    vec4 codeBias[LAYERS];
    vec4 w1[CODES * G1];   // input i's weights to outputs 4 o .. 4 o + 3 at [i * G1 + o]
    vec4 w2[WIDTH1 * G2];
    vec4 b2[G2];
    vec4 w3[WIDTH2];       // the output layer's, to the (at most four) channels
    vec4 b3;
};

vec4 elu(vec4 a) { return max(a, 0.0) + exp(min(a, 0.0)) - 1.0; }

vec3 decode() {
    float v[LAYERS * 4];
    vec3 value = frame.offset;
    for (int l = 0; l < LAYERS; ++l) {
        vec4 x = (codesAt(l) - codeBias[l]) * codeScale[l];
        for (int c = 0; c < CHANNELS; ++c) value[c] += dot(frame.basis[l * 3 + c], x);
        for (int k = 0; k < 4; ++k) v[l * 4 + k] = x[k];
    }
    vec4 h1[G1];
    for (int o = 0; o < G1; ++o) {
        vec4 a = frame.hidden[o];
        for (int i = 0; i < CODES; ++i) a += v[i] * w1[i * G1 + o];
        h1[o] = elu(a);
    }
    vec4 h2[G2];
    for (int o = 0; o < G2; ++o) {
        vec4 a = b2[o];
        for (int j = 0; j < G1; ++j)
            a += h1[j].x * w2[(4 * j) * G2 + o] + h1[j].y * w2[(4 * j + 1) * G2 + o] +
                 h1[j].z * w2[(4 * j + 2) * G2 + o] + h1[j].w * w2[(4 * j + 3) * G2 + o];
        h2[o] = elu(a);
    }
    vec4 y = b3;
    for (int j = 0; j < G2; ++j)
        y += h2[j].x * w3[4 * j] + h2[j].y * w3[4 * j + 1] + h2[j].z * w3[4 * j + 2] + h2[j].w * w3[4 * j + 3];
    value += y.xyz;
    return clamp(CHANNELS == 3 ? value : vec3(value.x), 0.0, 1.0);
}
#endif

void main() {
#if defined(FLAT)
    colour = vec4(codesAt(0).rgb / 255.0, 1.0);
#elif defined(PLAIN)
    colour = vec4(decode(), 1.0);
#else
    vec4 codes[BTFLUT_MAX_LAYERS];
    for (int l = 0; l < BTFLUT_MAX_LAYERS; ++l)
        codes[l] = l < (BTFLUT_NETWORK_CODES + 3) / 4 ? floor(codesAt(l) + 0.5) : vec4(0.0);
    colour = vec4(btflutLearnedPredictionOf(btflutNetworkValue(codes, frame)).colour, 1.0);
#endif
}
