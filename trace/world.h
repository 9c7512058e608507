// The scene prepared for tracing: camera-relative transforms in Real (trace/math.h), object
// bounds, and the brute-force closest-hit and any-hit queries (the `list` structure every other
// one must match).
#pragma once

#include "trace/accel/accel.h"
#include "trace/camera.h"
#include "trace/scene.h"
#include "trace/shapes/table.h"
#include "trace/texture.h"
#include "trace/transform.h"

#include <tbb/enumerable_thread_specific.h>

#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace glint {
inline namespace GLINT_PRECISION {

struct Object {
    ShapeKind shape;
    Transform transform; // object → camera-relative world
    std::uint32_t material;
    ShapeParams params; // what the shape's routines read (trace/shapes/table.h); its mesh, if any
    bool bounded;       // false for planes
    Bounds bounds;      // camera-relative world bounds, conservative
};

// A material as shading reads it (scene colours in the tracer's precision).
struct Phong {
    Vec3 ambient, diffuse, specular;
    Real shininess, reflectivity, transmission, ior;
    Real checker_size; // 0: none
    Vec3 checker_diffuse, checker_ambient;
    const Texture* texture; // base colour texture (in SceneGeometry::textures), or none
    // Where the material cuts out (DESIGN §13) or is one-sided (§14): what its meshes'
    // intersections read.
    std::optional<CutOut> cut_out;
    Vec3 emission;                   // added unshadowed at every hit (DESIGN §13)
    const Texture* emission_texture; // multiplies `emission` where given, or none
    const Texture* normal_texture;   // a tangent-space normal map, or none
    Real normal_scale;
    // A glTF metallic-roughness material (DESIGN §14), whose Phong inputs vary per texel
    // (trace/shading.h, surface_colours); its textures in SceneGeometry::textures, or none.
    struct MetalRough {
        Vec3 base;
        Real metallic, roughness, transmission, occlusion_strength, coverage;
        const Texture *metal_rough, *occlusion;
    };
    std::optional<MetalRough> metal_rough;
    bool unlit; // Material::unlit: `emission` is its colour, and no light adds to it
};

struct Light {
    Vec3 position; // camera-relative
    Vec3 color;
};

// A hit rebuilt for shading, in camera-relative world space.
struct SurfacePoint {
    Vec3 position;
    Vec3 normal;  // unit geometric normal, flipped to face the incoming ray
    Vec3 shading; // unit normal for shading: `normal`, or the mesh's smooth one on its side
    // Distance along `normal` that clears the surface's rounding error; 0 where neither side
    // needs it (both skip), or where only the far side would and the material does not transmit.
    Real offset;
    // The object itself when no ray leaving here on the normal's side can meet it again (a
    // convex solid left from outside, or a planar shape): such rays ignore it and start on the
    // surface, so they need no offset. kNoObject otherwise (meshes, solids left from inside).
    std::uint32_t skip = kNoObject;
    // The same for rays that go on through the surface, to the far side (transmitted and shadow
    // rays through glass): the object for planar shapes and convex solids left from inside;
    // kNoObject for rays into a solid, which must still find its far wall.
    std::uint32_t skip_through = kNoObject;
    bool entering = true;  // the ray meets the side the shape's outward normal is on
    Vec3 object_point{0};  // M⁻¹o + t·M⁻¹d, where the checker is evaluated
    Vec3 object_normal{0}; // the shape's outward normal there, object space (as the shape gives it)
    Vec3 spawn() const { return skip == kNoObject ? position + offset * normal : position; }
    Vec3 spawn_through() const {
        return skip_through == kNoObject ? position - offset * normal : position;
    }
};

// A query's SlabRay, made on first use: only queries that find a hit pay its divisions.
class LazySlab {
  public:
    LazySlab() = default;
    explicit LazySlab(const Ray& ray) : ray_(&ray) {}
    const SlabRay& get() const {
        if (!slab_) slab_.emplace(*ray_);
        return *slab_;
    }

  private:
    const Ray* ray_ = nullptr;
    mutable std::optional<SlabRay> slab_;
};

// Below this many bounded objects, testing each one's box beats any hierarchy: the default
// structure is then the plain list (model only what the scene needs).
inline constexpr std::size_t kListBelow = 16;

// What the camera does not change: the meshes with their BVHs (object space) and the materials.
// Built once per scene and shared by every World of it (a preview's camera moves, a tradeoff
// sweep's settings).
struct SceneGeometry {
    explicit SceneGeometry(const Scene& scene);
    // The same scene after an animation's pose (Animation::pose): `moved` meshes (indices in
    // Scene::meshes) prepared again, every other shared with `previous`.
    SceneGeometry(const SceneGeometry& previous, const Scene& scene,
                  std::span<const std::uint32_t> moved);
    // `scene`'s geometry after its animation posed it: `previous` itself where the pose moves no
    // mesh (node animation alone), else a geometry with the moving meshes prepared again.
    static std::shared_ptr<const SceneGeometry> posed(std::shared_ptr<const SceneGeometry> previous,
                                                      const Scene& scene);

    std::vector<std::shared_ptr<const Mesh>> meshes;
    std::vector<Texture> textures; // what Phong::texture points into
    std::vector<Phong> materials;
    bool transmissive = false; // some material transmits: shadow rays must count crossings
    bool unlit = false;        // some material is unlit: its hits cast no shadow rays
    // Some material reflects or transmits: a hit may cast a secondary ray, or omit one (the
    // frame's cut-off weights, trace/cutoff.h). Without one, every omitted weight is 0.
    bool secondary = false;
    double build_seconds = 0;  // the meshes' BVHs

  private:
    void prepare_materials(const Scene& scene);
};

class World {
  public:
    // `accel`: the acceleration structure; by default list below kListBelow objects, else bvh.
    explicit World(const Scene& scene, std::optional<AccelKind> accel = std::nullopt);
    // The same with the scene's geometry prepared already (SceneGeometry(scene), or `geometry()`
    // of a World of the same scene).
    World(const Scene& scene, std::shared_ptr<const SceneGeometry> geometry,
          std::optional<AccelKind> accel);
    // The same scene with another camera, size or render settings (`scene` must differ from
    // `previous`'s in nothing else): shares `previous`'s geometry, so no mesh is prepared again,
    // and keeps its structure's kind. A BVH or list is refitted to the moved boxes rather than
    // built anew; every structure returns the list's hits, so the image is the same either way.
    World(const Scene& scene, const World& previous);

    // The closest hit in (0, t_max) on any object but `skip`; ties go to the lower index.
    Hit intersect(const Ray& ray, Real t_max = kInfinity, std::uint32_t skip = kNoObject) const;
    // Whether anything other than object `skip` is hit in (0, t_max).
    bool occluded(const Ray& ray, Real t_max, std::uint32_t skip = kNoObject) const;
    // Whether an opaque object (one whose material does not transmit) other than `skip` is hit
    // in (0, t_max); sets `transmissive` when a transmissive one is hit there too (when the
    // answer is false, whether any is).
    bool opaque_between(const Ray& ray, Real t_max, std::uint32_t skip, bool& transmissive) const;
    // Packets of up to kMaxPacket coherent rays (a tile's camera rays, its shadow rays towards
    // one light, its primary hits' reflected rays): exactly intersect(rays[i], kInfinity,
    // skips[i]) (skips null: kNoObject) and occluded(rays[i], t_max, skips[i]) for each, with
    // the BVH's nodes fetched once per packet (WideBvh::traverse_packet). With the list, object
    // by object, a mesh's own BVH taking as a packet the rays that meet its box; with any other
    // structure, ray by ray.
    void intersect_packet(std::span<const Ray> rays, Hit* hits,
                          const std::uint32_t* skips = nullptr) const;
    void occluded_packet(std::span<const Ray> rays, Real t_max, const std::uint32_t* skips,
                         bool* occluded) const;
    // The same for opaque_between(rays[i], t_max, skips[i], transmissive[i]) (a tile's shadow
    // rays in a scene with glass).
    void opaque_between_packet(std::span<const Ray> rays, Real t_max, const std::uint32_t* skips,
                               bool* opaque, bool* transmissive) const;
    // The first hit on one object alone, in (0, t_max).
    Hit intersect_one(std::uint32_t object, const Ray& ray, Real t_max = kInfinity) const;
    // The same for a packet of up to kMaxPacket coherent rays (an item buffer's block of pixels
    // that all name `object`): hits[i] = intersect_one(object, rays[i]), bit for bit. A mesh's
    // own BVH is traversed by the packet; other shapes are one test per ray either way.
    void intersect_one_packet(std::uint32_t object, std::span<const Ray> rays, Hit* hits) const;
    SurfacePoint surface(const Ray& ray, const Hit& hit) const;

    const PinholeCamera& camera() const { return camera_; }
    const std::vector<Object>& objects() const { return objects_; }
    const Mesh& mesh(std::uint32_t index) const { return *geometry_->meshes[index]; }
    const std::vector<Light>& lights() const { return lights_; }
    const Phong& material(std::uint32_t object) const {
        return geometry_->materials[objects_[object].material];
    }
    Vec3 background() const { return background_; }
    // What a ray that hits nothing returns: the environment's radiance in its direction
    // (DESIGN §14), or the background colour where the scene has none.
    Vec3 missed(const Ray& ray) const {
        if (!environment_) return background_;
        return Vec3(environment_radiance(*environment_, glm::normalize(glm::dvec3(ray.direction))));
    }
    const Environment* environment() const { return environment_.get(); }
    Vec3 ambient() const { return ambient_; }
    const RenderSettings& settings() const { return settings_; }
    const std::shared_ptr<const SceneGeometry>& geometry() const { return geometry_; }
    const Accelerator& accelerator() const { return accel_; }
    double build_seconds() const {
        return build_seconds_;
    } // acceleration structures, meshes' included

    // Counts nodes visited and primitives tested by every query from now on (a little slower).
    void count_traversals(bool on) { counting_ = on; }
    TraversalCounters traversal_counts() const { return counters_.combine(std::plus<>()); }

  private:
    // The object's first hit in (0, t_max), counted only if the ray meets the object's box in
    // that interval (`box_tested`: the structure has checked that already; `slab`: the ray's).
    // shape_of(t_max, wanted): the shape's hit in object space (shape_of() or leaf_shape_hit).
    // `object`: an Object, or its copy in a BVH leaf (LeafObject). Wanted::any: a hit, not
    // always the first (the box check does not depend on which).
    template <class Placed, class ShapeOf>
    ShapeHit intersect_object(const Placed& object, const LazySlab& slab, Real t_max,
                              bool box_tested, const ShapeOf& shape_of,
                              Wanted wanted = Wanted::nearest) const;
    // The same without the box check: the shape's own intersection routine, on the ray in
    // object space (taken there by the object's transform, or its leaf copy's ToObject); a
    // mesh's with `wanted` (intersect_mesh), every other shape's whatever it is.
    template <class Counters>
    static ShapeHit intersect_shape(ShapeKind shape, const ShapeParams& params, const Ray& ray,
                                    Real t_max, Counters& counters, Wanted wanted);
    // intersect_shape for `object` on `ray` (taken to object space by its transform), as a
    // shape_of.
    template <class Counters>
    auto shape_of(const Object& object, const Ray& ray, Counters& counters) const;
    // What four of a leaf's objects from a slot on share, computed on first use and kept for
    // the leaf's next slots (leaf_shape_hit): the roots of its spheres placed without rotation
    // or shear (sphere_roots4), and where the ray crosses its cylinders (cylinder_crossings4).
    struct LeafLanes {
        std::uint32_t sphere_first = 0, sphere_end = 0; // the slots `roots` holds: none yet
        SphereRoots roots[4];
        std::uint32_t cylinder_first = 0, cylinder_end = 0; // and `crossings`
        CylinderCrossings crossings[4];
    };
    template <class Counters>
    ShapeHit leaf_shape_hit(std::uint32_t slot, const Ray& ray, Real t_max, LeafLanes& lanes,
                            Counters& counters, Wanted wanted) const;
    struct LeafObject;
    template <class Counters>
    ShapeHit other_leaf_shape_hit(const LeafObject& leaf, std::uint32_t slot, const Ray& ray,
                                  Real t_max, LeafLanes& lanes, Counters& counters,
                                  Wanted wanted) const;
    // The eight-wide BVH's leaf [begin, end) for one ray: visit(index, object, t_max, shape_of)
    // for each of its objects in slot order, until one returns true (then true).
    template <class Counters, class Visit>
    bool visit_leaf(const Ray& ray, std::uint32_t begin, std::uint32_t end, Real& t_max,
                    Counters& counters, Visit&& visit) const;
    // A closest-hit query: its best hit so far, and the tie rule (world.cpp), the same for a
    // single ray and a packet's.
    struct Closest {
        const Ray* ray = nullptr;
        LazySlab slab;
        std::uint32_t skip = kNoObject;
        Hit best;
    };
    // Starts `query` (t_max, skip set) on the unbounded objects; the limit for the structure.
    template <class Counters> Real begin_closest(Closest& query, Counters& counters) const;
    template <class Placed, class ShapeOf>
    void consider(Closest& query, std::uint32_t index, const Placed& object,
                  const ShapeOf& shape_of) const;
    // consider()'s two halves: the limit an object is tested up to, and the tie rule.
    static Real consider_limit(const Closest& query);
    static void keep(Closest& query, std::uint32_t index, const ShapeHit& h);
    // The bounded objects the ray may meet, through the structure: visit(index, object, t_max,
    // shape_of) as the structure's visitor (accel.h) with the object's shape_of; with the
    // eight-wide BVH, from leaf_objects_ (visit_leaf), nearest box first unless kNearestFirst is
    // false (WideBvh::traverse_leaves).
    template <bool kNearestFirst = true, class Counters, class Visit>
    void traverse(const Ray& ray, Real& t_max, Counters& counters, Visit&& visit) const;
    template <class Counters>
    Hit closest(const Ray& ray, Real t_max, std::uint32_t skip, Counters& counters) const;
    template <class Counters>
    void closest_packet(std::span<const Ray> rays, const std::uint32_t* skips, Hit* hits,
                        Counters& counters) const;
    // The list's part of closest_packet, after begin_closest: its objects in order, each for the
    // rays that meet its box; a mesh met by several rays takes them as a packet.
    template <class Counters>
    void closest_list_packet(const ItemList& list, std::span<const Ray> rays, Closest* query,
                             Counters& counters) const;
    // Whether object `object` (other than `skip`) is hit in (0, t_max) and `blocks` it.
    template <class Placed, class ShapeOf, class Blocks>
    bool blocks_ray(const LazySlab& slab, Real t_max, std::uint32_t skip, std::uint32_t index,
                    const Placed& object, bool box_tested, const ShapeOf& shape_of,
                    const Blocks& blocks) const;
    // Whether an object other than `skip` for which `blocks(object)` holds is hit in (0, t_max).
    template <class Counters, class Blocks>
    bool any(const Ray& ray, Real t_max, std::uint32_t skip, Counters& counters,
             const Blocks& blocks) const;
    // Whether `object` stops light (opaque_between's question); notes in `glass` when not.
    bool stops_light(std::uint32_t object, bool& glass) const {
        const bool stops = material(object).transmission == 0;
        glass |= !stops;
        return stops;
    }
    // any() for a packet; blocks(i, object) for ray i.
    template <class Counters, class Blocks>
    void any_packet(std::span<const Ray> rays, Real t_max, const std::uint32_t* skips, bool* found,
                    Counters& counters, const Blocks& blocks) const;
    // The list's part of any_packet for the rays `which` names (the unbounded objects asked
    // already), as closest_list_packet takes its objects.
    template <class Counters, class Blocks>
    void any_list_packet(const ItemList& list, std::span<const Ray> rays, Real t_max,
                         const std::uint32_t* skips, const LazySlab* slab, const int* which,
                         int count, bool* found, Counters& counters, const Blocks& blocks) const;

    // The camera-relative part: objects, lights and bounds; the structure is the caller's.
    struct CameraRelative {};
    World(const Scene& scene, std::shared_ptr<const SceneGeometry> geometry, CameraRelative);
    // The bounded objects' boxes, in item order (bounded_), for the top-level structure.
    std::vector<Bounds> item_bounds() const;

    std::shared_ptr<const SceneGeometry> geometry_;
    PinholeCamera camera_;
    std::vector<Object> objects_;
    std::vector<Light> lights_;
    Vec3 background_, ambient_;
    std::shared_ptr<const Environment> environment_;
    RenderSettings settings_;
    std::vector<std::uint32_t> unbounded_; // planes: tested by every ray
    std::vector<std::uint32_t> bounded_;   // accelerator item → object index
    Accelerator accel_;
    // With the eight-wide BVH, its leaves' objects in its slot order, so that the objects a leaf
    // names are adjacent in memory (empty for other structures): of objects_[index], what its
    // intersection reads (the ray's way to object space, the shape, the box a hit is checked
    // against), two thirds of an Object. Every object in the tree is bounded.
    struct LeafObject {
        ToObject to_object;
        std::uint32_t index;
        ShapeParams params;
        Bounds bounds;
        ShapeKind shape;
        bool sphere4; // a sphere placed without rotation or shear: its roots by sphere_roots4
        static constexpr bool bounded = true;
    };
    std::vector<LeafObject> leaf_objects_;
    // Beside leaf_objects_, their ways to object space again, in structure of arrays, so that a
    // leaf's spheres and cylinders are tested four at a time (leaf_shape_hit); the other shapes
    // take the ray there one at a time, by the copy's ToObject.
    ToObjectColumns leaf_to_object_;
    // Asks for what a leaf's first test reads (its first object's copy, and the spheres'
    // offsets and scales from its first slot), as soon as a ray's box test meets the leaf.
    void prefetch_leaf(std::uint32_t first) const {
        prefetch_bytes(&leaf_objects_[first], sizeof(LeafObject));
        for (int axis = 0; axis < 3; ++axis)
            __builtin_prefetch(leaf_to_object_.offset(axis, first));
        __builtin_prefetch(leaf_to_object_.inverse_scale(first));
    }
    void order_leaves();
    double build_seconds_ = 0;
    bool counting_ = false;
    mutable tbb::enumerable_thread_specific<TraversalCounters> counters_;
};

} // namespace GLINT_PRECISION
} // namespace glint
