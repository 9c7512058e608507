#!/usr/bin/env bash
# One Khronos sample model (models/khronos/NAME, docs/MODELS.md) through glint: rendered small in
# ray and hybrid mode, with the built-in studio environment, must exit 0 and give the same bytes
# in both (hybrid = ray, with one-sided faces culled and the environment behind the model).
#
#   tests/khronos_model.sh GLINT MODEL.gltf
set -euo pipefail
glint=$1 model=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for mode in ray hybrid; do
  "$glint" render "$model" --size 96x72 --environment studio --mode "$mode" -o "$out/$mode.png" \
    >"$out/$mode.log" 2>&1 || { cat "$out/$mode.log"; echo "$mode mode failed on $model"; exit 1; }
done
cmp "$out/ray.png" "$out/hybrid.png" ||
  { echo "hybrid mode's bytes differ from ray mode's"; exit 1; }
echo "$model: both modes, the same bytes"
