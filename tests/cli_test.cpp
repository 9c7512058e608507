// The glint command as a user meets it: what a successful render prints and writes, and every
// class of bad input exiting 2 with its message while leaving no file behind and an existing
// output untouched.
#include "run_glint.h"
#include "test_scenes.h"

#include "io/png.h"
#include "trace/frame_records.h"
#include "trace/image.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>
#include <sys/wait.h>
#include <utility>

namespace glint {
namespace {

namespace fs = std::filesystem;

using testing::glint;
using testing::Outcome;
using testing::slurp;
using testing::write;

fs::path fresh_dir() {
    return testing::fresh_dir("glint_cli");
}

TEST(Cli, RenderWritesThePngAndReportsPathTimeAndRayCounts) {
    const fs::path dir = fresh_dir();
    const Outcome r =
        glint(dir, "render '" GLINT_SOURCE_DIR
                   "/scenes/default.json' -o a.png --size 64x48 --samples 1 --stats s.json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("wrote a.png (64x48"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(" s (render "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("3072 primary"), std::string::npos) << r.out;
    const Image image = read_png(dir / "a.png");
    EXPECT_EQ(image.width, 64);
    EXPECT_EQ(image.height, 48);
    const auto stats = nlohmann::json::parse(slurp(dir / "s.json"));
    EXPECT_EQ(stats["rays"]["primary"], 3072);
    EXPECT_GT(stats["rays"]["shadow"], 0);
    EXPECT_GT(stats["rays"]["reflection"], 0);
    EXPECT_GT(stats["seconds"]["total"], 0.0);
    EXPECT_TRUE(r.err.empty()) << "no progress output when stderr is not a terminal: " << r.err;
}

// Output names are read by their extension in any case, as scene names are: x.PNG is a PNG.
TEST(Cli, AnOutputExtensionInCapitalsIsItsFormat) {
    const fs::path dir = fresh_dir();
    const Outcome r = glint(dir, "render --size 16x12 --mode ray -o x.PNG");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_png(dir / "x.PNG").width, 16);
}

// A note about a model given as the scene names the file once (the note itself does not: the
// scene's path is printed before it); a note about a JSON scene's mesh names the mesh file.
TEST(Cli, AModelsNoteNamesItsFileOnce) {
    const fs::path dir = fresh_dir();
    write(dir / "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2\n");
    Outcome r = glint(dir, "render m.obj --size 16x12 --mode ray -o a.png");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("glint: note: m.obj: 1 line and point statements (l, p) ignored"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find("m.obj: m.obj"), std::string::npos) << r.err;
    write(dir / "s.json", R"({"objects": [{"shape": "mesh", "file": "m.obj"}]})");
    r = glint(dir, "render s.json --size 16x12 --mode ray -o a.png");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("glint: note: s.json: m.obj: 1 line and point statements"),
              std::string::npos)
        << r.err;
}

// explain takes the scene's and the frame's options, not render's outputs: each is refused by
// its name (BadRunTest has -o), before anything is traced or written.
TEST(Cli, ExplainRefusesRendersOutputsByName) {
    const fs::path dir = fresh_dir();
    for (const auto& [args, message] : std::initializer_list<std::pair<std::string, std::string>>{
             {"--stats s.json", "glint: error: --stats: render's"},
             {"--aov depth", "glint: error: --aov: render's"},
             {"--aa-map m.png", "glint: error: --aa-map: render's"}}) {
        const Outcome r = glint(dir, "explain " + args + " 10 10 --json e.json");
        EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
        for (const char* file : {"e.json", "s.json", "m.png"})
            EXPECT_FALSE(fs::exists(dir / file)) << args << ": wrote " << file;
    }
}

// Counters reach JSON through their field lists (trace/frame_records.h): render's --stats and
// compare's --json write the resolve's counters under the same names, in their "hybrid" objects,
// and the same counts for the same frame; the rays under RayCounts' names.
TEST(Cli, RenderAndCompareWriteTheResolveCountersUnderTheirFieldNames) {
    const fs::path dir = fresh_dir();
    const std::string scene = "'" GLINT_SOURCE_DIR "/scenes/default.json' --size 64x48 ";
    const Outcome render = glint(dir, "render " + scene + "-o a.png --stats s.json");
    ASSERT_EQ(render.exit_code, 0) << render.err;
    const Outcome compare = glint(dir, "compare " + scene + "--json c.json");
    ASSERT_EQ(compare.exit_code, 0) << compare.err;
    const auto stats = nlohmann::json::parse(slurp(dir / "s.json"));
    const auto comparison = nlohmann::json::parse(slurp(dir / "c.json"));
    std::vector<std::string> names;
    const PrimaryStats resolve;
    for_each_field(resolve, [&](const std::string& name, auto) { names.push_back(name); });
    ASSERT_EQ(names.size(), 7u);
    for (const std::string& name : names) {
        ASSERT_TRUE(stats["hybrid"].contains(name)) << name;
        ASSERT_TRUE(comparison["hybrid"].contains(name)) << name;
        EXPECT_EQ(stats["hybrid"][name], comparison["hybrid"][name]) << name;
    }
    EXPECT_GT(stats["hybrid"]["exact_intersections"], 0);
    for (const char* old : {"fallback_pixels", "corrected_pixels", "edge_pixels", "checked_pixels",
                            "candidate_tests", "traced_pixels"})
        EXPECT_FALSE(comparison.contains(old)) << old << ": a second name for a counter";
    const RayCounts rays;
    for_each_field(rays, [&](const std::string& name, auto) {
        EXPECT_TRUE(stats["rays"].contains(name)) << name;
    });
}

// A process loads only what its run uses (DESIGN's "model only what a scene requires"): a
// ray-mode render loads no GL library (OSMesa and EGL are opened when a context is made:
// raster/gl_library.h), no GLFW or X11 (opened for a preview's window: preview/glfw_library.h),
// no MPI (glint-mpi's alone) and no OpenEXR (its plug-in, opened for an EXR), as the dynamic
// loader lists what it loads (LD_DEBUG=files, libraries opened at run time included). Hybrid
// renders with each GL backend load their library, and a preview loads GLFW before it finds no
// display, so the listing is seen to cover what is opened late.
TEST(Cli, ARayModeRenderLoadsNoGlWindowMpiOrExrLibrary) {
    const fs::path dir = fresh_dir();
    const std::string render =
        "render '" GLINT_SOURCE_DIR "/scenes/default.json' --size 16x12 --threads 1 ";
    const auto loads = [](const Outcome& run, const std::string& library) {
        return run.err.find("file=" + library) != std::string::npos;
    };
    const Outcome ray = glint(dir, render + "--mode ray -o r.png", "env LD_DEBUG=files");
    ASSERT_EQ(ray.exit_code, 0) << ray.err;
    ASSERT_TRUE(loads(ray, "libtbb")) << "no listing from the loader: " << ray.err.substr(0, 400);
    for (const char* library :
         {"libEGL", "libOSMesa", "libglfw", "libX11", "libmpi", "libOpenEXR", "libglint_exr"})
        EXPECT_FALSE(loads(ray, library)) << library;
    for (const auto& [gl, library] : {std::pair{"osmesa", "libOSMesa"}, {"egl", "libEGL"}}) {
        const Outcome hybrid =
            glint(dir, render + "--mode hybrid --gl " + gl + " -o h.png", "env LD_DEBUG=files");
        ASSERT_EQ(hybrid.exit_code, 0) << gl << ": " << hybrid.err.substr(0, 400);
        EXPECT_TRUE(loads(hybrid, library)) << gl;
    }
    const Outcome preview = glint(dir, "preview '" GLINT_SOURCE_DIR "/scenes/default.json'",
                                  "env -u DISPLAY -u WAYLAND_DISPLAY LD_DEBUG=files");
    EXPECT_EQ(preview.exit_code, 1) << preview.err.substr(0, 400);
    EXPECT_TRUE(loads(preview, "libglfw"));
}

// GLINT_KERNEL chooses the SIMD kernel (trace/kernel.h): --stats and `glint info` name the one
// that ran, the portable one forced renders the same bytes, and a name that is not a kernel is
// refused before any work, exit 2.
TEST(Cli, TheKernelIsNamedForcedByGlintKernelAndCheckedAtStartUp) {
    const fs::path dir = fresh_dir();
    const std::string render =
        "render '" GLINT_SOURCE_DIR "/scenes/default.json' --size 64x48 --mode ray --stats ";
    const Outcome widest = glint(dir, render + "w.json -o w.png");
    ASSERT_EQ(widest.exit_code, 0) << widest.err;
    const std::string kernel = nlohmann::json::parse(slurp(dir / "w.json"))["kernel"];
    EXPECT_TRUE(kernel == "sse" || kernel == "avx2" || kernel == "avx512") << kernel;
    const Outcome portable = glint(dir, render + "p.json -o p.png", "env GLINT_KERNEL=sse");
    ASSERT_EQ(portable.exit_code, 0) << portable.err;
    EXPECT_EQ(nlohmann::json::parse(slurp(dir / "p.json"))["kernel"], "sse");
    EXPECT_EQ(slurp(dir / "w.png"), slurp(dir / "p.png"));
    const Outcome info = glint(dir, "info", "env GLINT_KERNEL=sse");
    EXPECT_NE(info.out.find("kernel: sse ("), std::string::npos) << info.out;
    const Outcome bad = glint(dir, render + "b.json -o b.png", "env GLINT_KERNEL=avx9");
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("GLINT_KERNEL=avx9 is not a kernel (sse, avx2, avx512)"),
              std::string::npos)
        << bad.err;
    EXPECT_FALSE(fs::exists(dir / "b.png"));
}

// --packet-levels casts the first levels of each tile's reflected and transmitted rays ahead
// in packets (TileLighting, whose own test checks every ray): the same bytes and ray counts as
// without, and --stats says how many levels were asked for. Packets run in the eight-wide BVH
// alone, hence --accel bvh for a scene that `auto` would trace with the list.
TEST(Cli, PacketLevelsCastAheadAndLeaveTheImageAsItWas) {
    const fs::path dir = fresh_dir();
    const std::string render = "render '" GLINT_SOURCE_DIR
                               "/scenes/default.json' --size 64x48 --mode ray --accel bvh --stats ";
    const Outcome alone = glint(dir, render + "a.json -o a.png");
    ASSERT_EQ(alone.exit_code, 0) << alone.err;
    const Outcome ahead = glint(dir, render + "b.json -o b.png --packet-levels 3");
    ASSERT_EQ(ahead.exit_code, 0) << ahead.err;
    EXPECT_EQ(slurp(dir / "a.png"), slurp(dir / "b.png"));
    const auto a = nlohmann::json::parse(slurp(dir / "a.json"));
    const auto b = nlohmann::json::parse(slurp(dir / "b.json"));
    EXPECT_EQ(a["packet_levels"], 0);
    EXPECT_EQ(b["packet_levels"], 3);
    EXPECT_GT(b["rays"]["reflection"], 0);
    EXPECT_EQ(a["rays"], b["rays"]);
}

// No display: the preview says so and names the two ways on, and opens nothing.
TEST(Cli, PreviewWithoutADisplayNamesGlintRenderAndXvfbRun) {
    const fs::path dir = fresh_dir();
    const Outcome r = glint(dir, "preview '" GLINT_SOURCE_DIR "/scenes/default.json'",
                            "env -u DISPLAY -u WAYLAND_DISPLAY");
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("no display"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("`glint render "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("`xvfb-run -a glint preview "), std::string::npos) << r.err;
}

// Fields of one CSV line (no field of glint's CSV holds a comma).
std::vector<std::string> fields(const std::string& line) {
    std::vector<std::string> out(1);
    for (const char c : line) {
        if (c == ',')
            out.emplace_back();
        else
            out.back().push_back(c);
    }
    return out;
}

TEST(Cli, TradeoffWritesTheCsvAPlotPerSceneAndTheSummary) {
    const fs::path dir = fresh_dir();
    const Outcome r = glint(dir, "tradeoff '" GLINT_SOURCE_DIR "/scenes/default.json' --size "
                                 "40x30 --repeat 1 -o sweep");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::istringstream csv(slurp(dir / "sweep" / "tradeoff.csv"));
    std::string line;
    std::getline(csv, line);
    const std::vector<std::string> header = fields(line);
    const auto column = [&](const std::string& name) {
        return std::find(header.begin(), header.end(), name) - header.begin();
    };
    int rows = 0, on_front = 0, bounds_checked = 0, grids = 0, adaptive = 0;
    while (std::getline(csv, line)) {
        const std::vector<std::string> row = fields(line);
        ASSERT_EQ(row.size(), header.size()) << line;
        ++rows;
        on_front += row[column("pareto")] == "yes";
        EXPECT_NE(row[column("cutoff_bound_held")], "no") << line;
        bounds_checked += row[column("cutoff_bound_held")] == "yes";
        // The radiance error sits beside the bytes': zero where the bytes are exact and the
        // float images too (identical settings), never negative, and at least the byte error's
        // floor where bytes differ by more than 1/255 (a byte step is 1/255 in radiance, less
        // its rounding: > (k − 1)/255 for k steps).
        // A frame's time less its GL set-up: more than nothing, never negative (it was when
        // the set-up hid behind the World's preparation and was subtracted twice).
        EXPECT_GT(std::stod(row[column("seconds_frame")]), 0) << line;
        EXPECT_LE(std::stod(row[column("seconds_frame")]), std::stod(row[column("seconds_total")]))
            << line;
        const double rmse = std::stod(row[column("rmse_radiance")]);
        const double largest = std::stod(row[column("max_error_radiance")]);
        EXPECT_GE(rmse, 0) << line;
        EXPECT_GE(largest, rmse) << line;
        const int byte_error = std::stoi(row[column("max_abs_error_255")]);
        if (byte_error > 1) {
            EXPECT_GT(largest, (byte_error - 1) / 255.0) << line;
        }
        // Why it differs (docs/DIFFERENCES.md): pixels wherever bytes do,
        // and the causes' shares summing to 1 wherever the radiance does.
        const unsigned long differing = std::stoul(row[column("differing_pixels")]);
        EXPECT_EQ(differing > 0, byte_error > 0) << line;
        double shares = 0;
        for (const char* cause :
             {"sampling", "depth", "cutoff", "primary", "secondary", "shadow", "precision"})
            shares += std::stod(row[column(std::string("share_") + cause)]);
        if (differing > 0) {
            EXPECT_NEAR(shares, 1.0, 1e-4) << line;
        }
        if (row[column("divisor")] != "1" && differing > 0) {
            EXPECT_EQ(std::stod(row[column("share_sampling")]), 1.0) << line; // enlarged
        }
        const unsigned long n = std::stoul(row[column("samples")]);
        const unsigned long primary = std::stoul(row[column("rays_primary")]);
        if (row[column("antialias")] == "adaptive") {
            // The centres, then the grids of the refined pixels.
            EXPECT_EQ(primary, 1200u + n * n * std::stoul(row[column("refined_pixels")])) << line;
            EXPECT_EQ(row[column("reference")], "uniform 8x8") << line;
            ++adaptive;
            continue;
        }
        EXPECT_EQ(primary, n * n *
                               (row[column("divisor")] == "1"   ? 1200u
                                : row[column("divisor")] == "2" ? 300u
                                                                : 70u))
            << line;
        grids += row[column("reference")] == "uniform 8x8";
    }
    EXPECT_EQ(grids, 4);    // uniform 1×1 to 4×4 against 8×8
    EXPECT_EQ(adaptive, 5); // adaptive 4×4 over five thresholds
    EXPECT_GE(rows, 30);    // every knob's values, a setting reached by two knobs once
    EXPECT_GE(on_front, 1);
    EXPECT_GE(bounds_checked, 10); // every float ray-mode run at full size
    EXPECT_GT(fs::file_size(dir / "sweep" / "default.svg"), 0u);
    EXPECT_EQ(read_png(dir / "sweep" / "default.png").width, 1100);
    const std::string summary = slurp(dir / "sweep" / "summary.md");
    EXPECT_NE(summary.find("## default (40×30, 10 objects)"), std::string::npos) << summary;
    EXPECT_NE(summary.find("| PSNR ≥ 40 dB |"), std::string::npos) << summary;
    // Each knob's dominant cause, and the maps of the fastest setting within 40 dB.
    EXPECT_NE(summary.find("| max_depth | "), std::string::npos) << summary;
    EXPECT_NE(summary.find("| the error is mostly | beyond the default setting's |"),
              std::string::npos)
        << summary;
    // The fastest setting within 40 dB depends on the timings: its maps where it errs (every
    // thumbnail the summary names is written), "identical" where it is exact.
    const std::size_t row = summary.find("| PSNR ≥ 40 dB |");
    const std::string budget_row = summary.substr(row, summary.find('\n', row) - row);
    if (budget_row.find("| identical |") == std::string::npos) {
        EXPECT_NE(budget_row.find("](./default-psnr-40-causes.png)"), std::string::npos)
            << budget_row;
        EXPECT_GT(read_png(dir / "sweep" / "default-psnr-40-heat.png").width, 0);
    } else {
        EXPECT_NE(budget_row.find("| exact | 0/255 |"), std::string::npos) << budget_row;
    }
    EXPECT_NE(summary.find("](./default.svg)"), std::string::npos) << summary;
    EXPECT_NE(summary.find("](./default-antialiasing.svg)"), std::string::npos) << summary;
    EXPECT_NE(summary.find("| hybrid auto tess 32 4x4 adaptive 0.02 |"), std::string::npos)
        << summary;
    // The default setting it names is the one the sweep starts from: auto raster, not mesh.
    EXPECT_NE(summary.find("from the default setting (hybrid, auto raster, tessellation 32,"),
              std::string::npos)
        << summary;
    EXPECT_GT(fs::file_size(dir / "sweep" / "default-antialiasing.svg"), 0u);
}

// The commands take NFF files and scenes with OBJ meshes as they take JSON scenes.
// compare --a --b (docs/DIFFERENCES.md): both images, the heat and cause
// maps, the float error, and JSON whose causes add up; explain --against at a pixel the map
// paints names the same cause. A bad side writes nothing.
TEST(Cli, CompareTwoSettingsWritesTheMapsAndExplainAgainstAgrees) {
    const fs::path dir = fresh_dir();
    const std::string scene = "'" GLINT_SOURCE_DIR "/scenes/mirrors.json' --size 64x48 --samples 1 ";
    Outcome r = glint(dir, "compare " + scene + "--a '--max-depth 2' --b '--max-depth 10' -o m.exr --json m.json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* file : {"m-a.png", "m-b.png", "m-heat.png", "m-causes.png", "m-heat.exr"})
        EXPECT_TRUE(fs::exists(dir / file)) << file;
    EXPECT_NE(r.out.find("depth"), std::string::npos) << r.out;
    const nlohmann::json j = nlohmann::json::parse(slurp(dir / "m.json"));
    EXPECT_EQ(j["schema"], "glint-compare-sides/1");
    const auto differing = j["differing_pixels"].get<std::uint64_t>();
    ASSERT_GT(differing, 0u);
    EXPECT_EQ(j["causes"]["depth"]["pixels"].get<std::uint64_t>(), differing);
    EXPECT_EQ(j["causes"]["depth"]["levels"]["3"].get<std::uint64_t>(), differing);
    EXPECT_DOUBLE_EQ(j["causes"]["depth"]["share"].get<double>(), 1.0);
    EXPECT_GT(j["a"]["seconds"].get<double>(), 0.0);
    EXPECT_GT(j["time_ratio"].get<double>(), 0.0);

    // The left mirror's corridor: pixel (4, 30) goes deeper than 2 reflections.
    r = glint(dir, "explain " + scene + "4 30 --max-depth 2 --against '--max-depth 10' --json e.json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("<- depth"), std::string::npos) << r.out;
    const nlohmann::json e = nlohmann::json::parse(slurp(dir / "e.json"));
    EXPECT_EQ(e["schema"], "glint-explain-against/1");
    EXPECT_EQ(e["cause"], "depth");
    r = glint(dir, "explain " + scene + "4 30 --against '--samples 1'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("no difference"), std::string::npos) << r.out;

    const fs::path bad = fresh_dir() / "bad";
    fs::create_directories(bad);
    r = glint(bad, "compare " + scene + "--a '--max-depth 2' --b '--tess 1' -o m --json m.json");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--b \"--tess 1\": --tess"), std::string::npos) << r.err;
    r = glint(bad, "explain " + scene + "3 3 --against '--size 4x4' --json e.json");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--against \"--size 4x4\": --size: both sides render the same scene"),
              std::string::npos)
        << r.err;
    for (const auto& entry : fs::directory_iterator(bad))
        EXPECT_TRUE(entry.path().extension() == ".txt") << entry.path() << " written";
}

TEST(Cli, CompareAndTradeoffTakeNffAndObjScenes) {
    const fs::path dir = fresh_dir();
    Outcome r = glint(dir, "compare '" GLINT_SOURCE_DIR "/tests/data/spd/rings-1.nff' --size "
                           "64x64 -o rings");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_png(dir / "rings-hybrid.png").width, 64);
    r = glint(dir, "tradeoff '" GLINT_SOURCE_DIR "/tests/data/spd/tree-3.nff' '" GLINT_SOURCE_DIR
                   "/scenes/instances.json' --size 32x24 --repeat 1 -o sweep");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string summary = slurp(dir / "sweep" / "summary.md");
    EXPECT_NE(summary.find("## tree-3 (32×24"), std::string::npos) << summary;
    EXPECT_NE(summary.find("## instances (32×24"), std::string::npos) << summary;
}

TEST(Cli, WithoutArgumentsRendersTheDefaultSceneIntoOut) {
    const fs::path dir = fresh_dir();
    const Outcome r = glint(dir, "render --size 16x12");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "out/default.png"));
}

