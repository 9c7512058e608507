#include "trace/accel/grid.h"

#include <algorithm>

namespace glint {
inline namespace GLINT_PRECISION {

UniformGrid::UniformGrid(std::span<const Bounds> items) {
    if (items.empty()) return;
    for (const Bounds& b : items) bounds_.extend(b);
    // Pad so that items on the outer faces lie inside the outermost cells.
    const Vec3 pad = 1e-5_r * (bounds_.hi - bounds_.lo) + 1e-30_r;
    bounds_.lo -= pad, bounds_.hi += pad;
    const Vec3 extent = bounds_.hi - bounds_.lo;
    // About three items per cell; cells cubic where the extent allows, 1 to 256 per axis.
    const Real volume =
        std::max(extent.x, 1e-30_r) * std::max(extent.y, 1e-30_r) * std::max(extent.z, 1e-30_r);
    const Real cell = std::cbrt(volume / (3.0_r * static_cast<Real>(items.size())));
    for (int a = 0; a < 3; ++a) {
        resolution_[a] = 1 + bin_index(std::ceil(extent[a] / cell) - 1, 256);
        cell_size_[a] = extent[a] / static_cast<Real>(resolution_[a]);
        inverse_cell_[a] = 1.0_r / cell_size_[a];
    }
    // A sixty-fourth of a cell lists an item in a neighbour only when it nearly touches it (9%
    // more item tests on rings-3 than none, docs/PERFORMANCE.md) and covers the rounding of rays
    // cast from up to about 5,000 cells away (grid.h); rays from farther test every item.
    rounding_ = 8.0_r * gamma(3) * (glm::abs(bounds_.lo) + glm::abs(bounds_.hi));
    margin_ = cell_size_ / 64.0_r + 2.0_r * rounding_;
    item_count_ = static_cast<std::uint32_t>(items.size());
    const std::size_t cells =
        static_cast<std::size_t>(resolution_.x) * resolution_.y * resolution_.z;
    const auto cell_range = [&](const Bounds& b, glm::ivec3& lo, glm::ivec3& hi) {
        for (int a = 0; a < 3; ++a) {
            lo[a] = bin_index((b.lo[a] - margin_[a] - bounds_.lo[a]) * inverse_cell_[a],
                              resolution_[a]);
            hi[a] = bin_index((b.hi[a] + margin_[a] - bounds_.lo[a]) * inverse_cell_[a],
                              resolution_[a]);
        }
    };
    // Two passes (count, then fill) into compressed rows.
    cell_start_.assign(cells + 1, 0);
    glm::ivec3 lo, hi;
    for (const Bounds& b : items) {
        cell_range(b, lo, hi);
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x)
                    ++cell_start_[(static_cast<std::size_t>(z) * resolution_.y + y) *
                                      resolution_.x +
                                  x + 1];
    }
    for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
    cell_items_.resize(cell_start_[cells]);
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::uint32_t i = 0; i < items.size(); ++i) {
        cell_range(items[i], lo, hi);
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x)
                    cell_items_[fill[(static_cast<std::size_t>(z) * resolution_.y + y) *
                                         resolution_.x +
                                     x]++] = i;
    }
}

} // namespace GLINT_PRECISION
} // namespace glint
