#include "frame/explain.h"

#include "frame/record_json.h"
#include "frame/text_format.h"
#include "io/error.h"
#include "trace/frame_records.h"
#include "trace/shapes/table.h"
#include "trace/transform.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>

namespace glint {

PixelExplanation explain_frame_pixel(const World& world, const FrameSettings& settings, int x,
                                     int y, int a, int b) {
    const RenderSettings& render = world.settings();
    Frame frame;
    bool refined = false;
    if (render.samples > 1 && render.antialias == Antialias::adaptive) {
        frame = render_frame(world, settings);
        refined = frame.result.refined[static_cast<std::size_t>(y) * world.camera().width() + x];
    } else {
        draw_item_buffers(world, settings, frame);
    }
    return explain_pixel(world, primary_source(frame, settings.resolve), x, y, a, b, refined);
}

namespace {

const char* transform_name(TransformClass kind) {
    switch (kind) {
    case TransformClass::identity:
        return "identity";
    case TransformClass::translation:
        return "translation";
    case TransformClass::uniform_scale:
        return "uniform scale";
    case TransformClass::general:
        break;
    }
    return "general affine";
}

const char* why_name(OmittedRay::Why why) {
    switch (why) {
    case OmittedRay::Why::max_depth:
        return "max_depth";
    case OmittedRay::Why::min_weight:
        return "min_weight";
    case OmittedRay::Why::tree_budget:
        break;
    }
    return "tree_budget";
}

// What the text and the JSON both say about a scene's object and a light's shadow.
struct Facts {
    const Scene& scene;
    const World& world;
    DVec3 eye;

