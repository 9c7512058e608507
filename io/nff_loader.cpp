// NFF, the Neutral File Format of Eric Haines' Standard Procedural Databases (docs/SCENES.md,
// "NFF scenes"). Read as whitespace-separated tokens, since the generators put on one line what
// the format describes on several; every error names the file and the line of the token at fault.
#include "io/error.h"
#include "io/nff_loader.h"
#include "io/polygon.h"
#include "io/read_text.h"
#include "io/scene_check.h"
#include "trace/shapes/table.h"

#include <cmath>
#include <map>
#include <numbers>
#include <sstream>
#include <string_view>
#include <tuple>

namespace glint {
namespace {

// SPD's rendering rules (its Readme): a ray tree at most 5 deep counting the eye ray, that is 4
// reflections, and no adaptive cut-off.
constexpr int kSpdMaxDepth = 4;
// Vertices of one `p` or `pp` entry: far beyond any real file (the gears have 144).
constexpr int kMaxPolygonVertices = 1 << 16;

struct Token {
    std::string_view text;
    int line = 0;
};

class NffReader {
  public:
    NffReader(const std::string& text, std::string name) : text_(text), name_(std::move(name)) {}

    Scene read() {
        scene_.materials.push_back(Material{});
        scene_.material_names.push_back("default");
        scene_.render.max_depth = kSpdMaxDepth;
        scene_.render.min_reflectivity = 0.0f;
        bool viewed = false;
        while (const std::optional<Token> t = next()) {
            const std::string_view word = t->text;
            if (word == "v") {
                if (viewed) fail(t->line, "a second view ('v'); NFF has one");
                view(*t);
                viewed = true;
            } else if (word == "b") {
                scene_.background = colour(*t, "background");
                background_line_ = t->line;
            } else if (word == "l") {
                light(*t);
            } else if (word == "f") {
                fill(*t);
            } else if (word == "c") {
                cone(*t);
            } else if (word == "s") {
                sphere(*t);
            } else if (word == "p" || word == "pp") {
                polygon(*t, word == "pp");
            } else {
                fail(t->line, "unknown entity '" + printable(word, 40) +
                                  "' (NFF has v, b, l, f, c, s, p, pp)");
            }
        }
        if (!viewed) fail(1, "no view: an NFF file needs a 'v' entry (from, at, up, angle, ...)");
        flush_meshes();
        // NFF leaves light intensity open; SPD's renderers share one unit among the lights.
        // 1/√n keeps scenes with many lights (tree has 7) from going dark, as 1/n would.
        const float share =
            1.0f / std::sqrt(static_cast<float>(std::max<std::size_t>(1, scene_.lights.size())));
        for (PointLight& l : scene_.lights)
            if (l.color == glm::vec3(-1.0f)) l.color = glm::vec3(share);
        if (degenerate_polygons_ > 0)
            scene_.notes.push_back(std::to_string(degenerate_polygons_) +
                                   " polygon(s) of zero area left out");
        check_scene(scene_, [&](const std::string& path) { return place_of(path); });
        return std::move(scene_);
    }

  private:
    // A part of the scene model (io/scene_check.h) as the line of the entity that gave it and
    // the entity's field in NFF's words.
    std::string place_of(const std::string& path) const {
        const auto part = [&](std::size_t i) {
            std::size_t at = 0;
            for (std::size_t k = 0; k < i && at != std::string::npos; ++k) {
                at = path.find('/', at);
                if (at != std::string::npos) ++at;
            }
            if (at == std::string::npos) return std::string();
            return path.substr(at, path.find('/', at) - at);
        };
        const auto index = [&] { return static_cast<std::size_t>(std::stoul(part(1))); };
        const std::string top = part(0);
        int line = 1;
        std::string what = path;
        const auto field = [&](const std::string& name) { return part(2) == name; };
        if (top == "camera") {
            const std::string f = part(1);
            line = f == "eye" ? view_.from : f == "up" ? view_.up : f == "fov_y" ? view_.angle
                 : f == "width" || f == "height" ? view_.resolution : view_.at;
            what = f == "eye" ? "v's from" : f == "look_at" ? "v's at" : f == "up" ? "v's up"
                 : f == "fov_y" ? "v's angle" : f == "width" || f == "height" ? "v's resolution"
                 : "v's from and at";
        } else if (top == "background") {
            line = background_line_, what = "b's background";
        } else if (top == "lights") {
            line = light_lines_.empty() ? 1 : part(1).empty() ? light_lines_.back()
                                                              : light_lines_.at(index());
            what = field("color") ? "l's colour" : part(1).empty() ? "l" : "l's position";
        } else if (top == "materials") {
            line = material_lines_.at(index());
            what = field("diffuse") || field("ambient") ? "f's colour × Kd"
                 : field("specular") || field("reflectivity") ? "f's Ks"
                 : field("shininess") ? "f's shine" : field("transmission") ? "f's T"
                 : field("ior") ? "f's index of refraction" : "f";
        } else if (top == "objects") {
            line = object_lines_.at(index());
            what = field("top_radius") ? "c's radii" : "the object's placement";
        } else if (top == "meshes") {
            line = mesh_lines_.at(index()), what = "the polygons' vertices";
        }
        return name_ + ":" + std::to_string(line) + ": " + what;
    }

