#!/usr/bin/env bash
# Mutation testing: do the tests notice a plausible bug? Each mutant of tests/mutations.txt (one
# small change to voxgi.h, a shader or a tool source) is applied to a copy of the sources, built, and run
# against the tests its entry names. CAUGHT: a test failed (or crashed, or hung); SURVIVED: the
# tests passed with the bug in place, so they miss that kind of bug. Run by hand (it takes
# minutes); `make test` does not run it. See usage() below.
set -u
CALLER=$PWD
cd "$(dirname "$0")/.." || exit 2

usage() {
    cat <<'EOF'
Usage: bash tests/mutate.sh [options]

Applies each mutant of tests/mutations.txt to a copy of the sources, builds the test programs
it names (-O1, no sanitizers), runs them and prints one line per mutant:

  CAUGHT     a listed test failed, crashed or timed out (the test that did is named)
  SURVIVED   every listed test passed with the bug in place
  PENDING    not caught, and a listed program is not in the Makefile yet
  INVALID    the mutant does not build (or a mutated shader does not compile): fix the entry
  UNTESTED   every run it lists already fails without the mutation (see the baseline)

First the unmutated sources are built and every run the mutants list is run once (the baseline):
a run that fails there, or whose filter matches no test, cannot judge a mutant and is left out.
The baseline's times also set each run's time limit.

Options:
  --only ID[,ID...]   only these mutants
  --list              list the mutants (id, file, tests, what they simulate) and exit
  -j N, --jobs N      mutants built and run at once (default: the number of processors)
  --timeout SECONDS   the most any one test program may run (default 300)
  --no-baseline       skip the baseline (then the time limit is --timeout for every run)
  --mutations FILE    another list than tests/mutations.txt (same format)
  -h, --help          this text

Exit status: 0 when every mutant was caught (or is pending), 1 when one survived, is invalid
or untested, or the baseline failed; 2 for a bad option or a broken mutation list (such as an
original text that does not occur exactly once in its file).
EOF
}

LIST=tests/mutations.txt
JOBS=$(nproc 2>/dev/null || echo 2)
TIMEOUT=300
ONLY=
LIST_ONLY=0
BASELINE=1

die() { echo "mutate.sh: $*" >&2; exit 2; }

while [ $# -gt 0 ]; do
    case $1 in
        --only) [ $# -ge 2 ] || die "--only needs a list of ids"; ONLY=$2; shift 2 ;;
        --only=*) ONLY=${1#*=}; shift ;;
        --list) LIST_ONLY=1; shift ;;
        -j|--jobs) [ $# -ge 2 ] || die "$1 needs a number"; JOBS=$2; shift 2 ;;
        -j*) JOBS=${1#-j}; shift ;;
        --jobs=*) JOBS=${1#*=}; shift ;;
        --timeout) [ $# -ge 2 ] || die "--timeout needs seconds"; TIMEOUT=$2; shift 2 ;;
        --timeout=*) TIMEOUT=${1#*=}; shift ;;
        --no-baseline) BASELINE=0; shift ;;
        --mutations) [ $# -ge 2 ] || die "--mutations needs a file"; LIST=$2; shift 2 ;;
        --mutations=*) LIST=${1#*=}; shift ;;
        -h|--help) usage; exit 0 ;;
        *) echo "mutate.sh: unknown option: $1" >&2; usage >&2; exit 2 ;;
    esac
