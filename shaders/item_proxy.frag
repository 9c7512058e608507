#version 330 core
// Proxy mode (and planes in every mode): the fragment's own camera ray, inverse-transformed into
// object space, intersected exactly with the unit primitive; misses are discarded and the depth
// written is the true hit's, so ids carry no tessellation error. Same conventions as trace/.
// Per object, from item.vert (uniforms for planes, instance attributes for proxy boxes):
flat in uint item_object_id; // object index + 1
flat in vec3 item_diffuse;
flat in mat4 item_world_to_object; // camera-relative world → object (M⁻¹)
flat in int item_shape; // ShapeKind, as the SHAPE_ constants the C++ side inserts (item_buffer.cpp)
flat in float item_top_radius;
flat in int item_open; // cylinders and cones without caps
uniform vec3 forward;         // unit viewing direction
uniform vec3 right_scaled;    // right · tan(fov_y/2) · aspect
uniform vec3 up_scaled;       // up · tan(fov_y/2)
uniform vec2 viewport;
uniform float near;
uniform bool flat_preview; // write `colour` too, as item_mesh.frag does
layout(location = 0) out uint item;
layout(location = 1) out vec4 colour;

const float kInfinity = 1.0 / 0.0;

float nearest(float t0, float t1) {
    if (t0 > t1) { float s = t0; t0 = t1; t1 = s; }
    return t0 > 0.0 ? t0 : (t1 > 0.0 ? t1 : kInfinity);
}

// Cancellation-free sphere roots (Ray Tracing Gems ch. 7), as trace/shapes/sphere.h.
float sphere(vec3 o, vec3 d) {
    float a = dot(d, d), b = dot(o, d), c = dot(o, o) - 1.0;
    vec3 closest = o - (b / a) * d;
    float discriminant = a * (1.0 - dot(closest, closest));
    if (discriminant < 0.0) return kInfinity;
    float q = -(b + (b < 0.0 ? -1.0 : 1.0) * sqrt(discriminant));
    return nearest(c / q, q / a);
}

float plane(vec3 o, vec3 d) {
    float t = -o.y / d.y;
    return t > 0.0 ? t : kInfinity;
}

float disk(vec3 o, vec3 d, float radius, float height) {
    float t = (height - o.y) / d.y;
    vec3 p = o + t * d;
    return (t > 0.0 && dot(p.xz, p.xz) <= radius * radius) ? t : kInfinity;
}

float box(vec3 o, vec3 d) {
    vec3 inverse = 1.0 / d;
    vec3 t0 = (-1.0 - o) * inverse, t1 = (1.0 - o) * inverse;
    vec3 lo = min(t0, t1), hi = max(t0, t1);
    float t_near = max(max(lo.x, lo.y), lo.z), t_far = min(min(hi.x, hi.y), hi.z);
    return t_near <= t_far ? nearest(t_near, t_far) : kInfinity;
}

// Side of x² + z² = r(y)², r(y) = 1 − k·y, 0 ≤ y ≤ 1 (k = 0: the cylinder).
float side(vec3 o, vec3 d, float k) {
    float w = 1.0 - k * o.y, wd = -k * d.y;
    float a = dot(d.xz, d.xz) - wd * wd, b = dot(o.xz, d.xz) - w * wd, c = dot(o.xz, o.xz) - w * w;
    float discriminant = b * b - a * c;
    if (discriminant < 0.0 || a == 0.0) return kInfinity;
    float q = -(b + (b < 0.0 ? -1.0 : 1.0) * sqrt(discriminant));
    float best = kInfinity;
    float roots[2] = float[2](c / q, q / a);
    for (int i = 0; i < 2; ++i) {
        float y = o.y + roots[i] * d.y;
        if (roots[i] > 0.0 && y >= 0.0 && y <= 1.0) best = min(best, roots[i]);
    }
    return best;
}

void main() {
    vec2 ndc = 2.0 * gl_FragCoord.xy / viewport - 1.0; // pixel centres, GL's row 0 at the bottom
    vec3 d = normalize(forward + ndc.x * right_scaled + ndc.y * up_scaled);
    vec3 o = item_world_to_object[3].xyz; // the eye is the camera-relative origin
    vec3 dl = mat3(item_world_to_object) * d;
    float t = kInfinity;
    if (item_shape == SHAPE_SPHERE) t = sphere(o, dl);
    else if (item_shape == SHAPE_PLANE) t = plane(o, dl);
    else if (item_shape == SHAPE_BOX) t = box(o, dl);
    else if (item_shape == SHAPE_DISK) t = disk(o, dl, 1.0, 0.0);
    else if (item_shape == SHAPE_CYLINDER || item_shape == SHAPE_CONE) {
        float k = item_shape == SHAPE_CYLINDER ? 0.0 : 1.0 - item_top_radius;
        t = side(o, dl, k);
        if (item_open == 0) t = min(t, disk(o, dl, 1.0, 0.0));
        if (item_open == 0 && (item_shape == SHAPE_CYLINDER || item_top_radius > 0.0))
            t = min(t, disk(o, dl, 1.0 - k, 1.0));
    }
    if (flat_preview) { // derivatives before the discard, over the whole 2×2 quad
        vec3 p = t < kInfinity ? t * d : vec3(0.0);
        vec3 facet = cross(dFdx(p), dFdy(p));
        vec3 n = length(facet) > 0.0 ? normalize(facet) : vec3(0.0);
        colour = vec4(item_diffuse * (0.15 + 0.85 * abs(dot(n, d))), 1.0);
    }
    if (t == kInfinity) discard;
    gl_FragDepth = near / (t * dot(d, forward)); // reverse-Z: near / view depth
    item = item_object_id;
}
