/* fuzz/fuzz.h - what the libFuzzer harnesses share: a check that aborts (libFuzzer then saves the
 * input as a crash), a CPU context made once per process, and a reader that turns the fuzzer's
 * bytes into counts, choices and numbers (zeros once the bytes run out, so every input decodes). */
#ifndef VOXGI_FUZZ_H
#define VOXGI_FUZZ_H
#include "../voxgi.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A broken promise of the code under test: printed, then abort(), which libFuzzer reports as a
   crash (a test program that runs the harnesses defines its own first). */
#ifndef FUZZ_CHECK
#define FUZZ_CHECK(cond) do {                                                                      \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "%s:%d: fuzz check failed: %s\n", __FILE__, __LINE__, #cond);          \
            abort();                                                                               \
        }                                                                                          \
    } while (0)
#endif

/* One CPU context for the whole run, on the calling thread, with a memory budget so that a grid
   or map asked for by the input is refused (VOXGI_ERR_TOO_LARGE) rather than filling memory. */
static inline voxgi_context *fuzz_context(void)
{
    static voxgi_context *ctx;
    if (!ctx) {
        voxgi_desc desc;
        memset(&desc, 0, sizeof desc);
        desc.backend = VOXGI_BACKEND_CPU;
        desc.thread_count = 1;
        desc.memory_budget = (size_t)64 << 20;
        FUZZ_CHECK(voxgi_create(&desc, &ctx) == VOXGI_OK);
    }
    return ctx;
}

typedef struct fuzz_bytes { const uint8_t *p; size_t left; } fuzz_bytes;

static inline unsigned fuzz_u8(fuzz_bytes *b)
{
    if (!b->left) return 0;
    b->left--;
    return *b->p++;
}
static inline uint32_t fuzz_u32(fuzz_bytes *b)
{
    uint32_t v = 0;
    int i;
    for (i = 0; i < 4; i++) v |= (uint32_t)fuzz_u8(b) << (8 * i);
    return v;
}
/* 0 .. n-1 */
static inline unsigned fuzz_below(fuzz_bytes *b, unsigned n) { return fuzz_u8(b) % n; }

/* A float that is often one of the values that break arithmetic: zeros of both signs, denormals,
   the largest float, infinities, NaN, values past a float's reach when squared, and otherwise
   small ordinary numbers or any 32 bits at all. */
static inline float fuzz_float(fuzz_bytes *b)
{
    static const float special[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 2.0f, 1e-3f, 1e-40f, -1e-45f, FLT_MIN, FLT_MAX, -FLT_MAX,
                                    1e20f, -1e20f, 1e30f, 3.14159265f};
    unsigned k = fuzz_u8(b);
    uint32_t bits;
    float f;
    if (k < 128) return (float)((int)k - 64) / 16.0f;
    if (k < 128 + 16) return special[k - 128];
    if (k < 150) return INFINITY;
    if (k < 156) return -INFINITY;
    if (k < 162) return NAN;
    bits = fuzz_u32(b);
    memcpy(&f, &bits, sizeof f);
    return f;
}
static inline double fuzz_double(fuzz_bytes *b)
{
    unsigned k = fuzz_u8(b);
    uint64_t bits;
    double d;
    if (k < 200) return (double)((int)k - 100) / 16.0;
    if (k < 220) return (double)fuzz_float(b);
    if (k == 220) return 1e300;
    if (k == 221) return DBL_MIN / 4;
    bits = (uint64_t)fuzz_u32(b) | (uint64_t)fuzz_u32(b) << 32;
    memcpy(&d, &bits, sizeof d);
    return d;
}
/* An int that is usually 0..limit-1, sometimes negative or near INT32_MAX: the values a desc must
   refuse, never a large valid one that would only make an execution slow. */
static inline int fuzz_int(fuzz_bytes *b, int limit)
{
    unsigned k = fuzz_u8(b);
    if (k < 244) return (int)(k % (unsigned)limit);
    if (k < 250) return -1 - (int)(k - 244) * 1000;
    return INT32_MAX - (int)(k - 250);
}
/* A count the API takes without an upper limit (samples, rays): 0..limit-1, or negative (refused);
   never one so large that it only asks for hours of valid work. */
static inline int fuzz_count(fuzz_bytes *b, int limit)
{
    unsigned k = fuzz_u8(b);
    return k < 248 ? (int)(k % (unsigned)limit) : -1 - (int)(k - 248);
}
/* fuzz_int's small values moved up to lo .. lo+limit-1; its values to refuse kept. */
static inline int fuzz_int_from(fuzz_bytes *b, int lo, int limit)
{
    int v = fuzz_int(b, limit);
    return v >= 0 && v < limit ? lo + v : v;
}
#endif
