#!/usr/bin/env bash
# Runs every test of voxgi and prints "N passed, N failed" last (skips are listed, never passed).
# Expects `make test` to have built build/ ($VOXGI_BUILD when set: `make B=dir test` sets it), the
# normal and the ASan+UBSan test programs. VOXGI_CI=1 (CI): also the programs built at -O0 and -O3
# (-O1 is the sanitizers' build), and any skip fails the run.
#
# The checks run in parallel, at most one per processor at once (VOXGI_TEST_JOBS=n: n at once).
# Each check's output is kept apart and printed whole, in the order the checks are listed below
# (the compile matrix, the programs, the ASan programs, the leak canary, the README), so the log
# and the tallies are the same whatever finishes first. No two checks share a file: each has its
# own files under one temporary directory, and the test programs make their own (mkdtemp,
# tmpfile).
set -u
cd "$(dirname "$0")/.."
B=${VOXGI_BUILD:-build}
passed=0; failed=0; skipped=0

record() { # name status [detail]
    case "$2" in
        pass) passed=$((passed + 1)); echo "PASS $1" ;;
        skip) skipped=$((skipped + 1)); echo "SKIP $1: $3" ;;
        *) failed=$((failed + 1)); echo "FAIL $1${3:+: $3}" ;;
    esac
}

# A test program's report: its output less the RESULT line, whose tallies it adds.
report_program() { # label output exit-status
    local label=$1 out=$2 rc=$3 line
    echo "== $label"
    printf '%s\n' "$out" | grep -v '^RESULT '
    line=$(printf '%s\n' "$out" | grep '^RESULT ' | tail -n 1)
    if [ -z "$line" ]; then
        record "$label" fail "exited with status $rc before reporting"
        return
    fi
    set -- $line
    passed=$((passed + $2)); failed=$((failed + $3)); skipped=$((skipped + $4))
    [ "$rc" -ne 0 ] && [ "$3" -eq 0 ] && record "$label" fail "exit status $rc"
}

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# ---------------------------------------------------------------- the checks, queued
# check NAME KIND COMMAND...: queues check number N (from 0). Its command runs later, in the
# background, with its output in $tmp/N.out and its exit status in $tmp/N.rc; report_KIND prints
# its result. KIND:
#   program  a test program (its lines, and the tallies of its RESULT line)
#   status   a function, given N last, that writes "pass", or "fail" and the reason, to $tmp/N.status
#   canary, readme   the leak canary, tests/readme_snippet.sh
# heading TEXT: a line the next check's report starts with.
n=0
names=(); kinds=(); heads=(); cmds=()
head_next=
check() {
    names[n]=$1; kinds[n]=$2; heads[n]=$head_next
    head_next=
    if [ "$2" = status ]; then shift 2; set -- "$@" "$n"; else shift 2; fi
    cmds[n]=$(printf '%q ' "$@")
    n=$((n + 1))
}
heading() { head_next=$1; }

# One entry of the compile matrix: pass, or fail and the compiler's first 600 bytes. The C99
# entries are optimised, so that every configuration also meets the warnings only the optimiser's
# flow analysis gives (the code paths are the same in every standard); the rest build at -O0.
matrix_entry() { # std variant N
    local std=$1 variant=$2 bin=$tmp/matrix$3 comp opt=-O0
    case $std in c++*) comp="${CXX:-c++} -x c++";; *) comp="${CC:-cc} -x c";; esac
    [ "$std" = c99 ] && opt=-O1
    if $comp -std=$std -Wall -Wextra -pedantic -Werror $variant $opt -o "$bin" \
            tests/compile/tu_impl.c tests/compile/tu_use.c -lm -lpthread 2>"$bin.err" && "$bin"; then
        echo pass > "$tmp/$3.status"
    else
        { echo fail; head -c 600 "$bin.err"; } > "$tmp/$3.status"
    fi
}

