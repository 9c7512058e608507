// The scene as loaded and validated (docs/SCENES.md): what the file says, in double positions and
// transforms and float colours, the same for both precisions of the tracer (trace/math.h).
// Everything after loading may assume it valid; World (trace/world.h) prepares it for tracing.
#pragma once

#include "trace/names.h"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint {

using DVec3 = glm::dvec3;
using DMat4 = glm::dmat4;

// Largest coordinate or transform entry a scene may use: squares of differences must still be
// finite in float (3.4e38) with room to spare.
inline constexpr double kMaxCoordinate = 1e15;

// The closed set of shapes: defined, with its names, in trace/shapes/table.h.
enum class ShapeKind : std::uint8_t;

struct Camera {
    DVec3 eye{0.0, 0.0, 5.0};
    DVec3 look_at{0.0, 0.0, 0.0};
    DVec3 up{0.0, 1.0, 0.0};
    double fov_y = 45.0; // full vertical angle, degrees
    int width = 800;
    int height = 600;

    bool operator==(const Camera&) const = default;
};

struct PointLight {
    DVec3 position;
    glm::vec3 color{1.0f};
};

// A checkerboard in object space (docs/SCENES.md): where the cell index is odd, its colours
// replace the material's diffuse and ambient.
struct Checker {
    float size = 0.0f; // 0: no checker
    glm::vec3 diffuse{0.0f};
    glm::vec3 ambient{0.0f};
};

// The indices of refraction a scene may give: above 0 (as any material's) and at most this.
inline constexpr double kMaxIor = 100;
inline bool usable_ior(double ior) {
    return ior > 0 && ior <= kMaxIor;
}

// How texture coordinates outside [0, 1] map into a texture (glTF's sampler wrap modes).
enum class Wrap : std::uint8_t { repeat, clamp, mirror };

template <> struct EnumNames<Wrap> {
    static constexpr auto names = name_table("repeat", "clamp", "mirror");
};

// A decoded image: 8-bit RGB, rows from the top (texture coordinate v = 0), as the file stores
// them. Its bytes are colours as glint's are, byte / 255, with no transfer curve (docs/SCENES.md,
// "Textures").
struct TextureImage {
    std::string name; // the file or glTF image it came from, for messages and `glint explain`
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb; // width × height × 3
    // Its alpha channel, width × height bytes, where the file has one; empty: opaque (1).
    std::vector<std::uint8_t> alpha;
};

// A texture: an image (shared by every texture that samples it), how it wraps, and the affine
// map its texture coordinates go through first (glTF's KHR_texture_transform: offset · rotation
// · scale; the identity elsewhere).
struct Texture {
    std::shared_ptr<const TextureImage> image;
    Wrap wrap_s = Wrap::repeat, wrap_t = Wrap::repeat;
    glm::mat3 uv_transform{1.0f};
    // Its bytes are sRGB-encoded colours to decode to linear before filtering (a glTF base
    // colour or emissive texture under `glint render --colour srgb`); else byte / 255.
    bool srgb = false;
    // Which of a mesh's texture coordinate sets it reads: 0 (TriangleMesh::uvs) or 1 (uvs1).
    int set = 0;
};

inline constexpr std::uint32_t kNoTexture = ~std::uint32_t{0};

// What a glTF metallic-roughness material gives per texel (DESIGN §14): its factors and the
// textures that scale them (Material::metal_rough). At namespace scope: clang cannot construct
// a nested class with member initializers inside std::optional of its enclosing class.
struct MetalRoughInputs {
    glm::vec3 base{1.0f};  // baseColorFactor's RGB
    float metallic = 1.0f; // metallicFactor
    float roughness = 1.0f;
    float transmission = 0.0f;
    float occlusion_strength = 1.0f;
    // alphaMode BLEND: what shows of the surface (the factor's alpha); 1 elsewhere.
    float coverage = 1.0f;
    std::uint32_t metal_rough_texture = kNoTexture; // metallic in blue, roughness in green
    std::uint32_t occlusion_texture = kNoTexture;   // in red
};

