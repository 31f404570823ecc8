/* tests/test_threads.c - voxgi used from two threads at once, each thread with its own context (the
 * rule voxgi.h states: a context is used by one thread at a time; different contexts share
 * nothing). Built and run by `make test` as a plain program and, with ThreadSanitizer, by
 * `make tsan` (the race detector watches every access voxgi makes from both callers and from
 * each context's own worker threads).
 *
 * The oracle: each job's results from two threads at once are bit for bit the ones the same job
 * gives alone on the main thread first (voxgi's results do not depend on timing or thread
 * count): the voxels' bits and albedo, and every method's image. On GL, each thread makes its
 * own headless GL 4.5 context (tools/headless_gl.h) and a voxgi context on it. */
#define _POSIX_C_SOURCE 200809L /* pthread_barrier_t */
#include "fixtures.h"
#include <pthread.h>

/* One thread's work on its own CPU context: the built-in scene voxelized (bits and albedo) and
   rendered by every method of voxgi_render, small (a method the scene cannot use gives its
   refusal, the same each time). */
enum { W = 24, H = 16, METHODS = VOXGI_RENDER_LINESPACE + 1 };
typedef struct job {
    const char *scene;
    int threads;                     /* the context's workers */
    voxgi_result result, rendered[METHODS];
    char error[256];
    uint32_t *bits;
    float *albedo, *image[METHODS];
    size_t bit_bytes, albedo_count;
} job;

static void *run(void *arg)
{
    job *j = (job *)arg;
    voxgi_desc desc;
    voxgi_context *ctx = NULL;
    voxgi_builtin_scene bs;
    voxgi_voxelize_desc vd;
    voxgi_fit_desc fit = {32, 0, 1};
    voxgi_render_desc rd;
    voxgi_voxels *vox = NULL;
    voxgi_voxels_info info;
    int m;
    memset(&desc, 0, sizeof desc);
    memset(&bs, 0, sizeof bs);
    desc.backend = VOXGI_BACKEND_CPU;
    desc.thread_count = j->threads;
    if ((j->result = voxgi_create(&desc, &ctx)) != VOXGI_OK) return NULL;
    if ((j->result = voxgi_builtin_scene_create(ctx, j->scene, &bs)) != VOXGI_OK) goto done;
    memset(&vd, 0, sizeof vd);
    vd.attributes = VOXGI_ATTRIBUTE_ALBEDO;
    if ((j->result = voxgi_fit_grid(ctx, &bs.scene, &fit, &vd.grid)) != VOXGI_OK ||
        (j->result = voxgi_voxelize(ctx, &bs.scene, &vd, &vox)) != VOXGI_OK)
        goto done;
    voxgi_voxels_query(vox, &info);
    j->albedo_count = (size_t)info.voxel_count * 3;
    if ((j->result = voxgi_voxels_read(ctx, vox, NULL, 0, &j->bit_bytes)) != VOXGI_OK) goto done;
    j->bits = (uint32_t *)malloc(j->bit_bytes);
    j->albedo = (float *)malloc(j->albedo_count * 4 + 4);
    if (!j->bits || !j->albedo) { j->result = VOXGI_ERR_OUT_OF_MEMORY; goto done; }
    if ((j->result = voxgi_voxels_read(ctx, vox, j->bits, j->bit_bytes, NULL)) != VOXGI_OK ||
        (j->result = voxgi_voxels_read_attribute(ctx, vox, VOXGI_ATTRIBUTE_ALBEDO, j->albedo, j->albedo_count * 4 + 4, NULL)) != VOXGI_OK)
        goto done;
    for (m = 0; m < METHODS; m++) {
        if (!(j->image[m] = (float *)calloc(W * H, 12))) { j->result = VOXGI_ERR_OUT_OF_MEMORY; goto done; }
        memset(&rd, 0, sizeof rd);
        rd.method = (voxgi_render_method)m;
        rd.camera = bs.camera;
        rd.camera.width = W, rd.camera.height = H;
        rd.samples = 2;        /* the reference's paths, the others' camera rays */
        rd.resolution = 32;
        j->rendered[m] = voxgi_render(ctx, &bs.scene, &rd, j->image[m], W * H * 12, NULL);
    }
done:
    if (j->result != VOXGI_OK) snprintf(j->error, sizeof j->error, "%s: %s", voxgi_result_string(j->result), ctx ? voxgi_last_error(ctx) : "no context");
    voxgi_voxels_destroy(ctx, vox);
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
    return NULL;
}

static void job_free(job *j)
{
    int m;
    free(j->bits);
    free(j->albedo);
    for (m = 0; m < METHODS; m++) free(j->image[m]);
}

