/* tools/cli_measure.c - what render --compare and the reports measure with: the one rule for an
 * image's error against a reference (the pixels around the emitters the camera sees left out),
 * the converged reference the reports share, and the Cornell box with a mesh in place of its
 * tall block. */
#include "cli.h"
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ the scene's triangles */
/* The mesh vertex v of `mesh`, as doubles. */
static void vertex_at(const voxgi_mesh *mesh, size_t v, double p[3])
{
    const float *f = (const float *)((const char *)mesh->positions + v * (mesh->position_stride ? mesh->position_stride : 12));
    p[0] = f[0]; p[1] = f[1]; p[2] = f[2];
}

static size_t triangle_vertex(const voxgi_mesh *mesh, size_t t, int k) { return mesh->indices ? mesh->indices[3 * t + (size_t)k] : 3 * t + (size_t)k; }

const voxgi_material *cli_triangle_material(const voxgi_scene *scene, uint32_t id)
{
    size_t m, t = id;
    for (m = 0; m < scene->mesh_count; m++) {
        const voxgi_mesh *mesh = &scene->meshes[m];
        size_t n = mesh->indices ? mesh->index_count / 3 : mesh->vertex_count / 3;
        if (t < n) {
            uint32_t mat = mesh->material_ids ? mesh->material_ids[t] : mesh->material;
            return scene->materials && mat < scene->material_count ? &scene->materials[mat] : NULL;
        }
        t -= n;
    }
    return NULL;
}

/* ------------------------------------------------------------------ the error rule */
/* Whether the scene's triangle `id` has a material with emission > 0 in any channel (the
   library's default material emits nothing). */
static int triangle_emits(const voxgi_scene *scene, uint32_t id)
{
    const voxgi_material *mt = cli_triangle_material(scene, id);
    return mt && (mt->emission[0] > 0 || mt->emission[1] > 0 || mt->emission[2] > 0);
}

int cli_error_mask_make(cli_session *s, voxgi_context *ctx, const voxgi_scene *scene, const voxgi_camera *camera, cli_error_mask *m)
{
    size_t w = (size_t)camera->width, h = (size_t)camera->height, p, x, y;
    uint32_t *tri = NULL;
    unsigned char *row = NULL;
    voxgi_info ci;
    cli_context cpu;
    voxgi_context *use = ctx;
    voxgi_result r;
    memset(m, 0, sizeof *m);
    memset(&cpu, 0, sizeof cpu);
    m->width = camera->width;
    m->height = camera->height;
    voxgi_query_info(ctx, &ci);
    if (ci.backend != VOXGI_BACKEND_CPU) { /* the CPU's ray-cast G-buffer on every backend: one mask for a scene and view */
        if (cli_context_try(s, &cpu, VOXGI_BACKEND_CPU, VXT_GL_AUTO, ci.thread_count, 0)) return cli_fail(s, "the error mask: %s", s->error);
        use = cpu.vx;
    }
    tri = (uint32_t *)malloc(w * h * sizeof *tri);
    row = (unsigned char *)calloc(w * h, 1);
    m->masked = (unsigned char *)calloc(w * h, 1);
    if (!tri || !row || !m->masked) {
        r = VOXGI_ERR_OUT_OF_MEMORY;
        cli_fail(s, "the error mask: out of memory");
    } else if ((r = voxgi_gbuffer_render(use, scene, camera, NULL, NULL, tri)) != VOXGI_OK)
        cli_fail_lib(s, use, "the error mask's G-buffer");
    if (r == VOXGI_OK) {
        for (p = 0; p < w * h; p++) tri[p] = tri[p] != UINT32_MAX && triangle_emits(scene, tri[p]); /* 1: the centre sees an emitter */
        for (y = 0; y < h; y++) /* dilated along rows, then along columns: the (2 margin + 1)^2 square */
            for (x = 0; x < w; x++)
                if (tri[y * w + x]) {
                    size_t lo = x >= CLI_EMITTER_MARGIN ? x - CLI_EMITTER_MARGIN : 0, hi = x + CLI_EMITTER_MARGIN < w ? x + CLI_EMITTER_MARGIN : w - 1, k;
                    for (k = lo; k <= hi; k++) row[y * w + k] = 1;
                }
        for (y = 0; y < h; y++)
            for (x = 0; x < w; x++)
                if (row[y * w + x]) {
                    size_t lo = y >= CLI_EMITTER_MARGIN ? y - CLI_EMITTER_MARGIN : 0, hi = y + CLI_EMITTER_MARGIN < h ? y + CLI_EMITTER_MARGIN : h - 1, k;
                    for (k = lo; k <= hi; k++) m->masked[k * w + x] = 1;
                }
        for (p = 0; p < w * h; p++) m->masked_pixels += m->masked[p];
    }
    free(tri);
    free(row);
    if (cpu.vx) cli_context_close(s, &cpu);
    if (r != VOXGI_OK) {
        cli_error_mask_free(m);
        return CLI_EXIT_FAILURE;
    }
    return 0;
}

