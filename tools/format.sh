#!/usr/bin/env bash
# tools/format.sh [--check]: formats every C++ source of the repository with clang-format-14 and
# the style in .clang-format; with --check changes nothing and fails (exit 1) listing the files
# that differ, as CI runs it. The Flex and Bison sources (lang/*.l, lang/*.y) are left as written,
# and so are the shading-language headers (shaders/, tests/golden/, tests/corpus/): they are .h files
# but not C++.
set -euo pipefail
cd "$(dirname "$0")/.."
format=clang-format-14
command -v "$format" >/dev/null || { echo "format.sh: $format is not installed (tools/setup.sh installs it)" >&2; exit 2; }
mapfile -t files < <(git ls-files '*.cpp' '*.h' '*.inl' ':!:shaders/' ':!:tests/golden/include/' ':!:tests/corpus/*.h')
if [[ ${1:-} == --check ]]; then
    bad=()
    for f in "${files[@]}"; do
        "$format" --dry-run --Werror "$f" >/dev/null 2>&1 || bad+=("$f")
    done
    if ((${#bad[@]})); then
        echo "format.sh: ${#bad[@]} file(s) not formatted (run tools/format.sh):" >&2
        printf '  %s\n' "${bad[@]}" >&2
        exit 1
    fi
    echo "format.sh: ${#files[@]} files formatted"
    exit 0
fi
"$format" -i "${files[@]}"
