// One frame across MPI ranks (docs/DISTRIBUTED.md): `mpirun -np N glint render …` (and a
// `glint tradeoff` sweep spread over ranks, one setting per rank at a time). Every rank
// loads the scene and builds its own structures; tiles are handed out as ranks ask for them
// (trace/tiles.h's TileExchange) and gathered on rank 0 after each pass; rank 0 decides what a
// later pass refines, writes the PNG and prints the report.
//
// app/distributed.cpp is compiled twice (app/CMakeLists.txt): into glint, the Python module and the
// fuzzer without MPI, where everything here is one process and nothing loads Open MPI's libraries
// (3 ms of every start), and into glint-mpi with it. glint started by mpirun becomes glint-mpi,
// built beside it, before it reads its arguments (start_ranks).
#pragma once

#include "app/rank_records.h"

#include "trace/stopwatch.h"
#include "trace/tiles.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace glint {

// Called first thing in main(), with its argv: when mpirun started this process with others,
// glint-mpi joins them (MPI initialised) and glint runs glint-mpi in its place with the same
// arguments, or, where no glint-mpi was built beside it, refuses (exit 2, one message). Returns
// an exit code to stop with, or -1 to go on.
int start_ranks(char** argv);
// Called last: leaves MPI, if it was joined.
void finish_ranks();

int rank();  // 0 in a single process
int ranks(); // 1 in a single process
inline bool on_ranks() {
    return ranks() > 1;
}

// Runs `step` (a command's input checks) on every rank and agrees on the outcome: 0 when it
// succeeded everywhere; else the exit code of the worst failure (2 for bad input, 1 for other
// errors), its message printed once, by rank 0 (naming the rank when it was not rank 0's own).
// In a single process it just runs `step`, whose exceptions propagate as they always have.
int agree_on(const std::function<void()>& step);

// A command body on ranks: as guarded() (app/options.h), but an error on one rank after the
// ranks agreed to start cannot be waited out by the others, so it prints its message (naming the
// rank) and aborts every rank with the exit code a single run would give.
int guarded_on_ranks(const std::function<int()>& body);

// The tile claims and pixel exchange of one frame of `tiles` tiles over MPI (collective: every
// rank makes it, and lets it go, together), and what its exchanges after each kind of pass took
// and moved (into figures.centres, .grids, .spread).
std::unique_ptr<TileExchange> make_exchange(int tiles);
void exchange_figures(const TileExchange& exchange, RankFigures& figures);

// Every rank's bytes on rank 0 (one vector per rank there; empty elsewhere).
std::vector<std::vector<char>> gather_bytes(const std::vector<char>& mine);

// Every rank's records on rank 0 (app/rank_records.h: each packed and read back by name), one
// vector per rank there; empty elsewhere.
template <Record R> std::vector<std::vector<R>> gather_records(const std::vector<R>& mine) {
    std::vector<char> bytes;
    for (const R& record : mine) pack(record, bytes);
    std::vector<std::vector<R>> all;
    for (const std::vector<char>& rank_bytes : gather_bytes(bytes)) {
        std::vector<R>& records = all.emplace_back();
        const char* at = rank_bytes.data();
        const char* end = at + rank_bytes.size();
        while (at < end) unpack(records.emplace_back(), at, end);
    }
    return all;
}

// Each rank's figures for one frame, on rank 0 (one entry per rank there; empty elsewhere).
std::vector<RankFigures> gather_figures(const RankFigures& mine);

// Sums the frame's counters over ranks, field by field, on every rank.
void sum_over_ranks(FrameCounters& counters);

} // namespace glint
