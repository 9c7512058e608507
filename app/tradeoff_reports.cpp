// `glint tradeoff`'s reports: the CSV, a plot per scene (gnuplot: SVG and PNG) and the markdown
// summary (docs/TRADEOFF.md).
#include "app/tradeoff.h"

#include "io/error.h"

#include "io/write_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <map>
#include <sstream>

namespace glint {
namespace tradeoff {

namespace {

std::string format(const char* pattern, double value) {
    char text[64];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

// Indices of the runs on the Pareto front of (frame time, PSNR): none is both faster and closer.
// Runs measured against different references (the exact image, the 8×8 grid) each have their own.
std::vector<std::size_t> pareto_front(const std::vector<Run>& runs) {
    std::vector<std::size_t> order(runs.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return runs[a].frame_seconds() < runs[b].frame_seconds();
    });
    std::vector<std::size_t> front;
    for (const bool against_grid : {false, true}) {
        double best = -1;
        for (const std::size_t i : order)
            if (runs[i].setting.against_grid == against_grid && runs[i].diff.psnr_db > best)
                front.push_back(i), best = runs[i].diff.psnr_db;
    }
    return front;
}

// Runs gnuplot on `script`; throws when it fails.
void gnuplot(const std::string& script) {
    FILE* pipe = popen("gnuplot", "w");
    if (!pipe) throw std::runtime_error("cannot run gnuplot");
    std::fwrite(script.data(), 1, script.size(), pipe);
    if (pclose(pipe) != 0) throw std::runtime_error("gnuplot failed on the plot script");
}

// The cause most of `sum`'s squared error owes to, as the summary writes it: "depth (92%)".
std::string dominant(const CauseFigures& sum) {
    Cause top = Cause::none;
    std::uint64_t pixels = 0;
    for (std::size_t c = 1; c < kCauses; ++c) {
        const auto cause = static_cast<Cause>(c);
        pixels += sum.at(cause).pixels;
        if (sum.at(cause).squared_error > 0 &&
            (top == Cause::none || sum.at(cause).squared_error > sum.at(top).squared_error))
            top = cause;
    }
    if (top == Cause::none) return pixels > 0 ? "below a byte's error" : "no pixel differs";
    return std::string(name_of(top)) + format(" (%.0f%%)", 100 * sum.share(top));
}

// Per knob, which cause its runs' error owes most to (docs/DIFFERENCES.md, "In glint tradeoff"):
// the squared radiance error against the exact image, summed by cause over every run the knob
// reached; and the same beyond the default setting's own error (each cause's excess over the
// default run's, which every knob's runs share: its depth and cut-off against the exact image).
std::string knob_causes(const std::vector<Run>& runs, const Scene& scene) {
    Setting base; // the sweep's default setting (tradeoff.h)
    base.max_depth = scene.render.max_depth;
    base.min_reflectivity = scene.render.min_reflectivity;
    const std::string base_label = base.label(scene);
    const Run* default_run = nullptr;
    for (const Run& r : runs)
        if (r.label == base_label) default_run = &r;
    std::vector<std::string> knobs;
    std::map<std::string, std::pair<CauseFigures, CauseFigures>> sums; // all, beyond the default
    for (const Run& r : runs) {
        if (r.setting.against_grid) continue;
        std::istringstream names(r.knobs);
        for (std::string knob; std::getline(names, knob, '+');) {
            if (!sums.count(knob)) knobs.push_back(knob);
            auto& [all, beyond] = sums[knob];
            for (std::size_t c = 1; c < kCauses; ++c) {
                const auto cause = static_cast<Cause>(c);
                const CauseError& e = r.causes.at(cause);
                all.at(cause).pixels += e.pixels;
                all.at(cause).squared_error += e.squared_error;
                if (!default_run || &r == default_run) continue;
                const CauseError& d = default_run->causes.at(cause);
                beyond.at(cause).pixels += e.pixels > d.pixels ? e.pixels - d.pixels : 0;
                beyond.at(cause).squared_error += std::max(0.0, e.squared_error - d.squared_error);
            }
        }
    }
    std::ostringstream md;
    md << "| knob | differing pixels (all its runs) | the error is mostly | beyond the default "
          "setting's |\n|---|---:|---|---|\n";
    for (const std::string& knob : knobs) {
        const auto& [all, beyond] = sums[knob];
        std::uint64_t pixels = 0;
        for (std::size_t c = 1; c < kCauses; ++c) pixels += all.at(static_cast<Cause>(c)).pixels;
        md << "| " << knob << " | " << pixels << " | " << dominant(all) << " | "
           << (!default_run ? std::string("–")
               : dominant(beyond) == "no pixel differs"
                   ? std::string("nothing: the default's error alone")
                   : dominant(beyond))
           << " |\n";
    }
    return md.str() + "\n";
}

} // namespace

const Run* fastest(const std::vector<Run>& runs, const std::function<bool(const Run&)>& within) {
    const Run* best = nullptr;
    for (const Run& r : runs)
        if (within(r) && (!best || r.frame_seconds() < best->frame_seconds())) best = &r;
    return best;
}

std::vector<Budget> error_budgets() {
    // Against the exact image: the antialiasing runs have their own table.
    const auto exact = [](const Run& r) { return !r.setting.against_grid; };
    return {
        {"PSNR ≥ 40 dB", "psnr-40", [=](const Run& r) { return exact(r) && r.diff.psnr_db >= 40; }},
        {"PSNR ≥ 50 dB", "psnr-50", [=](const Run& r) { return exact(r) && r.diff.psnr_db >= 50; }},
        {"every pixel within 1/255", "within-1",
         [=](const Run& r) { return exact(r) && r.diff.max_abs_error <= 1; }},
        {"exact", "exact", [=](const Run& r) { return exact(r) && r.diff.max_abs_error == 0; }}};
}

std::string psnr_text(double psnr) {
    return std::isinf(psnr) ? "exact" : format("%.1f", psnr);
}

void plot(const std::string& name, const std::vector<Run>& runs, const fs::path& dir,
          const std::string& reference) {
    double top = 0;
    bool any_exact = false;
    for (const Run& r : runs) {
        if (std::isinf(r.diff.psnr_db))
            any_exact = true;
        else
            top = std::max(top, r.diff.psnr_db);
    }
    top += 10;
    const auto point = [&](const Run& r) {
        return std::to_string(r.frame_seconds()) + ' ' +
               std::to_string(std::isinf(r.diff.psnr_db) ? top : r.diff.psnr_db) + " \"" + r.label +
               "\"\n";
    };
    std::vector<std::string> knobs; // in sweep order, by the first knob that reached a run
    std::map<std::string, std::string> points;
    for (const Run& r : runs) {
        const std::string knob = r.knobs.substr(0, r.knobs.find('+'));
        if (!points.count(knob)) knobs.push_back(knob);
        points[knob] += point(r);
    }
    std::ostringstream script, draw;
    for (std::size_t k = 0; k < knobs.size(); ++k)
        script << "$knob" << k << " << EOD\n" << points[knobs[k]] << "EOD\n";
    script << "$front << EOD\n";
    for (const std::size_t i : pareto_front(runs)) script << point(runs[i]);
    script << "EOD\nset logscale x\nset grid\nset key outside right top\n"
           << "set xlabel 'frame time (s, log scale; GL context and shader compilation excluded)'\n"
           << "set ylabel 'PSNR against " << reference << " (dB)'\n"
           << "set title '" << name << ": time against error"
           << (any_exact ? " (dashed line: identical to " + reference + ")" : "") << "'\n";
    if (any_exact)
        script << "set arrow from graph 0, first " << top << " to graph 1, first " << top
               << " nohead dashtype 2\n";
    draw << "plot ";
    for (std::size_t k = 0; k < knobs.size(); ++k)
        draw << "$knob" << k << " using 1:2 with points pointtype 7 pointsize 1 title '" << knobs[k]
             << "', ";
    draw << "$front using 1:2 with steps linewidth 2 linecolor 'gray40' title 'Pareto front', "
            "$front using 1:2:3 with labels font ',8' offset 0.5,0.5 left notitle\n";
    const std::string base = (dir / name).string();
    gnuplot(script.str() +
            "set terminal svg size 1100,650 dynamic noenhanced font 'sans,11'\nset output '" +
            base + ".svg'\n" + draw.str());
    gnuplot(script.str() +
            "set terminal pngcairo size 1100,650 noenhanced font 'sans,10'\nset output '" + base +
            ".png'\n" + draw.str());
}

void write_csv(const std::vector<SceneResult>& results, const fs::path& path) {
    std::ostringstream csv;
    csv << "scene,width,height,knobs,label,precision,mode,raster,tessellation,resolve,max_depth,"
           "min_reflectivity,accel,divisor,seconds_frame,seconds_total,seconds_prepare,"
           "seconds_context,seconds_compile,seconds_upload,seconds_raster,seconds_primary,"
           "seconds_shading,psnr_db,max_abs_error_255,fraction_over_1_255,id_agreement,"
           "rays_primary,rays_shadow,rays_reflection,rays_transmission,cutoff_bound_255,cutoff_"
           "bound_held,pareto,samples,antialias,aa_threshold,refined_pixels,reference,"
           "fraction_over_2_255,rmse_radiance,max_error_radiance,differing_pixels,share_sampling,"
           "share_depth,share_cutoff,share_primary,share_secondary,share_shadow,share_precision\n";
    for (const SceneResult& sr : results) {
        const std::vector<std::size_t> front = pareto_front(sr.runs);
        for (std::size_t i = 0; i < sr.runs.size(); ++i) {
            const Run& r = sr.runs[i];
            const Setting& s = r.setting;
            const FrameSettings& f = s.frame;
            const PhaseTimes& t = r.frame.times;
            const RayCounts& rays = r.frame.result.rays;
            const bool hybrid = f.mode == Mode::hybrid;
            csv << sr.name << ',' << sr.scene.camera.width << ',' << sr.scene.camera.height << ','
                << r.knobs << ",\"" << r.label << "\"," << name_of(f.precision) << ','
                << name_of(f.mode) << ',' << (hybrid ? name_of(f.raster) : "") << ','
                << (hybrid && f.raster != RasterMode::proxy ? std::to_string(f.tessellation) : "")
                << ',' << (hybrid ? name_of(f.resolve) : "") << ',' << s.max_depth << ','
                << s.min_reflectivity << ',' << (s.accel ? name_of(*s.accel) : "auto") << ','
                << s.divisor << ',' << r.frame_seconds() << ',' << r.total_seconds() << ','
                << t.prepare << ',' << t.context << ',' << t.compile << ',' << t.upload << ','
                << t.raster << ',' << t.primary << ',' << t.shading << ','
                << (std::isinf(r.diff.psnr_db) ? "inf" : format("%.3f", r.diff.psnr_db)) << ','
                << r.diff.max_abs_error << ',' << r.diff.fraction_over_one << ','
                << (r.agreement ? format("%.6f", *r.agreement) : "") << ',' << rays.primary << ','
                << rays.shadow << ',' << rays.reflection << ',' << rays.transmission << ','
                << r.bound.max << ',' << (r.bound_held ? (*r.bound_held ? "yes" : "no") : "") << ','
                << (std::find(front.begin(), front.end(), i) != front.end() ? "yes" : "") << ','
                << s.samples << ',' << name_of(s.antialias) << ',' << s.aa_threshold << ','
                << r.refined.value_or(0) << ',' << (s.against_grid ? "uniform 8x8" : "exact") << ','
                << r.diff.fraction_over_two << ',' << format("%.6g", r.diff.rmse) << ','
                << format("%.6g", r.diff.max_radiance_error);
            std::uint64_t differing = 0;
            for (std::size_t c = 1; c < kCauses; ++c)
                differing += r.causes.at(static_cast<Cause>(c)).pixels;
            csv << ',' << differing;
            for (std::size_t c = 1; c < kCauses; ++c)
                csv << ',' << format("%.6g", r.causes.share(static_cast<Cause>(c)));
            csv << '\n';
        }
    }
    write_file_atomically(path, csv.str());
}

std::string markdown(const std::vector<SceneResult>& results, const TradeoffArgs& args,
                     const fs::path& plots, const std::string& gl_renderer, double seconds) {
    std::ostringstream md;
    const std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
    const int threads = args.threads > 0 ? args.threads : tbb::this_task_arena::max_concurrency();
    md << "# Speed against accuracy\n\n"
       << "Generated by `glint tradeoff` on " << date << " (" << threads
       << " threads, GL: " << gl_renderer << ", median of " << args.repeat << " runs each, "
       << format("%.0f", seconds) << " s in all). Regenerate the shipped scenes' results with\n\n"
       << "```sh\n./glint tradeoff -o docs/tradeoff --summary docs/TRADEOFF.md\n```\n\n"
       << "**Exact image**: ray traced in double precision (`glint::f64`), reflections followed "
          "to depth "
       << kMaxDepth
       << " with no weight cut-off. **Error**: PSNR over every 8-bit channel (identical images: "
          "*exact*), largest channel difference, pixels off by more than 1/255; the CSV adds "
          "pixels off by more than 2/255 and, in linear radiance against the exact float image "
          "(errors below 1/255 and above 1 that bytes hide), the RMSE and the largest "
          "difference. **Frame time**: "
          "everything but the one-time set-up (GL context and shader compilation, ~0.2 s on "
          "llvmpipe, reported in the CSV; the meshes and their BVHs, prepared once per scene): "
          "preparing the world (transforms, the top-level acceleration structure), tessellation "
          "upload, item buffer, primary visibility, shading. Each knob "
          "is varied alone from the default setting (hybrid, auto raster, tessellation 32, exact "
          "resolve, the scene's depth and cut-off, automatic structure, one sample a pixel: the "
          "antialiasing knobs have their own section per scene); the trace-only knobs in "
          "ray mode. Smaller sizes are enlarged by pixel replication before comparing. "
          "**Cut-off bound**: what the reflection cut-off may cost each pixel "
          "(`trace/cutoff.h`), checked on every pixel against the untruncated float render "
          "(*held*). **Why it errs**: each differing pixel's cause, where its ray trees and the "
          "exact image's first part (depth, cut-off, primary or secondary hit, shadow, sampling, "
          "precision: [DIFFERENCES.md](DIFFERENCES.md)); per knob the cause most of its squared "
          "radiance error owes to, and the heat and cause maps of each budget's fastest setting. "
          "All runs: [tradeoff.csv]("
       << (plots / "tradeoff.csv").generic_string() << ").\n\n";
    for (const SceneResult& sr : results) {
        md << "## " << sr.name << " (" << sr.scene.camera.width << "×" << sr.scene.camera.height
           << ", " << sr.scene.objects.size() << " objects)\n\n"
           << "![" << sr.name << ": frame time against PSNR]("
           << (plots / (sr.name + ".svg")).generic_string() << ")\n\n"
           << "The exact image took " << format("%.3f", sr.reference_seconds)
           << " s; its own cut-off bound is " << sr.reference_bound.max << "/255.\n\n"
           << "| error budget | fastest setting | frame time (s) | PSNR (dB) | max error | where "
              "it errs: heat, causes |\n"
           << "|---|---|---:|---:|---:|---|\n";
        for (const Budget& budget : error_budgets()) {
            const Run* r = fastest(sr.runs, budget.within);
            if (!r) {
                md << "| " << budget.name << " | none of the runs | | | | |\n";
                continue;
            }
            md << "| " << budget.name << " | " << r->label << " | "
               << format("%.4f", r->frame_seconds()) << " | " << psnr_text(r->diff.psnr_db) << " | "
               << r->diff.max_abs_error << "/255 | ";
            if (!r->thumbnails.empty())
                md << "![heat](" << (plots / (r->thumbnails + "-heat.png")).generic_string()
                   << ") ![causes](" << (plots / (r->thumbnails + "-causes.png")).generic_string()
                   << ")";
            else
                md << "identical";
            md << " |\n";
        }
        md << "\n" << knob_causes(sr.runs, sr.scene);
        md << "\n### Antialiasing\n\n"
           << "Against the uniform " << kGridReference << "×" << kGridReference
           << " image of the default setting (ray traced, " << format("%.3f", sr.grid_seconds)
           << " s): uniform grids, and adaptive at " << args.samples << "×" << args.samples
           << " over its threshold (docs/ANTIALIASING.md).\n\n"
           << "![" << sr.name << ": antialiasing, frame time against PSNR]("
           << (plots / (sr.name + "-antialiasing.svg")).generic_string() << ")\n\n"
           << "| setting | frame time (s) | PSNR (dB) | pixels within 2/255 | refined pixels |\n"
           << "|---|---:|---:|---:|---:|\n";
        for (const Run& r : sr.runs) {
            if (!r.setting.against_grid) continue;
            md << "| " << r.label << " | " << format("%.4f", r.frame_seconds()) << " | "
               << psnr_text(r.diff.psnr_db) << " | "
               << format("%.2f%%", 100 * (1 - r.diff.fraction_over_two)) << " | "
               << (r.refined ? format("%.1f%%", 100.0 * static_cast<double>(*r.refined) /
                                                    static_cast<double>(r.pixels))
                             : std::string("–"))
               << " |\n";
        }
        md << "\n<details><summary>Every run</summary>\n\n"
           << "| knob | setting | frame time (s) | PSNR (dB) | max error | off > 1/255 | id "
              "agreement | reflection rays | cut-off bound |\n"
           << "|---|---|---:|---:|---:|---:|---:|---:|---|\n";
        for (const Run& r : sr.runs)
            md << "| " << r.knobs << " | " << r.label << " | " << format("%.4f", r.frame_seconds())
               << " | " << psnr_text(r.diff.psnr_db) << " | " << r.diff.max_abs_error << " | "
               << format("%.3f%%", 100 * r.diff.fraction_over_one) << " | "
               << (r.agreement ? format("%.4f", *r.agreement) : "–") << " | "
               << r.frame.result.rays.reflection << " | " << r.bound.max << "/255"
               << (r.bound_held ? (*r.bound_held ? ", held" : ", **violated**") : "") << " |\n";
        md << "\n</details>\n\n";
    }
    return md.str();
}

} // namespace tradeoff
} // namespace glint
