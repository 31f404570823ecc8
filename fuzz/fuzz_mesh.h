/* fuzz/fuzz_mesh.h - the mesh harnesses' one body: the fuzzer's bytes loaded by
 * voxgi_io_load_mesh_memory under a name whose extension is the harness's format (the content may
 * still pick another loader, as it does for a file), and the check of any load's outcome: it
 * either fails, leaving the mesh empty and a message that names the input, or gives a mesh that
 * callers can use as it is: arrays present, every index and material id in range, every number
 * finite. */
#ifndef VOXGI_FUZZ_MESH_H
#define VOXGI_FUZZ_MESH_H
#include "fuzz.h"
#include "../voxgi_io.h"

static inline int fuzz_all_finite(const float *v, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (!isfinite(v[i])) return 0;
    return 1;
}

/* A load's outcome: rc, the mesh and the message of the input called name. */
static inline void fuzz_mesh_check(int rc, voxgi_io_mesh *mesh, const char *err, size_t err_size, const char *name)
{
    voxgi_io_mesh m = *mesh;
    size_t i;
    if (rc != 0) {
        FUZZ_CHECK(!m.positions && !m.indices && !m.materials && !m.scene_materials && !m.triangle_count);
        FUZZ_CHECK(strncmp(err, name, strlen(name)) == 0 && strlen(err) < err_size);
        return;
    }
    FUZZ_CHECK(m.positions && m.indices && m.material_ids && m.materials && m.scene_materials);
    FUZZ_CHECK(m.vertex_count > 0 && m.triangle_count > 0 && m.material_count > 0);
    for (i = 0; i < 3 * m.triangle_count; i++) FUZZ_CHECK(m.indices[i] < m.vertex_count);
    for (i = 0; i < m.triangle_count; i++) FUZZ_CHECK(m.material_ids[i] < m.material_count);
    FUZZ_CHECK(fuzz_all_finite(m.positions, 3 * m.vertex_count));
    FUZZ_CHECK(!m.normals || fuzz_all_finite(m.normals, 3 * m.vertex_count));
    FUZZ_CHECK(!m.uvs || fuzz_all_finite(m.uvs, 2 * m.vertex_count));
    for (i = 0; i < m.material_count; i++) {
        FUZZ_CHECK(memchr(m.materials[i].name, 0, sizeof m.materials[i].name) != NULL);
        FUZZ_CHECK(fuzz_all_finite(m.materials[i].albedo, 3) && fuzz_all_finite(m.materials[i].emission, 3) && isfinite(m.materials[i].opacity));
    }
    FUZZ_CHECK(m.mesh.positions == m.positions && m.mesh.vertex_count == m.vertex_count && m.mesh.index_count == 3 * m.triangle_count);
    voxgi_io_mesh_free(mesh);
}

static inline void fuzz_mesh(const uint8_t *data, size_t size, const char *name)
{
    voxgi_io_mesh m;
    char err[256];
    int rc = voxgi_io_load_mesh_memory(data, size, name, &m, err, sizeof err);
    fuzz_mesh_check(rc, &m, err, sizeof err, name);
}
#endif
