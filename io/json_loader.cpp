#include "io/json_loader.h"

#include "io/environment_file.h"
#include "io/read_text.h"

#include "io/obj_loader.h"
#include "io/scene_check.h"
#include "trace/shapes/table.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <map>
#include <sstream>
#include <tuple>

namespace glint {
namespace {

using nlohmann::json;

// A JSON value and its JSON pointer (RFC 6901), for messages.
struct Node {
    const json& value;
    std::string path;

    Node operator[](std::size_t index) const {
        return {value[index], path + "/" + std::to_string(index)};
    }
    Node child(const std::string& key) const {
        std::string escaped;
        for (char c : key) escaped += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
        return {value.at(key), path + "/" + escaped};
    }
};

std::string type_name(const json& v) {
    if (v.is_number()) return "a number";
    if (v.is_string()) return "a string";
    if (v.is_array()) return "an array";
    if (v.is_object()) return "an object";
    if (v.is_boolean()) return "a boolean";
    return "null";
}

template <class Words> std::string join(const Words& words) {
    std::string out;
    for (std::string_view w : words) out += (out.empty() ? "" : ", ") + std::string(w);
    return out;
}

// The shapes that take an optional key, for its error message: "cylinders and cones".
std::string shapes_taking(bool ShapeKeys::*key) {
    std::vector<std::string> plural;
    for (std::size_t i = 0; i < kShapeTraits.size(); ++i) {
        if (!(kShapeTraits[i].keys.*key)) continue;
        const std::string name(EnumNames<ShapeKind>::names[i]);
        plural.push_back(name + (name.ends_with("sh") ? "es" : "s"));
    }
    std::string out;
    for (std::size_t i = 0; i < plural.size(); ++i)
        out += (i == 0 ? "" : i + 1 == plural.size() ? " and " : ", ") + plural[i];
    return out;
}

class Loader {
  public:
    explicit Loader(std::string file) : file_(std::move(file)) {}

    Scene load(const json& root) {
        root_ = &root;
        const Node top{root, ""};
        expect_object(top, {"description", "camera", "background", "ambient", "environment",
                            "lights", "materials", "objects", "render"});
        Scene scene;
        if (has(top, "description")) string(top.child("description"));
        if (has(top, "camera")) scene.camera = camera(top.child("camera"));
        if (has(top, "background")) scene.background = colour(top.child("background"));
        if (has(top, "ambient")) scene.ambient = colour(top.child("ambient"));
        if (has(top, "environment")) { // DESIGN §14: a file beside the scene, or the studio
            const Node node = top.child("environment");
            const std::string spec = string(node);
            if (spec != kNoEnvironment)
                scene.environment = load_environment(
                    spec, std::filesystem::path(file_).parent_path(), file_ + ": " + node.path);
        }
        if (has(top, "lights")) {
            const Node lights = array(top.child("lights"));
            for (std::size_t i = 0; i < lights.value.size(); ++i)
                scene.lights.push_back(light(lights[i]));
        }
        scene.materials.push_back(Material{});
        scene.material_names.push_back("default");
        material_places_.push_back("/materials/default");
        material_names_.push_back("default");
        if (has(top, "materials")) materials(top.child("materials"), scene);
        if (has(top, "render")) scene.render = render(top.child("render"));
        if (has(top, "objects")) {
            const Node objects = array(top.child("objects"));
            for (std::size_t i = 0; i < objects.value.size(); ++i) object(objects[i], scene);
        }
        check_scene(scene, [&](const std::string& path) { return place_of(path); });
        return scene;
    }

