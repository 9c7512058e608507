#include "frame/explain_against.h"

#include "frame/text_format.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>

namespace glint {

PixelAgainst explain_against(const RenderedSide& a, const RenderedSide& b, int x, int y,
                             int sample) {
    const std::uint32_t pixel[] = {static_cast<std::uint32_t>(y) *
                                       static_cast<std::uint32_t>(a.side().scene.camera.width) +
                                   static_cast<std::uint32_t>(x)};
    return explain_against(std::move(a.trees(pixel).front()), std::move(b.trees(pixel).front()), x,
                           y, sample);
}

PixelAgainst explain_against(PixelTrees a, PixelTrees b, int x, int y, int sample) {
    PixelAgainst p;
    p.x = x, p.y = y;
    p.a = std::move(a), p.b = std::move(b);
    p.why = pixel_difference(p.a, p.b, false);
    const auto centre = [](const PixelTrees& t) { return (t.grid / 2) * t.grid + t.grid / 2; };
    const bool same_grid = p.a.grid == p.b.grid;
    if (sample >= 0 && same_grid) {
        p.sample_a = p.sample_b = sample;
    } else if (same_grid && p.why.cause != Cause::none && p.why.cause != Cause::precision &&
               p.why.cause != Cause::sampling) {
        p.sample_a = p.sample_b = p.why.sample;
    } else {
        p.sample_a = centre(p.a), p.sample_b = centre(p.b);
    }
    return p;
}

namespace {

// A colour with four decimals: "(0.1250, 0.0000, 1.2000)".
std::string rgb_text(DVec3 c) {
    std::string out = "(";
    for (int k = 0; k < 3; ++k) {
        char text[32];
        // No "-0.0000": a share that rounds to 0 is written as 0.
        std::snprintf(text, sizeof text, "%.4f", std::abs(c[k]) < 5e-5 ? 0.0 : c[k]);
        out += (k ? ", " : "") + std::string(text);
    }
    return out + ")";
}

// A row of the side-by-side table: one aligned pair of nodes.
struct Row {
    std::string path; // "P", "P.R", "P.R.T": the primary ray, then reflected R and transmitted T
    int node_a = -1, node_b = -1;
    DVec3 delta{0};          // B's share − A's share
    bool diverges = false;   // the first divergence is at this row
    bool in_subtree = false; // at or below the first divergence
};

// The aligned rows of the shown samples, with their paths and shares' differences.
std::vector<Row> rows_of(const PixelAgainst& p) {
    const SampleTree& ta = p.a.samples[static_cast<std::size_t>(p.sample_a)];
    const SampleTree& tb = p.b.samples[static_cast<std::size_t>(p.sample_b)];
    const bool shown_diverges =
        p.sample_a == p.sample_b && p.why.sample == p.sample_a && p.a.grid == p.b.grid;
    std::vector<Row> rows;
    int divergence_row = -1;
    for (const auto& [i, j] : align_trees(ta, tb)) {
        Row row;
        row.node_a = i, row.node_b = j;
        // The path: the parent's row's path, then R or T.
        const TreeNode& node =
            i >= 0 ? ta[static_cast<std::size_t>(i)] : tb[static_cast<std::size_t>(j)];
        if (node.kind == RayKind::primary) {
            row.path = "P";
        } else {
            // Find the parent row: the row whose node has this one as a child.
            for (std::size_t r = rows.size(); r-- > 0;) {
                const Row& up = rows[r];
                const auto is_child = [&](const SampleTree& t, int parent, int child) {
                    if (parent < 0 || child < 0) return false;
                    const TreeNode& n = t[static_cast<std::size_t>(parent)];
                    return n.child[0] == child || n.child[1] == child;
                };
                if (is_child(ta, up.node_a, i) || is_child(tb, up.node_b, j)) {
                    row.path = up.path + (node.kind == RayKind::reflection ? ".R" : ".T");
                    row.in_subtree = up.in_subtree;
                    break;
                }
            }
        }
        const DVec3 share_a = i >= 0 ? ta[static_cast<std::size_t>(i)].share() : DVec3(0);
        const DVec3 share_b = j >= 0 ? tb[static_cast<std::size_t>(j)].share() : DVec3(0);
        row.delta = share_b - share_a;
        if (shown_diverges && divergence_row < 0 &&
            ((p.why.node_a >= 0 && p.why.node_a == i) ||
             (p.why.node_b >= 0 && p.why.node_b == j))) {
            // depth and cutoff name the child one side cast; primary, secondary and shadow the
            // pair of nodes where the trees part.
            row.diverges = true, row.in_subtree = true;
            divergence_row = static_cast<int>(rows.size());
        }
        rows.push_back(row);
    }
    return rows;
}

std::string node_text(const Scene& scene, const SampleTree& tree, int index) {
    if (index < 0) return "-";
    const TreeNode& n = tree[static_cast<std::size_t>(index)];
    std::string text;
    if (n.object == kNoObject) {
        text = "background";
    } else {
        text = "object " + std::to_string(n.object);
        if (n.object < scene.object_names.size() && !scene.object_names[n.object].empty())
            text.append(" \"").append(scene.object_names[n.object]).append("\"");
        std::string lights;
        for (const Verdict v : n.lights)
            lights.append(lights.empty() ? "" : ",").append(name_of(v));
        if (!lights.empty()) text.append(" [").append(lights).append("]");
    }
    for (std::size_t k = 0; k < 2; ++k)
        if (n.stop[k] != Stop::cast && n.stop[k] != Stop::none)
            text.append(k ? " T:" : " R:").append(name_of(n.stop[k]));
    return text;
}

std::string cause_sentence(const PixelAgainst& p) {
    const Divergence& w = p.why;
    const std::string level = std::to_string(w.level);
    switch (w.cause) {
    case Cause::none:
        return "no difference: the pixel's bytes agree";
    case Cause::sampling:
        return "sampling: A takes " + std::to_string(p.a.grid) + "x" + std::to_string(p.a.grid) +
               " samples, B " + std::to_string(p.b.grid) + "x" + std::to_string(p.b.grid);
    case Cause::depth:
        return "depth: at level " + level + " one side stops at its maximum depth, the other " +
               "casts the ray";
    case Cause::cutoff:
        return "cutoff: at level " + level + " one side stops at the weight cut-off, the other " +
               "casts the ray";
    case Cause::primary:
        return "primary: the primary ray hits another object";
    case Cause::secondary:
        return "secondary: the ray at level " + level + " hits another object";
    case Cause::shadow:
        return "shadow: a shadow verdict differs at level " + level;
    case Cause::precision:
        break;
    }
    return "precision: the trees match node for node; only the numbers differ";
}

std::string sample_name(const PixelTrees& t, int sample) {
    if (t.grid == 1) return "one sample";
    return "sample (" + std::to_string(sample % t.grid) + ", " + std::to_string(sample / t.grid) +
           ") of " + std::to_string(t.grid) + "x" + std::to_string(t.grid);
}

// The difference B − A of the shown samples' colours, split: the subtree where they part, and the
// rest.
std::pair<DVec3, DVec3> split(const std::vector<Row>& rows) {
    DVec3 subtree(0), rest(0);
    for (const Row& row : rows) (row.in_subtree ? subtree : rest) += row.delta;
    return {subtree, rest};
}

} // namespace

std::string against_text(const RenderedSide& a, const RenderedSide& b, const PixelAgainst& p,
                         const std::string& scene_path) {
    const Scene& scene = a.side().scene;
    std::string out = "pixel (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ") of " +
                      scene_path + " (" + std::to_string(scene.camera.width) + "x" +
                      std::to_string(scene.camera.height) + ")\n";
    out += "A: " + a.side().label + " = " + describe_side(a.side()) + "\n   bytes " +
           bytes_text(p.a.bytes) + ", radiance " + rgb_text(p.a.radiance) + "\n";
    out += "B: " + b.side().label + " = " + describe_side(b.side()) + "\n   bytes " +
           bytes_text(p.b.bytes) + ", radiance " + rgb_text(p.b.radiance) + "\n";
    out += "cause: " + cause_sentence(p) + "\n";
    if (p.why.cause == Cause::none) return out;
    out += "\nshown: A's " + sample_name(p.a, p.sample_a) + ", B's " +
           sample_name(p.b, p.sample_b) + "; each node's share of the sample's colour is " +
           "weight x (ambient + emission + diffuse + specular)\n\n";
    const std::vector<Row> rows = rows_of(p);
    const SampleTree& ta = p.a.samples[static_cast<std::size_t>(p.sample_a)];
    const SampleTree& tb = p.b.samples[static_cast<std::size_t>(p.sample_b)];
    char line[512];
    std::snprintf(line, sizeof line, "  %-12s %-38s %-38s %s\n", "node", "A", "B", "share B - A");
    out += line;
    for (const Row& row : rows) {
        std::snprintf(line, sizeof line, "%s %-12s %-38s %-38s %s%s\n", row.diverges ? ">" : " ",
                      row.path.c_str(), node_text(scene, ta, row.node_a).c_str(),
                      node_text(scene, tb, row.node_b).c_str(), rgb_text(row.delta).c_str(),
                      row.diverges ? ("  <- " + std::string(name_of(p.why.cause))).c_str() : "");
        out += line;
    }
    const auto [subtree, rest] = split(rows);
    out += "\nthe sample's colour, B - A = " + rgb_text(subtree + rest) + ": " + rgb_text(subtree) +
           " from the subtree where the trees part, " + rgb_text(rest) + " from the rest\n";
    return out;
}

