// A quad from its centre and half-axes, two triangles from gl_VertexID (no vertex buffers).
uniform mat4 viewProjection;
uniform vec3 center;
uniform vec3 halfTangent;    // tangent * width / 2
uniform vec3 halfBitangent;  // bitangent * height / 2
uniform float uvScale;

out vec2 uv;
out vec2 quadPosition;  // [0, 1]^2 across the quad: x along the tangent, y along the bitangent

void main() {
    const vec2 corners[6] = vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
    vec2 c = corners[gl_VertexID];
    // Texture x along the tangent, y along the bitangent (image y up: row 0 at the top).
    uv = vec2(0.5 + 0.5 * c.x, 0.5 - 0.5 * c.y) * uvScale;
    quadPosition = 0.5 + 0.5 * c;
    gl_Position = viewProjection * vec4(center + c.x * halfTangent + c.y * halfBitangent, 1.0);
}
