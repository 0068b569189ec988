// A material on a curved surface: the light (and the view) in the surface's own frame at each
// fragment, and the LUT for that direction from the bank's grid (btflut.glsl's one filtered
// fetch; a bank with a predictor: the prediction, then its match LUT), so highlights and
// shadows move across the object as they would on the material.
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
// The part of the texture the shape wraps (x, y, width, height; rows top first), repeated
// mirrored: every other tile flipped, so tiles meet without seams. Where the bank's mask leaves
// background in the image, the mask's largest rectangle (ShapeRenderer, as the web page does).
uniform bool windowed;
uniform vec4 window;

in vec3 worldPosition;
in vec3 worldNormal;
in vec3 worldTangent;
in vec2 tiled;
out vec4 colour;

#if defined(PREDICTOR)
// A bank with a predictor, as an engine draws it (EngineTextures): btflut.glsl's second
// btflutRelight, its weights per fragment for that fragment's light.
uniform sampler2DArray planes;
uniform sampler2DArray weights;
uniform sampler2D labels;
uniform BtflutPredictor predictor;
#endif

void main() {
    vec2 f = fract(tiled);
    vec2 uv = windowed ? window.xy + mix(f, 1.0 - f, mod(floor(tiled), 2.0)) * window.zw : tiled;
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
#if defined(BTFLUT_NETWORK)
    // A learned model, its decoder specialised to it (learned_shader.h): its frame at this
    // fragment's light (and view: a model of views), as an engine draws a curved mesh.
    BtflutPrediction predicted = btflutNetworkPrediction(planes, uv, btflutNetworkFrame(lightTangent, viewTangent));
    colour = vec4(btflutRelightPrediction(luts, planes, labels, predictor, uv, lightTangent, layer,
                                          uvec2(gl_FragCoord.xy), predicted),
                  1.0);
    return;
#elif defined(PREDICTOR)
    // A learned model of views: predicted for this fragment's view, matched by its layer's LUTs.
    colour = vec4(btflutRelight(luts, planes, weights, labels, predictor, uv, lightTangent, viewTangent, layer,
                                uvec2(gl_FragCoord.xy)),
                  1.0);
    return;
#endif
    BtflutMaterial m = BtflutMaterial(layer, rgbLuts, greyReference, inputCode, outputCode, true);
    vec3 texel = texture(reference, uv).rgb;
    colour = vec4(btflutRelight(luts, m, texel, lightTangent, uvec2(gl_FragCoord.xy)), 1.0);
}
