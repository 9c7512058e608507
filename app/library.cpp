#include "app/library.h"

#include "app/explain.h"
#include "app/render_stats.h"
#include "frame/gl_pass.h"
#include "trace/cutoff.h"
#include "trace/image.h"
#include "trace/stopwatch.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <optional>

namespace glint {
namespace {

namespace fs = std::filesystem;

// The keywords that change what is read from the scene's file: given to a call, it reads the file
// again instead of using glint.load's scene.
constexpr const char* kReadingKeywords[] = {"size",      "camera", "time",
                                            "animation", "colour", "framing"};

// What a call's command offers that a call cannot take: files it would write, and compare's
// sides (Scene.compare's own arguments). glint.load takes only the keywords that choose what is
// read (the rest are a render's).
bool excluded(Call call, const std::string& keyword) {
    static const std::vector<std::string> load_takes = {"camera", "time", "animation"};
    switch (call) {
    case Call::load:
        return std::find(load_takes.begin(), load_takes.end(), keyword) == load_takes.end();
    case Call::render:
        return false;
    case Call::explain:
        return keyword == "json";
    case Call::compare:
        return keyword == "output" || keyword == "json" || keyword == "exr" || keyword == "a" ||
               keyword == "b";
    }
    return true;
}

std::string keyword_of(const std::string& flag) {
    if (flag == "--aov") return "aovs";
    std::string keyword = flag.substr(2);
    std::replace(keyword.begin(), keyword.end(), '-', '_');
    return keyword;
}

// A command's parser without help or extras: the options the call's command adds.
struct Parser {
    CLI::App app;
    Call call;
    Keywords given;

    explicit Parser(Call call) : app("glint"), call(call) {
        app.set_help_flag();
        app.allow_extras(false);
    }

    // The option a keyword names, or null where the call takes no such setting.
    const CLI::Option* option(const std::string& keyword) const {
        if (keyword.empty() || keyword == "aov" || excluded(call, keyword)) return nullptr;
        const CLI::Option* o = app.get_option_no_throw(flag_of(keyword));
        return o && !o->get_group().empty() ? o : nullptr; // group "": refused (refuse_option)
    }

    // A UsageError or a parse error's message: where it begins with a given keyword's flag, a
    // SettingError naming the keyword instead.
    [[noreturn]] void raise(const std::string& message) const {
        for (const Keyword& k : given) {
            const std::string flag = flag_of(k.name);
            if (message.rfind(flag, 0) == 0 &&
                (message.size() == flag.size() || message[flag.size()] == ':' ||
                 message[flag.size()] == ' '))
                throw SettingError(k.name, k.name + message.substr(flag.size()));
        }
        throw UsageError(message);
    }

    // Parses the positionals and the keywords (UnknownSetting, SettingError).
    void parse(const std::vector<std::string>& positionals, Keywords keywords) {
        given = std::move(keywords);
        std::vector<std::string> tokens = positionals;
        for (const Keyword& k : given) {
            const CLI::Option* o = option(k.name);
            if (!o) throw UnknownSetting(k.name);
            if (o->get_expected_max() == 0) { // a flag: given as true or false
                if (k.values.size() != 1 || (k.values[0] != "true" && k.values[0] != "false"))
                    throw SettingError(k.name, k.name + ": takes True or False, not '" +
                                                   (k.values.empty() ? "" : k.values[0]) + "'");
                if (k.values[0] == "true") tokens.push_back(flag_of(k.name));
                continue;
            }
            if (k.values.empty()) throw SettingError(k.name, k.name + ": needs a value");
            for (const std::string& value : k.values) {
                tokens.push_back(flag_of(k.name));
                tokens.push_back(value);
            }
        }
        std::reverse(tokens.begin(), tokens.end()); // CLI11 takes them last first
        try {
            app.parse(tokens);
        } catch (const CLI::ParseError& e) {
            raise(e.what());
        }
    }