TEST(Cli, OverridesChangeWhatIsTraced) {
    const fs::path dir = fresh_dir();
    const Outcome r = glint(dir, "render --size 16x12 --max-depth 0 -o a.png --threads 1");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find(" 0 reflection"), std::string::npos) << r.out;
}

struct BadRun {
    const char* what;
    const char* scene; // written to scene.json (scene.nff if the args name it) when not empty
    const char* args;
    const char* message;
};

void PrintTo(const BadRun& bad, std::ostream* out) {
    *out << bad.what;
}

class BadRunTest : public ::testing::TestWithParam<BadRun> {};

TEST_P(BadRunTest, ExitsTwoWithItsMessageAndWritesNothing) {
    const BadRun& bad = GetParam();
    const fs::path dir = fresh_dir();
    const bool nff = std::string_view(bad.args).find("scene.nff") != std::string_view::npos;
    if (*bad.scene) write(dir / (nff ? "scene.nff" : "scene.json"), bad.scene);
    write(dir / "keep.png", "precious");
    // The preview has no -o: its only output is --screenshot, which its cases name.
    const bool preview = std::string_view(bad.args).starts_with("preview");
    Outcome r = glint(dir, std::string(bad.args) + (preview ? "" : " -o new.png"));
    EXPECT_EQ(r.exit_code, 2) << bad.what << ": " << r.err;
    EXPECT_NE(r.err.find(bad.message), std::string::npos) << bad.what << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir / "new.png")) << bad.what;
    r = glint(dir, std::string(bad.args) + " -o keep.png");
    EXPECT_EQ(r.exit_code, 2) << bad.what;
    EXPECT_EQ(slurp(dir / "keep.png"), "precious")
        << bad.what << ": an existing output was touched";
    for (const auto& entry : fs::directory_iterator(dir))
        EXPECT_EQ(entry.path().filename().string().find(".keep.png."), std::string::npos)
            << "temporary file left";
}

