// `glint explain SCENE X Y --against "FLAGS"` (docs/EXPLAIN.md, "Against another setting"): one
// pixel's ray trees under two settings side by side, node by node in the walk's order, the first
// place they part marked with its cause (trace/ray_tree.h, DESIGN §13), each node's share of the
// sample's colour on both sides, and the difference split between the subtree where they part
// and the rest. The cause is found as `glint compare --a --b` finds it for its cause map.
#pragma once

#include "frame/difference.h"

#include <string>

namespace glint {

// The pixel on both sides: its trees, whether it differs and why, and which sample to show.
struct PixelAgainst {
    int x = 0, y = 0;
    PixelTrees a, b;
    Divergence why;   // cause none: the pixel's bytes agree
    int sample_a = 0; // the samples shown, row-major in each side's grid
    int sample_b = 0;
};

// The pixel (in range: the caller checks) on both rendered sides. `sample`: b·N + a of the grid
// asked for (--sample), or -1 for the first sample whose trees part (the centre where none do or
// the grids differ).
PixelAgainst explain_against(const RenderedSide& a, const RenderedSide& b, int x, int y,
                             int sample = -1);
// The same from the pixel's trees on both sides, traced already (RenderedSide::trees).
PixelAgainst explain_against(PixelTrees a, PixelTrees b, int x, int y, int sample = -1);

// For people: the settings, the bytes, the cause, then the two trees' nodes side by side.
std::string against_text(const RenderedSide& a, const RenderedSide& b, const PixelAgainst& p,
                         const std::string& scene_path);

// The same as JSON, indented, schema "glint-explain-against/1" (docs/EXPLAIN.md).
std::string against_json(const RenderedSide& a, const RenderedSide& b, const PixelAgainst& p,
                         const std::string& scene_path);

} // namespace glint
