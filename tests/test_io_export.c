/* tests/test_io_export.c - voxgi_io.h's exports (.vox, .npy, PLY points, OBJ outer faces), each read
 * back by a reader written here from the format's description (not from the writer), and numpy's
 * own reader where python3 has numpy.
 *
 * The grid: 300 x 20 x 20 unit voxels at the origin, so that MagicaVoxel's 256 limit splits it in
 * two models. Three coloured quads, voxelized conservatively with their albedo: a floor lying on
 * the plane y = 3 (two layers of voxels, so faces between set voxels exist), a wall at x = 270.3
 * (in the second model) and a slanted quad across both models (voxels with mixed albedo). */
#define _XOPEN_SOURCE 700 /* mkdtemp */
#include "harness.h"
#include "fixtures.h"
#include "../voxgi_io.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#define GX 300
#define GY 20
#define GZ 20

static char tmp_dir[512];
static voxgi_context *ctx;
static voxgi_voxels *vox;    /* the three quads, with ALBEDO */
static uint32_t *truth_bits; /* read back through voxgi.h */
static float *truth_albedo;  /* 3 per set voxel, in bit-grid order */
static uint64_t truth_count;

static const char *tmp_path(const char *name)
{
    static char ring[4][1024];
    static int next;
    char *path = ring[next++ % 4];
    snprintf(path, sizeof ring[0], "%s/%s", tmp_dir, name);
    return path;
}

static uint64_t lin(int i, int j, int k) { return (uint64_t)i + (uint64_t)GX * ((uint64_t)j + (uint64_t)GY * (uint64_t)k); }
static int truth_set(int i, int j, int k)
{
    if (i < 0 || j < 0 || k < 0 || i >= GX || j >= GY || k >= GZ) return 0;
    return voxgi_bit_get(truth_bits, lin(i, j, k));
}
static uint32_t *truth_rows; /* per voxel: the set voxels before it, counted one by one */
/* The albedo row of set voxel idx. */
static uint64_t truth_row(uint64_t idx) { return truth_rows[idx]; }
/* IEC 61966-2-1's sRGB encoding. */
static double srgb_of(double c)
{
    if (c <= 0) return 0;
    if (c >= 1) return 1;
    return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1 / 2.4) - 0.055;
}

static unsigned char *read_all(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    unsigned char *data;
    long n;
    *size = 0;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    data = (unsigned char *)malloc((size_t)n + 1);
    if (data && fread(data, 1, (size_t)n, f) != (size_t)n) { free(data); data = NULL; }
    fclose(f);
    if (data) data[n] = 0, *size = (size_t)n;
    return data;
}
static uint32_t le32(const unsigned char *p) { return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24; }

static void make_voxels(void)
{
    static const voxgi_material mats[3] = {{{0.8f, 0.1f, 0.1f}, {0, 0, 0}, 0}, {{0.1f, 0.2f, 0.9f}, {0, 0, 0}, 0}, {{0.2f, 0.7f, 0.3f}, {0, 0, 0}, 0}};
    static const float floor_quad[12] = {0.5f, 3, 0.5f, 0.5f, 3, 19.5f, 299.5f, 3, 19.5f, 299.5f, 3, 0.5f};
    static const float wall[12] = {270.3f, 0.5f, 2.5f, 270.3f, 19.5f, 2.5f, 270.3f, 19.5f, 17.5f, 270.3f, 0.5f, 17.5f};
    static const float slant[12] = {10, 5, 1, 290, 5, 1, 290, 18, 19, 10, 18, 19};
    static quads q;
    static voxgi_scene sc;
    static voxgi_mesh mesh;
    voxgi_voxelize_desc vd;
    voxgi_voxels_info info;
    size_t need = 0;
    quad(&q, floor_quad, 0);
    quad(&q, wall, 1);
    quad(&q, slant, 2);
    scene_of_quads(&sc, &mesh, &q, mats, 3, NULL, 0);
    memset(&vd, 0, sizeof vd);
    vd.grid.voxel_size = 1;
    vd.grid.res[0] = GX, vd.grid.res[1] = GY, vd.grid.res[2] = GZ;
    vd.method = VOXGI_METHOD_CONSERVATIVE;
    vd.attributes = VOXGI_ATTRIBUTE_ALBEDO;
    if (!(ctx = make_ctx(VOXGI_BACKEND_CPU, 0)) || voxgi_voxelize(ctx, &sc, &vd, &vox) != VOXGI_OK) {
        printf("cannot voxelize the test scene: %s\n", ctx ? voxgi_last_error(ctx) : "no context");
        exit(1);
    }
    voxgi_voxels_query(vox, &info);
    voxgi_voxels_read(ctx, vox, NULL, 0, &need);
    truth_bits = (uint32_t *)malloc(need);
    voxgi_voxels_read(ctx, vox, truth_bits, need, NULL);
    truth_albedo = attr_read(ctx, vox, VOXGI_ATTRIBUTE_ALBEDO);
    truth_count = info.voxel_count;
    truth_rows = (uint32_t *)malloc((size_t)GX * GY * GZ * sizeof *truth_rows);
    if (truth_rows) {
        uint64_t q, n = 0;
        for (q = 0; q < (uint64_t)GX * GY * GZ; q++) truth_rows[q] = (uint32_t)n, n += (uint64_t)voxgi_bit_get(truth_bits, q);
    }
    if (!truth_albedo || !truth_rows || truth_count < 1000) {
        printf("the test scene gave %llu voxels and %s albedo\n", (unsigned long long)truth_count, truth_albedo ? "an" : "no");
        exit(1);
    }
}

