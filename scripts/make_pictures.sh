#!/usr/bin/env bash
# Remakes the pictures under docs/pictures/ (the README's gallery) from the bundled and shared
# datasets, with exactly the commands the README shows beside them (tests/docs/run_examples.py
# checks that each of the README's gallery commands is here, word for word). Builds nothing:
# build first (bash scripts/build.sh).
#   bash scripts/make_pictures.sh [BUILD_DIR]      (default: ./build)
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
build_arg=${1:-${BUILD_DIR:-build}}
if [ ! -x "$build_arg/app/isocurv" ]; then
  echo "make_pictures: no $build_arg/app/isocurv; build first (bash scripts/build.sh)" >&2
  exit 1
fi
if [ ! -d ../shared/datasets ]; then
  echo "make_pictures: the shared datasets are not at $(dirname "$repo")/shared/datasets" >&2
  exit 1
fi
build=$(cd "$build_arg" && pwd)
# The commands run as the README shows them, from a folder that looks like the checkout's root
# (build/ and ../shared/ beside it), so their outputs do not land in the checkout.
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
mkdir "$scratch/checkout"
ln -s "$build" "$scratch/checkout/build"
ln -s "$(cd ../shared && pwd)" "$scratch/shared"
export PATH="$build/app:$PATH"

pictures=(lobster_H_volume.png dragon_lines.svg octaflower_si.png screen_gyroid_K.png)
commands=(
  'isocurv render ../shared/datasets/lobster/lobster.vol --spacing 1 1 1.4 --iso 40 --estimator volume --color H --range -0.25 0.25 --view +z --azimuth 15 --elevation -25 -o lobster_H_volume.png'
  'isocurv lines ../shared/datasets/aa_dragon/dragon-256-aa-l0_1.vol --view +z -o dragon_lines.svg'
  'isocurv features ../shared/datasets/aa_octaflower/octa-flower17k-128-aa-l0_1.vol --radius 3% -o octaflower_features.vtp'
  'isocurv render octaflower_features.vtp --color SI_ii --title "Octa-flower | shape index from integral invariants, r = 3%" -o octaflower_si.png'
  'isocurv screen build/datasets/gyroid.vdb --color K --zoom 1.5 -o screen_gyroid_K.png'
)
cd "$scratch/checkout"
for c in "${commands[@]}"; do
  echo "+ $c"
  bash -c "$c"
done
mkdir -p "$repo/docs/pictures"
for p in "${pictures[@]}"; do
  cp "$p" "$repo/docs/pictures/$p"
  echo "wrote docs/pictures/$p"
done