    // Runs a check that may throw UsageError, attributing it to its keyword.
    template <class F> auto checked(const F& check) const {
        try {
            return check();
        } catch (const SettingError&) {
            throw;
        } catch (const UsageError& e) {
            raise(e.what());
        }
    }
};

// The load's keywords, then the call's (a call's keyword replaces the load's of that name).
Keywords merged(const LoadedScene& loaded, const Keywords& given) {
    Keywords all;
    for (const Keyword& k : loaded.keywords)
        if (std::none_of(given.begin(), given.end(),
                         [&](const Keyword& g) { return g.name == k.name; }))
            all.push_back(k);
    all.insert(all.end(), given.begin(), given.end());
    return all;
}

// glint.load's scene, unless the call's keywords change what is read from the file.
std::shared_ptr<const Scene> preloaded(const LoadedScene& loaded, const Keywords& given) {
    for (const Keyword& k : given)
        for (const char* reading : kReadingKeywords)
            if (k.name == reading) return nullptr;
    return loaded.scene;
}

bool wants(const std::vector<Aov>& aovs, Aov aov) {
    return std::find(aovs.begin(), aovs.end(), aov) != aovs.end();
}

void add_render_options(CLI::App& cmd, SceneOptions& scene, FrameOptions& frame,
                        std::vector<std::string>& aovs, std::string& colour) {
    scene.add_to(cmd);
    frame.add_to(cmd, true);
    add_aov_option(cmd, aovs);
    add_colour_option(cmd, colour);
}

} // namespace

std::string flag_of(const std::string& keyword) {
    if (keyword == "aovs") return "--aov";
    std::string flag = "--" + keyword;
    std::replace(flag.begin(), flag.end(), '_', '-');
    return flag;
}

std::vector<std::string> keywords_of(Call call) {
    Parser parser(call);
    SceneOptions scene;
    FrameOptions frame;
    ExplainArgs explain_args;
    CompareArgs compare_args;
    std::vector<std::string> aovs;
    std::string colour;
    switch (call) {
    case Call::load:
        scene.add_to(parser.app);
        break;
    case Call::render:
        add_render_options(parser.app, scene, frame, aovs, colour);
        break;
    case Call::explain:
        explain_args.add_to(parser.app);
        break;
    case Call::compare:
        compare_args.add_to(parser.app);
        break;
    }
    std::vector<std::string> names;
    for (const CLI::Option* o : parser.app.get_options()) {
        for (const std::string& flag : o->get_lnames()) {
            const std::string keyword = keyword_of("--" + flag);
            if (parser.option(keyword) == o) names.push_back(keyword);
        }
    }
    return names;
}

LoadedScene load_by_keywords(const fs::path& path, const Keywords& given) {
    Parser parser(Call::load);
    SceneOptions options;
    options.add_to(parser.app);
    parser.parse({path.string()}, given);
    LoadedScene loaded{path, given, nullptr};
    loaded.scene = std::make_shared<const Scene>(parser.checked([&] { return options.load(); }));
    return loaded;
}

RenderedFrame render_by_keywords(const LoadedScene& loaded, const Keywords& given,
                                 const std::atomic<bool>* cancel) {
    const Stopwatch total;
    Stopwatch phase;
    Parser parser(Call::render);
    SceneOptions options;
    FrameOptions frame_options;
    std::vector<std::string> aov_names;
    std::string colour = "linear";
    add_render_options(parser.app, options, frame_options, aov_names, colour);
    parser.parse({loaded.path.string()}, merged(loaded, given));
    options.preloaded = preloaded(loaded, given);
    options.srgb = colour == "srgb";

    RenderedFrame out;
    out.aovs = parser.checked([&] { return parse_aovs(aov_names); });
    FrameSettings settings = parser.checked([&] { return frame_options.settings(); });
    const Scene scene = parser.checked([&] { return options.load(); });
    parser.checked([&] { check_frame_memory(scene, settings.mode, 1); });
    out.width = scene.camera.width, out.height = scene.camera.height;
    const double load_seconds = phase.lap();

    // As `glint render` does: the GL pass makes its context beside the World's preparation.
    std::optional<GlPass> gl;
    if (needs_gl(settings, scene.objects.size())) gl.emplace(settings);
    World world(scene, options.accel_kind());
    world.count_traversals(true); // the stats' traversal figures, as --stats counts them
    const double prepare_seconds = phase.lap();
    settings.aovs =
        wants(out.aovs, Aov::depth) || wants(out.aovs, Aov::normal) || wants(out.aovs, Aov::id);
    settings.cancel = cancel;
    out.frame = render_frame(world, settings, nullptr, gl ? &*gl : nullptr);
    if (cancel && cancel->load()) throw Cancelled();

    const RenderResult& result = out.frame.result;
    out.image = options.srgb ? to_srgb_bytes(result.display()) : result.bytes();
    if (wants(out.aovs, Aov::cutoff)) out.cutoff = cutoff_radiance(scene, result);
    const int threads =
        frame_options.threads > 0 ? frame_options.threads : tbb::this_task_arena::max_concurrency();
    const RenderReport report{loaded.path,
                              {},
                              scene,
                              frame_options,
                              world,
                              out.frame,
                              cutoff_summary(scene, result),
                              threads,
                              load_seconds,
                              prepare_seconds,
                              0,
                              total.seconds()};
    out.stats = stats_json(report).dump(2);
    return out;
}

std::string explain_by_keywords(const LoadedScene& loaded, int x, int y, const Keywords& given) {
    Parser parser(Call::explain);
    ExplainArgs args;
    args.add_to(parser.app);
    parser.parse({loaded.path.string(), std::to_string(x), std::to_string(y)},
                 merged(loaded, given));
    args.scene.preloaded = preloaded(loaded, given);
    return parser.checked([&] { return explain(args).json; });
}

ComparedSides compare_by_keywords(const LoadedScene& loaded, const std::string& a,
                                  const std::string& b, const Keywords& given,
                                  const std::atomic<bool>* cancel) {
    Parser parser(Call::compare);
    CompareArgs args;
    args.add_to(parser.app);
    // An empty side is compare's own settings, as a side `glint compare` is not given.
    std::vector<std::string> tokens{loaded.path.string()};
    if (!a.empty()) tokens.insert(tokens.end(), {"--a", a});
    if (!b.empty()) tokens.insert(tokens.end(), {"--b", b});
    parser.parse(tokens, merged(loaded, given));
    args.scene.preloaded = preloaded(loaded, given);
    return parser.checked([&] { return compare_sides(args, cancel); });
}

RenderedFrame side_frame(const RenderedSide& side) {
    RenderedFrame out;
    out.width = side.side().scene.camera.width, out.height = side.side().scene.camera.height;
    out.frame.result = side.frame().result;
    out.frame.times = side.frame().times;
    out.image = out.frame.result.bytes();
    return out;
}

} // namespace glint
