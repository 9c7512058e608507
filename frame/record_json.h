// A record (trace/record.h) as JSON, each field under the name its field list gives: so that a
// counter has the same key in every output (render's --stats, compare's --json, explain's
// --json) and in the MPI ranks' records.
#pragma once

#include "trace/record.h"

#include <nlohmann/json.hpp>

#include <type_traits>

namespace glint {

// {"name": value, …} in the list's order; a record inside is an object, an empty optional null.
template <Record R> nlohmann::ordered_json record_json(const R& record) {
    nlohmann::ordered_json out = nlohmann::ordered_json::object();
    RecordFields<R>::visit(record, [&](const char* name, const auto& field) {
        using F = std::remove_cvref_t<decltype(field)>;
        if constexpr (Record<F>)
            out[name] = record_json(field);
        else if constexpr (is_optional<F>::value)
            out[name] = field ? nlohmann::ordered_json(*field) : nlohmann::ordered_json(nullptr);
        else
            out[name] = field;
    });
    return out;
}

} // namespace glint
