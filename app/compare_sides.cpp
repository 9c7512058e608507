// `glint compare SCENE --a "FLAGS" --b "FLAGS"`: any two settings of one scene, their images, the
// heat map of their difference and the map of its causes, and per cause its pixels, its share of
// the error and the levels where the trees parted (docs/DIFFERENCES.md).
#include "app/compare.h"
#include "app/phase_json.h"

#include "frame/difference_maps.h"
#include "io/exr.h"
#include "io/extension.h"
#include "io/png.h"
#include "trace/stopwatch.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace glint {

namespace {

namespace fs = std::filesystem;

std::string trimmed(const std::string& text) {
    const std::size_t first = text.find_first_not_of(" \t\n");
    if (first == std::string::npos) return "";
    return text.substr(first, text.find_last_not_of(" \t\n") - first + 1);
}

} // namespace

Side parse_side(const std::string& flag, const std::string& text, const Scene& base,
                const SceneOptions& shared, const FrameOptions& frame) {
    std::string rest = trimmed(text);
    if (rest.empty())
        throw UsageError(flag + " is empty: give the side's render flags, e.g. " + flag +
                         " \"--max-depth 2\", or " + flag + " exact");
    const bool exact = rest == "exact" || rest.rfind("exact ", 0) == 0;
    if (exact) rest = trimmed(rest.substr(5));

    CLI::App parser{flag};
    parser.set_help_flag();
    parser.allow_extras(false);
    RenderOptions render;
    FrameOptions side_frame = frame; // what the side does not give stays the command's
    std::string precision;
    render.add_to(parser);
    side_frame.add_to(parser, true, false);
    CLI::Option* precision_option =
        parser.add_option("--precision", precision, "float or double (double: ray mode only)")
            ->check(CLI::IsMember(all_names<Precision>()));
    const std::string shared_why =
        "both sides render the same scene at the same size: give it outside " + flag;
    refuse_option(parser, "--size", shared_why);
    refuse_option(parser, "--camera", shared_why);
    refuse_option(parser, "--gl", "both sides draw with the same GL: give it outside " + flag);
    for (const char* own : {"-o,--output", "--json", "--exr", "--a", "--b", "--against"})
        refuse_option(parser, own, "the command's own, not a side's: give it outside " + flag,
                      std::string(own) != "--exr");
    try {
        parser.parse(rest, false);
    } catch (const CLI::ParseError& e) {
        throw UsageError(flag + " \"" + text + "\": " + e.what());
    }

    Side side;
    side.label = trimmed(text);
    side.scene = base;
    side.accel = shared.accel_kind();
    try {
        side.frame = side_frame.settings();
    } catch (const UsageError& e) {
        throw UsageError(flag + " \"" + text + "\": " + e.what());
    }
    if (exact) {
        const Mode given = side.frame.mode;
        make_exact(side);
        if (parser.get_option("--mode")->count()) side.frame.mode = given; // refused below
    }
    render.apply(side.scene); // what the side gives changes even `exact`
    if (render.accel_option->count()) side.accel = render.accel_kind();
    if (precision_option->count()) side.frame.precision = *from_name<Precision>(precision);
    if (side.frame.precision == Precision::f64 && side.frame.mode != Mode::ray)
        throw UsageError(flag + " \"" + text + "\": double precision" + (exact ? " (exact)" : "") +
                         " is the reference tracer, ray mode only: it draws no item buffer, so "
                         "--mode hybrid cannot go with it");
    return side;
}

