#!/usr/bin/env bash
# Anchor benchmark for the ray core: `voxgi bench rays` against Intel Embree 3 casting the same
# two ray sets (tools/ray_sets.h) on the same threads, best Embree kernel per set.
#
# usage: bench/anchors_rays.sh [MESH ...]
#   MESH     default: the standard meshes in ../shared/meshes next to the project, if present
# environment:
#   RAYS=1000000       incoherent segments
#   RUNS=3             runs per set (voxgi: the median; Embree: the best)
#   THREADS=$(nproc)   threads of both
#   NATIVE=1           also voxgi built for this CPU (-march=native: AVX2's eight-wide nodes where
#                      the CPU has them), as Embree picks its kernels at run time; 0: not
#   LINESPACE="4,3 8,3"  line spaces (n,depth) that also cast the incoherent set, exact and fast,
#                      against Embree's rtcOccluded on the same segments (voxgi as built); "": none
#   EMBREE_CFLAGS, EMBREE_LIBS   for an Embree outside the default paths
#
# Embree is optional for the project: without its headers this script says so and exits 0.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$root/build
anchor=$build/anchor_embree
voxgi=$build/voxgi
CC=${CC:-cc}
CXX=${CXX:-c++}
EMBREE_CFLAGS=${EMBREE_CFLAGS:-}
EMBREE_LIBS=${EMBREE_LIBS:--lembree3}
rays=${RAYS:-1000000}
runs=${RUNS:-3}
threads=${THREADS:-$(nproc)}
native=${NATIVE:-1}
linespaces=${LINESPACE-4,3 8,3}

if [[ ${1:-} == -h || ${1:-} == --help ]]; then
    sed -n '2,15s/^# \{0,1\}//p' "${BASH_SOURCE[0]}"
    exit 0
fi
meshes=("$@")
if ((${#meshes[@]} == 0)); then
    for m in bunny suzanne teapot dragon; do
        [[ -f $root/../shared/meshes/$m.obj ]] && meshes+=("$root/../shared/meshes/$m.obj")
    done
    if ((${#meshes[@]} == 0)); then
        echo "anchors_rays: no mesh given and none found in ../shared/meshes; skipping" >&2
        exit 0
    fi
fi
# shellcheck disable=SC2086
if ! echo '#include <embree3/rtcore.h>' | "$CXX" -std=c++17 $EMBREE_CFLAGS -x c++ -E - >/dev/null 2>&1; then
    echo "anchors_rays: Embree 3 headers not found; the Embree anchor is optional." >&2
    echo "anchors_rays: on Debian/Ubuntu: apt-get install libembree-dev" >&2
    exit 0
fi
srcs=("$root/bench/anchor_embree.cpp" "$root/tools/ray_sets.h" "$root/voxgi_io.h" "$root/voxgi.h")
stale=0
[[ -x $anchor ]] || stale=1
for s in "${srcs[@]}"; do
    if [[ $s -nt $anchor ]]; then stale=1; fi
done
if ((stale)); then
    echo "anchors_rays: building $(basename "$anchor")" >&2
    mkdir -p "$build"
    # shellcheck disable=SC2086
    "$CXX" -std=c++17 -O2 -Wall -Wextra -pedantic $EMBREE_CFLAGS -I"$root/tools" "$root/bench/anchor_embree.cpp" \
        -o "$anchor" $EMBREE_LIBS -lpthread
fi
json_num() { sed -n "s/.*\"$2\"[[:space:]]*:[[:space:]]*\([-+0-9.eE]*\).*/\1/p" <<<"$1" | head -n 1; }
json_str() { sed -n "s/.*\"$2\"[[:space:]]*:[[:space:]]*\"\([^\"]*\)\".*/\1/p" <<<"$1" | head -n 1; }

table() { # VOXGI_BINARY
    echo "| mesh | triangles | coherent, voxgi | Embree (kernel) | ratio | incoherent, voxgi | Embree (kernel) | ratio | hits, voxgi - Embree |"
    echo "|---|---:|---:|---:|---:|---:|---:|---:|---|"
    for mesh in "${meshes[@]}"; do
        v=$("$1" bench rays "$mesh" --rays "$rays" --runs "$runs" --threads "$threads" --json)
        e=$("$anchor" "$mesh" "$rays" "$threads" "$runs")
        vc=$(json_num "$v" coherent_intersect_mrays) vi=$(json_num "$v" incoherent_occluded_mrays)
        ec=$(json_num "$e" coherent_intersect_mrays) ei=$(json_num "$e" incoherent_occluded_mrays)
        agree="$(($(json_num "$v" coherent_hits) - $(json_num "$e" coherent_hits))), $(($(json_num "$v" incoherent_occluded) - $(json_num "$e" incoherent_occluded)))"
        awk -v m="$(basename "$mesh")" -v t="$(json_num "$v" triangles)" -v vc="$vc" -v ec="$ec" -v vi="$vi" -v ei="$ei" \
            -v kc="$(json_str "$e" coherent_kernel)" -v ki="$(json_str "$e" incoherent_kernel)" -v a="$agree" \
            'BEGIN { printf "| %s | %d | %.1f M/s | %.1f M/s (%s) | %.2fx | %.1f M/s | %.1f M/s (%s) | %.2fx | %s |\n", m, t, vc, ec, kc, vc / ec, vi, ei, ki, vi / ei, a }'
    done
}
echo "voxgi as built ($voxgi):"
echo
table "$voxgi"
if [[ -n $linespaces ]]; then
    echo
    echo "The line space's shadow rays, the incoherent set (voxgi as built):"
    echo
    echo "| mesh | n, depth | build | exact | x Embree | fast | x Embree | fast: wrongly blocked | exact - core |"
    echo "|---|---|---:|---:|---:|---:|---:|---:|---:|"
    for mesh in "${meshes[@]}"; do
        e=$("$anchor" "$mesh" "$rays" "$threads" "$runs")
        ei=$(json_num "$e" incoherent_occluded_mrays)
        for ls in $linespaces; do
            v=$("$voxgi" bench rays "$mesh" --rays "$rays" --runs "$runs" --threads "$threads" --linespace "$ls" --json | tail -n 1)
            awk -v m="$(basename "$mesh")" -v ls="$ls" -v b="$(json_num "$v" linespace_build_ms)" -v ex="$(json_num "$v" linespace_exact_mrays)" \
                -v fa="$(json_num "$v" linespace_fast_mrays)" -v w="$(json_num "$v" linespace_fast_wrong)" -v d="$(json_num "$v" linespace_exact_disagree)" \
                -v ei="$ei" -v n="$rays" \
                'BEGIN { printf "| %s | %s | %.0f ms | %.2f M/s | %.3fx | %.2f M/s | %.3fx | %.2f%% | %d |\n", m, ls, b, ex, ex / ei, fa, fa / ei, 100 * w / n, d }'
        done
    done
fi
if [[ $native == 1 ]]; then
    echo "anchors_rays: building voxgi for this CPU (-march=native)" >&2
    if make -s -C "$root" B="$build/native" CFLAGS="-O2 -g -march=native" "$build/native/voxgi" >&2; then
        echo
        echo "voxgi built for this CPU (-march=native):"
        echo
        table "$build/native/voxgi"
    else
        echo "anchors_rays: the compiler cannot build for -march=native; that table is left out" >&2
    fi
fi
echo
echo "($threads threads, $rays incoherent segments, 262144 camera rays; wall-clock rates on this machine; the last"
echo "column: closest hits of the camera's rays, occluded segments - a ray grazing an edge may fall either way)"
