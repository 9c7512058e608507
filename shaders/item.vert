#version 330 core
// Item buffer vertices: object-space positions through one model-view-projection (reverse-Z,
// infinite far plane), or, for analytic full-screen passes (planes), a triangle covering the
// viewport whose fragments compute their own depth.
layout(location = 0) in vec3 position;
uniform mat4 model_view_projection;
uniform mat4 model; // object → camera-relative world, for the flat preview's normals
uniform bool full_screen;
out vec3 view_position;

void main() {
    if (full_screen) {
        vec2 corner = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
        gl_Position = vec4(corner, 0.5, 1.0);
        view_position = vec3(0.0);
    } else {
        view_position = (model * vec4(position, 1.0)).xyz;
        gl_Position = model_view_projection * vec4(position, 1.0);
    }
}
