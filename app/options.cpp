#include "app/options.h"

#include "io/environment_file.h"

#include "io/load_scene.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <regex>

#include <sys/resource.h>
#include <unistd.h>

namespace glint {

namespace fs = std::filesystem;

void SceneOptions::add_to(CLI::App& cmd) {
    cmd.add_option("scene", scene,
                   "Scene file: JSON (.json), NFF (.nff), or a model: OBJ (.obj), glTF (.gltf, "
                   ".glb); default scenes/default.json");
    camera_option = cmd.add_option("--camera", camera,
                                   "glTF: look through the file's camera N (default: its first)")
                        ->check(CLI::NonNegativeNumber);
    cmd.add_option("--size", size, "Image size WIDTHxHEIGHT, overriding the scene's camera");
    time_option = cmd.add_option("--time", time,
                                 "glTF: place the model's nodes at T seconds of its animation "
                                 "(a sequence's first frame; default: the nodes as the file "
                                 "places them)");
    animation_option =
        cmd.add_option("--animation", animation,
                       "glTF: which of the file's animations --time and --frames play (default 0)");
    cmd.add_option("--framing", framing,
                   "A model without a camera of its own: frame it from the front (head-on down "
                   "-Z, a glTF's default) or three-quarter (above and to the right, an OBJ's "
                   "default)")
        ->check(CLI::IsMember(all_names<ModelView>()));
    cmd.add_option("--environment", environment,
                   "What rays that leave the scene return: an equirectangular .hdr or .exr file "
                   "(linear radiance), studio (built in: a neutral room with soft lights), or "
                   "none (the background colour); default: the scene's own, else none");
    render.add_to(cmd);
}

void RenderOptions::add_to(CLI::App& cmd) {
    accel_option =
        cmd.add_option("--accel", accel,
                       "Acceleration structure: bvh (8-wide, SIMD), bvh2 (binary), spheres, grid, "
                       "kd or list; auto: list below 16 objects, else bvh")
            ->capture_default_str()
            ->check(CLI::IsMember([] {
                std::vector<std::string> names = all_names<AccelKind>();
                names.insert(names.begin(), "auto");
                return names;
            }()));
    max_depth_option =
        cmd.add_option("--max-depth", max_depth, "Maximum reflection depth (0 = none)")
            ->check(CLI::Range(0, kMaxDepth));
    min_reflectivity_option =
        cmd.add_option("--min-reflectivity", min_reflectivity,
                       "Smallest path weight for which a reflection ray is still cast")
            ->check(CLI::Range(0.0, 1.0));
    samples_option = cmd.add_option("--samples", samples,
                                    "Antialiasing: an NxN grid of samples in every pixel "
                                    "(1 to 16), overriding the scene's render.samples")
                         ->check(CLI::Range(1, kMaxSamples));
    cmd.add_option("--aa", antialias,
                   "uniform: every pixel's grid; adaptive: the grid only where the adaptive rule "
                   "finds an edge (docs/ANTIALIASING.md); default the scene's")
        ->check(CLI::IsMember(all_names<Antialias>()));
    aa_threshold_option =
        cmd.add_option("--aa-threshold", aa_threshold,
                       "Adaptive: the largest colour difference (0 to 1, per channel) between "
                       "neighbours' first samples that leaves a pixel unrefined")
            ->check(CLI::Range(0.0, 1.0));
    packet_levels_option =
        cmd.add_option("--packet-levels", packet_levels,
                       "Secondary rays in packets: cast the first N levels of each tile's "
                       "reflected and transmitted rays ahead, 16 to a packet in the bvh. The image "
                       "is the same for any N; on SPD's scenes one level was within 3% of none "
                       "either way (docs/PERFORMANCE.md)")
            ->capture_default_str()
            ->check(CLI::Range(0, kMaxDepth));
}

void RenderOptions::apply(Scene& scene) const {
    RenderSettings& render = scene.render;
    if (max_depth_option->count()) render.max_depth = max_depth;
    if (min_reflectivity_option->count())
        render.min_reflectivity = static_cast<float>(min_reflectivity);
    if (samples_option->count()) render.samples = samples;
    if (!antialias.empty()) render.antialias = *from_name<Antialias>(antialias);
    if (aa_threshold_option->count()) render.aa_threshold = aa_threshold;
    if (packet_levels_option->count()) render.packet_levels = packet_levels;
}

std::optional<AccelKind> RenderOptions::accel_kind() const {
    return from_name<AccelKind>(accel);
}

fs::path SceneOptions::scene_path() const {
    if (!scene.empty()) return scene;
    const fs::path local = "scenes/default.json";
    if (fs::exists(local)) return local;
    return fs::path(GLINT_SOURCE_DIR) / local; // glint run from outside its checkout
}

Scene SceneOptions::load() const {
    ModelOptions model;
    if (camera_option->count()) model.camera = camera;
    if (!size.empty()) model.size = parse_size(size, "--size");
    if (time_option->count() && !(time >= 0 && time <= 1e9))
        throw UsageError("--time " + time_option->as<std::string>() +
                         ": must be 0 or more seconds (at most 1e9)");
    if (animation_option->count() && animation < 0)
        throw UsageError("--animation " + std::to_string(animation) + ": must be 0 or more");
    if (time_option->count() || animation_option->count() || animate || animate_if_any)
        model.time = time;
    model.quiet_without_animation =
        animate_if_any && !time_option->count() && !animation_option->count();
    model.animation = animation;
    model.srgb = srgb;
    if (!framing.empty()) model.view = from_name<ModelView>(framing);
    Scene loaded = preloaded ? *preloaded : load_scene_with_notes(scene_path(), model);
    render.apply(loaded);
    if (environment == kNoEnvironment)
        loaded.environment = nullptr;
    else if (!environment.empty())
        try { // a flag's value: bad usage, as --size's is
            loaded.environment = load_environment(environment, fs::current_path(), "--environment");
        } catch (const SceneError& e) {
            throw UsageError(e.what());
        }
    return loaded;
}

void FrameOptions::add_to(CLI::App& cmd, bool with_mode, bool with_gl) {
    if (with_mode)
        cmd.add_option("--mode", mode, "Primary visibility: hybrid (item buffer) or ray")
            ->capture_default_str()
            ->check(CLI::IsMember(all_names<Mode>()));
    if (with_gl)
        cmd.add_option("--gl", gl, "Headless GL for the item buffer: osmesa or egl")
            ->capture_default_str()
            ->check(CLI::IsMember(all_names<GlBackend>()));
    cmd.add_option("--raster", raster,
                   "Item buffer: mesh (tessellated), proxy (exact, per-fragment) or auto (per "
                   "object, whichever the cost model says draws faster)")
        ->capture_default_str()
        ->check(CLI::IsMember(all_names<RasterMode>()));
    cmd.add_option("--tess", tessellation, "Segments around curved outlines in mesh mode")
        ->capture_default_str()
        ->check(CLI::Range(kMinTessellation, kMaxTessellation));
    cmd.add_option("--resolve", resolve,
                   "exact: check the interval tessellation leaves uncertain; trust: take the item "
                   "buffer's word")
        ->capture_default_str()
        ->check(CLI::IsMember(all_names<Resolve>()));
    cmd.add_option("--threads", threads, "Worker threads; default all cores")
        ->check(CLI::Range(1, 1024));
    cmd.add_flag("--aa-sample-ids", aa_sample_ids,
                 "Adaptive antialiasing in hybrid mode: also refine pixels whose NxN item-buffer "
                 "samples name more than one object (finds objects thinner than a pixel; draws "
                 "the NxN item buffer, and the image may then differ from ray mode's)");
}

FrameSettings FrameOptions::settings() const {
    FrameSettings s; // the options' checks admit only these names
    s.mode = *from_name<Mode>(mode);
    s.gl = *from_name<GlBackend>(gl);
    s.raster = *from_name<RasterMode>(raster);
    s.tessellation = tessellation;
    s.resolve = *from_name<Resolve>(resolve);
    s.threads = threads;
    s.aa_sample_ids = aa_sample_ids;
    if (s.aa_sample_ids && s.mode == Mode::ray)
        throw UsageError("--aa-sample-ids refines where the item buffer's samples name several "
                         "objects: hybrid mode only (--mode ray draws no item buffer)");
    return s;
}

std::string FrameOptions::describe() const {
    const FrameSettings s = settings();
    if (s.mode == Mode::ray) return std::string(name_of(s.mode));
    return std::string(name_of(s.mode)) + " (" + gl + ", " + raster +
           (s.raster != RasterMode::proxy ? " tess " + std::to_string(tessellation) : "") + ", " +
           resolve + ")";
}

void refuse_option(CLI::App& cmd, const std::string& name, const std::string& why,
                   bool takes_value) {
    const std::string shown = name.substr(0, name.find(','));
    const auto refuse = [shown, why] { throw CLI::ValidationError(shown, why); };
    CLI::Option* option =
        takes_value
            ? cmd.add_option_function<std::vector<std::string>>( // given any number of times
                  name, [refuse](const std::vector<std::string>&) { refuse(); })
            : cmd.add_flag_callback(name, refuse);
    option->group(""); // not in --help: the command does not take it
}

void add_aov_option(CLI::App& cmd, std::vector<std::string>& aovs) {
    cmd.add_option("--aov", aovs,
                   "EXR only: add channels for each pixel centre's primary hit, comma-separated: "
                   "depth (Z), normal (N.X, N.Y, N.Z), id, cutoff")
        ->delimiter(',');
}

std::vector<Aov> parse_aovs(const std::vector<std::string>& names) {
    std::vector<Aov> aovs;
    for (const std::string& name : names) {
        const std::optional<Aov> aov = from_name<Aov>(name);
        if (!aov) throw UsageError("--aov " + name + ": not an AOV (depth, normal, id, cutoff)");
        if (std::find(aovs.begin(), aovs.end(), *aov) == aovs.end()) aovs.push_back(*aov);
    }
    return aovs;
}

void add_colour_option(CLI::App& cmd, std::string& colour) {
    cmd.add_option("--colour", colour,
                   "linear: texture bytes are colours and the PNG holds round(255·c) (the "
                   "default, DESIGN §11); srgb: a glTF's base colour and emissive textures are "
                   "decoded from sRGB, shading is linear, and the PNG is sRGB-encoded (EXR stays "
                   "linear)")
        ->capture_default_str()
        ->check(CLI::IsMember({"linear", "srgb"}));
}

std::pair<int, int> parse_size(const std::string& text, const std::string& flag) {
    static const std::regex size_pattern(R"((\d{1,5})x(\d{1,5}))");
    std::smatch m;
    if (!std::regex_match(text, m, size_pattern))
        throw UsageError(flag + " " + text + ": expected WIDTHxHEIGHT, e.g. 800x600");
    const int w = std::stoi(m[1]), h = std::stoi(m[2]);
    if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide)
        throw UsageError(flag + " " + text + ": each side must be 1 to " +
                         std::to_string(kMaxImageSide));
    return {w, h};
}

