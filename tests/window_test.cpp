// The preview in a real window (run under `xvfb-run -a`, see CMakeLists.txt): scripted runs save
// the window's framebuffer, which must show what the headless passes compute.
#include "test_scenes.h"

#include "frame/difference_maps.h"
#include "frame/explain.h"
#include "frame/frame.h"
#include "io/gltf_loader.h"
#include "io/png.h"
#include "preview/preview.h"
#include "preview/ray_overlay.h"
#include "preview/views.h"
#include "trace/image_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace glint {
namespace {

namespace fs = std::filesystem;

using testing::shipped;

// Runs the scripted preview and returns its screenshot (the panel hidden unless `panel`).
Image screenshot(const Scene& scene, View view, const std::string& name, bool panel = false) {
    const fs::path path = fs::path(::testing::TempDir()) /
                          ("glint-preview-" + name + "-" + std::string(name_of(view)) + ".png");
    fs::remove(path);
    PreviewOptions options;
    options.scene = scene;
    options.scene_name = name + ".json";
    options.frames = 2;
    options.screenshot = path;
    options.view = view;
    options.panel = panel;
    try {
        EXPECT_EQ(run_preview(options), 0);
        return read_png(path);
    } catch (const std::exception& e) {
        ADD_FAILURE() << name << ", " << view_label(view) << ": " << e.what();
        return {};
    }
}

Frame headless_hybrid(const Scene& scene) {
    return render_frame(World(scene), FrameSettings{});
}

// The acceptance test: the refined window shows the headless hybrid render of the same camera.
// The trace is the same code on the same item buffer, and both GL passes are llvmpipe, so the
// images are identical here; the bound allows what a different rasterizer could change: ids at
// silhouette pixels, which exact resolve traces in full, so at most float-rounding ties there
// (the same 0.01 % of pixels beyond 1/255 that hybrid and ray images are held to).
TEST(Preview, ScriptedScreenshotOfTheDefaultSceneMatchesTheHeadlessHybridRender) {
    // Smaller under the sanitizers (test_scenes.h): the claim holds at any size.
    Scene scene = shipped("default");
    scene.camera.width /= testing::kSanitizerShrink,
        scene.camera.height /= testing::kSanitizerShrink;
    const Image shown = screenshot(scene, View::final, "default");
    ASSERT_EQ(shown.width, scene.camera.width);
    ASSERT_EQ(shown.height, scene.camera.height);
    const ImageDifference diff = compare_images(headless_hybrid(scene).result.bytes(), shown);
    EXPECT_LE(diff.fraction_over_one, 1e-4) << diff.pixels_over_one << " pixels";
}

// Every view of every shipped scene, at a small size: the final view is the headless render,
// the item-buffer view is the headless item buffer in false colour, and each other view is an
// image of its own (not the final image, not one flat colour).
TEST(Preview, EveryViewOfEveryShippedSceneShowsWhatItShould) {
    for (const char* name : testing::kShippedScenes) {
        SCOPED_TRACE(name);
        Scene scene = shipped(name);
        scene.camera.width = 160, scene.camera.height = 120;
        // One sample: the views are the point here; the test above refines to the samples.
        scene.render.samples = 1;
        const Frame headless = headless_hybrid(scene);
        const Image final_view = screenshot(scene, View::final, name);
        EXPECT_LE(compare_images(headless.result.bytes(), final_view).fraction_over_one, 1e-4);
        const Image items = screenshot(scene, View::items, name);
        const IdImage& ids = headless.items->ids;
        EXPECT_EQ(items.rgb, false_colour(ids.ids, ids.width, ids.height).rgb);
        for (const View view : {View::depth, View::normals, View::difference, View::reflections}) {
            SCOPED_TRACE(std::string(view_label(view)));
            const Image shown = screenshot(scene, view, name);
            ASSERT_EQ(shown.width, 160);
            ASSERT_EQ(shown.height, 120);
            EXPECT_NE(shown.rgb, final_view.rgb);
            EXPECT_NE(std::count(shown.rgb.begin(), shown.rgb.end(), shown.rgb[0]),
                      static_cast<std::ptrdiff_t>(shown.rgb.size()));
        }
    }
}

// Issue 19's reuse: settings that leave the camera (depth, cut-off) restart the trace on the item
// buffer already drawn; a raster change uploads and draws again. The count is the preview's own
// (ItemBuffer::draws), printed when it exits.
std::size_t item_buffer_draws(const std::string& keys) {
    PreviewOptions options;
    options.scene = shipped("default");
    options.scene.camera.width = 160, options.scene.camera.height = 120;
    options.scene.render.samples = 1;
    options.scene_name = "default.json";
    options.frames = 2;
    options.keys = keys;
    ::testing::internal::CaptureStdout();
    const int code = run_preview(options);
    const std::string out = ::testing::internal::GetCapturedStdout();
    EXPECT_EQ(code, 0);
    const std::size_t at = out.find("item buffers drawn: ");
    if (at == std::string::npos) {
        ADD_FAILURE() << "no draw count in: " << out;
        return 0;
    }
    return std::stoul(out.substr(at + 20));
}

TEST(Preview, ChangingDepthOrCutOffDrawsNoItemBuffer) {
    EXPECT_EQ(item_buffer_draws(""), 1u);
    EXPECT_EQ(item_buffer_draws("[[],.,"), 1u); // depth − − +, cut-off ÷2 ×2 ÷2
    EXPECT_EQ(item_buffer_draws("E2T1"), 1u);   // resolve, a view, the tracer, the final view
    EXPECT_EQ(item_buffer_draws("[M]"), 2u);    // the raster mode: a new upload, a new draw
    EXPECT_EQ(item_buffer_draws("R=-"), 3u);    // reset (camera unchanged), tessellation twice
}

// Runs a scripted preview of `options` to a screenshot, with its standard output.
std::pair<Image, std::string> scripted(PreviewOptions options, const std::string& name) {
    const fs::path path = fs::path(::testing::TempDir()) / ("glint-preview-" + name + ".png");
    fs::remove(path);
    options.frames = std::max(options.frames, 2);
    options.screenshot = path;
    ::testing::internal::CaptureStdout();
    int code = -1;
    try {
        code = run_preview(options);
    } catch (const std::exception& e) {
        ADD_FAILURE() << name << ": " << e.what();
    }
    const std::string out = ::testing::internal::GetCapturedStdout();
    EXPECT_EQ(code, 0) << name;
    return {fs::exists(path) ? read_png(path) : Image{}, out};
}

PreviewOptions preview_of(const std::string& name, int width, int height) {
    PreviewOptions options;
    options.scene = shipped(name, width, height);
    options.scene.render.samples = 1;
    options.scene_name = name + ".json";
    return options;
}

// From "pixel (" to the end of the "rays:" line: the explanation without its first line, which
// names how it was asked for (the preview, or the command line's settings).
std::string explanation_body(const std::string& out) {
    const std::size_t from = out.find("pixel (");
    const std::size_t rays = out.find("rays: this tree", from);
    if (from == std::string::npos || rays == std::string::npos) return "(none in: " + out + ")";
    return out.substr(from, out.find('\n', rays) - from);
}

// How far point (x, y) lies from segment s, in pixels.
double distance_to(const OverlaySegment& s, double x, double y) {
    const double dx = s.x1 - s.x0, dy = s.y1 - s.y0;
    const double length2 = dx * dx + dy * dy;
    const double t =
        length2 > 0 ? std::clamp(((x - s.x0) * dx + (y - s.y0) * dy) / length2, 0.0, 1.0) : 0.0;
    return std::hypot(x - (s.x0 + t * dx), y - (s.y0 + t * dy));
}

// Issue 21: a scripted click draws the pixel's ray tree into the scene and prints the same
// explanation as `glint explain`. Against the same run without the click, the screenshot changes
// only inside the panel (which now shows the explanation) and along the tree's segments, as
// tree_segments projects them: within 4 pixels of a line (2 wide, antialiased), 9 of the primary
// ray's ring (radius 6). And it does change along them.
TEST(Preview, AClickDrawsThePixelsTreeAlongItsRaysAndPrintsWhatExplainPrints) {
    const int width = 640, height = 480, x = 130, y = 250; // the red ellipsoid, left of the panel
    PreviewOptions options = preview_of("default", width, height);
    const auto [before, unused] = scripted(options, "unclicked");
    options.click = std::pair{x, y};
    const auto [after, out] = scripted(options, "clicked");
    ASSERT_EQ(before.width, width);
    ASSERT_EQ(after.width, width);

    const World world(options.scene);
    const PixelExplanation e = explain_pixel(world, {}, x, y, 0, 0);
    ASSERT_GT(e.rays.size(), 1u) << "the pixel should reflect";
    const std::vector<OverlaySegment> segments = tree_segments(world, e);
    const PanelPlace panel = panel_place(width, height);
    int along = 0, stray = 0;
    for (int py = 0; py < height; ++py) {
        for (int px = 0; px < width; ++px) {
            if (!std::equal(before.pixel(px, py), before.pixel(px, py) + 3, after.pixel(px, py))) {
                if (px >= panel.x - 2 && px <= panel.x + panel.width + 2 &&
                    py <= panel.y + panel.height + 2)
                    continue;
                bool near = false;
                for (const OverlaySegment& s : segments)
                    near |= distance_to(s, px + 0.5, py + 0.5) <=
                            (s.kind == OverlaySegment::Kind::primary ? 9 : 4);
                (near ? along : stray) += 1;
            }
        }
    }
    EXPECT_EQ(stray, 0) << "pixels changed away from the tree and the panel";
    EXPECT_GT(along, 100) << "the tree was not drawn";

    const std::string command = std::string("'" GLINT_BINARY "' explain ") + GLINT_SOURCE_DIR +
                                "/scenes/default.json " + std::to_string(x) + " " +
                                std::to_string(y) + " --size 640x480 --samples 1";
    FILE* pipe = popen(command.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string cli;
    char buffer[4096];
    while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) cli.append(buffer, n);
    EXPECT_EQ(pclose(pipe), 0);
    EXPECT_EQ(explanation_body(out), explanation_body(cli));
}

// The panel's settings, set through its own path (scripted --set): the trace follows them (the
// screenshot is the headless render with those settings) and the preview reports them.
TEST(Preview, ThePanelsControlsChangeWhatIsTraced) {
    PreviewOptions options = preview_of("default", 320, 240);
    options.settings = {"mode=ray", "depth=0", "accel=kd", "panel=off"};
    const auto [shown, out] = scripted(options, "panel-settings");
    EXPECT_NE(out.find("glint: panel: depth = 0"), std::string::npos) << out;
    EXPECT_NE(out.find("settings: ray, depth 0, cut-off 0.01, kd, view final"), std::string::npos)
        << out;
    Scene expected = options.scene;
    expected.render.max_depth = 0;
    FrameSettings ray;
    ray.mode = Mode::ray;
    const Frame headless = render_frame(World(expected, AccelKind::kd), ray);
    EXPECT_EQ(shown.rgb, headless.result.bytes().rgb);
    EXPECT_NE(shown.rgb, render_frame(World(options.scene), ray).result.bytes().rgb);
}

// An animated model's time (the panel's Animation slider, scripted --set time=T): the window
// shows the model posed at T, its skin included, as a sequence's frame at T renders it (the
// camera the one it opened with, as a sequence keeps its first frame's).
TEST(Preview, TheTimeSettingPosesAnAnimatedModel) {
    const std::string model =
        (fs::path(GLINT_SOURCE_DIR) / "models/khronos/RiggedSimple/glTF/RiggedSimple.gltf").string();
    ModelOptions at_zero;
    at_zero.time = 0;
    at_zero.size = std::pair{160, 120};
    PreviewOptions options;
    options.scene = load_gltf(model, at_zero);
    options.scene.render.samples = 1;
    options.scene_name = model;
    options.settings = {"mode=ray", "time=1", "panel=off"};
    const auto [shown, out] = scripted(options, "time");
    EXPECT_NE(out.find("glint: panel: time = 1"), std::string::npos) << out;
    Scene expected = options.scene;
    ASSERT_TRUE(expected.animation);
    expected.animation->pose(expected, 1.0);
    FrameSettings ray;
    ray.mode = Mode::ray;
    EXPECT_EQ(shown.rgb, render_frame(World(expected), ray).result.bytes().rgb);
    EXPECT_NE(shown.rgb, render_frame(World(options.scene), ray).result.bytes().rgb) << "it moved";
}

// The reference (docs/PREVIEW.md, "The panel"): the cause map view against exact is `glint
// compare`'s cause map of the same two settings, and a click in it prints the pixel's two trees
// with the cause the map paints there.
TEST(Preview, TheCauseMapViewIsComparesAndAClickShowsBothTrees) {
    PreviewOptions options = preview_of("mirrors", 160, 120);
    Side live{"live", options.scene, std::nullopt, FrameSettings{}};
    live.scene.render.max_depth = 2;
    Side exact{"exact", options.scene, std::nullopt, FrameSettings{}};
    make_exact(exact);
    const RenderedSide a(live), b(exact);
    const FrameDifference d = difference(a, b, false);
    const Image map = cause_map(d, a.frame().result.bytes());
    const auto first = std::find(d.causes.begin(), d.causes.end(), Cause::depth);
    ASSERT_NE(first, d.causes.end()) << "depth 2 should differ from exact in the mirrors";
    const auto p = static_cast<int>(first - d.causes.begin());
    options.settings = {"depth=2", "reference=exact", "view=causes", "panel=off"};
    options.click = std::pair{p % 160, p / 160};
    const auto [shown, out] = scripted(options, "reference-causes");
    ASSERT_EQ(shown.width, 160);
    ASSERT_EQ(shown.height, 120);
    int differing = 0;
    for (int y = 0; y < 120; ++y)
        for (int x = 0; x < 160; ++x)
            differing += !std::equal(shown.pixel(x, y), shown.pixel(x, y) + 3, map.pixel(x, y));
    EXPECT_LE(differing, 2) << "pixels where the view is not compare's cause map";
    EXPECT_NE(out.find("cause: depth"), std::string::npos) << out;
    EXPECT_NE(out.find("<- depth"), std::string::npos) << out;
    EXPECT_NE(out.find("against exact"), std::string::npos) << out;
}

// G hides the panel (and an explained tree): the screenshot is then the render alone.
TEST(Preview, GHidesThePanelForCleanScreenshots) {
    PreviewOptions options = preview_of("default", 320, 240);
    const Image render = render_frame(World(options.scene), FrameSettings{}).result.bytes();
    const auto [with_panel, unused] = scripted(options, "with-panel");
    EXPECT_NE(with_panel.rgb, render.rgb);
    options.keys = "G";
    options.click = std::pair{60, 150};
    const auto [hidden, out] = scripted(options, "panel-hidden");
    EXPECT_NE(out.find("pixel (60, 150)"), std::string::npos);
    EXPECT_LE(compare_images(render, hidden).fraction_over_one, 1e-4);
}

} // namespace
} // namespace glint
