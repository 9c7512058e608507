#include "trace/world.h"

#include "trace/stopwatch.h"

#include <cassert>
#include <cmath>

namespace glint {
inline namespace GLINT_PRECISION {
namespace {

// World bounds of M·(object bounds): the eight corners mapped in double, then widened by a few
// float ulps so that the float box still contains every point the float transform produces.
Bounds world_bounds(const std::pair<DVec3, DVec3>& local, const DMat4& m) {
    const auto [lo, hi] = transformed_box(local, m);
    const DVec3 pad = (glm::abs(lo) + glm::abs(hi) + (hi - lo)) * (8.0 * kUnitRoundoff);
    return {Vec3(lo - pad), Vec3(hi + pad)};
}

// Whether a shape's hit on `object` stands: a ray's hit counts only where the ray also meets the
// object's box within t_max (World::intersect_object says why), loosely, as the structures
// prune.
// `object`: an Object, or its BVH leaf copy.
template <class Placed>
bool within_box(const Placed& object, const ShapeHit& hit, const LazySlab& slab, Real t_max) {
    return !hit.found() || !object.bounded || slab.get().hits(object.bounds, loose(t_max));
}

// A packet's blocks(r, ·) for ray r, as any() takes it.
template <class Blocks> auto ray_blocks(const Blocks& blocks, std::size_t r) {
    return [&blocks, r](std::uint32_t object) { return blocks(r, object); };
}

// A shape's hit on object `index` as the World's Hit, or no hit.
Hit hit_on(std::uint32_t index, const ShapeHit& h) {
    return h.found() ? Hit{h.t, index, h.part, h.u, h.v} : Hit{};
}

} // namespace

SceneGeometry::SceneGeometry(const Scene& scene) : textures(scene.textures) {
    prepare_materials(scene);
    const Stopwatch watch;
    for (const TriangleMesh& mesh : scene.meshes)
        meshes.push_back(std::make_shared<const Mesh>(prepare_mesh(mesh)));
    build_seconds = watch.seconds();
}

SceneGeometry::SceneGeometry(const SceneGeometry& previous, const Scene& scene,
                             std::span<const std::uint32_t> moved)
    : meshes(previous.meshes), textures(scene.textures) {
    prepare_materials(scene);
    const Stopwatch watch;
    for (const std::uint32_t m : moved)
        meshes[m] = std::make_shared<const Mesh>(prepare_mesh(scene.meshes[m]));
    build_seconds = watch.seconds();
}

std::shared_ptr<const SceneGeometry>
SceneGeometry::posed(std::shared_ptr<const SceneGeometry> previous, const Scene& scene) {
    const std::vector<std::uint32_t> moving =
        scene.animation ? scene.animation->moving_meshes() : std::vector<std::uint32_t>();
    if (moving.empty()) return previous;
    return std::make_shared<const SceneGeometry>(*previous, scene, moving);
}

void SceneGeometry::prepare_materials(const Scene& scene) {
    const auto texture = [&](std::uint32_t index) {
        return index == kNoTexture ? nullptr : &textures[index];
    };
    for (const Material& m : scene.materials) {
        std::optional<CutOut> cut_out;
        if (m.cut_out || !m.double_sided)
            cut_out = CutOut{m.cut_out,
                             texture(m.alpha_texture != kNoTexture ? m.alpha_texture : m.texture),
                             m.alpha, m.alpha_cutoff, !m.double_sided};
        std::optional<Phong::MetalRough> metal_rough;
        if (const std::optional<MetalRoughInputs>& p = m.metal_rough)
            metal_rough = Phong::MetalRough{Vec3(p->base),
                                            p->metallic,
                                            p->roughness,
                                            p->transmission,
                                            p->occlusion_strength,
                                            p->coverage,
                                            texture(p->metal_rough_texture),
                                            texture(p->occlusion_texture)};
        materials.push_back({Vec3(m.ambient), Vec3(m.diffuse), Vec3(m.specular), m.shininess,
                             m.reflectivity, m.transmission, m.ior, m.checker.size,
                             Vec3(m.checker.diffuse), Vec3(m.checker.ambient), texture(m.texture),
                             cut_out, Vec3(m.emission), texture(m.emission_texture),
                             texture(m.normal_texture), m.normal_scale, metal_rough, m.unlit});
        transmissive |= m.transmission > 0;
        unlit |= m.unlit;
        secondary |= m.reflectivity > 0 || m.transmission > 0;
    }
}

World::World(const Scene& scene, std::shared_ptr<const SceneGeometry> geometry, CameraRelative)
    : geometry_(std::move(geometry)), camera_(scene.camera), background_(scene.background),
      ambient_(scene.ambient), environment_(scene.environment), settings_(scene.render) {
    // Camera-relative coordinates, composed in double: precision follows the scene's size, not
    // its distance from the world origin (docs/ARCHITECTURE.md, "Conventions": transforms).
    const DMat4 to_camera = translation_matrix(-scene.camera.eye);
    objects_.reserve(scene.objects.size());
    UnitBoxes unit_boxes(scene.meshes);
    for (const SceneObject& o : scene.objects) {
        const DMat4 m = to_camera * o.transform;
        const std::optional<ObjectBox> box = unit_boxes(o);
        // The shapes given by vertices are the ones with a mesh (SceneObject::mesh), and the
        // ones a material can cut out (their triangles have texture coordinates).
        const bool triangles = shape_traits(o.shape).keys.vertices;
        const std::optional<CutOut>& cut_out = geometry_->materials[o.material].cut_out;
        const ShapeParams params{o.top_radius, o.open,
                                 triangles ? geometry_->meshes[o.mesh].get() : nullptr,
                                 triangles && cut_out ? &*cut_out : nullptr};
        objects_.push_back({o.shape, make_transform(m), o.material, params, box.has_value(),
                            box ? world_bounds(*box, m) : Bounds{}});
    }
    for (const PointLight& light : scene.lights)
        lights_.push_back({Vec3(light.position - scene.camera.eye), Vec3(light.color)});
    for (std::uint32_t i = 0; i < objects_.size(); ++i)
        (objects_[i].bounded ? bounded_ : unbounded_).push_back(i);
}

std::vector<Bounds> World::item_bounds() const {
    std::vector<Bounds> boxes;
    boxes.reserve(bounded_.size());
    for (const std::uint32_t object : bounded_) boxes.push_back(objects_[object].bounds);
    return boxes;
}

World::World(const Scene& scene, std::optional<AccelKind> accel)
    : World(scene, std::make_shared<const SceneGeometry>(scene), accel) {
    build_seconds_ += geometry_->build_seconds;
}

World::World(const Scene& scene, std::shared_ptr<const SceneGeometry> geometry,
             std::optional<AccelKind> accel)
    : World(scene, std::move(geometry), CameraRelative{}) {
    const Stopwatch watch;
    const AccelKind kind =
        accel.value_or(bounded_.size() < kListBelow ? AccelKind::list : AccelKind::bvh);
    accel_ = Accelerator(kind, item_bounds());
    order_leaves();
    build_seconds_ = watch.seconds();
}

World::World(const Scene& scene, const World& previous)
    : World(scene, previous.geometry_, CameraRelative{}) {
    const Stopwatch watch;
    accel_ = previous.accel_.refitted(item_bounds());
    order_leaves();
    build_seconds_ = watch.seconds();
}

void World::order_leaves() {
    leaf_objects_.clear();
    const WideBvh* bvh = accel_.wide_bvh();
    if (!bvh) return;
    leaf_objects_.reserve(bvh->items().size());
    leaf_to_object_.assign(bvh->items().size());
    for (const std::uint32_t item : bvh->items()) {
        const Object& o = objects_[bounded_[item]];
        const std::size_t slot = leaf_objects_.size();
        leaf_to_object_.set(slot, o.transform);
        leaf_objects_.push_back({o.transform.to_object_part(), bounded_[item], o.params, o.bounds,
                                 o.shape,
                                 o.shape == ShapeKind::sphere && !leaf_to_object_.general(slot)});
    }
}

template <bool kNearestFirst, class Counters, class Visit>
void World::traverse(const Ray& ray, Real& t_max, Counters& counters, Visit&& visit) const {
    if (const WideBvh* bvh = accel_.wide_bvh()) {
        bvh->traverse_leaves<kNearestFirst>(
            ray, t_max, counters,
            [&](std::uint32_t begin, std::uint32_t end, Real& limit) {
                return visit_leaf(ray, begin, end, limit, counters, visit);
            },
            [this](std::uint32_t first) { prefetch_leaf(first); });
        return;
    }
    accel_.traverse(ray, t_max, counters, [&](std::uint32_t item, Real& limit) {
        const Object& object = objects_[bounded_[item]];
        return visit(bounded_[item], object, limit, shape_of(object, ray, counters));
    });
}

// A hit counts only when the ray meets the object's box within (0, t_max), as the list has
// always required by testing each box first. The hierarchies, which test larger boxes, check it
// here after a hit, so that every structure answers exactly the list's queries. It matters only
// for objects thinner than float resolves at their distance from the camera (a cone squashed to
// 1e-8 at 8 units, found by fuzz_scene): their object-space rays are noise, and their "hits" can
// lie far outside their box.
// Box tests against a limit use it widened by rounding (loose(), trace/math.h).

template <class Placed, class ShapeOf>
ShapeHit World::intersect_object(const Placed& object, const LazySlab& slab, Real t_max,
                                 bool box_tested, const ShapeOf& shape_of, Wanted wanted) const {
    const ShapeHit hit = shape_of(t_max, wanted);
    return box_tested || within_box(object, hit, slab, t_max) ? hit : ShapeHit{};
}

template <class Counters>
ShapeHit World::intersect_shape(ShapeKind shape, const ShapeParams& params, const Ray& ray,
                                Real t_max, Counters& counters, Wanted wanted) {
    if (shape == ShapeKind::mesh) // may stop early; every other shape has its one answer
        return intersect_mesh(*params.mesh, ray, t_max, counters, wanted, params.cut_out);
    return visit_shape(shape,
                       [&]<class S>(S) { return S::intersect(params, ray, t_max, counters); });
}

template <class Counters>
auto World::shape_of(const Object& object, const Ray& ray, Counters& counters) const {
    return [&object, &ray, &counters](Real t_max, Wanted wanted) {
        return intersect_shape(object.shape, object.params, object.transform.to_object(ray), t_max,
                               counters, wanted);
    };
}

// A leaf object's shape hit, the same as its own test's: a sphere placed without rotation or
// shear from the roots sphere_roots4 gives it and the leaf's next three slots, computed together
// on first use (LeafLanes); any other object in other_leaf_shape_hit.
template <class Counters>
ShapeHit World::leaf_shape_hit(std::uint32_t slot, const Ray& ray, Real t_max, LeafLanes& lanes,
                               Counters& counters, Wanted wanted) const {
    const LeafObject& leaf = leaf_objects_[slot];
    if (!leaf.sphere4) return other_leaf_shape_hit(leaf, slot, ray, t_max, lanes, counters, wanted);
    if (slot < lanes.sphere_first || slot >= lanes.sphere_end) {
        const ToObjectColumns& c = leaf_to_object_;
        sphere_roots4(ray, c.offset(0, slot), c.offset(1, slot), c.offset(2, slot),
                      c.inverse_scale(slot), lanes.roots);
        lanes.sphere_first = slot, lanes.sphere_end = slot + 4;
    }
    return sphere_hit(lanes.roots[slot - lanes.sphere_first], t_max);
}

// A cylinder from the crossings of it and the next three slots, computed together on first use
// (the ray taken to their four spaces by to_object4, then cylinder_crossings4); any other shape
// by its own test on the ray in its space. Out of line: inlined into leaf_shape_hit, it cost
// balls-4 (spheres only) 1.2% more instructions and rings-7 1.9% (callgrind, 320×180, ray mode).
template <class Counters>
[[gnu::noinline]] ShapeHit World::other_leaf_shape_hit(const LeafObject& leaf, std::uint32_t slot,
                                                       const Ray& ray, Real t_max, LeafLanes& lanes,
                                                       Counters& counters, Wanted wanted) const {
    if (leaf.shape == ShapeKind::cylinder) {
        if (slot < lanes.cylinder_first || slot >= lanes.cylinder_end) {
            Rays4 local;
            leaf_to_object_.to_object4(ray, slot, local);
            cylinder_crossings4(local, lanes.crossings);
            lanes.cylinder_first = slot, lanes.cylinder_end = slot + 4;
        }
        return cylinder_hit(lanes.crossings[slot - lanes.cylinder_first], t_max, leaf.params.open);
    }
    return intersect_shape(leaf.shape, leaf.params, leaf.to_object(ray), t_max, counters, wanted);
}

template <class Counters, class Visit>
bool World::visit_leaf(const Ray& ray, std::uint32_t begin, std::uint32_t end, Real& t_max,
                       Counters& counters, Visit&& visit) const {
    LeafLanes lanes;
    for (std::uint32_t slot = begin; slot < end; ++slot) {
        counters.primitive();
        const LeafObject& leaf = leaf_objects_[slot];
        const auto shape = [&, slot](Real limit, Wanted wanted) {
            return leaf_shape_hit(slot, ray, limit, lanes, counters, wanted);
        };
        if (visit(leaf.index, leaf, t_max, shape)) return true;
    }
    return false;
}

// Ties: on equal t the lower object index wins, whatever order a structure visits objects in,
// so every structure returns exactly the list's hit. Each object is therefore tested up to the
// next float above the best t, and an equal t replaces the best only from a lower index.
Real World::consider_limit(const Closest& query) {
    const Hit& best = query.best;
    return best.found() ? std::nextafter(best.t, kInfinity) : best.t;
}

void World::keep(Closest& query, std::uint32_t index, const ShapeHit& h) {
    Hit& best = query.best;
    if (h.t < best.t || (h.t == best.t && best.found() && index < best.object))
        best = {h.t, index, h.part, h.u, h.v};
}

template <class Placed, class ShapeOf>
void World::consider(Closest& query, std::uint32_t index, const Placed& object,
                     const ShapeOf& shape_of) const {
    if (index == query.skip) return;
    const bool boxes_tested = accel_.kind() == AccelKind::list; // each item's box, first
    keep(query, index,
         intersect_object(object, query.slab, consider_limit(query), boxes_tested, shape_of));
}

// Let the structure prune only beyond the best hit, loosely: ties at best.t must still be seen.
template <class Counters> Real World::begin_closest(Closest& query, Counters& counters) const {
    for (const std::uint32_t object : unbounded_)
        counters.primitive(), consider(query, object, objects_[object],
                                       shape_of(objects_[object], *query.ray, counters));
    return loose(query.best.t);
}

template <class Counters>
Hit World::closest(const Ray& ray, Real t_max, std::uint32_t skip, Counters& counters) const {
    Closest query{&ray, LazySlab(ray), skip, {}};
    query.best.t = t_max;
    Real limit = begin_closest(query, counters);
    traverse(ray, limit, counters,
             [&](std::uint32_t index, const auto& object, Real& t_limit, const auto& shape) {
                 consider(query, index, object, shape);
                 t_limit = loose(query.best.t);
                 return false;
             });
    return query.best;
}

template <class Counters>
void World::closest_packet(std::span<const Ray> rays, const std::uint32_t* skips, Hit* hits,
                           Counters& counters) const {
    assert(rays.size() <= kMaxPacket);
    const auto skip = [&](std::size_t r) { return skips ? skips[r] : kNoObject; };
    const WideBvh* bvh = accel_.wide_bvh();
    const ItemList* list = accel_.item_list();
    if (!bvh && !list) {
        for (std::size_t r = 0; r < rays.size(); ++r)
            hits[r] = closest(rays[r], kInfinity, skip(r), counters);
        return;
    }
    Closest query[kMaxPacket];
    Real limit[kMaxPacket] = {};
    for (std::size_t r = 0; r < rays.size(); ++r) {
        query[r] = {&rays[r], LazySlab(rays[r]), skip(r), {}};
        limit[r] = begin_closest(query[r], counters);
    }
    if (list) {
        closest_list_packet(*list, rays, query, counters);
        for (std::size_t r = 0; r < rays.size(); ++r) hits[r] = query[r].best;
        return;
    }
    bvh->traverse_packet(
        rays.data(), static_cast<int>(rays.size()), limit, counters,
        [&](int r, std::uint32_t begin, std::uint32_t end, Real& t_limit) {
            visit_leaf(rays[r], begin, end, t_limit, counters,
                       [&](std::uint32_t index, const auto& object, Real&, const auto& shape) {
                           consider(query[r], index, object, shape);
                           return false;
                       });
            t_limit = loose(query[r].best.t);
            return false;
        },
        [this](std::uint32_t first) { prefetch_leaf(first); });
    for (std::size_t r = 0; r < rays.size(); ++r) hits[r] = query[r].best;
}

// Each ray meets the list's objects in the list's order, its box tests and its limits its own
// (ItemList::traverse, closest()'s visitor): only the order across rays is the packet's, and a
// mesh's test, which intersect_mesh_packet answers for each ray as intersect_mesh would.
template <class Counters>
void World::closest_list_packet(const ItemList& list, std::span<const Ray> rays, Closest* query,
                                Counters& counters) const {
    const int count = static_cast<int>(rays.size());
    for (std::uint32_t item = 0; item < list.bounds.size(); ++item) {
        const std::uint32_t index = bounded_[item];
        const Object& object = objects_[index];
        int met[kMaxPacket], n = 0; // the rays whose test the object is
        for (int r = 0; r < count; ++r) {
            counters.node();
            if (!query[r].slab.get().hits(list.bounds[item], loose(query[r].best.t))) continue;
            counters.primitive();
            if (index != query[r].skip) met[n++] = r;
        }
        if (object.shape == ShapeKind::mesh && n > 1) {
            Ray local[kMaxPacket];
            Real limit[kMaxPacket];
            ShapeHit found[kMaxPacket];
            for (int k = 0; k < n; ++k)
                local[k] = object.transform.to_object(rays[met[k]]),
                limit[k] = consider_limit(query[met[k]]);
            intersect_mesh_packet(*object.params.mesh, local, n, limit, found, counters,
                                  Wanted::nearest, object.params.cut_out);
            for (int k = 0; k < n; ++k) keep(query[met[k]], index, found[k]);
        } else {
            for (int k = 0; k < n; ++k)
                consider(query[met[k]], index, object, shape_of(object, rays[met[k]], counters));
        }
    }
}

template <class Placed, class ShapeOf, class Blocks>
bool World::blocks_ray(const LazySlab& slab, Real t_max, std::uint32_t skip, std::uint32_t index,
                       const Placed& object, bool box_tested, const ShapeOf& shape_of,
                       const Blocks& blocks) const {
    return index != skip &&
           intersect_object(object, slab, t_max, box_tested, shape_of, Wanted::any).found() &&
           blocks(index);
}

template <class Counters, class Blocks>
bool World::any(const Ray& ray, Real t_max, std::uint32_t skip, Counters& counters,
                const Blocks& blocks) const {
    const LazySlab slab(ray);
    const bool boxes_tested = accel_.kind() == AccelKind::list; // each item's box, first
    for (const std::uint32_t object : unbounded_) {
        counters.primitive();
        if (blocks_ray(slab, t_max, skip, object, objects_[object], false,
                       shape_of(objects_[object], ray, counters), blocks))
            return true;
    }
    bool found = false;
    // Boxes loosely, as intersect_object checks them after a hit: the list, testing each box
    // first against t_max itself, missed an occluder whose box entry rounded just beyond the
    // end of a shadow ray 2e9 long, which the BVH counted (fuzz_nff).
    // Any blocker will do: each node's children are taken unsorted.
    Real limit = loose(t_max);
    traverse<false>(ray, limit, counters,
                    [&](std::uint32_t index, const auto& object, Real&, const auto& shape) {
                        found = blocks_ray(slab, t_max, skip, index, object, boxes_tested, shape,
                                           blocks);
                        return found;
                    });
    return found;
}

template <class Counters, class Blocks>
void World::any_packet(std::span<const Ray> rays, Real t_max, const std::uint32_t* skips,
                       bool* found, Counters& counters, const Blocks& blocks) const {
    assert(rays.size() <= kMaxPacket);
    const WideBvh* bvh = accel_.wide_bvh();
    const ItemList* list = accel_.item_list();
    if (!bvh && !list) {
        for (std::size_t r = 0; r < rays.size(); ++r)
            found[r] = any(rays[r], t_max, skips[r], counters, ray_blocks(blocks, r));
        return;
    }
    // The unbounded objects ray by ray; the rays they leave unanswered go through the structure.
    LazySlab slab[kMaxPacket];
    Ray pending[kMaxPacket];
    Real limit[kMaxPacket];
    int which[kMaxPacket], count = 0;
    for (std::size_t r = 0; r < rays.size(); ++r) {
        slab[r] = LazySlab(rays[r]);
        found[r] = false;
        for (const std::uint32_t object : unbounded_) {
            counters.primitive();
            if ((found[r] = blocks_ray(slab[r], t_max, skips[r], object, objects_[object], false,
                                       shape_of(objects_[object], rays[r], counters),
                                       ray_blocks(blocks, r))))
                break;
        }
        if (found[r]) continue;
        which[count] = static_cast<int>(r);
        pending[count] = rays[r];
        limit[count++] = loose(t_max);
    }
    if (list)
        return any_list_packet(*list, rays, t_max, skips, slab, which, count, found, counters,
                               blocks);
    bvh->traverse_packet<false>( // any blocker will do: each node's children unsorted
        pending, count, limit, counters,
        [&](int k, std::uint32_t begin, std::uint32_t end, Real& limit) {
            const int r = which[k];
            return found[r] = visit_leaf(
                       rays[r], begin, end, limit, counters,
                       [&](std::uint32_t index, const auto& object, Real&, const auto& shape) {
                           return blocks_ray(slab[r], t_max, skips[r], index, object, false, shape,
                                             ray_blocks(blocks, r));
                       });
        },
        [this](std::uint32_t first) { prefetch_leaf(first); });
}

// As closest_list_packet: each ray's own box tests, against loose(t_max) as any() makes them,
// and its own tests in the list's order until one blocks it.
template <class Counters, class Blocks>
void World::any_list_packet(const ItemList& list, std::span<const Ray> rays, Real t_max,
                            const std::uint32_t* skips, const LazySlab* slab, const int* which,
                            int count, bool* found, Counters& counters,
                            const Blocks& blocks) const {
    const Real box_limit = loose(t_max);
    int left = count; // rays not yet blocked
    for (std::uint32_t item = 0; item < list.bounds.size() && left > 0; ++item) {
        const std::uint32_t index = bounded_[item];
        const Object& object = objects_[index];
        int met[kMaxPacket], n = 0;
        for (int k = 0; k < count; ++k) {
            const int r = which[k];
            if (found[r]) continue;
            counters.node();
            if (!slab[r].get().hits(list.bounds[item], box_limit)) continue;
            counters.primitive();
            if (index != skips[r]) met[n++] = r;
        }
        if (object.shape == ShapeKind::mesh && n > 1) {
            Ray local[kMaxPacket];
            Real limit[kMaxPacket];
            ShapeHit hit[kMaxPacket];
            for (int k = 0; k < n; ++k)
                local[k] = object.transform.to_object(rays[met[k]]), limit[k] = t_max;
            intersect_mesh_packet(*object.params.mesh, local, n, limit, hit, counters, Wanted::any,
                                  object.params.cut_out);
            for (int k = 0; k < n; ++k)
                found[met[k]] = hit[k].found() && blocks(static_cast<std::size_t>(met[k]), index);
        } else {
            for (int k = 0; k < n; ++k) {
                const auto r = static_cast<std::size_t>(met[k]);
                found[r] = blocks_ray(slab[r], t_max, skips[r], index, object, true,
                                      shape_of(object, rays[r], counters), ray_blocks(blocks, r));
            }
        }
        for (int k = 0; k < n; ++k) left -= found[met[k]];
    }
}

Hit World::intersect(const Ray& ray, Real t_max, std::uint32_t skip) const {
    if (counting_) return closest(ray, t_max, skip, counters_.local());
    NoCounters none;
    return closest(ray, t_max, skip, none);
}

bool World::occluded(const Ray& ray, Real t_max, std::uint32_t skip) const {
    const auto every = [](std::uint32_t) { return true; };
    if (counting_) return any(ray, t_max, skip, counters_.local(), every);
    NoCounters none;
    return any(ray, t_max, skip, none, every);
}

bool World::opaque_between(const Ray& ray, Real t_max, std::uint32_t skip,
                           bool& transmissive) const {
    transmissive = false;
    const auto blocks = [&](std::uint32_t object) { return stops_light(object, transmissive); };
    if (counting_) return any(ray, t_max, skip, counters_.local(), blocks);
    NoCounters none;
    return any(ray, t_max, skip, none, blocks);
}

void World::intersect_packet(std::span<const Ray> rays, Hit* hits,
                             const std::uint32_t* skips) const {
    if (counting_) return closest_packet(rays, skips, hits, counters_.local());
    NoCounters none;
    closest_packet(rays, skips, hits, none);
}

void World::occluded_packet(std::span<const Ray> rays, Real t_max, const std::uint32_t* skips,
                            bool* occluded) const {
    const auto every = [](std::size_t, std::uint32_t) { return true; };
    if (counting_) return any_packet(rays, t_max, skips, occluded, counters_.local(), every);
    NoCounters none;
    any_packet(rays, t_max, skips, occluded, none, every);
}

void World::opaque_between_packet(std::span<const Ray> rays, Real t_max, const std::uint32_t* skips,
                                  bool* opaque, bool* transmissive) const {
    std::fill_n(transmissive, rays.size(), false);
    const auto blocks = [&](std::size_t r, std::uint32_t object) {
        return stops_light(object, transmissive[r]);
    };
    if (counting_) return any_packet(rays, t_max, skips, opaque, counters_.local(), blocks);
    NoCounters none;
    any_packet(rays, t_max, skips, opaque, none, blocks);
}

Hit World::intersect_one(std::uint32_t object, const Ray& ray, Real t_max) const {
    NoCounters none;
    return hit_on(object, intersect_object(objects_[object], LazySlab(ray), t_max, false,
                                           shape_of(objects_[object], ray, none)));
}

void World::intersect_one_packet(std::uint32_t index, std::span<const Ray> rays, Hit* hits) const {
    assert(rays.size() <= kMaxPacket);
    const Object& object = objects_[index];
    if (object.shape != ShapeKind::mesh) {
        for (std::size_t r = 0; r < rays.size(); ++r) hits[r] = intersect_one(index, rays[r]);
        return;
    }
    // intersect_one's steps for each ray (intersect_object: the shape in object space, then the
    // box check after a hit), with the mesh's part taken by the packet.
    const int count = static_cast<int>(rays.size());
    Ray local[kMaxPacket] = {};
    Real t_max[kMaxPacket] = {};
    ShapeHit found[kMaxPacket];
    for (int r = 0; r < count; ++r)
        local[r] = object.transform.to_object(rays[r]), t_max[r] = kInfinity;
    NoCounters none;
    intersect_mesh_packet(*object.params.mesh, local, count, t_max, found, none, Wanted::nearest,
                          object.params.cut_out);
    for (int r = 0; r < count; ++r)
        hits[r] = within_box(object, found[r], LazySlab(rays[r]), t_max[r])
                      ? hit_on(index, found[r])
                      : Hit{};
}

namespace {

// A normal map's normal at a mesh hit (glTF 2.0 §3.9.3): the texel (each channel 2c − 1, x and y
// × the scale) in the tangent frame of the outward shading normal `n` (world), with the tangent
// the mesh's (interpolated) or, without one, the triangle's direction of increasing u, and the
// bitangent n × t × w, w = the tangent's sign (for a computed one, so that it points towards
// decreasing v: up the image). Tangent and bitangent are made in object space (`object_normal`,
// the shape's) and taken to the world as directions, so that a mirroring M keeps the frame's
// handedness; the tangent is then made orthogonal to n. Where the frame degenerates (no u
// direction on the triangle), n itself.
Vec3 normal_mapped(const Mesh& mesh, const Phong& material, const Hit& hit, const Transform& m,
                   Vec3 object_normal, Vec3 n) {
    const glm::uvec3 tri = mesh.triangles[hit.primitive];
    const Real b1 = hit.u, b2 = hit.v, b0 = 1 - b1 - b2;
    Vec3 tangent;
    Real sign;
    if (!mesh.tangents.empty()) {
        const glm::vec4 &t0 = mesh.tangents[tri.x], &t1 = mesh.tangents[tri.y],
                        &t2 = mesh.tangents[tri.z];
        tangent = b0 * Vec3(t0) + b1 * Vec3(t1) + b2 * Vec3(t2);
        sign = t0.w < 0 ? -1 : 1;
    } else {
        const Vec3 dp1 = mesh.vertices[tri.y] - mesh.vertices[tri.x];
        const Vec3 dp2 = mesh.vertices[tri.z] - mesh.vertices[tri.x];
        const std::vector<glm::vec2>& uvs = mesh_uvs(mesh, material.normal_texture->set);
        const glm::vec2 duv1 = uvs[tri.y] - uvs[tri.x];
        const glm::vec2 duv2 = uvs[tri.z] - uvs[tri.x];
        const Real det = Real(duv1.x) * duv2.y - Real(duv2.x) * duv1.y;
        if (det == 0) return n;
        tangent = (dp1 * Real(duv2.y) - dp2 * Real(duv1.y)) / det;
        const Vec3 towards_v = (dp2 * Real(duv1.x) - dp1 * Real(duv2.x)) / det;
        sign = glm::dot(glm::cross(object_normal, tangent), towards_v) < 0 ? 1 : -1;
    }
    const Vec3 bitangent = glm::cross(object_normal, tangent) * sign;
    Vec3 t = m.linear * tangent;
    Vec3 b = m.linear * bitangent;
    t -= n * glm::dot(n, t);
    b -= n * glm::dot(n, b);
    const Real tl = glm::length(t), bl = glm::length(b);
    if (!(tl > 0) || !(bl > 0) || !std::isfinite(tl) || !std::isfinite(bl)) return n;
    const glm::vec2 uv = mesh_uv(mesh, hit.primitive, hit.u, hit.v, material.normal_texture->set);
    const Vec3 texel(sample_texture(*material.normal_texture, uv).colour);
    const Vec3 c = 2.0_r * texel - 1.0_r;
    const Vec3 mapped =
        (t / tl) * (c.x * material.normal_scale) + (b / bl) * (c.y * material.normal_scale) + n * c.z;
    const Real length = glm::length(mapped);
    return length > 0 && std::isfinite(length) ? mapped / length : n;
}

} // namespace

SurfacePoint World::surface(const Ray& ray, const Hit& hit) const {
    const Object& object = objects_[hit.object];
    const Transform& m = object.transform;
    const Ray local = m.to_object(ray);
    const Vec3 p = local.origin + hit.t * local.direction;
    const SurfaceSample s =
        visit_shape(object.shape, [&]<class S>(S) { return S::surface(object.params, p, hit); });
    Vec3 normal = m.normal_to_world(s.normal);
    const bool from_inside = glm::dot(normal, ray.direction) > 0;
    if (from_inside) normal = -normal;
    // A vertex normal is flipped with the facet, so that it points to the same side; where
    // interpolation cancels it out (opposed vertex normals), the facet normal stands in.
    Vec3 shading = normal;
    if (s.shading != Vec3(0.0_r)) {
        const Vec3 smooth = m.normal_to_world(s.shading);
        const Real length = glm::length(smooth);
        if (length > 0 && std::isfinite(length))
            shading = (from_inside ? -smooth : smooth) / length;
    }
    const Phong& material = geometry_->materials[object.material];
    if (material.normal_texture && object.params.mesh &&
        !mesh_uvs(*object.params.mesh, material.normal_texture->set).empty()) {
        const Vec3 outward = normal_mapped(*object.params.mesh, material, hit, m,
                                           s.shading != Vec3(0.0_r) ? s.shading : s.normal,
                                           from_inside ? -shading : shading);
        shading = from_inside ? -outward : outward;
    }
    // A convex solid lies behind the tangent plane at every surface point, and a planar shape in
    // it: a ray leaving on the normal's side cannot meet the object again, so it skips the
    // object instead of stepping off it. No offset is needed then, and none can be too large
    // for a small neighbour (a millimetre sphere on a kilometre floor, where the offset below
    // would be 2e-3). A ray going on through the surface leaves a planar shape the same way, and
    // a convex solid it was inside of (the solid lies behind the tangent plane it crosses); into
    // a solid it must still find the far wall, so it steps off instead.
    const ShapeTraits& traits = shape_traits(object.shape);
    SurfacePoint point{m.point_to_world(s.point), normal, shading, 0.0_r};
    point.entering = !from_inside;
    point.object_point = p;
    point.object_normal = s.normal;
    if (traits.planar || (traits.convex && !from_inside)) point.skip = hit.object;
    if (traits.planar || (traits.convex && from_inside)) point.skip_through = hit.object;
    const bool through = material.transmission > 0;
    if (point.skip != kNoObject && (!through || point.skip_through != kNoObject)) return point;
    // Spawn offset (Wächter & Binder, Ray Tracing Gems ch. 6; pbrt-v4's OffsetRayOrigin): a new
    // ray from this point is intersected with this object after mapping back by M⁻¹, so it must
    // leave the object-space error box of the point: its extent along the object normal is
    // |n|·error (surface projection + float round trip, see roundtrip_error). Moving δ along the
    // world normal moves the object point δ·|M⁻ᵀn| along n, hence δ = |n|·error / |M⁻ᵀn|, to
    // either side. Twice that keeps the sign of the next intersection's near root (c = |o|² − 1
    // for spheres, o − 1 for box faces) clear of its own rounding.
    const Vec3 error = m.roundtrip_error(s.point, s.error);
    point.offset = 2.0_r * glm::dot(glm::abs(s.normal), error) / m.normal_stretch(s.normal);
    return point;
}

} // namespace GLINT_PRECISION
} // namespace glint
