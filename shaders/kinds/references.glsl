// ---------------------------------------------------------------------------------------------
// References blended (material.json "kind": "references"): K references, one to a layer of
// `planes`; the light's weight on each from the weight grid (`weights`), rounded to
// 1 / BTFLUT_WEIGHT_UNIT as btflut's CPU rounds its barycentric weights.

// A blend of references, one at a time: `weight` (an integer, of BTFLUT_WEIGHT_UNIT) times
// the reference's texel. Start from btflutNoPrediction().
void btflutAddReference(inout BtflutPrediction p, float weight, vec4 texel) {
    p.channels += weight * btflutBytes(texel).rgb;
    p.colour += weight / float(BTFLUT_WEIGHT_UNIT) * texel.rgb;
}


// The blend at texture coordinate `uv` for a light in the tangent frame (btflutPrediction; one
// view).
BtflutPrediction btflutReferencesPredictionAt(sampler2DArray planes, sampler2DArray weights, BtflutPredictor p, vec2 uv,
                                              vec3 lightTangent, vec3 viewTangent) {
    BtflutPrediction prediction = btflutNoPrediction();
    vec2 disk = btflutDiskPoint(lightTangent);
    vec4 w4 = vec4(0.0);
    for (int k = 0; k < p.planes; ++k) {
        if (k % 4 == 0) w4 = btflutWeightLayer(weights, disk, k / 4);
        float w = floor(w4[k % 4] * float(BTFLUT_WEIGHT_UNIT) + 0.5);
        if (w != 0.0) btflutAddReference(prediction, w, texture(planes, vec3(uv, float(k))));
    }
    return prediction;
}
