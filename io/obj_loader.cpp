// OBJ through tinyobjloader. tinyobjloader is lenient: a number it cannot read becomes 0, an
// index beyond the vertices is only a warning, and a face's vertex count is kept in a byte. So
// every line is checked here first, and an error names the line; tinyobjloader then reads the
// checked text and its checked MTL libraries. Faces are triangulated by ear clipping
// (io/polygon.h): tinyobjloader's own triangulation is a fan, wrong for concave faces.
#include "io/obj_loader.h"

#include "io/error.h"
#include "io/polygon.h"
#include "io/read_text.h"
#include "io/texture_file.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <sstream>
#include <string_view>

namespace glint {
namespace {

// Statements of the OBJ format that describe no triangle (free-form geometry, grouping,
// display attributes): read past. Anything else is not OBJ.
constexpr std::array<std::string_view, 27> kIgnored = {
    "o",     "g",    "s",      "vp",     "cstype",     "deg",       "bmat",  "step",  "curv",
    "curv2", "surf", "parm",   "trim",   "hole",       "scrv",      "sp",    "end",   "con",
    "mg",    "lod",  "usemap", "maplib", "shadow_obj", "trace_obj", "ctech", "stech", "bevel"};
// tinyobjloader stores a face's vertex count in a byte.
constexpr std::size_t kMaxFaceVertices = 255;

std::vector<std::string_view> split(std::string_view line) {
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        const std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
        if (i > start) words.push_back(line.substr(start, i - start));
    }
    return words;
}

// Checks every line of a text, statement by statement (`statement`, the format's own), and keeps
// what it checked for tinyobjloader to read.
class LineChecker {
  public:
    explicit LineChecker(std::string name) : name_(std::move(name)) {}
    virtual ~LineChecker() = default;

    void check(const std::string& text) {
        std::size_t start = 0;
        int line = 0;
        while (start <= text.size()) {
            std::size_t end = text.find('\n', start);
            if (end == std::string::npos) end = text.size();
            ++line;
            std::string_view l = std::string_view(text).substr(start, end - start);
            if (const std::size_t hash = l.find('#'); hash != std::string_view::npos)
                l = l.substr(0, hash);
            if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
            // Checked as appended to `clean`; tinyobjloader ends a line at a lone '\r' too, and
            // a blank keeps the lines the same.
            const std::size_t from = clean.size();
            clean += l;
            std::replace(clean.begin() + static_cast<std::ptrdiff_t>(from), clean.end(), '\r', ' ');
            statement(split(std::string_view(clean).substr(from)), line);
            clean += '\n';
            start = end + 1;
        }
        finish(line);
    }

    // The text as checked, line for line: comments cut and '\r' blanked. tinyobjloader reads
    // this, not the file, so that it sees exactly the statements checked here (it takes '#'
    // as a comment only at the start of a line, and a lone '\r' as a line break: a face after
    // "1#" or a '\r' in a group name once reached it unchecked, found by fuzz_obj).
    std::string clean;

  protected:
    virtual void statement(const std::vector<std::string_view>& words, int line) = 0;
    virtual void finish(int /*last_line*/) {}

    [[noreturn]] void fail(int line, const std::string& message) const {
        throw SceneError(name_ + ":" + std::to_string(line) + ": " + message);
    }

    void numbers(const std::vector<std::string_view>& w, int line, std::size_t lo, std::size_t hi,
                 bool position) const {
        if (w.size() - 1 < lo || w.size() - 1 > hi)
            fail(line, std::string(w[0]) + " needs " + std::to_string(lo) +
                           (lo == hi ? "" : " to " + std::to_string(hi)) + " numbers, got " +
                           std::to_string(w.size() - 1));
        for (std::size_t i = 1; i < w.size(); ++i) {
            double v = 0;
            if (!parse_number(w[i], v))
                fail(line, "expected a number in " + std::string(w[0]) + ", got '" +
                               printable(w[i], 40) + "'");
            if (position && i <= 3 && std::abs(v) > kMaxCoordinate)
                fail(line, "coordinate beyond 1e15, too large for float");
        }
    }

  private:
    std::string name_;
};

// An OBJ file's lines; collects the material libraries it names and what will be ignored.
class ObjChecker : public LineChecker {
  public:
    using LineChecker::fail;
    using LineChecker::LineChecker;

    std::vector<std::pair<std::string, int>> libraries; // as named, with their mtllib line
    std::size_t lines_and_points = 0;

