/* fuzz/fuzz_ply.c - libFuzzer harness: PLY, ASCII and binary_little_endian through voxgi_io_load_mesh_memory. */
#include "fuzz_mesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_mesh(data, size, "fuzz.ply");
    return 0;
}