/* Whether two runs of a job gave the same results, bit for bit; what differs is printed. */
static int same(const job *a, const job *b, const char *what)
{
    int ok = a->result == VOXGI_OK && b->result == VOXGI_OK && a->bit_bytes == b->bit_bytes && a->albedo_count == b->albedo_count;
    if (ok && memcmp(a->bits, b->bits, a->bit_bytes)) printf("    %s: the voxels' bits differ\n", what), ok = 0;
    if (ok && memcmp(a->albedo, b->albedo, a->albedo_count * 4)) printf("    %s: the voxels' albedo differs\n", what), ok = 0;
    int m;
    for (m = 0; ok && m < METHODS; m++)
        if (a->rendered[m] != b->rendered[m] || memcmp(a->image[m], b->image[m], W * H * 12))
            printf("    %s: method %d: %s and %s, the images %s\n", what, m, voxgi_result_string(a->rendered[m]), voxgi_result_string(b->rendered[m]),
                   memcmp(a->image[m], b->image[m], W * H * 12) ? "differ" : "equal"), ok = 0;
    return ok;
}

/* Two CPU contexts on two threads at once, each with two workers of its own (four threads in
   voxgi at once), each job's results equal to its run alone; then both threads on the same
   scene. */
static void test_two_cpu_contexts_at_once(void)
{
    static const char *const scenes[2][2] = {{"cornell-box", "rsm-walls"}, {"cornell-box", "cornell-box"}};
    int round, k;
    for (round = 0; round < 2; round++) {
        job alone[2], together[2];
        pthread_t t[2];
        memset(alone, 0, sizeof alone);
        memset(together, 0, sizeof together);
        for (k = 0; k < 2; k++) {
            alone[k].scene = together[k].scene = scenes[round][k];
            alone[k].threads = together[k].threads = 2;
            run(&alone[k]);
            TH_CHECK(alone[k].result == VOXGI_OK, "%s alone: %s", alone[k].scene, alone[k].error);
        }
        for (k = 0; k < 2; k++) TH_CHECK(pthread_create(&t[k], NULL, run, &together[k]) == 0, "pthread_create");
        for (k = 0; k < 2; k++) pthread_join(t[k], NULL);
        for (k = 0; k < 2; k++) {
            TH_CHECK(together[k].result == VOXGI_OK, "%s on thread %d: %s", together[k].scene, k, together[k].error);
            TH_CHECK(same(&alone[k], &together[k], together[k].scene), "%s: two threads at once give other results than one alone", together[k].scene);
        }
        for (k = 0; k < 2; k++) {
            int m, rendered = 0;
            for (m = 0; m < METHODS; m++) rendered += together[k].rendered[m] == VOXGI_OK;
            printf("    %s on thread %d: %lu words of voxels, %d of %d methods rendered, equal to the job alone\n", together[k].scene, k,
                   (unsigned long)(together[k].bit_bytes / 4), rendered, METHODS);
            TH_CHECK(rendered >= 8, "%s: only %d methods rendered", together[k].scene, rendered);
        }
        for (k = 0; k < 2; k++) { job_free(&alone[k]); job_free(&together[k]); }
    }
}

/* One thread's work on GL: its own GL context and voxgi context, the scene voxelized (bits) and
   cone-traced; then it waits at the barrier (when there is one) so that no thread tears its GL
   context down while the other still works. */
typedef struct gl_job {
    vxt_gl_kind kind;
    const char *scene;
    pthread_barrier_t *barrier;
    voxgi_result result;
    char error[512];
    uint32_t *bits;
    size_t bit_bytes;
    float image[W * H * 3];
} gl_job;

/* GL contexts made and destroyed one thread at a time: Mesa's surfaceless EGL display is one per
   process, and a thread's eglInitialize rewrites the extension strings another thread may be
   reading. voxgi's work on the contexts runs at once. */
static pthread_mutex_t gl_create_lock = PTHREAD_MUTEX_INITIALIZER;