  private:
    // A part of the scene model (io/scene_check.h) as the place in this file it came from:
    // the JSON pointer of its part, then as much of the rest of its path as the file spells out.
    std::string place_of(const std::string& path) const {
        std::vector<std::string> parts = path_parts(path);
        std::string pointer;
        std::size_t next = 0;
        const auto index = [&] { return static_cast<std::size_t>(std::stoul(parts.at(1))); };
        // What came from an OBJ file (its MTL materials, its meshes) is named by the scene's
        // file key, then the part of the model the rule is about.
        const auto in_obj = [&](const std::string& file_key, std::string what) {
            for (std::size_t k = 2; k < parts.size(); ++k) what += " " + parts[k];
            return file_ + ": " + file_key + ": " + what;
        };
        if (parts[0] == "materials" && parts.size() > 1) {
            pointer = material_places_.at(index()), next = 2;
            if (pointer.ends_with("/file"))
                return in_obj(pointer, "material '" + material_names_.at(index()) + "'");
        } else if (parts[0] == "objects" && parts.size() > 1) {
            pointer = object_places_.at(index()), next = 2;
        } else if (parts[0] == "meshes" && parts.size() > 1) {
            const MeshPlace& mesh = mesh_places_.at(index());
            pointer = mesh.pointer, next = 2;
            if (pointer.ends_with("/file")) return in_obj(pointer, "mesh");
            // Indices given as triples: the model's flat index k is triple k/3, corner k mod 3.
            if (mesh.triples && parts.size() == 4 && parts[2] == "indices") {
                const std::size_t k = std::stoul(parts[3]);
                parts = {"", "", "indices", std::to_string(k / 3), std::to_string(k % 3)};
            }
        } else if (path == "render/min_reflectivity" && root_->contains("render") &&
                   (*root_)["render"].is_object() && (*root_)["render"].contains("min_weight")) {
            parts = {"render", "min_weight"};
        }
        for (; next < parts.size(); ++next) {
            const std::string longer = pointer + "/" + parts[next];
            if (!root_->contains(json::json_pointer(longer))) break;
            pointer = longer;
        }
        return file_ + ": " + (pointer.empty() ? "/" : pointer);
    }

    [[noreturn]] void fail(const Node& node, const std::string& message) const {
        throw SceneError(file_ + ": " + (node.path.empty() ? "/" : node.path) + ": " + message);
    }

    static bool has(const Node& node, const char* key) { return node.value.contains(key); }

    void expect_object(const Node& node, std::initializer_list<std::string_view> keys) const {
        if (!node.value.is_object()) fail(node, "expected an object, got " + type_name(node.value));
        for (const auto& [key, _] : node.value.items())
            if (std::find(keys.begin(), keys.end(), key) == keys.end())
                fail(node.child(key),
                     "unknown key '" + key + "' (expected one of: " + join(keys) + ")");
    }

    Node array(const Node& node) const {
        if (!node.value.is_array()) fail(node, "expected an array, got " + type_name(node.value));
        return node;
    }

    std::string string(const Node& node) const {
        if (!node.value.is_string()) fail(node, "expected a string, got " + type_name(node.value));
        return node.value.get<std::string>();
    }

    bool boolean(const Node& node) const {
        if (!node.value.is_boolean())
            fail(node, "expected true or false, got " + type_name(node.value));
        return node.value.get<bool>();
    }

    double number(const Node& node) const {
        if (!node.value.is_number()) fail(node, "expected a number, got " + type_name(node.value));
        const double v = node.value.get<double>();
        if (!std::isfinite(v)) fail(node, "must be finite");
        return v;
    }

    // A number as the model's float holds it: one beyond float's range is held at ±3e38, still
    // beyond every range the scene check allows.
    float real(const Node& node) const {
        return static_cast<float>(std::clamp(number(node), -3e38, 3e38));
    }

    // A whole number that an int holds; its range is the scene check's (io/scene_check.h).
    int whole(const Node& node) const {
        const double v = number(node);
        if (v != std::floor(v)) fail(node, "must be a whole number");
        return static_cast<int>(std::clamp(v, -1e9, 1e9));
    }

    DVec3 vec3(const Node& node) const {
        if (!node.value.is_array() || node.value.size() != 3)
            fail(node,
                 "expected an array of 3 numbers, got " +
                     (node.value.is_array() ? "an array of " + std::to_string(node.value.size())
                                            : type_name(node.value)));
        return {number(node[0]), number(node[1]), number(node[2])};
    }

    // A position or a colour: its range is the scene check's (io/scene_check.h). A colour
    // beyond float's range stays beyond it (+inf), so that the check sees it.
    DVec3 point(const Node& node) const { return vec3(node); }
    glm::vec3 colour(const Node& node) const {
        return glm::vec3(glm::clamp(vec3(node), DVec3(-3e38), DVec3(3e38)));
    }

