#!/usr/bin/env bash
# Golden outputs: a fixed list of CLI runs whose outputs (files and JSON values, timings left
# out) are reduced to SHA-256 sums. A behaviour-preserving change keeps every sum.
#
#   tests/golden.sh            run, compare with tests/golden.sums, exit 1 on any difference
#   tests/golden.sh --update   run and rewrite tests/golden.sums
#   VOXGI=path/to/voxgi        the tool to run (default build/voxgi, built by `make`)
#
# Left out: timings, thread counts and renderer names, and the GL runs whose results depend
# on the order of float additions (attribute blending by atomics, radiance mips built by
# float blending): those are held to their CPU twins by the tests instead, with tolerances.
set -u
cd "$(dirname "$0")/.."
VOXGI=${VOXGI:-build/voxgi}
sums=tests/golden.sums
mode=check
[ "${1:-}" = "--update" ] && mode=update
[ -x "$VOXGI" ] || { echo "golden.sh: $VOXGI not built (run make)" >&2; exit 2; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out=$tmp/sums

# JSON with the machine-dependent values removed: timings (ms, *_ms), threads, renderer, file names
# (the errors, rel_rmse and rms, stay).
strip_json() {
    sed -E -e 's/"([a-z_]*_)?ms":[-0-9.e+]+,?//g' -e 's/"mrays_per_s":[-0-9.e+]+,?//g' -e 's/"(threads|renderer|output)":("[^"]*"|[0-9]+),?//g'
}
# report CSVs without the columns that hold or derive from timings.
strip_csv() {
    awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) keep[i] = ($i !~ /(^|_)ms($|_)|speedup|pareto/) }
             { line = ""; for (i = 1; i <= NF; i++) if (keep[i]) line = line $i ","; print line }'
}
sum() { sha256sum | cut -c1-64; }

# run LABEL ARGS... : runs the tool, records its exit status and the sums of its JSON and files
run() {
    local label=$1 rc
    shift
    rm -f "$tmp"/o.*
    "$VOXGI" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
    rc=$?
    {
        printf '%s exit %d\n' "$label" "$rc"
        if [ "$rc" -eq 0 ]; then
            grep '^{' "$tmp/stdout" | strip_json | sum | sed "s/^/$label json /"
            for f in "$tmp"/o.*; do
                [ -e "$f" ] && printf '%s %s %s\n' "$label" "${f##*/}" "$(sum <"$f")"
            done
        fi
    } >>"$out"
    printf '.'
}

T="--threads 2"
# 1. every voxelization method on each backend (a method a backend lacks records its exit status)
methods="conservative thin solid slicemap slicemap-atomic atlas atlas-compute geometry volume-buffer volume-buffer-m1"
for backend in cpu gl; do
    for m in $methods; do
        for mesh in builtin:sphere builtin:cube builtin:subdivided-quad; do
            run "voxelize-$m-$backend-${mesh#builtin:}" voxelize "$mesh" --res 40 --method "$m" \
                --backend "$backend" $T --json -o "$tmp/o.binvox"
        done
    done
    for solid in vote flood; do
        run "voxelize-solid-$solid-$backend" voxelize builtin:sphere --res 40 --method solid \
            --solid-mode "$solid" --backend "$backend" $T --json -o "$tmp/o.binvox"
    done
    run "voxelize-solid-x-$backend" voxelize builtin:sphere --res 33 --per-axis --method solid \
        --axis x --backend "$backend" $T --json -o "$tmp/o.binvox"
    run "voxelize-grid-$backend" voxelize builtin:sphere --grid -1.3 -1.1 -0.9 0.05 48 44 40 \
        --backend "$backend" $T --json -o "$tmp/o.binvox"
done

# 2. octrees: structure and sizes
for f in float32 float16; do
    run "svo-$f" svo builtin:sphere --res 32 --format "$f" --neighbours --bricks --backend cpu $T --json
done
run svo-albedo svo builtin:cube --res 16 --attributes albedo --backend cpu $T --json
run svo-gl svo builtin:sphere --res 32 --neighbours --backend gl $T --json

# 3. images: the reference and cone tracing on each built-in scene, fixed seed
for scene in cornell-box rsm-walls leak-box furnace leak-room foliage; do
    run "reference-$scene" render "$scene" --size 24 24 --spp 8 --seed 3 $T --json -o "$tmp/o.pfm"
    run "vct-$scene" render "$scene" --method vct --backend cpu --res 24 --cones 8 --size 24 24 \
        --spp 8 --seed 3 $T --json -o "$tmp/o.pfm"
done
run reference-unlimited render cornell-box --size 16 16 --spp 4 --bounces -1 --seed 2 $T --json -o "$tmp/o.pfm"
run reference-sun render rsm-walls --size 16 16 --spp 4 --sun 0.3 -1 0.2 2 $T --json -o "$tmp/o.pfm"
run vct-aniso render cornell-box --method vct --backend cpu --res 24 --anisotropic --cones 16 \
    --size 24 24 --spp 4 $T --json -o "$tmp/o.pfm"
run vct-octree render cornell-box --method vct --backend cpu --res 24 --octree float16 --bricks \
    --size 24 24 --spp 4 $T --json -o "$tmp/o.pfm"
run vct-stride render cornell-box --method vct --backend cpu --res 24 --cone-stride 2 --step 1 \
    --size 24 24 --spp 4 $T --json -o "$tmp/o.pfm"
run vct-bounces render cornell-box --method vct --backend cpu --res 24 --bounces 3 \
    --size 24 24 --spp 4 --inject-samples 2 $T --json -o "$tmp/o.pfm"
