#!/usr/bin/env bash
# fuzz/seeds.sh TARGET OUT_DIR [AFFRAY]: collects the seed corpus of a fuzz target from the
# repository into OUT_DIR (emptied first), as flat file names that keep the source path
# (tests/golden/arrays.sl -> tests_golden_arrays.sl). The seeds are the repository's own files,
# never copies kept in fuzz/ (except fuzz/corpus/fuzz_texture, tiny images made for it):
#   fuzz_sl       shaders/, tests/corpus/, tests/golden/ (and its shaders/, include/), tests/scenes/
#   fuzz_afb      those shaders compiled by AFFRAY (the affray program, required) with -o X.afb
#   fuzz_rib      scenes/, tests/golden/ (and its archives/), tests/scenes/
#   fuzz_texture  fuzz/corpus/fuzz_texture/, shaders/maps/, tests/scenes/
# fuzz/regressions/TARGET/ is not a seed directory here: the replay tests and tools/fuzz.sh read
# it directly. Every seed runs within a second in build-fuzz (the slowest, the largest corpus
# shaders and the first to load OpenImageIO, take 0.1-0.6 s), far from libFuzzer's -timeout.
set -euo pipefail

target=${1:?usage: fuzz/seeds.sh TARGET OUT_DIR [AFFRAY]}
out=${2:?usage: fuzz/seeds.sh TARGET OUT_DIR [AFFRAY]}
affray=${3:-}
root=$(cd "$(dirname "$0")/.." && pwd)

# Copies the files matching the globs (relative to the root) into $out.
collect() {
    local f rel
    shopt -s nullglob
    for f in "$@"; do
        rel=${f#"$root"/}
        cp "$f" "$out/${rel//\//_}"
    done
}

rm -rf "$out"
mkdir -p "$out"
case "$target" in
    fuzz_sl)
        collect "$root"/shaders/*.sl "$root"/shaders/*.h "$root"/tests/corpus/*.sl "$root"/tests/corpus/*.h \
                "$root"/tests/golden/*.sl "$root"/tests/golden/shaders/*.sl "$root"/tests/golden/include/*.h \
                "$root"/tests/scenes/*/*.sl ;;
    fuzz_afb)
        [[ -x "$affray" ]] || { echo "fuzz/seeds.sh: fuzz_afb needs the affray program as third argument" >&2; exit 2; }
        shopt -s nullglob
        for f in "$root"/shaders/*.sl "$root"/tests/corpus/*.sl; do
            rel=${f#"$root"/}
            name=${rel//\//_}
            "$affray" compile "$f" -o "$out/${name%.sl}.afb" -I "$root/tests/corpus" >/dev/null 2>&1 || true
        done ;;
    fuzz_rib)
        collect "$root"/scenes/*.rib "$root"/tests/golden/*.rib "$root"/tests/golden/archives/*.rib \
                "$root"/tests/golden/archives/*/*.rib "$root"/tests/scenes/*/*.rib ;;
    fuzz_texture)
        collect "$root"/fuzz/corpus/fuzz_texture/* "$root"/shaders/maps/* "$root"/tests/scenes/*/*.exr ;;
    *)
        echo "fuzz/seeds.sh: unknown target '$target' (fuzz_sl, fuzz_afb, fuzz_rib, fuzz_texture)" >&2
        exit 2 ;;
esac
echo "fuzz/seeds.sh: $(find "$out" -type f | wc -l) seeds for $target in $out"
