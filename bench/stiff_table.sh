#!/usr/bin/env bash
# bench/stiff_table.sh: regenerates the table of docs/stiff.md. Renders every scene of the stiff
# suite (tests/scenes/stiff/) with `affray render --stats` and the options on its `##stiff-args:` line,
# runs the scene's brute-force test case (tests/renderer/stiff_test.cpp), and prints one Markdown
# row per case. Use a Release build:
#
#   cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build -j2
#   bench/stiff_table.sh [BUILD_DIR] [--threads N]
#
# Wall times are those of this machine and thread count (default 2); the other figures do not
# depend on either.
set -euo pipefail
cd "$(dirname "$0")/.."

build=build
threads=2
while [ $# -gt 0 ]; do
    case "$1" in
        --threads) threads="$2"; shift 2 ;;
        *) build="$1"; shift ;;
    esac
done
affray="$build/tools/affray"
tests="$build/tests/affray_tests"
for program in "$affray" "$tests"; do
    [ -x "$program" ] || { echo "stiff_table.sh: $program not found; build first" >&2; exit 1; }
done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# scene|test case|what is stiff about it
cases=(
    "freq1000|stiff: frequency 1000 on a unit patch|wave.sl at frequency 1000: 1000 ripples per unit, slopes up to 380"
    "amp1000|stiff: amplitude 1000 on a unit patch|wave.sl with Km = 1000: heights of +-1000 over one unit, slopes up to 50000"
    "needles|stiff: needles with sigma 1e-4|16 needles exp(-r^2/sigma^2), sigma = 1e-4: about 1/200 of a pixel wide"
    "singular-sqrt|stiff: sqrt whose argument reaches 0 inside a region|sqrt(abs(s - c)) + sqrt(r): infinite slope on a line and at a point"
    "singular-log|stiff: log whose argument reaches 0 inside a region|log(r): -infinity at a point, unbounded regions there"
    "singular-div|stiff: division by a range containing 0|sin(x)/x: 0/0 at a point, division by a range containing 0"
    "far-offset|stiff: the patch placed 1e6 units from the origin|patch and camera 1e6 units from the origin"
    "far-distance|stiff: the patch seen from 1e6 units away|camera 1e6 units away, field of view 7e-5 degree"
    "grazing|stiff: grazing rays within 0.1 degree of the surface|every camera ray meets the plane at 0 to 0.1 degree"
    "tolerance|stiff: tolerance 1e-4 pixel|wave.sl rendered with --tolerance 1e-4"
    "sphere-poles|stiff: a displaced sphere seen at its poles|lumps of noise on a sphere seen at its north pole, where dPdu and dPdu x dPdv vanish"
)

field() {  # field NAME JSON
    sed -n "s/.*\"$1\":\([^,}]*\).*/\1/p" <<<"$2"
}

echo "| case | what is stiff | image | evaluations (regions) per ray, mean | evaluations per ray, max | depth-limit hits | largest certified error | brute-force misses | wall time |"
echo "|---|---|---|---|---|---|---|---|---|"
for entry in "${cases[@]}"; do
    IFS='|' read -r scene test what <<<"$entry"
    rib="tests/scenes/stiff/$scene.rib"
    args=$(sed -n 's/^##stiff-args: *//p' "$rib")
    # shellcheck disable=SC2086  # the options are words
    json=$("$affray" render "$rib" -o "$out/$scene.exr" --stats --threads "$threads" $args 2>/dev/null | tail -n 1)
    if "$tests" "$test" >"$out/$scene.log" 2>&1; then misses=0; else misses="FAIL ($test)"; fi
    printf '| `%s`%s | %s | %sx%s | %s | %s | %s | %s | %s | %s s |\n' "$scene" "${args:+ \`$args\`}" "$what" \
        "$(field width "$json")" "$(field height "$json")" "$(field regions_per_ray_mean "$json")" \
        "$(field regions_per_ray_max "$json")" "$(field depth_limit_hits "$json")" \
        "$(field max_certified_error "$json")" "$misses" "$(field wall_seconds "$json")"
done