run vct-nogi-png render rsm-walls --method vct --backend cpu --res 24 --no-gi \
    --size 24 24 --spp 4 --exposure 2 $T --json -o "$tmp/o.png"
run vct-compare render leak-box --method vct --backend cpu --res 24 --compare 16 \
    --size 16 16 --spp 4 $T --json -o "$tmp/o.pfm"

# the light-space passes: transmittance and reflective shadow maps
run tsm-foliage render foliage --method tsm --size 24 24 --tsm-size 64 --slices 32 --seed 3 $T --json -o "$tmp/o.pfm"
run tsm-sigma render foliage --method tsm --size 16 16 --tsm-size 32 --sigma 0.5 --spp 2 $T --json -o "$tmp/o.pfm"
run rsm-walls render rsm-walls --method rsm --size 24 24 --rsm-size 64 --rsm-samples 32 --res 24 --seed 3 $T --json -o "$tmp/o.pfm"
run rsm-hierarchical render rsm-walls --method rsm --size 16 16 --rsm-size 32 --rsm-samples 16 --visibility hierarchical --res 16 \
    $T --json -o "$tmp/o.pfm"
run rsm-cornell render cornell-box --method rsm --size 16 16 --rsm-size 24 --rsm-samples 16 --rsm-points 2 --gather-stride 2 --res 16 --spp 2 \
    $T --json -o "$tmp/o.pfm"
run sh-cornell render cornell-box --method sh --size 16 16 --res 16 --spp 2 $T --json -o "$tmp/o.pfm"
run ssao-cornell render cornell-box --method ssao --size 16 16 --rays 8 --steps 8 $T --json -o "$tmp/o.pfm"
run ssao-points render cornell-box --method ssao --point-sampling --size 16 16 --rays 8 $T --json -o "$tmp/o.pfm"
run vao-cornell render cornell-box --method vao --size 16 16 --rays 8 --res 32 $T --json -o "$tmp/o.pfm"
run ao-reference render cornell-box --ao-radius 0.1 --size 16 16 --spp 8 $T --json -o "$tmp/o.pfm"
run ssgi-cornell render cornell-box --method ssgi --size 16 16 --rays 8 --steps 8 --spp 2 $T --json -o "$tmp/o.pfm"
run hybrid-cornell render cornell-box --method hybrid --size 16 16 --rays 8 --res 32 --spp 2 $T --json -o "$tmp/o.pfm"
run ssao-half render cornell-box --method ssao --size 16 16 --rays 8 --steps 8 --half-res on --blur 2 $T --json -o "$tmp/o.pfm"
run ssgi-half render cornell-box --method ssgi --size 16 16 --rays 8 --steps 8 --spp 2 --half-res on --blur 3 $T --json -o "$tmp/o.pfm"
run hybrid-hidden render cornell-box --method hybrid --hidden-light on --size 16 16 --rays 8 --res 32 --spp 2 --blur 2 $T --json -o "$tmp/o.pfm"
run reference-screen-light render cornell-box --size 16 16 --spp 4 --screen-light-only $T --json -o "$tmp/o.pfm"
run linespace-exact render cornell-box --method linespace --backend cpu --size 16 16 --ls-n 4 --ls-depth 2 $T --json -o "$tmp/o.pfm"
run linespace-fast render cornell-box --method linespace --backend cpu --size 16 16 --ls-mode fast --ls-n 3 --ls-depth 3 --samples 5 \
    --supersample 1 --packets on $T --json -o "$tmp/o.pfm"

# GL cone tracing: llvmpipe gives the same bits run after run (a GPU need not: mips by blending)
run vct-gl render cornell-box --method vct --backend gl --res 24 --cones 8 --size 24 24 --spp 8 \
    --seed 3 $T --json -o "$tmp/o.pfm"
run vct-gl-aniso render rsm-walls --method vct --backend gl --res 24 --anisotropic --size 24 24 \
    --spp 4 $T --json -o "$tmp/o.pfm"
run rsm-gl render cornell-box --method rsm --backend gl --size 16 16 --rsm-size 24 --rsm-samples 16 --rsm-points 2 --gather-stride 2 \
    --res 16 --spp 2 $T --json -o "$tmp/o.pfm"
run sh-gl render cornell-box --method sh --backend gl --size 16 16 --res 16 --spp 2 $T --json -o "$tmp/o.pfm"
run ssao-gl render cornell-box --method ssao --backend gl --size 16 16 --rays 8 --steps 8 $T --json -o "$tmp/o.pfm"
run hybrid-gl render cornell-box --method hybrid --backend gl --size 16 16 --rays 8 --res 32 --spp 2 $T --json -o "$tmp/o.pfm"

# 4. the cone tracer's report at a tiny size (the error columns, not the times)
rm -rf "$tmp/report"
"$VOXGI" report vct --size 16 --spp 64 --res 16,24 --cones 8 --steps 1 --strides 1,2 \
    --filters isotropic,anisotropic,octree --backend cpu --no-stages $T --out "$tmp/report" >/dev/null 2>&1
printf 'report-vct exit %d\n' $? >>"$out"
printf 'report-vct csv %s\n' "$(strip_csv <"$tmp/report/vct.csv" | sum)" >>"$out"
echo

if [ "$mode" = update ]; then
    cp "$out" "$sums"
    echo "golden.sh: wrote $(wc -l <"$sums") sums to $sums"
    exit 0
fi
if diff -u "$sums" "$out" >"$tmp/diff"; then
    echo "golden.sh: all $(wc -l <"$sums") sums as recorded"
else
    cat "$tmp/diff"
    echo "golden.sh: outputs differ from $sums" >&2
    exit 1
fi
