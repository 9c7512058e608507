// The small shared vocabulary: the closed sets' names (trace/names.h), where every enumerator has
// one name, distinct from the others, reading a name back gives the enumerator, and all_values
// lists every enumerator in order; and the one
// timer (trace/stopwatch.h).
#include "frame/frame.h"
#include "preview/views.h"
#include "trace/accel/accel_kind.h"
#include "trace/stopwatch.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <thread>

namespace glint {
namespace {

template <class Enum> void expect_round_trip(std::size_t count) {
    const auto& names = EnumNames<Enum>::names;
    ASSERT_EQ(names.size(), count);
    EXPECT_EQ(std::set<std::string_view>(names.begin(), names.end()).size(), count);
    for (std::size_t i = 0; i < count; ++i) {
        const Enum value = static_cast<Enum>(i);
        EXPECT_EQ(from_name<Enum>(name_of(value)), value) << names[i];
        EXPECT_EQ(all_values<Enum>()[i], value) << names[i];
    }
    EXPECT_EQ(all_names<Enum>().size(), count);
    EXPECT_EQ(all_values<Enum>().size(), count);
    EXPECT_FALSE(from_name<Enum>("").has_value());
    EXPECT_FALSE(from_name<Enum>("no such name").has_value());
}

TEST(Names, EveryClosedSetNamesEachMemberOnceAndReadsItBack) {
    expect_round_trip<Mode>(2);
    expect_round_trip<GlBackend>(2);
    expect_round_trip<RasterMode>(3);
    expect_round_trip<Resolve>(2);
    expect_round_trip<Precision>(2);
    expect_round_trip<AccelKind>(6);
    expect_round_trip<ShapeKind>(8);
    expect_round_trip<View>(kViewCount);
    EXPECT_EQ(name_of(ShapeKind::mesh), "mesh");
    EXPECT_EQ(name_of(View::difference), "difference");
}

// timed() adds the work's wall time to what is there, also when the work throws (a phase that
// failed still took its time), and passes the work's result through. Lower bounds only: a slow
// machine cannot fail it.
TEST(Stopwatch, TimedAddsTheWorksTimeAndPassesItsResultThrough) {
    double seconds = 1;
    const int result = timed(seconds, [] {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        return 42;
    });
    EXPECT_EQ(result, 42);
    EXPECT_GE(seconds, 1.002);
    const double before = seconds;
    EXPECT_THROW(timed(seconds,
                       []() -> int {
                           std::this_thread::sleep_for(std::chrono::milliseconds(2));
                           throw std::runtime_error("failed");
                       }),
                 std::runtime_error);
    EXPECT_GE(seconds, before + 0.002);
    Stopwatch watch;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    const double lap = watch.lap();
    EXPECT_GE(lap, 0.002);
}

} // namespace
} // namespace glint
