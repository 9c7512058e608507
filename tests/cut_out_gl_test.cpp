// Cut-outs (DESIGN §13) in the item buffer: the id pass discards the fragments the tracer cuts
// away, and the exact resolve keeps hybrid = ray byte for byte where GL's texture filtering and
// the tracer's disagree at the mask's edge. Both GL backends.
#include "cut_out_scene.h"
#include "test_scenes.h"

#include "frame/frame.h"
#include "raster/item_buffer.h"
#include "raster/tessellation.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

class CutOutGl : public ::testing::TestWithParam<GlBackend> {};

// Away from the mask's edge (a 3×3 neighbourhood of one object by ray), the item buffer names
// what the ray hits: the sphere or background through the masked half, the quad on the other.
TEST_P(CutOutGl, TheIdPassDiscardsTheMaskedFragments) {
    const Scene scene = testing::cut_out_scene(96, 72);
    const World world(scene);
    const std::vector<Hit> by_ray = primary_hits_by_ray(world);
    const auto context = make_context(GetParam());
    ItemBuffer items;
    items.upload(world, RasterMode::mesh, kDefaultTessellation);
    const ItemBufferResult drawn = items.draw(world);
    const int w = scene.camera.width, h = scene.camera.height;
    int masked = 0, kept = 0;
    for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
            const std::uint32_t id = by_ray[y * w + x].object + 1;
            bool interior = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    interior &= by_ray[(y + dy) * w + x + dx].object + 1 == id;
            if (!interior) continue;
            ASSERT_EQ(drawn.ids.ids[y * w + x], id) << "pixel " << x << "," << y;
            const bool left = x < w / 2;
            masked += left && id == testing::kCutOutSphere + 1;
            kept += !left && id == testing::kCutOutQuad + 1;
        }
    EXPECT_GT(masked, 100); // the sphere seen through the quad's masked half
    EXPECT_GT(kept, 1000);
}

// Hybrid = ray, byte for byte, with 3×3 samples, uniform and adaptive, in every raster mode, on
// the zoomed mask, which GL and the tracer cut differently inside a region of one id.
TEST_P(CutOutGl, HybridEqualsRayModeOnACutOutScene) {
    for (const bool zoomed : {true, false}) {
        for (const Antialias aa : {Antialias::adaptive, Antialias::uniform}) {
            Scene scene = zoomed ? testing::zoomed_cut_out_scene(80, 60)
                                 : testing::cut_out_scene(80, 60);
            scene.render.samples = 3;
            scene.render.antialias = aa;
            const World world(scene);
            for (const RasterMode raster : all_values<RasterMode>()) {
                FrameSettings settings{Mode::ray,      GetParam(), raster, kDefaultTessellation,
                                       Resolve::exact, 0};
                const Frame ray = render_frame(world, settings);
                settings.mode = Mode::hybrid;
                const Frame hybrid = render_frame(world, settings);
                EXPECT_EQ(ray.result.bytes().rgb, hybrid.result.bytes().rgb)
                    << (zoomed ? "zoomed " : "") << name_of(aa) << " " << name_of(raster);
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, CutOutGl, ::testing::Values(GlBackend::osmesa, GlBackend::egl),
                         [](const auto& info) { return std::string(name_of(info.param)); });

} // namespace
} // namespace glint