  private:
    void finish(int last_line) override {
        if (faces_ == 0) fail(last_line, "no faces (f): an OBJ mesh needs at least one");
    }

    // One index of a face corner: 1..count, or −count..−1 counting back from the last.
    void index(std::string_view s, std::size_t count, const char* what, const char* plural,
               int line) const {
        long long i = 0;
        const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), i);
        if (error != std::errc() || end != s.data() + s.size() || i == 0)
            fail(line, std::string("expected a ") + what +
                           " index (1 or more, or negative from "
                           "the last), got '" +
                           printable(s, 40) + "'");
        const long long n = static_cast<long long>(count);
        if (i > n || i < -n)
            fail(line, std::string(what) + " index " + std::to_string(i) + " is beyond the " +
                           std::to_string(count) + " " + plural + " defined so far");
    }

    void face(const std::vector<std::string_view>& w, int line) {
        if (w.size() - 1 < 3) fail(line, "a face needs at least 3 vertices");
        if (w.size() - 1 > kMaxFaceVertices)
            fail(line, "a face has more than " + std::to_string(kMaxFaceVertices) + " vertices");
        for (std::size_t k = 1; k < w.size(); ++k) {
            // v, v/t, v//n or v/t/n
            std::array<std::string_view, 3> parts;
            std::size_t count = 0, from = 0;
            const std::string_view c = w[k];
            while (true) {
                const std::size_t slash = c.find('/', from);
                if (count == 3) fail(line, "a face corner has at most 3 parts (v/t/n)");
                parts[count++] =
                    c.substr(from, slash == std::string_view::npos ? c.npos : slash - from);
                if (slash == std::string_view::npos) break;
                from = slash + 1;
            }
            index(parts[0], vertices_, "vertex", "vertices", line);
            if (count > 1 && !parts[1].empty())
                index(parts[1], texcoords_, "texture coordinate", "texture coordinates", line);
            if (count > 2) index(parts[2], normals_, "normal", "normals", line);
        }
        ++faces_;
    }

    void statement(const std::vector<std::string_view>& w, int line) override {
        if (w.empty()) return;
        const std::string_view k = w[0];
        if (k == "v") {
            numbers(w, line, 3, 7, true); // x y z [w] or x y z r g b
            ++vertices_;
        } else if (k == "vn") {
            numbers(w, line, 3, 3, false);
            ++normals_;
        } else if (k == "vt") {
            numbers(w, line, 1, 3, false);
            ++texcoords_;
        } else if (k == "f") {
            face(w, line);
        } else if (k == "l" || k == "p") {
            ++lines_and_points;
        } else if (k == "mtllib") {
            for (std::size_t i = 1; i < w.size(); ++i) libraries.emplace_back(w[i], line);
        } else if (k == "usemtl") {
            if (w.size() < 2) fail(line, "usemtl needs a material name");
        } else if (std::find(kIgnored.begin(), kIgnored.end(), k) == kIgnored.end()) {
            fail(line, "unknown statement '" + printable(k, 40) + "'");
        }
    }

    std::size_t vertices_ = 0, normals_ = 0, texcoords_ = 0, faces_ = 0;
};

// MTL statements glint reads (docs/SCENES.md, "OBJ"), and those it reads past with a warning:
// texture maps other than map_Kd, emission, and the PBR extension's parameters.
constexpr std::array<std::string_view, 5> kMtlColours = {"Ka", "Kd", "Ks", "Ke", "Tf"};
constexpr std::array<std::string_view, 13> kMtlNumbers = {
    "Ns", "Ni", "d", "Tr", "illum", "sharpness", "Pr", "Pm", "Ps", "Pc", "Pcr", "aniso", "anisor"};
constexpr std::array<std::string_view, 16> kMtlMaps = {
    "map_Ka", "map_Kd", "map_Ks", "map_Ke", "map_Ns", "map_d",  "map_Tr", "map_bump",
    "bump",   "disp",   "decal",  "refl",   "map_Pr", "map_Pm", "map_Ps", "norm"};

// An MTL library's lines: each statement known, with its numbers, inside a newmtl.
class MtlChecker : public LineChecker {
  public:
    using LineChecker::LineChecker;

    // Statements read past, each with the first line it is on.
    std::map<std::string, int> unused;

  private:
    static bool in(std::string_view k, const auto& set) {
        return std::find(set.begin(), set.end(), k) != set.end();
    }