// clang-format off
INSTANTIATE_TEST_SUITE_P(EveryClass, BadRunTest, ::testing::Values(
    BadRun{"NFF: a word for a number", "v from 0 0 1 at 0 0 0 up 0 1 0 angle 40 hither 1 resolution 8 8\ns 0 0 x 1\n", "render scene.nff", "glint: error: scene.nff:2: expected a number for s's centre, got 'x'"},
    BadRun{"NFF: cut short", "v from 0 0 1 at 0 0 0 up 0 1 0 angle 40 hither 1 resolution 8 8\np 3\n0 0 0\n", "compare scene.nff", "glint: error: scene.nff:3: the file ends inside 'p' (line 2)"},
    BadRun{"OBJ missing", R"({"objects": [{"shape": "mesh", "file": "none.obj"}]})", "render scene.json", "scene.json: /objects/0/file: none.obj: cannot open mesh file"},
    BadRun{"malformed JSON", "{\"objects\": [", "render scene.json", "glint: error: scene.json:1:14: malformed JSON"},
    BadRun{"unknown key", R"({"objects": [{"shape": "sphere", "materal": "x"}]})", "render scene.json", "scene.json: /objects/0/materal: unknown key"},
    BadRun{"wrong type", R"({"camera": {"width": "wide"}})", "render scene.json", "scene.json: /camera/width: expected a number"},
    BadRun{"missing material", R"({"objects": [{"shape": "sphere", "material": "gold"}]})", "render scene.json", "/objects/0/material: no material named 'gold'"},
    BadRun{"number beyond double", R"({"camera": {"eye": [0, 0, 1e400]}})", "render scene.json", "scene.json:1:27: number overflow parsing '1e400'"},
    BadRun{"zero scale", R"({"objects": [{"shape": "box", "transform": [{"scale": 0}]}]})", "render scene.json", "/objects/0/transform/0/scale: components must be non-zero"},
    BadRun{"out of range", R"({"render": {"min_reflectivity": 2}})", "render scene.json", "/render/min_reflectivity: must be between 0 and 1"},
    BadRun{"singular transform", R"({"objects": [{"shape": "box", "transform": [{"matrix": [[1,2,3,0],[2,4,6,0],[0,0,1,0],[0,0,0,1]]}]}]})", "render scene.json", "/objects/0/transform: transform is singular"},
    BadRun{"missing scene file", "", "render nowhere.json", "nowhere.json: cannot open scene file"},
    BadRun{"scene is a directory", "", "render .", ".: is a directory"},
    BadRun{"endless scene file", "", "render /dev/zero", "/dev/zero: scene file is larger than allowed; the limit is 64 MiB"},
    BadRun{"nesting too deep", R"({"objects": [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]})",
           "render scene.json", "scene.json:1:44: JSON nested deeper than 32 levels"},
    BadRun{"bad size", "", "render --size 64by48", "--size 64by48: expected WIDTHxHEIGHT"},
    BadRun{"size too large", "", "render --size 99999x10", "each side must be 1 to 16384"},
    BadRun{"negative depth", "", "render --max-depth -1", "--max-depth"},
    BadRun{"depth beyond limit", "", "render --max-depth 1000000000", "--max-depth"},
    BadRun{"reflectivity out of range", "", "render --min-reflectivity 1.5", "--min-reflectivity"},
    BadRun{"zero threads", "", "render --threads 0", "--threads"},
    BadRun{"unknown flag", "", "render --fast", "--fast"},
    BadRun{"unknown mode", "", "render --mode magic", "--mode"},
    BadRun{"unknown GL backend", "", "render --gl glx", "--gl"},
    BadRun{"unknown raster mode", "", "render --raster voxels", "--raster"},
    BadRun{"tessellation below the minimum", "", "render --tess 2", "--tess"},
    BadRun{"unknown resolve", "", "render --resolve maybe", "--resolve"},
    BadRun{"compare: bad scene", R"({"objects": 1})", "compare scene.json", "scene.json: /objects: expected an array"},
    BadRun{"preview: bad scene", R"({"objects": 1})", "preview scene.json", "scene.json: /objects: expected an array"},
    BadRun{"preview: screenshot not PNG", "", "preview --screenshot shot.jpg", "--screenshot shot.jpg: glint writes PNG files (.png)"},
    BadRun{"preview: screenshot nowhere", "", "preview --screenshot no/such/dir/a.png", "--screenshot no/such/dir/a.png: directory no/such/dir does not exist"},
    BadRun{"preview: spin without frames", "", "preview --spin 5", "--spin: orbits during the --frames N scripted frames; give --frames"},
    BadRun{"preview: unknown view", "", "preview --view xray", "--view"},
    BadRun{"preview: no GL choice", "", "preview --gl egl", "--gl"},
    BadRun{"preview: click outside the image", "", "preview --click 800,10", "--click 800,10: the pixel is outside the 800x600 image"},
    BadRun{"preview: click not X,Y", "", "preview --click 10", "--click 10: expected X,Y"},
    BadRun{"preview: unknown panel setting", "", "preview --set speed=11", "--set no setting named 'speed' (the panel's: mode, raster, resolve, depth, cutoff, tess, samples, aa, accel, view, panel, reference, time)"},
    BadRun{"preview: panel setting out of range", "", "preview --set depth=deep", "--set depth=deep: expected a number from 0 to 64"},
    BadRun{"preview: panel setting not a name", "", "preview --set mode=fast", "--set mode=fast: expected one of hybrid, ray"},
    BadRun{"tradeoff: bad scene", R"({"objects": 1})", "tradeoff scene.json", "scene.json: /objects: expected an array"},
    BadRun{"tradeoff: bad size", "", "tradeoff --size 0x5", "--size 0x5: each side must be 1 to 16384"},
    BadRun{"tradeoff: no repeat", "", "tradeoff --repeat 0", "--repeat"},
    BadRun{"no samples", "", "render --samples 0", "--samples"},
    BadRun{"samples beyond 16", "", "compare --samples 17", "--samples"},
    BadRun{"unknown antialiasing", "", "render --aa jitter", "--aa"},
    BadRun{"threshold out of range", "", "render --aa-threshold 1.5", "--aa-threshold"},
    BadRun{"packet levels beyond 64", "", "render --packet-levels 65", "--packet-levels: Value 65 not in range 0 to 64"},
    BadRun{"scene: samples beyond 16", R"({"render": {"samples": 17}})", "render scene.json", "scene.json: /render/samples: must be between 1 and 16"},
    BadRun{"scene: unknown antialiasing", R"({"render": {"antialias": "jitter"}})", "render scene.json", "scene.json: /render/antialias: expected uniform or adaptive"},
    BadRun{"scene: threshold out of range", R"({"render": {"aa_threshold": -0.1}})", "render scene.json", "scene.json: /render/aa_threshold: must be between 0 and 1"},
    BadRun{"sample grid beyond GL", "", "render --size 3840x2160 --samples 16", "a 3840x2160 image with 16x16 samples needs an item buffer of 61440x34560, beyond the largest GL draws (16384 a side): use fewer samples, a smaller --size, or --mode ray"},
    BadRun{"adaptive map without adaptive", "", "render --samples 1 --aa-map map.png", "--aa-map map.png: maps adaptive antialiasing; give --aa adaptive and --samples N > 1"},
    BadRun{"tradeoff: samples beyond 16", "", "tradeoff --samples 20", "--samples"},
    BadRun{"stats into a missing directory", "", "render --stats no/dir/s.json", "--stats no/dir/s.json: directory no/dir does not exist"},
    // A command or flag that does not apply is refused by name, not left to a vaguer message.
    BadRun{"a command misspelt", "", "rendr", "glint: error: no command 'rendr'; did you mean 'render'? (glint's commands: render, explain,"},
    BadRun{"no such command", "", "paint scene.json", "glint: error: no command 'paint' (glint's commands: render,"},
    BadRun{"explain: render's -o", "", "explain -o x.png 10 10", "glint: error: -o: explain writes no image"},
    BadRun{"sample ids in ray mode", "", "render --aa-sample-ids --mode ray", "glint: error: --aa-sample-ids refines where the item buffer's samples name several objects: hybrid mode only"},
    BadRun{"preview: --gl", "", "preview --gl egl", "glint: error: --gl: the preview draws with its window's own GL context"},
    // compare's sides (docs/DIFFERENCES.md): each message names the side.
    BadRun{"compare: unknown flag in a side", "", "compare --size 8x6 --a '--fast'", "glint: error: --a \"--fast\": The following argument was not expected: --fast"},
    BadRun{"compare: bad value in a side", "", "compare --size 8x6 --b '--max-depth deep'", "glint: error: --b \"--max-depth deep\": --max-depth: Value deep not in range 0 to 64"},
    BadRun{"compare: shared flag in a side", "", "compare --size 8x6 --b '--size 10x10'", "glint: error: --b \"--size 10x10\": --size: both sides render the same scene at the same size: give it outside --b"},
    BadRun{"compare: camera in a side", "", "compare --size 8x6 --a '--camera 1'", "glint: error: --a \"--camera 1\": --camera: both sides render the same scene"},
    BadRun{"compare: empty side", "", "compare --size 8x6 --a ' '", "glint: error: --a is empty: give the side's render flags"},
    BadRun{"compare: exact in hybrid mode", "", "compare --size 8x6 --a 'exact --mode hybrid'", "--mode hybrid cannot go with it"},
    BadRun{"compare: a word in a side", "", "compare --size 8x6 --a 'deep'", "glint: error: --a \"deep\": The following argument was not expected: deep"},
    BadRun{"compare: --exr without sides", "", "compare --size 8x6 --exr", "glint: error: --exr writes the float error of --a against --b"}
), [](const auto& info) { return testing::test_name(info.param.what); });
// clang-format on

