/* fuzz/fuzz_mtl.c - libFuzzer harness: the MTL parser. MTL files are read only beside an OBJ file
 * (voxgi_io_load_mesh), so the bytes become a file in a directory of this process's own, next to
 * a fixed OBJ whose faces use materials "a" and "b" of it. */
#ifndef _XOPEN_SOURCE
#define _XOPEN_SOURCE 700 /* mkdtemp */
#endif
#include "fuzz_mesh.h"

#include <unistd.h>

static char dir[512], obj_path[600], mtl_path[600];

static void remove_files(void)
{
    remove(obj_path);
    remove(mtl_path);
    rmdir(dir);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char obj[] = "mtllib fuzz.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\nf 3 2 1\n";
    voxgi_io_mesh m;
    char err[1024];
    FILE *f;
    if (!dir[0]) {
        /* a file written and read per execution: in memory (/dev/shm) where there is one, 30 times faster than a disk's /tmp */
        const char *base = getenv("TMPDIR");
        if (!base || !*base) base = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
        snprintf(dir, sizeof dir, "%s/voxgi_fuzz_mtl_XXXXXX", base);
        FUZZ_CHECK(mkdtemp(dir) != NULL);
        snprintf(obj_path, sizeof obj_path, "%s/fuzz.obj", dir);
        snprintf(mtl_path, sizeof mtl_path, "%s/fuzz.mtl", dir);
        FUZZ_CHECK((f = fopen(obj_path, "wb")) != NULL);
        FUZZ_CHECK(fwrite(obj, 1, sizeof obj - 1, f) == sizeof obj - 1 && fclose(f) == 0);
        atexit(remove_files);
    }
    FUZZ_CHECK((f = fopen(mtl_path, "wb")) != NULL);
    FUZZ_CHECK(fwrite(data, 1, size, f) == size && fclose(f) == 0);
    fuzz_mesh_check(voxgi_io_load_mesh(obj_path, &m, err, sizeof err), &m, err, sizeof err, dir); /* the message names the OBJ or the MTL file */
    return 0;
}