    void statement(const std::vector<std::string_view>& w, int line) override {
        if (w.empty()) return;
        const std::string_view k = w[0];
        if (k == "newmtl") {
            if (w.size() < 2) fail(line, "newmtl needs a material name");
            named_ = true;
            return;
        }
        const bool colour = in(k, kMtlColours), number = in(k, kMtlNumbers);
        if (!colour && !number && !in(k, kMtlMaps))
            fail(line, "unknown MTL statement '" + printable(k, 40) + "'");
        if (!named_) fail(line, std::string(k) + " before any newmtl");
        if (colour) numbers(w, line, 3, 3, false); // r g b (not spectral or xyz)
        if (number) numbers(w, line, 1, 1, false);
        static constexpr std::array<std::string_view, 7> kRead = {"Ka", "Kd",    "Ks", "Ns",
                                                                  "Ni", "d",     "Tr"};
        if (k != "map_Kd" && k != "map_d" && k != "illum" && !in(k, kRead))
            unused.emplace(k, line);
    }

    bool named_ = false;
};

glm::vec3 mtl_colour(const tinyobj::real_t (&c)[3], const std::string& what,
                     const std::string& material, const std::string& name) {
    for (const tinyobj::real_t v : c)
        if (!(v >= 0 && v <= kMaxColour))
            throw SceneError(name + ": material '" + printable(material) + "': " + what +
                             " components must be between 0 and 1e6");
    return {c[0], c[1], c[2]};
}

// An MTL material in glint's model (docs/SCENES.md, "OBJ"): Kd the diffuse and ambient, Ks the
// specular, Ns the shininess; illum 3 to 7 (ray-traced reflection) make the mean of Ks the
// reflectivity; illum 4, 6 and 7 (refraction) and any d below 1 (or Tr above 0) transmit
// 1 − d of the light, with Ni the index of refraction.
Material mtl_material(const tinyobj::material_t& m, const std::string& name) {
    const auto fail = [&](const std::string& what) {
        throw SceneError(name + ": material '" + printable(m.name) + "': " + what);
    };
    Material material;
    material.diffuse = mtl_colour(m.diffuse, "Kd", m.name, name);
    material.ambient = material.diffuse;
    material.specular = mtl_colour(m.specular, "Ks", m.name, name);
    // Ns's range is the scene check's (io/scene_check.h), as `shininess`.
    material.shininess = m.shininess;
    if (!(m.dissolve >= 0 && m.dissolve <= 1)) fail("d must be between 0 and 1 (Tr: 1 − d)");
    if (m.illum >= 3 && m.illum <= 7)
        material.reflectivity =
            std::min(1.0f, (material.specular.x + material.specular.y + material.specular.z) / 3);
    const bool refracts = m.illum == 4 || m.illum == 6 || m.illum == 7;
    if (refracts || m.dissolve < 1) {
        material.transmission = refracts && m.dissolve == 1 ? 1.0f : 1.0f - m.dissolve;
        if (!usable_ior(m.ior))
            fail("Ni (the index of refraction) must be above 0 and at most 100 where it transmits");
        material.ior = m.ior;
    }
    return material;
}

// One part being built: its vertices are the file's distinct (position, normal, texture
// coordinate) triples it uses.
struct PartBuilder {
    ObjPart part;
    std::map<std::array<int, 3>, std::uint32_t> corners;
    bool all_normals = true, all_uvs = true;
};

} // namespace

