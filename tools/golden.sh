#!/usr/bin/env bash
# tools/golden.sh: runs the golden cases of tests/golden/ (see tests/golden/README.md) and prints a
# unified diff for each case whose output is not its NAME.expected; exits 1 if any differs. With
# --update, rewrites every .expected from the current output instead (review the changes with git
# diff). CASE names (NAME.sl, NAME.rib or NAME) limit the run to those cases; without them the
# checks of the directory itself run too (enough cases, each with its .expected).
# The cases are those of BUILD_DIR/tests/affray_tests ("golden: NAME.sl", tests/golden/
# golden_test.cpp, which runs BUILD_DIR's affray): that file alone builds the text, and writes it
# with AFFRAY_GOLDEN_UPDATE=1, so the check and the update cannot disagree.
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
tests=$build/tests/affray_tests
[[ -x $tests ]] || { echo "golden.sh: no $tests: build first (cmake --build $build)" >&2; exit 2; }
dir=$root/tests/golden

# The Catch2 test spec: the named cases, or every case (with --update) or every golden test.
if [[ $# -gt 0 ]]; then
    spec=""
    for name in "$@"; do
        if [[ -f $dir/$name ]]; then file=$name
        elif [[ -f $dir/$name.sl ]]; then file=$name.sl
        elif [[ -f $dir/$name.rib ]]; then file=$name.rib
        else echo "golden.sh: no case '$name' in tests/golden" >&2; exit 2
        fi
        spec+="${spec:+,}golden: $file"
    done
elif [[ $update -eq 1 ]]; then
    spec="[golden][case]"
else
    spec="[golden]"
fi

rc=0
if [[ $update -eq 1 ]]; then
    AFFRAY_GOLDEN_UPDATE=1 "$tests" "$spec" || rc=$?
    [[ $rc -eq 0 ]] && echo "golden: .expected files written; review them with git diff tests/golden"
else
    "$tests" "$spec" || rc=$?
fi
[[ $rc -eq 0 ]] || exit 1