    Camera camera(const Node& node) const {
        expect_object(node, {"eye", "look_at", "up", "fov_y", "width", "height"});
        Camera c;
        if (has(node, "eye")) c.eye = point(node.child("eye"));
        if (has(node, "look_at")) c.look_at = point(node.child("look_at"));
        if (has(node, "up")) c.up = point(node.child("up"));
        if (has(node, "fov_y")) c.fov_y = number(node.child("fov_y"));
        if (has(node, "width")) c.width = whole(node.child("width"));
        if (has(node, "height")) c.height = whole(node.child("height"));
        return c;
    }

    PointLight light(const Node& node) const {
        expect_object(node, {"type", "position", "color"});
        if (has(node, "type") && string(node.child("type")) != "point")
            fail(node.child("type"),
                 "unknown light type '" + string(node.child("type")) + "' (glint has: point)");
        if (!has(node, "position")) fail(node, "a light needs a position");
        PointLight l;
        l.position = point(node.child("position"));
        if (has(node, "color")) l.color = colour(node.child("color"));
        return l;
    }

    void materials(const Node& node, Scene& scene) const {
        if (!node.value.is_object())
            fail(node, "expected an object of named materials, got " + type_name(node.value));
        for (const auto& [name, _] : node.value.items()) {
            if (name.empty()) fail(node, "material names must not be empty");
            const Material m = material(node.child(name));
            if (name == "default") { // redefines the material of objects that name none
                scene.materials[0] = m;
                continue;
            }
            scene.materials.push_back(m);
            scene.material_names.push_back(name);
            material_places_.push_back(node.child(name).path);
            material_names_.push_back(name);
        }
    }

    Material material(const Node& node) const {
        expect_object(node, {"ambient", "diffuse", "specular", "shininess", "reflectivity",
                             "transmission", "ior", "checker"});
        Material m;
        if (has(node, "diffuse")) m.diffuse = colour(node.child("diffuse"));
        m.ambient = has(node, "ambient") ? colour(node.child("ambient")) : m.diffuse;
        if (has(node, "specular")) m.specular = colour(node.child("specular"));
        if (has(node, "shininess")) m.shininess = real(node.child("shininess"));
        if (has(node, "reflectivity")) m.reflectivity = real(node.child("reflectivity"));
        if (has(node, "transmission")) m.transmission = real(node.child("transmission"));
        if (has(node, "ior")) m.ior = real(node.child("ior"));
        if (has(node, "checker")) m.checker = checker(node.child("checker"));
        return m;
    }

    Checker checker(const Node& node) const {
        expect_object(node, {"size", "diffuse", "ambient"});
        if (!has(node, "size")) fail(node, "a checker needs a size");
        if (!has(node, "diffuse")) fail(node, "a checker needs a diffuse colour");
        Checker c;
        // The model's size 0 means no checker: a file's checker must not say 0 (the rest of the
        // range is the scene check's).
        c.size = real(node.child("size"));
        if (c.size == 0) fail(node.child("size"), "must be above 0 and at most 1e15");
        c.diffuse = colour(node.child("diffuse"));
        c.ambient = has(node, "ambient") ? colour(node.child("ambient")) : c.diffuse;
        return c;
    }

    RenderSettings render(const Node& node) const {
        expect_object(node, {"max_depth", "min_weight", "min_reflectivity", "samples", "antialias",
                             "aa_threshold"});
        RenderSettings r;
        if (has(node, "samples")) r.samples = whole(node.child("samples"));
        if (has(node, "antialias")) {
            const Node aa = node.child("antialias");
            const std::optional<Antialias> kind = from_name<Antialias>(string(aa));
            if (!kind) fail(aa, "expected uniform or adaptive");
            r.antialias = *kind;
        }
        if (has(node, "aa_threshold")) r.aa_threshold = real(node.child("aa_threshold"));
        if (has(node, "max_depth")) r.max_depth = whole(node.child("max_depth"));
        // min_reflectivity is the name from before transmission; both mean the same.
        if (has(node, "min_weight") && has(node, "min_reflectivity"))
            fail(node.child("min_reflectivity"),
                 "give min_weight or min_reflectivity (its older name), not both");
        for (const char* key : {"min_weight", "min_reflectivity"})
            if (has(node, key)) r.min_reflectivity = real(node.child(key));
        return r;
    }

