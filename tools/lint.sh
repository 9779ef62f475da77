#!/usr/bin/env bash
# tools/lint.sh [BUILD_DIR]: runs clang-tidy-14 with the checks in .clang-tidy over every C++
# source of the repository that git knows (so the Flex and Bison outputs in the build directory
# are never linted), two files at a time, with the compile commands of BUILD_DIR (build-lint by
# default; configured with CMAKE_EXPORT_COMPILE_COMMANDS=ON, and its generated parser header
# built, if it has none yet). Exit 0 with no finding; exit 1 printing the findings, each once
# (file:line:col: message [check]); exit 2 if clang-tidy-14 is not installed. A full run costs
# about 46 CPU-minutes, most of it the static analyser on the Catch2 tests (over 20 minutes on two
# idle cores, 78 on a loaded one), too long for CI's budget, so CI does not run it: run it before
# sending a change, or lint one file with
# `clang-tidy-14 -p build-lint --extra-arg=-Wno-unknown-warning-option FILE`.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
tidy=clang-tidy-14
command -v "$tidy" >/dev/null || { echo "lint.sh: $tidy is not installed (apt-get install clang-tidy-14)" >&2; exit 2; }
build=${1:-build-lint}
jobs=2

# The compile commands, and lang/parser.hh, which the lang sources include.
if [[ ! -f $build/compile_commands.json ]]; then
    cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON >/dev/null
fi
if [[ ! -f $build/lang/parser.hh ]]; then
    cmake --build "$build" --target affray_lang -j"$jobs" >/dev/null
fi

# Every source git knows that the build compiles; a source missing from the compile commands
# (a new file before the build is reconfigured, a benchmark with AFFRAY_BENCH=OFF) is named. The
# layering check's test tree (tests/tools/check_layers/) is never compiled, so never linted.
mapfile -t listed < <(git ls-files '*.cpp' ':!:tests/tools/check_layers/')
mapfile -t files < <(python3 - "$build/compile_commands.json" "$root" "${listed[@]}" <<'EOF'
import json, os, sys
db, root, files = sys.argv[1], sys.argv[2], sys.argv[3:]
compiled = {os.path.realpath(os.path.join(e["directory"], e["file"])) for e in json.load(open(db))}
for f in files:
    if os.path.realpath(os.path.join(root, f)) in compiled: print(f)
    else: print(f"lint.sh: {f} is not in {db}, not linted (reconfigure the build)", file=sys.stderr)
EOF
)

# clang-tidy reads the compiler's flags, GCC's included: a warning option clang does not know
# is not a finding. Each file's report goes to a file of its own, merged afterwards; a run that
# fails without a finding (clang-tidy crashed) keeps its whole output.
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
lint_one() {
    local log=$out/${1//\//_}.log
    "$tidy" -p "$build" --quiet --extra-arg=-Wno-unknown-warning-option "$1" >"$log" 2>&1 && return
    grep -qE ': (warning|error): ' "$log" || { echo "lint.sh: $tidy failed on $1:"; cat "$log"; } >"$log.failed"
}
export -f lint_one
export tidy build out
printf '%s\n' "${files[@]}" | xargs -P "$jobs" -I{} bash -c 'lint_one "$1"' _ {}
if compgen -G "$out/*.failed" >/dev/null; then cat "$out"/*.failed >&2; exit 1; fi

# A header's finding is reported by every source that includes it: print each one once.
findings=$(cat "$out"/*.log /dev/null | grep -E '^/.*:[0-9]+:[0-9]+: (warning|error): ' | sed "s|^$root/||" | sort -u -t: -k1,1 -k2,2n -k3,3n -k4 || true)
if [[ -n $findings ]]; then
    echo "$findings"
    echo "lint.sh: $(echo "$findings" | wc -l) finding(s) in ${#files[@]} files" >&2
    exit 1
fi
echo "lint.sh: ${#files[@]} files, no findings"
