// Planar polygons as triangles: NFF's `p` and `pp` entries, which may be concave (the SPD gears
// have 144-vertex faces with teeth).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace glint {

// The polygon's normal by Newell's method: the sum over its edges, robust to collinear and
// duplicate vertices and exact for planar polygons; its length is twice the polygon's area.
glm::dvec3 newell_normal(const std::vector<glm::dvec3>& polygon);

// Triangles (indices into `polygon`) covering a simple planar polygon, concave or not, each
// wound as the polygon is (counter-clockwise seen from the side its Newell normal points to).
// Ear clipping in the plane of the polygon's largest normal component. Zero-area triangles are
// left out; a polygon of zero area gives none. If the outline crosses itself, so that no ear is
// left, the rest is cut as a fan from its first vertex.
std::vector<glm::uvec3> triangulate_polygon(const std::vector<glm::dvec3>& polygon);

} // namespace glint
