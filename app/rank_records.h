// The messages glint's MPI ranks exchange (docs/DISTRIBUTED.md), each a record whose fields are
// listed once, by name (trace/record.h; the tracer's counters in trace/frame_records.h): a
// frame's counters, each rank's figures, a tradeoff run's figures, and a frame's pixels, layer by
// layer. tests/record_test.cpp round-trips them all.
#pragma once

#include "trace/frame_records.h"
#include "trace/ray_tree.h"
#include "trace/tiles.h"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace glint {

// A frame's counters, summed over ranks (each rank counts its own tiles' rays and resolves).
struct FrameCounters {
    RayCounts rays;
    PrimaryStats primary;
};
template <> struct RecordFields<FrameCounters> {
    template <class R, class V> static void visit(R& r, V&& v) {
        v("rays", r.rays), v("primary", r.primary);
    }
};

// What one kind of pass's exchanges moved on a rank: its pixels gathered on rank 0, and the
// masks rank 0 handed out for it. Bytes are the messages' payloads (records and their counts).
struct PassExchange {
    double seconds = 0;          // wall time in the exchange, waiting for the others included
    std::uint64_t sent = 0;      // bytes this rank sent
    std::uint64_t received = 0;  // bytes this rank received
    std::uint64_t exchanges = 0; // gathers and hand-outs
};
template <> struct RecordFields<PassExchange> {
    template <class R, class V> static void visit(R& r, V&& v) {
        v("seconds", r.seconds), v("sent", r.sent), v("received", r.received);
        v("exchanges", r.exchanges);
    }
};

// What each rank did for one frame, gathered on rank 0 for the report.
struct RankFigures {
    double load = 0, prepare = 0; // scene load and World (structures), seconds
    double gl = 0;                // GL context, shaders, upload, item buffer
    double trace = 0;             // the passes' primary hits and shading (tiles sent as traced)
    // The exchanges after each kind of pass (trace/tiles.h's FramePass).
    PassExchange centres, grids, spread;
    std::uint64_t tiles = 0; // tiles traced (all passes)
    std::uint64_t rays = 0;  // rays cast

    PassExchange& after(FramePass pass) {
        return pass == FramePass::centres ? centres : pass == FramePass::grids ? grids : spread;
    }
    PassExchange exchange() const { // all passes'
        PassExchange sum;
        for (const PassExchange* p : {&centres, &grids, &spread}) {
            sum.seconds += p->seconds, sum.sent += p->sent, sum.received += p->received;
            sum.exchanges += p->exchanges;
        }
        return sum;
    }
};
template <> struct RecordFields<RankFigures> {
    template <class R, class V> static void visit(R& r, V&& v) {
        v("load", r.load), v("prepare", r.prepare), v("gl", r.gl), v("trace", r.trace);
        v("centres", r.centres), v("grids", r.grids), v("spread", r.spread);
        v("tiles", r.tiles), v("rays", r.rays);
    }
};

// What a tradeoff run's differing pixels owe to one cause (trace/ray_tree.h).
struct CauseError {
    std::uint64_t pixels = 0;
    double squared_error = 0; // Σ over its pixels and channels of the radiance difference²
};
template <> struct RecordFields<CauseError> {
    template <class R, class V> static void visit(R& r, V&& v) {
        v("pixels", r.pixels), v("squared_error", r.squared_error);
    }
};

// A run's differing pixels by cause (frame/difference.h's tallies, without their levels).
struct CauseFigures {
    CauseError sampling, depth, cutoff, primary, secondary, shadow, precision;

    const CauseError& at(Cause cause) const {
        switch (cause) {
        case Cause::sampling:
            return sampling;
        case Cause::depth:
            return depth;
        case Cause::cutoff:
            return cutoff;
        case Cause::primary:
            return primary;
        case Cause::secondary:
            return secondary;
        case Cause::shadow:
            return shadow;
        case Cause::precision:
        case Cause::none:
            break;
        }
        return precision;
    }
    CauseError& at(Cause cause) { return const_cast<CauseError&>(std::as_const(*this).at(cause)); }
    double squared_error() const {
        double sum = 0;
        for (std::size_t c = 1; c < kCauses; ++c) sum += at(static_cast<Cause>(c)).squared_error;
        return sum;
    }
    // The cause's share of the squared error (0 where there is none).
    double share(Cause cause) const {
        const double total = squared_error();
        return total > 0 ? at(cause).squared_error / total : 0;
    }
};
template <> struct RecordFields<CauseFigures> {
    template <class R, class V> static void visit(R& r, V&& v) {
        v("sampling", r.sampling), v("depth", r.depth), v("cutoff", r.cutoff);
        v("primary", r.primary), v("secondary", r.secondary), v("shadow", r.shadow);
        v("precision", r.precision);
    }
};

