#!/usr/bin/env bash
# glint across MPI ranks (docs/DISTRIBUTED.md), run by ctest where MPI was found:
#   mpi_test.sh GLINT MPIRUN identical NP   the image of `mpirun -np NP` is byte for byte the
#                                           single process's (and on three scenes its EXR with
#                                           every AOV): shipped and SPD scenes, each in one
#                                           mode and with one of: one sample, adaptive 3x3,
#                                           uniform 2x2, in turn, shifted by NP, so that NP 2 and
#                                           3 together render each scene in both modes (each
#                                           mpirun costs seconds where starting MPI is slow)
#   mpi_test.sh GLINT MPIRUN bad-input      bad input on the ranks: exit 2, one message, no file
#   mpi_test.sh GLINT MPIRUN tradeoff       a sweep spread over 2 ranks gives the single process's
#                                           CSV, timings (and the Pareto marks they decide) aside
#   mpi_test.sh GLINT MPIRUN killed-rank    a rank killed mid-render ends the run with an error,
#                                           not a hang, and leaves no output
#   mpi_test.sh GLINT MPIRUN frames         a sequence's frames spread over 2 ranks are the single
#                                           process's, file for file
set -euo pipefail
glint=$(realpath "$1") mpirun=$2 what=$3
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# Open MPI refuses root unless told; CI runs as root. --oversubscribe: 3 ranks on 2 cores.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
work=$(mktemp -d "${TMPDIR:-/tmp}/glint-mpi.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

case "$what" in
identical)
  np=$4
  scenes=("$root"/scenes/*.json "$root"/tests/data/spd/{balls-1,gears-1,tree-3}.nff)
  variants=("--samples 1" "--samples 3 --aa adaptive" "--samples 2 --aa uniform")
  modes=(hybrid ray)
  runs=0
  for i in "${!scenes[@]}"; do
    scene=${scenes[$i]}
    for mode in "${modes[$(((i + np) % 2))]}"; do
      for samples in "${variants[$(((i + np) % 3))]}"; do
        args=("$scene" --size 160x64 --mode "$mode" $samples --threads 1) # 10 tiles
        "$glint" render "${args[@]}" -o "$work/one.png" >/dev/null
        "$mpirun" -np "$np" --bind-to none "$glint" render "${args[@]}" -o "$work/many.png" >"$work/out.txt"
        cmp -s "$work/one.png" "$work/many.png" || fail "np $np: ${args[*]}: the images differ"
        grep -q "ranks: $np × 1 threads" "$work/out.txt" || fail "np $np: no per-rank report"
        [ "$(grep -c '^  rank ' "$work/out.txt")" -eq "$np" ] || fail "np $np: not one line per rank"
        runs=$((runs + 1))
        # The float image and every AOV too, on the first scenes (an EXR's bytes are a function
        # of its floats: same floats, same file).
        if [ "$i" -lt 3 ]; then
          aovs=(--aov depth,normal,id,cutoff)
          "$glint" render "${args[@]}" "${aovs[@]}" -o "$work/one.exr" >/dev/null
          "$mpirun" -np "$np" --bind-to none "$glint" render "${args[@]}" "${aovs[@]}" \
            -o "$work/many.exr" >/dev/null
          cmp -s "$work/one.exr" "$work/many.exr" || fail "np $np: ${args[*]}: the EXRs differ"
          runs=$((runs + 1))
        fi
      done
    done
  done
  echo "np $np: $runs renders identical to the single process's"
  ;;
bad-input)
  cd "$work"
  echo '{"objects": [{"shape": "sphere", "material": "gold"}]}' >bad.json
  for args in "bad.json -o a.png" "--size 0x5 -o a.png" "$root/scenes/default.json -o no/dir/a.png"; do
    set +e
    "$mpirun" -np 2 "$glint" render $args >out.txt 2>err.txt
    code=$?
    set -e
    [ "$code" -eq 2 ] || fail "'$args': exit $code, not 2: $(cat err.txt)"
    [ "$(grep -c 'glint: error' err.txt)" -eq 1 ] || fail "'$args': not one message: $(cat err.txt)"
    [ ! -e a.png ] && [ -z "$(ls -A no 2>/dev/null)" ] || fail "'$args': wrote a file"
  done
  set +e
  "$mpirun" -np 2 "$glint" compare "$root/scenes/default.json" >out.txt 2>err.txt
  code=$?
  set -e
  [ "$code" -eq 2 ] && grep -q "only \`glint render\` and \`glint tradeoff\` run across MPI ranks" err.txt ||
    fail "compare on ranks: exit $code: $(cat err.txt)"
  echo "bad input on ranks: exit 2, one message, nothing written"
  ;;
tradeoff)
  cd "$work"
  args=("$root/scenes/default.json" --size 64x48 --repeat 1 --samples 2 --threads 1)
  "$glint" tradeoff "${args[@]}" -o one >/dev/null
  "$mpirun" -np 2 --bind-to none "$glint" tradeoff "${args[@]}" -o many >out.txt
  grep -q "over 2 ranks" out.txt || fail "the sweep did not say it was spread"
  python3 - one/tradeoff.csv many/tradeoff.csv <<'PY' || fail "the CSVs differ"
import csv, sys
def rows(path):
    return [{k: v for k, v in r.items() if not k.startswith("seconds") and k != "pareto"}
            for r in csv.DictReader(open(path))]
one, many = rows(sys.argv[1]), rows(sys.argv[2])
sys.exit(0 if one == many and len(one) > 20 else 1)
PY
  for file in default.svg default.png default-antialiasing.svg summary.md; do
    [ -s "many/$file" ] || fail "no $file"
  done
  echo "tradeoff over 2 ranks: the single process's CSV, $(($(wc -l <one/tradeoff.csv) - 1)) settings"
  ;;
killed-rank)
  cd "$work"
  # Long enough to be killed mid-render: ray mode, 4x4 samples a pixel at 1280x960, one thread a
  # rank (a minute or so alone on 2 cores).
  "$mpirun" -np 2 --bind-to none "$glint" render "$root/scenes/default.json" --mode ray \
    --size 1280x960 --samples 4 --aa uniform --threads 1 -o killed.png >out.txt 2>err.txt &
  launcher=$!
  victim=
  for _ in $(seq 100); do # find rank 1 among the launcher's descendants, up to 10 s
    for pid in $(pgrep -f "render $root/scenes/default.json --mode ray --size 1280x960" || true); do
      if tr '\0' '\n' <"/proc/$pid/environ" 2>/dev/null | grep -qx 'OMPI_COMM_WORLD_RANK=1'; then
        victim=$pid
      fi
    done
    [ -n "$victim" ] && break
    sleep 0.1
  done
  [ -n "$victim" ] || { kill "$launcher"; fail "rank 1 never started"; }
  sleep 2 # both ranks are rendering now
  kill -9 "$victim"
  started=$SECONDS
  set +e
  for _ in $(seq 600); do kill -0 "$launcher" 2>/dev/null || break; sleep 0.1; done
  if kill -0 "$launcher" 2>/dev/null; then kill -9 "$launcher"; fail "mpirun still running 60 s after rank 1 died"; fi
  wait "$launcher"
  code=$?
  set -e
  [ "$code" -ne 0 ] || fail "the run exited 0 after losing a rank"
  [ ! -e killed.png ] || fail "an image was written"
  [ -z "$(ls -A | grep -v '^out.txt$\|^err.txt$')" ] || fail "files left: $(ls -A)"
  echo "rank 1 killed: mpirun exited $code after $((SECONDS - started)) s, no image"
  ;;
frames)
  args=("$root/scenes/default.json" --frames 5 --orbit --size 48x36 --threads 1)
  "$glint" render "${args[@]}" -o "$work/one-%d.png" >/dev/null
  "$mpirun" -np 2 --bind-to none "$glint" render "${args[@]}" -o "$work/many-%d.png" >"$work/out.txt"
  for k in 0 1 2 3 4; do
    cmp -s "$work/one-$k.png" "$work/many-$k.png" || fail "frame $k differs from the single process's"
  done
  grep -q "rank 1: frame 4/5" "$work/out.txt" || fail "frame 4 was not rank 1's"
  echo "5 frames over 2 ranks, each the single process's"
  ;;
*) fail "unknown test $what" ;;
esac
