#!/usr/bin/env bash
# tools/fuzz.sh [--time SECONDS] [--runs N] [--jobs N] [--parallel N] [--keep-going] [--build DIR] [TARGET...]:
# coverage-guided fuzzing of affray's front ends with libFuzzer (issue 17; fuzz/README.md).
# Configures and builds build-fuzz (clang-14, AFFRAY_FUZZ: ASan + UBSan + libFuzzer, -O1 -g1), or
# with --build DIR builds the targets in DIR, a build already configured with AFFRAY_FUZZ (CI's
# sanitizer build is one: no third build of the libraries); collects each target's seeds from the
# repository (fuzz/seeds.sh), then runs each target (all
# four by default: fuzz_sl fuzz_afb fuzz_rib fuzz_texture) for SECONDS (default 60; --runs N
# stops it after N executions if that comes first) with -timeout=25 -rss_limit_mb=2048 and its
# dictionary. SECONDS bound the whole of a target's run, its seeds and the loading of its corpus
# included (only the rerun of a finding comes after). New inputs go to build-fuzz/corpus/TARGET,
# kept from run to run. Prints per target the executions, coverage (cov: edges, ft: features) and
# corpus size. A crash, leak, timeout or
# out-of-memory keeps its input under build-fuzz/artifacts/TARGET/ with a line saying how to
# reproduce it, the report's stack and (up to 4 KB) the input in base64, so that a CI log alone
# reproduces it; if that input fails again when run alone, the exit status is 1 and, without
# --keep-going, the remaining targets are not run. (One that does not fail again is reported and
# not counted: see below.) --parallel N runs N targets at once (one core each).
set -euo pipefail
cd "$(dirname "$0")/.."

time=60
limits=(-timeout=25 -rss_limit_mb=2048)  # of a run and of the rerun of a finding
# libFuzzer's entropic schedule counts a feature rare until it has been hit 255 times, and looks
# each feature of each run up in its list of rare ones: with the tens of thousands of features of
# the seeds that search took 30-40% of the time. Rare below 16 hits, the list stays short.
tuning=(-entropic_feature_frequency_threshold=16)
runs=0
jobs=1
parallel=1
keep_going=0
build=
targets=()
all=(fuzz_sl fuzz_afb fuzz_rib fuzz_texture)
while [[ $# -gt 0 ]]; do
    case "$1" in
        --time) time=${2:?--time needs SECONDS}; shift 2 ;;
        --runs) runs=${2:?--runs needs N}; shift 2 ;;
        --jobs) jobs=${2:?--jobs needs N}; shift 2 ;;
        --parallel) parallel=${2:?--parallel needs N}; shift 2 ;;
        --keep-going) keep_going=1; shift ;;
        --build) build=${2:?--build needs DIR}; shift 2 ;;
        -h|--help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        fuzz_sl|fuzz_afb|fuzz_rib|fuzz_texture) targets+=("$1"); shift ;;
        *) echo "tools/fuzz.sh: unknown argument '$1' (targets: ${all[*]})" >&2; exit 2 ;;
    esac