/* ------------------------------------------------------------------ .vox */

/* A .vox reader from MagicaVoxel's format description: chunks under MAIN; SIZE + XYZI per model;
   the scene graph nTRN (with _t) -> nGRP -> nTRN -> nSHP; RGBA entry e is colour index e + 1. A
   model's voxel v lies at _t + v - floor(size / 2). */
#define VOX_MAX_MODELS 16
#define VOX_MAX_NODES 64
typedef struct vox_file {
    int models, size[VOX_MAX_MODELS][3];
    const unsigned char *xyzi[VOX_MAX_MODELS];
    uint32_t count[VOX_MAX_MODELS];
    int node_kind[VOX_MAX_NODES]; /* 0 none, 1 nTRN, 2 nGRP, 3 nSHP */
    int trn_child[VOX_MAX_NODES], trn_t[VOX_MAX_NODES][3], grp_n[VOX_MAX_NODES], grp_child[VOX_MAX_NODES][VOX_MAX_MODELS], shp_model[VOX_MAX_NODES];
    unsigned char palette[256][4];
    int have_palette;
} vox_file;

/* Reads a DICT at p; the value of "_t" as three ints into t when present. Returns the end. */
static const unsigned char *vox_dict(const unsigned char *p, int t[3])
{
    uint32_t n = le32(p), e;
    p += 4;
    for (e = 0; e < n; e++) {
        uint32_t kl = le32(p), vl;
        const unsigned char *key = p + 4;
        p += 4 + kl;
        vl = le32(p);
        if (t && kl == 2 && !memcmp(key, "_t", 2)) {
            char value[64];
            snprintf(value, sizeof value, "%.*s", (int)vl, (const char *)p + 4);
            if (sscanf(value, "%d %d %d", &t[0], &t[1], &t[2]) != 3) TH_CHECK(0, "_t '%s' is not three integers", value);
        }
        p += 4 + vl;
    }
    return p;
}

static int vox_parse(const unsigned char *d, size_t size, vox_file *v)
{
    const unsigned char *p, *end;
    memset(v, 0, sizeof *v);
    if (size < 20 || memcmp(d, "VOX ", 4) || le32(d + 4) != 150 || memcmp(d + 8, "MAIN", 4) || le32(d + 12) != 0) return 0;
    if (le32(d + 16) != size - 20) { TH_CHECK(0, "MAIN's children hold %u bytes, the file %lu after MAIN's header", le32(d + 16), (unsigned long)size - 20); return 0; }
    for (p = d + 20, end = d + size; p + 12 <= end;) {
        uint32_t content = le32(p + 4), children = le32(p + 8);
        const unsigned char *c = p + 12;
        if (c + content + children > end) return 0;
        if (!memcmp(p, "SIZE", 4) && v->models < VOX_MAX_MODELS) {
            v->size[v->models][0] = (int)le32(c), v->size[v->models][1] = (int)le32(c + 4), v->size[v->models][2] = (int)le32(c + 8);
        } else if (!memcmp(p, "XYZI", 4) && v->models < VOX_MAX_MODELS) {
            v->count[v->models] = le32(c);
            TH_CHECK(content == 4 + 4 * v->count[v->models], "XYZI of %u voxels has %u bytes", v->count[v->models], content);
            v->xyzi[v->models++] = c + 4;
        } else if (!memcmp(p, "RGBA", 4) && content == 1024) {
            memcpy(v->palette, c, 1024);
            v->have_palette = 1;
        } else if (!memcmp(p, "nTRN", 4) || !memcmp(p, "nGRP", 4) || !memcmp(p, "nSHP", 4)) {
            uint32_t id = le32(c);
            const unsigned char *q = vox_dict(c + 4, NULL);
            if (id >= VOX_MAX_NODES) return 0;
            if (!memcmp(p, "nTRN", 4)) {
                uint32_t frames, f;
                v->node_kind[id] = 1;
                v->trn_child[id] = (int)le32(q);
                TH_CHECK(le32(q + 4) == UINT32_MAX, "nTRN %u: reserved id %u, not -1", id, le32(q + 4));
                frames = le32(q + 12);
                for (q += 16, f = 0; f < frames; f++) q = vox_dict(q, v->trn_t[id]);
            } else if (!memcmp(p, "nGRP", 4)) {
                uint32_t k;
                v->node_kind[id] = 2;
                v->grp_n[id] = (int)le32(q);
                for (k = 0; k < le32(q) && k < VOX_MAX_MODELS; k++) v->grp_child[id][k] = (int)le32(q + 4 + 4 * k);
                q += 4 + 4 * le32(q);
            } else {
                v->node_kind[id] = 3;
                TH_CHECK(le32(q) == 1, "nSHP %u holds %u models", id, le32(q));
                v->shp_model[id] = (int)le32(q + 4);
                q = vox_dict(q + 8, NULL);
            }
            TH_CHECK(q == c + content, "%.4s %u: %ld bytes read of %u", (const char *)p, id, (long)(q - c), content);
        }
        p = c + content + children;
    }
    return p == end;
}

