#include "app/distributed.h"

#include "app/options.h"
#include "io/error.h"
#include "io/write_file.h"

#include <cerrno>
#include <chrono>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <mutex>
#include <numeric>
#include <thread>
#include <unistd.h>

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

} // namespace

int rank() {
    return rank_;
}
int ranks() {
    return ranks_;
}

#ifdef GLINT_HAVE_MPI

namespace {

bool joined_ = false;

// The exit code a single run gives for an exception (guarded(), app/options.cpp).
int exit_code_of(const std::exception& e) {
    return dynamic_cast<const UsageError*>(&e) || dynamic_cast<const SceneError*>(&e) ? 2 : 1;
}

// Set once this rank's work is done (finish_ranks): nothing is left to say or to remove.
volatile std::sig_atomic_t finished_ = 0;

// mpirun ends every rank with SIGTERM when one is lost (killed, crashed) or the run is
// interrupted: rank 0 says so in one line, and whatever rank removes the temporary file of an
// output it was writing (io/write_file.h), then ends as SIGTERM would have ended it. Once the
// rank has finished, the signal is let pass: a rank that leaves with a non-zero code (an error
// every rank agreed on, which rank 0 has already reported) makes mpirun end the others, and
// that must not add "a rank was lost" to the report, nor take this rank's own exit code.
void on_terminate(int) {
    if (finished_) return;
    if (rank_ == 0) {
        static const char message[] =
            "glint: error: rank 0: mpirun is ending the run (a rank was lost, or the run was "
            "interrupted); no output was written\n";
        [[maybe_unused]] const ssize_t n = ::write(2, message, sizeof message - 1);
    }
    remove_pending_write();
    std::signal(SIGTERM, SIG_DFL);
    std::raise(SIGTERM);
}

} // namespace

