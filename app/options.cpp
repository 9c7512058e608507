#include "app/options.h"

#include "trace/scene_loader.h"

#include <iostream>
#include <regex>

namespace glint {

namespace fs = std::filesystem;

void SceneOptions::add_to(CLI::App& cmd) {
    cmd.add_option("scene", scene, "Scene file (JSON); default scenes/default.json");
    cmd.add_option("--size", size, "Image size WIDTHxHEIGHT, overriding the scene's camera");
    cmd.add_option("--accel", accel,
                   "Acceleration structure: bvh, spheres, grid, kd or list; auto: list below 16 "
                   "objects, else bvh")
        ->capture_default_str()
        ->check(CLI::IsMember({"auto", "bvh", "spheres", "grid", "kd", "list"}));
    max_depth_option =
        cmd.add_option("--max-depth", max_depth, "Maximum reflection depth (0 = none)")
            ->check(CLI::Range(0, kMaxDepth));
    min_reflectivity_option =
        cmd.add_option("--min-reflectivity", min_reflectivity,
                       "Smallest path weight for which a reflection ray is still cast")
            ->check(CLI::Range(0.0, 1.0));
}

fs::path SceneOptions::scene_path() const {
    if (!scene.empty()) return scene;
    const fs::path local = "scenes/default.json";
    if (fs::exists(local)) return local;
    return fs::path(GLINT_SOURCE_DIR) / local; // glint run from outside its checkout
}

Scene SceneOptions::load() const {
    Scene loaded = load_scene(scene_path());
    if (!size.empty()) {
        static const std::regex size_pattern(R"((\d{1,5})x(\d{1,5}))");
        std::smatch m;
        if (!std::regex_match(size, m, size_pattern))
            throw UsageError("--size " + size + ": expected WIDTHxHEIGHT, e.g. 800x600");
        const int w = std::stoi(m[1]), h = std::stoi(m[2]);
        if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide)
            throw UsageError("--size " + size + ": each side must be 1 to " +
                             std::to_string(kMaxImageSide));
        loaded.camera.width = w, loaded.camera.height = h;
    }
    if (max_depth_option->count()) loaded.render.max_depth = max_depth;
    if (min_reflectivity_option->count())
        loaded.render.min_reflectivity = static_cast<float>(min_reflectivity);
    return loaded;
}

std::optional<AccelKind> SceneOptions::accel_kind() const {
    return accel_from_name(accel);
}

void FrameOptions::add_to(CLI::App& cmd, bool with_mode) {
    if (with_mode)
        cmd.add_option("--mode", mode, "Primary visibility: hybrid (item buffer) or ray")
            ->capture_default_str()
            ->check(CLI::IsMember({"hybrid", "ray"}));
    cmd.add_option("--gl", gl, "Headless GL for the item buffer: osmesa or egl")
        ->capture_default_str()
        ->check(CLI::IsMember({"osmesa", "egl"}));
    cmd.add_option("--raster", raster,
                   "Item buffer: mesh (tessellated) or proxy (exact, per-fragment)")
        ->capture_default_str()
        ->check(CLI::IsMember({"mesh", "proxy"}));
    cmd.add_option("--tess", tessellation, "Segments around curved outlines in mesh mode")
        ->capture_default_str()
        ->check(CLI::Range(kMinTessellation, kMaxTessellation));
    cmd.add_option("--resolve", resolve,
                   "exact: check the interval tessellation leaves uncertain; trust: take the item "
                   "buffer's word")
        ->capture_default_str()
        ->check(CLI::IsMember({"exact", "trust"}));
    cmd.add_option("--threads", threads, "Worker threads; default all cores")
        ->check(CLI::Range(1, 1024));
}

FrameSettings FrameOptions::settings() const {
    return {mode == "ray" ? Mode::ray : Mode::hybrid,
            gl == "egl" ? GlBackend::egl : GlBackend::osmesa,
            raster == "proxy" ? RasterMode::proxy : RasterMode::mesh,
            tessellation,
            resolve == "trust" ? Resolve::trust : Resolve::exact,
            threads};
}

std::string FrameOptions::describe() const {
    if (mode == "ray") return "ray";
    return "hybrid (" + gl + ", " + raster +
           (raster == "mesh" ? " tess " + std::to_string(tessellation) : "") + ", " + resolve + ")";
}

void check_output(const fs::path& path, const std::string& flag) {
    const fs::path dir = path.has_parent_path() ? path.parent_path() : ".";
    if (!fs::is_directory(dir))
        throw UsageError(flag + " " + path.string() + ": directory " + dir.string() +
                         " does not exist");
    if (fs::is_directory(path)) throw UsageError(flag + " " + path.string() + ": is a directory");
}

int guarded(const std::function<int()>& body) {
    try {
        return body();
    } catch (const UsageError& e) {
        std::cerr << "glint: error: " << e.what() << "\n";
        return 2;
    } catch (const SceneError& e) {
        std::cerr << "glint: error: " << e.what() << "\n";
        return 2;
    } catch (const GlError& e) {
        std::cerr << "glint: error: no OpenGL for the item buffer: " << e.what()
                  << "\nglint: render without GL with --mode ray\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "glint: error: " << e.what() << "\n";
        return 1;
    }
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace glint
