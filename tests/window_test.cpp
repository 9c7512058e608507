// The preview in a real window (run under `xvfb-run -a`, see CMakeLists.txt): scripted runs save
// the window's framebuffer, which must show what the headless passes compute.
#include "test_scenes.h"

#include "frame/frame.h"
#include "preview/preview.h"
#include "preview/views.h"
#include "trace/image_metrics.h"
#include "trace/scene_loader.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace glint {
namespace {

namespace fs = std::filesystem;

using testing::shipped;

// Runs the scripted preview and returns its screenshot.
Image screenshot(const Scene& scene, View view, const std::string& name) {
    const fs::path path = fs::path(::testing::TempDir()) /
                          ("glint-preview-" + name + "-" + std::string(name_of(view)) + ".png");
    fs::remove(path);
    PreviewOptions options;
    options.scene = scene;
    options.scene_name = name + ".json";
    options.frames = 2;
    options.screenshot = path;
    options.view = view;
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
    const Scene scene = shipped("default");
    const Image shown = screenshot(scene, View::final, "default");
    ASSERT_EQ(shown.width, scene.camera.width);
    ASSERT_EQ(shown.height, scene.camera.height);
    const ImageDifference diff = compare_images(headless_hybrid(scene).result.image, shown);
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
        EXPECT_LE(compare_images(headless.result.image, final_view).fraction_over_one, 1e-4);
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

} // namespace
} // namespace glint
