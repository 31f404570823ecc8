#!/usr/bin/env bash
# Runs the libFuzzer harnesses that `make fuzz` built (docs/fuzzing.md), one after the other.
#
#   bash fuzz/run.sh BUILD_DIR SECONDS NAME...     fuzz each harness SECONDS seconds
#   bash fuzz/run.sh --regress BUILD_DIR NAME...   run each harness once over every input of its
#                                                  seed corpus and fuzz/regressions/, no fuzzing
#
# Fuzzing: harness NAME starts from BUILD_DIR/corpus-NAME (the committed seeds, fuzz/corpus/NAME,
# copied in, plus what earlier runs added: new inputs stay out of git) and reads
# fuzz/regressions/NAME too; its log is BUILD_DIR/NAME.log and what it finds (crash-*, leak-*,
# timeout-*, oom-*) goes to BUILD_DIR/findings-NAME/. A table of every harness's executions and
# findings closes the run. Exits non-zero when any harness found something, naming the input.
set -u
cd "$(dirname "$0")/.."

# The largest input each harness is handed: a few times its largest seed.
max_len() {
    case $1 in
        gltf|glb|svo) echo 16384 ;;
        api|mtl|binvox|pfm) echo 2048 ;;
        *) echo 8192 ;;
    esac
}

inputs() { # NAME: every seed and regression input of harness NAME
    find "fuzz/corpus/$1" "fuzz/regressions/$1" -type f 2>/dev/null | sort
}

if [ "${1:-}" = --regress ]; then
    build=$2; shift 2
    status=0
    for name in "$@"; do
        mapfile -t files < <(inputs "$name")
        if [ ${#files[@]} -eq 0 ]; then echo "fuzz-regress: $name: no inputs"; continue; fi
        if "$build/fuzz_$name" "${files[@]}" >"$build/$name.regress.log" 2>&1; then
            echo "fuzz-regress: $name: ${#files[@]} inputs, no finding"
        else
            echo "fuzz-regress: $name: FAILED, see $build/$name.regress.log"
            status=1
        fi
    done
    exit $status
fi

build=$1; seconds=$2; shift 2
rows=(); status=0
for name in "$@"; do
    corpus=$build/corpus-$name findings=$build/findings-$name log=$build/$name.log
    mkdir -p "$corpus" "$findings" "fuzz/regressions/$name"
    cp fuzz/corpus/"$name"/* "$corpus"/ 2>/dev/null
    echo "fuzz: $name for $seconds s (log: $log)"
    start=$(date +%s%N)
    "$build/fuzz_$name" "$corpus" "fuzz/regressions/$name" -max_total_time="$seconds" -max_len="$(max_len "$name")" \
        -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 -artifact_prefix="$findings/" >"$log" 2>&1
    rc=$?
    ms=$(( ($(date +%s%N) - start) / 1000000 + 1 ))
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
    added=$(sed -n 's/^stat::new_units_added: *//p' "$log" | tail -n 1)
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -n 1 | cut -d' ' -f2)
    found=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log")
    # a crash ends the harness before its final stats: count its runs from the last status line
    [ -z "$runs" ] && runs=$(grep -o '^#[0-9]*' "$log" | tail -n 1 | tr -d '#')
    secs=$(( (ms + 500) / 1000 ))
    rate=$(( ${runs:-0} * 1000 / ms ))
    count=0
    if [ -n "$found" ] || [ "$rc" -ne 0 ]; then
        status=1
        count=$(printf '%s\n' "$found" | grep -c .)
        [ "$count" -eq 0 ] && count=1
        echo "fuzz: $name FAILED (exit $rc): ${found:-see $log}"
        grep -m 3 -E '^(==[0-9]+==ERROR|SUMMARY|.*fuzz check failed)' "$log" | sed 's/^/    /'
    fi
    echo "fuzz: $name: ${runs:-?} executions in $secs s, $rate exec/s, coverage ${cov:-?}, ${added:-0} new inputs, $count findings"
    rows+=("$(printf '%-8s %7s %12s %8s %8s %9s' "$name" "$secs" "${runs:-?}" "$rate" "${cov:-?}" "$count")")
done
echo
printf '%-8s %7s %12s %8s %8s %9s\n' harness seconds executions exec/s coverage findings
printf '%s\n' "${rows[@]}"
[ $status -eq 0 ] || echo "fuzz: findings above; each input is in $build/findings-NAME/ (replay: $build/fuzz_NAME FILE)"
exit $status