void cli_error_mask_free(cli_error_mask *m)
{
    free(m->masked);
    memset(m, 0, sizeof *m);
}

double cli_masked_error(const cli_error_mask *m, const float *img, const float *ref, double *rms_out, double *mean_out)
{
    size_t p, n = (size_t)m->width * (size_t)m->height, kept = 0;
    double sq = 0, sum = 0, rms, mean;
    int c;
    for (p = 0; p < n; p++) {
        if (m->masked[p]) continue;
        kept++;
        for (c = 0; c < 3; c++) {
            double d = (double)img[3 * p + (size_t)c] - ref[3 * p + (size_t)c];
            sq += d * d;
            sum += ref[3 * p + (size_t)c];
        }
    }
    rms = kept ? sqrt(sq / (3.0 * (double)kept)) : NAN;
    mean = kept ? sum / (3.0 * (double)kept) : NAN;
    if (rms_out) *rms_out = rms;
    if (mean_out) *mean_out = mean;
    return kept && mean > 0 ? rms / mean : NAN;
}

/* ------------------------------------------------------------------ a converged reference */
int cli_reference_make(cli_session *s, voxgi_context *ctx, const voxgi_scene *scene, const voxgi_camera *camera, int spp, int bounces,
                       double ao_radius, cli_reference *R)
{
    size_t bytes = (size_t)camera->width * (size_t)camera->height * 12;
    voxgi_render_desc rd;
    voxgi_render_info ri;
    float *quick;
    double e16;
    memset(R, 0, sizeof *R);
    memset(&rd, 0, sizeof rd);
    rd.method = VOXGI_RENDER_REFERENCE;
    rd.camera = *camera;
    rd.hide_emitters = 1;
    if (bounces == 0) rd.direct_only = 1; /* bounces 0 now means one: the direct light alone is direct_only */
    else rd.bounces = bounces;
    rd.reference.ao_radius = (float)ao_radius;
    rd.samples = spp ? spp : 16; /* the path tracer's old default (now 64) */
    rd.seed = 1000003; /* independent of the images' seeds */
    R->spp = spp;
    if (!(R->image = (float *)malloc(bytes)) || !(quick = (float *)malloc(bytes))) {
        cli_reference_free(R);
        return cli_fail(s, "the reference: out of memory");
    }
    if (ao_radius > 0) cli_status(s, "the reference's ambient occlusion within %g, %d spp", ao_radius, spp);
    else cli_status(s, "the reference, %d bounce%s, %d spp", bounces, bounces == 1 ? "" : "s", spp);
    if (voxgi_render(ctx, scene, &rd, R->image, bytes, &ri) != VOXGI_OK) {
        free(quick);
        cli_reference_free(R);
        return cli_fail_lib(s, ctx, "the reference");
    }
    if (cli_error_mask_make(s, ctx, scene, camera, &R->mask)) {
        free(quick);
        cli_reference_free(R);
        return 1;
    }
    rd.samples = 16; /* its convergence */
    rd.seed = 7;
    if (voxgi_render(ctx, scene, &rd, quick, bytes, &ri) != VOXGI_OK) {
        free(quick);
        cli_reference_free(R);
        return cli_fail_lib(s, ctx, "the reference at 16 spp");
    }
    e16 = cli_masked_error(&R->mask, quick, R->image, NULL, NULL);
    R->c = e16 / sqrt(1.0 / 16 + 1.0 / spp);
    R->ms_per_spp = (voxgi_render_stage_ms(&ri, "bvh") + voxgi_render_stage_ms(&ri, "render")) / 16;
    free(quick);
    return 0;
}

void cli_reference_free(cli_reference *R)
{
    free(R->image);
    cli_error_mask_free(&R->mask);
    memset(R, 0, sizeof *R);
}

double cli_reference_ms(const cli_reference *R, double e)
{
    double inv_k = (e / R->c) * (e / R->c) - 1.0 / R->spp;
    return inv_k > 0 ? R->ms_per_spp * fmax(1, 1 / inv_k) : HUGE_VAL; /* a sample per pixel at least */
}

