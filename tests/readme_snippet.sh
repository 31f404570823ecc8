#!/usr/bin/env bash
# Keeps the README's quickstart honest.
#
# README.md marks three fenced blocks with an HTML comment on the line before them (blank lines
# between are allowed):
#   <!-- quickstart: examples/quickstart.c -->   a ```c block: must equal that file byte for byte
#   <!-- own-mesh: examples/own_mesh.c -->       a ```c block: likewise
#   <!-- quickstart-output -->                   a ```text block: exactly what the program prints
# The script also wants the README to show the compile command below, then compiles the file
# with it, runs it and compares its standard output with the quickstart-output block.
# Prints "PASS readme_snippet" and exits 0, or prints "FAIL readme_snippet: why" and exits 1.
set -u
cd "$(dirname "$0")/.." || { echo "FAIL readme_snippet: cannot enter the repository root"; exit 1; }

readme=README.md
example=examples/quickstart.c
code_marker="<!-- quickstart: $example -->"
output_marker="<!-- quickstart-output -->"
compile="cc -std=c99 -Wall -Wextra -pedantic -Werror -DVOXGI_NO_GL $example -lm -lpthread"

fail() { echo "FAIL readme_snippet: $*"; exit 1; }

[ -f "$readme" ] || fail "$readme not found"
[ -f "$example" ] || fail "$example not found"
tmp=$(mktemp -d) || fail "mktemp failed"
trap 'rm -rf "$tmp"' EXIT

# block MARKER FENCE OUT: writes the body of the fenced block that follows the one line equal to
# MARKER to OUT, each line with its newline; on a problem, returns 1 with the reason in $tmp/why.
block() {
    awk -v marker="$1" -v fence="$2" -v why="$tmp/why" '
        $0 == marker { found++; if (state == 0) state = 1; next }
        state == 1 && $0 ~ /^[ \t]*$/ { next }
        state == 1 && $0 == fence { state = 2; next }
        state == 1 { problem = "the line after " marker " is not " fence; state = 4; next }
        state == 2 && $0 == "```" { state = 3; next }
        state == 2 { print; next }
        END {
            if (found != 1) problem = (found + 0) " lines of the README are " marker " (want exactly one)"
            else if (problem == "" && state != 3) problem = "no closed " fence " block after " marker
            if (problem != "") { print problem > why; exit 1 }
        }' "$readme" > "$3" || return 1
}

block "$code_marker" '```c' "$tmp/snippet.c" || fail "$(cat "$tmp/why")"
if ! cmp -s "$tmp/snippet.c" "$example"; then
    where=$(cmp "$tmp/snippet.c" "$example" 2>&1 | sed -n '1{s/^.*differ: //;s/^cmp: //;p;}')
    fail "the README's quickstart block differs from $example${where:+ (first difference: $where)}"
fi
# The "your own mesh" block is examples/own_mesh.c byte for byte (the Makefile builds that file,
# tests/run.sh runs it).
own_mesh=examples/own_mesh.c
block "<!-- own-mesh: $own_mesh -->" '```c' "$tmp/own_mesh.c" || fail "$(cat "$tmp/why")"
cmp -s "$tmp/own_mesh.c" "$own_mesh" || fail "the README's \"your own mesh\" block differs from $own_mesh"
block "$output_marker" '```text' "$tmp/expected" || fail "$(cat "$tmp/why")"
[ -s "$tmp/expected" ] || fail "the block after $output_marker is empty"
grep -qF -- "$compile" "$readme" || fail "the README does not show the compile command: $compile"

# The README's command, with the compiler the caller chose and the program kept out of the tree.
${CC:-cc} -std=c99 -Wall -Wextra -pedantic -Werror -DVOXGI_NO_GL "$example" -lm -lpthread \
    -o "$tmp/quickstart" 2>"$tmp/err" || fail "$example does not compile: $(head -c 600 "$tmp/err" | tr '\n' ' ')"

run=("$tmp/quickstart")
command -v timeout >/dev/null 2>&1 && run=(timeout 60 "$tmp/quickstart")
"${run[@]}" >"$tmp/out" 2>"$tmp/err"
rc=$?
[ "$rc" -eq 0 ] || fail "$example exited with status $rc: $(head -c 600 "$tmp/err" | tr '\n' ' ')"
cmp -s "$tmp/out" "$tmp/expected" ||
    fail "$example printed '$(head -c 200 "$tmp/out" | tr '\n' ' ')' where the README says '$(head -c 200 "$tmp/expected" | tr '\n' ' ')'"
echo "PASS readme_snippet"
