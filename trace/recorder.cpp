#include "trace/recorder.h"

namespace glint {
inline namespace GLINT_PRECISION {

RecordedRay& RayRecorder::open() {
    return rays_[static_cast<std::size_t>(open_.back())];
}

void RayRecorder::begin(RayKind kind, const Ray& ray, const Hit& hit, Real factor, Real weight,
                        int depth) {
    RecordedRay node;
    node.kind = kind, node.parent = open_.empty() ? -1 : open_.back(), node.depth = depth;
    node.factor = factor, node.weight = weight, node.ray = ray, node.hit = hit;
    const int index = static_cast<int>(rays_.size());
    rays_.push_back(std::move(node));
    if (!open_.empty()) open().children.push_back(index);
    open_.push_back(index);
}

void RayRecorder::end(Vec3 colour) {
    open().colour = colour;
    open_.pop_back();
}

void RayRecorder::surface(const SurfacePoint& point, bool odd_cell,
                          const std::optional<TexelSample>& texel, Vec3 ambient,
                          Vec3 emission) {
    RecordedRay& node = open();
    node.surface = point, node.odd_cell = odd_cell, node.texel = texel, node.ambient = ambient;
    node.emission = emission;
}

void RayRecorder::light(const LightTerm& term) {
    open().lights.push_back(term);
}

void RayRecorder::omitted(RayKind kind, Real weight, OmittedRay::Why why) {
    open().omitted.push_back({kind, weight, why});
}

} // namespace GLINT_PRECISION
} // namespace glint