# Parts left out (voxgi.h's CONFIGURATION). part_entry: the part's macros in C (the implementation
# at -O0, where the compiler meets every unused function; its object must hold no symbol of the
# part and be smaller than the whole one, part_whole's; tu_use, which renders every method, must
# find the part's methods refused and the public structs' layout, `tu_use --layout`, the whole
# build's: a part left out takes its implementation only) or C++ (-fsyntax-only). The whole
# objects and layouts come from the first part check queued, which the others wait for.
part_whole() { # N: the whole implementation's objects and layouts, with and without GL; every part's symbols in them
    local gl missing=""
    for gl in "" -DVOXGI_NO_GL; do
        ${CC:-cc} -x c -std=c99 -Wall -Wextra -pedantic -Werror -O0 $gl -c -o "$tmp/part_whole$gl.o" \
            tests/compile/tu_impl.c 2>>"$tmp/part_whole.err" || rm -f "$tmp/part_whole$gl.o"
        { [ -e "$tmp/part_whole$gl.o" ] &&
          ${CC:-cc} -x c -std=c99 -Wall -Wextra -pedantic -Werror -O0 $gl -c -o "$tmp/part_whole_use$gl.o" tests/compile/tu_use.c &&
          ${CC:-cc} -o "$tmp/part_whole_use$gl" "$tmp/part_whole$gl.o" "$tmp/part_whole_use$gl.o" -lm -lpthread &&
          "$tmp/part_whole_use$gl" --layout > "$tmp/part_whole$gl.layout"; } 2>>"$tmp/part_whole.err" || rm -f "$tmp/part_whole$gl.layout"
    done
    if [ -e "$tmp/part_whole.o" ]; then
        for key in "${!part_symbols[@]}"; do
            nm "$tmp/part_whole.o" | awk '{print $NF}' | grep -qE "${part_symbols[$key]}" || missing="$missing $key"
        done
    fi
    if [ ! -e "$tmp/part_whole.layout" ] || [ ! -e "$tmp/part_whole-DVOXGI_NO_GL.layout" ]; then
        { echo fail; head -c 600 "$tmp/part_whole.err"; } > "$tmp/$1.status"
    elif [ -n "$missing" ]; then
        { echo fail; echo "no symbol of$missing in the whole object: their patterns test nothing"; } > "$tmp/$1.status"
    else
        echo pass > "$tmp/$1.status"
    fi
    touch "$tmp/part_whole.done"
}
part_entry() { # std key macros N
    local std=$1 key=$2 macros=$3 obj=$tmp/part$4 whole left size whole_size
    if [ "${std#c++}" != "$std" ]; then
        if ${CXX:-c++} -x c++ -std=$std -Wall -Wextra -pedantic -Werror -fsyntax-only $macros \
                tests/compile/tu_impl.c tests/compile/tu_use.c 2>"$obj.err"; then
            echo pass
        else
            echo fail; head -c 600 "$obj.err"
        fi > "$tmp/$4.status"
        return
    fi
    if ! { ${CC:-cc} -x c -std=$std -Wall -Wextra -pedantic -Werror -O0 $macros -c -o "$obj.o" tests/compile/tu_impl.c &&
           ${CC:-cc} -x c -std=$std -Wall -Wextra -pedantic -Werror -O0 $macros -c -o "$obj.use.o" tests/compile/tu_use.c &&
           ${CC:-cc} -o "$obj" "$obj.o" "$obj.use.o" -lm -lpthread && "$obj"; } 2>"$obj.err"; then
        { echo fail; head -c 600 "$obj.err"; } > "$tmp/$4.status"
        return
    fi
    while [ ! -e "$tmp/part_whole.done" ]; do sleep 0.1; done
    case $macros in *-DVOXGI_NO_GL*) whole=$tmp/part_whole-DVOXGI_NO_GL.o;; *) whole=$tmp/part_whole.o;; esac
    left=$(nm "$obj.o" | awk '{print $NF}' | grep -E "${part_symbols[$key]}" | head -n 8 | tr '\n' ' ')
    size=$(size "$obj.o" | awk 'NR == 2 {print $4}')
    whole_size=$(size "$whole" 2>/dev/null | awk 'NR == 2 {print $4}')
    echo "    without $key$(case $macros in *-DVOXGI_NO_GL*) echo ", without GL";; esac): $size of ${whole_size:-?} bytes (text and data, -O0)"
    if [ -n "$left" ]; then
        { echo fail; echo "still in the object: $left"; } > "$tmp/$4.status"
    elif [ -z "$whole_size" ] || [ "$size" -ge "$whole_size" ]; then
        { echo fail; echo "the object is not smaller than the whole one (${whole_size:-none})"; } > "$tmp/$4.status"
    elif ! "$obj" --layout > "$obj.layout" 2>&1 || ! cmp -s "$obj.layout" "${whole%.o}.layout"; then
        { echo fail; echo "the public structs' layout is not the whole build's:" \
              $(diff <(tr ' ' '\n' < "${whole%.o}.layout" 2>/dev/null) <(tr ' ' '\n' < "$obj.layout") | grep '^[<>]' | head -n 8); } > "$tmp/$4.status"
    else
        echo pass > "$tmp/$4.status"
    fi
}
# A part left out while another that needs it stays must stop at the #error that names both.
part_error() { # N
    if ${CC:-cc} -x c -std=c99 -fsyntax-only -DVOXGI_NO_CONE_TRACING tests/compile/tu_impl.c 2>"$tmp/part_error.err"; then
        { echo fail; echo "VOXGI_NO_CONE_TRACING alone compiled"; } > "$tmp/$1.status"
    elif grep -q '#error.*VOXGI_NO_CONE_TRACING needs VOXGI_NO_LIGHT_INJECTION' "$tmp/part_error.err"; then
        echo pass > "$tmp/$1.status"
    else
        { echo fail; head -c 600 "$tmp/part_error.err"; } > "$tmp/$1.status"
    fi
}

# The mutants' list (tests/mutations.txt, for `make mutate`) parses, and each mutant's original
# text is still in its file exactly once: a list the code has moved away from fails here.
mutation_list() { # N
    if bash tests/mutate.sh --list > "$tmp/mutation_list.out" 2>&1; then echo pass; else echo fail; tail -n 5 "$tmp/mutation_list.out"; fi > "$tmp/$1.status"
}

# Every exported symbol of the implementation (the object the tests link) is voxgi_.
exported_symbols() { # N
    local bad
    bad=$(nm -g --defined-only "$B/voxgi_impl.o" | awk '{print $3}' | grep -v -e '^voxgi_' || true)
    if [ -z "$bad" ]; then echo pass; else echo fail; echo "$bad"; fi > "$tmp/$1.status"
}

