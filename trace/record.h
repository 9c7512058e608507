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

// Appends `record`'s fields to `out`, in their listed order (optionals as a presence byte, then
// the value when present).
template <Record R> void pack(const R& record, std::vector<char>& out) {
    for_each_field(record, [&](const std::string&, const auto& field) {
        using F = std::remove_cvref_t<decltype(field)>;
        const auto put = [&](const auto& value) {
            const char* bytes = reinterpret_cast<const char*>(&value);
            out.insert(out.end(), bytes, bytes + sizeof(value));
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

// Reads back what pack wrote, from `at` (advanced past it); throws std::runtime_error when the
// bytes end first.
template <Record R> void unpack(R& record, const char*& at, const char* end) {
    for_each_field(record, [&](const std::string& name, auto& field) {
        using F = std::remove_cvref_t<decltype(field)>;
        const auto get = [&](auto& value) {
            if (end - at < static_cast<std::ptrdiff_t>(sizeof(value)))
                throw std::runtime_error("a record from another rank ends before its field " + name);
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
