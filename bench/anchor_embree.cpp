// anchor_embree: Intel Embree 3 casting the very ray sets of `voxgi bench rays` (tools/ray_sets.h)
// on a mesh, with the same thread count, as an outside reference point ("anchor") for the ray core.
//
// For each set it times every Embree kernel and reports the best: rtcIntersect1 and rtcIntersect4/
// 8/16 over consecutive rays (the camera's rays come in 4 x 4 pixel tiles, so a packet of 16 is a
// tile) for the coherent closest hits, rtcOccluded1/4/8/16 for the incoherent segments. The rays are
// split into chunks of 4096 that the threads take in turn. Prints one JSON line in the keys of
// `voxgi bench rays --json`, plus each kernel's rate.
//
// Build (Debian 12: apt-get install libembree-dev):
//   g++ -std=c++17 -O2 -Itools bench/anchor_embree.cpp -lembree3 -lpthread

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

#define VOXGI_IO_IMPLEMENTATION /* the mesh loaders (voxgi_io.h) compiled into this program */
#include "../voxgi_io.h"
#include "ray_sets.h"

namespace {

double now_ms()
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Runs f(first, end) over [0, n) in chunks of 4096 on `threads` threads; returns the wall time.
template <class F> double parallel_ms(size_t n, int threads, F f)
{
    std::atomic<size_t> next(0);
    double t0 = now_ms();
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; t++)
        pool.emplace_back([&] {
            for (;;) {
                size_t first = next.fetch_add(4096);
                if (first >= n) return;
                f(first, std::min(n, first + 4096));
            }
        });
    for (auto &th : pool) th.join();
    return now_ms() - t0;
}

// One ray from the set's 8 floats (origin, tnear, direction, tfar).
void fill1(RTCRay &r, const float *q)
{
    r.org_x = q[0]; r.org_y = q[1]; r.org_z = q[2]; r.tnear = q[3];
    r.dir_x = q[4]; r.dir_y = q[5]; r.dir_z = q[6]; r.tfar = q[7];
    r.time = 0; r.mask = 0xFFFFFFFFu; r.id = 0; r.flags = 0;
}

template <int N, class RayN> void fill(RayN &r, const float *rays, size_t first, size_t end, int *valid)
{
    for (int k = 0; k < N; k++) {
        size_t i = first + (size_t)k;
        valid[k] = i < end ? -1 : 0;
        const float *q = rays + 8 * (i < end ? i : first);
        r.org_x[k] = q[0]; r.org_y[k] = q[1]; r.org_z[k] = q[2]; r.tnear[k] = q[3];
        r.dir_x[k] = q[4]; r.dir_y[k] = q[5]; r.dir_z[k] = q[6]; r.tfar[k] = q[7];
        r.time[k] = 0; r.mask[k] = 0xFFFFFFFFu; r.id[k] = 0; r.flags[k] = 0;
    }
}

struct Counts { std::atomic<size_t> hits{0}; };

template <int N, class RayHitN, class F> void intersect_n(RTCScene scene, const float *rays, size_t first, size_t end, Counts &c, F call)
{
    size_t hits = 0;
    for (size_t i = first; i < end; i += N) {
        RayHitN rh;
        int valid[N];
        fill<N>(rh.ray, rays, i, end, valid);
        for (int k = 0; k < N; k++) { rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID; rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID; }
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        call(valid, scene, &ctx, &rh);
        for (int k = 0; k < N; k++) hits += valid[k] && rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
    }
    c.hits += hits;
}

template <int N, class RayN, class F> void occluded_n(RTCScene scene, const float *rays, size_t first, size_t end, Counts &c, F call)
{
    size_t hits = 0;
    for (size_t i = first; i < end; i += N) {
        RayN r;
        int valid[N];
        fill<N>(r, rays, i, end, valid);
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        call(valid, scene, &ctx, &r);
        for (int k = 0; k < N; k++) hits += valid[k] && r.tfar[k] < 0; // occluded: tfar set to -inf
    }
    c.hits += hits;
}

} // namespace

