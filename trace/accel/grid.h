// Uniform grid (space division): cells of equal size, about three items per cell, each listing
// the items whose boxes overlap it; traversed cell by cell along the ray with a 3D-DDA
// (Amanatides & Woo 1987).
//
// Rounding. The DDA decides which cell a point of the ray is in by comparing computed crossing
// distances; near a cell face it can be wrong by a few ulps of the coordinates involved, and then
// it skips the neighbouring cell where the ray only grazes it (or leaves a cell before the one
// hit that counts). Each item is therefore listed in every cell within a margin of its box, and
// a ray whose possible error exceeds that margin (one cast from very far away, or a grid whose
// cells float cannot resolve at its distance from the origin) tests every item instead. Either
// way the grid visits every item the list would count (tests/accel_test.cpp, fuzz_nff).
#pragma once

#include "trace/accel/counters.h"
#include "trace/bounds.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

namespace glint {
inline namespace GLINT_PRECISION {

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
        Real t_enter, t_exit;
        if (!slab.clip(bounds_, t_max, t_enter, t_exit)) return;
        if (!within_margin(ray, t_exit)) {
            counters.node();
            for (std::uint32_t i = 0; i < item_count_; ++i) {
                counters.primitive();
                if (visit(i, t_max)) return;
            }
            return;
        }
        const Vec3 p = ray.origin + t_enter * ray.direction;
        glm::ivec3 cell, step;
        for (int a = 0; a < 3; ++a) {
            cell[a] = bin_index((p[a] - bounds_.lo[a]) * inverse_cell_[a], resolution_[a]);
            step[a] = ray.direction[a] > 0 ? 1 : ray.direction[a] < 0 ? -1 : 0;
        }
        // Where the ray leaves the current cell across axis a's face, recomputed from the face
        // rather than accumulated, so that its error does not grow with the steps taken.
        const auto crossing = [&](int a) {
            if (step[a] == 0) return kInfinity;
            const Real face =
                bounds_.lo[a] + static_cast<Real>(cell[a] + (step[a] > 0)) * cell_size_[a];
            return (face - ray.origin[a]) * inverse_direction[a];
        };
        Vec3 t_next(crossing(0), crossing(1), crossing(2));
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
            // exit is enlarged by the same relative margin as box tests, for rounding; what it
            // admits lies within the items' margin (within_margin).
            if (t_max <= t_next[a] * (1.0_r + 2.0_r * gamma(3)) || t_next[a] == kInfinity) return;
            cell[a] += step[a];
            if (cell[a] < 0 || cell[a] >= resolution_[a]) return;
            t_next[a] = crossing(a);
        }
    }

  private:
    // Whether the DDA's possible error along this ray, up to t_end, stays within the margin the
    // items were listed with. Its position errors along axis a are a few γ3 of the coordinates
    // it computes with: the origin, the distance travelled (crossings, the entry point, the
    // slack of box tests and of the early exit above) and the grid's own faces (rounding_).
    bool within_margin(const Ray& ray, Real t_end) const {
        const Vec3 error =
            16.0_r * gamma(3) * (glm::abs(ray.origin) + t_end * glm::abs(ray.direction));
        return glm::all(glm::lessThanEqual(error + rounding_, margin_));
    }

    Bounds bounds_;
    glm::ivec3 resolution_{0};
    Vec3 cell_size_{0.0_r}, inverse_cell_{0.0_r};
    Vec3 rounding_{0.0_r}; // bound on the error of faces and bins computed from bounds_
    Vec3 margin_{0.0_r};   // each item is listed in every cell this close to its box
    std::uint32_t item_count_ = 0;
    std::vector<std::uint32_t>
        cell_start_; // per cell, into cell_items_ (CSR), one extra at the end
    std::vector<std::uint32_t> cell_items_;
};

} // namespace GLINT_PRECISION
} // namespace glint