done
[[ ${#targets[@]} -eq 0 ]] && targets=("${all[@]}")

if [[ -z "$build" ]]; then
    build=build-fuzz
    echo "== fuzz: building $build (clang-14, ASan + UBSan + libFuzzer) =="
    cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
          -DAFFRAY_FUZZ=ON -DAFFRAY_TESTS=OFF -DAFFRAY_BENCH=OFF -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" >/dev/null
elif grep -q '^AFFRAY_FUZZ:BOOL=ON$' "$build/CMakeCache.txt" 2>/dev/null; then
    echo "== fuzz: building the targets in $build =="
else
    echo "tools/fuzz.sh: $build is not a build configured with -DAFFRAY_FUZZ=ON" >&2
    exit 2
fi
start=$(date +%s)
# The .afb seeds are compiled by the Release build's affray when there is one (CI builds it
# first), else by this build's.
affray=build/tools/affray
[[ -x "$affray" ]] || affray=$build/tools/affray
extra=()
[[ "$affray" == "$build/tools/affray" ]] && extra=(affray)
mkdir -p "$build/logs"
if ! cmake --build "$build" -j2 --target "${targets[@]}" "${extra[@]}" >"$build/logs/build.log" 2>&1; then
    grep -B2 -A8 -m5 "error" "$build/logs/build.log" >&2 || tail -30 "$build/logs/build.log" >&2
    echo "tools/fuzz.sh: the build failed (log: $build/logs/build.log)" >&2
    exit 2
fi

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
echo "fuzz: built in $(( $(date +%s) - start )) s"
# Runs target $1 and writes its summary to $build/logs/$1.summary; returns 1 for a finding that
# fails again alone.
fuzz_one() {
    local t=$1
    local seeds=$build/seeds/$t corpus=$build/corpus/$t artifacts=$build/artifacts/$t log=$build/logs/$t.log
    local out=$build/logs/$t.summary
    local start
    start=$(date +%s)
    mkdir -p "$corpus" "$artifacts" "$(dirname "$log")"
    : >"$out"
    fuzz/seeds.sh "$t" "$seeds" "$affray" >/dev/null
    local dict=()
    case "$t" in
        fuzz_sl) dict=(-dict=fuzz/sl.dict) ;;
        fuzz_rib) dict=(-dict=fuzz/rib.dict) ;;
    esac
    local run_flags=()
    [[ "$jobs" -gt 1 ]] && run_flags=(-fork="$jobs")
    [[ "$runs" -gt 0 ]] && run_flags+=(-runs="$runs")
    echo "== fuzz: $t for ${time} s ==" >>"$out"
    # libFuzzer's -max_total_time counts from the start of the process but is first checked once
    # every input of the corpus has run: loading a large corpus is bounded by `timeout` instead,
    # whose SIGINT makes libFuzzer print its statistics and stop (exit 72; timeout's own 124).
    local left=$(( start + time - $(date +%s) )) rc=0
    [[ $left -lt 1 ]] && left=1
    timeout -s INT -k 10 "$left" "$build/fuzz/$t" "$corpus" "$seeds" "fuzz/regressions/$t" "${dict[@]}" \
        "${run_flags[@]}" -max_total_time="$left" "${limits[@]}" "${tuning[@]}" -print_final_stats=1 \
        -artifact_prefix="$artifacts/" </dev/null >"$log" 2>&1 || rc=$?
    local stopped=
    if [[ $rc -eq 124 ]] && grep -q "libFuzzer: run interrupted" "$log"; then
        rc=0
        grep -q "INITED" "$log" && stopped=" (stopped by the time limit)" ||
            stopped=" (stopped by the time limit while loading the corpus)"
    fi
    local execs last cov ft
    execs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || true)
    last=$(grep -E '^#[0-9]+' "$log" | tail -1 || true)
    cov=$(grep -o 'cov: [0-9]*' <<<"$last" | grep -o '[0-9]*' || true)
    ft=$(grep -o 'ft: [0-9]*' <<<"$last" | grep -o '[0-9]*' || true)
    printf '%s: %s executions in %d s%s, cov %s, ft %s, corpus %d files\n' "$t" "${execs:-?}" \
        $(( $(date +%s) - start )) "$stopped" "${cov:-?}" "${ft:-?}" "$(find "$corpus" -type f | wc -l)" >>"$out"
    [[ $rc -eq 0 ]] && return 0
    local crash
    crash=$(grep -o "Test unit written to .*" "$log" | tail -1 | sed 's/Test unit written to //' || true)
    grep -m1 -E "ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)|runtime error:|==ERROR" "$log" >>"$out" || true
    # A finding counts when its input fails again alone, in a fresh process with the same
    # limits. One that does not (a timeout under a loaded machine, a sanitizer failing inside
    # itself) is reported with its log and input, and does not fail the run.
    if [[ -n "$crash" && -f "$crash" ]] && "$build/fuzz/$t" "${limits[@]}" "$crash" >"$log.replay" 2>&1; then
        echo "$t: the input above did not fail again when run alone (log: $log.replay); not counted" >>"$out"
        return 0
    fi
    echo "$t FAILED (exit $rc); log: $log" >>"$out"
    [[ -n "$crash" ]] && echo "reproduce: $build/fuzz/$t $crash" >>"$out"
    # CI keeps only what is printed: the report's stack (affray's and the libraries' frames, not
    # libFuzzer's or the sanitizer's) and, when small, the input itself, so that the finding can
    # be reproduced from the log alone (base64 -d > input).
    grep -m3 -E "Assertion|terminate called|what\(\):" "$log" >>"$out" || true
    grep -E '^ +#[0-9]+ ' "$log" | grep -v -E 'fuzzer::|__sanitizer|__asan|__ubsan|libc_start|_start |raise |abort ' |
        head -12 >>"$out" || true
    if [[ -n "$crash" && -f "$crash" && $(stat -c %s "$crash") -le 4096 ]]; then
        echo "the input, base64:" >>"$out"
        base64 -w 100 "$crash" >>"$out"
    fi
    return 1
}

# The targets run `parallel` at a time (each libFuzzer process uses one core); their summaries
# are printed in the targets' order.
status=0
for ((i = 0; i < ${#targets[@]}; i += parallel)); do
    batch=("${targets[@]:i:parallel}")
    pids=()
    for t in "${batch[@]}"; do
        fuzz_one "$t" &
        pids+=($!)
    done
    failed=0
    for k in "${!batch[@]}"; do
        wait "${pids[$k]}" || failed=1
        cat "$build/logs/${batch[$k]}.summary"
    done
    if [[ $failed -eq 1 ]]; then
        status=1
        [[ $keep_going -eq 1 ]] || exit 1
    fi
done
exit $status