// What `glint tradeoff` measured of one setting on a rank, sent to rank 0 for the CSV.
struct RunFigures {
    PhaseTimes times;
    RayCounts rays;
    ImageDifference diff{};
    std::optional<double> agreement; // against the reference's ids
    int bound_max = 0;               // the cut-off bound (trace/cutoff.h)
    std::uint64_t bound_pixels_over_one = 0;
    double largest_omitted_weight = 0;
    std::optional<bool> bound_held;
    std::optional<std::uint64_t> refined;
    std::uint64_t pixels = 0;
    CauseFigures causes; // against the run's reference
};
template <> struct RecordFields<RunFigures> {
    template <class R, class V> static void visit(R& r, V&& v) {
        v("times", r.times), v("rays", r.rays), v("diff", r.diff), v("agreement", r.agreement);
        v("bound_max", r.bound_max), v("bound_pixels_over_one", r.bound_pixels_over_one);
        v("largest_omitted_weight", r.largest_omitted_weight), v("bound_held", r.bound_held);
        v("refined", r.refined), v("pixels", r.pixels), v("causes", r.causes);
    }
};

// A frame's pixels after a pass, as layers: each pixel sends the layers its frame keeps (every
// rank's frame keeps the same), each a record.
struct PixelColour {
    float r = 0, g = 0, b = 0;
};
template <> struct RecordFields<PixelColour> {
    template <class R, class V> static void visit(R& p, V&& v) {
        v("r", p.r), v("g", p.g), v("b", p.b);
    }
};
struct PixelFacts {
    PixelColour radiance;
    float omitted_weight = 0;
    std::uint32_t id = 0;
};
template <> struct RecordFields<PixelFacts> {
    template <class R, class V> static void visit(R& p, V&& v) {
        v("radiance", p.radiance), v("omitted_weight", p.omitted_weight), v("id", p.id);
    }
};
struct PixelAov {
    float depth = 0;
    PixelColour normal; // x, y, z as r, g, b
    std::uint32_t id = 0;
};
template <> struct RecordFields<PixelAov> {
    template <class R, class V> static void visit(R& p, V&& v) {
        v("depth", p.depth), v("normal", p.normal), v("id", p.id);
    }
};
// A rank's pixels of one tile follow its number; which pixels, and which layers, both sides
// know (every pixel of the tile, or those of the pass's mask).
struct TileHeader {
    std::uint32_t tile = 0;
};
template <> struct RecordFields<TileHeader> {
    template <class R, class V> static void visit(R& t, V&& v) { v("tile", t.tile); }
};
// Which pixels a pass refines, as rank 0 hands it out: the image's pixel count and how many runs
// follow, then the runs, row by row from the top left: `skip` pixels not refined, `take` refined.
struct MaskHeader {
    std::uint64_t pixels = 0;
    std::uint64_t runs = 0;
};
template <> struct RecordFields<MaskHeader> {
    template <class R, class V> static void visit(R& m, V&& v) {
        v("pixels", m.pixels), v("runs", m.runs);
    }
};
struct MaskRun {
    std::uint32_t skip = 0, take = 0;
};
template <> struct RecordFields<MaskRun> {
    template <class R, class V> static void visit(R& m, V&& v) {
        v("skip", m.skip), v("take", m.take);
    }
};

// A mask (1 where a pixel is refined) as MaskHeader and MaskRun records, and read back.
inline void pack_mask(const std::vector<std::uint8_t>& mask, std::vector<char>& out) {
    std::vector<MaskRun> runs;
    for (std::size_t i = 0; i < mask.size();) {
        MaskRun run;
        for (; i < mask.size() && !mask[i]; ++i) ++run.skip;
        for (; i < mask.size() && mask[i]; ++i) ++run.take;
        if (run.take) runs.push_back(run);
    }
    pack(MaskHeader{mask.size(), runs.size()}, out);
    for (const MaskRun& run : runs) pack(run, out);
}
inline std::vector<std::uint8_t> unpack_mask(const char*& at, const char* end) {
    MaskHeader header;
    unpack(header, at, end);
    std::vector<std::uint8_t> mask(header.pixels, 0);
    std::size_t i = 0;
    for (std::uint64_t r = 0; r < header.runs; ++r) {
        MaskRun run;
        unpack(run, at, end);
        if (std::uint64_t{run.skip} + run.take > mask.size() - i)
            throw std::runtime_error("a mask from rank 0 runs past its image");
        i += run.skip;
        std::fill_n(mask.begin() + static_cast<std::ptrdiff_t>(i), run.take, 1);
        i += run.take;
    }
    return mask;
}