// `glint explain` (docs/EXPLAIN.md): the tree for people on stdout, and JSON whose schema the
// doc gives, read back here; its bytes are the rendered pixel's.
TEST(Cli, ExplainPrintsThePixelsTreeAndWritesJsonThatReadsBack) {
    const fs::path dir = fresh_dir();
    ASSERT_EQ(glint(dir, "render " GLINT_SOURCE_DIR "/scenes/default.json --size 80x60 -o a.png")
                  .exit_code,
              0);
    const Outcome r = glint(dir, "explain " GLINT_SOURCE_DIR
                                 "/scenes/default.json 41 33 --size 80x60 --json e.json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* expected :
         {"ray 0: primary", "item buffer (the pixel centre", "M⁻¹o = ", "normalize(M⁻ᵀn')",
          "R_0 = ambient + diffuse + specular", "→ bytes ", "rays: this tree"})
        EXPECT_NE(r.out.find(expected), std::string::npos) << expected << " in\n" << r.out;
    const nlohmann::json e = nlohmann::json::parse(slurp(dir / "e.json"));
    EXPECT_EQ(e["schema"], "glint-explain/1");
    EXPECT_EQ(e["pixel"], nlohmann::json::array({41, 33}));
    EXPECT_EQ(e["samples"], 3);
    EXPECT_EQ(e["sample"], nlohmann::json::array({1, 1}));
    const nlohmann::json& rays = e["rays"];
    ASSERT_GE(rays.size(), 1u);
    EXPECT_EQ(rays[0]["kind"], "primary");
    EXPECT_TRUE(rays[0]["parent"].is_null());
    for (const auto& ray : rays)
        for (const auto& child : ray["children"])
            EXPECT_EQ(rays[child["ray"].get<std::size_t>()]["parent"], ray["index"]);
    EXPECT_FALSE(e["item_buffer"].is_null()); // hybrid by default
    EXPECT_EQ(e["tree_rays"]["primary"], 1);
    const Image image = read_png(dir / "a.png");
    const std::uint8_t* pixel = image.pixel(41, 33);
    EXPECT_EQ(e["pixel_bytes"], nlohmann::json::array({pixel[0], pixel[1], pixel[2]}));
}