/* .vox round trip: the voxels placed by the scene graph are exactly the grid's (MagicaVoxel
   (x,y,z) = (i, 19 - k, j)), two models of 256 x 20 x 20 and 44 x 20 x 20 with _t (128,10,10) and
   (278,10,10), and each voxel's palette colour is its albedo's sRGB within half a palette step
   (25.5 red and blue, 21.25 green; +1 for rounding). */
static void test_vox_round_trip(void)
{
    char err[512];
    size_t size;
    unsigned char *d;
    uint8_t *seen = (uint8_t *)calloc((size_t)GX * GY * GZ, 1);
    vox_file v;
    int m, node, placed_models = 0;
    uint64_t placed = 0, wrong_colour = 0;
    double worst[3] = {0, 0, 0};
    TH_CHECK(voxgi_io_write_vox(ctx, vox, tmp_path("grid.vox"), err, sizeof err) == 0, "write: %s", err);
    d = read_all(tmp_path("grid.vox"), &size);
    TH_CHECK(d && vox_parse(d, size, &v), "the .vox chunks do not parse (%lu bytes)", (unsigned long)size);
    if (!d || !seen || th_.cur_failed) { free(d); free(seen); return; }
    TH_CHECK(v.models == 2 && v.have_palette, "%d models, palette %d", v.models, v.have_palette);
    TH_CHECK(v.node_kind[0] == 1 && v.node_kind[v.trn_child[0]] == 2, "the root is not nTRN -> nGRP");
    node = v.trn_child[0];
    for (m = 0; m < v.grp_n[node] && m < VOX_MAX_MODELS; m++) {
        int trn = v.grp_child[node][m], shp = v.trn_child[trn], model = v.shp_model[shp], c;
        const int *t = v.trn_t[trn], *s;
        uint32_t e;
        TH_CHECK(v.node_kind[trn] == 1 && v.node_kind[shp] == 3 && model >= 0 && model < v.models, "group child %d is not nTRN -> nSHP", m);
        if (th_.cur_failed) break;
        s = v.size[model];
        for (c = 0; c < 3; c++) TH_CHECK(s[c] >= 1 && s[c] <= 256, "model %d size %d on axis %d", model, s[c], c);
        placed_models++;
        for (e = 0; e < v.count[model]; e++) {
            const unsigned char *q = v.xyzi[model] + 4 * e;
            int x = t[0] + q[0] - s[0] / 2, y = t[1] + q[1] - s[1] / 2, z = t[2] + q[2] - s[2] / 2;
            int i = x, j = z, k = GZ - 1 - y, index = q[3];
            uint64_t idx;
            const unsigned char *rgba;
            if (!truth_set(i, j, k) || q[0] >= s[0] || q[1] >= s[1] || q[2] >= s[2]) {
                TH_CHECK(0, "model %d voxel (%d,%d,%d) at (%d,%d,%d): voxel (%d,%d,%d) is not set", model, q[0], q[1], q[2], x, y, z, i, j, k);
                continue;
            }
            idx = lin(i, j, k);
            TH_CHECK(!seen[idx]++, "voxel (%d,%d,%d) twice", i, j, k);
            placed++;
            TH_CHECK(index >= 1, "colour index 0 (empty) at (%d,%d,%d)", i, j, k);
            rgba = v.palette[(index + 255) % 256]; /* entry index - 1 */
            for (c = 0; c < 3; c++) {
                double want = 255 * srgb_of(truth_albedo[3 * truth_row(idx) + (uint64_t)c]), diff = fabs(rgba[c] - want);
                if (diff > worst[c]) worst[c] = diff;
                if (diff > (c == 1 ? 21.25 : 25.5) + 1) wrong_colour++;
            }
        }
    }
    TH_CHECK(placed_models == 2 && placed == truth_count, "%d models placed %llu voxels of %llu", placed_models, (unsigned long long)placed,
             (unsigned long long)truth_count);
    TH_CHECK(v.size[0][0] == 256 && v.size[1][0] == 44 && v.size[0][1] == 20 && v.size[0][2] == 20, "model sizes %dx%dx%d, %dx%dx%d", v.size[0][0],
             v.size[0][1], v.size[0][2], v.size[1][0], v.size[1][1], v.size[1][2]);
    TH_CHECK(!wrong_colour, "%llu channels off their palette colour by more than half a step (worst %.1f %.1f %.1f)", (unsigned long long)wrong_colour,
             worst[0], worst[1], worst[2]);
    printf("    %llu voxels in 2 models, _t (%d %d %d) and (%d %d %d); worst palette error %.1f %.1f %.1f\n", (unsigned long long)placed,
           v.trn_t[2][0], v.trn_t[2][1], v.trn_t[2][2], v.trn_t[4][0], v.trn_t[4][1], v.trn_t[4][2], worst[0], worst[1], worst[2]);
    free(d);
    free(seen);
}

