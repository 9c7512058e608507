#include "trace/accel/accel.h"

namespace glint {
inline namespace GLINT_PRECISION {

Accelerator::Accelerator(AccelKind kind, std::vector<Bounds> items) {
    switch (kind) {
    case AccelKind::list:
        structure_.emplace<ItemList>(ItemList{std::move(items)});
        break;
    case AccelKind::bvh:
        structure_.emplace<WideBvh>(items);
        break;
    case AccelKind::spheres:
        structure_.emplace<SphereTree>(items);
        break;
    case AccelKind::grid:
        structure_.emplace<UniformGrid>(items);
        break;
    case AccelKind::kd:
        structure_.emplace<KdTree>(items);
        break;
    case AccelKind::bvh2:
        structure_.emplace<BinaryBvh>(items);
        break;
    }
}

Accelerator Accelerator::refitted(std::vector<Bounds> items) const {
    if (const WideBvh* bvh = std::get_if<WideBvh>(&structure_)) {
        Accelerator moved;
        moved.structure_.emplace<WideBvh>(bvh->refitted(items));
        return moved;
    }
    if (const BinaryBvh* bvh = std::get_if<BinaryBvh>(&structure_)) {
        Accelerator moved;
        moved.structure_.emplace<BinaryBvh>(bvh->refitted(items));
        return moved;
    }
    return Accelerator(kind(), std::move(items));
}

std::size_t Accelerator::memory_bytes() const {
    return std::visit([](const auto& s) { return s.memory_bytes(); }, structure_);
}

std::size_t Accelerator::node_count() const {
    return std::visit([](const auto& s) { return s.node_count(); }, structure_);
}

} // namespace GLINT_PRECISION
} // namespace glint
