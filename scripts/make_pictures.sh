#!/usr/bin/env bash
# Remakes the pictures under docs/pictures/ (the README's gallery) from the bundled and shared
# datasets, with exactly the commands the README shows beside them (tests/docs/run_examples.py
# checks that each of the README's gallery commands is here, word for word). Builds nothing:
# build first (bash scripts/build.sh).
#   bash scripts/make_pictures.sh [--check] [--only NAME[,NAME...]] [--tolerance L:P] [BUILD_DIR]
#     (default BUILD_DIR: ./build)
#   --check      make the pictures in a scratch folder and compare each with docs/pictures/,
#                writing nothing there: a PNG is current when its size is the same and at most
#                P% of its pixels differ by more than L levels in a channel (--tolerance, default
#                32:0.5); an SVG when its text is the same but for numbers within 0.5 of each
#                other. Lists the stale pictures; exit status 1 when any is stale (or a command
#                fails), 0 when all are current. Comparing pixels needs /usr/bin/python3 with
#                numpy; without it the files are compared byte for byte.
#   --only       only these pictures (names as in docs/pictures/), and the commands that make them
# Exit status 2 on a usage error.
set -euo pipefail
# docs/pictures/ of the checkout this script is in, also when it is run through a link to its
# folder (the examples test runs it from a scratch folder whose scripts/ and build/ are links).
pictures_dir=$(cd -P "$(dirname "$0")" && cd .. && pwd)/docs/pictures
cd "$(dirname "$0")/.."
repo=$PWD

usage() {  # the comment above, on stderr with status 2 (a usage error), or on stdout for --help
  if [ "${1:-2}" = 0 ]; then sed -n '6,16p' "$0" | cut -c3-; exit 0; fi
  sed -n '6,16p' "$0" | cut -c3- >&2; exit 2
}
check=0 only="" tolerance="32:0.5" build_arg=""
while [ $# -gt 0 ]; do
  case "$1" in
    --check) check=1 ;;
    --only) [ $# -ge 2 ] || usage; only=$2; shift ;;
    --only=*) only=${1#--only=} ;;
    --tolerance) [ $# -ge 2 ] || usage; tolerance=$2; shift ;;
    --tolerance=*) tolerance=${1#--tolerance=} ;;
    -h|--help) usage 0 ;;
    -*) echo "make_pictures: unknown option $1" >&2; usage ;;
    *) [ -z "$build_arg" ] || usage; build_arg=$1 ;;
  esac
  shift
done
if ! [[ $tolerance =~ ^[0-9]+:[0-9]*\.?[0-9]+$ ]]; then
  echo "make_pictures: --tolerance takes LEVELS:PERCENT, e.g. 32:0.5, not '$tolerance'" >&2
  exit 2
fi
build_arg=${build_arg:-${BUILD_DIR:-build}}
if [ ! -x "$build_arg/app/isocurv" ]; then
  echo "make_pictures: no $build_arg/app/isocurv; build first (bash scripts/build.sh)" >&2
  exit 1
fi
build=$(cd "$build_arg" && pwd)
# The commands run as the README shows them, from a folder that looks like the checkout's root
# (build/ and ../shared/ beside it), so their outputs do not land in the checkout.
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
mkdir "$scratch/checkout"
ln -s "$build" "$scratch/checkout/build"
if [ -d ../shared ]; then ln -s "$(cd ../shared && pwd)" "$scratch/shared"; fi
export PATH="$build/app:$PATH"

pictures=(lobster_H_volume.png dragon_lines.svg octaflower_si.png screen_gyroid_K.png)
commands=(
  'isocurv render ../shared/datasets/lobster/lobster.vol --spacing 1 1 1.4 --iso 40 --estimator volume --color H --range -0.25 0.25 --view +z --azimuth 15 --elevation -25 -o lobster_H_volume.png'
  'isocurv lines ../shared/datasets/aa_dragon/dragon-256-aa-l0_1.vol --view +z -o dragon_lines.svg'
  'isocurv features ../shared/datasets/aa_octaflower/octa-flower17k-128-aa-l0_1.vol --radius 3% -o octaflower_features.vtp'
  'isocurv render octaflower_features.vtp --color SI_ii --title "Octa-flower | shape index from integral invariants, r = 3%" -o octaflower_si.png'
  'isocurv screen build/datasets/gyroid.vdb --color K --zoom 1.5 -o screen_gyroid_K.png'
)
# The commands (indices into commands) that make each picture, in order.
declare -A makes=(
  [lobster_H_volume.png]="0"
  [dragon_lines.svg]="1"
  [octaflower_si.png]="2 3"
  [screen_gyroid_K.png]="4"
)

chosen=("${pictures[@]}")
if [ -n "$only" ]; then
  IFS=, read -r -a chosen <<< "$only"
  for p in "${chosen[@]}"; do
    if [ -z "${makes[$p]+x}" ]; then
      echo "make_pictures: no picture '$p'; the pictures are: ${pictures[*]}" >&2
      exit 2
    fi
  done
fi