/* ------------------------------------------------------------------ .npy */

/* The .npy format 1.0 header: magic, version, length, then a Python dict literal. */
typedef struct npy_file { char descr[16]; int fortran, dims, shape[4]; const unsigned char *data; size_t data_size; } npy_file;

static int npy_parse(const unsigned char *d, size_t size, npy_file *n)
{
    size_t hlen;
    const char *h, *s;
    char header[1024];
    memset(n, 0, sizeof *n);
    if (size < 10 || memcmp(d, "\x93NUMPY", 6) || d[6] != 1 || d[7] != 0) return 0;
    hlen = (size_t)d[8] | (size_t)d[9] << 8;
    if (10 + hlen > size || hlen >= sizeof header) return 0;
    TH_CHECK((10 + hlen) % 16 == 0 && d[10 + hlen - 1] == '\n', "header of %lu bytes, not aligned to 16 or not ending in a newline", (unsigned long)hlen);
    memcpy(header, d + 10, hlen);
    header[hlen] = 0;
    h = header;
    if (!(s = strstr(h, "'descr': '")) || sscanf(s + 10, "%15[^']", n->descr) != 1) return 0;
    if (!(s = strstr(h, "'fortran_order': "))) return 0;
    n->fortran = !strncmp(s + 17, "True", 4);
    if (!n->fortran && strncmp(s + 17, "False", 5)) return 0;
    if (!(s = strstr(h, "'shape': ("))) return 0;
    for (s += 10; n->dims < 4 && *s != ')';) {
        char *e;
        n->shape[n->dims++] = (int)strtol(s, &e, 10);
        if (e == s) return 0;
        for (s = e; *s == ',' || *s == ' '; s++) {}
    }
    n->data = d + 10 + hlen;
    n->data_size = size - 10 - hlen;
    return 1;
}

/* The element offset of [i, j, k, c] in an array of shape (GX, GY, GZ, w), in its stated order. */
static size_t npy_offset(const npy_file *n, int i, int j, int k, int c, int w)
{
    if (n->fortran) return (size_t)i + (size_t)GX * ((size_t)j + (size_t)GY * ((size_t)k + (size_t)GZ * (size_t)c));
    return (((size_t)i * GY + (size_t)j) * GZ + (size_t)k) * (size_t)w + (size_t)c;
}

/* .npy round trip: occupancy '|u1' of shape (300, 20, 20), [i, j, k] = voxel (i, j, k), read in
   the order the header states; albedo '<f4' of shape (300, 20, 20, 3) equal to
   voxgi_voxels_read_attribute's floats bit for bit, 0 at empty voxels. */