    [[noreturn]] void fail(int line, const std::string& message) const {
        throw SceneError(name_ + ":" + std::to_string(line) + ": " + message);
    }

    // White space within a line: C's isspace less the newline, spelt out (isspace is a call per
    // byte, and follows the locale a host program such as Python may set).
    static bool blank(char c) {
        return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
    }

    // The next token, skipping white space and # comments; nothing at the end of the file.
    std::optional<Token> next() {
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (c == '\n') {
                ++line_, ++pos_;
            } else if (blank(c)) {
                ++pos_;
            } else if (c == '#') {
                while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
            } else {
                const std::size_t start = pos_;
                while (pos_ < text_.size() && !blank(text_[pos_]) && text_[pos_] != '\n') ++pos_;
                last_line_ = line_;
                return Token{std::string_view(text_).substr(start, pos_ - start), line_};
            }
        }
        return std::nullopt;
    }

    // Whether the next token starts like a number (optional light colours).
    bool number_follows() {
        const std::size_t pos = pos_;
        const int line = line_, last_line = last_line_;
        const std::optional<Token> t = next();
        pos_ = pos, line_ = line, last_line_ = last_line;
        if (!t) return false;
        const char c = t->text[0];
        return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
    }

    // The next token as a finite number; `what` names it for messages, `entity` is the keyword.
    double number(const Token& entity, const char* what) {
        const std::optional<Token> t = next();
        if (!t)
            fail(last_line_, "the file ends inside '" + printable(entity.text) + "' (line " +
                                 std::to_string(entity.line) + "), before its " + what);
        double value = 0;
        if (!parse_number(t->text, value))
            fail(t->line, "expected a number for " + printable(entity.text) + "'s " + what +
                              ", got '" + printable(t->text, 40) + "'");
        if (std::abs(value) > kMaxCoordinate)
            fail(t->line,
                 printable(entity.text) + "'s " + what + " is beyond 1e15, too large for float");
        return value;
    }

    double number_in(const Token& entity, const char* what, double lo, double hi) {
        const double v = number(entity, what);
        if (v < lo || v > hi) {
            std::ostringstream message;
            message << entity.text << "'s " << what << " must be between " << lo << " and " << hi
                    << ", got " << v;
            fail(last_line_, message.str());
        }
        return v;
    }

    int integer_in(const Token& entity, const char* what, int lo, int hi) {
        const double v = number_in(entity, what, lo, hi);
        if (v != std::floor(v))
            fail(last_line_, printable(entity.text) + "'s " + what + " must be a whole number");
        return static_cast<int>(v);
    }

    DVec3 vec3(const Token& entity, const char* what) {
        DVec3 v;
        for (int i = 0; i < 3; ++i) v[i] = number(entity, what);
        return v;
    }

    // Its range is the scene check's (io/scene_check.h); numbers are within ±1e15 here.
    glm::vec3 colour(const Token& entity, const char* what) {
        return glm::vec3(vec3(entity, what));
    }

    // Expects the keyword `word` of the view block next.
    Token keyword(const Token& view, const char* word) {
        const std::optional<Token> t = next();
        if (!t || t->text != word)
            fail(last_line_, std::string("the view ('v', line ") + std::to_string(view.line) +
                                 ") needs '" + word + "' here" +
                                 (t ? ", got '" + printable(t->text, 40) + "'"
                                    : ", but the file ends"));
        return *t;
    }

