#include "app/distributed.h"

#include "app/options.h"
#include "io/error.h"

#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>

#ifdef GLINT_HAVE_MPI
#include <mpi.h>
#endif

namespace glint {

namespace {

// How many processes mpirun started with this one, from the launcher's environment (Open MPI,
// or PMI/PMIx launchers); 1 when glint was started by hand.
int launched_ranks() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
        if (const char* value = std::getenv(name)) return std::max(1, std::atoi(value));
    return 1;
}

[[maybe_unused]] int launched_rank() {
    for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"})
        if (const char* value = std::getenv(name)) return std::atoi(value);
    return 0;
}

int rank_ = 0, ranks_ = 1;
bool joined_ = false;

// The exit code a single run gives for an exception (guarded(), app/options.cpp).
int exit_code_of(const std::exception& e) {
    return dynamic_cast<const UsageError*>(&e) || dynamic_cast<const SceneError*>(&e) ? 2 : 1;
}

} // namespace

int rank() {
    return rank_;
}
int ranks() {
    return ranks_;
}

#ifdef GLINT_HAVE_MPI

int start_ranks() {
    if (launched_ranks() <= 1) return -1;
    // Worker threads claim tiles (MPI_Fetch_and_op), one at a time under a mutex.
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
    joined_ = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
    if (provided < MPI_THREAD_SERIALIZED) {
        if (rank_ == 0)
            std::fprintf(stderr, "glint: error: this MPI does not let threads call it one at a "
                                 "time (MPI_THREAD_SERIALIZED), which claiming tiles needs\n");
        finish_ranks();
        return 1;
    }
    return -1;
}

void finish_ranks() {
    if (joined_) MPI_Finalize();
    joined_ = false;
}