static void test_npy_round_trip(void)
{
    char err[512];
    size_t size;
    unsigned char *d;
    npy_file n;
    int i, j, k, c;
    uint64_t wrong = 0, ones = 0;
    TH_CHECK(voxgi_io_write_npy(ctx, vox, tmp_path("grid.npy"), err, sizeof err) == 0, "write: %s", err);
    d = read_all(tmp_path("grid.npy"), &size);
    TH_CHECK(d && npy_parse(d, size, &n), "the .npy header does not parse");
    if (!d || th_.cur_failed) { free(d); return; }
    TH_CHECK(!strcmp(n.descr, "|u1") && n.dims == 3 && n.shape[0] == GX && n.shape[1] == GY && n.shape[2] == GZ && n.data_size == (size_t)GX * GY * GZ,
             "descr %s, %d dims (%d %d %d), %lu bytes of data", n.descr, n.dims, n.shape[0], n.shape[1], n.shape[2], (unsigned long)n.data_size);
    if (th_.cur_failed) { free(d); return; }
    for (i = 0; i < GX; i++)
        for (j = 0; j < GY; j++)
            for (k = 0; k < GZ; k++) {
                unsigned char b = n.data[npy_offset(&n, i, j, k, 0, 1)];
                wrong += b != (unsigned char)truth_set(i, j, k);
                ones += b == 1;
            }
    TH_CHECK(!wrong && ones == truth_count, "occupancy: %llu cells wrong, %llu ones of %llu", (unsigned long long)wrong, (unsigned long long)ones,
             (unsigned long long)truth_count);
    free(d);
    TH_CHECK(voxgi_io_write_npy_attribute(ctx, vox, VOXGI_ATTRIBUTE_ALBEDO, tmp_path("albedo.npy"), err, sizeof err) == 0, "write albedo: %s", err);
    d = read_all(tmp_path("albedo.npy"), &size);
    TH_CHECK(d && npy_parse(d, size, &n), "the albedo .npy header does not parse");
    if (!d || th_.cur_failed) { free(d); return; }
    TH_CHECK(!strcmp(n.descr, "<f4") && n.dims == 4 && n.shape[0] == GX && n.shape[3] == 3 && n.data_size == (size_t)GX * GY * GZ * 12,
             "albedo: descr %s, %d dims, %lu bytes", n.descr, n.dims, (unsigned long)n.data_size);
    if (th_.cur_failed) { free(d); return; }
    for (wrong = 0, i = 0; i < GX; i++)
        for (j = 0; j < GY; j++)
            for (k = 0; k < GZ; k++)
                for (c = 0; c < 3; c++) {
                    uint32_t u = le32(n.data + 4 * npy_offset(&n, i, j, k, c, 3));
                    float got, want = truth_set(i, j, k) ? truth_albedo[3 * truth_row(lin(i, j, k)) + (uint64_t)c] : 0.0f;
                    memcpy(&got, &u, 4);
                    wrong += memcmp(&got, &want, 4) != 0;
                }
    TH_CHECK(!wrong, "albedo: %llu values differ", (unsigned long long)wrong);
    free(d);
}

/* numpy.load of both files (tools/deps.sh installs Debian's numpy; the first python3 on PATH, or
   $VOXGI_PYTHON, that imports it; skipped loudly where none does): shape, dtype, the count of ones
   and sum(i + 1000 j + 1000000 k) over them, and the albedo's sum, against the same sums over
   voxgi's bits and attribute. */
static void test_npy_numpy_load(void)
{
    char python[512] = "", cmd[2048], line[512], err[512];
    double want_sum = 0, want_albedo = 0, got_sum = -1, got_albedo = -1, got_count = -1;
    int i, j, k, c, ok = 0;
    FILE *p = popen("for p in ${VOXGI_PYTHON:-} $(which -a python3 2>/dev/null); do \"$p\" -c 'import numpy' >/dev/null 2>&1 && { echo \"$p\"; exit 0; }; "
                    "done; exit 1", "r");
    if (p) {
        if (fgets(python, sizeof python, p)) python[strcspn(python, "\n")] = 0;
        pclose(p);
    }
    if (!python[0]) {
        th_skip("no python3 on PATH imports numpy (tools/deps.sh installs python3-numpy): numpy.load not tried (the test's own .npy reader still ran)");
        return;
    }
    TH_CHECK(voxgi_io_write_npy(ctx, vox, tmp_path("np.npy"), err, sizeof err) == 0, "write: %s", err);
    TH_CHECK(voxgi_io_write_npy_attribute(ctx, vox, VOXGI_ATTRIBUTE_ALBEDO, tmp_path("np_albedo.npy"), err, sizeof err) == 0, "write: %s", err);
    for (i = 0; i < GX; i++)
        for (j = 0; j < GY; j++)
            for (k = 0; k < GZ; k++)
                if (truth_set(i, j, k)) {
                    want_sum += i + 1000.0 * j + 1000000.0 * k;
                    for (c = 0; c < 3; c++) want_albedo += truth_albedo[3 * truth_row(lin(i, j, k)) + (uint64_t)c];
                }
    snprintf(cmd, sizeof cmd,
             "'%s' -c \"import numpy as n; a=n.load('%s'); b=n.load('%s'); i,j,k=n.nonzero(a); "
             "print(a.shape==(%d,%d,%d) and a.dtype==n.uint8 and b.shape==(%d,%d,%d,3) and b.dtype==n.float32, len(i), "
             "float((i+1000.0*j+1000000.0*k).sum()), float(b.astype(n.float64).sum()))\"",
             python, tmp_path("np.npy"), tmp_path("np_albedo.npy"), GX, GY, GZ, GX, GY, GZ);
    p = popen(cmd, "r");
    if (p && fgets(line, sizeof line, p)) ok = sscanf(line, "True %lf %lf %lf", &got_count, &got_sum, &got_albedo) == 3;
    if (p) pclose(p);
    TH_CHECK(ok && got_count == (double)truth_count && got_sum == want_sum && fabs(got_albedo - want_albedo) < 1e-6 * want_albedo,
             "numpy: %s (want %llu ones, sum %.0f, albedo %.6f)", ok ? line : "no answer", (unsigned long long)truth_count, want_sum, want_albedo);
    printf("    numpy.load: %.0f ones, index sum %.0f, albedo sum %.6f (voxgi: %.6f)\n", got_count, got_sum, got_albedo, want_albedo);
}

