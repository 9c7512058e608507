// What every reader shares: a file read whole within its limit, numbers as scene text writes
// them, and JSON's nesting checked before it is parsed.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace glint {

// The whole file, refused beyond kMaxSceneBytes (read no further: /dev/zero ends too). `kind`
// names it in errors ("scene file", "mesh file").
std::string read_scene_file(const std::filesystem::path& path, const std::string& kind);

// A number as scene text writes it ("1", "-2.5e-3", "+4"): finite, the whole token.
bool parse_number(std::string_view token, double& value);

// "file:line:column" of the byte at `offset` (0-based) in `text`, named `name`.
std::string text_place(const std::string& name, const std::string& text, std::size_t offset);

// JSON text nested deeper than `limit` levels is refused at the bracket that goes too deep,
// before it is parsed: a million brackets should cost a message, not a stack.
void check_json_nesting(const std::string& text, const std::string& name, int limit);

} // namespace glint