// Bad input to explain: exit 2, one message, and no JSON written.
TEST(Cli, ExplainRefusesAPixelOrSampleOutsideTheImageAndItsGrid) {
    const fs::path dir = fresh_dir();
    const std::string scene = GLINT_SOURCE_DIR "/scenes/default.json --size 80x60 --mode ray ";
    for (const auto& [args, message] : std::initializer_list<std::pair<std::string, std::string>>{
             {"80 10", "pixel (80, 10) is outside the 80x60 image (X 0 to 79, Y 0 to 59)"},
             {"10 -1", "pixel (10, -1) is outside the 80x60 image"},
             {"10 10 --sample 3,0", "--sample 3,0 is outside the pixel's 3x3 grid of samples"},
             {"10 10 --sample 1", "--sample 1: expected A,B"},
             {"10 ten", "Y 'ten' is not a whole number"},
             {"10", "explain needs the pixel: glint explain [SCENE] X Y"},
             {"10 10 --json no/dir/e.json",
              "--json no/dir/e.json: directory no/dir does not exist"}}) {
        const bool json = args.find("--json") != std::string::npos;
        const Outcome r = glint(dir, "explain " + scene + args + (json ? "" : " --json e.json"));
        EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
        EXPECT_FALSE(fs::exists(dir / "e.json")) << args;
    }
    // Without a scene, a number that is not whole is still judged as the pixel's X, with the
    // same message as with a scene.
    for (const char* args : {"1.5 10", "1e3 10"}) {
        const Outcome r = glint(dir, std::string("explain ") + args + " --json e.json");
        EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
        const std::string x = std::string(args).substr(0, std::string(args).find(' '));
        EXPECT_NE(r.err.find("glint: error: X '" + x + "' is not a whole number"),
                  std::string::npos)
            << args << ": " << r.err;
        EXPECT_FALSE(fs::exists(dir / "e.json")) << args;
    }
}