double cli_red_excess(const cli_reference *R, const float *img)
{
    size_t p, n = (size_t)R->mask.width * (size_t)R->mask.height;
    double excess = 0, sum = 0;
    for (p = 0; p < n; p++) {
        const float *a = img + 3 * p, *b = R->image + 3 * p;
        double d;
        if (R->mask.masked[p]) continue;
        d = ((double)a[0] - a[1]) - ((double)b[0] - b[1]);
        if (d > 0) excess += d;
        sum += ((double)b[0] + b[1] + b[2]) / 3;
    }
    return sum > 0 ? excess / sum : NAN;
}

/* ------------------------------------------------------------------ what the reports share */
double cli_scene_longest_side(const voxgi_scene *scene)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, side = 0;
    size_t m, t;
    int k, a;
    for (m = 0; m < scene->mesh_count; m++) {
        const voxgi_mesh *mesh = &scene->meshes[m];
        size_t n = mesh->indices ? mesh->index_count / 3 : mesh->vertex_count / 3;
        for (t = 0; t < n; t++)
            for (k = 0; k < 3; k++) {
                double p[3];
                vertex_at(mesh, triangle_vertex(mesh, t, k), p);
                for (a = 0; a < 3; a++) { lo[a] = fmin(lo[a], p[a]); hi[a] = fmax(hi[a], p[a]); }
            }
    }
    for (a = 0; a < 3; a++) side = fmax(side, hi[a] - lo[a]);
    return side > 0 ? side : 1;
}

void cli_vct_defaults(voxgi_render_desc *vd, const voxgi_camera *camera)
{
    memset(vd, 0, sizeof *vd);
    vd->method = VOXGI_RENDER_VCT;
    vd->camera = *camera; /* the rest zero: the library's defaults, which CLI_VCT_* name */
    vd->seed = 1;
    vd->hide_emitters = 1;
}