    void view(const Token& v) {
        Camera& c = scene_.camera;
        const Token from = keyword(v, "from");
        c.eye = vec3(from, "position");
        const Token at = keyword(v, "at");
        c.look_at = vec3(at, "position");
        const Token up = keyword(v, "up");
        c.up = vec3(up, "direction");
        const Token angle_token = keyword(v, "angle");
        const double angle = number(angle_token, "field of view");
        const Token hither = keyword(v, "hither");
        number(hither, "distance"); // the near plane of z-buffers; a ray tracer has none
        const Token resolution = keyword(v, "resolution");
        c.width = integer_in(resolution, "width", -1000000000, 1000000000);
        c.height = integer_in(resolution, "height", -1000000000, 1000000000);
        view_ = {from.line, at.line, up.line, angle_token.line, resolution.line};
        // NFF's angle spans the centres of the outermost pixels; glint's fov_y spans the image's
        // edges, half a pixel further on each side.
        const double h = std::tan(angle * std::numbers::pi / 360.0);
        c.fov_y = c.height > 1 ? 360.0 / std::numbers::pi * std::atan(h * c.height / (c.height - 1))
                               : angle;
    }

    void light(const Token& l) {
        light_lines_.push_back(l.line);
        PointLight light;
        light.position = vec3(l, "position");
        if (number_follows()) {
            light.color = colour(l, "colour");
        } else {
            light.color = glm::vec3(-1.0f); // the share of a unit total, once all are counted
        }
        scene_.lights.push_back(light);
    }

    void fill(const Token& f) {
        // Ranges are the scene check's (io/scene_check.h), on the material they make.
        const glm::vec3 rgb = colour(f, "colour");
        const double kd = number(f, "Kd");
        const double ks = number(f, "Ks");
        const double shine = number(f, "shine");
        const double transmission = number(f, "T");
        const double ior = number(f, "index of refraction");
        Material m;
        m.transmission = static_cast<float>(transmission);
        // Only a transmitting material's index matters (and must then be usable).
        m.ior = transmission > 0 ? static_cast<float>(ior) : 1.5f;
        m.diffuse = rgb * static_cast<float>(kd);
        m.ambient = m.diffuse; // the scene's ambient light is 0: only glint's default matters
        m.specular = glm::vec3(static_cast<float>(ks));
        m.shininess = static_cast<float>(shine);
        m.reflectivity = static_cast<float>(ks); // as SPD's renderers: Ks is also the mirror
        const auto key = std::make_tuple(m.diffuse.x, m.diffuse.y, m.diffuse.z, m.specular.x,
                                         m.shininess, m.transmission, m.ior);
        const auto [it, added] =
            materials_.emplace(key, static_cast<std::uint32_t>(scene_.materials.size()));
        if (added) {
            scene_.materials.push_back(m);
            scene_.material_names.push_back("nff-" + std::to_string(f.line));
            material_lines_.push_back(f.line);
        }
        if (it->second != material_) flush_meshes();
        material_ = it->second;
    }

    void add(SceneObject o, int line) {
        o.material = material_;
        scene_.objects.push_back(o);
        object_lines_.push_back(line);
    }

    void sphere(const Token& s) {
        const DVec3 centre = vec3(s, "centre");
        const double r = std::abs(number(s, "radius"));
        SceneObject o;
        o.shape = ShapeKind::sphere;
        o.transform = translation_matrix(centre) * scale_matrix(DVec3(r)); // r = 0: singular
        add(o, s.line);
    }

