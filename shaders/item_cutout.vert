#version 330 core
// Cut-out meshes (DESIGN §13): drawn one object at a time, their texture coordinates passed on
// so that item_cutout.frag discards the fragments the tracer's intersection cuts away.
layout(location = 0) in vec3 position;
layout(location = 1) in vec2 uv; // absent (0, 0) for a mesh without texture coordinates
uniform mat4 model_view_projection;
uniform mat4 model; // object → camera-relative world, for the flat preview's normals
uniform mat3 uv_transform; // the texture's (KHR_texture_transform), as the tracer applies it
out vec3 view_position;
out vec2 texture_uv;

void main() {
    view_position = (model * vec4(position, 1.0)).xyz;
    texture_uv = (uv_transform * vec3(uv, 1.0)).xy;
    gl_Position = model_view_projection * vec4(position, 1.0);
}