    DVec3 to_scene(Vec3 p) const { return DVec3(p) + eye; } // the tracer's world is eye-relative
    std::string object(std::uint32_t index) const {
        std::string text = "object " + std::to_string(index);
        if (!name(index).empty()) text += " \"" + name(index) + "\"";
        return text;
    }
    std::string name(std::uint32_t index) const {
        return index < scene.object_names.size() ? scene.object_names[index] : std::string();
    }
    const char* shape(std::uint32_t index) const {
        return name_of(scene.objects[index].shape).data();
    }
    const char* transform(std::uint32_t index) const {
        return transform_name(make_transform(scene.objects[index].transform).kind);
    }
    static const char* shadow(const LightTerm& term) {
        if (!term.in_front()) return "behind";
        if (term.through == 0) return "blocked";
        return term.through == 1 ? "lit" : "glass";
    }
};

std::string vec(DVec3 v, const char* format = "%.6g") {
    std::string out = "(";
    for (int i = 0; i < 3; ++i) {
        char number[32];
        std::snprintf(number, sizeof number, format, v[i]);
        out += (i ? ", " : "") + std::string(number);
    }
    return out + ")";
}
std::string num(double x, const char* format = "%.6g");
std::string vec2(glm::vec2 v) {
    return "(" + num(v.x) + ", " + num(v.y) + ")";
}
std::string colour(Vec3 c) {
    return vec(DVec3(c), "%.4f");
}
std::string num(double x, const char* format) {
    char text[32];
    std::snprintf(text, sizeof text, format, x);
    return text;
}
std::string counts(const RayCounts& r) {
    return std::to_string(r.primary) + " primary, " + std::to_string(r.shadow) + " shadow, " +
           std::to_string(r.reflection) + " reflection, " + std::to_string(r.transmission) +
           " transmission";
}

// One ray's paragraph, in one body: the lecture's steps in their order, ray → hit → object
// space → normals → lights → children → R_p.
void write_ray(std::string& out, const Facts& facts, const PixelExplanation& e, std::size_t i) {
    const RecordedRay& r = e.rays[i];
    const std::string indent(static_cast<std::size_t>(2 * r.depth), ' ');
    const auto line = [&](const std::string& text) { out += indent + text + "\n"; };
    std::string head = "ray " + std::to_string(i) + ": " + std::string(name_of(r.kind));
    if (r.parent >= 0)
        head += " of ray " + std::to_string(r.parent) + " (depth " + std::to_string(r.depth) +
                ", weight " + num(r.factor) + ", path weight " + num(r.weight) + ")";
    line(head);
    line("  o = " + vec(facts.to_scene(r.ray.origin)) + ", d = " + vec(DVec3(r.ray.direction)));
    for (const CutThrough& c : e.cut_through[i])
        line("  passes through " + facts.object(c.object) + " at t = " + num(c.t) +
             ": cut out there (alpha " + num(c.alpha) + " < cut-off " + num(c.cutoff) + ")");
    if (!r.hit.found()) {
        if (const Environment* environment = facts.world.environment()) {
            line("  hits nothing: leaves the scene into the environment (" +
                 printable(environment->name) + ")");
            line("  R_" + std::to_string(i) + " = environment(d) = " + colour(r.colour));
        } else {
            line("  hits nothing: the background");
            line("  R_" + std::to_string(i) + " = background = " + colour(r.colour));
        }
        return;
    }
    const std::uint32_t o = r.hit.object;
    const Ray& local = e.object_rays[i];
    line("  hits " + facts.object(o) + " (" + facts.shape(o) + ", M " + facts.transform(o) +
         ") at t = " + num(r.hit.t));
    line("  object space: M⁻¹o = " + vec(DVec3(local.origin)) +
         " (w = 1), M⁻¹d = " + vec(DVec3(local.direction)) + " (w = 0)");
    line("  hit point: p' = M⁻¹o + t·M⁻¹d = " + vec(DVec3(r.surface.object_point)) +
         ", p = " + vec(facts.to_scene(r.surface.position)));
    line("  normal: n' = " + vec(DVec3(r.surface.object_normal)) + ", n = normalize(M⁻ᵀn') = " +
         vec(DVec3(r.surface.normal)) + (r.surface.entering ? "" : " (flipped: seen from inside)"));
    if (r.surface.shading != r.surface.normal)
        line("  shading normal (smooth mesh): " + vec(DVec3(r.surface.shading)));
    if (r.odd_cell) line("  checker: an odd cell, its colours in place of the material's");
    if (r.texel) {
        const TextureImage& image = *facts.world.material(o).texture->image;
        const TexelSample& t = *r.texel;
        line("  texture: " + printable(image.name) + " (" + std::to_string(image.width) + " × " +
             std::to_string(image.height) + ") at uv " +
             vec2(t.texel / glm::vec2(image.width, image.height)) + ": texel position " +
             vec2(t.texel) + ", nearest texel [" + std::to_string(t.nearest.x) + ", " +
             std::to_string(t.nearest.y) + "], bilinear colour " + colour(Vec3(t.colour)) +
             " × the diffuse and ambient colours");
    }
    line("  ambient  k_a·I_a = " + colour(r.ambient));
    const bool emits = r.emission != Vec3(0);
    if (emits) line("  emission E = " + colour(r.emission) + " (unshadowed)");
    Vec3 diffuse(0), specular(0);
    for (std::size_t k = 0; k < r.lights.size(); ++k) {
        const LightTerm& term = r.lights[k];
        const Light& light = facts.world.lights()[term.light];
        std::string verdict = Facts::shadow(term);
        if (verdict == "blocked" && e.blockers[i][k] != kNoObject)
            verdict += " by " + facts.object(e.blockers[i][k]);
        if (verdict == "glass")
            verdict = "through glass, " + std::to_string(term.shadow_rays) +
                      " segments, transmission " + num(term.through);
        std::string text = "  light " + std::to_string(term.light) + " at " +
                           vec(facts.to_scene(light.position)) + ": n·l = " + num(term.n_dot_l);
        if (!term.in_front()) {
            line(text + ", behind the surface: no shadow ray");
            continue;
        }
        line(text + "; shadow ray: " + verdict);
        if (term.through == 0) continue;
        line("    diffuse  I·k_d(n·l) = " + colour(term.diffuse));
        line("    specular I·k_s(r·v)^n = " + colour(term.specular));
        diffuse += term.diffuse, specular += term.specular;
    }
    // R_p = ambient + diffuse + specular + k·R_q for each child q, then the numbers.
    const std::string p = "R_" + std::to_string(i);
    std::string terms = emits ? "ambient + emission + diffuse + specular"
                              : "ambient + diffuse + specular";
    std::string numbers = colour(r.ambient) + " + " + (emits ? colour(r.emission) + " + " : "") +
                          colour(diffuse) + " + " + colour(specular);
    for (const int child : r.children) {
        const RecordedRay& c = e.rays[static_cast<std::size_t>(child)];
        line("  " + std::string(name_of(c.kind)) + ": k = " + num(c.factor) + " → ray " +
             std::to_string(child));
        terms += " + " + num(c.factor) + "·R_" + std::to_string(child);
        numbers += " + " + num(c.factor) + "·" + colour(c.colour);
    }
    for (const OmittedRay& omitted : r.omitted)
        line("  " + std::string(name_of(omitted.kind)) + ": not cast (" + why_name(omitted.why) +
             "; path weight " + num(omitted.weight) + ")");
    const std::string pad(p.size() + 2, ' ');
    line("  " + p + " = " + terms);
    line("  " + pad + " = " + numbers);
    line("  " + pad + " = " + colour(r.colour));
}

// Nine significant digits: every float the tracer computed round-trips, without the
// double expansion's tail (0.1f is 0.100000001, not 0.10000000149011612).
double real(double v) {
    return std::strtod(num(v, "%.9g").c_str(), nullptr);
}
nlohmann::ordered_json json_vec(DVec3 v) {
    return {real(v.x), real(v.y), real(v.z)};
}

} // namespace

std::string explanation_text(const Scene& scene, const World& world, const PixelExplanation& e,
                             const std::string& what) {
    const Facts facts{scene, world, scene.camera.eye};
    std::string out = "glint explain: " + what + "\n";
    out += "pixel (" + std::to_string(e.x) + ", " + std::to_string(e.y) + ")";
    if (e.n > 1)
        out += ", sample (" + std::to_string(e.a) + ", " + std::to_string(e.b) + ") of its " +
               std::to_string(e.n) + "x" + std::to_string(e.n) + " grid";
    if (e.n > 1 && !e.averaged)
        out += " (adaptive antialiasing left this pixel unrefined: the render traced this centre "
               "sample alone)";
    out += "\n";
    if (const auto& item = e.item_buffer) {
        out += item->first_pass ? "item buffer (the pixel centre, in the first pass; the grid is "
                                  "traced by ray): "
                                : "item buffer: ";
        out += item->id == 0
                   ? "nothing drawn"
                   : "id " + std::to_string(item->id) + " = " + facts.object(item->id - 1) +
                         ", view depth " + num(item->view_depth);
        out += "; resolve: " + std::string(item->outcome()) +
               (item->resolve.edges ? " (on an id edge: every object in front tested)" : "") +
               ", " + std::to_string(item->resolve.tests) + " other objects intersected\n";
    }
    out += "\n";
    for (std::size_t i = 0; i < e.rays.size(); ++i) write_ray(out, facts, e, i);
    out += "\nsample: R_0 = " + colour(e.rays.front().colour) + " → bytes " +
           bytes_text(e.sample_bytes) + "\n";
    out += "pixel: ";
    out += e.averaged ? "the mean of its " + std::to_string(e.n * e.n) +
                            " samples, each clamped, " + colour(e.pixel_colour)
                      : std::string("this sample");
    out += " → bytes " + bytes_text(e.pixel_bytes) + "\n";
    out += "rays: this tree " + counts(e.tree_rays);
    if (e.averaged) out += "; the pixel " + counts(e.pixel_rays);
    return out + "\n";
}

std::string explanation_json(const Scene& scene, const World& world, const PixelExplanation& e,
                             const std::string& scene_path, const std::string& settings) {
    using json = nlohmann::ordered_json;
    const Facts facts{scene, world, scene.camera.eye};
    json rays = json::array();
    for (std::size_t i = 0; i < e.rays.size(); ++i) {
        const RecordedRay& r = e.rays[i];
        json ray = {{"index", i},
                    {"kind", name_of(r.kind)},
                    {"parent", r.parent < 0 ? json(nullptr) : json(r.parent)},
                    {"depth", r.depth},
                    {"factor", real(r.factor)},
                    {"weight", real(r.weight)},
                    {"origin", json_vec(facts.to_scene(r.ray.origin))},
                    {"direction", json_vec(DVec3(r.ray.direction))},
                    {"hit", nullptr}};
        if (!e.cut_through[i].empty()) {
            json passed = json::array();
            for (const CutThrough& c : e.cut_through[i])
                passed.push_back({{"object", c.object},
                                  {"t", real(c.t)},
                                  {"alpha", real(c.alpha)},
                                  {"cutoff", real(c.cutoff)}});
            ray["cut_through"] = std::move(passed);
        }
        if (!r.hit.found()) // what the ray that left the scene returned
            ray[world.environment() ? "environment" : "background"] = json_vec(DVec3(r.colour));
        if (r.hit.found()) {
            const std::uint32_t o = r.hit.object;
            const Ray& local = e.object_rays[i];
            ray["hit"] = {{"object", o},
                          {"name", facts.name(o)},
                          {"shape", facts.shape(o)},
                          {"transform", facts.transform(o)},
                          {"t", real(r.hit.t)},
                          {"object_origin", json_vec(DVec3(local.origin))},
                          {"object_direction", json_vec(DVec3(local.direction))},
                          {"object_point", json_vec(DVec3(r.surface.object_point))},
                          {"point", json_vec(facts.to_scene(r.surface.position))},
                          {"object_normal", json_vec(DVec3(r.surface.object_normal))},
                          {"normal", json_vec(DVec3(r.surface.normal))},
                          {"shading_normal", json_vec(DVec3(r.surface.shading))},
                          {"entering", r.surface.entering},
                          {"checker_odd", r.odd_cell}};
            if (r.texel) {
                const TextureImage& image = *world.material(o).texture->image;
                ray["hit"]["texture"] = {
                    {"image", printable(image.name)},
                    {"size", {image.width, image.height}},
                    {"texel", {r.texel->texel.x, r.texel->texel.y}},
                    {"nearest", {r.texel->nearest.x, r.texel->nearest.y}},
                    {"colour", json_vec(DVec3(Vec3(r.texel->colour)))}};
            }
            ray["ambient"] = json_vec(DVec3(r.ambient));
            ray["emission"] = json_vec(DVec3(r.emission));
            json lights = json::array();
            for (std::size_t k = 0; k < r.lights.size(); ++k) {
                const LightTerm& term = r.lights[k];
                const std::uint32_t blocker = e.blockers[i][k];
                lights.push_back(
                    {{"light", term.light},
                     {"position", json_vec(facts.to_scene(world.lights()[term.light].position))},
                     {"n_dot_l", real(term.n_dot_l)},
                     {"shadow", Facts::shadow(term)},
                     {"through", real(term.through)},
                     {"shadow_rays", term.shadow_rays},
                     {"blocker", blocker == kNoObject ? json(nullptr) : json(blocker)},
                     {"diffuse", json_vec(DVec3(term.diffuse))},
                     {"specular", json_vec(DVec3(term.specular))}});
            }
            ray["lights"] = std::move(lights);
        }
        json children = json::array();
        for (const int child : r.children)
            children.push_back({{"ray", child},
                                {"kind", name_of(e.rays[static_cast<std::size_t>(child)].kind)},
                                {"factor", real(e.rays[static_cast<std::size_t>(child)].factor)}});
        ray["children"] = std::move(children);
        json omitted = json::array();
        for (const OmittedRay& o : r.omitted)
            omitted.push_back(
                {{"kind", name_of(o.kind)}, {"weight", real(o.weight)}, {"why", why_name(o.why)}});
        ray["omitted"] = std::move(omitted);
        ray["colour"] = json_vec(DVec3(r.colour));
        rays.push_back(std::move(ray));
    }
    json out = {{"schema", "glint-explain/1"},
                {"scene", scene_path},
                {"settings", settings},
                {"width", scene.camera.width},
                {"height", scene.camera.height},
                {"pixel", {e.x, e.y}},
                {"samples", e.n},
                {"sample", {e.a, e.b}},
                {"item_buffer", nullptr}};
    if (const auto& item = e.item_buffer)
        out["item_buffer"] = {{"id", item->id},
                              {"object", item->id == 0 ? json(nullptr) : json(item->id - 1)},
                              {"view_depth", real(item->view_depth)},
                              {"outcome", item->outcome()},
                              {"edge", item->resolve.edges > 0},
                              {"tests", item->resolve.tests},
                              {"first_pass", item->first_pass}};
    out["rays"] = std::move(rays);
    out["sample_colour"] = json_vec(DVec3(e.rays.front().colour));
    out["sample_bytes"] = e.sample_bytes;
    out["averaged"] = e.averaged;
    out["pixel_colour"] = json_vec(DVec3(e.pixel_colour));
    out["pixel_bytes"] = e.pixel_bytes;
    out["tree_rays"] = record_json(e.tree_rays);
    out["pixel_rays"] = record_json(e.pixel_rays);
    return out.dump(2) + "\n";
}

} // namespace glint
