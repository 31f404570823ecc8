#!/usr/bin/env bash
# Anchor benchmark: voxgi's exact conservative CPU voxelization against
# OpenVDB's meshToLevelSet on the same grid with the same thread counts.
#
# usage: bench/anchors.sh [MESH] [RESOLUTION]
#   MESH        default ../shared/meshes/dragon.obj next to the project, if present
#   RESOLUTION  voxels per axis of a cubic grid fitted to the mesh (default 512)
# environment:
#   RUNS=5              repetitions per measurement (the median is reported)
#   THREADS=$(nproc)    thread count of the parallel row (a 1-thread row always runs)
#   OPENVDB_CFLAGS, OPENVDB_LIBS   for an OpenVDB outside the default paths
#
# OpenVDB is optional for the project: without its headers this script says
# so and exits 0.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$root/build
anchor=$build/anchor_openvdb
voxgi=$build/voxgi

CC=${CC:-cc}
CXX=${CXX:-c++}
OPENVDB_CFLAGS=${OPENVDB_CFLAGS:-}
OPENVDB_LIBS=${OPENVDB_LIBS:--lopenvdb -ltbb}
runs=${RUNS:-5}
threads=${THREADS:-$(nproc)}

if [[ ${1:-} == -h || ${1:-} == --help ]]; then
    sed -n '2,14s/^# \{0,1\}//p' "${BASH_SOURCE[0]}"
    exit 0
fi

mesh=${1:-}
res=${2:-512}
if [[ -z $mesh ]]; then
    mesh=$root/../shared/meshes/dragon.obj
    if [[ ! -f $mesh ]]; then
        echo "anchors: no mesh given and ../shared/meshes/dragon.obj not found; skipping" >&2
        echo "anchors: usage: bench/anchors.sh MESH [RESOLUTION]" >&2
        exit 0
    fi
fi
if [[ ! -f $mesh ]]; then
    echo "anchors: mesh not found: $mesh" >&2
    exit 1
fi

# Preprocessing the header is enough to detect OpenVDB and its header-only
# dependencies (Boost, Imath) without paying for a full compile.
# shellcheck disable=SC2086
if ! echo '#include <openvdb/tools/MeshToVolume.h>' |
        "$CXX" -std=c++17 $OPENVDB_CFLAGS -x c++ -E - >/dev/null 2>&1; then
    echo "anchors: OpenVDB headers not found; the OpenVDB anchor is optional." >&2
    echo "anchors: on Debian/Ubuntu: apt-get install libopenvdb-dev libboost-dev" >&2
    exit 0
fi

# Rebuild the anchor when it is missing or older than its sources.
srcs=("$root/bench/anchor_openvdb.cpp" "$root/voxgi_io.h" "$root/voxgi.h")
stale=0
[[ -x $anchor ]] || stale=1
for s in "${srcs[@]}"; do
    if [[ $s -nt $anchor ]]; then stale=1; fi
done
if ((stale)); then
    echo "anchors: building $(basename "$anchor")" >&2
    mkdir -p "$build"
    # shellcheck disable=SC2086
    "$CXX" -std=c++17 -O2 -Wall -Wextra -pedantic $OPENVDB_CFLAGS -I"$root/tools" \
        "$root/bench/anchor_openvdb.cpp" \
        -o "$anchor" $OPENVDB_LIBS
fi

# Value of a numeric key in a one-line JSON object ("" when absent).
json_num() {
    sed -n "s/.*\"$2\"[[:space:]]*:[[:space:]]*\([-+0-9.eE]*\).*/\1/p" <<<"$1" | head -n 1
}

read -r -a grid <<<"$("$anchor" "$mesh" --fit "$res")"
if ((${#grid[@]} != 7)); then
    echo "anchors: could not fit a grid to $mesh" >&2
    exit 1
fi

thread_list=(1)
if ((threads > 1)); then thread_list+=("$threads"); fi

have_voxgi=1
if [[ ! -x $voxgi ]]; then
    have_voxgi=0
    echo "anchors: $voxgi not built yet; reporting the OpenVDB side only" >&2
fi

rows=()
for t in "${thread_list[@]}"; do
    vms=""
    if ((have_voxgi)); then
        echo "anchors: voxgi, $t thread(s)" >&2
        if out=$("$voxgi" voxelize "$mesh" --grid "${grid[@]}" --backend cpu \
                --threads "$t" --json --runs "$runs"); then
            out=$(grep '{' <<<"$out" | tail -n 1 || true)
            vms=$(json_num "$out" ms)
            vvox=$(json_num "$out" voxels)
            rows+=("| voxgi cpu | $t | ${vms:-?} | ${vvox:-?} | |")
        else
            echo "anchors: voxgi failed with $t thread(s)" >&2
        fi
    fi
    echo "anchors: openvdb, $t thread(s)" >&2
    out=$("$anchor" "$mesh" --grid "${grid[@]}" --threads "$t" --runs "$runs" --json)
    oms=$(json_num "$out" ms)
    ovox=$(json_num "$out" active_voxels_in_grid)
    tris=$(json_num "$out" triangles)
    ratio=""
    if [[ -n $vms ]]; then
        ratio=$(awk -v o="$oms" -v v="$vms" 'BEGIN { if (v > 0) printf "%.2f", o / v }')
    fi
    rows+=("| openvdb meshToLevelSet | $t | $oms | $ovox | $ratio |")
done

echo "mesh: $(basename "$mesh") ($tris triangles), grid ${grid[4]}x${grid[5]}x${grid[6]}," \
    "origin (${grid[0]}, ${grid[1]}, ${grid[2]}), voxel ${grid[3]}, median of $runs runs"
echo
echo "| tool | threads | ms (median) | voxels | openvdb_ms / voxgi_ms |"
echo "|---|---:|---:|---:|---:|"
printf '%s\n' "${rows[@]}"
echo
echo "voxgi counts voxels whose closed box touches a triangle; OpenVDB counts the"
echo "active voxels of a level set of half width 1 voxel that lie inside the grid."