    DMat4 transform_entry(const Node& node) const {
        expect_object(node, {"translate", "scale", "rotate", "matrix"});
        if (node.value.size() != 1)
            fail(node, "each transform entry has exactly one of: translate, scale, rotate, matrix");
        if (has(node, "translate")) return translation_matrix(vec3(node.child("translate")));
        if (has(node, "scale")) {
            const Node s = node.child("scale");
            const DVec3 factors = s.value.is_number() ? DVec3(number(s)) : vec3(s);
            if (factors.x == 0 || factors.y == 0 || factors.z == 0)
                fail(s, "components must be non-zero");
            return scale_matrix(factors);
        }
        if (has(node, "rotate")) {
            const Node r = node.child("rotate");
            expect_object(r, {"axis", "degrees"});
            if (!has(r, "axis") || !has(r, "degrees")) fail(r, "rotate needs an axis and degrees");
            const DVec3 axis = vec3(r.child("axis"));
            if (glm::length(axis) == 0) fail(r.child("axis"), "must not be zero");
            return rotation_matrix(axis, number(r.child("degrees")));
        }
        const Node m = node.child("matrix");
        if (!m.value.is_array() || m.value.size() != 4) fail(m, "expected 4 rows of 4 numbers");
        DMat4 result(1.0);
        for (std::size_t row = 0; row < 4; ++row) {
            const Node r = m[row];
            if (!r.value.is_array() || r.value.size() != 4) fail(r, "expected a row of 4 numbers");
            for (std::size_t col = 0; col < 4; ++col)
                result[static_cast<int>(col)][static_cast<int>(row)] = number(r[col]);
        }
        if (result[0][3] != 0 || result[1][3] != 0 || result[2][3] != 0 || result[3][3] != 1)
            fail(m[3], "the last row of an affine matrix must be [0, 0, 0, 1]");
        return result;
    }

    DMat4 transform(const Node& node) const {
        array(node);
        DMat4 m(1.0);
        // Applied in order, first entry first: [scale, rotate, translate] gives M = T·R·S.
        for (std::size_t i = 0; i < node.value.size(); ++i) m = transform_entry(node[i]) * m;
        return m;
    }

    // The vertices (and indices) of a shape that takes them: one triangle when it takes no
    // indices.
    TriangleMesh mesh(const Node& node, ShapeKind shape) const {
        if (!has(node, "vertices")) fail(node, std::string(name_of(shape)) + " needs vertices");
        const Node vertices = array(node.child("vertices"));
        TriangleMesh mesh;
        if (vertices.value.size() > kMaxMeshVertices) // before reading them
            fail(vertices, "has " + std::to_string(vertices.value.size()) +
                               " vertices; the limit is " + std::to_string(kMaxMeshVertices));
        for (std::size_t i = 0; i < vertices.value.size(); ++i) {
            const DVec3 v = point(vertices[i]);
            mesh.vertices.push_back(glm::vec3(v));
        }
        if (!shape_traits(shape).keys.indices) {
            if (mesh.vertices.size() != 3) fail(vertices, "a triangle has exactly 3 vertices");
            mesh.triangles.push_back({0, 1, 2});
            return mesh;
        }
        if (!has(node, "indices")) fail(node, "mesh needs indices (3 per triangle)");
        const Node indices = array(node.child("indices"));
        // Either a flat list [a, b, c, d, e, f, …] or triples [[a, b, c], [d, e, f], …].
        std::vector<std::uint32_t> flat;
        // A vertex's number; that it names one of the vertices is the scene check's.
        const auto index = [&](const Node& n) {
            const double v = number(n);
            if (v != std::floor(v)) fail(n, "must be a whole number");
            if (v < 0) fail(n, "must not be negative");
            flat.push_back(static_cast<std::uint32_t>(std::min(v, 4294967295.0)));
        };
        for (std::size_t i = 0; i < indices.value.size(); ++i) {
            const Node entry = indices[i];
            if (entry.value.is_array()) {
                if (entry.value.size() != 3) fail(entry, "a triangle has exactly 3 indices");
                for (std::size_t k = 0; k < 3; ++k) index(entry[k]);
            } else {
                index(entry);
            }
        }
        if (flat.empty() || flat.size() % 3 != 0)
            fail(indices,
                 "needs a positive multiple of 3 indices, got " + std::to_string(flat.size()));
        for (std::size_t i = 0; i < flat.size(); i += 3)
            mesh.triangles.push_back({flat[i], flat[i + 1], flat[i + 2]});
        return mesh;
    }

