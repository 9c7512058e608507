// What `render` and `compare` (and later commands) share: the scene and its overrides, the
// frame settings, output checks, and turning exceptions into exit codes.
#pragma once

#include "app/commands.h"
#include "frame/frame.h"

#include "io/exr.h"
#include "io/model_scene.h"

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace glint {

// Bad command-line input: exit code 2.
class UsageError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// A frame stopped from outside before its last tile (FrameSettings::cancel): the Python module's
// Ctrl-C, raised there as KeyboardInterrupt.
class Cancelled : public std::runtime_error {
  public:
    Cancelled() : std::runtime_error("cancelled") {}
};

// The scene's render settings a command line may override (and each side of `glint compare
// --a … --b …`, app/compare_sides.cpp): only those given change the scene's.
struct RenderOptions {
    std::string accel = "auto";
    int max_depth = 0;
    double min_reflectivity = 0;
    int samples = 1;
    std::string antialias;
    float aa_threshold = kDefaultAaThreshold;
    int packet_levels = 0;
    CLI::Option* max_depth_option = nullptr;
    CLI::Option* min_reflectivity_option = nullptr;
    CLI::Option* samples_option = nullptr;
    CLI::Option* aa_threshold_option = nullptr;
    CLI::Option* packet_levels_option = nullptr;
    CLI::Option* accel_option = nullptr;

    void add_to(CLI::App& cmd);
    // Sets the scene's render settings that were given.
    void apply(Scene& scene) const;
    // The --accel choice; nothing for auto (list below kListBelow objects, else bvh).
    std::optional<AccelKind> accel_kind() const;
};

struct SceneOptions {
    std::string scene;
    std::string size;
    int camera = 0;
    CLI::Option* camera_option = nullptr;
    double time = 0;     // `--time T`: a glTF model's animation at T seconds (DESIGN §13)
    int animation = 0;   // `--animation K`: which of its animations
    CLI::Option* time_option = nullptr;
    CLI::Option* animation_option = nullptr;
    // Set by a sequence (`glint render --frames`): the scene's animation is read even without
    // --time, to be played from T (default 0). `animate_if_any`, the preview's: the same where
    // the file has an animation, with no note where it has none.
    bool animate = false, animate_if_any = false;
    bool srgb = false; // `glint render --colour srgb`: ModelOptions::srgb
    std::string framing;     // `--framing`: ModelOptions::view; empty: the format's default
    std::string environment; // `--environment`: a file, studio or none; empty: the scene's
    RenderOptions render;
    // The scene read already (the Python module's glint.load): load() starts from a copy of it
    // instead of reading the file. The caller leaves it null where the options change what is
    // read (app/library.cpp).
    std::shared_ptr<const Scene> preloaded;

    void add_to(CLI::App& cmd);
    std::filesystem::path scene_path() const; // the given scene, or scenes/default.json
    // Loads the scene (SceneError on bad input) and applies the overrides (UsageError).
    Scene load() const;
    std::optional<AccelKind> accel_kind() const { return render.accel_kind(); }
};

struct FrameOptions {
    std::string mode = "hybrid";
    std::string gl = "osmesa";
    std::string raster = "auto";
    std::string resolve = "exact";
    int tessellation = kDefaultTessellation;
    int threads = 0;
    bool aa_sample_ids = false;

    // `with_mode`: whether --mode is offered (compare runs both modes); `with_gl`: whether --gl
    // is (the preview's GL is its window's).
    void add_to(CLI::App& cmd, bool with_mode, bool with_gl = true);
    FrameSettings settings() const;
    // One line for people: "hybrid (osmesa, mesh, tess 32, exact)".
    std::string describe() const;
};

// An option that another command takes and `cmd` does not (explain's -o, preview's --gl): the
// parser accepts it only to refuse it by name, saying `why`, instead of letting its value fall
// into a positional argument with a vaguer message. `takes_value`: an option, else a flag.
void refuse_option(CLI::App& cmd, const std::string& name, const std::string& why,
                   bool takes_value = true);

// render's --aov: the channels of each pixel centre's primary hit (the Python module's `aovs`).
void add_aov_option(CLI::App& cmd, std::vector<std::string>& aovs);
// The AOVs named, in the order given, each once; UsageError naming one that is not an AOV.
std::vector<Aov> parse_aovs(const std::vector<std::string>& names);
// render's --colour: linear (DESIGN §11's bytes) or srgb.
void add_colour_option(CLI::App& cmd, std::string& colour);

// WIDTHxHEIGHT, each side 1 to kMaxImageSide; UsageError naming `flag` otherwise.
std::pair<int, int> parse_size(const std::string& text, const std::string& flag);

// An output file must be creatable: its directory exists and takes a new file (a probe file is
// made and removed), and the path is not itself a directory. UsageError otherwise.
void check_output(const std::filesystem::path& path, const std::string& flag);

// Creates the directory that the default output goes to (out/); UsageError when it cannot.
void create_output_directory(const std::filesystem::path& output);

// What check_frame_memory counts, the formula docs/SCENES.md ("Limits") quotes and
// Cli.TheMemoryRuleIsTheOneScenesMdQuotes holds it to: width × height × these bytes a pixel, by
// mode, times the frames alive at once; and in hybrid mode with an N×N grid, width × height × N²
// × kSampleGridBytesPerSample more.
// Per pixel, from what a frame holds: primary hits (20 B with their barycentrics), the ids and
// cut-off weights (8 B), the float image (12 B; 24 B with a sample grid's clamped mean) and the
// PNG's bytes (3 B) and their encoding (~3 B); hybrid adds the read-back ids and depths (8 B)
// and the GL side: llvmpipe's id and depth attachments and the pixel-pack buffer. Peak resident
// memory measured at 4000×3000 minus that at 8×6 (docs/SCENES.md, "Limits"), before the float
// image: 31 B a pixel in ray mode, 39 B in hybrid mode; the 12 B it adds are added to each, and
// the margin above covers allocator slack and the AOVs.
inline constexpr std::uint64_t kFrameBytesPerPixelRay = 52;
inline constexpr std::uint64_t kFrameBytesPerPixelHybrid = 76;
// The sample grid's item buffer: its ids and depths read back (8 B a sample), llvmpipe's id and
// depth attachments (8 B) and the pixel-pack buffer and depth read-back (8 B).
inline constexpr std::uint64_t kSampleGridBytesPerSample = 24;

// Refuses, before anything is allocated, a frame that would not fit in the memory this process
// may use (MemAvailable, or a lower address-space limit): UsageError naming the size. Counts
// the scene's antialiasing: in hybrid mode, an N×N grid's item buffer holds N² samples a pixel
// (and cannot exceed kMaxItemBufferSide a side). `frames`: how many frames of this size are
// alive at once.
void check_frame_memory(const Scene& scene, Mode mode, int frames);

// The largest side of an item buffer glint draws (llvmpipe's limit, and most GPUs').
inline constexpr int kMaxItemBufferSide = 16384;

// One line for people: "4x4 samples, adaptive (threshold 0.02)"; empty for one sample.
std::string describe_antialiasing(const RenderSettings& render);

// Loads a scene (any format load_scene reads) and prints what the loader left out or changed
// ("glint: note: …") and what a model asked for that glint could not give it ("glint: warning:
// …") on stderr, as every command that renders a scene does.
Scene load_scene_with_notes(const std::filesystem::path& path, const ModelOptions& options = {});

// Runs a command body, turning exceptions into glint's exit codes and one-line messages:
// bad input 2, anything else 1.
int guarded(const std::function<int()>& body);

} // namespace glint
