/* fuzz/fuzz_binvox.c - libFuzzer harness: voxgi_binvox_read on the bytes as a stream (fmemopen).
 * The first call learns the grid; a grid it accepts must be one voxgi accepts (voxgi_validate_grid,
 * where only the fuzzing context's memory budget may refuse it); then, where the bits are at most
 * 1 MiB, the second call reads them into a buffer of exactly the size the first one asked for. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L /* fmemopen */
#endif
#include "fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    voxgi_context *ctx = fuzz_context();
    voxgi_grid grid;
    size_t needed = 0;
    uint32_t *bits;
    FILE *f;
    voxgi_result r;
    if (!size || !(f = fmemopen((void *)(uintptr_t)data, size, "rb"))) return 0;
    r = voxgi_binvox_read(f, &grid, NULL, 0, &needed);
    if (r == VOXGI_OK) {
        voxgi_result valid = voxgi_validate_grid(ctx, &grid);
        FUZZ_CHECK(valid == VOXGI_OK || valid == VOXGI_ERR_TOO_LARGE); /* larger than the harness's memory budget */
        FUZZ_CHECK(needed == (size_t)((voxgi_grid_voxel_count(&grid) + 31) / 32 * 4));
        if (needed <= ((size_t)1 << 20) && (bits = (uint32_t *)malloc(needed)) != NULL) {
            rewind(f);
            r = voxgi_binvox_read(f, &grid, bits, needed, NULL);
            FUZZ_CHECK(r == VOXGI_OK || r == VOXGI_ERR_FORMAT);
            free(bits);
        }
    } else {
        FUZZ_CHECK(r == VOXGI_ERR_FORMAT || r == VOXGI_ERR_TOO_LARGE);
    }
    fclose(f);
    return 0;
}
