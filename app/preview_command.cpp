// `glint preview`: the scene in a window (preview/preview.h), or scripted for tests and docs.
#include "app/options.h"

#include "io/extension.h"
#include "preview/preview.h"
#include "preview/window.h"

#include <cctype>
#include <cstdio>
#include <iostream>

namespace glint {
namespace {

struct PreviewArgs {
    SceneOptions scene;
    FrameOptions frame;
    int frames = 0;
    std::string screenshot;
    double spin = 0;
    std::string keys;
    std::string view = "final";
    std::string click;
    std::vector<std::string> settings;
    bool no_panel = false;
};

PreviewOptions prepare(const PreviewArgs& args) {
    PreviewOptions options;
    options.frames = args.frames;
    options.spin = args.spin;
    options.keys = args.keys;
    options.screenshot = args.screenshot;
    if (!options.screenshot.empty()) {
        if (extension_of(options.screenshot) != ".png")
            throw UsageError("--screenshot " + args.screenshot + ": glint writes PNG files (.png)");
        check_output(options.screenshot, "--screenshot");
    }
    if (args.spin != 0 && args.frames == 0)
        throw UsageError("--spin: orbits during the --frames N scripted frames; give --frames");
    if (!args.keys.empty() && args.frames == 0)
        throw UsageError("--keys " + args.keys +
                         ": pressed during the --frames N scripted frames; give --frames");
    for (const char key : args.keys)
        if (!std::isgraph(static_cast<unsigned char>(key)))
            throw UsageError("--keys " + args.keys +
                             ": keys are printable characters, one a frame (e.g. \"[]M\")");
    for (const std::string& assignment : args.settings) {
        try {
            check_preview_setting(assignment);
        } catch (const std::invalid_argument& e) {
            throw UsageError(std::string("--set ") + e.what());
        }
    }
    options.settings = args.settings;
    options.panel = !args.no_panel;
    // An animated glTF model is read with its animation, posed at --time (default 0), so that
    // the panel's Animation slider and the space key can play it.
    SceneOptions scene = args.scene;
    scene.animate_if_any = true;
    options.scene = scene.load();
    options.time = scene.time;
    options.scene_name = args.scene.scene_path().string();
    if (!args.click.empty()) {
        const Camera& camera = options.scene.camera;
        int x = 0, y = 0;
        char end = 0;
        if (std::sscanf(args.click.c_str(), "%d,%d%c", &x, &y, &end) != 2)
            throw UsageError("--click " + args.click + ": expected X,Y (the pixel's column, row)");
        if (x < 0 || y < 0 || x >= camera.width || y >= camera.height)
            throw UsageError("--click " + args.click + ": the pixel is outside the " +
                             std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                             " image");
        options.click = std::pair{x, y};
    }
    options.accel = args.scene.accel_kind();
    options.frame = args.frame.settings();
    options.view = *from_name<View>(args.view); // checked by --view
    // The preview holds the item buffer, its flat image and four traced views of each frame
    // (and its sample grids, refined tile by tile, need no item buffer of their own).
    Scene one_sample = options.scene;
    one_sample.render.samples = 1;
    check_frame_memory(one_sample, Mode::hybrid, 2);
    return options;
}

int run(const PreviewArgs& args) {
    const PreviewOptions options = prepare(args);
    try {
        return run_preview(options);
    } catch (const NoDisplayError& e) {
        std::cerr << "glint: error: no display to open the preview window on (" << e.what()
                  << ")\nglint: render without a window with `glint render " << options.scene_name
                  << "`, or give the preview a virtual display: `xvfb-run -a glint preview "
                  << options.scene_name << "`\n";
        return 1;
    } catch (const GlError& e) {
        std::cerr << "glint: error: the preview window has no usable OpenGL: " << e.what()
                  << "\nglint: render without a window with `glint render`\n";
        return 1;
    }
}

} // namespace

Command add_preview_command(CLI::App& app) {
    auto args = std::make_shared<PreviewArgs>();
    CLI::App* cmd = app.add_subcommand(
        "preview", "Open a scene in a window: fly the camera and watch the trace refine (H: keys)");
    args->scene.add_to(*cmd);
    args->frame.add_to(*cmd, true, false);
    refuse_option(*cmd, "--gl",
                  "the preview draws with its window's own GL context (GLFW); --gl chooses the "
                  "headless back end of render, explain, compare and tradeoff");
    cmd->add_option("--frames", args->frames,
                    "Scripted: draw at least N frames, wait until the trace has refined, then exit")
        ->check(CLI::Range(0, 1000000));
    cmd->add_option("--screenshot", args->screenshot,
                    "Scripted: save the refined window's framebuffer to this PNG, then exit");
    cmd->add_option("--spin", args->spin,
                    "Scripted: orbit this many degrees each of the --frames frames (to measure "
                    "responsiveness while the trace restarts)")
        ->check(CLI::Range(-360.0, 360.0));
    cmd->add_option("--keys", args->keys,
                    "Scripted: press these keys, one a frame from the second (e.g. \"[],.\": "
                    "depth and cut-off; H lists the keys)");
    cmd->add_option("--view", args->view,
                    "The view shown first: final, items (item buffer), depth, normals, "
                    "difference (ray vs hybrid) or reflections (reflection depth)")
        ->capture_default_str()
        ->check(CLI::IsMember(all_names<View>()));
    cmd->add_option("--click", args->click,
                    "Click pixel X,Y once the trace has finished: explain it (as glint explain "
                    "does) and draw its ray tree");
    cmd->add_option("--set", args->settings,
                    "Scripted: set one of the panel's settings, name=value, through the panel's "
                    "own path on the second frame (mode, raster, resolve, depth, cutoff, tess, "
                    "samples, aa, accel, view, panel); repeatable");
    cmd->add_flag("--no-panel", args->no_panel,
                  "Start with the panel hidden (G shows it), e.g. for clean screenshots");
    return {cmd, [args] { prepare(*args); },
            [args] { return guarded([&] { return run(*args); }); }};
}

} // namespace glint
