/* fuzz/fuzz_gltf.c - libFuzzer harness: glTF JSON (.gltf: the JSON tokeniser, data-URI buffers, accessors, materials, the node tree) through voxgi_io_load_mesh_memory. */
#include "fuzz_mesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_mesh(data, size, "fuzz.gltf");
    return 0;
}