/* ------------------------------------------------------------------ the Cornell box with a mesh */
int cli_cornell_mesh_open(cli_session *s, voxgi_context *ctx, const char *path, cli_cornell_mesh *c)
{
    const double eps = 1e-3; /* 1 mm: the room's walls meet at its bounding box, the light hangs 0.1 mm below the ceiling */
    double room_lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, room_hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    double blo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, bhi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, top = -HUGE_VAL;
    double mlo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, mhi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, scale = HUGE_VAL;
    const voxgi_mesh *box;
    size_t t, nt, v, kept = 0, found = 0;
    unsigned char *is_block = NULL;
    int k, a;
    const char *base, *dot;
    memset(c, 0, sizeof *c);
    if (cli_mesh_open(s, path, &c->mesh)) return CLI_EXIT_FAILURE; /* a bad file fails before anything else */
    if (voxgi_builtin_scene_create(ctx, "cornell-box", &c->bs) != VOXGI_OK) {
        cli_fail_lib(s, ctx, NULL);
        goto fail;
    }
    if (c->bs.scene.mesh_count != 1) {
        cli_fail(s, "--cornell-mesh: the built-in Cornell box is not one mesh");
        goto fail;
    }
    box = &c->bs.scene.meshes[0];
    nt = box->indices ? box->index_count / 3 : box->vertex_count / 3;
    /* The tall block, by geometry: the blocks are the triangles that do not emit and lie more than
       1 mm inside the room's bounding box across (x, z) and below its top (the floor, walls and
       ceiling each touch its sides); the tall block is those of them whose highest corner is the
       highest (every triangle of a block reaches its top). */
    for (t = 0; t < nt; t++)
        for (k = 0; k < 3; k++) {
            double p[3];
            vertex_at(box, triangle_vertex(box, t, k), p);
            for (a = 0; a < 3; a++) { room_lo[a] = fmin(room_lo[a], p[a]); room_hi[a] = fmax(room_hi[a], p[a]); }
        }
    if (!(is_block = (unsigned char *)calloc(nt ? nt : 1, 1))) {
        cli_fail(s, "out of memory");
        goto fail;
    }
    for (t = 0; t < nt; t++) {
        double high = -HUGE_VAL;
        int inside = !triangle_emits(&c->bs.scene, (uint32_t)t);
        for (k = 0; k < 3 && inside; k++) {
            double p[3];
            vertex_at(box, triangle_vertex(box, t, k), p);
            inside = p[0] > room_lo[0] + eps && p[0] < room_hi[0] - eps && p[2] > room_lo[2] + eps && p[2] < room_hi[2] - eps && p[1] < room_hi[1] - eps;
            high = fmax(high, p[1]);
        }
        if (inside) {
            is_block[t] = 1;
            top = fmax(top, high);
        }
    }
    for (t = 0; t < nt; t++) {
        double high = -HUGE_VAL, p[3];
        if (!is_block[t]) continue;
        for (k = 0; k < 3; k++) { vertex_at(box, triangle_vertex(box, t, k), p); high = fmax(high, p[1]); }
        if (high < top - eps) { is_block[t] = 0; continue; } /* the short block */
        for (k = 0; k < 3; k++) {
            vertex_at(box, triangle_vertex(box, t, k), p);
            for (a = 0; a < 3; a++) { blo[a] = fmin(blo[a], p[a]); bhi[a] = fmax(bhi[a], p[a]); }
        }
        if (!found++) c->material = box->material_ids ? box->material_ids[t] : box->material;
    }
    if (!found || !(bhi[1] - blo[1] > eps)) {
        cli_fail(s, "--cornell-mesh: no tall block found in the built-in Cornell box");
        goto fail;
    }
    /* the box without it */
    c->box_indices = (uint32_t *)malloc(3 * nt * sizeof *c->box_indices);
    c->box_materials = (uint32_t *)malloc(nt * sizeof *c->box_materials);
    c->positions = (float *)malloc(c->mesh.vm.vertex_count * 12);
    if (!c->box_indices || !c->box_materials || !c->positions) {
        cli_fail(s, "out of memory");
        goto fail;
    }
    for (t = 0; t < nt; t++) {
        if (is_block[t]) continue;
        for (k = 0; k < 3; k++) c->box_indices[3 * kept + (size_t)k] = (uint32_t)triangle_vertex(box, t, k);
        c->box_materials[kept++] = box->material_ids ? box->material_ids[t] : box->material;
    }
    c->meshes[0] = *box;
    c->meshes[0].indices = c->box_indices;
    c->meshes[0].index_count = 3 * kept;
    c->meshes[0].material_ids = c->box_materials;
    /* the mesh, scaled uniformly to fit the block's bounding box, standing on its floor at its centre */
    for (t = 0; t < cli_mesh_triangles(&c->mesh); t++)
        for (k = 0; k < 3; k++) {
            double p[3];
            vertex_at(&c->mesh.vm, triangle_vertex(&c->mesh.vm, t, k), p);
            for (a = 0; a < 3; a++) { mlo[a] = fmin(mlo[a], p[a]); mhi[a] = fmax(mhi[a], p[a]); }
        }
    for (a = 0; a < 3; a++)
        if (mhi[a] - mlo[a] > 0) scale = fmin(scale, (bhi[a] - blo[a]) / (mhi[a] - mlo[a]));
    if (!(scale < HUGE_VAL)) {
        cli_fail(s, "--cornell-mesh: %s has no extent", path);
        goto fail;
    }
    for (v = 0; v < c->mesh.vm.vertex_count; v++) {
        double p[3];
        vertex_at(&c->mesh.vm, v, p);
        for (a = 0; a < 3; a++) {
            double from = a == 1 ? mlo[a] : 0.5 * (mlo[a] + mhi[a]), to = a == 1 ? blo[a] : 0.5 * (blo[a] + bhi[a]);
            c->positions[3 * v + (size_t)a] = (float)(to + scale * (p[a] - from));
        }
    }
    c->meshes[1] = c->mesh.vm;
    c->meshes[1].positions = c->positions;
    c->meshes[1].position_stride = 0;
    c->meshes[1].material_ids = NULL; /* the block's material, whatever the file says */
    c->meshes[1].material = c->material;
    c->scene = c->bs.scene;
    c->scene.meshes = c->meshes;
    c->scene.mesh_count = 2;
    c->scale = scale;
    for (a = 0; a < 3; a++) { c->block_lo[a] = blo[a]; c->block_hi[a] = bhi[a]; }
    /* the name: cornell-box+ the file's name without its directory and extension (builtin:sphere as it is) */
    base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    dot = strncmp(path, "builtin:", 8) == 0 ? NULL : strrchr(base, '.');
    snprintf(c->name, sizeof c->name, "cornell-box+%.*s", dot && dot > base ? (int)(dot - base) : (int)strlen(base), base);
    free(is_block);
    return 0;
fail:
    free(is_block);
    cli_cornell_mesh_close(ctx, c);
    return CLI_EXIT_FAILURE;
}

void cli_cornell_mesh_close(voxgi_context *ctx, cli_cornell_mesh *c)
{
    free(c->box_indices);
    free(c->box_materials);
    free(c->positions);
    voxgi_builtin_scene_destroy(ctx, &c->bs);
    if (c->mesh.name[0]) cli_mesh_close(&c->mesh);
    memset(c, 0, sizeof *c);
}
