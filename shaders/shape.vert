// A sphere or a cylinder from gl_VertexID (no vertex buffers): a grid of `around` x `along`
// cells, two triangles each. Each vertex carries its normal and its tangent (the direction
// of texture +u), so the fragment shader has the material's frame at every point.
uniform mat4 viewProjection;
uniform int shape;        // 0: sphere of radius 1; 1: cylinder of radius 1 and height 2 (open)
uniform int around;       // cells around the axis (z)
uniform int along;        // cells along it
uniform vec2 uvRepeats;   // texture repeats around and along

out vec3 worldPosition;
out vec3 worldNormal;
out vec3 worldTangent;
out vec2 tiled;

void main() {
    const ivec2 corners[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));
    int cell = gl_VertexID / 6;
    ivec2 at = ivec2(cell % around, cell / around) + corners[gl_VertexID % 6];
    float u = float(at.x) / float(around), v = float(at.y) / float(along);
    float phi = 6.28318530718 * u;
    vec3 radial = vec3(cos(phi), sin(phi), 0.0);
    worldTangent = vec3(-sin(phi), cos(phi), 0.0);
    if (shape == 0) {
        float theta = 3.14159265359 * (1.0 - v);  // from the south pole (v = 0) to the north
        worldPosition = vec3(sin(theta) * radial.xy, cos(theta));
        worldNormal = worldPosition;
    } else {
        worldPosition = vec3(radial.xy, 2.0 * v - 1.0);
        worldNormal = radial;
    }
    tiled = vec2(u, 1.0 - v) * uvRepeats;  // texture rows run down the image: image up is +v on the shape
    gl_Position = viewProjection * vec4(worldPosition, 1.0);
}
