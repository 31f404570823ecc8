/* fuzz/fuzz_glb.c - libFuzzer harness: binary glTF (.glb: the chunk structure, then the same JSON and its BIN chunk) through voxgi_io_load_mesh_memory. */
#include "fuzz_mesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_mesh(data, size, "fuzz.glb");
    return 0;
}