    // One object's keys and the checks between them, in one body: the keys, their checks against
    // the shape's traits and the mesh or OBJ parts they make, read top to bottom as in
    // docs/SCENES.md.
    void object(const Node& node, Scene& scene) const {
        expect_object(node, {"name", "shape", "material", "transform", "top_radius", "open",
                             "vertices", "indices", "file"});
        if (!has(node, "shape"))
            fail(node, "an object needs a shape (" + join(EnumNames<ShapeKind>::names) + ")");
        const Node shape_node = node.child("shape");
        const std::string shape = string(shape_node);
        const auto it = std::find(EnumNames<ShapeKind>::names.begin(),
                                  EnumNames<ShapeKind>::names.end(), shape);
        if (it == EnumNames<ShapeKind>::names.end())
            fail(shape_node, "unknown shape '" + shape + "'");
        SceneObject o;
        o.shape = static_cast<ShapeKind>(it - EnumNames<ShapeKind>::names.begin());
        const ShapeKeys& keys = shape_traits(o.shape).keys;
        const auto only = [&](const char* key, bool ShapeKeys::*takes, const std::string& what) {
            if (has(node, key) && !(keys.*takes))
                fail(node.child(key), "only " + shapes_taking(takes) + " " + what);
        };
        only("top_radius", &ShapeKeys::top_radius, "have a top_radius");
        only("open", &ShapeKeys::open, "can be open");
        only("vertices", &ShapeKeys::vertices, "have vertices");
        only("indices", &ShapeKeys::indices, "have indices");
        only("file", &ShapeKeys::file, "are read from files");
        const bool from_file = has(node, "file");
        if (from_file) {
            if (has(node, "vertices") || has(node, "indices"))
                fail(node.child("file"), "a mesh has either a file or vertices and indices");
        }
        if (has(node, "material")) {
            const Node m = node.child("material");
            const std::string name = string(m);
            const auto found =
                std::find(scene.material_names.begin(), scene.material_names.end(), name);
            if (found == scene.material_names.end()) {
                std::string known;
                for (const std::string& n : scene.material_names)
                    known += (known.empty() ? "" : ", ") + n;
                fail(m, "no material named '" + name + "' (known: " + known + ")");
            }
            o.material = static_cast<std::uint32_t>(found - scene.material_names.begin());
        }
        if (has(node, "transform")) o.transform = transform(node.child("transform"));
        if (has(node, "top_radius")) o.top_radius = real(node.child("top_radius"));
        if (has(node, "open")) o.open = boolean(node.child("open"));
        std::vector<SceneObject> placed;
        if (from_file) {
            // Each part (one per MTL material) of the file is an object; every further object
            // naming the same file places the same meshes again (instances).
            for (const auto& [mesh, material] : obj_parts(node.child("file"), scene)) {
                SceneObject part = o;
                part.mesh = mesh;
                if (!has(node, "material")) part.material = material;
                placed.push_back(part);
            }
        } else {
            if (keys.vertices) {
                o.mesh = static_cast<std::uint32_t>(scene.meshes.size());
                scene.meshes.push_back(mesh(node, o.shape));
                const bool triples = has(node, "indices") && node.child("indices").value.is_array() &&
                                     !node.child("indices").value.empty() &&
                                     node.child("indices").value[0].is_array();
                mesh_places_.push_back({node.path, triples});
            }
            placed.push_back(o);
        }
        object_places_.insert(object_places_.end(), placed.size(), node.path);
        if (has(node, "name")) {
            scene.object_names.resize(scene.objects.size());
            scene.object_names.insert(scene.object_names.end(), placed.size(),
                                      string(node.child("name")));
        }
        scene.objects.insert(scene.objects.end(), placed.begin(), placed.end());
    }