namespace {

// What -o PREFIX writes: PREFIX-{a,b,heat,causes}.png, and the float error as PREFIX-heat.exr with
// --exr or a PREFIX ending in .exr.
struct Outputs {
    std::string prefix;
    bool exr = false;
};

Outputs outputs_of(const CompareArgs& args) {
    Outputs out{args.prefix, args.exr};
    if (extension_of(out.prefix) == ".exr") { // in any case, as render's -o reads it
        out.prefix = out.prefix.substr(0, out.prefix.size() - 4);
        out.exr = true;
    }
    return out;
}

struct Job {
    Side a, b;
};

Job prepare_sides(const CompareArgs& args) {
    const Outputs out = outputs_of(args);
    if (args.exr && args.prefix.empty())
        throw UsageError("--exr writes PREFIX-heat.exr: give -o PREFIX");
    if (!out.prefix.empty()) check_output(out.prefix + "-a.png", "-o");
    if (!args.json.empty()) check_output(args.json, "--json");
    const Scene base = args.scene.load();
    const auto side = [&](const char* flag, const CLI::Option* option, const std::string& text) {
        if (option->count()) return parse_side(flag, text, base, args.scene, args.frame);
        Side s; // not given: the command's own settings
        s.label = "(compare's own settings)";
        s.scene = base, s.accel = args.scene.accel_kind(), s.frame = args.frame.settings();
        return s;
    };
    Job job{side("--a", args.a_option, args.a), side("--b", args.b_option, args.b)};
    check_frame_memory(job.a.scene, job.a.frame.mode, 2);
    check_frame_memory(job.b.scene, job.b.frame.mode, 2);
    return job;
}

// The float error, |A − B| per channel in linear radiance.
FloatImage error_image(const RenderResult& a, const RenderResult& b) {
    FloatImage out(a.radiance.width, a.radiance.height);
    for (std::size_t i = 0; i < out.rgb.size(); ++i)
        out.rgb[i] = std::abs(a.radiance.rgb[i] - b.radiance.rgb[i]);
    return out;
}

std::string levels_text(const CauseTally& t) {
    std::string text;
    for (std::size_t level = 0; level < t.levels.size(); ++level)
        if (t.levels[level] > 0)
            text += (text.empty() ? "" : " ") + std::to_string(level) + ":" +
                    std::to_string(t.levels[level]);
    return text;
}

void print_sides(const CompareArgs& args, const RenderedSide& a, const RenderedSide& b,
                 const FrameDifference& d, const ImageDifference& diff) {
    const Scene& scene = a.side().scene;
    const double ta = a.frame().times.per_frame(), tb = b.frame().times.per_frame();
    std::printf("glint compare: %s, %dx%d, %zu objects\n", args.scene.scene_path().c_str(),
                scene.camera.width, scene.camera.height, scene.objects.size());
    std::printf("A: %-28s %s\n", a.side().label.c_str(), describe_side(a.side()).c_str());
    std::printf("B: %-28s %s\n", b.side().label.c_str(), describe_side(b.side()).c_str());
    std::printf("frame time: A %.4f s, B %.4f s, B/A %.3f (each less the one-time GL set-up)\n\n",
                ta, tb, tb / ta);
    const double pixels = static_cast<double>(d.causes.size());
    std::printf("differing pixels:  %llu of %.0f (%.4f%%)\n",
                static_cast<unsigned long long>(d.differing), pixels,
                100 * static_cast<double>(d.differing) / pixels);
    if (std::isinf(diff.psnr_db))
        std::printf("PSNR:              inf (identical bytes)\n");
    else
        std::printf("PSNR:              %.2f dB\n", diff.psnr_db);
    std::printf("radiance error:    RMSE %.3g, largest %.3g (linear, unclamped)\n", diff.rmse,
                diff.max_radiance_error);
    std::printf("causes found in:   %.4f s (%llu differing pixels traced again on both sides, "
                "%.3f of A's frame; the rest took other sample grids)\n\n",
                d.trace_seconds, static_cast<unsigned long long>(d.traced), d.trace_seconds / ta);
    std::printf("%-10s %10s %9s %12s  %s\n", "cause", "pixels", "share", "largest", "by level");
    for (std::size_t c = 1; c < kCauses; ++c) {
        const CauseTally& t = d.tallies[c];
        std::printf("%-10s %10llu %8.2f%% %12.4g  %s\n", name_of(static_cast<Cause>(c)).data(),
                    static_cast<unsigned long long>(t.pixels), 100 * d.share(static_cast<Cause>(c)),
                    t.largest, levels_text(t).c_str());
    }
}

nlohmann::ordered_json side_json(const RenderedSide& s) {
    return {{"flags", s.side().label},
            {"settings", describe_side(s.side())},
            {"seconds", s.frame().times.per_frame()},
            {"phases", phase_seconds_json(s.frame().times)}};
}

nlohmann::ordered_json sides_json(const CompareArgs& args, const RenderedSide& a,
                                  const RenderedSide& b, const FrameDifference& d,
                                  const ImageDifference& diff) {
    nlohmann::ordered_json causes = nlohmann::ordered_json::object();
    for (std::size_t c = 1; c < kCauses; ++c) {
        const CauseTally& t = d.tallies[c];
        nlohmann::ordered_json entry = {{"pixels", t.pixels},
                                        {"share", d.share(static_cast<Cause>(c))},
                                        {"largest_error", t.largest}};
        const auto cause = static_cast<Cause>(c);
        if (cause == Cause::depth || cause == Cause::cutoff || cause == Cause::secondary) {
            nlohmann::ordered_json levels = nlohmann::ordered_json::object();
            for (std::size_t level = 0; level < t.levels.size(); ++level)
                if (t.levels[level] > 0) levels[std::to_string(level)] = t.levels[level];
            entry["levels"] = levels;
        }
        causes[std::string(name_of(cause))] = entry;
    }
    const Scene& scene = a.side().scene;
    return {{"schema", "glint-compare-sides/1"},
            {"scene", args.scene.scene_path().string()},
            {"width", scene.camera.width},
            {"height", scene.camera.height},
            {"pixels", d.causes.size()},
            {"a", side_json(a)},
            {"b", side_json(b)},
            {"time_ratio", b.frame().times.per_frame() / a.frame().times.per_frame()},
            {"differing_pixels", d.differing},
            {"psnr_db", std::isinf(diff.psnr_db) ? nlohmann::ordered_json(nullptr)
                                                 : nlohmann::ordered_json(diff.psnr_db)},
            {"rmse_radiance", diff.rmse},
            {"max_error_radiance", diff.max_radiance_error},
            {"squared_error", d.squared_error},
            {"traced_pixels", d.traced},
            {"trace_seconds", d.trace_seconds},
            {"causes", causes}};
}

} // namespace