struct PixelPathKey {
    std::uint64_t key = 0;
};
template <> struct RecordFields<PixelPathKey> {
    template <class R, class V> static void visit(R& p, V&& v) { v("key", p.key); }
};

inline PixelColour colour_at(const FloatImage& image, std::size_t i) {
    const float* c = image.pixel(i);
    return {c[0], c[1], c[2]};
}
inline void set_colour(FloatImage& image, std::size_t i, const PixelColour& c) {
    float* p = image.pixel(i);
    p[0] = c.r, p[1] = c.g, p[2] = c.b;
}

// What a refining pass (the grids of a mask's pixels) changes of a pixel: its colour and cut-off
// weight (and the clamped mean, sent beside it); its id, AOVs and path key stay the first pass's.
struct PixelRefinement {
    PixelColour radiance;
    float omitted_weight = 0;
};
template <> struct RecordFields<PixelRefinement> {
    template <class R, class V> static void visit(R& p, V&& v) {
        v("radiance", p.radiance), v("omitted_weight", p.omitted_weight);
    }
};

// Which of a pixel's layers a pass wrote: all those the frame keeps, or (a pass over a mask's
// pixels) those a refinement changes.
enum class PassLayers { all, refinement };

// Pixel i of `result` (and of `keys`, where given): the layers a pass of `layers` wrote, at `at`
// (advanced past them), which has room for them (pixel_bytes).
inline void pack_pixel(const RenderResult& result, const std::vector<std::uint64_t>* keys,
                       std::size_t i, char*& at, PassLayers layers = PassLayers::all) {
    if (layers == PassLayers::refinement)
        pack_to(PixelRefinement{colour_at(result.radiance, i), result.omitted_at(i)}, at);
    else
        pack_to(PixelFacts{colour_at(result.radiance, i), result.omitted_at(i), result.ids[i]}, at);
    if (!result.clamped.empty()) pack_to(colour_at(result.clamped, i), at);
    if (layers == PassLayers::refinement) return;
    if (!result.aovs.empty()) {
        const float* n = &result.aovs.normal[3 * i];
        pack_to(PixelAov{result.aovs.depth[i], {n[0], n[1], n[2]}, result.aovs.id[i]}, at);
    }
    if (keys) pack_to(PixelPathKey{(*keys)[i]}, at);
}

// The bytes pack_pixel writes for each pixel of `result`.
inline std::size_t pixel_bytes(const RenderResult& result, const std::vector<std::uint64_t>* keys,
                               PassLayers layers) {
    std::size_t bytes = layers == PassLayers::refinement ? sizeof(PixelRefinement)
                                                         : sizeof(PixelFacts);
    if (!result.clamped.empty()) bytes += sizeof(PixelColour);
    if (layers == PassLayers::all && !result.aovs.empty()) bytes += sizeof(PixelAov);
    if (layers == PassLayers::all && keys) bytes += sizeof(PixelPathKey);
    return bytes;
}

// Reads back what pack_pixel wrote into pixel i of `result` (and `keys`).
inline void unpack_pixel(RenderResult& result, std::vector<std::uint64_t>* keys, std::size_t i,
                         const char*& at, const char* end, PassLayers layers = PassLayers::all) {
    if (layers == PassLayers::refinement) {
        PixelRefinement refinement;
        unpack(refinement, at, end);
        set_colour(result.radiance, i, refinement.radiance);
        result.set_omitted(i, refinement.omitted_weight);
    } else {
        PixelFacts facts;
        unpack(facts, at, end);
        set_colour(result.radiance, i, facts.radiance);
        result.set_omitted(i, facts.omitted_weight), result.ids[i] = facts.id;
    }
    if (!result.clamped.empty()) {
        PixelColour clamped;
        unpack(clamped, at, end);
        set_colour(result.clamped, i, clamped);
    }
    if (layers == PassLayers::refinement) return;
    if (!result.aovs.empty()) {
        PixelAov aov;
        unpack(aov, at, end);
        result.aovs.depth[i] = aov.depth, result.aovs.id[i] = aov.id;
        float* n = &result.aovs.normal[3 * i];
        n[0] = aov.normal.r, n[1] = aov.normal.g, n[2] = aov.normal.b;
    }
    if (keys) {
        PixelPathKey key;
        unpack(key, at, end);
        (*keys)[i] = key.key;
    }
}

} // namespace glint