TEST(Cli, OutputIntoAMissingDirectoryOrNotPngOrExrIsAnError) {
    const fs::path dir = fresh_dir();
    Outcome r = glint(dir, "render -o missing/dir/a.png");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("-o missing/dir/a.png: directory missing/dir does not exist"),
              std::string::npos)
        << r.err;
    r = glint(dir, "render -o a.jpg");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("glint writes PNG (.png) and OpenEXR (.exr) files"), std::string::npos)
        << r.err;
}

// --aov adds channels to an EXR: with a PNG, or a name that is no AOV, it is bad input (exit 2)
// and nothing is written; with an EXR, the file is written and the report names it.
TEST(Cli, AovsGoIntoAnExrAndAreRefusedForAPngOrAnUnknownName) {
    const fs::path dir = fresh_dir();
    Outcome r = glint(dir, "render --size 16x12 -o a.png --aov depth");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--aov depth: AOVs are channels of an OpenEXR file"), std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "a.png"));
    r = glint(dir, "render --size 16x12 -o a.exr --aov depth,albedo");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--aov albedo: not an AOV (depth, normal, id, cutoff)"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(dir / "a.exr"));
    r = glint(dir, "render --size 16x12 --mode ray -o a.exr --aov depth,normal,id,cutoff");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("glint: wrote a.exr"), std::string::npos) << r.out;
    const std::string exr = slurp(dir / "a.exr");
    ASSERT_GE(exr.size(), 4u);
    EXPECT_EQ(exr.substr(0, 4), std::string("\x76\x2f\x31\x01")); // OpenEXR's magic number
}