ObjModel parse_obj(const std::string& text, const std::string& name,
                   const std::function<std::optional<std::string>(const std::string&)>& read_mtl) {
    ObjChecker checker(name);
    checker.check(text);
    ObjModel model;
    std::string mtl_text;
    for (const auto& [library, line] : checker.libraries) {
        const auto t = read_mtl(library);
        if (!t) {
            model.warnings.push_back(name + ":" + std::to_string(line) + ": material library '" +
                                     printable(library) +
                                     "' cannot be read: its materials are the default one");
            continue;
        }
        // Named after the OBJ that uses it, as the OBJ is after the scene: "m.obj: m.mtl:2: …".
        MtlChecker mtl(name + ": " +
                       (std::filesystem::path(name).parent_path() / library).string());
        mtl.check(*t);
        mtl_text += mtl.clean;
        if (!mtl.unused.empty()) {
            std::string list;
            for (const auto& [statement, at] : mtl.unused)
                list += (list.empty() ? "" : ", ") + statement + " (line " + std::to_string(at) + ")";
            model.warnings.push_back(name + ": " + printable(library) +
                                     ": statements glint does not use: " + list);
        }
    }
    if (checker.lines_and_points > 0)
        model.notes.push_back(std::to_string(checker.lines_and_points) +
                              " line and point statements (l, p) ignored: glint draws surfaces");

    tinyobj::ObjReaderConfig config;
    config.triangulate = false; // ear clipping below, right for concave faces too
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromString(checker.clean, mtl_text, config) || !reader.Error().empty())
        throw SceneError(name + ": " + reader.Error());
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    const std::vector<tinyobj::material_t>& materials = reader.GetMaterials();

    const auto within = [](int index, const std::vector<tinyobj::real_t>& xyz) {
        return index >= 0 && 3 * static_cast<std::size_t>(index) + 2 < xyz.size();
    };
    std::map<int, PartBuilder> parts; // by MTL material (−1: none)
    std::size_t degenerate = 0;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        const tinyobj::mesh_t& mesh = shape.mesh;
        std::size_t offset = 0;
        for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
            const std::size_t n = mesh.num_face_vertices[f];
            const int material_id = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
            PartBuilder& b =
                parts[material_id >= 0 && static_cast<std::size_t>(material_id) < materials.size()
                          ? material_id
                          : -1];
            std::vector<glm::dvec3> polygon;
            std::vector<std::uint32_t> corners;
            for (std::size_t k = 0; k < n; ++k) {
                const tinyobj::index_t& i = mesh.indices[offset + k];
                // The checker bounded every index; this guards memory should the two readers
                // ever disagree again.
                if (!within(i.vertex_index, attrib.vertices) ||
                    (i.normal_index >= 0 && !within(i.normal_index, attrib.normals)) ||
                    (i.texcoord_index >= 0 &&
                     2 * static_cast<std::size_t>(i.texcoord_index) + 1 >= attrib.texcoords.size()))
                    throw SceneError(name + ": a face index is beyond the vertices, normals or "
                                            "texture coordinates");
                const auto vi = static_cast<std::size_t>(i.vertex_index);
                const glm::vec3 p(attrib.vertices[3 * vi], attrib.vertices[3 * vi + 1],
                                  attrib.vertices[3 * vi + 2]);
                polygon.emplace_back(p);
                const auto [it, added] =
                    b.corners.emplace(std::array{i.vertex_index, i.normal_index, i.texcoord_index},
                                      static_cast<std::uint32_t>(b.part.mesh.vertices.size()));
                if (added) {
                    b.part.mesh.vertices.push_back(p);
                    if (i.texcoord_index >= 0) {
                        // OBJ's v runs up from the image's bottom row; glint's down from its top.
                        const auto ti = static_cast<std::size_t>(i.texcoord_index);
                        b.part.mesh.uvs.emplace_back(attrib.texcoords[2 * ti],
                                                     1.0f - attrib.texcoords[2 * ti + 1]);
                    } else {
                        b.all_uvs = false;
                        b.part.mesh.uvs.emplace_back(0.0f);
                    }
                    if (i.normal_index >= 0) {
                        const auto ni = static_cast<std::size_t>(i.normal_index);
                        b.part.mesh.normals.emplace_back(attrib.normals[3 * ni],
                                                         attrib.normals[3 * ni + 1],
                                                         attrib.normals[3 * ni + 2]);
                    } else {
                        b.all_normals = false;
                        b.part.mesh.normals.emplace_back(0.0f);
                    }
                }
                corners.push_back(it->second);
            }
            offset += n;
            const std::vector<glm::uvec3> triangles = triangulate_polygon(polygon);
            if (triangles.empty()) ++degenerate;
            for (const glm::uvec3& t : triangles)
                b.part.mesh.triangles.push_back({corners[t.x], corners[t.y], corners[t.z]});
        }
    }
    if (degenerate > 0)
        model.notes.push_back(std::to_string(degenerate) +
                              " face(s) of zero area left out");
    for (auto& [id, b] : parts) {
        if (b.part.mesh.triangles.empty()) continue;
        if (b.part.mesh.vertices.size() > kMaxMeshVertices ||
            b.part.mesh.triangles.size() > kMaxMeshTriangles)
            throw SceneError(name + ": more than 2^24 vertices or triangles in one material");
        // Smooth shading needs a normal at every vertex; a part with some missing is flat.
        if (!b.all_normals) b.part.mesh.normals.clear();
        if (!b.all_uvs) b.part.mesh.uvs.clear(); // a texture needs them at every corner
        for (glm::vec3& n : b.part.mesh.normals)
            if (!std::isfinite(n.x + n.y + n.z)) n = glm::vec3(0.0f); // the facet stands in
        if (id >= 0) {
            const tinyobj::material_t& m = materials[static_cast<std::size_t>(id)];
            b.part.material = mtl_material(m, name);
            b.part.material_name = m.name;
            // A texture map's file and wrap mode, read where the faces have coordinates for it.
            // (clang 14, the sanitizer build's compiler, cannot capture a structured binding.)
            const bool no_uvs = b.part.mesh.uvs.empty();
            const auto texture_map = [&](const std::string& file, const tinyobj::texture_option_t& o,
                                         const char* statement, std::string& part_file,
                                         Wrap& wrap) {
                part_file = file;
                if (o.clamp) wrap = Wrap::clamp;
                if (!file.empty() && no_uvs)
                    model.warnings.push_back(name + ": material '" + printable(m.name) + "': " +
                                             statement + " not used: its faces have no texture "
                                                         "coordinates (vt) at every corner");
            };
            texture_map(m.diffuse_texname, m.diffuse_texopt, "map_Kd", b.part.texture_file,
                        b.part.texture_wrap);
            texture_map(m.alpha_texname, m.alpha_texopt, "map_d", b.part.alpha_file,
                        b.part.alpha_wrap);
        }
        model.parts.push_back(std::move(b.part));
    }
    return model;
}

