#version 330 core
// A cut-out mesh's fragment: its alpha is the material's factor times the base colour texture's
// alpha at the fragment (bilinear, with the texture's wrap modes, as the tracer samples it);
// below the cut-off the fragment is discarded, as the tracer's hit is no hit. GL's filtering is
// not the tracer's to the bit: the exact resolve tests cut-out objects from the eye
// (trace/primary_hits.cpp), so a disagreement at a mask's edge costs a test, not a wrong pixel.
uniform bool flat_preview;
uniform uint object_id; // object index + 1
uniform vec3 diffuse;
uniform float alpha;    // the material's factor
uniform float cutoff;
uniform bool textured;  // the texture has an alpha channel and the mesh texture coordinates
uniform sampler2D alpha_texture; // R8
in vec3 view_position;
in vec2 texture_uv;
layout(location = 0) out uint item;
layout(location = 1) out vec4 colour;

void main() {
    float a = alpha * (textured ? texture(alpha_texture, texture_uv).r : 1.0);
    if (a < cutoff) discard;
    item = object_id;
    if (flat_preview) {
        vec3 facet = cross(dFdx(view_position), dFdy(view_position));
        vec3 n = length(facet) > 0.0 ? normalize(facet) : vec3(0.0);
        colour = vec4(diffuse * (0.15 + 0.85 * abs(dot(n, normalize(view_position)))), 1.0);
    }
}
