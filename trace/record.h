// Records with named fields: what crosses between MPI ranks, and the counters every JSON output
// writes. Each record lists its fields once, in RecordFields<T>::visit (name, member); pack and
// unpack both walk that list, so a field added to it is sent and read back in its place and no
// other field moves, and frame/record_json.h writes it under the same names. tests/record_test.cpp
// round-trips every record field by field, and checks that each plain record's list covers its
// struct. Fields are arithmetic values, std::optional of one, or records themselves (visited
// with their name as a prefix).
#pragma once

#include <concepts>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace glint {

// Specialised beside each record: template <class R, class Visit> static void visit(R& r,
// Visit&& v) calling v("name", r.member) for each field, in a fixed order; R is T or const T.
template <class T> struct RecordFields;

template <class T>
concept Record = requires { sizeof(RecordFields<std::remove_const_t<T>>); };

template <class T> struct is_optional : std::false_type {};
template <class T> struct is_optional<std::optional<T>> : std::true_type {};

// Calls leaf(name, value) for each arithmetic field of `record`, records inside it flattened as
// "outer.inner", optionals given as they are.
template <class R, class Leaf> void for_each_field(R& record, Leaf&& leaf, const std::string& prefix = "") {
    RecordFields<std::remove_const_t<R>>::visit(record, [&](const char* name, auto& field) {
        using F = std::remove_cvref_t<decltype(field)>;
        if constexpr (Record<F>)
            for_each_field(field, leaf, prefix + name + ".");
        else
            leaf(prefix + name, field);
    });
}

// Calls leaf(name, value) for each arithmetic field of `record` as for_each_field does, with each
// field's own name (not qualified by the records it is in), building no strings: for pack and
// unpack, which run once per pixel.
template <class R, class Leaf> void for_each_value(R& record, Leaf&& leaf) {
    RecordFields<std::remove_const_t<R>>::visit(record, [&](const char* name, auto& field) {
        using F = std::remove_cvref_t<decltype(field)>;
        if constexpr (Record<F>)
            for_each_value(field, leaf);
        else
            leaf(name, field);
    });
}

// The bytes pack writes for `record`.
template <Record R> std::size_t packed_size(const R& record) {
    std::size_t bytes = 0;
    for_each_value(record, [&](const char*, const auto& field) {
        using F = std::remove_cvref_t<decltype(field)>;
        if constexpr (is_optional<F>::value)
            bytes += 1 + (field ? sizeof(*field) : 0);
        else
            bytes += sizeof(field);
    });
    return bytes;
}

// Writes `record`'s fields at `at` (advanced past them), in their listed order (optionals as a
// presence byte, then the value when present); the caller has made room for packed_size bytes.
template <Record R> void pack_to(const R& record, char*& at) {
    for_each_value(record, [&](const char*, const auto& field) {
        using F = std::remove_cvref_t<decltype(field)>;
        const auto put = [&](const auto& value) {
            std::memcpy(at, &value, sizeof(value));
            at += sizeof(value);
        };
        if constexpr (is_optional<F>::value) {
            put(static_cast<char>(field.has_value()));
            if (field) put(*field);
        } else {
            static_assert(std::is_arithmetic_v<F>, "a record's fields are numbers");
            put(field);
        }
    });
}

// Appends `record`'s fields to `out`, as pack_to writes them.
template <Record R> void pack(const R& record, std::vector<char>& out) {
    const std::size_t start = out.size();
    out.resize(start + packed_size(record));
    char* at = out.data() + start;
    pack_to(record, at);
}

// Reads back what pack wrote, from `at` (advanced past it); throws std::runtime_error when the
// bytes end first.
template <Record R> void unpack(R& record, const char*& at, const char* end) {
    for_each_value(record, [&](const char* name, auto& field) {
        using F = std::remove_cvref_t<decltype(field)>;
        const auto get = [&](auto& value) {
            if (end - at < static_cast<std::ptrdiff_t>(sizeof(value)))
                throw std::runtime_error(std::string("a record from another rank ends before its "
                                                     "field ") + name);
            std::memcpy(&value, at, sizeof(value));
            at += sizeof(value);
        };
        if constexpr (is_optional<F>::value) {
            char present = 0;
            get(present);
            if (present) {
                typename F::value_type value{};
                get(value);
                field = value;
            } else {
                field.reset();
            }
        } else {
            get(field);
        }
    });
}

} // namespace glint