void add_part_textures(ObjPart& part, std::vector<Texture>& textures) {
    Material& material = *part.material;
    if (part.texture) {
        material.texture = static_cast<std::uint32_t>(textures.size());
        textures.push_back(*part.texture);
    }
    if (part.alpha) {
        material.alpha_texture = static_cast<std::uint32_t>(textures.size());
        textures.push_back(*part.alpha);
        material.cut_out = true;
        material.alpha_cutoff = kObjAlphaCutoff;
    }
}

ObjModel load_obj(const std::filesystem::path& path) {
    const std::string text = read_scene_file(path, "mesh file");
    const std::filesystem::path dir = path.parent_path();
    ObjModel model = parse_obj(text, path.string(), [&](const std::string& library) {
        try {
            return std::optional<std::string>(read_scene_file(dir / library, "material library"));
        } catch (const SceneError&) {
            return std::optional<std::string>();
        }
    });
    // Windows exporters write `.\tex.jpg`: where no file has that name, its backslashes are
    // read as separators.
    const auto texture_path = [](const std::filesystem::path& dir, const std::string& file) {
        std::filesystem::path literal = dir / file;
        if (file.find('\\') == std::string::npos || std::filesystem::exists(literal)) return literal;
        std::string slashed = file;
        std::replace(slashed.begin(), slashed.end(), '\\', '/');
        return dir / slashed;
    };
    // Each file decoded once, for map_Kd and map_d apart (a map_d's alpha is made from it).
    using Decoded = std::map<std::string, std::shared_ptr<const TextureImage>>;
    Decoded colours, alphas;
    const auto decode = [&](Decoded& decoded, const ObjPart& part, const std::string& file,
                            const char* statement, auto&& adjust) {
        auto [it, added] = decoded.emplace(file, nullptr);
        if (added)
            if (auto image = load_texture(texture_path(dir, file),
                                          path.string() + ": material '" +
                                              printable(part.material_name) + "' " + statement,
                                          model.warnings)) {
                adjust(*image);
                it->second = std::make_shared<const TextureImage>(std::move(*image));
            }
        return it->second;
    };
    for (ObjPart& part : model.parts) {
        if (part.mesh.uvs.empty()) continue;
        if (!part.texture_file.empty())
            if (const auto image =
                    decode(colours, part, part.texture_file, "map_Kd", [](TextureImage&) {}))
                part.texture = Texture{image, part.texture_wrap, part.texture_wrap};
        // map_d: the image's alpha channel, or where it has none its grey level (the mean of
        // its channels), becomes the alpha a cut-out reads.
        if (!part.alpha_file.empty())
            if (const auto image =
                    decode(alphas, part, part.alpha_file, "map_d", [](TextureImage& image) {
                        if (!image.alpha.empty()) return;
                        image.alpha.resize(image.rgb.size() / 3);
                        for (std::size_t i = 0; i < image.alpha.size(); ++i)
                            image.alpha[i] = static_cast<std::uint8_t>(
                                (image.rgb[3 * i] + image.rgb[3 * i + 1] + image.rgb[3 * i + 2] + 1) / 3);
                    }))
                part.alpha = Texture{image, part.alpha_wrap, part.alpha_wrap};
    }
    return model;
}

} // namespace glint
