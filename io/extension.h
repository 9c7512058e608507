// A file's format as its name says it: the extension, lowercased, so that a scene, a model or an
// output file is read or written whatever the case of its name (x.PNG, model.GLB).
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace glint {

// ".png" for "out/x.PNG"; empty for a name without an extension.
inline std::string extension_of(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension;
}

} // namespace glint