TEST(Cli, AnUnwritablePlaceIsRefusedBeforeRendering) {
    // /proc accepts no new files, even from root (CI runs as root, so a read-only directory
    // would not do). Every output flag of every command is checked before any work.
    const fs::path dir = fresh_dir();
    for (const char* args : {"render --size 8x6 -o /proc/glint-test.png",
                             "render --size 8x6 -o a.png --stats /proc/glint-test.json",
                             "compare --size 8x6 -o /proc/glint-test",
                             "compare --size 8x6 --json /proc/glint-test.json",
                             "bench --benchmark_out=/proc/glint-test.json"}) {
        const Outcome r = glint(dir, args);
        EXPECT_EQ(r.exit_code, 2) << args;
        EXPECT_NE(r.err.find("cannot write in /proc"), std::string::npos) << r.err;
        EXPECT_EQ(r.out, "") << args;
    }
    EXPECT_FALSE(fs::exists(dir / "a.png"));
}

TEST(Cli, AnImageLargerThanMemoryIsRefusedBeforeAllocating) {
#ifdef GLINT_SANITIZE
    GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: no ulimit -v under it";
#else
    // 16384² pixels need ~6 GiB in ray mode and ~16 GiB in hybrid mode; an address-space limit
    // of 4 GiB stands in for a small machine. The refusal comes at once, before any work.
    const fs::path dir = fresh_dir();
    for (const char* mode : {"ray", "hybrid"}) {
        const Outcome r =
            glint(dir, std::string("render --size 16384x16384 --samples 1 -o a.png --mode ") + mode,
                  "ulimit -v 4194304 &&");
        EXPECT_EQ(r.exit_code, 2) << mode << ": " << r.err;
        EXPECT_NE(r.err.find("a 16384x16384 image needs about"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("of memory is available: render it smaller (--size)"),
                  std::string::npos)
            << r.err;
        EXPECT_FALSE(fs::exists(dir / "a.png"));
    }
#endif
}

// The memory rule is one formula (app/options.h), which docs/SCENES.md quotes: the refusal's
// figures are the ones the doc's bytes a pixel and a sample give, and so is its example.
TEST(Cli, TheMemoryRuleIsTheOneScenesMdQuotes) {
#ifdef GLINT_SANITIZE
    GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: no ulimit -v under it";
#else
    const std::string doc = slurp(GLINT_SOURCE_DIR "/docs/SCENES.md");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(doc, m,
                                  std::regex(R"(× (\d+) bytes \(ray mode\) or (\d+) bytes \(hybrid )"
                                             R"(mode\), and in hybrid mode with N×N samples width × )"
                                             R"(height × N² × (\d+) bytes more.*: 16384 × 16384 in )"
                                             R"(ray mode needs ([0-9.]+) GiB)")))
        << "SCENES.md's image memory row";
    const double ray = std::stod(m[1]), hybrid = std::stod(m[2]), sample = std::stod(m[3]);
    const auto gib = [](double bytes) {
        char text[32];
        std::snprintf(text, sizeof text, "%.1f GiB", bytes / (1u << 30));
        return std::string(text);
    };
    EXPECT_EQ(gib(16384.0 * 16384 * ray), m[4].str() + " GiB");
    const fs::path dir = fresh_dir();
    const struct {
        std::string args;
        double bytes;
    } cases[] = {
        {"--size 16384x16384 --samples 1 --mode ray", 16384.0 * 16384 * ray},
        {"--size 16384x16384 --samples 1 --mode hybrid", 16384.0 * 16384 * hybrid},
        {"--size 1920x1080 --samples 8 --mode hybrid", 1920.0 * 1080 * (hybrid + 64 * sample)},
    };
    for (const auto& c : cases) {
        const Outcome r = glint(dir, "render -o a.png " + c.args, "ulimit -v 1048576 &&");
        EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.err;
        EXPECT_NE(r.err.find("needs about " + gib(c.bytes)), std::string::npos)
            << c.args << ": " << r.err;
    }
#endif
}