for p in "${chosen[@]}"; do
  for i in ${makes[$p]}; do
    if [[ ${commands[$i]} == *../shared/datasets* ]] && [ ! -d ../shared/datasets ]; then
      echo "make_pictures: $p needs the shared datasets, which are not at $(dirname "$repo")/shared/datasets" >&2
      exit 1
    fi
  done
done

cd "$scratch/checkout"
for p in "${chosen[@]}"; do
  for i in ${makes[$p]}; do
    c=${commands[$i]}
    echo "+ $c"
    bash -c "$c" || {
      echo "make_pictures: this command failed (status $?), making $p: $c" >&2
      exit 1
    }
  done
done

if [ "$check" = 0 ]; then
  mkdir -p "$pictures_dir"
  for p in "${chosen[@]}"; do
    cp "$p" "$pictures_dir/$p"
    echo "wrote docs/pictures/$p"
  done
  exit 0
fi

# --check: compare each new picture with docs/pictures/.
stale=0
if /usr/bin/python3 -c 'import numpy' 2>/dev/null; then
  for p in "${chosen[@]}"; do
    if ! /usr/bin/python3 - "$p" "$pictures_dir/$p" "$tolerance" <<'EOF'; then stale=1; fi
import os, re, struct, sys, zlib
import numpy as np

new, old, tolerance = sys.argv[1], sys.argv[2], sys.argv[3]
levels, percent = int(tolerance.split(":")[0]), float(tolerance.split(":")[1])
name = os.path.basename(new)


def read_png(path):
    """The pixels of an 8-bit, non-interlaced PNG as an (h, w, channels) uint8 array."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG file")
    pos, ihdr, idat = 8, None, []
    while pos + 8 <= len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
    w, h, depth, ctype, _, _, interlace = ihdr
    if depth != 8 or interlace != 0 or ctype not in (0, 2, 4, 6):
        raise ValueError(f"a PNG this check does not read (bit depth {depth}, colour type {ctype})")
    bpp = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
    raw, stride = zlib.decompress(b"".join(idat)), w * bpp
    out, prev = np.zeros((h, stride), np.uint8), np.zeros(stride, np.int64)
    for y in range(h):
        start = y * (stride + 1)
        kind = raw[start]
        line = np.frombuffer(raw, np.uint8, stride, start + 1).astype(np.int64)
        if kind == 0:
            cur = line
        elif kind == 1:  # Sub: a running sum along each channel
            cur = line.reshape(w, bpp).cumsum(axis=0).reshape(-1) % 256
        elif kind == 2:  # Up
            cur = (line + prev) % 256
        else:  # Average, Paeth: byte by byte
            f, up, r = line.tolist(), prev.tolist(), [0] * stride
            for x in range(stride):
                a = r[x - bpp] if x >= bpp else 0
                b = up[x]
                if kind == 3:
                    r[x] = (f[x] + (a + b) // 2) & 255
                else:
                    c = up[x - bpp] if x >= bpp else 0
                    pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                    pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                    r[x] = (f[x] + pred) & 255
            cur = np.array(r, np.int64)
        out[y], prev = cur, cur
    return out.reshape(h, w, bpp)


def numbers_and_text(path):
    parts = re.split(r"(-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?)", open(path, encoding="utf-8").read())
    return parts[0::2], np.array([float(x) for x in parts[1::2]])


if not os.path.exists(old):
    print(f"STALE    {name}: not in docs/pictures/")
    sys.exit(1)
if name.endswith(".png"):
    a, b = read_png(new), read_png(old)
    if a.shape != b.shape:
        print(f"STALE    {name}: {a.shape[1]}x{a.shape[0]}, docs/pictures/ has {b.shape[1]}x{b.shape[0]}")
        sys.exit(1)
    differ = 100.0 * (np.abs(a.astype(np.int16) - b.astype(np.int16)).max(axis=2) > levels).mean()
    state = "STALE   " if differ > percent else "current "
    print(f"{state} {name}: {differ:.2f}% of the pixels differ by more than {levels} levels "
          f"(at most {percent:g}% allowed)")
    sys.exit(1 if differ > percent else 0)
text_a, num_a = numbers_and_text(new)
text_b, num_b = numbers_and_text(old)
if text_a != text_b or num_a.shape != num_b.shape:
    print(f"STALE    {name}: a different drawing ({len(num_a)} numbers against {len(num_b)} in docs/pictures/)")
    sys.exit(1)
worst = float(np.abs(num_a - num_b).max()) if len(num_a) else 0.0
state = "STALE   " if worst > 0.5 else "current "
print(f"{state} {name}: the same drawing, coordinates within {worst:.3g} (at most 0.5 allowed)")
sys.exit(1 if worst > 0.5 else 0)
EOF
  done
else
  echo "make_pictures: no /usr/bin/python3 with numpy: comparing the files byte for byte" >&2
  for p in "${chosen[@]}"; do
    if cmp -s "$p" "$pictures_dir/$p"; then
      echo "current  $p: the same bytes"
    else
      echo "STALE    $p: not the same bytes"
      stale=1
    fi
  done
fi
if [ "$stale" = 1 ]; then
  echo "make_pictures: some pictures in docs/pictures/ are stale; remake them with bash scripts/make_pictures.sh" >&2
  exit 1
fi
echo "make_pictures: the pictures checked are current"