# 1. shaders.h, as built and as committed, must be what tools/embed_shaders.c makes of shaders/*.glsl
# (at once: it takes no time)
if ! "$B/embed_shaders" "$tmp/shaders.h" shaders/*.glsl || ! cmp -s "$tmp/shaders.h" shaders.h; then
    record shaders_h_is_fresh fail "shaders.h differs from shaders/*.glsl: run 'make shaders.h'"
elif ! git rev-parse --verify -q HEAD >/dev/null 2>&1; then
    record shaders_h_is_committed skip "not a git checkout"
elif git show HEAD:shaders.h 2>/dev/null | cmp -s - shaders.h; then
    record shaders_h_is_fresh pass
else
    record shaders_h_is_fresh fail "the committed shaders.h is stale: commit the regenerated one"
fi

# 2. the compile matrix: C and C++ standards, two translation units, static, without GL, without
# threads, without each part (VOXGI_NO_<PART>)
heading "== compile matrix"
avx2=""
grep -qw avx2 /proc/cpuinfo 2>/dev/null && avx2="-mavx2 -mfma" # where the CPU can run it: the AVX2 paths
for std in c99 c11 c++11 c++17; do
    for variant in "" "-DVOXGI_STATIC" "-DVOXGI_NO_GL" "-DVOXGI_NO_THREADS" "-DVOXGI_NO_SIMD" "-DVOXGI_NO_GL -DVOXGI_STATIC" ${avx2:+"$avx2"}; do
        name="compile_${std}${variant:+_$(echo "$variant" | tr -d ' -' | tr 'A-Z' 'a-z')}"
        check "$name" status matrix_entry "$std" "$variant"
    done
done
# Each part left out alone (VOXGI_NO_CONE_TRACING with VOXGI_NO_LIGHT_INJECTION, which it needs)
# and with VOXGI_NO_GL, then all of them; part_symbols: what must be gone from the object.
declare -A part_macros part_symbols
part_macros=([octree]="-DVOXGI_NO_OCTREE" [cone_tracing]="-DVOXGI_NO_CONE_TRACING -DVOXGI_NO_LIGHT_INJECTION"
             [light_injection]="-DVOXGI_NO_LIGHT_INJECTION" [light_space]="-DVOXGI_NO_LIGHT_SPACE"
             [screen_space]="-DVOXGI_NO_SCREEN_SPACE" [line_space]="-DVOXGI_NO_LINE_SPACE" [reference]="-DVOXGI_NO_REFERENCE")
part_symbols=([octree]='^voxgi__?svo_|^voxgi__glsl_(cone_)?svo'
              [light_injection]='^voxgi__?(inject|vct)_|^voxgi__light_(casters|maps_gl)$|^voxgi__glsl_(inject$|light_map)'
              [light_space]='^voxgi__?(tsm|rsm|sh)_|^voxgi__view_|^voxgi__glsl_(tsm|rsm|sh)_'
              [screen_space]='^voxgi_(ao|ssgi|screen_filter|hammersley|radical_inverse)(_|$)|^voxgi__(screen|filter)_|^voxgi__glsl_screen_'
              [line_space]='^voxgi_(linespace|_ls)_|^voxgi__glsl_linespace(_light|_rays)?$'
              [reference]='^voxgi__(path|ref_rows|reference_trace|camera_sees)$')
part_symbols[cone_tracing]="^voxgi__?cone_|^voxgi_specular_half_angle$|^voxgi__glsl_(cone_|out_rgba)|${part_symbols[light_injection]}"
part_macros[all_parts]="${part_macros[*]}"
part_symbols[all_parts]="$(IFS='|'; echo "${part_symbols[*]}")" # voxel visibility (voxgi_voxels_occluded) is part 5's: it stays
check part_whole_objects status part_whole
for key in octree cone_tracing light_injection light_space screen_space line_space reference all_parts; do
    for gl in "" " -DVOXGI_NO_GL"; do
        for std in c99 c++11; do
            check "compile_${std}_no_${key}${gl:+_no_gl}" status part_entry "$std" "$key" "${part_macros[$key]}$gl"
        done
    done
done
check compile_c99_no_cone_tracing_alone_is_an_error status part_error
check exported_symbols_are_prefixed status exported_symbols
check mutation_list_matches_the_code status mutation_list

# 3. the test programs, then again under AddressSanitizer and UndefinedBehaviorSanitizer
programs=$(sed -n 's/^TESTS *:= *//p' Makefile) # the Makefile's list: one list of the test programs
export VOXGI_REQUIRE_GL=${VOXGI_REQUIRE_GL:-0}  # CI sets 1: there a GL context must exist
for t in $programs; do
    check "$t" program env VOXGI_TOOL="$B/voxgi" "$B/$t"
done
check test_rays_scalar program "$B/test_rays_scalar" # the ray core built with VOXGI_NO_SIMD
if ! grep -qw avx2 /proc/cpuinfo 2>/dev/null; then # the ray core's eight-wide nodes
    record test_rays_avx2 skip "this CPU has no AVX2"
elif [ ! -x "$B/test_rays_avx2" ]; then
    record test_rays_avx2 skip "the compiler cannot target AVX2 (-mavx2 -mfma)"
else
    check test_rays_avx2 program "$B/test_rays_avx2"
fi
# CI (VOXGI_CI=1): the same programs built at the other optimisation levels (the Makefile builds them)
if [ "${VOXGI_CI:-0}" = 1 ]; then
    for level in $(sed -n 's/^OPT_LEVELS *:= *//p' Makefile); do # the Makefile's list
        for t in $programs; do
            check "O$level/$t" program env VOXGI_TOOL="$B/O$level/voxgi" "$B/O$level/$t"
        done
    done
fi
# (every check starts after these lines, so all see the settings; only the ASan programs read them)
export ASAN_OPTIONS=detect_leaks=1
export LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1
for t in $programs; do
    check "asan/$t" program env VOXGI_TOOL="$B/asan/voxgi" "$B/asan/$t"
