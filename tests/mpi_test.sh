#!/usr/bin/env bash
# glint across MPI ranks (docs/DISTRIBUTED.md), run by ctest where MPI was found:
#   mpi_test.sh GLINT MPIRUN identical NP   the output of `mpirun -np NP` is byte for byte the
#                                           single process's: every shipped and SPD scene in both
#                                           modes with adaptive 3x3, the (scene, mode) pairs dealt
#                                           out over NP 2, 3 and 4 in turn, every other pair as an
#                                           EXR with every AOV; and the shipped scenes with one
#                                           sample and uniform 2x2 too (each mpirun costs about
#                                           0.5 s of MPI start-up, hence one run a pair); NP 2
#                                           also checks that `mpirun -np 1` is one process
#   mpi_test.sh GLINT MPIRUN bad-input      bad input on the ranks: exit 2, one message, no file;
#                                           glint with no glint-mpi beside it refuses so too
#   mpi_test.sh GLINT MPIRUN tradeoff       a sweep spread over 2 ranks gives the single process's
#                                           CSV, timings (and the Pareto marks they decide) aside
#   mpi_test.sh GLINT MPIRUN killed-rank    a rank that dies mid-frame (SIGKILL at a given tile,
#                                           GLINT_TEST_RANK_KILL) ends the run with rank 0's
#                                           message, not a hang, non-zero, and leaves no output;
#                                           rank 0 dying leaves none either
#   mpi_test.sh GLINT MPIRUN slow-rank      a rank slowed down (GLINT_TEST_RANK_SLOW) takes fewer
#                                           tiles, and the image is the single process's
#   mpi_test.sh GLINT MPIRUN frames         a sequence's frames spread over 2 ranks (a skinned
#                                           model's too) are the single process's, file for file
#   mpi_test.sh GLINT MPIRUN cluster-sim    tools/cluster-sim refuses without root (exit 2), and
#                                           as root runs 2 ranks over a simulated 1 Gbit/s link
#                                           end to end, its table printed, nothing left behind
set -euo pipefail
glint=$(realpath "$1") mpirun=$2 what=$3
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# Open MPI refuses root unless told; CI runs as root. --oversubscribe: 3 ranks on 2 cores.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
# One machine: shared memory only (no TCP interfaces probed), a third of MPI's start-up here.
export OMPI_MCA_btl=self,vader OMPI_MCA_pml=ob1
work=$(mktemp -d "${TMPDIR:-/tmp}/glint-mpi.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

case "$what" in
identical)
  np=$4
  scenes=("$root"/scenes/*.json "$root"/scenes/spd/*.nff)
  modes=(hybrid ray)
  runs=0
  # The single process's output and NP ranks', compared byte for byte (an EXR's bytes are a
  # function of its floats: same floats, same file).
  same() { # EXTENSION ARGS...
    local ext=$1
    shift
    "$glint" render "$@" -o "$work/one.$ext" >/dev/null
    "$mpirun" -np "$np" --bind-to none "$glint" render "$@" -o "$work/many.$ext" >"$work/out.txt"
    cmp -s "$work/one.$ext" "$work/many.$ext" || fail "np $np: $*: the ${ext^^}s differ"
    grep -q "ranks: $np × 1 threads" "$work/out.txt" || fail "np $np: no per-rank report"
    [ "$(grep -c '^  rank ' "$work/out.txt")" -eq "$np" ] || fail "np $np: not one line per rank"
    runs=$((runs + 1))
  }
  pair=0
  for scene in "${scenes[@]}"; do
    for mode in "${modes[@]}"; do
      if [ $((pair % 3 + 2)) -eq "$np" ]; then # 160x64: 10 tiles
        args=("$scene" --size 160x64 --mode "$mode" --samples 3 --aa adaptive --threads 1)
        if [ $((pair / 3 % 2)) -eq 0 ]; then
          same png "${args[@]}"
        else
          same exr "${args[@]}" --aov depth,normal,id,cutoff
        fi
      fi
      pair=$((pair + 1))
    done
  done
  # One sample a pixel and uniform 2x2 on the shipped scenes, dealt out likewise.
  variants=("--samples 1" "--samples 2 --aa uniform")
  i=0
  for scene in "$root"/scenes/*.json; do
    if [ $((i % 3 + 2)) -eq "$np" ]; then
      same png "$scene" --size 160x64 --mode "${modes[$((i % 2))]}" ${variants[$((i % 2))]} --threads 1
    fi
    i=$((i + 1))
  done
  if [ "$np" -eq 2 ]; then # one rank: one process, no MPI at all
    "$glint" render "${scenes[0]}" --size 160x64 -o "$work/one.png" >/dev/null
    "$mpirun" -np 1 "$glint" render "${scenes[0]}" --size 160x64 -o "$work/many.png" >"$work/out.txt"
    cmp -s "$work/one.png" "$work/many.png" || fail "np 1: the images differ"
    ! grep -q "^ranks:" "$work/out.txt" || fail "np 1 reported ranks"
  fi
  echo "np $np: $runs outputs identical to the single process's"
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
  # glint becomes glint-mpi under mpirun (app/distributed.h); copied alone, it refuses.
  mkdir alone && cp "$glint" alone/glint
  set +e
  "$mpirun" -np 2 alone/glint render "$root/scenes/default.json" -o a.png >out.txt 2>err.txt
  code=$?
  set -e
  [ "$code" -eq 2 ] && [ "$(grep -c 'glint: error' err.txt)" -eq 1 ] &&
    grep -q "built without MPI: no .*/alone/glint-mpi beside it" err.txt && [ ! -e a.png ] ||
    fail "glint without glint-mpi under mpirun: exit $code: $(cat err.txt)"
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
  # Long enough not to end first: ray mode, 4x4 samples a pixel at 1280x960, one thread a rank
  # (a minute or so alone on 2 cores). The rank dies as it takes its third tile.
  long=("$root/scenes/default.json" --mode ray --size 1280x960 --samples 4 --aa uniform --threads 1)
  for victim in 1 0; do
    set +e
    GLINT_TEST_RANK_KILL=$victim:3 timeout 60 "$mpirun" -np 2 --bind-to none "$glint" render \
      "${long[@]}" -o killed.png >out.txt 2>err.txt
    code=$?
    set -e
    [ "$code" -ne 124 ] || fail "rank $victim killed: mpirun still running after 60 s"
    [ "$code" -ne 0 ] || fail "rank $victim killed: the run exited 0"
    if [ "$victim" -ne 0 ]; then
      grep -q "^glint: error: rank 0: mpirun is ending the run (a rank was lost" err.txt ||
        fail "rank $victim killed: no message from rank 0: $(cat err.txt)"
    fi
    [ -z "$(ls -A | grep -v '^out.txt$\|^err.txt$')" ] || fail "rank $victim killed: files left: $(ls -A)"
    echo "rank $victim killed at its third tile: exit $code, no output"
  done
  ;;
slow-rank)
  cd "$work"
  # Rank 1 sleeps 20 ms before each tile (a tile here takes a few): it should take far fewer
  # of the 35 tiles, and the image is the same.
  args=("$root/scenes/default.json" --size 224x160 --mode ray --samples 3 --aa adaptive --threads 1)
  "$glint" render "${args[@]}" -o one.png >/dev/null
  GLINT_TEST_RANK_SLOW=1:20 "$mpirun" -np 2 --bind-to none "$glint" render "${args[@]}" \
    -o many.png >out.txt
  cmp -s one.png many.png || fail "a slowed rank changed the image"
  tiles() { sed -n "s/^  rank $1: \([0-9]*\) tiles.*/\1/p" out.txt; }
  [ "$(tiles 1)" -lt "$(($(tiles 0) / 2))" ] ||
    fail "the slowed rank took $(tiles 1) tiles against rank 0's $(tiles 0)"
  echo "rank 1 slowed: $(tiles 1) tiles against rank 0's $(tiles 0), the same image"
  ;;
