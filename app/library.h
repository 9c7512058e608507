// glint as a library: what the Python module (python/, docs/PYTHON.md) calls. Each call takes the
// command line's settings by keyword (`max_depth` is --max-depth, `aovs` is --aov) and reads them
// with the command's own options, so that the names, limits, checks and messages are written
// once, for the CLI and for Python alike.
#pragma once

#include "app/compare.h"
#include "app/options.h"

#include <atomic>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace glint {

// A value a setting's check refuses (Python: ValueError). `keyword` is the setting's name as
// given; the message names it in place of the flag.
class SettingError : public UsageError {
  public:
    SettingError(std::string keyword, const std::string& message)
        : UsageError(message), keyword(std::move(keyword)) {}
    const std::string keyword;
};

// A keyword that is no setting of the call (Python: TypeError).
class UnknownSetting : public UsageError {
  public:
    using UsageError::UsageError;
};

// One setting given by keyword: its values as the command line spells them ("3", "800x600";
// several for a list), or none for a flag given as true.
struct Keyword {
    std::string name;
    std::vector<std::string> values;
};
using Keywords = std::vector<Keyword>;

// A keyword's flag: `max_depth` is --max-depth; `aovs` is --aov (Python's plural for a list).
std::string flag_of(const std::string& keyword);

// The calls, each with the settings its command takes.
enum class Call { load, render, explain, compare };

// The keywords a call takes, in the order its command's --help lists them.
std::vector<std::string> keywords_of(Call call);

// A scene as glint.load read it: its path, the load's keywords (camera, time, animation), kept
// for the calls that load it again, and the scene.
struct LoadedScene {
    std::filesystem::path path;
    Keywords keywords;
    std::shared_ptr<const Scene> scene;
};

// Loads a scene as `glint render` does (notes and warnings on stderr); SceneError on bad input.
LoadedScene load_by_keywords(const std::filesystem::path& path, const Keywords& given);

// A rendered frame and what the Python module's Frame reads of it.
struct RenderedFrame {
    int width = 0, height = 0; // as rendered
    Frame frame;
    Image image;               // the PNG's bytes (through the sRGB curve with colour="srgb")
    std::vector<Aov> aovs;     // asked for
    std::vector<float> cutoff; // the cutoff AOV, where asked for
    std::string stats;         // JSON: `glint render --stats`'s fields ("output": null)
};

// Renders as `glint render SCENE [flags]` would, writing nothing. The scene is glint.load's, or
// read again where a keyword changes what is read (size, camera, time, animation, colour).
// Cancelled once `cancel` is set (between tiles).
RenderedFrame render_by_keywords(const LoadedScene& loaded, const Keywords& given,
                                 const std::atomic<bool>* cancel);

// `glint explain SCENE X Y [flags] --json`'s JSON (with `against`: --against's).
std::string explain_by_keywords(const LoadedScene& loaded, int x, int y, const Keywords& given);

// `glint compare SCENE --a A --b B [flags]`: the two sides' flags as text ("--max-depth 2",
// "exact"). Cancelled once `cancel` is set.
ComparedSides compare_by_keywords(const LoadedScene& loaded, const std::string& a,
                                  const std::string& b, const Keywords& given,
                                  const std::atomic<bool>* cancel);

// A side of a comparison as a frame: its size, its frame's result (copied), its PNG bytes.
RenderedFrame side_frame(const RenderedSide& side);

} // namespace glint
