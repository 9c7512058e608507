// One frame across MPI ranks (docs/DISTRIBUTED.md): `mpirun -np N glint render …` (and a
// `glint tradeoff` sweep spread over ranks, one setting per rank at a time). Every rank
// loads the scene and builds its own structures; tiles are handed out as ranks ask for them
// (trace/tiles.h's TileExchange) and exchanged after each pass; rank 0 writes the PNG and
// prints the report. Without mpirun, or in a build without MPI, glint is one process as always:
// nothing here is called but the checks.
#pragma once

#include "trace/stopwatch.h"
#include "trace/tiles.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace glint {

// Called first thing in main(): when mpirun started this process with others, joins them (MPI
// initialised); a build without MPI refuses (exit 2, one message). Returns an exit code to stop
// with, or -1 to go on.
int start_ranks();
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
// rank makes it, and lets it go, together), with the seconds its exchanges took.
std::unique_ptr<TileExchange> make_exchange(int tiles);
double exchange_seconds(const TileExchange& exchange);

// What each rank did for one frame, gathered on rank 0 (one entry per rank there; empty
// elsewhere).
struct RankFigures {
    double load = 0, prepare = 0; // scene load and World (structures), seconds
    double gl = 0;                // GL context, shaders, upload, item buffer
    double trace = 0;             // primary hits and shading, exchanges excluded
    double exchange = 0;          // pixels exchanged after each pass
    double tiles = 0;             // tiles traced (first pass)
    double rays = 0;              // rays cast
};
std::vector<RankFigures> gather_figures(const RankFigures& mine);

// Every rank's numbers on rank 0 (one vector per rank there; empty elsewhere).
std::vector<std::vector<double>> gather_numbers(const std::vector<double>& mine);

// Sums over ranks, on every rank.
void sum_over_ranks(std::vector<std::uint64_t>& values);

} // namespace glint