int agree_on(const std::function<void()>& step) {
    if (!on_ranks()) {
        step();
        return 0;
    }
    int status = 0;
    std::string message;
    try {
        step();
    } catch (const std::exception& e) {
        status = exit_code_of(e), message = e.what();
    }
    int worst = 0;
    MPI_Allreduce(&status, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (worst == 0) return 0;
    // The message of the lowest failing rank, on rank 0: every rank reads the same files, so it is
    // usually rank 0's own.
    int failing = status != 0 ? rank_ : ranks_, first = 0;
    MPI_Allreduce(&failing, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (first != 0) {
        if (rank_ == first) {
            const int length = static_cast<int>(message.size());
            MPI_Send(&length, 1, MPI_INT, 0, 0, MPI_COMM_WORLD);
            MPI_Send(message.data(), length, MPI_CHAR, 0, 1, MPI_COMM_WORLD);
        } else if (rank_ == 0) {
            int length = 0;
            MPI_Recv(&length, 1, MPI_INT, first, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            message.resize(static_cast<std::size_t>(length));
            MPI_Recv(message.data(), length, MPI_CHAR, first, 1, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            message = "rank " + std::to_string(first) + ": " + message;
        }
    }
    if (rank_ == 0) std::fprintf(stderr, "glint: error: %s\n", message.c_str());
    return worst;
}

int guarded_on_ranks(const std::function<int()>& body) {
    if (!on_ranks()) return guarded(body);
    try {
        return body();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint: error: rank %d: %s\n", rank_, e.what());
        std::fflush(stderr);
        MPI_Abort(MPI_COMM_WORLD, exit_code_of(e));
        return exit_code_of(e);
    }
}

namespace {

// Tiles claimed from a counter on rank 0 (an MPI window, fetch-and-add), counted from 0 again
// after each loop's exchange; the exchange is every rank's list of tiles and their pixels, packed
// tile by tile (colour 3 bytes, cut-off weight 4, id 4, path key 8 when asked), gathered by every
// rank.
class MpiExchange final : public TileExchange {
  public:
    explicit MpiExchange(int tiles) : TileExchange(tiles), tiles_(tiles) {
        std::int64_t* counter = nullptr;
        MPI_Win_allocate(rank_ == 0 ? static_cast<MPI_Aint>(sizeof(std::int64_t)) : 0,
                         sizeof(std::int64_t), MPI_INFO_NULL, MPI_COMM_WORLD, &counter, &window_);
        if (rank_ == 0) *counter = 0;
        MPI_Barrier(MPI_COMM_WORLD); // the counter is 0 before anyone adds to it
        MPI_Win_lock_all(0, window_);
    }
    ~MpiExchange() override {
        MPI_Win_unlock_all(window_);
        MPI_Win_free(&window_);
    }
    double seconds() const { return seconds_; }

    int claim() override {
        const std::lock_guard lock(mutex_);
        if (exhausted_) return -1;
        const std::int64_t one = 1;
        std::int64_t tile = 0;
        MPI_Fetch_and_op(&one, &tile, MPI_INT64_T, 0, 0, MPI_SUM, window_);
        MPI_Win_flush(0, window_);
        if (tile >= tiles_) exhausted_ = true;
        return exhausted_ ? -1 : static_cast<int>(tile);
    }

    void share(RenderResult& result, std::vector<std::uint64_t>* keys) override {
        const Stopwatch watch;
        const int width = result.radiance.width, height = result.radiance.height;
        std::vector<int> my_tiles;
        std::vector<char> mine;
        for (int t = 0; t < tiles_; ++t) {
            if (!this->mine()[static_cast<std::size_t>(t)]) continue;
            my_tiles.push_back(t);
            for_each_pixel_of_tile(width, height, t,
                                   [&](std::size_t i) { pack_pixel(result, keys, i, mine); });
        }
        // Every rank's tiles and pixels, in rank order, each rank's tiles ascending: as packed.
        const std::vector<int> tiles = all_gather(my_tiles);
        const std::vector<char> all = all_gather(mine);
        const char* at = all.data();
        const char* const end = at + all.size();
        // Every pixel packs the same layers, so this rank's own tiles (already in place) are
        // skipped by their size.
        std::vector<char> one;
        pack_pixel(result, keys, 0, one);
        for (const int t : tiles) {
            if (this->mine()[static_cast<std::size_t>(t)]) {
                at += tile_rect(width, height, t).pixels() * one.size();
                continue;
            }
            for_each_pixel_of_tile(width, height, t,
                                   [&](std::size_t i) { unpack_pixel(result, keys, i, at, end); });
        }
        // Every rank has finished claiming (it is here): the next loop counts from 0 again, and
        // nobody claims before it does.
        if (rank_ == 0) {
            const std::int64_t zero = 0;
            MPI_Accumulate(&zero, 1, MPI_INT64_T, 0, 0, 1, MPI_INT64_T, MPI_REPLACE, window_);
            MPI_Win_flush(0, window_);
        }
        MPI_Barrier(MPI_COMM_WORLD);
        next_loop();
        exhausted_ = false;
        seconds_ += watch.seconds();
    }

  private:
    // Every rank's `mine`, concatenated in rank order, on every rank.
    template <class T> static std::vector<T> all_gather(const std::vector<T>& mine) {
        const std::size_t bytes = mine.size() * sizeof(T);
        if (bytes > static_cast<std::size_t>(INT_MAX))
            throw std::runtime_error("a rank's share of the frame is over 2 GiB: use more ranks");
        const int count = static_cast<int>(bytes);
        std::vector<int> counts(static_cast<std::size_t>(ranks_)), offsets(counts.size());
        MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
        long long total = 0;
        for (std::size_t r = 0; r < counts.size(); ++r) {
            if (total > INT_MAX) throw std::runtime_error("the frame is over 2 GiB to exchange");
            offsets[r] = static_cast<int>(total), total += counts[r];
        }
        std::vector<T> all(static_cast<std::size_t>(total) / sizeof(T));
        MPI_Allgatherv(mine.data(), count, MPI_BYTE, all.data(), counts.data(), offsets.data(),
                       MPI_BYTE, MPI_COMM_WORLD);
        return all;
    }

    int tiles_;
    MPI_Win window_ = MPI_WIN_NULL;
    std::mutex mutex_; // one claim at a time (MPI_THREAD_SERIALIZED)
    bool exhausted_ = false;
    double seconds_ = 0;
};

} // namespace

std::unique_ptr<TileExchange> make_exchange(int tiles) {
    return std::make_unique<MpiExchange>(tiles);
}

double exchange_seconds(const TileExchange& exchange) {
    return static_cast<const MpiExchange&>(exchange).seconds();
}

std::vector<std::vector<char>> gather_bytes(const std::vector<char>& mine) {
    const int count = static_cast<int>(mine.size());
    std::vector<int> counts(static_cast<std::size_t>(ranks_)), offsets(counts.size());
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    int total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) offsets[r] = total, total += counts[r];
    std::vector<char> all(rank_ == 0 ? static_cast<std::size_t>(total) : 0);
    MPI_Gatherv(mine.data(), count, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE,
                0, MPI_COMM_WORLD);
    std::vector<std::vector<char>> out;
    if (rank_ == 0)
        for (std::size_t r = 0; r < counts.size(); ++r)
            out.emplace_back(all.begin() + offsets[r], all.begin() + offsets[r] + counts[r]);
    return out;
}

std::vector<RankFigures> gather_figures(const RankFigures& mine) {
    std::vector<RankFigures> all;
    for (const std::vector<RankFigures>& rank_figures : gather_records(std::vector{mine}))
        all.push_back(rank_figures.at(0));
    return all;
}

void sum_over_ranks(FrameCounters& counters) {
    // The counters as one array, in their fields' order, summed, and read back in that order.
    std::vector<std::uint64_t> values;
    for_each_field(counters, [&](const std::string&, std::uint64_t value) { values.push_back(value); });
    MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_UINT64_T,
                  MPI_SUM, MPI_COMM_WORLD);
    std::size_t k = 0;
    for_each_field(counters, [&](const std::string&, std::uint64_t& value) { value = values[k++]; });
}

#else // a build without MPI: one process, always

int start_ranks() {
    if (launched_ranks() <= 1) return -1;
    if (launched_rank() == 0)
        std::fprintf(stderr,
                     "glint: error: started by mpirun with %d ranks, but this glint was "
                     "built without MPI (install libopenmpi-dev and build again; "
                     "./glint does both)\n",
                     launched_ranks());
    return 2;
}

void finish_ranks() {}

int agree_on(const std::function<void()>& step) {
    step();
    return 0;
}

int guarded_on_ranks(const std::function<int()>& body) {
    return guarded(body);
}

std::unique_ptr<TileExchange> make_exchange(int) {
    return nullptr;
}

double exchange_seconds(const TileExchange&) {
    return 0;
}

std::vector<std::vector<char>> gather_bytes(const std::vector<char>& mine) {
    return {mine};
}

std::vector<RankFigures> gather_figures(const RankFigures& mine) {
    return {mine};
}

void sum_over_ranks(FrameCounters&) {}

#endif

} // namespace glint
