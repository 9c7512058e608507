#include "io/read_text.h"

#include "io/error.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>

namespace glint {

std::string text_place(const std::string& name, const std::string& text, std::size_t offset) {
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < std::min(offset, text.size()); ++i) {
        if (text[i] == '\n')
            ++line, column = 1;
        else
            ++column;
    }
    return name + ":" + std::to_string(line) + ":" + std::to_string(column);
}

void check_json_nesting(const std::string& text, const std::string& name, int limit) {
    int depth = 0;
    bool in_string = false, escaped = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (in_string) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > limit)
                throw SceneError(text_place(name, text, i) + ": JSON nested deeper than " +
                                 std::to_string(limit) + " levels");
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

bool parse_number(std::string_view token, double& value) {
    if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    return error == std::errc() && end == token.data() + token.size() && std::isfinite(value);
}

std::string read_scene_file(const std::filesystem::path& path, const std::string& kind) {
    const std::string name = path.string();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw SceneError(name + ": is a directory, not a " + kind);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SceneError(name + ": cannot open " + kind + ": " + std::strerror(errno));
    const auto size = std::filesystem::file_size(path, ec);
    const std::string limit = "; the limit is " + std::to_string(kMaxSceneBytes >> 20) + " MiB";
    if (!ec && size > kMaxSceneBytes)
        throw SceneError(name + ": " + kind + " is " + std::to_string(size >> 20) + " MiB" + limit);
    // Read no more than the limit allows: devices and pipes (/dev/zero) have no size to ask.
    std::string text;
    if (!ec) text.reserve(size);
    char chunk[1 << 16];
    while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
        text.append(chunk, static_cast<std::size_t>(in.gcount()));
        if (text.size() > kMaxSceneBytes)
            throw SceneError(name + ": " + kind + " is larger than allowed" + limit);
    }
    if (in.bad()) throw SceneError(name + ": cannot read " + kind + ": " + std::strerror(errno));
    return text;
}

} // namespace glint
