/* fuzz/fuzz_obj.c - libFuzzer harness: Wavefront OBJ through voxgi_io_load_mesh_memory (which
 * skips mtllib: fuzz_mtl.c feeds the MTL parser). */
#include "fuzz_mesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_mesh(data, size, "fuzz.obj");
    return 0;
}