done
# CI: two contexts on two threads at once under ThreadSanitizer (the Makefile builds it then); a
# race exits 66. The GL driver's own races are suppressed by library (tests/tsan.supp).
if [ "${VOXGI_CI:-0}" = 1 ]; then
    check tsan/test_threads program env TSAN_OPTIONS="suppressions=$PWD/tests/tsan.supp" "$B/tsan/test_threads"
fi
# The leak checks above must still catch a leak of voxgi's: a program that leaks its voxels on
# purpose (on GL when a context exists) has to be reported, with voxgi_voxelize in the trace.
check leak_checks_catch_a_voxgi_leak canary "$B/asan/leak_canary"

# 4. the README's quickstart compiles, runs and prints what the README says
check readme_snippet readme bash tests/readme_snippet.sh

# 5. the examples (examples/*.c, which the Makefile builds): each runs, shows what it printed,
# and is held to an oracle of its own
# The conservative voxels of the tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1) of voxelize.c and
# octree.c on voxgi_fit_grid's n^3 grid (voxel 1/n and a hair, centred on the tetrahedron),
# exactly: voxel (i,j,k) meets the face z = 0 when k = 0 and i + j <= n (the faces y = 0 and
# x = 0 alike), and the face x + y + z = 1 when its box straddles the plane, n - 2 <= i + j + k
# <= n (at i + j + k = n - 3 its far corner would touch the plane; the hair moves it off).
tet_awk='function tet(i, j, k, n) { return (k == 0 && i + j <= n) || (j == 0 && i + k <= n) || (i == 0 && j + k <= n) || (n - 2 <= i + j + k && i + j + k <= n) }'
example_run() { # NAME OUT ARGS...: build/example_NAME ARGS, its output into OUT and shown indented; its exit status
    local name=$1 out=$2 rc
    shift 2
    "$B/example_$name" "$@" > "$out" 2>&1
    rc=$?
    sed 's/^/    /' "$out"
    return $rc
}
example_status() { # N WHY: pass when WHY is empty, else fail for WHY
    if [ -z "$2" ]; then echo pass; else printf 'fail\n%s\n' "$2"; fi > "$tmp/$1.status"
}
# png_check FILE W H: nothing when FILE is a PNG of W x H 8-bit RGB pixels that are not all black,
# else why. The IDAT chunks' zlib stream, less its 2-byte header, is the deflate data that gzip
# inflates behind a gzip header (complaining of the missing trailer). A black image's filtered
# rows are all zero bytes after each row's filter type, whichever filter a row took; any other
# image's are not.
png_hex() { od -An -v -tx1 -j "$2" -N "$3" "$1" | tr -d ' \n'; } # FILE OFFSET COUNT
png_check() {
    local f=$1 w=$2 h=$3 off=8 size len
    [ -s "$f" ] || { echo "no PNG at $f"; return; }
    [ "$(png_hex "$f" 0 8)" = 89504e470d0a1a0a ] || { echo "$f is not a PNG"; return; }
    [ "$(png_hex "$f" 12 14)" = "$(printf '49484452%08x%08x0802' "$w" "$h")" ] || { echo "$f is not $w x $h 8-bit RGB: IHDR $(png_hex "$f" 12 14)"; return; }
    size=$(wc -c < "$f")
    : > "$f.idat"
    while [ $((off + 8)) -le "$size" ]; do
        len=$((16#$(png_hex "$f" "$off" 4)))
        [ "$(png_hex "$f" $((off + 4)) 4)" = 49444154 ] && tail -c +$((off + 9)) "$f" | head -c "$len" >> "$f.idat"
        off=$((off + 12 + len))
    done
    { printf '\037\213\010\000\000\000\000\000\000\377'; tail -c +3 "$f.idat"; } | gzip -dc 2>/dev/null |
        od -An -v -tu1 -w$((1 + 3 * w)) | awk -v w="$w" -v h="$h" '
            NF != 1 + 3 * w { bad = 1 }
            { rows++; for (i = 2; i <= NF; i++) if ($i != 0) lit++ }
            END { if (bad || rows != h) print "its pixels do not inflate to " h " rows of " w; else if (!lit) print "all black" }'
}
example_voxelize() { # N: the voxel count and the slices z = 0, 3, 6 of the 8^3 grid are the exact set's
    local out=$tmp/example_voxelize.txt rc
    example_run voxelize "$out"
    rc=$?
    [ $rc -ne 0 ] && { example_status "$1" "exit status $rc"; return; }
    example_status "$1" "$(awk "$tet_awk"'
        bad { next }
        NR == 1 { if ($0 !~ /^[0-9]+ of 8\^3 voxels touch/) { bad = "no voxel count: " $0 } count = $1; next }
        /^slice z=/ { k = substr($2, 3) + 0; j = 8; slices++; next }
        { if (length($0) != 8 || j < 1) { bad = "not a row of slice z=" k ": " $0; next }
          j--; rows++
          for (i = 0; i < 8; i++) if ((substr($0, i + 1, 1) == "#") != tet(i, j, k, 8)) bad = "slice z=" k ", voxel (" i ", " j "): not the exact set" }
        END { if (bad) { print bad; exit }
              for (i = 0; i < 8; i++) for (j = 0; j < 8; j++) for (k = 0; k < 8; k++) exact += tet(i, j, k, 8)
              if (count != exact) print count " voxels where the exact set has " exact
              else if (slices != 3 || rows != 24) print slices " slices of " rows " rows in all, not 3 of 8 rows" }' "$out")"
}
example_octree() { # N: the nodes per level are the exact voxels' cells; the points' voxels set or empty as the exact set's
    local out=$tmp/example_octree.txt rc
    example_run octree "$out"
    rc=$?
    [ $rc -ne 0 ] && { example_status "$1" "exit status $rc"; return; }
    example_status "$1" "$(awk "$tet_awk"'
        /^octree of depth/ { depth = $4 + 0; leaves = $5 }
        /^  level / { nodes[$2 + 0] = $3; levels++ }
        /^memory:/ { bytes = $2; dense = $7 }
        /^point / { s = $0; sub(/.*voxel \(/, "", s); split(s, f, /[ ),]+/) # i j k set|empty albedo r g b alpha a
            if ((f[4] == "set") != tet(f[1], f[2], f[3], 32)) bad = "voxel (" f[1] " " f[2] " " f[3] ") " f[4] ": not the exact set"
            else if (f[4] == "set" && (f[6] f[7] f[8] f[10] != "0.900.200.101.00")) bad = "a set voxel of albedo " f[6] " " f[7] " " f[8] " alpha " f[10]
            else if (f[4] == "empty" && f[10] != "0.00") bad = "an empty voxel of alpha " f[10]
            points[f[4]]++ }
        END { if (bad) { print bad; exit }
              if (depth != 5 || levels != 6) { print "depth " depth " with " levels " levels, not 5 with 6"; exit }
              for (i = 0; i < 32; i++) for (j = 0; j < 32; j++) for (k = 0; k < 32; k++) if (tet(i, j, k, 32))
                  for (l = 0; l <= 5; l++) { c = l SUBSEP int(i / 2 ^ (5 - l)) SUBSEP int(j / 2 ^ (5 - l)) SUBSEP int(k / 2 ^ (5 - l)); if (!(c in cell)) { cell[c]; want[l]++ } }
              for (l = 0; l <= 5; l++) if (nodes[l] != want[l]) { print "level " l ": " nodes[l] " nodes where the exact voxels fill " want[l] " cells"; exit }
              if (leaves != want[5]) print leaves " leaf voxels where the exact set has " want[5]
              else if (!(bytes > 0 && bytes < dense)) print "memory " bytes " bytes, the dense grid " dense
              else if (!points["set"] || !points["empty"]) print "no set and empty point both" }' "$out")"
}
example_render() { # N: a floor and a box on it (no bottom) as OBJ, rendered by vct at 64 x 64: the settings used, the stages' times, a PNG of that size not all black
    local dir=$tmp/example_render rc why
    mkdir -p "$dir"
    printf '%s\n' 'v -2 0 -2' 'v 2 0 -2' 'v 2 0 2' 'v -2 0 2' 'f 1 4 3 2' \
        'v -0.5 0 -0.5' 'v 0.5 0 -0.5' 'v 0.5 1 -0.5' 'v -0.5 1 -0.5' 'v -0.5 0 0.5' 'v 0.5 0 0.5' 'v 0.5 1 0.5' 'v -0.5 1 0.5' \
        'f 5 8 7 6' 'f 9 10 11 12' 'f 8 12 11 7' 'f 5 9 12 8' 'f 6 7 11 10' > "$dir/scene.obj"
    example_run render "$dir/out.txt" "$dir/scene.obj" vct "$dir/vct.png" 64
    rc=$?
    if [ $rc -ne 0 ]; then why="exit status $rc"
    elif ! grep -q '^vct: 64 x 64, .*resolution 96, .*cones 24' "$dir/out.txt"; then why="no line of the settings used (the library's defaults)"
    elif ! grep -qE '^  cones +[0-9]+\.[0-9]+ ms$' "$dir/out.txt"; then why="no time of the stage cones"
    else why=$(png_check "$dir/vct.png" 64 64)
    fi
    if [ -z "$why" ]; then
        "$B/example_render" "$dir/scene.obj" no-such-method "$dir/x.png" > "$dir/usage.txt" 2>&1
        rc=$?
        [ $rc -eq 2 ] || why="an unknown method: exit status $rc, not 2 (usage)"
    fi
    example_status "$1" "$why"
}
example_own_mesh() { # N: the README's "your own mesh": a floor and a box as OBJ, loaded with voxgi_io.h and rendered: a 128 x 128 PPM not all black; a bad file refused with its line
    local dir=$tmp/example_own_mesh rc why=
    mkdir -p "$dir"
    printf '%s\n' 'v -2 0 -2' 'v 2 0 -2' 'v 2 0 2' 'v -2 0 2' 'f 1 4 3 2' \
        'v -0.5 0 -0.5' 'v 0.5 0 -0.5' 'v 0.5 1 -0.5' 'v -0.5 1 -0.5' 'v -0.5 0 0.5' 'v 0.5 0 0.5' 'v 0.5 1 0.5' 'v -0.5 1 0.5' \
        'f 5 8 7 6' 'f 9 10 11 12' 'f 8 12 11 7' 'f 5 9 12 8' 'f 6 7 11 10' > "$dir/scene.obj"
    example_run own_mesh "$dir/out.txt" "$dir/scene.obj" "$dir/scene.ppm"
    rc=$?
    if [ $rc -ne 0 ]; then why="exit status $rc"
    elif [ "$(head -c 15 "$dir/scene.ppm" | od -An -c | tr -d ' \n')" != 'P6\n128128\n255\n' ]; then why="no 128 x 128 PPM header"
    elif [ "$(wc -c < "$dir/scene.ppm")" -ne $((15 + 3 * 128 * 128)) ]; then why="the PPM is not 15 + 3 x 128 x 128 bytes"
    elif [ -z "$(tail -c +16 "$dir/scene.ppm" | tr -d '\000' | head -c 1)" ]; then why="all black"
    else
        printf 'v 0 0 0\nf 1 2 3\n' > "$dir/bad.obj"
        "$B/example_own_mesh" "$dir/bad.obj" "$dir/bad.ppm" > "$dir/bad.txt" 2>&1 && why="a bad OBJ rendered"
        grep -q 'bad.obj: line 2: ' "$dir/bad.txt" || why="a bad OBJ's message lacks its line: $(head -c 200 "$dir/bad.txt")"
    fi
    example_status "$1" "$why"
}
example_ambient_occlusion() { # N: the corner occluded, the open floor and wall not at all
    local out=$tmp/example_ambient_occlusion.txt rc
    example_run ambient_occlusion "$out"
    rc=$?
    [ $rc -ne 0 ] && { example_status "$1" "exit status $rc"; return; }
    example_status "$1" "$(awk '
        /^occlusion / { split($0, s, ": "); split(s[2], v, /[ (]+/); ao[s[1]] = v[1] + 0; px[s[1]] = v[2] + 0; n++ }
        END { c = "occlusion at the corner"; f = "occlusion on the open floor"; w = "occlusion on the open wall"
              if (n != 3 || !px[c] || !px[f] || !px[w]) print "not three regions with pixels"
              else if (!(ao[c] >= 0.25)) print "the corner occluded " ao[c] ", not at least 0.25"
              else if (!(ao[f] <= 0.01 && ao[w] <= 0.01)) print "the open floor and wall occluded " ao[f] " and " ao[w] ", not at most 0.01" }' "$out")"
}
example_gl_cone_trace() { # N: its own GL context and G-buffer: irradiance seen at some pixels, positive and finite, as a PNG
    local dir=$tmp/example_gl_cone_trace rc why
    mkdir -p "$dir"
    example_run gl_cone_trace "$dir/out.txt" "$dir/irradiance.png"
    rc=$?
    if [ $rc -eq 77 ] && [ "$VOXGI_REQUIRE_GL" != 1 ]; then
        printf 'skip\n%s\n' "no GL 4.5 context through EGL" > "$tmp/$1.status"
        return
    elif [ $rc -eq 77 ]; then why="no GL 4.5 context through EGL, and VOXGI_REQUIRE_GL=1"
    elif [ $rc -ne 0 ]; then why="exit status $rc"
    else
        why=$(awk '/pixels see a surface; mean irradiance/ { seen = 1
                if (!($1 > 0)) print "no pixel sees a surface"
                else if ($12 !~ /^[0-9]+\.[0-9]+$/ || $13 !~ /^[0-9]+\.[0-9]+$/ || $14 !~ /^[0-9]+\.[0-9]+,$/ || !($12 > 0 && $13 > 0 && $14 + 0 > 0) ||
                         $15 " " $16 != "all finite")
                    print "the mean irradiance is not positive and finite: " $12 " " $13 " " $14 " " $15 " " $16 }
            END { if (!seen) print "no mean irradiance" }' "$dir/out.txt")
        [ -z "$why" ] && why=$(png_check "$dir/irradiance.png" 64 64)
    fi
    example_status "$1" "$why"
}
# The viewer (examples/viewer.c, GLFW) in a virtual X server: 3 frames of the Cornell box from a
# fixed camera off the scene's own, by cone tracing on GL (Mesa's llvmpipe through GLX) and by the
# direct light alone, the last frame's pixels saved (glReadPixels) and held to `voxgi render` of the
# same view, method and size on GL through EGL (the same library, another context and program):
# the reference's radiance through the same sRGB transfer (vxt_srgb8) against the screenshot's
# bytes, and the screenshot decoded to linear against the reference clamped to [0, 1] (what a
# display shows). Measured (128 x 96, both methods): mean absolute difference 0 levels (every byte
# equal), relative RMSE 0.0039 (vct) and 0.0035 (direct), the 8-bit quantisation alone; allowed:
# 0.5 levels and 0.02. Planted by hand, each fails it: no sRGB transfer (34 levels), the
# screenshot's or the texture's rows unflipped (28), fovy off by one degree (3.8 levels, RMSE
# 0.56), vct without its indirect light or direct with it (10.8 each). Then the voxel view (the
# voxels as instanced cubes, rasterised) against tests/viewer_voxels.py's ray cast of the voxels it
# saved (--voxels-npy), pixel by pixel: measured 5 of 12,288 pixels more than one level off (the
# ray meets a cube's edge), allowed 0.5%. Planted by hand, each fails it: the top and bottom shades
# swapped (14.7% of the pixels off), fovy off by one degree (8.8%), no depth test (26.5%), cubes
# half a voxel off (5.5%), the faces between two set voxels drawn too (1.3%, where they fight the
# outer faces for depth). Skipped
# where the viewer is not built (no GLFW), Xvfb cannot start or no python3 imports numpy
# (VOXGI_CI=1 fails on any skip).
viewer_compare() { # DIR W H METHOD: nothing when DIR/METHOD.ppm matches DIR/METHOD.pfm, else why; prints the measures
    local dir=$1 w=$2 h=$3 m=$4
    { od -An -v -tu1 -j "$(head -n 3 "$dir/$m.ppm" | wc -c)" "$dir/$m.ppm" | tr -s ' ' '\n' | sed -n 's/^\(..*\)/s \1/p'
      od -An -v -tf4 -j "$(head -n 3 "$dir/$m.pfm" | wc -c)" "$dir/$m.pfm" | tr -s ' ' '\n' | sed -n 's/^\(..*\)/r \1/p'; } |
        awk -v w="$w" -v h="$h" -v m="$m" -v measured="$dir/$m.measured" '
            function srgb8(v,  x) { x = v > 0 ? (v < 1 ? v : 1) : 0; x = x <= 0.0031308 ? 12.92 * x : 1.055 * exp(log(x) / 2.4) - 0.055; return int(x * 255 + 0.5) }
            function linear(b,  x) { x = b / 255; return x <= 0.04045 ? x / 12.92 : exp(2.4 * log((x + 0.055) / 1.055)) }
            $1 == "s" { shot[ns++] = $2; next }
            { i = nr++; p = int(i / 3); ref[3 * ((h - 1 - int(p / w)) * w + p % w) + i % 3] = $2 } # PFM rows from the bottom
            END { n = 3 * w * h
                  if (ns != n || nr != n) { print m ": the screenshot has " ns " values, the reference " nr ", not " n; exit }
                  for (i = 0; i < n; i++) { d = shot[i] - srgb8(ref[i]); mad += d < 0 ? -d : d
                      r = ref[i] < 0 ? 0 : (ref[i] > 1 ? 1 : ref[i]); e = linear(shot[i]) - r; se += e * e; sr += r * r }
                  printf("    %s: screenshot vs voxgi render: mean absolute difference %.3f levels, relative RMSE %.4f\n", m, mad / n, sqrt(se / sr)) > measured
                  if (!(sr > 0)) print m ": the reference is black"
                  else if (!(mad / n <= 0.5 && sqrt(se / sr) <= 0.02))
                      printf("%s: the screenshot differs from voxgi render: mean absolute difference %.3f levels (at most 0.5), relative RMSE %.4f (at most 0.02)", m, mad / n, sqrt(se / sr)) }'
    cat "$dir/$m.measured" >&2 2>/dev/null
}
example_viewer() { # N
    local dir=$tmp/example_viewer cam="0.4 0.35 -0.6 0.278 0.25 0.28 40" rc why= w=128 h=96 m
    mkdir -p "$dir"
    if [ ! -x "$B/example_viewer" ]; then
        printf 'skip\n%s\n' "not built: GLFW's header is missing (bash tools/deps.sh installs libglfw3-dev)" > "$tmp/$1.status"
        return
    elif ! command -v xvfb-run > /dev/null 2>&1; then
        printf 'skip\n%s\n' "no xvfb-run (bash tools/deps.sh installs xvfb)" > "$tmp/$1.status"
        return
    fi
    for m in vct direct; do
        # xvfb-run keeps its authority file in a directory of TMPDIR's; the GL is Mesa's software rasteriser
        TMPDIR=$dir LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe xvfb-run -a -s '-screen 0 640x480x24' \
            "$B/example_viewer" cornell-box --method $m --size $w $h --camera $cam --frames 3 --screenshot "$dir/$m.ppm" > "$dir/$m.txt" 2>&1
        rc=$?
        sed 's/^/    /' "$dir/$m.txt"
        if [ $rc -ne 0 ] && grep -q 'Xvfb failed to start' "$dir/$m.txt"; then
            printf 'skip\n%s\n' "Xvfb cannot start here" > "$tmp/$1.status"
            return
        elif [ $rc -eq 77 ]; then why="no OpenGL 4.5 core context under Xvfb (llvmpipe)"
        elif [ $rc -ne 0 ]; then why="$m: exit status $rc"
        elif [ "$(head -n 3 "$dir/$m.ppm" | tr '\n' ' ')" != "P6 $w $h 255 " ]; then why="$m: no $w x $h PPM"
        elif ! "$B/voxgi" render cornell-box --method vct $([ $m = direct ] && echo --no-gi) --backend gl --size $w $h --camera $cam \
                -o "$dir/$m.pfm" > "$dir/$m.ref.txt" 2>&1; then
            why="$m: voxgi render: $(head -c 300 "$dir/$m.ref.txt")"
        else
            why=$(viewer_compare "$dir" $w $h $m)
        fi
        [ -n "$why" ] && break
    done
    if [ -z "$why" ]; then
        local python= p grid
        for p in ${VOXGI_PYTHON:-} $(which -a python3 2>/dev/null); do "$p" -c 'import numpy' > /dev/null 2>&1 && { python=$p; break; }; done
        if [ -z "$python" ]; then
            printf 'skip\n%s\n' "no python3 on PATH imports numpy (bash tools/deps.sh installs python3-numpy): the voxel view not checked" > "$tmp/$1.status"
            return
        fi
        TMPDIR=$dir LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe xvfb-run -a -s '-screen 0 640x480x24' \
            "$B/example_viewer" cornell-box --method voxels --size $w $h --camera $cam --frames 3 --screenshot "$dir/voxels.ppm" \
            --voxels-npy "$dir/voxels" > "$dir/voxels.txt" 2>&1
        rc=$?
        sed 's/^/    /' "$dir/voxels.txt"
        grid=$(sed -n 's/^viewer: voxels [0-9]* x [0-9]* x [0-9]*, origin \([^,]*\), voxel size \([^,]*\),.*/\1 \2/p' "$dir/voxels.txt")
        if [ $rc -ne 0 ]; then why="voxels: exit status $rc"
        elif [ -z "$grid" ]; then why="voxels: the viewer printed no grid"
        elif ! "$python" tests/viewer_voxels.py "$dir/voxels.ppm" "$dir/voxels" $grid $cam > "$dir/voxels.check" 2>&1; then
            why="voxels: $(tail -n 1 "$dir/voxels.check")"
        fi
        cat "$dir/voxels.check" >&2 2>/dev/null
    fi
    example_status "$1" "$why"
}
heading "== examples"
for e in voxelize octree render own_mesh ambient_occlusion gl_cone_trace viewer; do
    check "example_$e" status "example_$e"
done

# ---------------------------------------------------------------- the reports
report_status() { # N: what the check printed, then its status
    local status
    cat "$tmp/$1.out"
    status=$(head -n 1 "$tmp/$1.status" 2>/dev/null)
    record "${names[$1]}" "${status:-fail}" "$(tail -n +2 "$tmp/$1.status" 2>/dev/null)"
}
report_canary() { # N
    local canary rc
    echo "== leak canary"
    canary=$(cat "$tmp/$1.out"); rc=$(cat "$tmp/$1.rc")
    if [ "$rc" -ne 0 ] && printf '%s\n' "$canary" | grep -q 'LeakSanitizer' \
            && printf '%s\n' "$canary" | grep -q 'voxgi_voxelize'; then
        record leak_checks_catch_a_voxgi_leak pass
    else
        record leak_checks_catch_a_voxgi_leak fail "exit $rc: $(printf '%s\n' "$canary" | head -c 600)"
    fi
}
report_readme() { # N: tests/readme_snippet.sh prints "PASS readme_snippet" or "FAIL readme_snippet: why"
    local out rc
    out=$(cat "$tmp/$1.out"); rc=$(cat "$tmp/$1.rc")
    printf '%s\n' "$out" | grep -v -e '^PASS readme_snippet$' -e '^FAIL readme_snippet' || true
    if [ "$rc" -eq 0 ] && printf '%s\n' "$out" | grep -qx 'PASS readme_snippet'; then
        record readme_snippet pass
    else
        record readme_snippet fail "$(printf '%s\n' "$out" | sed -n 's/^FAIL readme_snippet: //p' | head -c 600)"
    fi
}
report() { # N
    [ -n "${heads[$1]}" ] && echo "${heads[$1]}"
    case ${kinds[$1]} in
        program) report_program "${names[$1]}" "$(cat "$tmp/$1.out")" "$(cat "$tmp/$1.rc")" ;;
        status) report_status "$1" ;;
        canary) report_canary "$1" ;;
        readme) report_readme "$1" ;;
    esac
}

