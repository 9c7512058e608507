// Numbers as explain's text writes them, shared by its two forms (frame/explain.cpp,
// frame/explain_against.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace glint {

// A pixel's three bytes: "(12, 200, 255)".
inline std::string bytes_text(const std::array<std::uint8_t, 3>& b) {
    return "(" + std::to_string(b[0]) + ", " + std::to_string(b[1]) + ", " + std::to_string(b[2]) +
           ")";
}

} // namespace glint