struct Material {
    glm::vec3 ambient{0.8f};
    glm::vec3 diffuse{0.8f};
    glm::vec3 specular{0.0f};
    float shininess = 32.0f;
    float reflectivity = 0.0f;
    float transmission = 0.0f; // fraction of the transmitted ray's colour added
    float ior = 1.5f;          // index of refraction, where transmission > 0
    Checker checker;
    // A base colour texture (index into Scene::textures): on meshes with texture coordinates,
    // its colour multiplies the diffuse and ambient colours (docs/SCENES.md, "Textures").
    std::uint32_t texture = kNoTexture;
    // Cut-outs (DESIGN §13, docs/SCENES.md "Cut-outs"): with `cut_out`, a hit whose alpha (this
    // factor × the base colour texture's alpha there) is below `alpha_cutoff` is no hit.
    float alpha = 1.0f;
    bool cut_out = false;
    float alpha_cutoff = 0.5f;
    // Where the alpha comes from when not the base colour texture (OBJ's map_d), or kNoTexture.
    std::uint32_t alpha_texture = kNoTexture;
    // Emission (DESIGN §13): this colour × the emission texture's at the hit, added unshadowed.
    glm::vec3 emission{0.0f};
    std::uint32_t emission_texture = kNoTexture;
    // A tangent-space normal map (glTF's normalTexture) on meshes with texture coordinates, its
    // x and y scaled by `normal_scale` (docs/SCENES.md, "Normal maps").
    std::uint32_t normal_texture = kNoTexture;
    float normal_scale = 1.0f;
    // False: one-sided (a glTF material's `doubleSided: false`, DESIGN §14): a triangle whose
    // winding faces away from the ray is no hit. JSON, OBJ and NFF materials are two-sided.
    bool double_sided = true;
    // A glTF metallic-roughness material (DESIGN §14): shading derives the Phong colours above
    // from it per texel. The fields above hold them with every texel 1 (the preview's colour).
    std::optional<MetalRoughInputs> metal_rough;
    // Unlit (glTF's KHR_materials_unlit): the colour is `emission` × `emission_texture`'s texel
    // (the base colour's, a missing one leaving the factor) × the vertex colours, and no light
    // or reflection adds to it; every other colour is 0.
    bool unlit = false;
};

// Triangles as given (counter-clockwise front), object space.
struct TriangleMesh {
    std::vector<glm::vec3> vertices;
    std::vector<glm::uvec3> triangles; // indices into vertices
    // One unit shading normal per vertex (smooth shading), or none (flat: the facet normal).
    std::vector<glm::vec3> normals;
    // One texture coordinate per vertex (u right, v down from the image's top row), or none;
    // `uvs1` the second set (glTF's TEXCOORD_1), or none.
    std::vector<glm::vec2> uvs, uvs1;
    // One colour per vertex (glTF's COLOR_0), multiplying the diffuse and ambient colours, or none.
    std::vector<glm::vec3> colours;
    // One tangent per vertex (glTF's TANGENT: xyz the direction of increasing u, w = ±1 the
    // bitangent's sign), or none: normal maps then take each triangle's from its coordinates.
    std::vector<glm::vec4> tangents;
};

struct SceneObject {
    ShapeKind shape{}; // the first in trace/shapes/table.h: sphere
    std::uint32_t material = 0;
    DMat4 transform{1.0};    // object → world, composed from the scene's transform list
    float top_radius = 0.0f; // cones only
    bool open = false;       // cylinders and cones: no end caps (NFF's `c`)
    std::uint32_t mesh = 0;  // index into Scene::meshes for triangles and meshes
};

// Antialiasing (DESIGN §11, docs/ANTIALIASING.md): every pixel the mean of its N×N sample grid,
// or the grid only where the adaptive rule finds an edge and the pixel centre elsewhere.
enum class Antialias : std::uint8_t { uniform, adaptive };

template <> struct EnumNames<Antialias> {
    static constexpr auto names = name_table("uniform", "adaptive");
};

inline constexpr int kMaxSamples = 16; // per side of a pixel's sample grid
// The adaptive rule's contrast threshold: the largest channel difference (0…1) between a pixel's
// and a neighbour's one-sample colours that still leaves the pixel unrefined.
inline constexpr float kDefaultAaThreshold = 0.02f;

struct RenderSettings {
    int max_depth = 5;
    // The smallest path weight (product of the reflectivities and transmissions along the path)
    // for which a reflected or transmitted ray is still cast; the scene file's `min_weight`.
    float min_reflectivity = 0.01f;
    int samples = 1; // N: an N×N grid of samples in every pixel
    Antialias antialias = Antialias::uniform;
    float aa_threshold = kDefaultAaThreshold;
    // How the frame is traced, not what it shows: the levels of each tile's ray trees whose
    // reflected and transmitted rays are cast ahead in packets (TileLighting, trace/pixel.h).
    // Any number gives the same image. Not a scene-file key: `--packet-levels`.
    int packet_levels = 0;
};

