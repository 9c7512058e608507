// The MPI ranks' messages (app/rank_records.h), without mpirun: every record packed and read back
// field by field, by name, each field given its own value first, so that a field dropped from a
// list, read into the wrong place or shifted by a new one fails here, not only under MPI.
#include "app/rank_records.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

namespace glint {
namespace {

// Every field of `record`, by name, as text (optionals as "none" or their value).
template <Record R> std::map<std::string, std::string> by_name(const R& record) {
    std::map<std::string, std::string> fields;
    for_each_field(record, [&](const std::string& name, const auto& field) {
        using F = std::remove_cvref_t<decltype(field)>;
        std::string text;
        if constexpr (is_optional<F>::value)
            text = field ? std::to_string(*field) : "none";
        else
            text = std::to_string(field);
        EXPECT_TRUE(fields.emplace(name, text).second) << "two fields named " << name;
    });
    return fields;
}

// Gives field k the value k + 1 (booleans alternate; an optional holds its value), so that no
// two fields hold the same value, and a field read from the wrong place shows.
template <Record R> R distinct_values() {
    R record{};
    int k = 0;
    for_each_field(record, [&](const std::string&, auto& field) {
        using F = std::remove_cvref_t<decltype(field)>;
        ++k;
        if constexpr (is_optional<F>::value) {
            using V = typename F::value_type;
            if constexpr (std::is_same_v<V, bool>)
                field = k % 2 == 0;
            else
                field = static_cast<V>(k + 0.5);
        } else {
            field = static_cast<F>(k + (std::is_floating_point_v<F> ? 0.25 : 0));
        }
    });
    return record;
}

template <Record R> void expect_round_trip(const R& record) {
    std::vector<char> bytes;
    pack(record, bytes);
    R back{};
    const char* at = bytes.data();
    unpack(back, at, bytes.data() + bytes.size());
    EXPECT_EQ(at, bytes.data() + bytes.size()) << "every byte read";
    EXPECT_EQ(by_name(back), by_name(record));
    // One byte short: an error naming the last field, never a read past the end.
    const char* short_at = bytes.data();
    R partial{};
    EXPECT_THROW(unpack(partial, short_at, bytes.data() + bytes.size() - 1), std::runtime_error);
}

// A plain record's fields, added up, fill its struct: a member added to the struct but not to
// its field list fails here.
template <Record R> std::size_t field_bytes() {
    std::size_t bytes = 0;
    R record{};
    for_each_field(record, [&](const std::string&, const auto& field) { bytes += sizeof(field); });
    return bytes;
}

TEST(Records, EveryRecordRoundTripsFieldByField) {
    expect_round_trip(distinct_values<FrameCounters>());
    expect_round_trip(distinct_values<RankFigures>());
    expect_round_trip(distinct_values<RunFigures>());
    expect_round_trip(distinct_values<PixelFacts>());
    expect_round_trip(distinct_values<PixelColour>());
    expect_round_trip(distinct_values<PixelAov>());
    expect_round_trip(distinct_values<PixelPathKey>());
    expect_round_trip(distinct_values<PixelRefinement>());
    expect_round_trip(distinct_values<PassExchange>());
    expect_round_trip(distinct_values<TileHeader>());
    expect_round_trip(distinct_values<MaskHeader>());
    expect_round_trip(distinct_values<MaskRun>());
    RunFigures absent = distinct_values<RunFigures>();
    absent.agreement.reset(), absent.bound_held.reset(), absent.refined.reset();
    expect_round_trip(absent);
}

TEST(Records, EachPlainRecordsFieldListCoversItsStruct) {
    EXPECT_EQ(field_bytes<RayCounts>(), sizeof(RayCounts));
    EXPECT_EQ(field_bytes<PrimaryStats>(), sizeof(PrimaryStats));
    EXPECT_EQ(field_bytes<PhaseTimes>(), sizeof(PhaseTimes));
    EXPECT_EQ(field_bytes<RankFigures>(), sizeof(RankFigures));
    EXPECT_EQ(field_bytes<PixelColour>(), sizeof(PixelColour));
    EXPECT_EQ(field_bytes<PixelPathKey>(), sizeof(PixelPathKey));
    EXPECT_EQ(field_bytes<PixelRefinement>(), sizeof(PixelRefinement));
    EXPECT_EQ(field_bytes<PixelFacts>(), sizeof(PixelFacts));
    EXPECT_EQ(field_bytes<PixelAov>(), sizeof(PixelAov));
    EXPECT_EQ(field_bytes<PassExchange>(), sizeof(PassExchange));
    EXPECT_EQ(field_bytes<TileHeader>(), sizeof(TileHeader));
    EXPECT_EQ(field_bytes<MaskHeader>(), sizeof(MaskHeader));
    EXPECT_EQ(field_bytes<MaskRun>(), sizeof(MaskRun));
    // ImageDifference: an int among doubles leaves 4 bytes of padding.
    EXPECT_EQ(field_bytes<ImageDifference>() + 4, sizeof(ImageDifference));
}

TEST(Records, NamesAreQualifiedByTheRecordTheyAreIn) {
    const auto names = by_name(distinct_values<RunFigures>());
    for (const char* name : {"times.shading", "rays.transmission", "diff.rmse",
                             "diff.max_radiance_error", "agreement", "bound_held", "pixels"})
        EXPECT_EQ(names.count(name), 1u) << name;
}

// A pass's mask as rank 0 hands it out: runs of pixels, read back pixel for pixel; empty, full,
// and a mask starting and ending with refined pixels included. A mask whose runs overrun its
// image is refused.
TEST(Records, AMaskRoundTripsAsRuns) {
    std::vector<std::vector<std::uint8_t>> masks = {{}, {0, 0, 0}, {1, 1}, {1, 0, 0, 1, 1, 0, 1}};
    std::vector<std::uint8_t> random(10007);
    unsigned state = 12345;
    for (std::uint8_t& m : random) m = ((state = state * 1103515245u + 12345u) >> 16) % 5 == 0;
    masks.push_back(random);
    for (const std::vector<std::uint8_t>& mask : masks) {
        std::vector<char> bytes;
        pack_mask(mask, bytes);
        const char* at = bytes.data();
        EXPECT_EQ(unpack_mask(at, bytes.data() + bytes.size()), mask);
        EXPECT_EQ(at, bytes.data() + bytes.size());
    }
    std::vector<char> bad;
    pack(MaskHeader{4, 1}, bad);
    pack(MaskRun{3, 2}, bad);
    const char* at = bad.data();
    EXPECT_THROW(unpack_mask(at, bad.data() + bad.size()), std::runtime_error);
}

// Pixel i's layers appended to `out`, as a rank's message holds them.
void pack_pixel(const RenderResult& result, const std::vector<std::uint64_t>* keys, std::size_t i,
                std::vector<char>& out, PassLayers layers = PassLayers::all) {
    const std::size_t start = out.size();
    out.resize(start + pixel_bytes(result, keys, layers));
    char* at = out.data() + start;
    glint::pack_pixel(result, keys, i, at, layers);
}

// A frame's pixel, with every layer a frame may keep (the clamped mean, the AOVs, the path key),
// packed from one result and read into another: each layer lands in its place.
TEST(Records, APixelsLayersRoundTripIntoAnotherFrame) {
    const auto make = [] {
        RenderResult r;
        r.radiance = FloatImage(2, 1), r.clamped = FloatImage(2, 1);
        r.omitted_weight.assign(2, 0), r.ids.assign(2, 0), r.aovs = PrimaryAovs(2);
        return r;
    };
    RenderResult from = make(), to = make();
    std::vector<std::uint64_t> keys = {0, 0xfedcba9876543210ull}, back_keys = {0, 0};
    from.radiance.set(1, std::array{1.5f, 2.5f, 3.5f});
    from.clamped.set(1, std::array{0.25f, 0.5f, 0.75f});
    from.omitted_weight[1] = 0.125f, from.ids[1] = 7;
    from.aovs.depth[1] = 9.5f, from.aovs.id[1] = 8;
    from.aovs.normal = {0, 0, 0, 0.6f, 0.8f, 0.0f};
    std::vector<char> bytes;
    pack_pixel(from, &keys, 1, bytes);
    EXPECT_EQ(bytes.size(), pixel_bytes(from, &keys, PassLayers::all));
    const char* at = bytes.data();
    unpack_pixel(to, &back_keys, 1, at, bytes.data() + bytes.size());
    EXPECT_EQ(at, bytes.data() + bytes.size());
    EXPECT_EQ(to.radiance.rgb, from.radiance.rgb);
    EXPECT_EQ(to.clamped.rgb, from.clamped.rgb);
    EXPECT_EQ(to.omitted_weight, from.omitted_weight);
    EXPECT_EQ(to.ids, from.ids);
    EXPECT_EQ(to.aovs.depth[1], 9.5f);
    EXPECT_EQ(to.aovs.id, from.aovs.id);
    EXPECT_EQ(to.aovs.normal, from.aovs.normal);
    EXPECT_EQ(back_keys, keys);

    // A refining pass's layers: colour, clamped mean and cut-off weight move; the id, AOVs and
    // key the receiving frame has (its first pass's) stay.
    RenderResult refined = make();
    refined.ids[1] = 3, refined.aovs.id[1] = 4, refined.aovs.depth[1] = 5.5f;
    std::vector<std::uint64_t> kept = {0, 42};
    bytes.clear();
    pack_pixel(from, &keys, 1, bytes, PassLayers::refinement);
    EXPECT_EQ(bytes.size(), 16u + 12u);
    EXPECT_EQ(bytes.size(), pixel_bytes(from, &keys, PassLayers::refinement));
    at = bytes.data();
    unpack_pixel(refined, &kept, 1, at, bytes.data() + bytes.size(), PassLayers::refinement);
    EXPECT_EQ(at, bytes.data() + bytes.size());
    EXPECT_EQ(refined.radiance.rgb, from.radiance.rgb);
    EXPECT_EQ(refined.clamped.rgb, from.clamped.rgb);
    EXPECT_EQ(refined.omitted_weight, from.omitted_weight);
    EXPECT_EQ(refined.ids[1], 3u);
    EXPECT_EQ(refined.aovs.id[1], 4u);
    EXPECT_EQ(refined.aovs.depth[1], 5.5f);
    EXPECT_EQ(kept[1], 42u);
}

} // namespace
} // namespace glint