// The sample grid's item buffer counts too: 1920×1080 with 8×8 samples needs ~3.3 GiB in hybrid
// mode (24 B a sample), refused under a 2 GiB limit before any work, where ray mode, which
// keeps no sample store, fits.
TEST(Cli, ASampleGridLargerThanMemoryIsRefusedBeforeAllocating) {
#ifdef GLINT_SANITIZE
    GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: no ulimit -v under it";
#else
    const fs::path dir = fresh_dir();
    const Outcome r =
        glint(dir, "render --size 1920x1080 --samples 8 -o a.png", "ulimit -v 2097152 &&");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("a 1920x1080 image with 8x8 samples needs about 3."), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("with fewer samples or with --mode ray"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "a.png"));
#endif
}

TEST(Cli, NoGlContextIsAClearErrorNamingRayMode) {
    // Mesa's version override makes both OSMesa and EGL refuse a 3.3 core context.
    const fs::path dir = fresh_dir();
    for (const char* gl : {"osmesa", "egl"}) {
        const Outcome r = glint(dir, std::string("render --size 8x6 -o a.png --gl ") + gl,
                                "MESA_GL_VERSION_OVERRIDE=2.1");
        EXPECT_EQ(r.exit_code, 1) << gl;
        EXPECT_NE(r.err.find("no OpenGL for the item buffer"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("--mode ray"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir / "a.png"));
    }
    EXPECT_EQ(glint(dir, "render --size 8x6 -o a.png --mode ray", "MESA_GL_VERSION_OVERRIDE=2.1")
                  .exit_code,
              0);
}

TEST(Cli, HelpAndVersionExitZero) {
    const fs::path dir = fresh_dir();
    EXPECT_EQ(glint(dir, "--help").exit_code, 0);
    EXPECT_EQ(glint(dir, "render --help").exit_code, 0);
    EXPECT_EQ(glint(dir, "--version").exit_code, 0);
    EXPECT_EQ(glint(dir, "").exit_code, 2);
}

} // namespace
} // namespace glint
