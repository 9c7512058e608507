// The explained pixel's ray tree drawn into the scene (docs/PREVIEW.md): each ray of the tree
// (frame/explain.h) projected through the camera into image coordinates, one colour per kind.
// Pure geometry: the preview draws these segments, and the window test checks that the
// screenshot changed along them.
#pragma once

#include "trace/explain.h"

#include <vector>

namespace glint {

struct OverlaySegment {
    enum class Kind { primary, reflection, transmission, shadow, blocked_shadow };
    Kind kind;
    // In image pixels, continuous (pixel (i, j)'s centre is (i + 0.5, j + 0.5)), y down. The
    // primary ray passes through the eye, so it projects to one point: the clicked pixel.
    float x0, y0, x1, y1;
};

// The tree's rays, in order: the primary ray (a point), each reflected and transmitted ray from
// its origin to its hit (or far along it, for a miss), and each shadow ray cast, from the surface
// to the light (blocked ones on their own kind). Parts behind the eye are cut away; a ray
// entirely behind it is left out.
std::vector<OverlaySegment> tree_segments(const World& world, const PixelExplanation& e);

} // namespace glint