// An environment (DESIGN §14): an equirectangular image of linear radiance that a ray leaving
// the scene returns in its direction (trace/texture.h, environment_radiance).
struct Environment {
    std::string name; // the file, or "studio" for the built-in one
    int width = 0, height = 0;
    std::vector<float> rgb; // width × height × 3, top row first
    glm::vec3 brightest{0.0f}; // each channel's largest texel (the cut-off bound's), set on reading
};

struct Scene;

// A model's motion (a glTF animation's node channels, skins and morph targets,
// io/gltf_animation.h): places the scene's objects, lights and file camera at any time t ≥ 0 in
// seconds (DESIGN §13, "Animation time"), and poses the meshes that skins and morph targets move
// (DESIGN §14). The materials, textures and other meshes do not move: a sequence prepares them
// once, and prepares again only the moving meshes.
class Animation {
  public:
    virtual ~Animation() = default;
    virtual std::string name() const = 0; // for people: "animation 0 (Walk)"
    virtual double duration() const = 0;  // its last key time
    // Sets `scene`'s object transforms (and the lights and camera that animated nodes carry)
    // to their values at time t; `scene` is the one the animation was read with.
    virtual void pose(Scene& scene, double t) const = 0;
    // The meshes (indices in Scene::meshes) that pose() changes.
    virtual std::vector<std::uint32_t> moving_meshes() const { return {}; }
};

struct Scene {
    Camera camera;
    glm::vec3 background{0.0f};
    glm::vec3 ambient{0.0f};
    std::vector<PointLight> lights;
    std::vector<Material> materials; // index 0 is the default material
    std::vector<std::string> material_names;
    std::vector<SceneObject> objects;
    // Objects' optional names, for people (`glint explain`), by object index; may be shorter
    // than `objects` (unnamed ones at the end). Every part of an OBJ file has its object's name.
    std::vector<std::string> object_names;
    std::vector<TriangleMesh> meshes;
    std::vector<Texture> textures;
    RenderSettings render;
    // What the loader left out or changed, for the user to read (NFF's transmission, ...); each
    // is printed after the scene's path, so a note names only another file it comes from.
    std::vector<std::string> notes;
    // What a model file asked for that glint could not give it (a missing texture or material
    // library): the model renders without it.
    std::vector<std::string> warnings;
    // A model's animation, where one was asked for (`--time`, `--frames`): none otherwise.
    std::shared_ptr<const Animation> animation;
    // What rays that leave the scene return (DESIGN §14), or none: the background colour.
    std::shared_ptr<const Environment> environment;
};

// Building blocks of a scene's transform list (column vectors: p' = M·p).
DMat4 translation_matrix(DVec3 offset);
DMat4 scale_matrix(DVec3 factors);
DMat4 rotation_matrix(DVec3 axis, double degrees); // right-handed about the normalised axis

// DESIGN §13's orbit: frame k of a sequence of n is `camera` rotated by 360°·k/n about the world
// +Y axis through its look-at point (a framed model's centre), keeping its distance, height and
// up (`glint render --frames n --orbit`).
Camera orbit_camera(const Camera& camera, int k, int n);

// Largest condition number (after scaling the rows of M⁻¹'s linear part to unit length) that
// glint accepts. Row scaling makes any rotated non-uniform scale perfectly conditioned, since
// float rounds each row of M⁻¹ relative to its own size; what remains measures how nearly
// parallel the rows are (shear). At 1e4, float's 7 digits leave about 3 in object coordinates.
// The double-precision tracer accepts exactly the same scenes, so that it can be their reference.
inline constexpr double kMaxConditionNumber = 1e4;

// Why M cannot place an object (singular, non-affine, out of float's range or too ill-conditioned
// to invert in float), or nothing when it can.
std::optional<std::string> why_unusable(const DMat4& m);

// The box M·[lo, hi] in double: the eight corners mapped, their smallest and largest coordinates.
std::pair<DVec3, DVec3> transformed_box(const std::pair<DVec3, DVec3>& local, const DMat4& m);

} // namespace glint
