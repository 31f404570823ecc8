#!/usr/bin/env bash
# Runs every test of voxgi and prints "N passed, N failed" last (skips are listed, never passed).
# Expects `make test` to have built build/ (the normal and the ASan+UBSan test programs).
set -u
cd "$(dirname "$0")/.."
B=build
passed=0; failed=0; skipped=0

record() { # name status [detail]
    case "$2" in
        pass) passed=$((passed + 1)); echo "PASS $1" ;;
        skip) skipped=$((skipped + 1)); echo "SKIP $1: $3" ;;
        *) failed=$((failed + 1)); echo "FAIL $1${3:+: $3}" ;;
    esac
}

run_program() { # label command...
    local label=$1 out rc line
    shift
    echo "== $label"
    out=$("$@" 2>&1); rc=$?
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

# 1. shaders.h, as built and as committed, must be what tools/embed_shaders.c makes of shaders/*.glsl
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if ! "$B/embed_shaders" "$tmp/shaders.h" shaders/*.glsl || ! cmp -s "$tmp/shaders.h" shaders.h; then
    record shaders_h_is_fresh fail "shaders.h differs from shaders/*.glsl: run 'make shaders.h'"
elif ! git rev-parse --verify -q HEAD >/dev/null 2>&1; then
    record shaders_h_is_committed skip "not a git checkout"
elif git show HEAD:shaders.h 2>/dev/null | cmp -s - shaders.h; then
    record shaders_h_is_fresh pass
else
    record shaders_h_is_fresh fail "the committed shaders.h is stale: commit the regenerated one"
fi

# 2. the compile matrix: C and C++ standards, two translation units, static, without GL, without threads
echo "== compile matrix"
for std in c99 c11 c++11 c++17; do
    for variant in "" "-DVOXGI_STATIC" "-DVOXGI_NO_GL" "-DVOXGI_NO_THREADS" "-DVOXGI_NO_GL -DVOXGI_STATIC"; do
        name="compile_${std}${variant:+_$(echo "$variant" | tr -d ' -' | tr 'A-Z' 'a-z')}"
        case $std in c++*) comp="${CXX:-c++} -x c++";; *) comp="${CC:-cc} -x c";; esac
        if $comp -std=$std -Wall -Wextra -pedantic -Werror $variant -O1 -o "$tmp/matrix" \
                tests/compile/tu_impl.c tests/compile/tu_use.c -lm -lpthread 2>"$tmp/err" && "$tmp/matrix"; then
            record "$name" pass
        else
            record "$name" fail "$(head -c 600 "$tmp/err")"
        fi
    done
done
# every exported symbol of the implementation is voxgi_
${CC:-cc} -std=c99 -c -o "$tmp/impl.o" tests/compile/tu_impl.c
bad=$(nm -g --defined-only "$tmp/impl.o" | awk '{print $3}' | grep -v -e '^voxgi_' -e '^tu_impl_version$' || true)
if [ -z "$bad" ]; then record exported_symbols_are_prefixed pass; else record exported_symbols_are_prefixed fail "$bad"; fi

# 3. the test programs, then again under AddressSanitizer and UndefinedBehaviorSanitizer
export VOXGI_REQUIRE_GL=${VOXGI_REQUIRE_GL:-0}  # CI sets 1: there a GL context must exist
for t in test_voxelize test_gl_voxelize test_reference test_vct test_mesh_io test_headless_gl test_tool; do
    run_program "$t" "$B/$t"
done
export ASAN_OPTIONS=detect_leaks=1
export LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1
for t in test_voxelize test_gl_voxelize test_reference test_vct test_mesh_io test_headless_gl test_tool; do
    run_program "asan/$t" env VOXGI_TOOL="$B/asan/voxgi" "$B/asan/$t"
done
# The leak checks above must still catch a leak of voxgi's: a program that leaks its voxels on
# purpose (on GL when a context exists) has to be reported, with voxgi_voxelize in the trace.
echo "== leak canary"
canary=$("$B/asan/leak_canary" 2>&1); rc=$?
if [ "$rc" -ne 0 ] && printf '%s\n' "$canary" | grep -q 'LeakSanitizer' \
        && printf '%s\n' "$canary" | grep -q 'voxgi_voxelize'; then
    record leak_checks_catch_a_voxgi_leak pass
else
    record leak_checks_catch_a_voxgi_leak fail "exit $rc: $(printf '%s\n' "$canary" | head -c 600)"
fi

echo
[ "$skipped" -gt 0 ] && echo "$skipped skipped (see SKIP lines above; a skip is not a pass)"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