int main(int argc, char **argv)
{
    if (argc < 2) {
        std::fprintf(stderr, "usage: anchor_embree MESH [RAYS] [THREADS] [RUNS]\n");
        return 2;
    }
    size_t nrays = argc > 2 ? (size_t)std::strtoull(argv[2], nullptr, 10) : 1000000;
    int threads = argc > 3 ? std::atoi(argv[3]) : (int)std::thread::hardware_concurrency(), runs = argc > 4 ? std::atoi(argv[4]) : 3;
    voxgi_io_mesh m;
    char err[512];
    if (voxgi_io_load_mesh(argv[1], &m, err, sizeof err)) {
        std::fprintf(stderr, "anchor_embree: %s\n", err);
        return 1;
    }
    double c[3], r;
    vxt_bounding_sphere(m.positions, m.vertex_count, c, &r);
    const size_t nc = (size_t)VXT_CAMERA_SIDE * VXT_CAMERA_SIDE;
    std::vector<float> coherent(8 * nc), incoherent(8 * nrays);
    vxt_camera_rays(c, r, coherent.data());
    vxt_segment_rays(c, r, nrays, incoherent.data());

    char config[64];
    std::snprintf(config, sizeof config, "threads=%d", threads);
    RTCDevice device = rtcNewDevice(config);
    RTCScene scene = rtcNewScene(device);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *v = (float *)rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.vertex_count);
    unsigned *idx = (unsigned *)rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), m.triangle_count);
    std::memcpy(v, m.positions, m.vertex_count * 3 * sizeof(float));
    std::memcpy(idx, m.indices, m.triangle_count * 3 * sizeof(unsigned));
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    double t0 = now_ms();
    rtcCommitScene(scene);
    double build_ms = now_ms() - t0;

    struct Kernel { double best_ms; size_t hits; };
    auto time_it = [&](size_t n, auto body) {
        double best = 1e30;
        Counts counts;
        for (int run = 0; run < runs; run++) {
            counts.hits = 0;
            best = std::min(best, parallel_ms(n, threads, [&](size_t first, size_t end) { body(first, end, counts); }));
        }
        return Kernel{best, counts.hits.load()};
    };
    const float *cr = coherent.data(), *ir = incoherent.data();
    Kernel ki[4] = {
        time_it(nc, [&](size_t f, size_t e, Counts &k) {
            size_t hits = 0;
            for (size_t i = f; i < e; i++) {
                RTCRayHit rh;
                fill1(rh.ray, cr + 8 * i);
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID; rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                RTCIntersectContext ctx;
                rtcInitIntersectContext(&ctx);
                rtcIntersect1(scene, &ctx, &rh);
                hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            }
            k.hits += hits;
        }),
        time_it(nc, [&](size_t f, size_t e, Counts &k) { intersect_n<4, RTCRayHit4>(scene, cr, f, e, k, [](int *va, RTCScene s, RTCIntersectContext *x, RTCRayHit4 *rh) { rtcIntersect4(va, s, x, rh); }); }),
        time_it(nc, [&](size_t f, size_t e, Counts &k) { intersect_n<8, RTCRayHit8>(scene, cr, f, e, k, [](int *va, RTCScene s, RTCIntersectContext *x, RTCRayHit8 *rh) { rtcIntersect8(va, s, x, rh); }); }),
        time_it(nc, [&](size_t f, size_t e, Counts &k) { intersect_n<16, RTCRayHit16>(scene, cr, f, e, k, [](int *va, RTCScene s, RTCIntersectContext *x, RTCRayHit16 *rh) { rtcIntersect16(va, s, x, rh); }); })};
    Kernel ko[4] = {
        time_it(nrays, [&](size_t f, size_t e, Counts &k) {
            size_t hits = 0;
            for (size_t i = f; i < e; i++) {
                RTCRay ray;
                fill1(ray, ir + 8 * i);
                RTCIntersectContext ctx;
                rtcInitIntersectContext(&ctx);
                rtcOccluded1(scene, &ctx, &ray);
                hits += ray.tfar < 0;
            }
            k.hits += hits;
        }),
        time_it(nrays, [&](size_t f, size_t e, Counts &k) { occluded_n<4, RTCRay4>(scene, ir, f, e, k, [](int *va, RTCScene s, RTCIntersectContext *x, RTCRay4 *ry) { rtcOccluded4(va, s, x, ry); }); }),
        time_it(nrays, [&](size_t f, size_t e, Counts &k) { occluded_n<8, RTCRay8>(scene, ir, f, e, k, [](int *va, RTCScene s, RTCIntersectContext *x, RTCRay8 *ry) { rtcOccluded8(va, s, x, ry); }); }),
        time_it(nrays, [&](size_t f, size_t e, Counts &k) { occluded_n<16, RTCRay16>(scene, ir, f, e, k, [](int *va, RTCScene s, RTCIntersectContext *x, RTCRay16 *ry) { rtcOccluded16(va, s, x, ry); }); })};
    const char *names[4] = {"1", "4", "8", "16"};
    int bi = 0, bo = 0;
    for (int k = 1; k < 4; k++) {
        if (ki[k].best_ms < ki[bi].best_ms) bi = k;
        if (ko[k].best_ms < ko[bo].best_ms) bo = k;
    }
    std::printf("{\"mesh\":\"%s\",\"triangles\":%zu,\"threads\":%d,\"build_ms\":%.3f,\"coherent_intersect_mrays\":%.3f,\"coherent_kernel\":\"rtcIntersect%s\","
                "\"coherent_hits\":%zu,\"incoherent_occluded_mrays\":%.3f,\"incoherent_kernel\":\"rtcOccluded%s\",\"incoherent_occluded\":%zu,\"kernels\":{",
                argv[1], m.triangle_count, threads, build_ms, nc / ki[bi].best_ms / 1e3, names[bi], ki[bi].hits, nrays / ko[bo].best_ms / 1e3, names[bo],
                ko[bo].hits);
    for (int k = 0; k < 4; k++)
        std::printf("%s\"rtcIntersect%s\":%.3f,\"rtcOccluded%s\":%.3f", k ? "," : "", names[k], nc / ki[k].best_ms / 1e3, names[k], nrays / ko[k].best_ms / 1e3);
    std::printf("}}\n");
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    voxgi_io_mesh_free(&m);
    return 0;
}
