#include "preview/comparison.h"

#include "frame/difference_maps.h"
#include "frame/explain_against.h"
#include "preview/views.h"

namespace glint {

namespace {

// The top `height` rows of a map: the frame, without the legend strip below it.
Image frame_part(const Image& map, int height) {
    Image out(map.width, height);
    std::copy_n(map.rgb.begin(), out.rgb.size(), out.rgb.begin());
    return out;
}

} // namespace

ReferenceComparison::ReferenceComparison(Input input)
    : input_(std::move(input)), thread_([this] { run(); }) {}

ReferenceComparison::~ReferenceComparison() {
    if (thread_.joinable()) thread_.join();
}

void ReferenceComparison::run() {
    try {
        live_ = std::make_unique<RenderedSide>(input_.live, input_.live_world, input_.live_ids);
        Side& ref = input_.reference;
        if (ref.frame.precision == Precision::f64) {
            reference_ = std::make_unique<RenderedSide>(ref); // ray mode: no GL
        } else {
            // Its own render settings and structure on the live scene's prepared geometry.
            auto world =
                std::make_shared<const World>(ref.scene, input_.live_world->geometry(), ref.accel);
            reference_ =
                std::make_unique<RenderedSide>(ref, std::move(world), input_.reference_ids);
        }
        difference_ = glint::difference(*live_, *reference_, false);
        const Image live = live_->frame().result.bytes();
        heat_ = frame_part(heat_map(difference_), live.height);
        causes_ = frame_part(cause_map(difference_, live), live.height);
        differing_ = Image(live.width, live.height);
        for (int y = 0; y < live.height; ++y)
            for (int x = 0; x < live.width; ++x) {
                const bool differs =
                    difference_.causes[static_cast<std::size_t>(y) * live.width + x] != Cause::none;
                const Rgb c = difference_colour(live.pixel(x, y), differs);
                std::copy(c.begin(), c.end(), differing_.pixel(x, y));
            }
    } catch (const std::exception& e) {
        error_ = e.what();
    }
    ready_.store(true, std::memory_order_release);
}

std::string ReferenceComparison::explain(int x, int y, const std::string& scene_name) const {
    if (!ready() || !error_.empty()) return "";
    return against_text(*live_, *reference_, explain_against(*live_, *reference_, x, y),
                        scene_name);
}

} // namespace glint
