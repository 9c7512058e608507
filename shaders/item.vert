#version 330 core
// Item buffer vertices: object-space positions through one model-view-projection (reverse-Z,
// infinite far plane), or, for analytic full-screen passes (planes), a triangle covering the
// viewport whose fragments compute their own depth. Objects drawn one at a time (planes) take
// their matrices, id, colour and shape from uniforms; instanced draws (every object sharing one
// mesh, tessellation or proxy box) from per-instance attributes. What the proxy shader needs
// per object (M⁻¹ and the shape) is passed on as flat outputs.
layout(location = 0) in vec3 position;
layout(location = 1) in mat4 instance_model_view_projection; // locations 1 to 4
layout(location = 5) in mat4 instance_model;                 // 5 to 8
layout(location = 9) in uint instance_object_id;
layout(location = 10) in vec3 instance_diffuse;
layout(location = 11) in mat4 instance_world_to_object; // 11 to 14
layout(location = 15) in vec3 instance_shape;           // shape, top radius, open (0 or 1)
uniform bool instanced;
uniform mat4 model_view_projection;
uniform mat4 model; // object → camera-relative world, for the flat preview's normals
uniform uint object_id; // object index + 1; 0 is background
uniform vec3 diffuse;
uniform bool full_screen;
uniform mat4 world_to_object; // camera-relative world → object (M⁻¹), for proxies
uniform int shape;            // ShapeKind
uniform float top_radius;
uniform bool open; // cylinders and cones without caps
out vec3 view_position;
flat out uint item_object_id;
flat out vec3 item_diffuse;
flat out mat4 item_world_to_object;
flat out int item_shape;
flat out float item_top_radius;
flat out int item_open;

void main() {
    item_object_id = instanced ? instance_object_id : object_id;
    item_diffuse = instanced ? instance_diffuse : diffuse;
    item_world_to_object = instanced ? instance_world_to_object : world_to_object;
    item_shape = instanced ? int(instance_shape.x) : shape;
    item_top_radius = instanced ? instance_shape.y : top_radius;
    item_open = instanced ? int(instance_shape.z) : int(open);
    if (full_screen) {
        vec2 corner = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
        gl_Position = vec4(corner, 0.5, 1.0);
        view_position = vec3(0.0);
    } else if (instanced) {
        view_position = (instance_model * vec4(position, 1.0)).xyz;
        gl_Position = instance_model_view_projection * vec4(position, 1.0);
    } else {
        view_position = (model * vec4(position, 1.0)).xyz;
        gl_Position = model_view_projection * vec4(position, 1.0);
    }
}