frames)
  args=("$root/scenes/default.json" --frames 5 --orbit --size 48x36 --threads 1)
  "$glint" render "${args[@]}" -o "$work/one-%d.png" >/dev/null
  "$mpirun" -np 2 --bind-to none "$glint" render "${args[@]}" -o "$work/many-%d.png" >"$work/out.txt"
  for k in 0 1 2 3 4; do
    cmp -s "$work/one-$k.png" "$work/many-$k.png" || fail "frame $k differs from the single process's"
  done
  grep -q "rank 1: frame 4/5" "$work/out.txt" || fail "frame 4 was not rank 1's"
  # A skinned model: each rank poses its frames' skins itself (DESIGN §14).
  skinned=("$root/models/khronos/RiggedSimple/glTF/RiggedSimple.gltf" --frames 4 --fps 4 --size 48x36 --threads 1)
  "$glint" render "${skinned[@]}" -o "$work/skin-one-%d.png" >/dev/null
  "$mpirun" -np 2 --bind-to none "$glint" render "${skinned[@]}" -o "$work/skin-many-%d.png" >/dev/null
  for k in 0 1 2 3; do
    cmp -s "$work/skin-one-$k.png" "$work/skin-many-$k.png" ||
      fail "skinned frame $k differs from the single process's"
  done
  cmp -s "$work/skin-one-0.png" "$work/skin-one-3.png" && fail "the skinned model did not move"
  echo "5 frames over 2 ranks, each the single process's; and 4 frames of a skinned model"
  ;;