done
[[ $JOBS =~ ^[1-9][0-9]*$ ]] || die "-j wants a positive number, not '$JOBS'"
[[ $TIMEOUT =~ ^[1-9][0-9]*$ ]] || die "--timeout wants a positive number of seconds, not '$TIMEOUT'"
[[ $LIST == /* ]] || [ -f "$LIST" ] || LIST=$CALLER/$LIST  # a path given from elsewhere
[ -f "$LIST" ] || die "no $LIST"

START=$SECONDS
WORK=$(mktemp -d "${TMPDIR:-/tmp}/voxgi-mutate.XXXXXX") || die "mktemp failed"
SRC=$WORK/src          # the snapshot of the sources every copy is made from
L=$WORK/list           # the parsed list: N.id N.file N.tests N.about N.original N.replacement
RES=$WORK/results      # N: "STATUS<tab>seconds<tab>detail" per mutant
mkdir -p "$SRC" "$L" "$RES"

# Background jobs ignore Ctrl-C in a script, and a test under `timeout` runs in a process group
# of its own: so on any exit, every process below the jobs this script started is ended by id.
started=()
descendants() { local c; for c in $(ps -o pid= --ppid "$1" 2>/dev/null); do echo "$c"; descendants "$c"; done; }
cleanup() {
    local p all=() below=()
    trap - EXIT INT TERM
    for p in "${started[@]+"${started[@]}"}"; do
        kill -0 "$p" 2>/dev/null || continue
        mapfile -t below < <(descendants "$p")
        all+=("$p" "${below[@]+"${below[@]}"}")
    done
    [ ${#all[@]} -gt 0 ] && kill "${all[@]}" 2>/dev/null
    wait 2>/dev/null
    rm -rf "$WORK"
}
trap cleanup EXIT
trap 'echo "mutate.sh: interrupted" >&2; exit 130' INT
trap 'exit 143' TERM

# make, unaffected by a calling make (`make mutate`): its flags and jobserver stay out.
mk() { env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make --no-print-directory "$@"; }

# ---------------------------------------------------------------- the sources, once
# A snapshot of the working tree (tracked files, and new untracked ones under tests/, shaders/,
# tools/ and fuzz/, e.g. a test program or a fuzz finding not committed yet), so that the whole run
# sees one version even while the files are being edited. Every mutant and the baseline copy this
# snapshot.
git rev-parse --is-inside-work-tree > /dev/null 2>&1 || die "needs a git checkout (it copies the files git knows of)"
{ git ls-files -z; git ls-files -z -o --exclude-standard -- tests shaders tools fuzz; } |
    while IFS= read -r -d '' f; do [ -f "$f" ] && printf '%s\0' "$f"; done |
    xargs -0 cp --parents -p -t "$SRC" || die "could not copy the sources"

# ---------------------------------------------------------------- the list
# Parsed by awk into files (code text is never passed through the shell's word splitting).
awk -v out="$L" '
function bad(msg) { printf "%s:%d: %s\n", FILENAME, FNR, msg > "/dev/stderr"; failed = 1; exit 2 }
function field(name) { sub("^" name ":[ \t]*", ""); printf "%s", $0 > (out "/" n "." name); close(out "/" n "." name) }
state == "original" && $0 == "-- replacement" { close(f); state = "replacement"; f = out "/" n ".replacement"; printf "" > f; first = 1; next }
state == "replacement" && $0 == "-- end" { close(f); state = ""; done[n] = 1; next }
state != "" {
    if ($0 ~ /^(== mutant|-- original|-- replacement|-- end)/) bad("\"" $0 "\" inside the text of mutant " n)
    printf "%s%s", (first ? "" : "\n"), $0 > f
    first = 0
    next
}
/^#/ || /^[ \t]*$/ { next }
/^== mutant / {
    if (n && !done[n]) bad("mutant " n " has no \"-- end\"")
    n++; sub(/^== mutant[ \t]*/, ""); sub(/[ \t]+$/, ""); printf "%s", $0 > (out "/" n ".id"); close(out "/" n ".id")
    next
}
n && /^file:/ { field("file"); next }
n && /^tests:/ { field("tests"); next }
n && /^about:/ { field("about"); next }
n && $0 == "-- original" { state = "original"; f = out "/" n ".original"; printf "" > f; first = 1; next }
{ bad("not understood: " $0) }
END {
    if (failed) exit 2
    if (state != "") bad("the list ends inside the text of mutant " n)
    if (n && !done[n]) bad("mutant " n " has no \"-- end\"")
    print n + 0 > (out "/count")
}' "$LIST" || die "$LIST is malformed"
COUNT=$(cat "$L/count")
[ "$COUNT" -gt 0 ] || die "$LIST has no mutants"

