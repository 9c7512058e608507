// The names of glint's closed sets (modes, structures, views, shapes, …), each spelled once: a
// table beside the enum, in the enum's order, that the CLI, window titles, CSV and JSON all read.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace glint {

// Specialised beside each named enum with `static constexpr auto names = name_table(…)`, one
// name per enumerator, in order.
template <class Enum> struct EnumNames;

template <class... Names> constexpr auto name_table(Names... names) {
    return std::array<std::string_view, sizeof...(Names)>{names...};
}

template <class Enum> constexpr std::string_view name_of(Enum value) {
    return EnumNames<Enum>::names[static_cast<std::size_t>(value)];
}

template <class Enum> constexpr std::optional<Enum> from_name(std::string_view name) {
    const auto& names = EnumNames<Enum>::names;
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return static_cast<Enum>(i);
    return std::nullopt;
}

// Every value, in order: loops over a closed set (tests, sweeps) that must not miss a new member.
template <class Enum> constexpr auto all_values() {
    std::array<Enum, EnumNames<Enum>::names.size()> values{};
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<Enum>(i);
    return values;
}

// Every name, in order: what a command-line option accepts.
template <class Enum> std::vector<std::string> all_names() {
    const auto& names = EnumNames<Enum>::names;
    return {names.begin(), names.end()};
}

} // namespace glint