/* ------------------------------------------------------------------ PLY points, OBJ faces */

/* PLY round trip: the header (binary_little_endian, vertex count, float x y z and uchar red green
   blue) and exactly 15 bytes per vertex; every vertex is the centre of a distinct set voxel, all
   are there, and each colour is round(255 sRGB(albedo)) within 1. */
static void test_ply_points_round_trip(void)
{
    static const char *const want[] = {"ply", "format binary_little_endian 1.0", "element vertex", "property float x", "property float y",
                                       "property float z", "property uchar red", "property uchar green", "property uchar blue", "end_header"};
    char err[512];
    size_t size, at = 0;
    unsigned char *d;
    uint8_t *seen = (uint8_t *)calloc((size_t)GX * GY * GZ, 1);
    unsigned long long vertices = 0, e, wrong = 0, off_colour = 0;
    int w = 0;
    TH_CHECK(voxgi_io_write_ply_points(ctx, vox, tmp_path("points.ply"), err, sizeof err) == 0, "write: %s", err);
    d = read_all(tmp_path("points.ply"), &size);
    TH_CHECK(d != NULL && seen != NULL, "nothing written");
    if (!d || !seen) { free(d); free(seen); return; }
    while (at < size && w < 10) { /* header lines; comments skipped */
        const char *line = (const char *)d + at, *nl = memchr(line, '\n', size - at);
        size_t len = nl ? (size_t)(nl - line) : 0;
        if (!nl) break;
        at += len + 1;
        if (!strncmp(line, "comment ", 8)) continue;
        TH_CHECK(!strncmp(line, want[w], strlen(want[w])), "header line '%.*s', want '%s'", (int)len, line, want[w]);
        if (w == 2) vertices = strtoull(line + 14, NULL, 10);
        w++;
    }
    TH_CHECK(w == 10 && vertices == truth_count && size - at == vertices * 15, "%d header lines, %llu vertices (%llu set), %lu data bytes", w, vertices,
             (unsigned long long)truth_count, (unsigned long)(size - at));
    for (e = 0; !th_.cur_failed && e < vertices; e++) {
        const unsigned char *v = d + at + 15 * e;
        float p[3];
        int c, ijk[3];
        for (c = 0; c < 3; c++) {
            uint32_t u = le32(v + 4 * c);
            memcpy(&p[c], &u, 4);
            ijk[c] = (int)floorf(p[c]);
            if (p[c] != (float)ijk[c] + 0.5f) wrong++;
        }
        if (!truth_set(ijk[0], ijk[1], ijk[2]) || seen[lin(ijk[0], ijk[1], ijk[2])]++) { wrong++; continue; }
        for (c = 0; c < 3; c++) {
            double want_byte = floor(255 * srgb_of(truth_albedo[3 * truth_row(lin(ijk[0], ijk[1], ijk[2])) + (uint64_t)c]) + 0.5);
            if (fabs(v[12 + c] - want_byte) > 1) off_colour++;
        }
    }
    TH_CHECK(!wrong && !off_colour, "%llu vertices not at a distinct set voxel's centre, %llu colours off", wrong, off_colour);
    free(d);
    free(seen);
}

/* The outer faces by brute force: per set voxel, its neighbours that are empty or outside. */
static unsigned long long exposed_faces(void)
{
    unsigned long long n = 0;
    int i, j, k;
    for (i = 0; i < GX; i++)
        for (j = 0; j < GY; j++)
            for (k = 0; k < GZ; k++)
                if (truth_set(i, j, k))
                    n += (unsigned long long)(!truth_set(i - 1, j, k) + !truth_set(i + 1, j, k) + !truth_set(i, j - 1, k) + !truth_set(i, j + 1, k) +
                                              !truth_set(i, j, k - 1) + !truth_set(i, j, k + 1));
    return n;
}