    // The meshes (and their materials) of an OBJ file, read once per scene: a path relative to
    // the scene file's directory, the same file named again reusing what was read.
    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& obj_parts(const Node& node,
                                                                          Scene& scene) const {
        const std::string given = string(node);
        if (given.empty()) fail(node, "must name an OBJ file");
        const std::filesystem::path path = std::filesystem::path(file_).parent_path() / given;
        std::error_code ec;
        const std::filesystem::path canonical = std::filesystem::weakly_canonical(path, ec);
        const std::string key = ec ? path.lexically_normal().string() : canonical.string();
        if (const auto it = obj_cache_.find(key); it != obj_cache_.end()) return it->second;
        ObjModel model;
        try {
            model = load_obj(path);
        } catch (const SceneError& e) {
            fail(node, e.what());
        }
        std::vector<std::pair<std::uint32_t, std::uint32_t>> parts;
        for (ObjPart& part : model.parts) {
            std::uint32_t material = 0;
            if (part.material) {
                add_part_textures(part, scene.textures);
                material = static_cast<std::uint32_t>(scene.materials.size());
                scene.materials.push_back(*part.material);
                scene.material_names.push_back(given + ":" + part.material_name);
                material_places_.push_back(node.path); // the file's MTL: named by the file key
                material_names_.push_back(given + ":" + part.material_name);
            }
            parts.emplace_back(static_cast<std::uint32_t>(scene.meshes.size()), material);
            scene.meshes.push_back(std::move(part.mesh));
            mesh_places_.push_back({node.path, false});
        }
        // A mesh file's notes name it: the scene's own path comes before them when printed.
        for (const std::string& note : model.notes) scene.notes.push_back(given + ": " + note);
        scene.warnings.insert(scene.warnings.end(), model.warnings.begin(), model.warnings.end());
        return obj_cache_.emplace(key, std::move(parts)).first->second;
    }

    // Where each material, object and mesh of the model came from (place_of).
    struct MeshPlace {
        std::string pointer; // the object that gave its vertices, or the file key naming its OBJ
        bool triples;        // its indices were given as [a, b, c] triples
    };

    std::string file_;
    const json* root_ = nullptr;
    mutable std::vector<std::string> material_places_, material_names_, object_places_;
    mutable std::vector<MeshPlace> mesh_places_;
    mutable std::map<std::string, std::vector<std::pair<std::uint32_t, std::uint32_t>>> obj_cache_;
};

// nlohmann's message without its "[json.exception.…] parse error at line 1, column 2: " prefix.
std::string bare_message(const json::exception& e) {
    std::string what = e.what();
    if (const auto bracket = what.find("] "); bracket != std::string::npos)
        what = what.substr(bracket + 2);
    if (const auto colon = what.find(": ");
        what.rfind("parse error", 0) == 0 && colon != std::string::npos)
        what = what.substr(colon + 2);
    return what;
}

} // namespace

Scene parse_scene(const std::string& text, const std::string& name) {
    check_json_nesting(text, name, kMaxJsonDepth); // no valid scene nests that far
    json root;
    try {
        root = json::parse(text);
    } catch (const json::parse_error& e) {
        // nlohmann counts the offending byte from 1.
        throw SceneError(text_place(name, text, e.byte > 0 ? e.byte - 1 : 0) +
                         ": malformed JSON: " + bare_message(e));
    } catch (const json::exception& e) {
        // A number too large for a double ("1e400") stops parsing without a position: find the
        // literal nlohmann quotes in its message.
        std::string what = bare_message(e);
        const auto open = what.find('\''), close = what.rfind('\'');
        std::size_t offset = 0;
        if (open != std::string::npos && close > open) {
            offset = text.find(what.substr(open + 1, close - open - 1));
            if (offset == std::string::npos) offset = 0;
        }
        throw SceneError(text_place(name, text, offset) + ": " + what +
                         " (numbers must be finite doubles)");
    }
    return Loader(name).load(root);
}

} // namespace glint
