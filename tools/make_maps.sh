#!/usr/bin/env bash
# tools/make_maps.sh: makes the texture maps in shaders/maps/ that the texture shaders, the
# gallery scenes and the tests read, with oiiotool (Debian's openimageio-tools, which
# tools/setup.sh installs). The maps are in the repository; run this to make them again (the
# pixels are the same every time: fixed seeds).
#   tiles.exr  256x256, one half-float channel: 8x8 raised and sunken squares (a checker of 0 and
#              1 blurred over 17 texels), so heights in [0, 1] with soft edges and flat tops.
#   blobs.exr  128x128, one half-float channel: uniform noise on a 16x16 grid enlarged with a
#              Catmull-Rom filter: rolling blobs, values slightly outside [0, 1] (its overshoot).
# and in tests/scenes/stiff/ (the thin-feature case of the stiff suite):
#   ridge.exr  4096x4096, one half-float channel: 0 but for column 2048, which is 1 (a ridge one
#              texel wide, 1/4096 of the map).
set -euo pipefail
cd "$(dirname "$0")/.."
out=shaders/maps
mkdir -p "$out"
command -v oiiotool >/dev/null || { echo "make_maps.sh: oiiotool is missing (apt-get install openimageio-tools)" >&2; exit 2; }
# Both maps tile (their periodic wrap shows no seam): the checker is blurred on a larger canvas
# and cut at a multiple of its period; the noise is enlarged as a 3x3 mosaic of itself and cut
# from the middle.
oiiotool --pattern checker:width=32:height=32:color1=0:color2=1 320x320 1 --blur 17x17 --cut 256x256+32+32 \
    --chnames Y -d half --compression zip -o "$out/tiles.exr"
oiiotool --pattern noise:type=uniform:min=0:max=1:mono=1:seed=7 16x16 1 --dup --dup --dup --dup --dup --dup --dup \
    --dup --mosaic 3x3 --resize:filter=catmull-rom 384x384 --cut 128x128+128+128 \
    --chnames Y -d half --compression zip -o "$out/blobs.exr"
oiiotool --pattern constant:color=0 4096x4096 1 --box:color=1:fill=1 2048,0,2048,4095 \
    --chnames Y -d half --compression zip -o tests/scenes/stiff/ridge.exr
echo "make_maps.sh: wrote $out/tiles.exr, $out/blobs.exr and tests/scenes/stiff/ridge.exr"