void check_output(const fs::path& path, const std::string& flag) {
    const fs::path dir = path.has_parent_path() ? path.parent_path() : ".";
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw UsageError(flag + " " + path.string() + ": directory " + dir.string() +
                         " does not exist");
    if (fs::is_directory(path, ec))
        throw UsageError(flag + " " + path.string() + ": is a directory");
    // Permissions alone do not tell (root, read-only mounts, /proc): make a file and remove it.
    std::string probe = (dir / ".glint-probe-XXXXXX").string();
    const int fd = mkstemp(probe.data());
    if (fd < 0)
        throw UsageError(flag + " " + path.string() + ": cannot write in " + dir.string() + ": " +
                         std::strerror(errno));
    ::close(fd);
    ::unlink(probe.c_str());
}

void create_output_directory(const fs::path& output) {
    std::error_code ec;
    if (output.has_parent_path() && !fs::create_directories(output.parent_path(), ec) && ec)
        throw UsageError("cannot create the output directory " + output.parent_path().string() +
                         ": " + ec.message() + " (choose another place with -o)");
}

namespace {

// Bytes one frame of width × height uses at its peak, roughly (options.h's constants).
std::uint64_t frame_memory_bytes(int width, int height, Mode mode) {
    const std::uint64_t per_pixel =
        mode == Mode::hybrid ? kFrameBytesPerPixelHybrid : kFrameBytesPerPixelRay;
    return static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) * per_pixel;
}