static void *run_gl(void *arg)
{
    gl_job *j = (gl_job *)arg;
    vxt_gl *gl;
    pthread_mutex_lock(&gl_create_lock);
    gl = vxt_gl_create(j->kind, j->error, sizeof j->error);
    pthread_mutex_unlock(&gl_create_lock);
    voxgi_desc desc;
    voxgi_context *ctx = NULL;
    voxgi_builtin_scene bs;
    voxgi_voxelize_desc vd;
    voxgi_fit_desc fit = {32, 0, 1};
    voxgi_render_desc rd;
    voxgi_voxels *vox = NULL;
    memset(&bs, 0, sizeof bs);
    j->result = VOXGI_ERR_GL;
    if (!gl) goto done;
    memset(&desc, 0, sizeof desc);
    desc.backend = VOXGI_BACKEND_GL;
    desc.gl_get_proc_address_user = vxt_gl_get_proc;
    desc.gl_user = gl;
    if ((j->result = voxgi_create(&desc, &ctx)) != VOXGI_OK || (j->result = voxgi_builtin_scene_create(ctx, j->scene, &bs)) != VOXGI_OK) goto done;
    memset(&vd, 0, sizeof vd);
    if ((j->result = voxgi_fit_grid(ctx, &bs.scene, &fit, &vd.grid)) != VOXGI_OK || (j->result = voxgi_voxelize(ctx, &bs.scene, &vd, &vox)) != VOXGI_OK ||
        (j->result = voxgi_voxels_read(ctx, vox, NULL, 0, &j->bit_bytes)) != VOXGI_OK)
        goto done;
    if (!(j->bits = (uint32_t *)malloc(j->bit_bytes))) { j->result = VOXGI_ERR_OUT_OF_MEMORY; goto done; }
    if ((j->result = voxgi_voxels_read(ctx, vox, j->bits, j->bit_bytes, NULL)) != VOXGI_OK) goto done;
    memset(&rd, 0, sizeof rd);
    rd.method = VOXGI_RENDER_VCT;
    rd.camera = bs.camera;
    rd.camera.width = W, rd.camera.height = H;
    rd.resolution = 32;
    j->result = voxgi_render(ctx, &bs.scene, &rd, j->image, sizeof j->image, NULL);
done:
    if (j->result != VOXGI_OK && ctx) snprintf(j->error, sizeof j->error, "%s: %s", voxgi_result_string(j->result), voxgi_last_error(ctx));
    if (j->barrier) pthread_barrier_wait(j->barrier);
    voxgi_voxels_destroy(ctx, vox);
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
    pthread_mutex_lock(&gl_create_lock);
    vxt_gl_destroy(gl);
    pthread_mutex_unlock(&gl_create_lock);
    return NULL;
}

/* Two GL contexts, one per thread, at once: each job's voxels and image equal to its run alone. */
static void test_two_gl_contexts_at_once(void)
{
    static const char *const scenes[2] = {"cornell-box", "rsm-walls"};
    static gl_job alone[2], together[2];
    pthread_barrier_t barrier;
    pthread_t t[2];
    vxt_gl_kind kind;
    int k;
    if (!have_gl()) return;
    kind = !strcmp(vxt_gl_kind_name(g_gl), "osmesa") ? VXT_GL_OSMESA : VXT_GL_EGL;
    gl_close(); /* each job makes its own */
    for (k = 0; k < 2; k++) {
        memset(&alone[k], 0, sizeof alone[k]);
        memset(&together[k], 0, sizeof together[k]);
        alone[k].kind = together[k].kind = kind;
        alone[k].scene = together[k].scene = scenes[k];
        run_gl(&alone[k]);
        TH_CHECK(alone[k].result == VOXGI_OK, "%s alone on GL: %s", scenes[k], alone[k].error);
    }
    pthread_barrier_init(&barrier, NULL, 2);
    for (k = 0; k < 2; k++) {
        together[k].barrier = &barrier;
        TH_CHECK(pthread_create(&t[k], NULL, run_gl, &together[k]) == 0, "pthread_create");
    }
    for (k = 0; k < 2; k++) pthread_join(t[k], NULL);
    pthread_barrier_destroy(&barrier);
    for (k = 0; k < 2; k++) {
        TH_CHECK(together[k].result == VOXGI_OK, "%s on GL thread %d: %s", scenes[k], k, together[k].error);
        TH_CHECK(alone[k].result == VOXGI_OK && together[k].result == VOXGI_OK && alone[k].bit_bytes == together[k].bit_bytes &&
                     !memcmp(alone[k].bits, together[k].bits, alone[k].bit_bytes),
                 "%s: the voxels on two GL threads differ from those alone", scenes[k]);
        TH_CHECK(!memcmp(alone[k].image, together[k].image, sizeof alone[k].image), "%s: the image on two GL threads differs from the one alone", scenes[k]);
        printf("    %s on GL thread %d: %lu words of voxels and the cone-traced image equal to the job alone\n", scenes[k], k,
               (unsigned long)(together[k].bit_bytes / 4));
        free(alone[k].bits);
        free(together[k].bits);
    }
    gl_open();
}

int main(void)
{
    gl_open();
    TH_RUN(test_two_cpu_contexts_at_once);
    TH_RUN(test_two_gl_contexts_at_once);
    gl_close();
    return th_finish();
}
