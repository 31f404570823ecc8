/* fuzz/fuzz_pfm.c - libFuzzer harness: the tool's PFM reader (tools/image_io.h,
 * vxt_read_pfm_stream) on the bytes as a stream (fmemopen). An image it accepts has the size its
 * header gave, within 1..65536 a side, and finite pixels; a refusal says why. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L /* fmemopen */
#endif
#include "fuzz.h"
#include "../tools/image_io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    float *rgb = NULL;
    int w = 0, h = 0;
    size_t i;
    char err[256] = "";
    FILE *f;
    if (!size || !(f = fmemopen((void *)(uintptr_t)data, size, "rb"))) return 0;
    if (vxt_read_pfm_stream(f, "fuzz.pfm", &rgb, &w, &h, err, sizeof err) == 0) {
        FUZZ_CHECK(rgb && w >= 1 && h >= 1 && w <= 65536 && h <= 65536);
        for (i = 0; i < (size_t)3 * (size_t)w * (size_t)h; i++) FUZZ_CHECK(isfinite(rgb[i]));
        free(rgb);
    } else {
        FUZZ_CHECK(!rgb && strncmp(err, "fuzz.pfm: ", 10) == 0);
    }
    fclose(f);
    return 0;
}