void check_compare_sides(const CompareArgs& args) {
    prepare_sides(args);
}

ComparedSides compare_sides(const CompareArgs& args, const std::atomic<bool>* cancel,
                            std::FILE* progress) {
    Job job = prepare_sides(args);
    job.a.frame.cancel = job.b.frame.cancel = cancel;
    if (progress) std::fprintf(progress, "glint: rendering A (%s)\n", describe_side(job.a).c_str());
    auto a = std::make_unique<const RenderedSide>(std::move(job.a));
    if (cancel && *cancel) throw Cancelled();
    if (progress) std::fprintf(progress, "glint: rendering B (%s)\n", describe_side(job.b).c_str());
    auto b = std::make_unique<const RenderedSide>(std::move(job.b));
    if (cancel && *cancel) throw Cancelled();
    const FrameDifference d = difference(*a, *b, outputs_of(args).exr);
    const ImageDifference diff = compare_results(a->frame().result, b->frame().result);
    std::string json = sides_json(args, *a, *b, d, diff).dump(2) + "\n";
    return {std::move(a), std::move(b), d, diff, std::move(json)};
}

int run_compare_sides(const CompareArgs& args) {
    const ComparedSides c = compare_sides(args, nullptr, stderr);
    const Outputs out = outputs_of(args);
    const RenderedSide &a = *c.a, &b = *c.b;
    print_sides(args, a, b, c.difference, c.image);
    if (!out.prefix.empty()) {
        const Image image_a = a.frame().result.bytes();
        write_png(out.prefix + "-a.png", image_a);
        write_png(out.prefix + "-b.png", b.frame().result.bytes());
        write_png(out.prefix + "-heat.png", heat_map(c.difference));
        write_png(out.prefix + "-causes.png", cause_map(c.difference, image_a));
        std::string wrote = out.prefix + "-{a,b,heat,causes}.png";
        if (out.exr) {
            const FloatImage error = error_image(a.frame().result, b.frame().result);
            write_exr(out.prefix + "-heat.exr", {&error});
            wrote += " and " + out.prefix + "-heat.exr";
        }
        std::printf("\nwrote %s\n", wrote.c_str());
    }
    if (!args.json.empty()) write_file_atomically(args.json, c.json);
    return 0;
}

} // namespace glint
