#version 330 core
// Mesh mode: the rasterized (tessellated or given) triangle's object, and for the interactive
// preview a flat-shaded colour (diffuse dimmed by the facet's angle to the eye).
uniform bool flat_preview; // write `colour` too (a second draw buffer is bound)
in vec3 view_position;
flat in uint item_object_id; // object index + 1 (item.vert: uniform or instance attribute)
flat in vec3 item_diffuse;
layout(location = 0) out uint item;
layout(location = 1) out vec4 colour;

void main() {
    item = item_object_id;
    if (flat_preview) {
        vec3 facet = cross(dFdx(view_position), dFdy(view_position));
        vec3 n = length(facet) > 0.0 ? normalize(facet) : vec3(0.0);
        colour = vec4(item_diffuse * (0.15 + 0.85 * abs(dot(n, normalize(view_position)))), 1.0);
    }
}