/* OBJ outer faces: as many quads as the brute-force count of exposed faces; each an axis-aligned
   unit square whose normal (from its counter-clockwise corners) points from a set voxel into an
   empty one (or out of the grid), and no face twice. */
static void test_obj_faces_round_trip(void)
{
    char err[512], line[256];
    float (*v)[3] = NULL;
    size_t nv = 0, cap = 0;
    unsigned long long faces = 0, bad = 0, want = exposed_faces();
    uint8_t *seen = (uint8_t *)calloc((size_t)GX * GY * GZ, 1); /* bit per face direction */
    FILE *f;
    TH_CHECK(voxgi_io_write_obj_faces(ctx, vox, tmp_path("faces.obj"), err, sizeof err) == 0, "write: %s", err);
    f = fopen(tmp_path("faces.obj"), "r");
    TH_CHECK(f != NULL && seen != NULL, "nothing written");
    if (!f || !seen) { if (f) fclose(f); free(seen); return; }
    while (fgets(line, sizeof line, f)) {
        unsigned long a[4];
        if (line[0] == 'v' && line[1] == ' ') {
            if (nv == cap && !(v = (float (*)[3])realloc(v, (cap = cap ? 2 * cap : 1024) * sizeof *v))) break;
            if (sscanf(line + 2, "%f %f %f", &v[nv][0], &v[nv][1], &v[nv][2]) != 3) bad++;
            nv++;
        } else if (line[0] == 'f' && line[1] == ' ') {
            double e1[3], e2[3], n[3], centre[3] = {0, 0, 0};
            int q, c, axis = -1, in[3], out[3];
            faces++;
            if (sscanf(line + 2, "%lu %lu %lu %lu", &a[0], &a[1], &a[2], &a[3]) != 4 || !a[0] || !a[1] || !a[2] || !a[3] || a[0] > nv || a[1] > nv ||
                a[2] > nv || a[3] > nv) { bad++; continue; }
            for (c = 0; c < 3; c++) {
                e1[c] = v[a[1] - 1][c] - v[a[0] - 1][c], e2[c] = v[a[2] - 1][c] - v[a[0] - 1][c];
                for (q = 0; q < 4; q++) centre[c] += v[a[q] - 1][c] / 4.0;
            }
            n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
            for (c = 0; c < 3; c++)
                if (fabs(fabs(n[c]) - 1) < 1e-6) axis = c;
            if (axis < 0) { bad++; continue; }
            for (c = 0; c < 3; c++) {
                in[c] = (int)floor(centre[c] - 0.5 * n[c]);
                out[c] = (int)floor(centre[c] + 0.5 * n[c]);
            }
            if (!truth_set(in[0], in[1], in[2]) || truth_set(out[0], out[1], out[2])) { bad++; continue; }
            q = 1 << (2 * axis + (n[axis] > 0));
            if (seen[lin(in[0], in[1], in[2])] & q) bad++;
            seen[lin(in[0], in[1], in[2])] |= (uint8_t)q;
        }
    }
    fclose(f);
    TH_CHECK(faces == want && !bad && nv == 4 * faces, "%llu faces (%llu exposed by brute force), %llu bad, %lu vertices", faces, want, bad, (unsigned long)nv);
    printf("    %llu outer faces of %llu voxels\n", faces, (unsigned long long)truth_count);
    free(v);
    free(seen);
}

/* ------------------------------------------------------------------ refusals */

/* Bad inputs: NULL voxels, context or path; a path under a regular file (the message names the file
   and strerror(ENOTDIR)); /dev/full, where writing fails (strerror(ENOSPC)); an attribute the voxels
   lack or that is not exportable. An empty grid is accepted: each file holds no voxel. */