// Bytes this process may still allocate: MemAvailable, or the address-space limit if lower.
std::optional<std::uint64_t> available_memory_bytes() {
    std::optional<std::uint64_t> available;
    std::ifstream meminfo("/proc/meminfo");
    unsigned long long kib = 0;
    for (std::string line; std::getline(meminfo, line);)
        if (std::sscanf(line.c_str(), "MemAvailable: %llu kB", &kib) == 1) available = kib * 1024;
    rlimit limit{};
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
        available = std::min<std::uint64_t>(available.value_or(UINT64_MAX), limit.rlim_cur);
    return available;
}

std::string gib(std::uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f GiB", static_cast<double>(bytes) / (1u << 30));
    return text;
}

} // namespace

void check_frame_memory(const Scene& scene, Mode mode, int frames) {
    const Camera& camera = scene.camera;
    const int n = scene.render.samples;
    const bool sample_grid = mode == Mode::hybrid && n > 1;
    const std::string size = std::to_string(camera.width) + "x" + std::to_string(camera.height);
    const std::string grid = std::to_string(n) + "x" + std::to_string(n) + " samples";
    if (sample_grid && std::max(camera.width, camera.height) * n > kMaxItemBufferSide)
        throw UsageError("a " + size + " image with " + grid + " needs an item buffer of " +
                         std::to_string(camera.width * n) + "x" +
                         std::to_string(camera.height * n) + ", beyond the largest GL draws (" +
                         std::to_string(kMaxItemBufferSide) +
                         " a side): use fewer samples, a smaller --size, or --mode ray");
    std::uint64_t needed = frames * frame_memory_bytes(camera.width, camera.height, mode);
    if (sample_grid)
        needed += std::uint64_t(frames) * camera.width * camera.height * std::uint64_t(n * n) *
                  kSampleGridBytesPerSample;
    const std::optional<std::uint64_t> available = available_memory_bytes();
    if (available && needed > *available)
        throw UsageError("a " + size + " image" + (sample_grid ? " with " + grid : "") +
                         " needs about " + gib(needed) +
                         (mode == Mode::hybrid ? " in hybrid mode" : "") + ", but only " +
                         gib(*available) + " of memory is available: render it smaller (--size)" +
                         (sample_grid ? ", with fewer samples" : "") +
                         (mode == Mode::hybrid ? " or with --mode ray" : ""));
}

std::string describe_antialiasing(const RenderSettings& render) {
    if (render.samples == 1) return "";
    char text[96];
    std::snprintf(text, sizeof text, "%dx%d samples, %s", render.samples, render.samples,
                  std::string(name_of(render.antialias)).c_str());
    std::string line = text;
    if (render.antialias == Antialias::adaptive) {
        std::snprintf(text, sizeof text, " (threshold %g)",
                      static_cast<double>(render.aa_threshold));
        line += text;
    }
    return line;
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

Scene load_scene_with_notes(const std::filesystem::path& path, const ModelOptions& options) {
    Scene scene = load_scene(path, options);
    for (const std::string& note : scene.notes)
        std::cerr << "glint: note: " << path.string() << ": " << note << '\n';
    for (const std::string& warning : scene.warnings) std::cerr << "glint: warning: " << warning << '\n';
    return scene;
}

} // namespace glint