# ---------------------------------------------------------------- running them
# The longest checks start first: the ASan programs, then the other programs, then the rest as
# queued (each compilation is short). Reports are printed in the queued order, each as soon as
# it and all before it are done.
max=${VOXGI_TEST_JOBS:-$(nproc 2>/dev/null || echo 2)}
[ "$max" -ge 1 ] 2>/dev/null || max=1
order=()
for ((i = 0; i < n; i++)); do [ "${kinds[i]}" = program ] && [ "${names[i]#asan/}" != "${names[i]}" ] && order+=("$i"); done
for ((i = 0; i < n; i++)); do [ "${kinds[i]}" = program ] && [ "${names[i]#asan/}" = "${names[i]}" ] && order+=("$i"); done
for ((i = 0; i < n; i++)); do [ "${kinds[i]}" != program ] && order+=("$i"); done

printed=0
print_finished() {
    while [ "$printed" -lt "$n" ] && [ -e "$tmp/$printed.rc" ]; do
        report "$printed"
        printed=$((printed + 1))
    done
}

# A check is done when its N.rc is there (written last); the running ones are those started less those done.
started=0
running() { local done=0 i; for ((i = 0; i < started; i++)); do [ -e "$tmp/${order[i]}.rc" ] && done=$((done + 1)); done; echo $((started - done)); }
for i in "${order[@]}"; do
    while [ "$(running)" -ge "$max" ]; do
        wait -n 2>/dev/null || sleep 0.1
        print_finished
    done
    ( t0=$(date +%s%N); eval "${cmds[i]}" > "$tmp/$i.out" 2>&1; rc=$?
      echo $(( ($(date +%s%N) - t0) / 1000000 )) "${names[i]}" > "$tmp/$i.ms"
      echo $rc > "$tmp/$i.rc.part"; mv "$tmp/$i.rc.part" "$tmp/$i.rc" ) &
    started=$((started + 1))
done
while [ "$printed" -lt "$n" ]; do
    wait -n 2>/dev/null || sleep 0.1
    print_finished
done
wait

echo
# where the time went: the slowest checks (wall clock, while others ran beside them)
echo "slowest checks (ms): $(cat "$tmp"/*.ms 2>/dev/null | sort -rn | head -n 8 | awk '{printf("%s%s %d", (NR > 1 ? ", " : ""), $2, $1)}')"
[ "$skipped" -gt 0 ] && echo "$skipped skipped (see SKIP lines above; a skip is not a pass)"
# In CI everything can run, so a skip means something is missing: it fails the run.
if [ "${VOXGI_CI:-0}" = 1 ] && [ "$skipped" -gt 0 ]; then
    record no_skips_in_ci fail "$skipped checks skipped; CI installs all they need"
fi
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
