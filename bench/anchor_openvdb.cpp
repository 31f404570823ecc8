// anchor_openvdb: times OpenVDB's mesh-to-level-set conversion on exactly the
// grid a voxgi benchmark uses, as an outside reference point ("anchor").
//
// Grid correspondence. A voxgi grid is an origin o, a voxel size s and counts
// (NX,NY,NZ); voxel (i,j,k) is the closed box [o+(i,j,k)s, o+(i+1,j+1,k+1)s].
// OpenVDB stores one value per integer index coordinate and places it at the
// voxel centre, so we use the linear transform
//     world = s * index + (o + s/2)
// which puts index (i,j,k) at o+(i+0.5,j+0.5,k+0.5)s, the centre of voxgi's
// voxel (i,j,k). The two grids then coincide cell for cell and voxgi's grid is
// the index range [0,NX) x [0,NY) x [0,NZ).
//
// With a band half width of 1 voxel OpenVDB activates the voxels whose centre
// lies within about one voxel of the surface. A box touched by a triangle has
// its centre within sqrt(3)/2 voxel of it, so the band holds roughly the same
// voxels as a conservative voxelization plus a thin shell: comparable work,
// not an identical set. The band may also spill past the grid's index range;
// those voxels are reported separately.
//
// Build (Debian 12: apt-get install libopenvdb-dev libboost-dev; the OpenVDB
// package does not pull in the Boost headers its own headers include):
//   g++ -std=c++17 -O2 -Itools bench/anchor_openvdb.cpp -lopenvdb -ltbb

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <vector>

#define VOXGI_IO_IMPLEMENTATION /* the mesh loaders (voxgi_io.h) compiled into this program */
#include "../voxgi_io.h"

namespace {

struct Grid {
    double origin[3];
    double size;
    int dims[3];
};

void usage(FILE *f)
{
    std::fprintf(f,
        "usage: anchor_openvdb MESH --grid OX OY OZ SIZE NX NY NZ"
        " [--threads T] [--runs R] [--json]\n"
        "       anchor_openvdb MESH --fit N\n"
        "\n"
        "Times openvdb::tools::meshToLevelSet (band half width 1 voxel) on the\n"
        "given grid: voxel (i,j,k) spans [O+(i,j,k)*SIZE, O+(i+1,j+1,k+1)*SIZE].\n"
        "  --threads T  TBB thread limit (default: all available)\n"
        "  --runs R     repetitions; the median wall time is reported (default 5)\n"
        "  --json       print one JSON object instead of text\n"
        "  --fit N      print a cubic N^3 grid around the mesh with one voxel of\n"
        "               padding, as \"OX OY OZ SIZE N N N\", and exit\n");
}

bool parse_double(const char *s, double *out)
{
    char *end = nullptr;
    errno = 0;
    double v = std::strtod(s, &end);
    if (end == s || *end != '\0' || errno != 0 || !std::isfinite(v)) return false;
    *out = v;
    return true;
}

bool parse_int(const char *s, long lo, long hi, int *out)
{
    char *end = nullptr;
    errno = 0;
    long v = std::strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno != 0 || v < lo || v > hi) return false;
    *out = static_cast<int>(v);
    return true;
}

