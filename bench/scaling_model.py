#!/usr/bin/env python3
"""The scaling model of docs/DISTRIBUTED.md, written once: the wall time of `mpirun -np N glint
render` predicted from one process's run (its --stats JSON), the ranks, the cores they share, and
the network's latency and bandwidth. tools/cluster-sim holds it against its runs.

    python3 bench/scaling_model.py ONE_PROCESS_STATS.json --ranks N --cores C
        --bandwidth 1e9 --latency 0.0002 [--start 0.5] [--aovs]

T(N) = S + L + max(F, B / bw) + X + C + w, with
  S  MPI's start and end (launching the ranks, MPI_Init, MPI_Finalize): measured, or --start
  L  scene load and structures, on every rank at once: one process's
  F  the frame's tracing: one process's frame time, when the ranks have the cores it had
     (N ranks on C cores trace what one process with C threads does; ranks beyond C share them)
  B  the bytes rank 0 receives, all passes: they travel while the ranks trace (each tile is
     sent as it is done), through rank 0's one link of bandwidth bw, so the frame takes at
     least B / bw
  X  what the exchanges add after each pass: the last tile's message (its bytes over bw), and
     two latencies (the tile counts, then the message); per adaptive decision after the first
     pass, the mask handed out (a latency, and its bytes to each other rank over bw)
  C  the claims: a rank other than 0 waits a round trip, and rank 0's poll (0.2 ms at most,
     0.1 on average), for each tile it takes; every loop hands out every tile, a share
     (N - 1)/N of them to other ranks, each wait costing its rank's core that time (hidden
     where two ranks share a core: the other traces meanwhile)
  w  rank 0's write: one process's
Bytes, per pass: every pixel's record (PixelFacts 20 bytes; the clamped mean 12 with N x N
samples; the AOVs 20; the path key 8 in adaptive antialiasing's first pass) for the first pass,
16 + 12 for each refined pixel in a refining pass, and 4 a tile (app/rank_records.h); a share
(N - 1)/N of it comes from other ranks.
"""
import argparse
import json
import math

TILE = 32
POLL_MEAN = 0.0001  # rank 0's poller: every 0.2 ms (app/distributed.cpp)


def bytes_per_pass(stats, ranks, aovs=False):
    """The bytes rank 0 receives after each pass, as a list (from one process's --stats)."""
    w, h = stats["width"], stats["height"]
    pixels = w * h
    tiles = math.ceil(w / TILE) * math.ceil(h / TILE)
    samples = stats["samples"]
    adaptive = samples > 1 and stats["antialias"] == "adaptive"
    clamped = 12 if samples > 1 else 0
    full = 20 + clamped + (20 if aovs else 0) + (8 if adaptive else 0)
    share = (ranks - 1) / ranks
    passes = stats.get("passes", 1)
    out = [share * (full * pixels + 4 * tiles)]
    if adaptive and passes > 1:
        refined = stats.get("refined_pixels", 0)
        # Each pixel is refined once, in the grids pass or one spreading round.
        later = share * ((16 + clamped) * refined + 4 * tiles * (passes - 1))
        out += [later / (passes - 1)] * (passes - 1)
    return out


def predict(stats, ranks, cores, bandwidth, latency, start, aovs=False):
    """Predicted seconds of each term and their sum, as a dict; `bandwidth` in bytes a second,
    `latency` one way in seconds."""
    s = stats["seconds"]
    w, h = stats["width"], stats["height"]
    tiles = math.ceil(w / TILE) * math.ceil(h / TILE)
    passes = stats.get("passes", 1)
    load = s["load"] + s["prepare"]
    # One process traced with stats["threads"] threads; the ranks have `cores` cores in all.
    frame = s["frame"] * stats["threads"] / min(cores, ranks) if ranks > 1 else s["frame"]
    per_pass = bytes_per_pass(stats, ranks, aovs)
    streamed = max(frame, sum(per_pass) / bandwidth)
    samples = stats["samples"]
    tile_message = TILE * TILE * (20 + (12 if samples > 1 else 0) + (20 if aovs else 0)
                                  + (8 if samples > 1 and stats["antialias"] == "adaptive" else 0))
    exchange = passes * (tile_message / bandwidth + 2 * latency)
    if passes > 1:  # the masks: a few bytes a run of refined pixels, to each other rank
        runs = stats.get("refined_pixels", 0) / 4
        exchange += (passes - 1) * latency + 8 * runs * (ranks - 1) / bandwidth
    shared = ranks > cores  # a rank waiting for a claim leaves its core to another
    claims = 0.0 if shared else (tiles * passes * (ranks - 1) / ranks * (2 * latency + POLL_MEAN)
                                 / min(cores, ranks))
    terms = {"start": start, "load": load, "frame": streamed, "exchange": exchange,
             "claims": claims, "write": s["write"]}
    terms["total"] = sum(terms.values())
    terms["bytes"] = sum(per_pass)
    return terms


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("stats", help="one process's --stats JSON")
    p.add_argument("--ranks", type=int, required=True)
    p.add_argument("--cores", type=int, required=True, help="cores the ranks have in all")
    p.add_argument("--bandwidth", type=float, required=True, help="bytes a second")
    p.add_argument("--latency", type=float, required=True, help="one way, seconds")
    p.add_argument("--start", type=float, default=0.5, help="MPI's start and end, seconds")
    p.add_argument("--aovs", action="store_true", help="the render keeps the AOVs")
    a = p.parse_args()
    with open(a.stats) as f:
        stats = json.load(f)
    terms = predict(stats, a.ranks, a.cores, a.bandwidth, a.latency, a.start, a.aovs)
    for name, value in terms.items():
        unit = "bytes" if name == "bytes" else "s"
        print(f"{name:>8}: {value:.4g} {unit}")


if __name__ == "__main__":
    main()
