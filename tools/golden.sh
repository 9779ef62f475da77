#!/usr/bin/env bash
# tools/golden.sh: runs the golden cases of tests/golden/ (see tests/golden/README.md) with
# BUILD_DIR/tools/affray and prints a unified diff for each case whose output is not its
# NAME.expected; exits 1 if any differs. With --update, rewrites every .expected from the current
# output instead (review the changes with git diff). CASE names (NAME.sl, NAME.rib or NAME) limit
# the run to those cases. The text is built exactly as tests/golden/golden_test.cpp builds it.
#
#   tools/golden.sh [--update] [BUILD_DIR] [CASE...]     (BUILD_DIR defaults to build/)
set -euo pipefail

update=0
if [[ ${1:-} == --update ]]; then
    update=1
    shift
fi
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
build=${1:-$root/build}
[[ $# -gt 0 ]] && shift
affray=$build/tools/affray
[[ -x $affray ]] || { echo "golden.sh: no $affray: build first (cmake --build $build)" >&2; exit 2; }
affray=$(cd "$build" && pwd -P)/tools/affray
dir=$(cd "$root/tests/golden" && pwd -P)
min_cases=60  # as kMinCases in golden_test.cpp

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Prints what affray prints for case $1 (a file name in $dir): "$ affray ARGS", stdout,
# "--- stderr" and stderr if any, "--- exit N"; $tmp shows as $TMP and $dir/ is cut from paths.
actual() {
    local file=$1 first words args rc=0 text
    IFS= read -r first <"$dir/$file" || true
    first=${first%$'\r'}
    if [[ $first != *golden:* ]]; then
        echo "$file: the first line has no \"golden: SUBCOMMAND ARGS...\" header" >&2
        return 1
    fi
    read -ra words <<<"${first#*golden:}"
    if [[ ${#words[@]} -eq 0 ]]; then
        echo "$file: the first line has no \"golden: SUBCOMMAND ARGS...\" header" >&2
        return 1
    fi
    args=("${words[0]}" "$file" "${words[@]:1}")
    # A render writes its image in the temporary directory, unless the case names one.
    if [[ ${words[0]} == render && " ${words[*]} " != *" -o "* ]]; then
        args+=(-o "$tmp/${file%.*}.exr")
    fi
    (cd "$dir" && exec timeout 120 "$affray" "${args[@]}") >"$tmp/stdout" 2>"$tmp/stderr" || rc=$?
    text=$(
        printf '$ affray %s\n' "${args[*]}"
        cat "$tmp/stdout"
        if [[ -s $tmp/stderr ]]; then
            echo "--- stderr"
            cat "$tmp/stderr"
        fi
        echo "--- exit $rc"
    )
    # shellcheck disable=SC2016  # a literal $TMP
    text=${text//"$tmp"/'$TMP'}
    text=${text//"$dir/"/}
    printf '%s\n' "$text"
}

cases=()
if [[ $# -gt 0 ]]; then
    for name in "$@"; do
        if [[ -f $dir/$name ]]; then cases+=("$name")
        elif [[ -f $dir/$name.sl ]]; then cases+=("$name.sl")
        elif [[ -f $dir/$name.rib ]]; then cases+=("$name.rib")
        else echo "golden.sh: no case '$name' in tests/golden" >&2; exit 2
        fi
    done
else
    while IFS= read -r path; do cases+=("${path##*/}"); done < <(find "$dir" -maxdepth 1 -type f \( -name '*.sl' -o -name '*.rib' \) | LC_ALL=C sort)
fi

failed=0
for file in "${cases[@]}"; do
    expected=$dir/${file%.*}.expected
    if ! actual "$file" >"$tmp/actual"; then
        failed=$((failed + 1))
        continue
    fi
    if [[ $update -eq 1 ]]; then
        cp "$tmp/actual" "$expected"
    elif [[ ! -f $expected ]]; then
        echo "FAIL $file: no ${expected##*/} (tools/golden.sh --update writes it)"
        failed=$((failed + 1))
    elif ! diff -u --label "expected ${expected##*/}" --label "actual" "$expected" "$tmp/actual"; then
        echo "FAIL $file"
        failed=$((failed + 1))
    fi
done

if [[ $# -eq 0 && ${#cases[@]} -lt $min_cases ]]; then
    echo "FAIL: ${#cases[@]} cases in tests/golden, fewer than $min_cases"
    failed=$((failed + 1))
fi
if [[ $update -eq 1 ]]; then
    echo "golden: ${#cases[@]} .expected files written; review them with git diff tests/golden"
else
    echo "golden: ${#cases[@]} cases, $failed failed"
fi
[[ $failed -eq 0 ]]