std::string against_json(const RenderedSide& a, const RenderedSide& b, const PixelAgainst& p,
                         const std::string& scene_path) {
    using json = nlohmann::ordered_json;
    const auto vec = [](DVec3 v) { return json::array({v.x, v.y, v.z}); };
    const auto side = [&](const RenderedSide& s, const PixelTrees& t, int sample) {
        return json{{"flags", s.side().label},
                    {"settings", describe_side(s.side())},
                    {"grid", t.grid},
                    {"sample",
                     t.grid == 1 ? json(nullptr) : json::array({sample % t.grid, sample / t.grid})},
                    {"bytes", t.bytes},
                    {"radiance", vec(t.radiance)}};
    };
    const auto node = [&](const SampleTree& tree, int index) -> json {
        if (index < 0) return nullptr;
        const TreeNode& n = tree[static_cast<std::size_t>(index)];
        json lights = json::array();
        for (const Verdict v : n.lights) lights.push_back(std::string(name_of(v)));
        json stops = json::object();
        for (std::size_t k = 0; k < 2; ++k)
            if (n.stop[k] != Stop::cast && n.stop[k] != Stop::none)
                stops[k ? "transmission" : "reflection"] = std::string(name_of(n.stop[k]));
        return {{"kind", std::string(name_of(n.kind))},
                {"depth", n.depth},
                {"object", n.object == kNoObject ? json(nullptr) : json(n.object)},
                {"lights", lights},
                {"not_cast", stops},
                {"weight", n.weight},
                {"colour", vec(n.colour)},
                {"share", vec(n.share())}};
    };
    json out = {{"schema", "glint-explain-against/1"},
                {"scene", scene_path},
                {"pixel", {p.x, p.y}},
                {"a", side(a, p.a, p.sample_a)},
                {"b", side(b, p.b, p.sample_b)},
                {"differs", p.why.cause != Cause::none},
                {"cause", p.why.cause == Cause::none ? json(nullptr)
                                                     : json(std::string(name_of(p.why.cause)))},
                {"level", p.why.level}};
    if (p.why.cause == Cause::none) return out.dump(2) + "\n";
    const std::vector<Row> rows = rows_of(p);
    const SampleTree& ta = p.a.samples[static_cast<std::size_t>(p.sample_a)];
    const SampleTree& tb = p.b.samples[static_cast<std::size_t>(p.sample_b)];
    json nodes = json::array();
    for (const Row& row : rows)
        nodes.push_back({{"path", row.path},
                         {"a", node(ta, row.node_a)},
                         {"b", node(tb, row.node_b)},
                         {"share_difference", vec(row.delta)},
                         {"first_divergence", row.diverges}});
    const auto [subtree, rest] = split(rows);
    out["nodes"] = nodes;
    out["split"] = {{"difference", vec(subtree + rest)},
                    {"diverging_subtree", vec(subtree)},
                    {"rest", vec(rest)}};
    return out.dump(2) + "\n";
}

} // namespace glint