int start_ranks(char**) {
    if (launched_ranks() <= 1) return -1;
    std::signal(SIGTERM, on_terminate);
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
    if (!joined_) return;
    finished_ = 1;
    // No rank leaves before every rank has come this far (rank 0 may still be reporting).
    MPI_Barrier(MPI_COMM_WORLD);
    MPI_Finalize();
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

// Test-only faults (tests/mpi_test.sh), read once per frame from the environment:
//   GLINT_TEST_RANK_KILL=R:K   rank R raises SIGKILL as it takes its K-th tile (counted from 1);
//   GLINT_TEST_RANK_SLOW=R:MS  rank R sleeps MS milliseconds before each tile it asks for.
struct TestFaults {
    int kill_at = 0;  // this rank's tile to die at; 0: never
    int slow_ms = 0;  // per tile
    static TestFaults read() {
        TestFaults faults;
        const auto for_me = [](const char* name, int& value) {
            int who = -1, what = 0;
            if (const char* text = std::getenv(name))
                if (std::sscanf(text, "%d:%d", &who, &what) == 2 && who == rank_) value = what;
        };
        for_me("GLINT_TEST_RANK_KILL", faults.kill_at);
        for_me("GLINT_TEST_RANK_SLOW", faults.slow_ms);
        return faults;
    }
};

// Tiles claimed from counters on rank 0 (an MPI window, fetch-and-add), one counter a loop so that
// no loop waits for the others to start it afresh. Each tile another rank traces is sent to rank 0
// as soon as it is done (a message of its number and its pixels' layers, app/rank_records.h,
// tagged with the loop), so that the pixels travel while the ranks trace; rank 0's poller thread
// receives them into its frame as they come, and at the loop's end takes the rest. Rank 0 alone
// holds the whole image and decides which pixels a later loop refines; that decision goes back to
// every rank as runs of pixels.
class MpiExchange final : public TileExchange {
  public:
    // A frame's loops: centres, grids and at most kMaxSpreadRounds rounds (trace/sampling.h).
    static constexpr int kLoops = 32;
    static constexpr int kTileTag = 100; // + the loop

    explicit MpiExchange(int tiles) : tiles_(tiles), faults_(TestFaults::read()) {
        std::int64_t* counters = nullptr;
        const MPI_Aint bytes = rank_ == 0 ? kLoops * static_cast<MPI_Aint>(sizeof(std::int64_t)) : 0;
        MPI_Win_allocate(bytes, sizeof(std::int64_t), MPI_INFO_NULL, MPI_COMM_WORLD, &counters,
                         &window_);
        if (rank_ == 0) std::fill_n(counters, kLoops, 0);
        MPI_Barrier(MPI_COMM_WORLD); // the counters are 0 before anyone adds to them
        MPI_Win_lock_all(0, window_);
        if (rank_ == 0) poller_ = std::thread([this] { poll(); });
    }
    ~MpiExchange() override {
        {
            const std::lock_guard lock(mutex_);
            stop_ = true;
        }
        if (poller_.joinable()) poller_.join();
        MPI_Win_unlock_all(window_);
        MPI_Win_free(&window_);
    }
    const RankFigures& figures() const { return figures_; } // its exchanges' fields only

    void open(FramePass pass, RenderResult& result, std::vector<std::uint64_t>* keys,
              const std::vector<std::uint8_t>* only) override {
        const std::lock_guard lock(mutex_);
        if (loop_ >= kLoops) throw std::logic_error("a frame of more loops than the exchange counts");
        pass_ = pass, result_ = &result, keys_ = keys, only_ = only;
        // A pass over a mask's pixels (adaptive antialiasing's grids) changes only their colour
        // and cut-off weight: their ids, AOVs and keys on this rank may be another rank's.
        layers_ = only ? PassLayers::refinement : PassLayers::all;
        exhausted_ = false, received_ = 0, sent_ = 0;
        open_ = true;
    }

    int claim() override {
        if (faults_.slow_ms > 0)
            std::this_thread::sleep_for(std::chrono::milliseconds(faults_.slow_ms));
        const std::lock_guard lock(mutex_);
        if (exhausted_) return -1;
        const std::int64_t one = 1;
        std::int64_t tile = 0;
        MPI_Fetch_and_op(&one, &tile, MPI_INT64_T, 0, loop_, MPI_SUM, window_);
        MPI_Win_flush(0, window_);
        if (tile >= tiles_) exhausted_ = true;
        if (exhausted_) return -1;
        ++claimed_;
        if (faults_.kill_at == claimed_) std::raise(SIGKILL);
        return static_cast<int>(tile);
    }

    void traced(int tile) override {
        if (rank_ == 0) return; // in place
        const Stopwatch watch;
        std::vector<char> bytes = spare_buffer();
        const std::size_t pixel = pixel_bytes(*result_, keys_, layers_);
        std::size_t size = sizeof(TileHeader);
        for_each_pixel(tile, [&](std::size_t) { size += pixel; });
        bytes.resize(size);
        char* at = bytes.data();
        pack_to(TileHeader{static_cast<std::uint32_t>(tile)}, at);
        for_each_pixel(tile, [&](std::size_t i) { pack_pixel(*result_, keys_, i, at, layers_); });
        const std::lock_guard lock(mutex_);
        if (bytes.size() > static_cast<std::size_t>(INT_MAX))
            throw std::runtime_error("a tile of over 2 GiB");
        Sending& sending = sending_.emplace_back(Sending{std::move(bytes), MPI_REQUEST_NULL});
        MPI_Isend(sending.bytes.data(), static_cast<int>(sending.bytes.size()), MPI_BYTE, 0,
                  kTileTag + loop_, MPI_COMM_WORLD, &sending.request);
        ++sent_;
        PassExchange& figures = figures_.after(pass_);
        figures.sent += sending.bytes.size();
        retire_sent(false);
        figures.seconds += watch.seconds();
    }

    void close() override {
        const Stopwatch watch;
        const std::lock_guard lock(mutex_);
        open_ = false; // the poller leaves MPI to this thread until the next loop
        PassExchange& figures = figures_.after(pass_);
        // How many tiles each rank sent, so that rank 0 knows when it has them all; then rank 0
        // takes those still on their way, and the others see their sends through.
        std::vector<int> counts(rank_ == 0 ? static_cast<std::size_t>(ranks_) : 0);
        MPI_Gather(&sent_, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
        if (rank_ == 0) {
            figures.received += sizeof(int) * static_cast<std::uint64_t>(ranks_ - 1);
            const int expected = std::accumulate(counts.begin(), counts.end(), 0);
            while (received_ < expected) receive(true);
        } else {
            figures.sent += sizeof(int);
            retire_sent(true);
        }
        ++loop_;
        ++figures.exchanges;
        figures.seconds += watch.seconds();
    }

    bool decides() const override { return rank_ == 0; }
    int tiles_taken() const override { return claimed_; }

    void agree(FramePass pass, std::vector<std::uint8_t>& mask) override {
        const Stopwatch watch;
        const std::lock_guard lock(mutex_);
        PassExchange& figures = figures_.after(pass);
        std::vector<char> bytes;
        if (rank_ == 0) pack_mask(mask, bytes);
        std::uint64_t size = bytes.size();
        MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
        if (size > static_cast<std::uint64_t>(INT_MAX))
            throw std::runtime_error("a mask of over 2 GiB to hand out");
        bytes.resize(size);
        MPI_Bcast(bytes.data(), static_cast<int>(size), MPI_BYTE, 0, MPI_COMM_WORLD);
        const std::uint64_t moved = sizeof size + size;
        if (rank_ == 0) {
            figures.sent += moved * static_cast<std::uint64_t>(ranks_ - 1);
        } else {
            figures.received += moved;
            const char* at = bytes.data();
            mask = unpack_mask(at, at + bytes.size());
        }
        ++figures.exchanges;
        figures.seconds += watch.seconds();
    }

  private:
    struct Sending {
        std::vector<char> bytes;
        MPI_Request request;
    };

    // Calls visit(i) for the pixels of `tile` the open loop writes.
    template <class Visit> void for_each_pixel(int tile, const Visit& visit) const {
        for_each_pixel_of_tile(result_->width(), result_->height(), tile, [&](std::size_t i) {
            if (!only_ || (*only_)[i]) visit(i);
        });
    }

    // A buffer of a tile already sent, for the next one (fresh pages cost more than the copy).
    std::vector<char> spare_buffer() {
        const std::lock_guard lock(mutex_);
        if (spare_.empty()) return {};
        std::vector<char> bytes = std::move(spare_.back());
        spare_.pop_back();
        return bytes;
    }

    // Sends that have completed give their buffers back; with `all`, waits for every one. Under
    // mutex_.
    void retire_sent(bool all) {
        while (!sending_.empty()) {
            int done = 0;
            if (all)
                MPI_Wait(&sending_.front().request, MPI_STATUS_IGNORE), done = 1;
            else
                MPI_Test(&sending_.front().request, &done, MPI_STATUS_IGNORE);
            if (!done) return;
            spare_.push_back(std::move(sending_.front().bytes));
            sending_.pop_front();
        }
    }

    // Rank 0: one tile's message of the open loop into the frame; with `wait`, waits for it,
    // else only takes one that has arrived. Returns whether it took one. Under mutex_.
    bool receive(bool wait) {
        MPI_Status status;
        int arrived = 1;
        const int tag = kTileTag + loop_;
        if (wait)
            MPI_Probe(MPI_ANY_SOURCE, tag, MPI_COMM_WORLD, &status);
        else
            MPI_Iprobe(MPI_ANY_SOURCE, tag, MPI_COMM_WORLD, &arrived, &status);
        if (!arrived) return false;
        const Stopwatch watch;
        int count = 0;
        MPI_Get_count(&status, MPI_BYTE, &count);
        incoming_.resize(static_cast<std::size_t>(count));
        MPI_Recv(incoming_.data(), count, MPI_BYTE, status.MPI_SOURCE, tag, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
        const char* at = incoming_.data();
        const char* const end = at + incoming_.size();
        TileHeader header;
        unpack(header, at, end);
        if (header.tile >= static_cast<std::uint32_t>(tiles_))
            throw std::runtime_error("a rank sent a tile the frame does not have");
        for_each_pixel(static_cast<int>(header.tile),
                       [&](std::size_t i) { unpack_pixel(*result_, keys_, i, at, end, layers_); });
        ++received_;
        PassExchange& figures = figures_.after(pass_);
        figures.received += static_cast<std::uint64_t>(count);
        if (!wait) figures.seconds += watch.seconds();
        return true;
    }

    // Rank 0, while a loop is open: takes the tiles that have arrived, and makes MPI progress
    // every 0.2 ms otherwise. Where the window's fetch-and-add travels as messages (over TCP,
    // osc/pt2pt), rank 0 answers another rank's claim only inside an MPI call, which its tracing
    // threads make only between their own tiles.
    void poll() {
        try {
            for (;;) {
                std::this_thread::sleep_for(std::chrono::microseconds(200));
                const std::lock_guard lock(mutex_);
                if (stop_) return;
                if (!open_) continue;
                while (receive(false)) {
                }
            }
        } catch (const std::exception& e) { // a message that is not a tile of this frame
            std::fprintf(stderr, "glint: error: rank 0: %s\n", e.what());
            std::fflush(stderr);
            MPI_Abort(MPI_COMM_WORLD, 1);
        }
    }

    int tiles_;
    TestFaults faults_;
    MPI_Win window_ = MPI_WIN_NULL;
    std::mutex mutex_; // one MPI call at a time (MPI_THREAD_SERIALIZED); guards what follows
    std::thread poller_;
    bool open_ = false, stop_ = false;
    FramePass pass_ = FramePass::centres;
    RenderResult* result_ = nullptr;
    std::vector<std::uint64_t>* keys_ = nullptr;
    const std::vector<std::uint8_t>* only_ = nullptr;
    PassLayers layers_ = PassLayers::all;
    bool exhausted_ = false;
    int loop_ = 0;     // this frame's loops so far: the counter this loop claims from, its tag
    int claimed_ = 0;  // this rank's tiles, all loops
    int sent_ = 0, received_ = 0; // tile messages this loop
    std::deque<Sending> sending_;
    std::vector<std::vector<char>> spare_;
    std::vector<char> incoming_;
    RankFigures figures_; // centres, grids, spread: what the exchanges after each moved
};

} // namespace

std::unique_ptr<TileExchange> make_exchange(int tiles) {
    return std::make_unique<MpiExchange>(tiles);
}

void exchange_figures(const TileExchange& exchange, RankFigures& figures) {
    const RankFigures& mine = static_cast<const MpiExchange&>(exchange).figures();
    figures.centres = mine.centres, figures.grids = mine.grids, figures.spread = mine.spread;
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

#else // the program without MPI (glint): one process; under mpirun it becomes glint-mpi

int start_ranks(char** argv) {
    if (launched_ranks() <= 1) return -1;
    // mpirun started this process among others: it becomes the program built beside it with
    // Open MPI, the same commands (the same process to mpirun; execv returns only on failure).
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    const std::filesystem::path mpi_program = self.parent_path() / "glint-mpi";
    if (!error && std::filesystem::exists(mpi_program, error)) {
        ::execv(mpi_program.c_str(), argv);
        if (launched_rank() == 0)
            std::fprintf(stderr, "glint: error: started by mpirun: cannot run %s: %s\n",
                         mpi_program.c_str(), std::strerror(errno));
        return 2;
    }
    if (launched_rank() == 0)
        std::fprintf(stderr,
                     "glint: error: started by mpirun with %d ranks, but this glint was "
                     "built without MPI: no %s beside it (install libopenmpi-dev and build "
                     "again; ./glint does both)\n",
                     launched_ranks(), mpi_program.c_str());
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

void exchange_figures(const TileExchange&, RankFigures&) {}

std::vector<std::vector<char>> gather_bytes(const std::vector<char>& mine) {
    return {mine};
}

std::vector<RankFigures> gather_figures(const RankFigures& mine) {
    return {mine};
}

void sum_over_ranks(FrameCounters&) {}

#endif

} // namespace glint