cluster-sim)
  sim=("/usr/bin/python3" "$root/tools/cluster-sim")
  if command -v setpriv >/dev/null; then # as nobody: no namespaces to be had
    # A copy nobody can read, wherever the clone is (mktemp's folders are the owner's alone).
    open=$(mktemp -d /tmp/glint-cluster-sim.XXXXXX)
    mkdir "$open/tools" "$open/bench"
    cp "$root/tools/cluster-sim" "$open/tools/" && cp "$root/bench/scaling_model.py" "$open/bench/"
    chmod -R a+rX "$open"
    set +e
    (cd / && setpriv --reuid=65534 --regid=65534 --clear-groups /usr/bin/python3 \
      "$open/tools/cluster-sim" --ranks 2 --net 1g --glint "$glint" -- "$root/scenes/default.json") \
      >"$work/out.txt" 2>"$work/err.txt"
    code=$?
    set -e
    rm -rf "$open"
    [ "$code" -eq 2 ] && grep -q "needs root" "$work/err.txt" ||
      fail "without root: exit $code: $(cat "$work/err.txt")"
  fi
  if [ "$(id -u)" -ne 0 ] || ! command -v ip >/dev/null; then
    echo "not root, or no iproute2: the simulated cluster itself is not run"
    exit 0
  fi
  before=$(ip netns list | wc -l)
  set +e
  "${sim[@]}" --ranks 2 --net 1g --glint "$glint" --timeout 120 -- \
    "$root/scenes/default.json" --size 64x48 --mode ray >"$work/out.txt" 2>"$work/err.txt"
  code=$?
  set -e
  if [ "$code" -eq 2 ] && grep -q "cannot make a network namespace here" "$work/err.txt"; then
    cat "$work/err.txt"
    echo "no network namespaces on this machine: the simulated cluster itself is not run"
    exit 0
  fi
  [ "$code" -eq 0 ] || fail "cluster-sim: exit $code: $(cat "$work/out.txt" "$work/err.txt")"
  grep -q '^| 2 | 1 Gbit/s .*|.*s |.*MB.*|.*%.*|.*s (' "$work/out.txt" ||
    fail "no table row: $(cat "$work/out.txt")"
  [ "$(ip netns list | wc -l)" -eq "$before" ] || fail "namespaces left: $(ip netns list)"
  echo "cluster-sim: 2 ranks over a simulated link, the single process's image, nothing left"
  ;;
*) fail "unknown test $what" ;;
esac
