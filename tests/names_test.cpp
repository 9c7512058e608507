// The closed sets' names (trace/names.h): every enumerator has one name, distinct from the
// others, and reading a name back gives the enumerator; anything else is not a name.
#include "frame/frame.h"
#include "preview/views.h"
#include "trace/accel/accel_kind.h"

#include <gtest/gtest.h>

#include <set>

namespace glint {
namespace {

template <class Enum> void expect_round_trip(std::size_t count) {
    const auto& names = EnumNames<Enum>::names;
    ASSERT_EQ(names.size(), count);
    EXPECT_EQ(std::set<std::string_view>(names.begin(), names.end()).size(), count);
    for (std::size_t i = 0; i < count; ++i) {
        const Enum value = static_cast<Enum>(i);
        EXPECT_EQ(from_name<Enum>(name_of(value)), value) << names[i];
    }
    EXPECT_EQ(all_names<Enum>().size(), count);
    EXPECT_FALSE(from_name<Enum>("").has_value());
    EXPECT_FALSE(from_name<Enum>("no such name").has_value());
}

TEST(Names, EveryClosedSetNamesEachMemberOnceAndReadsItBack) {
    expect_round_trip<Mode>(2);
    expect_round_trip<GlBackend>(2);
    expect_round_trip<RasterMode>(2);
    expect_round_trip<Resolve>(2);
    expect_round_trip<Precision>(2);
    expect_round_trip<AccelKind>(5);
    expect_round_trip<ShapeKind>(8);
    expect_round_trip<View>(kViewCount);
    EXPECT_EQ(name_of(ShapeKind::mesh), "mesh");
    EXPECT_EQ(name_of(View::difference), "difference");
}

} // namespace
} // namespace glint