    // An open truncated cone from base (radius r0) to apex (radius r1): glint's unit cone, radius
    // 1 at y = 0 and top_radius at y = 1, scaled by r0 across and by the length along y, turned
    // onto the axis and moved to the base. Negative radii (seen from inside) count as positive:
    // glint's surfaces are two-sided.
    void cone(const Token& c) {
        DVec3 base = vec3(c, "base");
        double r0 = std::abs(number(c, "base radius"));
        DVec3 apex = vec3(c, "apex");
        double r1 = std::abs(number(c, "apex radius"));
        if (r0 == 0 && r1 == 0) fail(last_line_, "a cone needs a non-zero radius at one end");
        if (base == apex) fail(last_line_, "a cone's base and apex must differ");
        if (r0 == 0) std::swap(base, apex), std::swap(r0, r1);
        const DVec3 axis = apex - base;
        const double length = glm::length(axis);
        const DVec3 y = axis / length;
        // Any unit x perpendicular to the axis: the cone is round.
        const DVec3 helper = std::abs(y.x) < 0.9 ? DVec3(1, 0, 0) : DVec3(0, 1, 0);
        const DVec3 x = glm::normalize(glm::cross(helper, y));
        const DVec3 z = glm::cross(x, y);
        DMat4 m(1.0);
        m[0] = glm::dvec4(x * r0, 0.0);
        m[1] = glm::dvec4(axis, 0.0);
        m[2] = glm::dvec4(z * r0, 0.0);
        m[3] = glm::dvec4(base, 1.0);
        SceneObject o;
        o.shape = r0 == r1 ? ShapeKind::cylinder : ShapeKind::cone;
        o.top_radius = o.shape == ShapeKind::cone ? static_cast<float>(r1 / r0) : 0.0f;
        o.open = true;
        o.transform = m;
        add(o, c.line);
    }

    // A polygon or patch, triangulated into the mesh of the current material run: a file's
    // thousands of polygons become a few meshes, each with its own BVH under the top level.
    void polygon(const Token& p, bool patch) {
        const int n = integer_in(p, "vertex count", 3, kMaxPolygonVertices);
        std::vector<glm::dvec3> points(static_cast<std::size_t>(n));
        std::vector<glm::dvec3> normals(patch ? points.size() : 0);
        for (int i = 0; i < n; ++i) {
            points[i] = vec3(p, "vertex");
            if (patch) normals[i] = vec3(p, "vertex normal");
        }
        const std::vector<glm::uvec3> triangles = triangulate_polygon(points);
        if (triangles.empty()) {
            ++degenerate_polygons_;
            return;
        }
        TriangleMesh& mesh = patch ? smooth_ : flat_;
        if (mesh.vertices.size() + points.size() > kMaxMeshVertices) flush_meshes();
        if (mesh.triangles.empty()) (patch ? smooth_line_ : flat_line_) = p.line;
        const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
        for (const glm::dvec3& q : points) mesh.vertices.push_back(glm::vec3(q));
        if (patch) {
            // A zero vertex normal gets the polygon's own.
            const glm::dvec3 facet = glm::normalize(newell_normal(points));
            for (const glm::dvec3& nv : normals)
                mesh.normals.push_back(glm::vec3(glm::length(nv) > 0 ? glm::normalize(nv) : facet));
        }
        for (const glm::uvec3& t : triangles) mesh.triangles.push_back(t + first);
    }

    void flush_meshes() {
        for (TriangleMesh* mesh : {&flat_, &smooth_}) {
            if (mesh->triangles.empty()) continue;
            SceneObject o;
            o.shape = ShapeKind::mesh;
            o.material = material_;
            o.mesh = static_cast<std::uint32_t>(scene_.meshes.size());
            scene_.meshes.push_back(std::move(*mesh));
            const int line = mesh == &flat_ ? flat_line_ : smooth_line_;
            mesh_lines_.push_back(line);
            add(o, line);
            *mesh = TriangleMesh{};
        }
    }

    const std::string& text_;
    std::string name_;
    std::size_t pos_ = 0;
    int line_ = 1;
    int last_line_ = 1; // of the last token read
    Scene scene_;
    std::map<std::tuple<float, float, float, float, float, float, float>, std::uint32_t> materials_;
    std::uint32_t material_ = 0;
    std::size_t degenerate_polygons_ = 0;
    TriangleMesh flat_, smooth_; // the current material's polygons and patches
    // Where the scene's parts came from (place_of): the lines of the view's keywords, of b, of
    // each light, material (f), object and mesh (its first polygon).
    struct ViewLines {
        int from = 1, at = 1, up = 1, angle = 1, resolution = 1;
    } view_;
    int background_line_ = 1, flat_line_ = 1, smooth_line_ = 1;
    std::vector<int> light_lines_, material_lines_{1}, object_lines_, mesh_lines_;
};

} // namespace

Scene parse_nff(const std::string& text, const std::string& name) {
    return NffReader(text, name).read();
}

} // namespace glint
