#include "io/polygon.h"

#include <cmath>
#include <numeric>

namespace glint {

glm::dvec3 newell_normal(const std::vector<glm::dvec3>& polygon) {
    glm::dvec3 n(0.0);
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const glm::dvec3& a = polygon[i];
        const glm::dvec3& b = polygon[(i + 1) % polygon.size()];
        n += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x),
                        (a.x - b.x) * (a.y + b.y));
    }
    return n;
}

std::vector<glm::uvec3> triangulate_polygon(const std::vector<glm::dvec3>& polygon) {
    std::vector<glm::uvec3> triangles;
    const glm::dvec3 normal = newell_normal(polygon);
    const glm::dvec3 a = glm::abs(normal);
    if (polygon.size() < 3 || !(a.x + a.y + a.z > 0)) return triangles;
    // Project onto the plane of the two other axes, in the order that keeps the winding, so that
    // counter-clockwise about the normal is a positive signed area.
    const int k = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    const double sign = normal[k] > 0 ? 1.0 : -1.0;
    std::vector<glm::dvec2> p;
    p.reserve(polygon.size());
    for (const glm::dvec3& q : polygon) p.emplace_back(q[u], q[v]);
    // Twice the signed area of (x, y, z), positive when they turn the polygon's way.
    const auto turn = [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
        const glm::dvec2 e = p[y] - p[x], f = p[z] - p[y];
        return sign * (e.x * f.y - e.y * f.x);
    };

    std::vector<std::uint32_t> left(polygon.size());
    std::iota(left.begin(), left.end(), 0u);
    // An ear: a convex corner whose triangle holds no other remaining vertex (on its edges
    // included, except vertices at its own corners' positions: outlines may touch themselves).
    const auto is_ear = [&](std::size_t at) {
        const std::size_t m = left.size();
        const std::uint32_t x = left[(at + m - 1) % m], y = left[at], z = left[(at + 1) % m];
        for (const std::uint32_t w : left) {
            if (w == x || w == y || w == z || p[w] == p[x] || p[w] == p[y] || p[w] == p[z])
                continue;
            if (turn(x, y, w) >= 0 && turn(y, z, w) >= 0 && turn(z, x, w) >= 0) return false;
        }
        return true;
    };
    std::size_t at = 0;
    while (left.size() > 3) {
        const std::size_t m = left.size();
        bool cut = false;
        for (std::size_t tries = 0; tries < m; ++tries, at = (at + 1) % m) {
            const std::uint32_t x = left[(at + m - 1) % m], y = left[at], z = left[(at + 1) % m];
            const double t = turn(x, y, z);
            if (t == 0) { // collinear or repeated corner: drop it, it covers nothing
                cut = true;
            } else if (t > 0 && is_ear(at)) {
                triangles.push_back({x, y, z});
                cut = true;
            }
            if (cut) break;
        }
        if (!cut) { // self-crossing outline: no ear left
            for (std::size_t i = 1; i + 1 < left.size(); ++i)
                if (turn(left[0], left[i], left[i + 1]) != 0)
                    triangles.push_back({left[0], left[i], left[i + 1]});
            return triangles;
        }
        left.erase(left.begin() + static_cast<std::ptrdiff_t>(at));
        at = (at + left.size() - 1) % left.size(); // the corner before may have become an ear
    }
    if (turn(left[0], left[1], left[2]) != 0) triangles.push_back({left[0], left[1], left[2]});
    return triangles;
}

} // namespace glint