# splice check|apply FILE ORIGINAL-FILE [REPLACEMENT-FILE]: how often the original text occurs
# in FILE (printed; status 0 when exactly once), and with apply, replaces that occurrence.
splice() {
    perl -e '
        my ($mode, $file, $of, $rf) = @ARGV;
        sub slurp { my $p = shift; local $/; open(my $h, "<", $p) or die "cannot read $p\n"; my $t = <$h>; return defined $t ? $t : "" }
        my ($t, $o) = (slurp($file), slurp($of));
        my ($n, $at, $pos) = (0, -1, 0);
        while (length($o) && ($pos = index($t, $o, $pos)) >= 0) { $at = $pos if !$n++; $pos++ }
        print "$n\n";
        exit 1 if $n != 1;
        exit 0 if $mode eq "check";
        substr($t, $at, length $o) = slurp($rf);
        open(my $h, ">", $file) or die "cannot write $file\n";
        print $h $t;
        close $h or die "cannot write $file\n";
    ' "$@"
}

# Every entry complete, ids unique, each original text exactly once in its file: a list that
# no longer matches the code stops the run here, before anything is built.
declare -A index_of
errors=0
for ((n = 1; n <= COUNT; n++)); do
    id=$(cat "$L/$n.id" 2>/dev/null)
    where="$LIST: mutant $n${id:+ ($id)}"
    if ! [[ $id =~ ^[A-Za-z0-9_-]+$ ]]; then echo "$where: bad id '$id'" >&2; errors=$((errors + 1)); continue; fi
    if [ -n "${index_of[$id]+x}" ]; then echo "$where: the id is used twice" >&2; errors=$((errors + 1)); fi
    index_of[$id]=$n
    for k in file tests about original replacement; do
        [ -f "$L/$n.$k" ] || { echo "$where: no '$k'" >&2; errors=$((errors + 1)); continue 2; }
    done
    file=$(cat "$L/$n.file")
    [ -s "$L/$n.tests" ] || { echo "$where: no tests listed" >&2; errors=$((errors + 1)); }
    [ -s "$L/$n.original" ] || { echo "$where: the original text is empty" >&2; errors=$((errors + 1)); continue; }
    cmp -s "$L/$n.original" "$L/$n.replacement" && { echo "$where: the replacement is the original" >&2; errors=$((errors + 1)); }
    if [[ $file == /* || $file == *..* ]] || [ ! -f "$SRC/$file" ]; then
        echo "$where: no file '$file' in the sources" >&2; errors=$((errors + 1)); continue
    fi
    if ! times=$(splice check "$SRC/$file" "$L/$n.original"); then
        echo "$where: its original text occurs $times times in $file, not once:" >&2
        { sed 's/^/    | /' "$L/$n.original"; echo; } >&2
        errors=$((errors + 1))
    fi
done
[ "$errors" -eq 0 ] || die "$errors problem(s) in $LIST (fix the entries to match the code)"

if [ "$LIST_ONLY" = 1 ]; then
    for ((n = 1; n <= COUNT; n++)); do
        printf '%-36s %-28s %s\n    %s\n' "$(cat "$L/$n.id")" "$(cat "$L/$n.file")" "$(cat "$L/$n.tests")" "$(cat "$L/$n.about")"
    done
    exit 0
fi

# The mutants to run, in list order.
selected=()
if [ -n "$ONLY" ]; then
    IFS=, read -r -a wanted <<< "$ONLY"
    for id in "${wanted[@]}"; do
        [ -n "${index_of[$id]+x}" ] || die "--only: no mutant '$id' in $LIST (--list lists them)"
        [[ " ${selected[*]-} " == *" ${index_of[$id]} "* ]] || selected+=("${index_of[$id]}")
    done
else
    for ((n = 1; n <= COUNT; n++)); do selected+=("$n"); done
fi

# ---------------------------------------------------------------- programs and runs
# A run is "program" or "program:filter". A program the Makefile does not list among its TESTS
# (or whose source is missing) is pending: someone is adding it.
# shellcheck disable=SC2016 # make's $($*), not the shell's
printf 'print-var-%%:\n\t@echo $($*)\n' > "$WORK/print.mk"
MAKE_TESTS=" $(cd "$SRC" && mk -s -f Makefile -f "$WORK/print.mk" print-var-TESTS 2>/dev/null) "
available() { [[ $MAKE_TESTS == *" $1 "* ]] && [ -f "$SRC/tests/$1.c" ]; }
runs_of() { cat "$L/$1.tests"; }  # N: its runs, space separated

# build_tree TREE JOBS PROGRAM...: the implementation object and these programs (and the tool,
# which test_tool runs), as the Makefile builds them, at -O1; the log in TREE/build.log.
build_tree() {
    local tree=$1 j=$2 p targets=()
    shift 2
    targets=("$tree/build/voxgi_impl.o")
    for p; do
        targets+=("$tree/build/$p")
        [ "$p" = test_tool ] && targets+=("$tree/build/voxgi")
    done
    (cd "$tree" && mk -s -j"$j" B="$tree/build" CFLAGS=-O1 "${targets[@]}") > "$tree/build.log" 2>&1
}

# run_prog TREE PROGRAM FILTER OUT LIMIT: runs it, output in OUT; its exit status (124: timed out).
# Its temporary files go to a directory of its own, removed afterwards (also after a timeout).
run_prog() {
    local tree=$1 prog=$2 filter=$3 out=$4 limit=$5 rc vars=()
    vars=(VOXGI_REQUIRE_GL=0 "VOXGI_TOOL=$tree/build/voxgi" "TMPDIR=$out.tmp")
    [ -n "$filter" ] && vars+=("TH_ONLY=$filter")
    mkdir -p "$out.tmp"
    (cd "$tree" && env -u TH_ONLY -u TH_EXCLUDE "${vars[@]}" timeout -k 10 "$limit" "build/$prog") > "$out" 2>&1 < /dev/null
    rc=$?
    rm -rf "$out.tmp"
    return $rc
}

# judge OUT STATUS: nothing when the run passed, else why not: the failed tests, and the first
# reason given (the harness prints it indented under the FAIL line). A FAIL may follow a progress
# line that did not end, so it is found anywhere in a line.
judge() {
    local out=$1 rc=$2 fails reason
    fails=$(sed -n 's/.*FAIL \(test_[A-Za-z0-9_]*\).*/\1/p' "$out" | awk '!seen[$0]++' | tr '\n' ' ')
    reason=$(awk '/FAIL test_/{f = 1; next} f && /^    /{sub(/^ +/, ""); print; exit}' "$out" | cut -c 1-160)
    if [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then echo "timed out"
    elif [ -n "$fails" ]; then echo "FAIL ${fails% }${reason:+ [$reason]}"
    elif [ "$rc" -ne 0 ]; then echo "exit status $rc"
    elif ! grep -q '^RESULT ' "$out"; then echo "no RESULT line"
    fi
}

# A tiny pool: start a job once fewer than JOBS run.
pool_wait() { while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n; done; }
pool_start() { pool_wait; "$@" & started+=($!); }

# ---------------------------------------------------------------- baseline
# Every distinct run of the selected mutants, on the unmutated sources: it must pass and test
# something, or it cannot tell a mutant from the code as it is. Its time sets the run's limit.
declare -A base_ok base_secs
allruns=()
declare -A seen
for n in "${selected[@]}"; do
    for run in $(runs_of "$n"); do
        [ -n "${seen[$run]+x}" ] && continue
        seen[$run]=1
        allruns+=("$run")
    done
done
baseline_failed=0
if [ "$BASELINE" = 1 ]; then
    B=$WORK/base
    cp -a "$SRC" "$B"
    progs=()
    for run in "${allruns[@]}"; do
        p=${run%%:*}
        available "$p" && [[ " ${progs[*]-} " != *" $p "* ]] && progs+=("$p")
    done
    echo "baseline: building ${progs[*]-} (unmutated)"
    if ! build_tree "$B" "$JOBS" "${progs[@]+"${progs[@]}"}"; then
        echo "baseline: the unmutated sources do not build:" >&2
        tail -n 20 "$B/build.log" >&2
        exit 1
    fi
    base_run() { # K RUN
        local k=$1 run=$2 t0=$SECONDS filter=
        [[ $run == *:* ]] && filter=${run#*:}
        run_prog "$B" "${run%%:*}" "$filter" "$B/run$k.out" "$TIMEOUT"
        echo "$? $((SECONDS - t0))" > "$B/run$k.rc"
    }
    k=0
    for run in "${allruns[@]}"; do
        k=$((k + 1))
        available "${run%%:*}" && pool_start base_run "$k" "$run"
    done
    wait
    k=0
    for run in "${allruns[@]}"; do
        k=$((k + 1))
        available "${run%%:*}" || continue
        read -r rc secs < "$B/run$k.rc"
        why=$(judge "$B/run$k.out" "$rc")
        read -r _ npass nfail nskip < <(grep '^RESULT ' "$B/run$k.out" | tail -n 1; echo "RESULT 0 0 0")
        if [ -z "$why" ] && [ "$npass" -eq 0 ] && [ "$nfail" -eq 0 ]; then why="its filter matches no test"; fi
        if [ -n "$why" ]; then
            echo "baseline: $run fails without a mutant ($why): left out"
            baseline_failed=1
            continue
        fi
        [ "$nskip" -gt 0 ] && echo "baseline: $run skips $nskip test(s) (no GL context?): those cannot catch anything"
        base_ok[$run]=1
        base_secs[$run]=$secs
    done
    echo "baseline: ${#base_ok[@]} of ${#allruns[@]} runs pass ($((SECONDS - START))s)"
    rm -rf "$B"
fi

# A run's time limit: generous against its baseline time (two mutants share the processors),
# never more than --timeout.
limit_of() {
    local s=${base_secs[$1]-}
    [ -z "$s" ] && { echo "$TIMEOUT"; return; }
    s=$((5 * s + 60))
    echo $((s < TIMEOUT ? s : TIMEOUT))
}

# ---------------------------------------------------------------- one mutant
# mutant N: copies the snapshot, applies the change, builds what its runs need, runs them in
# order until one fails. Writes RES/N and prints its line.
mutant() {
    local n=$1 t0=$SECONDS id file tree status='' detail='' run prog filter why pending='' ran='' progs=() j=1
    id=$(cat "$L/$n.id")
    file=$(cat "$L/$n.file")
    tree=$WORK/m$n
    cp -a "$SRC" "$tree"
    if ! splice apply "$tree/$file" "$L/$n.original" "$L/$n.replacement" > /dev/null; then
        status=INVALID detail="could not apply the change to $file"
    fi
    # a shader change reaches the library through shaders.h: make regenerates it when missing
    [[ $file == *.glsl ]] && rm -f "$tree/shaders.h"
    for run in $(runs_of "$n"); do
        prog=${run%%:*}
        available "$prog" && [[ " ${progs[*]-} " != *" $prog "* ]] && progs+=("$prog")
    done
    [ "${#selected[@]}" -eq 1 ] && j=$JOBS  # alone: the build may use every processor
    if [ -z "$status" ] && ! build_tree "$tree" "$j" "${progs[@]+"${progs[@]}"}"; then
        status=INVALID detail="does not build: $(grep -m 1 -E 'error|Error' "$tree/build.log" | cut -c 1-200)"
    fi
    for run in $(runs_of "$n"); do
        [ -n "$status" ] && break
        prog=${run%%:*}
        filter=
        [[ $run == *:* ]] && filter=${run#*:}
        if ! available "$prog"; then pending+=" $prog"; continue; fi
        [ "$BASELINE" = 1 ] && [ -z "${base_ok[$run]+x}" ] && continue  # fails without the mutant
        ran+=" $run"
        run_prog "$tree" "$prog" "$filter" "$WORK/m$n.$prog.out" "$(limit_of "$run")"
        why=$(judge "$WORK/m$n.$prog.out" "$?")
        [ -z "$why" ] && continue
        # a shader that no longer compiles fails its tests too, but that is a broken entry: the
        # compiler's log names the file and line (voxgi maps it to the shader's own name)
        if [[ $file == *.glsl ]] && grep -q "$(basename "$file"):[0-9]" "$WORK/m$n.$prog.out"; then
            status=INVALID detail="$(basename "$file") does not compile: $(grep -m 1 "$(basename "$file"):[0-9]" "$WORK/m$n.$prog.out" | sed "s/^[[:space:]]*//" | cut -c 1-200)"
        else
            status=CAUGHT detail="by $run: $why"
        fi
    done
    if [ -z "$status" ]; then
        if [ -n "$pending" ]; then status=PENDING detail="not caught yet; waiting for${pending} (not in the Makefile)"
        elif [ -z "$ran" ]; then status=UNTESTED detail="every listed run fails without the mutant"
        else status=SURVIVED detail="passed:${ran}"
        fi
    fi
    printf '%s\t%s\t%s\n' "$status" "$((SECONDS - t0))" "$detail" > "$RES/$n"
    printf '%-9s %-36s %s (%ss)\n' "$status" "$id" "$detail" "$((SECONDS - t0))"
    rm -rf "$tree" "$WORK/m$n".*
}

# ---------------------------------------------------------------- all of them
# Longest first (by the baseline times of their runs), so that the last to finish are short.
order=()
while read -r cost n; do order+=("$n"); done < <(
    for n in "${selected[@]}"; do
        cost=0
        for run in $(runs_of "$n"); do cost=$((cost + ${base_secs[$run]-0})); done
        echo "$cost $n"
    done | sort -k1,1nr -k2,2n)
echo "running ${#order[@]} mutant(s), $JOBS at once"
for n in "${order[@]}"; do pool_start mutant "$n"; done
wait

# ---------------------------------------------------------------- summary, in list order
echo
echo "== summary"
declare -A tally
for n in "${selected[@]}"; do
    IFS=$'\t' read -r status secs detail < "$RES/$n" || { status=LOST secs=0 detail="no result"; }
    tally[$status]=$(( ${tally[$status]-0} + 1 ))
    printf '%-9s %-36s %s\n' "$status" "$(cat "$L/$n.id")" "$detail"
done
elapsed=$((SECONDS - START))
summary="${#selected[@]} mutants: ${tally[CAUGHT]-0} caught, ${tally[SURVIVED]-0} survived, ${tally[PENDING]-0} pending, ${tally[INVALID]-0} invalid"
[ -n "${tally[UNTESTED]-}" ] && summary+=", ${tally[UNTESTED]} untested"
[ -n "${tally[LOST]-}" ] && summary+=", ${tally[LOST]} lost"
echo "$summary ($((elapsed / 60))m$((elapsed % 60))s)"
[ -z "${tally[SURVIVED]-}${tally[INVALID]-}${tally[UNTESTED]-}${tally[LOST]-}" ] && [ "$baseline_failed" = 0 ]