static void test_export_refusals(void)
{
    typedef int (*writer)(voxgi_context *, const voxgi_voxels *, const char *, char *, size_t);
    static const writer writers[4] = {voxgi_io_write_vox, voxgi_io_write_npy, voxgi_io_write_ply_points, voxgi_io_write_obj_faces};
    static const char *const names[4] = {"x.vox", "x.npy", "x.ply", "x.obj"};
    static const float far_triangle[9] = {100, 100, 100, 101, 100, 100, 100, 101, 100};
    char err[512], path[1024], want[1200];
    voxgi_voxels *empty = NULL;
    voxgi_voxelize_desc vd;
    voxgi_scene sc;
    voxgi_mesh mesh;
    FILE *f;
    int w;
    snprintf(path, sizeof path, "%s", tmp_path("plain_file"));
    f = fopen(path, "w");
    if (f) fclose(f);
    memset(&vd, 0, sizeof vd);
    vd.grid.voxel_size = 1;
    vd.grid.res[0] = vd.grid.res[1] = vd.grid.res[2] = 4;
    scene_of_triangles(&sc, &mesh, far_triangle, 3, NULL, 0);
    TH_CHECK(voxgi_voxelize(ctx, &sc, &vd, &empty) == VOXGI_OK, "empty grid: %s", voxgi_last_error(ctx));
    for (w = 0; w < 4; w++) {
        char under[1100];
        size_t size;
        unsigned char *d;
        TH_CHECK(writers[w](ctx, NULL, tmp_path(names[w]), err, sizeof err) != 0 && strstr(err, "NULL"), "%s: NULL voxels: %s", names[w], err);
        TH_CHECK(writers[w](NULL, vox, tmp_path(names[w]), err, sizeof err) != 0 && strstr(err, "NULL"), "%s: NULL context: %s", names[w], err);
        TH_CHECK(writers[w](ctx, vox, NULL, err, sizeof err) != 0 && strstr(err, "NULL"), "%s: NULL path: %s", names[w], err);
        TH_CHECK(writers[w](ctx, vox, NULL, NULL, 0) != 0, "%s: NULL path, no err", names[w]);
        snprintf(under, sizeof under, "%s/%s", path, names[w]);
        snprintf(want, sizeof want, "%s: cannot open for writing: %s", under, strerror(ENOTDIR));
        TH_CHECK(writers[w](ctx, vox, under, err, sizeof err) != 0 && !strcmp(err, want), "%s: under a file: '%s', want '%s'", names[w], err, want);
        if ((f = fopen("/dev/full", "wb")) != NULL) {
            fclose(f);
            snprintf(want, sizeof want, "/dev/full: cannot write: %s", strerror(ENOSPC));
            TH_CHECK(writers[w](ctx, vox, "/dev/full", err, sizeof err) != 0 && !strcmp(err, want), "%s: /dev/full: '%s', want '%s'", names[w], err, want);
        }
        if (!empty) continue;
        TH_CHECK(writers[w](ctx, empty, tmp_path(names[w]), err, sizeof err) == 0, "%s: empty grid refused: %s", names[w], err);
        d = read_all(tmp_path(names[w]), &size);
        if (w == 0) {
            vox_file v;
            TH_CHECK(d && vox_parse(d, size, &v) && v.models == 1 && v.count[0] == 0, "empty .vox: %d models", d ? v.models : -1);
        } else if (w == 1) {
            npy_file n;
            TH_CHECK(d && npy_parse(d, size, &n) && n.data_size == 64 && !memchr(n.data, 1, 64), "empty .npy");
        } else if (w == 2)
            TH_CHECK(d && strstr((const char *)d, "element vertex 0\n") && !strcmp((const char *)d + size - 11, "end_header\n"), "empty .ply");
        else
            TH_CHECK(d && !strstr((const char *)d, "\nf "), "empty .obj has faces");
        free(d);
    }
    TH_CHECK(voxgi_io_write_npy_attribute(ctx, vox, VOXGI_ATTRIBUTE_NORMAL, tmp_path("n.npy"), err, sizeof err) != 0 && strstr(err, "no attribute 2"),
             "a missing attribute: %s", err);
    TH_CHECK(voxgi_io_write_npy_attribute(ctx, vox, VOXGI_ATTRIBUTE_RADIANCE, tmp_path("n.npy"), err, sizeof err) != 0 && strstr(err, "not one of"),
             "radiance: %s", err);
    if (empty) voxgi_voxels_destroy(ctx, empty);
}

int main(void)
{
    char cmd[1100];
    const char *base = getenv("TMPDIR");
    snprintf(tmp_dir, sizeof tmp_dir, "%s/voxgi_export_XXXXXX", base && *base ? base : "/tmp");
    if (!mkdtemp(tmp_dir)) {
        printf("cannot create a temporary directory %s\n", tmp_dir);
        return 1;
    }
    make_voxels();
    TH_RUN(test_vox_round_trip);
    TH_RUN(test_npy_round_trip);
    TH_RUN(test_npy_numpy_load);
    TH_RUN(test_ply_points_round_trip);
    TH_RUN(test_obj_faces_round_trip);
    TH_RUN(test_export_refusals);
    voxgi_voxels_destroy(ctx, vox);
    voxgi_destroy(ctx);
    free(truth_bits);
    free(truth_albedo);
    free(truth_rows);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp_dir);
    if (system(cmd) != 0) printf("could not remove %s\n", tmp_dir);
    return th_finish();
}