// Cubic grid of n voxels per axis, centred on the mesh bounds, with at least
// one empty voxel on every side (the longest axis spans exactly n-2 voxels).
Grid fit_grid(const voxgi_io_mesh &m, int n)
{
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a) lo[a] = hi[a] = m.positions[a];
    for (size_t v = 1; v < m.vertex_count; ++v)
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], double(m.positions[3 * v + a]));
            hi[a] = std::max(hi[a], double(m.positions[3 * v + a]));
        }
    double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    Grid g;
    g.size = extent > 0 ? extent / (n - 2) : 1.0;
    for (int a = 0; a < 3; ++a) {
        g.origin[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * n * g.size;
        g.dims[a] = n;
    }
    return g;
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    size_t h = v.size() / 2;
    return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

int run(int argc, char **argv)
{
    const char *mesh_path = nullptr;
    Grid grid{};
    bool have_grid = false, json = false;
    int fit = 0, runs = 5;
    int threads = tbb::info::default_concurrency();

    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!std::strcmp(a, "--help") || !std::strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        } else if (!std::strcmp(a, "--grid") && i + 7 < argc) {
            bool ok = true;
            for (int k = 0; k < 3; ++k) ok = ok && parse_double(argv[i + 1 + k], &grid.origin[k]);
            ok = ok && parse_double(argv[i + 4], &grid.size) && grid.size > 0;
            for (int k = 0; k < 3; ++k) ok = ok && parse_int(argv[i + 5 + k], 1, 1 << 20, &grid.dims[k]);
            if (!ok) {
                std::fprintf(stderr, "anchor_openvdb: bad --grid values\n");
                return 2;
            }
            have_grid = true;
            i += 7;
        } else if (!std::strcmp(a, "--fit") && i + 1 < argc) {
            if (!parse_int(argv[++i], 3, 1 << 20, &fit)) {
                std::fprintf(stderr, "anchor_openvdb: --fit needs an integer >= 3\n");
                return 2;
            }
        } else if (!std::strcmp(a, "--threads") && i + 1 < argc) {
            if (!parse_int(argv[++i], 1, 4096, &threads)) {
                std::fprintf(stderr, "anchor_openvdb: bad --threads value\n");
                return 2;
            }
        } else if (!std::strcmp(a, "--runs") && i + 1 < argc) {
            if (!parse_int(argv[++i], 1, 100000, &runs)) {
                std::fprintf(stderr, "anchor_openvdb: bad --runs value\n");
                return 2;
            }
        } else if (!std::strcmp(a, "--json")) {
            json = true;
        } else if (a[0] != '-' && !mesh_path) {
            mesh_path = a;
        } else {
            std::fprintf(stderr, "anchor_openvdb: unexpected or incomplete argument '%s'\n", a);
            usage(stderr);
            return 2;
        }
    }
    if (!mesh_path || (!have_grid && !fit)) {
        usage(stderr);
        return 2;
    }

    voxgi_io_mesh mesh;
    char err[256] = "";
    if (voxgi_io_load_mesh(mesh_path, &mesh, err, sizeof err) != 0) {
        std::fprintf(stderr, "anchor_openvdb: %s\n", err); // err names the file
        return 1;
    }

    if (fit) {
        Grid g = fit_grid(mesh, fit);
        voxgi_io_mesh_free(&mesh);
        // 9 digits keep a float exact; both tools then parse this same text.
        std::printf("%.9g %.9g %.9g %.9g %d %d %d\n", g.origin[0], g.origin[1], g.origin[2],
                    g.size, g.dims[0], g.dims[1], g.dims[2]);
        return 0;
    }

    // OpenVDB wants its own vector types; copying is not part of the timing.
    std::vector<openvdb::Vec3s> points(mesh.vertex_count);
    std::vector<openvdb::Vec3I> triangles(mesh.triangle_count);
    for (size_t v = 0; v < mesh.vertex_count; ++v)
        points[v] = openvdb::Vec3s(mesh.positions + 3 * v);
    // The loader guarantees at least one triangle and in-range indices.
    for (size_t t = 0; t < mesh.triangle_count; ++t)
        triangles[t] = openvdb::Vec3I(mesh.indices + 3 * t);
    voxgi_io_mesh_free(&mesh);

    openvdb::initialize();
    openvdb::math::Transform::Ptr xform =
        openvdb::math::Transform::createLinearTransform(grid.size);
    xform->postTranslate(openvdb::Vec3d(grid.origin[0] + 0.5 * grid.size,
                                        grid.origin[1] + 0.5 * grid.size,
                                        grid.origin[2] + 0.5 * grid.size));

    // Caps every TBB parallel region in this process while it is alive.
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));

    std::vector<double> ms;
    openvdb::FloatGrid::Ptr sdf;
    for (int r = 0; r < runs; ++r) {
        sdf.reset(); // free the previous result outside the timed region
        auto t0 = std::chrono::steady_clock::now();
        sdf = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*xform, points, triangles, 1.0f);
        auto t1 = std::chrono::steady_clock::now();
        ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    }

    // Count active values (voxels or, rarely, tiles) clipped to the grid.
    const openvdb::CoordBBox bounds(openvdb::Coord(0, 0, 0),
                                    openvdb::Coord(grid.dims[0] - 1, grid.dims[1] - 1,
                                                   grid.dims[2] - 1));
    uint64_t active = sdf->activeVoxelCount(), inside = 0;
    for (auto it = sdf->cbeginValueOn(); it; ++it) {
        openvdb::CoordBBox b;
        it.getBoundingBox(b);
        b.intersect(bounds);
        if (!b.empty()) inside += b.volume();
    }

    const double med = median(ms);
    if (json) {
        std::printf("{\"tool\":\"openvdb\",\"triangles\":%zu,\"grid\":[%d,%d,%d],"
                    "\"ms\":%.3f,\"active_voxels\":%llu,\"active_voxels_in_grid\":%llu,"
                    "\"threads\":%d,\"runs\":%d}\n",
                    triangles.size(), grid.dims[0], grid.dims[1], grid.dims[2], med,
                    (unsigned long long)active, (unsigned long long)inside, threads, runs);
    } else {
        std::printf("openvdb meshToLevelSet, half width 1 voxel\n"
                    "triangles      %zu\n"
                    "grid           %d x %d x %d, voxel size %.9g\n"
                    "threads        %d\n"
                    "median         %.3f ms over %d runs (min %.3f, max %.3f)\n"
                    "active voxels  %llu (%llu inside the grid)\n",
                    triangles.size(), grid.dims[0], grid.dims[1], grid.dims[2], grid.size,
                    threads, med, runs, *std::min_element(ms.begin(), ms.end()),
                    *std::max_element(ms.begin(), ms.end()), (unsigned long long)active,
                    (unsigned long long)inside);
    }
    return 0;
}

} // namespace

int main(int argc, char **argv)
{
    try {
        return run(argc, argv);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "anchor_openvdb: %s\n", e.what());
        return 1;
    }
}
