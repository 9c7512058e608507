// Uniform grid (space division): cells of equal size, about three items per cell, each listing
// the items whose boxes overlap it; traversed cell by cell along the ray with a 3D-DDA
// (Amanatides & Woo 1987).
#pragma once

#include "trace/accel/counters.h"
#include "trace/bounds.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

namespace glint::inline GLINT_PRECISION {

class UniformGrid {
  public:
    UniformGrid() = default;
    explicit UniformGrid(std::span<const Bounds> items);

    std::size_t memory_bytes() const { return (cell_start_.size() + cell_items_.size()) * 4; }
    std::size_t node_count() const { return cell_start_.empty() ? 0 : cell_start_.size() - 1; }

    template <class Counters, class Visit>
    void traverse(const Ray& ray, Real& t_max, Counters& counters, Visit&& visit) const {
        if (cell_start_.empty()) return;
        const SlabRay slab(ray);
        const Vec3& inverse_direction = slab.inverse_direction;
        const Real t_enter = slab.entry(bounds_, t_max);
        if (t_enter == kInfinity) return;
        const Vec3 p = ray.origin + t_enter * ray.direction;
        glm::ivec3 cell, step;
        Vec3 t_next, t_delta;
        for (int a = 0; a < 3; ++a) {
            cell[a] = bin_index((p[a] - bounds_.lo[a]) * inverse_cell_[a], resolution_[a]);
            if (ray.direction[a] > 0) {
                step[a] = 1;
                t_next[a] = (bounds_.lo[a] + (cell[a] + 1) * cell_size_[a] - ray.origin[a]) *
                            inverse_direction[a];
                t_delta[a] = cell_size_[a] * inverse_direction[a];
            } else if (ray.direction[a] < 0) {
                step[a] = -1;
                t_next[a] = (bounds_.lo[a] + cell[a] * cell_size_[a] - ray.origin[a]) *
                            inverse_direction[a];
                t_delta[a] = -cell_size_[a] * inverse_direction[a];
            } else {
                step[a] = 0;
                t_next[a] = kInfinity;
                t_delta[a] = kInfinity;
            }
        }
        for (;;) {
            counters.node();
            const std::size_t c =
                (static_cast<std::size_t>(cell.z) * resolution_.y + cell.y) * resolution_.x +
                cell.x;
            // Items spanning several cells may be visited again; their test is idempotent.
            for (std::uint32_t i = cell_start_[c]; i < cell_start_[c + 1]; ++i) {
                counters.primitive();
                if (visit(cell_items_[i], t_max)) return;
            }
            const int a =
                t_next.x < t_next.y ? (t_next.x < t_next.z ? 0 : 2) : (t_next.y < t_next.z ? 1 : 2);
            // A hit before this cell's exit cannot be beaten by anything in later cells. The
            // exit is enlarged by the same relative margin as box tests, for rounding.
            if (t_max <= t_next[a] * (1.0_r + 2.0_r * gamma(3)) || t_next[a] == kInfinity) return;
            cell[a] += step[a];
            if (cell[a] < 0 || cell[a] >= resolution_[a]) return;
            t_next[a] += t_delta[a];
        }
    }

  private:
    Bounds bounds_;
    glm::ivec3 resolution_{0};
    Vec3 cell_size_{0.0_r}, inverse_cell_{0.0_r};
    std::vector<std::uint32_t>
        cell_start_; // per cell, into cell_items_ (CSR), one extra at the end
    std::vector<std::uint32_t> cell_items_;
};

} // namespace glint::inline GLINT_PRECISION
