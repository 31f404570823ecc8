/* tests/test_plan.c - part 14: the planner and images, CPU and GL (voxgi's G-buffer).

   The planner against what is known: the scene's counts on a scene built for them, each item kept
   or left out where the scene has or lacks what it needs, its bytes against what the passes then
   allocate (exactly where the formula is the pass's, within a factor where it is an estimate from
   the surface), what the camera sees, the grid and cones from an error, the octree under a budget;
   the plan following the render desc it is given (its radiance store, direct light only, bounces,
   hidden emitters) and voxgi_render running exactly the settings voxgi_render_resolve gives;
   every method's items, kept or left out with a reason that agrees, over a table of scenes and
   descs against rules derived from what each method reads;
   and the images following their plans (no voxels where nothing can bounce, no line space without
   an area light), logging what they leave out; voxgi's own G-buffer rasterized on GL against the
   CPU's ray cast. */
#include "../voxgi.h"
#include "fixtures.h"

static char g_log[4096];

static void keep_log(voxgi_log_level level, const char *message, void *user)
{
    (void)level;
    (void)user;
    if (strlen(g_log) + strlen(message) + 2 < sizeof g_log) {
        strcat(g_log, message);
        strcat(g_log, "\n");
    }
}

static voxgi_context *plan_ctx(void)
{
    voxgi_desc d;
    voxgi_context *ctx = NULL;
    ctx_desc(&d, VOXGI_BACKEND_CPU);
    d.logger.func = keep_log;
    return voxgi_create(&d, &ctx) == VOXGI_OK ? ctx : NULL;
}

/* The item's kept (0 or 1), or -1 (and a line) when the plan has no such item. */
static int kept(const voxgi_plan_info *p, voxgi_plan_item_id id)
{
    const voxgi_plan_item *it = voxgi_plan_find(p, id);
    if (!it) printf("    no item %d\n", (int)id);
    return it ? it->kept : -1;
}

/* The item's why, or "(none)" when the plan has no such item. */
static const char *why(const voxgi_plan_info *p, voxgi_plan_item_id id)
{
    const voxgi_plan_item *it = voxgi_plan_find(p, id);
    return it ? it->why : "(none)";
}

/* The item's bytes, or 0 when the plan has no such item. */
static uint64_t item_bytes(const voxgi_plan_info *p, voxgi_plan_item_id id)
{
    const voxgi_plan_item *it = voxgi_plan_find(p, id);
    return it ? it->bytes : 0;
}

/* d: method m, all else zero, and the camera (NULL: zero, the planner fits one) with resolution res. */
static void desc_of(voxgi_render_desc *d, voxgi_render_method m, const voxgi_camera *cam, int res)
{
    memset(d, 0, sizeof *d); /* the padding too: resolved descs are compared with memcmp */
    d->method = m;
    if (cam) d->camera = *cam;
    d->resolution = res;
}

static voxgi_result plan_of(voxgi_context *ctx, const voxgi_scene *sc, voxgi_render_method m, const voxgi_camera *cam, int res, voxgi_plan_info *p)
{
    voxgi_render_desc d;
    desc_of(&d, m, cam, res);
    return voxgi_plan(ctx, sc, &d, 0, p);
}

/* d: method m, a w x w view through the built-in scene's camera, all else zero. */
static void view_of(voxgi_render_desc *d, voxgi_render_method m, const voxgi_builtin_scene *bs, int w)
{
    desc_of(d, m, &bs->camera, 0);
    d->camera.width = d->camera.height = w;
}

/* The cone tracer's old zeros, which the images below were written against (the new zeros are
   the measured front's middle): 16 camera rays, 16 cones at every pixel, isotropic mips. */
static void vct_old_zeros(voxgi_render_desc *d)
{
    d->samples = 16;
    d->vct.cones.cones = 16;
    d->vct.cone_stride = 1;
    d->vct.radiance = VOXGI_VCT_ISOTROPIC;
}

/* A floor, an emissive quad, a translucent triangle, a black triangle; a point, a directional and a
   rect light: every count exact. No camera given: the planner fits one to the bounds (x and z in
   [-1, 1], y in [0, 1]: centre (0, 0.5, 0), largest half extent 1, so the eye at (0, 1.1, -3.2)),
   above the lamp's plane (y = 1), whose quad faces down (its first triangle's (v1 - v0) x (v2 - v0)
   is -Y): the camera sees its back, no emitter in view. */
static void test_plan_counts(void)
{
    voxgi_context *ctx = plan_ctx();
    static const float c_floor[12] = {-1, 0, -1, -1, 0, 1, 1, 0, 1, 1, 0, -1}, c_lamp[12] = {-0.2f, 1, -0.2f, 0.2f, 1, -0.2f, 0.2f, 1, 0.2f, -0.2f, 1, 0.2f};
    static const float c_glass[12] = {-0.5f, 0.3f, 0, 0.5f, 0.3f, 0, 0.5f, 0.6f, 0, -0.5f, 0.6f, 0};
    static const float c_black[12] = {-0.5f, 0.3f, 0.5f, 0.5f, 0.3f, 0.5f, 0.5f, 0.6f, 0.5f, -0.5f, 0.6f, 0.5f};
    voxgi_material mats[4];
    voxgi_light lights[3];
    voxgi_scene sc;
    voxgi_mesh mesh;
    voxgi_plan_info p;
    voxgi_render_desc d, used;
    voxgi_fit_desc fit;
    voxgi_grid g;
    quads q;
    memset(mats, 0, sizeof mats);
    memset(lights, 0, sizeof lights);
    memset(&q, 0, sizeof q);
    mats[0].albedo[0] = mats[0].albedo[1] = mats[0].albedo[2] = 0.5f;
    mats[1].emission[0] = mats[1].emission[1] = mats[1].emission[2] = 5;
    mats[2].albedo[1] = 0.3f;
    mats[2].transparency = 0.6f;
    lights[0].type = VOXGI_LIGHT_POINT;
    lights[1].type = VOXGI_LIGHT_DIRECTIONAL;
    lights[1].direction[1] = -1;
    lights[2].type = VOXGI_LIGHT_RECT;
    lights[2].position[1] = 2;
    lights[2].edge_u[0] = 0.1f;
    lights[2].edge_v[2] = 0.1f;
    quad(&q, c_floor, 0);
    quad(&q, c_lamp, 1);
    quad(&q, c_glass, 2);
    quad(&q, c_black, 3);
    scene_of_quads(&sc, &mesh, &q, mats, 4, lights, 3);
    TH_CHECK(ctx && plan_of(ctx, &sc, VOXGI_RENDER_VCT, NULL, 32, &p) == VOXGI_OK, "%s", ctx ? voxgi_last_error(ctx) : "no context");
    TH_CHECK(p.triangles == 8 && p.emissive_triangles == 2 && p.translucent_triangles == 2 && p.reflective_triangles == 4,
             "triangles %lu, emissive %lu, translucent %lu, reflective %lu", (unsigned long)p.triangles, (unsigned long)p.emissive_triangles,
             (unsigned long)p.translucent_triangles, (unsigned long)p.reflective_triangles);
    TH_CHECK(p.point_lights == 1 && p.directional_lights == 1 && p.rect_lights == 1 && p.spot_lights == 0 && p.area_lights == 2,
             "lights %d %d %d %d, areas %d", p.point_lights, p.directional_lights, p.rect_lights, p.spot_lights, p.area_lights);
    TH_CHECK(fabs(p.surface_area - (4 + 0.16 + 0.3 + 0.3)) < 1e-6, "surface %.9g", p.surface_area);
    TH_CHECK(p.emitters_in_view == 0, "the fitted camera sees the lamp's back: in view %d", p.emitters_in_view);
    desc_of(&d, VOXGI_RENDER_VCT, NULL, 32);
    memset(&used, 0, sizeof used);
    TH_CHECK(voxgi_render_resolve(ctx, &sc, &d, &used) == VOXGI_OK && used.resolution == 32, "resolution %d", used.resolution);
    TH_CHECK(fabs(used.camera.eye[0]) < 1e-12 && fabs(used.camera.eye[1] - 1.1) < 1e-12 && fabs(used.camera.eye[2] + 3.2) < 1e-12 &&
                 fabs(used.camera.target[0]) < 1e-12 && fabs(used.camera.target[1] - 0.5) < 1e-12 && fabs(used.camera.target[2]) < 1e-12 &&
                 used.camera.fovy_degrees == 40 && used.camera.width == 256 && used.camera.height == 256,
             "the fitted camera: eye (%g %g %g), target (%g %g %g), fovy %g, %d x %d", used.camera.eye[0], used.camera.eye[1], used.camera.eye[2],
             used.camera.target[0], used.camera.target[1], used.camera.target[2], used.camera.fovy_degrees, used.camera.width, used.camera.height);
    memset(&fit, 0, sizeof fit); /* the plan's grid: voxgi_fit_grid of the resolution, a voxel of padding */
    fit.res = 32;
    fit.padding = 1;
    TH_CHECK(voxgi_fit_grid(ctx, &sc, &fit, &g) == VOXGI_OK && !memcmp(g.origin, p.grid.origin, sizeof g.origin) && g.voxel_size == p.grid.voxel_size &&
                 !memcmp(g.res, p.grid.res, sizeof g.res), "the plan's grid: %d x %d x %d of %g", p.grid.res[0], p.grid.res[1], p.grid.res[2], p.grid.voxel_size);
    TH_CHECK(!kept(&p, VOXGI_PLAN_EMISSION) && !kept(&p, VOXGI_PLAN_OPACITY) && kept(&p, VOXGI_PLAN_CONES) == 1 && kept(&p, VOXGI_PLAN_DIRECT_LIGHT) == 1, "vct's items");
    TH_CHECK(!strcmp(why(&p, VOXGI_PLAN_OPACITY), "the cone tracer's voxels are opaque"), "opacity: %s", why(&p, VOXGI_PLAN_OPACITY));
    TH_CHECK(voxgi_plan_find(&p, VOXGI_PLAN_CONES) && !strcmp(voxgi_plan_find(&p, VOXGI_PLAN_CONES)->name, "cones") &&
                 voxgi_plan_find(&p, VOXGI_PLAN_CONES)->kind == VOXGI_PLAN_PASS && !voxgi_plan_find(&p, VOXGI_PLAN_SHADOW_MAPS),
             "the cones' item by its id: its old name, a pass; vct has no shadow maps");
    TH_CHECK(plan_of(ctx, &sc, VOXGI_RENDER_TSM, NULL, 0, &p) == VOXGI_OK && kept(&p, VOXGI_PLAN_TRANSMITTANCE_LAYERS) == 1 && kept(&p, VOXGI_PLAN_SHADOW_MAPS) == 1,
             "tsm's items");
    voxgi_destroy(ctx);
}

/* What the camera sees: the Cornell box's light from its camera, and from a camera turned away. */
static void test_plan_emitters_in_view(void)
{
    voxgi_context *ctx = plan_ctx();
    voxgi_builtin_scene bs;
    voxgi_camera away;
    voxgi_plan_info p;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    TH_CHECK(plan_of(ctx, &bs.scene, VOXGI_RENDER_REFERENCE, &bs.camera, 0, &p) == VOXGI_OK && p.emitters_in_view == 1 && kept(&p, VOXGI_PLAN_SEEN_EMISSION) == 1,
             "the camera's view: %d", p.emitters_in_view);
    away = bs.camera;
    away.target[1] = bs.camera.eye[1] - 10 * (bs.camera.target[1] - bs.camera.eye[1]) - 1000; /* down at the floor from the eye */
    away.target[0] = bs.camera.eye[0];
    away.target[2] = bs.camera.eye[2] + 1;
    away.fovy_degrees = 20;
    TH_CHECK(plan_of(ctx, &bs.scene, VOXGI_RENDER_REFERENCE, &away, 0, &p) == VOXGI_OK && p.emitters_in_view == 0 && kept(&p, VOXGI_PLAN_SEEN_EMISSION) == 0,
             "looking down: %d", p.emitters_in_view);
    TH_CHECK(!strcmp(why(&p, VOXGI_PLAN_SEEN_EMISSION), "the camera sees no emitter"), "%s", why(&p, VOXGI_PLAN_SEEN_EMISSION));
    { /* above the light, looking down at its back: in view, but it emits from its front face only */
        const voxgi_mesh *m;
        size_t mi, t;
        double c[3] = {0, 0, 0};
        int found = 0, a, k;
        for (mi = 0; mi < bs.scene.mesh_count && !found; mi++) {
            size_t nt;
            m = &bs.scene.meshes[mi];
            nt = m->indices ? m->index_count / 3 : m->vertex_count / 3;
            for (t = 0; t < nt && !found; t++) {
                uint32_t id = m->material_ids ? m->material_ids[t] : m->material;
                if (!(bs.scene.materials[id].emission[0] > 0)) continue;
                for (k = 0; k < 3; k++) {
                    size_t v = m->indices ? m->indices[3 * t + (size_t)k] : 3 * t + (size_t)k;
                    const float *q = (const float *)((const char *)m->positions + v * (m->position_stride ? m->position_stride : 12));
                    for (a = 0; a < 3; a++) c[a] += q[a] / 3.0;
                }
                found = 1;
            }
        }
        TH_CHECK(found, "the Cornell box has no emitter");
        memcpy(away.target, c, sizeof c);
        memcpy(away.eye, c, sizeof c);
        away.eye[1] += 0.5 * fabs(bs.camera.eye[2] - c[2]) + 1e-3;
        away.eye[2] += 1e-3;
        TH_CHECK(plan_of(ctx, &bs.scene, VOXGI_RENDER_REFERENCE, &away, 0, &p) == VOXGI_OK && p.emitters_in_view == 0, "the light's back: %d", p.emitters_in_view);
        away.eye[1] = c[1] - 0.5 * fabs(bs.camera.eye[2] - c[2]);
        TH_CHECK(plan_of(ctx, &bs.scene, VOXGI_RENDER_REFERENCE, &away, 0, &p) == VOXGI_OK && p.emitters_in_view == 1, "under the light: %d", p.emitters_in_view);
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* Bytes: the dense radiance volume (isotropic, the old default, and anisotropic, the new one) and
   the transmittance maps by their own formulas (exact, but for the radiance volume's few region
   labels), the set voxels and the line space estimated; each plan is of the very desc rendered. */
static void test_plan_bytes(void)
{
    voxgi_context *ctx = plan_ctx();
    voxgi_builtin_scene bs;
    voxgi_plan_info p;
    voxgi_render_desc d, used;
    voxgi_render_info vi;
    voxgi_linespace *L = NULL;
    voxgi_linespace_info li;
    static float rgb[3 * 8 * 8];
    const char *names[2] = {"rsm-walls", "foliage"};
    int k;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    for (k = 0; k < 2; k++) { /* ISOTROPIC; then DEFAULT, anisotropic without a budget */
        view_of(&d, VOXGI_RENDER_VCT, &bs, 8);
        vct_old_zeros(&d);
        d.resolution = 40;
        d.vct.cones.cones = 4;
        if (k) d.vct.radiance = VOXGI_VCT_RADIANCE_DEFAULT;
        TH_CHECK(voxgi_plan(ctx, &bs.scene, &d, 0, &p) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        TH_CHECK(voxgi_render(ctx, &bs.scene, &d, rgb, sizeof rgb, &vi) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        TH_CHECK(vi.used.vct.radiance == (k ? VOXGI_VCT_ANISOTROPIC : VOXGI_VCT_ISOTROPIC), "radiance %d", (int)vi.used.vct.radiance);
        {
            double dense = (double)item_bytes(&p, VOXGI_PLAN_RADIANCE_VOLUME), ratio = (double)p.voxels / (double)vi.voxels;
            TH_CHECK(kept(&p, VOXGI_PLAN_RADIANCE_VOLUME) == 1 && fabs(dense - (double)vi.bytes) <= 1e-3 * (double)vi.bytes,
                     "radiance volume (%s): planned %.0f, allocated %lu", k ? "anisotropic" : "isotropic", dense, (unsigned long)vi.bytes);
            TH_CHECK(ratio > 0.5 && ratio < 2, "set voxels: estimated %lu, voxelized %lu", (unsigned long)p.voxels, (unsigned long)vi.voxels);
            printf("    cornell-box at 40 (%s): voxels estimated %lu, voxelized %lu; radiance %.0f planned, %lu allocated\n", k ? "anisotropic" : "isotropic",
                   (unsigned long)p.voxels, (unsigned long)vi.voxels, dense, (unsigned long)vi.bytes);
        }
    }
    /* the line space: the tree voxgi_render builds (the resolved desc's: n 4, the scene's depth, 2 under 256 triangles, else 3) */
    desc_of(&d, VOXGI_RENDER_LINESPACE, NULL, 0);
    memset(&used, 0, sizeof used);
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &d, 0, &p) == VOXGI_OK && voxgi_render_resolve(ctx, &bs.scene, &d, &used) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(used.linespace.tree.n == 4 && used.linespace.tree.depth == (p.triangles < 256 ? 2 : 3), "the line space's n %d, depth %d (%lu triangles)",
             used.linespace.tree.n, used.linespace.tree.depth, (unsigned long)p.triangles);
    TH_CHECK(voxgi_linespace_create(ctx, &bs.scene, &used.linespace.tree, &L) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    if (L) {
        double ratio;
        voxgi_linespace_query(L, &li);
        ratio = (double)item_bytes(&p, VOXGI_PLAN_LINE_SPACE) / (double)li.bytes;
        TH_CHECK(kept(&p, VOXGI_PLAN_LINE_SPACE) == 1 && ratio > 0.5 && ratio < 2, "line space: estimated %lu, built %lu",
                 (unsigned long)item_bytes(&p, VOXGI_PLAN_LINE_SPACE), (unsigned long)li.bytes);
        view_of(&d, VOXGI_RENDER_LINESPACE, &bs, 8);
        TH_CHECK(voxgi_render(ctx, &bs.scene, &d, rgb, sizeof rgb, &vi) == VOXGI_OK && vi.tree.bytes == li.bytes, "the image's line space: %lu bytes, %lu built (%s)",
                 (unsigned long)vi.tree.bytes, (unsigned long)li.bytes, voxgi_last_error(ctx));
        voxgi_linespace_destroy(ctx, L);
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    for (k = 0; k < 2; k++) { /* a sun over opaque walls: maps without layers; the foliage's leaves: with them */
        TH_CHECK(voxgi_builtin_scene_create(ctx, names[k], &bs) == VOXGI_OK, "%s", names[k]);
        view_of(&d, VOXGI_RENDER_TSM, &bs, 8);
        TH_CHECK(voxgi_plan(ctx, &bs.scene, &d, 0, &p) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        TH_CHECK(voxgi_render(ctx, &bs.scene, &d, rgb, sizeof rgb, &vi) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        TH_CHECK(kept(&p, VOXGI_PLAN_TRANSMITTANCE_LAYERS) == k && item_bytes(&p, VOXGI_PLAN_SHADOW_MAPS) + item_bytes(&p, VOXGI_PLAN_TRANSMITTANCE_LAYERS) == vi.bytes,
                 "%s: layers %d, planned %lu + %lu, allocated %lu", names[k], kept(&p, VOXGI_PLAN_TRANSMITTANCE_LAYERS),
                 (unsigned long)item_bytes(&p, VOXGI_PLAN_SHADOW_MAPS), (unsigned long)item_bytes(&p, VOXGI_PLAN_TRANSMITTANCE_LAYERS), (unsigned long)vi.bytes);
        voxgi_builtin_scene_destroy(ctx, &bs);
    }
    voxgi_destroy(ctx);
}

/* Every method's zero desc resolves to the defaults the header and docs/ name (the settings each
   report measured best), and the settings line names the bounces only of the methods that read
   them (the reference's and the cone tracer's). */
static void test_render_defaults(void)
{
    /* per method: samples, bounces, resolution, the settings line's expected parts */
    static const struct { voxgi_render_method m; int samples, bounces, resolution; const char *has[3]; } want[] = {
        {VOXGI_RENDER_REFERENCE, 64, 1, 0, {"samples 64", "bounces 1", NULL}},
        {VOXGI_RENDER_VCT, 24, 1, 96, {"radiance anisotropic volume, cones 24, cone stride 6", "bounces 1", NULL}},
        {VOXGI_RENDER_TSM, 4, 0, 0, {"map size 512, slices 64", NULL, NULL}},
        {VOXGI_RENDER_RSM, 24, 1, 64, {"visibility hierarchical, gather stride 4, map size 256", NULL, NULL}},
        {VOXGI_RENDER_SH, 24, 1, 64, {"visibility hierarchical, gather stride 4, opening 0.5", NULL, NULL}},
        {VOXGI_RENDER_SSAO, 0, 0, 0, {"rays 16, steps 16", "half resolution off, blur 2", NULL}},
        {VOXGI_RENDER_VAO, 0, 0, 128, {"rays 16, steps 16", "half resolution off, blur 2", NULL}},
        {VOXGI_RENDER_SSGI, 24, 1, 0, {"rays 16, steps 16", "half resolution on, blur 8", NULL}},
        {VOXGI_RENDER_HYBRID, 24, 1, 128, {"half resolution on, blur 8", "hidden light on", NULL}},
        {VOXGI_RENDER_LINESPACE, 0, 0, 0, {"exact, n 4, depth 2, shadow samples 4, supersample 2", NULL, NULL}},
    };
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 2);
    voxgi_builtin_scene bs;
    size_t k;
    int i;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "the Cornell box");
    if (!ctx) return;
    TH_CHECK(sizeof want / sizeof want[0] == VOXGI_RENDER_METHOD_COUNT, "a method without its expected defaults");
    for (k = 0; k < sizeof want / sizeof want[0]; k++) {
        voxgi_render_desc d, u;
        char line[512];
        memset(&d, 0, sizeof d);
        d.method = want[k].m;
        TH_CHECK(voxgi_render_resolve(ctx, &bs.scene, &d, &u) == VOXGI_OK, "%s: %s", voxgi_render_method_name(d.method), voxgi_last_error(ctx));
        voxgi_render_describe(&u, line, sizeof line);
        TH_CHECK(u.samples == want[k].samples && u.bounces == want[k].bounces && u.resolution == want[k].resolution && u.camera.width == 256 && u.camera.height == 256,
                 "%s: samples %d, bounces %d, resolution %d, %d x %d", line, u.samples, u.bounces, u.resolution, u.camera.width, u.camera.height);
        for (i = 0; i < 3 && want[k].has[i]; i++) TH_CHECK(strstr(line, want[k].has[i]) != NULL, "'%s' lacks '%s'", line, want[k].has[i]);
        TH_CHECK((strstr(line, "bounces") != NULL) == (want[k].m == VOXGI_RENDER_REFERENCE || want[k].m == VOXGI_RENDER_VCT), "'%s': bounces it does not read", line);
    }
    for (i = -1; i <= 2; i++) { /* the cone tracer's bounces among the voxels: 4 cones a 4^3 block where there are any, full GI included */
        voxgi_render_desc d, u;
        char line[512];
        int among = i < 0 || i > 1;
        memset(&d, 0, sizeof d);
        d.method = VOXGI_RENDER_VCT;
        d.bounces = i;
        TH_CHECK(voxgi_render_resolve(ctx, &bs.scene, &d, &u) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        voxgi_render_describe(&u, line, sizeof line);
        TH_CHECK(u.vct.bounce_block == (among ? 4 : 0) && u.vct.bounce_cones.cones == (among ? 4 : 0) &&
                     (strstr(line, "bounce cones 4, bounce block 4") != NULL) == among, "bounces %d: block %d, cones %d ('%s')", i, u.vct.bounce_block,
                 u.vct.bounce_cones.cones, line);
        d.vct.bounce_block = 2;
        TH_CHECK(voxgi_render_resolve(ctx, &bs.scene, &d, &u) == VOXGI_OK && u.vct.bounce_block == (among ? 2 : 0), "bounces %d, block 2 asked: %d", i,
                 u.vct.bounce_block);
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* The cone tracer's settings from an error (the measured front: 8.05% at 64^3, 32 cones, stride 6;
   7.76% at 96^3, 24 cones; 7.55% at 96^3, 32 cones), its defaults without one (the front's middle),
   and the octree under a budget. */
static void test_plan_vct_settings(void)
{
    voxgi_context *ctx = plan_ctx();
    voxgi_builtin_scene bs;
    voxgi_render_desc q, used;
    voxgi_plan_info p;
    uint64_t dense;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    desc_of(&q, VOXGI_RENDER_VCT, NULL, 0);
    memset(&used, 0, sizeof used);
    q.error = 0.10;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, 0, &p) == VOXGI_OK && voxgi_render_resolve(ctx, &bs.scene, &q, &used) == VOXGI_OK && used.resolution == 64 &&
                 used.vct.cones.cones == 32 && used.vct.cone_stride == 6 && p.expected_error == 0.0805 && p.error_reachable,
             "10%%: %d^3, %d cones, stride %d (%.4f)", used.resolution, used.vct.cones.cones, used.vct.cone_stride, p.expected_error);
    q.error = 0.08;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, 0, &p) == VOXGI_OK && voxgi_render_resolve(ctx, &bs.scene, &q, &used) == VOXGI_OK && used.resolution == 96 &&
                 used.vct.cones.cones == 24 && used.vct.cone_stride == 6 && p.expected_error <= 0.08 && p.error_reachable,
             "8%%: %d^3, %d cones (%.4f)", used.resolution, used.vct.cones.cones, p.expected_error);
    q.error = 0.05;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, 0, &p) == VOXGI_OK && voxgi_render_resolve(ctx, &bs.scene, &q, &used) == VOXGI_OK && !p.error_reachable &&
                 used.resolution == 96 && used.vct.cones.cones == 32, "5%%: reachable %d, %d^3", p.error_reachable, used.resolution);
    q.resolution = 40; /* what is given stays; the error chooses the rest */
    q.vct.cones.cones = 8;
    TH_CHECK(voxgi_render_resolve(ctx, &bs.scene, &q, &used) == VOXGI_OK && used.resolution == 40 && used.vct.cones.cones == 8 && used.vct.cone_stride == 6,
             "5%% with 40^3 and 8 cones given: %d^3, %d cones, stride %d", used.resolution, used.vct.cones.cones, used.vct.cone_stride);
    /* no error: the library's default is the front's middle, anisotropic mips without a budget, 24 camera rays, one bounce */
    desc_of(&q, VOXGI_RENDER_VCT, NULL, 0);
    TH_CHECK(voxgi_render_resolve(ctx, &bs.scene, &q, &used) == VOXGI_OK && used.resolution == 96 && used.vct.cones.cones == 24 && used.vct.cone_stride == 6 &&
                 used.vct.radiance == VOXGI_VCT_ANISOTROPIC && used.samples == 24 && used.bounces == 1 && used.vct.inject_samples == 4,
             "the default: %d^3, %d cones, stride %d, radiance %d, %d samples, %d bounces, inject %d", used.resolution, used.vct.cones.cones,
             used.vct.cone_stride, (int)used.vct.radiance, used.samples, used.bounces, used.vct.inject_samples);
    q.resolution = 64;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, 0, &p) == VOXGI_OK && voxgi_render_resolve(ctx, &bs.scene, &q, &used) == VOXGI_OK &&
                 used.vct.radiance != VOXGI_VCT_OCTREE && kept(&p, VOXGI_PLAN_RADIANCE_VOLUME) == 1 && kept(&p, VOXGI_PLAN_RADIANCE_OCTREE) == 0, "no budget: dense");
    dense = item_bytes(&p, VOXGI_PLAN_RADIANCE_VOLUME);
    q.memory_budget = dense - 1;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, 0, &p) == VOXGI_OK && voxgi_render_resolve(ctx, &bs.scene, &q, &used) == VOXGI_OK &&
                 used.vct.radiance == VOXGI_VCT_OCTREE && kept(&p, VOXGI_PLAN_RADIANCE_OCTREE) == 1 && kept(&p, VOXGI_PLAN_RADIANCE_VOLUME) == 0,
             "a budget under the dense volume's %lu bytes: radiance %d", (unsigned long)dense, (int)used.vct.radiance);
    TH_CHECK(!strcmp(why(&p, VOXGI_PLAN_RADIANCE_OCTREE), "the dense volume is over the memory budget"), "%s", why(&p, VOXGI_PLAN_RADIANCE_OCTREE));
    q.memory_budget = 1000;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, 0, &p) == VOXGI_OK && voxgi_render_resolve(ctx, &bs.scene, &q, &used) == VOXGI_OK &&
                 used.vct.radiance != VOXGI_VCT_OCTREE && kept(&p, VOXGI_PLAN_RADIANCE_VOLUME) == 1, "a budget neither fits: the dense volume stays");
    q.memory_budget = dense - 1; /* a radiance asked for is kept whatever the budget */
    q.vct.radiance = VOXGI_VCT_ISOTROPIC;
    TH_CHECK(voxgi_render_resolve(ctx, &bs.scene, &q, &used) == VOXGI_OK && used.vct.radiance == VOXGI_VCT_ISOTROPIC, "isotropic asked for: %d", (int)used.vct.radiance);
    q.vct.radiance = VOXGI_VCT_RADIANCE_DEFAULT;
    q.memory_budget = 0;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, VOXGI_PLAN_EVERYTHING, &p) == VOXGI_OK && kept(&p, VOXGI_PLAN_EMISSION) == 1 && kept(&p, VOXGI_PLAN_BOUNCES) == 1,
             "everything kept");
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, 0, &p) == VOXGI_OK && kept(&p, VOXGI_PLAN_BOUNCES) == 0 && kept(&p, VOXGI_PLAN_VOXELIZATION) == 1 &&
                 !strcmp(why(&p, VOXGI_PLAN_VOXELIZATION), "a static scene: once (a change of lights re-injects only)"), "static: %s", why(&p, VOXGI_PLAN_VOXELIZATION));
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, VOXGI_PLAN_DYNAMIC, &p) == VOXGI_OK && kept(&p, VOXGI_PLAN_VOXELIZATION) == 1 &&
                 !strcmp(why(&p, VOXGI_PLAN_VOXELIZATION), "the geometry moves: every frame"), "dynamic: %s", why(&p, VOXGI_PLAN_VOXELIZATION));
    q.method = (voxgi_render_method)99;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, 0, &p) == VOXGI_ERR_INVALID_ARGUMENT && voxgi_render_resolve(ctx, &bs.scene, &q, &used) == VOXGI_ERR_INVALID_ARGUMENT,
             "method 99 accepted");
    q.method = VOXGI_RENDER_VCT;
    q.error = -1;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, 0, &p) == VOXGI_ERR_INVALID_ARGUMENT, "a negative error accepted");
    q.error = 0.1;
    q.method = VOXGI_RENDER_REFERENCE;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, 0, &p) == VOXGI_ERR_INVALID_ARGUMENT, "an error asked of the path tracer accepted");
    q.method = VOXGI_RENDER_VCT;
    q.error = 0;
    TH_CHECK(voxgi_plan(ctx, NULL, &q, 0, &p) == VOXGI_ERR_INVALID_ARGUMENT && voxgi_plan(ctx, &bs.scene, NULL, 0, &p) == VOXGI_ERR_INVALID_ARGUMENT &&
                 voxgi_plan(ctx, &bs.scene, &q, 0, NULL) == VOXGI_ERR_INVALID_ARGUMENT && voxgi_plan(NULL, &bs.scene, &q, 0, &p) == VOXGI_ERR_INVALID_ARGUMENT,
             "NULL accepted");
    TH_CHECK(voxgi_render_resolve(ctx, NULL, &q, &used) == VOXGI_ERR_INVALID_ARGUMENT && voxgi_render_resolve(ctx, &bs.scene, NULL, &used) == VOXGI_ERR_INVALID_ARGUMENT &&
                 voxgi_render_resolve(ctx, &bs.scene, &q, NULL) == VOXGI_ERR_INVALID_ARGUMENT && voxgi_render_resolve(NULL, &bs.scene, &q, &used) == VOXGI_ERR_INVALID_ARGUMENT,
             "resolve: NULL accepted");
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* The plan follows the desc: the radiance store asked for (the octree kept, the volume left out;
   and the other way), the direct light alone (no cones, voxels or injection), bounces, emitters
   hidden, kept voxels (nothing voxelized); and voxgi_render runs what voxgi_render_resolve gives
   for the same desc (info.used, byte for byte) and follows the plan voxgi_plan gives: the
   Cornell box at 16 x 16, 16^3. */
static void test_plan_follows_request(void)
{
    voxgi_context *ctx = plan_ctx();
    voxgi_builtin_scene bs;
    voxgi_render_desc d, used;
    voxgi_render_info info;
    voxgi_plan_info p;
    voxgi_voxels *vox = NULL;
    static float rgb[3 * 16 * 16];
    int k, i;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    view_of(&d, VOXGI_RENDER_VCT, &bs, 16);
    d.resolution = 16;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &d, 0, &p) == VOXGI_OK && kept(&p, VOXGI_PLAN_RADIANCE_VOLUME) == 1 && kept(&p, VOXGI_PLAN_RADIANCE_OCTREE) == 0 &&
                 kept(&p, VOXGI_PLAN_CONES) == 1 && kept(&p, VOXGI_PLAN_VOXELS) == 1 && kept(&p, VOXGI_PLAN_LIGHT_INJECTION) == 1,
             "the default: a dense volume, cones, voxels, injection");
    d.vct.radiance = VOXGI_VCT_OCTREE;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &d, 0, &p) == VOXGI_OK && kept(&p, VOXGI_PLAN_RADIANCE_OCTREE) == 1 && kept(&p, VOXGI_PLAN_RADIANCE_VOLUME) == 0 &&
                 !strcmp(why(&p, VOXGI_PLAN_RADIANCE_OCTREE), "asked for") && !strcmp(why(&p, VOXGI_PLAN_RADIANCE_VOLUME), "the octree asked for"),
             "the octree asked for: octree %d (%s), volume %d (%s)", kept(&p, VOXGI_PLAN_RADIANCE_OCTREE), why(&p, VOXGI_PLAN_RADIANCE_OCTREE),
             kept(&p, VOXGI_PLAN_RADIANCE_VOLUME), why(&p, VOXGI_PLAN_RADIANCE_VOLUME));
    d.memory_budget = 1; /* a volume asked for stays whatever the budget */
    d.vct.radiance = VOXGI_VCT_ANISOTROPIC;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &d, 0, &p) == VOXGI_OK && kept(&p, VOXGI_PLAN_RADIANCE_VOLUME) == 1 && kept(&p, VOXGI_PLAN_RADIANCE_OCTREE) == 0,
             "the volume asked for under a budget of 1 byte");
    {
        uint64_t aniso = item_bytes(&p, VOXGI_PLAN_RADIANCE_VOLUME);
        d.vct.radiance = VOXGI_VCT_ISOTROPIC;
        TH_CHECK(voxgi_plan(ctx, &bs.scene, &d, 0, &p) == VOXGI_OK && kept(&p, VOXGI_PLAN_RADIANCE_VOLUME) == 1 && item_bytes(&p, VOXGI_PLAN_RADIANCE_VOLUME) < aniso,
                 "isotropic mips: %lu bytes, anisotropic %lu", (unsigned long)item_bytes(&p, VOXGI_PLAN_RADIANCE_VOLUME), (unsigned long)aniso);
    }
    d.memory_budget = 0;
    d.vct.radiance = VOXGI_VCT_RADIANCE_DEFAULT;
    d.direct_only = 1;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &d, 0, &p) == VOXGI_OK && kept(&p, VOXGI_PLAN_CONES) == 0 && kept(&p, VOXGI_PLAN_VOXELS) == 0 &&
                 kept(&p, VOXGI_PLAN_LIGHT_INJECTION) == 0 && kept(&p, VOXGI_PLAN_RADIANCE_VOLUME) == 0 && kept(&p, VOXGI_PLAN_DIRECT_LIGHT) == 1 &&
                 !strcmp(why(&p, VOXGI_PLAN_CONES), "the direct light alone asked for"),
             "direct only: cones %d (%s), voxels %d, injection %d, direct %d", kept(&p, VOXGI_PLAN_CONES), why(&p, VOXGI_PLAN_CONES), kept(&p, VOXGI_PLAN_VOXELS),
             kept(&p, VOXGI_PLAN_LIGHT_INJECTION), kept(&p, VOXGI_PLAN_DIRECT_LIGHT));
    TH_CHECK(voxgi_render_resolve(ctx, &bs.scene, &d, &used) == VOXGI_OK && used.bounces == 0, "direct only: %d bounces", used.bounces);
    d.method = VOXGI_RENDER_RSM; /* the one-bounce methods too */
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &d, 0, &p) == VOXGI_OK && kept(&p, VOXGI_PLAN_GATHERS) == 0 && kept(&p, VOXGI_PLAN_REFLECTIVE_SHADOW_MAPS) == 0,
             "rsm, direct only: gathers %d, maps %d", kept(&p, VOXGI_PLAN_GATHERS), kept(&p, VOXGI_PLAN_REFLECTIVE_SHADOW_MAPS));
    d.direct_only = 0;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &d, 0, &p) == VOXGI_OK && kept(&p, VOXGI_PLAN_GATHERS) == 1 && kept(&p, VOXGI_PLAN_REFLECTIVE_SHADOW_MAPS) == 1,
             "rsm: gathers %d, maps %d", kept(&p, VOXGI_PLAN_GATHERS), kept(&p, VOXGI_PLAN_REFLECTIVE_SHADOW_MAPS));
    d.method = VOXGI_RENDER_VCT;
    d.bounces = 2;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &d, 0, &p) == VOXGI_OK && kept(&p, VOXGI_PLAN_BOUNCES) == 1, "two bounces: %s", why(&p, VOXGI_PLAN_BOUNCES));
    d.bounces = 0;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &d, 0, &p) == VOXGI_OK && kept(&p, VOXGI_PLAN_BOUNCES) == 0 && kept(&p, VOXGI_PLAN_SEEN_EMISSION) == 1,
             "one bounce: bounces %d; the camera's view: seen emission %d", kept(&p, VOXGI_PLAN_BOUNCES), kept(&p, VOXGI_PLAN_SEEN_EMISSION));
    d.hide_emitters = 1;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &d, 0, &p) == VOXGI_OK && kept(&p, VOXGI_PLAN_SEEN_EMISSION) == 0 &&
                 !strcmp(why(&p, VOXGI_PLAN_SEEN_EMISSION), "hidden (desc.hide_emitters)"), "emitters hidden: %s", why(&p, VOXGI_PLAN_SEEN_EMISSION));
    d.hide_emitters = 0;
    TH_CHECK(voxgi_render_voxelize(ctx, &bs.scene, &d, &vox) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    d.voxels = vox;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &d, 0, &p) == VOXGI_OK && kept(&p, VOXGI_PLAN_VOXELIZATION) == 0 && kept(&p, VOXGI_PLAN_LIGHT_INJECTION) == 1,
             "kept voxels: voxelization %d (%s)", kept(&p, VOXGI_PLAN_VOXELIZATION), why(&p, VOXGI_PLAN_VOXELIZATION));
    d.voxels = NULL;
    for (k = 0; k < 3; k++) { /* the default, the octree asked for, the direct light alone: what ran is what resolve says */
        voxgi_plan_info planned;
        view_of(&d, VOXGI_RENDER_VCT, &bs, 16);
        d.resolution = 16;
        d.seed = 3;
        if (k == 1) d.vct.radiance = VOXGI_VCT_OCTREE;
        if (k == 2) d.direct_only = 1;
        memset(&used, 0, sizeof used); /* the padding too (info's is zeroed by voxgi_render) */
        TH_CHECK(voxgi_render_resolve(ctx, &bs.scene, &d, &used) == VOXGI_OK && voxgi_plan(ctx, &bs.scene, &d, 0, &planned) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        TH_CHECK(voxgi_render(ctx, &bs.scene, &d, rgb, sizeof rgb, &info) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        TH_CHECK(!memcmp(&info.used, &used, sizeof used), "desc %d: info.used is not voxgi_render_resolve's", k);
        TH_CHECK(used.method == VOXGI_RENDER_VCT && used.resolution == 16 && used.vct.cones.cones == 24 && used.vct.cone_stride == 6 && used.samples == 24 &&
                     used.vct.radiance == (k == 1 ? VOXGI_VCT_OCTREE : VOXGI_VCT_ANISOTROPIC) && used.bounces == (k == 2 ? 0 : 1),
                 "desc %d resolved: %d^3, %d cones, stride %d, %d samples, radiance %d, %d bounces", k, used.resolution, used.vct.cones.cones, used.vct.cone_stride,
                 used.samples, (int)used.vct.radiance, used.bounces);
        TH_CHECK(info.plan.item_count == planned.item_count && info.plan.bytes == planned.bytes, "desc %d: the image's plan, %d items of %lu bytes; voxgi_plan's %d of %lu", k,
                 info.plan.item_count, (unsigned long)info.plan.bytes, planned.item_count, (unsigned long)planned.bytes);
        for (i = 0; i < planned.item_count && i < info.plan.item_count; i++)
            TH_CHECK(info.plan.items[i].id == planned.items[i].id && info.plan.items[i].kept == planned.items[i].kept && info.plan.items[i].bytes == planned.items[i].bytes,
                     "desc %d: the image's item %d (%s) is not voxgi_plan's", k, i, info.plan.items[i].name);
        TH_CHECK(k == 2 ? info.voxels == 0 && info.bytes == 0 && info.gathered == 0 : info.voxels > 0 && info.bytes > 0 && info.gathered > 0,
                 "desc %d: %lu voxels, %lu radiance bytes, %lu gathers", k, (unsigned long)info.voxels, (unsigned long)info.bytes, (unsigned long)info.gathered);
        TH_CHECK(info.stage_count >= 1 && voxgi_render_stage_ms(&info, info.stages[info.stage_count - 1].name) == info.stages[info.stage_count - 1].ms && voxgi_render_stage_ms(&info, "no such stage") == 0 &&
                     (voxgi_render_stage_ms(&info, "cones") > 0) == (k != 2),
                 "desc %d: the stages by name (%d stages, cones %g ms)", k, info.stage_count, voxgi_render_stage_ms(&info, "cones"));
    }
    voxgi_voxels_destroy(ctx, vox);
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* ----- every item's state and reason against the rules, over the conditions that decide them */

/* One cell of the table: the desc's bounces (-1, 0, 1, 2; or the direct light alone) and flag
   VOXGI_PLAN_EVERYTHING, and what the scene has: emitters, translucent materials, an area (rect)
   light, another light (none, a point, a directional one), any albedo, a camera. */
typedef struct plan_case {
    int bounces, direct_only, everything;
    int emitters, translucent, area, other, reflective, camera;
} plan_case;

/* What the planner reads of a case, derived from the case itself (not from a plan). */
typedef struct plan_facts {
    int lit, gi, seen, maps, areas, bounce_pass;
    const char *no_gi;
} plan_facts;

/* The item a rule expects: kept, and the reason that must come with it. */
typedef struct plan_expect {
    voxgi_plan_item_id id;
    int kept;
    const char *why;
} plan_expect;

/* Every reason the plans give, each a reason to keep (1) or to leave out (0): an item whose reason
   is of the other kind contradicts itself. */
static const struct { const char *why; int keeps; } plan_reasons[] = {
    {"everything asked for", 1}, {"what the voxels reflect", 1}, {"the voxels' light and mips face it", 1}, {"conservative, the scene's surface", 1},
    {"a static scene: once (a change of lights re-injects only)", 1}, {"the direct light into the voxels", 1}, {"light among the voxels before the cones", 1},
    {"within the budget", 1}, {"the indirect light at the pixels", 1}, {"shadow rays to the lights and emitters", 1},
    {"shadow rays to the other lights and emitters", 1}, {"the directional and spot lights' opaque depth", 1},
    {"light through translucent surfaces, a slicemap per absorption", 1}, {"the lit surfaces' points", 1}, {"the direct light's spherical harmonics", 1},
    {"the bounce's visibility", 1}, {"one bounce at the pixels", 1}, {"occlusion through the voxels", 1}, {"the image", 1}, {"one bounce from the screen", 1},
    {"soft shadows of the area lights", 1}, {"the area lights' direct light", 1}, {"the lights' and emitters' light along paths", 1}, {"emitters in view", 1},
    {"the direct light alone asked for", 0}, {"no light and no emitter", 0}, {"no reflective surface (every albedo is 0)", 0}, {"no emissive material", 0},
    {"emitters light the voxels as area lights and the pixels directly", 0}, {"no translucent material", 0}, {"the cone tracer's voxels are opaque", 0},
    {"one bounce: the cones at the pixels", 0}, {"the dense volume fits the budget (and its anisotropic mips are better)", 0},
    {"no directional or spot light", 0}, {"occlusion sees geometry only", 0}, {"occlusion through the depth buffer", 0},
    {"visibility through the depth buffer", 0}, {"no area light (rect light or emissive triangles)", 0}, {"the camera sees no emitter", 0}};

/* 1: the reason keeps, 0: it leaves out, -1: a reason this table does not know. */
static int plan_reason_keeps(const char *why)
{
    size_t i;
    for (i = 0; i < sizeof plan_reasons / sizeof plan_reasons[0]; i++)
        if (why && !strcmp(why, plan_reasons[i].why)) return plan_reasons[i].keeps;
    return -1;
}

/* The case's scene: a floor (y = 0), a lamp quad at y = 1 facing down (emissive or not), a pane
   at z = 0 (translucent or not), every albedo 0.5 or 0; a rect light above, and a point or a
   directional light. mats and lights are the caller's (3 each). */
static void plan_case_scene(const plan_case *c, voxgi_scene *sc, voxgi_mesh *mesh, quads *q, voxgi_material mats[3], voxgi_light lights[3])
{
    static const float c_floor[12] = {-1, 0, -1, -1, 0, 1, 1, 0, 1, 1, 0, -1}, c_lamp[12] = {-0.2f, 1, -0.2f, 0.2f, 1, -0.2f, 0.2f, 1, 0.2f, -0.2f, 1, 0.2f};
    static const float c_pane[12] = {-0.5f, 0.3f, 0, 0.5f, 0.3f, 0, 0.5f, 0.6f, 0, -0.5f, 0.6f, 0};
    float albedo = c->reflective ? 0.5f : 0;
    size_t nl = 0;
    int k;
    memset(mats, 0, 3 * sizeof *mats);
    memset(lights, 0, 3 * sizeof *lights);
    memset(q, 0, sizeof *q);
    for (k = 0; k < 3; k++) {
        mats[0].albedo[k] = mats[1].albedo[k] = mats[2].albedo[k] = albedo;
        mats[1].emission[k] = c->emitters ? 5.0f : 0.0f;
    }
    mats[2].transparency = c->translucent ? 0.6f : 0.0f;
    if (c->area) {
        lights[nl].type = VOXGI_LIGHT_RECT;
        lights[nl].position[1] = 2;
        lights[nl].edge_u[0] = 0.1f;
        lights[nl].edge_v[2] = 0.1f;
        lights[nl++].intensity[0] = 1;
    }
    if (c->other) {
        lights[nl].type = c->other == 1 ? VOXGI_LIGHT_POINT : VOXGI_LIGHT_DIRECTIONAL;
        lights[nl].position[1] = 0.8f;
        lights[nl].direction[1] = -1;
        lights[nl++].intensity[0] = 1;
    }
    quad(q, c_floor, 0);
    quad(q, c_lamp, 1);
    quad(q, c_pane, 2);
    scene_of_quads(sc, mesh, q, mats, 3, lights, nl);
}

/* The facts the rules read. The camera given looks from below the lamp's plane (eye y = 0.2) at
   its front, 7 degrees off its axis in a 40-degree view; the zero camera fitted to the bounds
   looks from y = 1.1, above it, at its back: an emitter is in view with the camera only. The lamp
   quad is one parallelogram: an area light of the line space's besides the rect light. */
static plan_facts plan_case_facts(const plan_case *c)
{
    plan_facts f;
    f.lit = c->everything || c->emitters || c->area || c->other;
    f.gi = f.lit && (c->everything || c->reflective) && !c->direct_only;
    f.no_gi = c->direct_only ? "the direct light alone asked for" : !f.lit ? "no light and no emitter" : "no reflective surface (every albedo is 0)";
    f.seen = c->everything || (c->emitters && c->camera);
    f.maps = c->other == 2;
    f.areas = c->area + c->emitters;
    f.bounce_pass = c->bounces == -1 || c->bounces > 1; /* 0 is the default: one bounce */
    return f;
}

static int plan_expect_add(plan_expect *e, int n, voxgi_plan_item_id id, int keep, const char *kept_why, const char *left_why)
{
    e[n].id = id;
    e[n].kept = keep;
    e[n].why = keep ? kept_why : left_why;
    return n + 1;
}

/* The items method m must plan for case c, from what each reads (part 14's rows): their number. */
static int plan_case_expect(voxgi_render_method m, const plan_case *c, plan_expect *e)
{
    plan_facts f = plan_case_facts(c);
    const char *all = "everything asked for", *dark = "no light and no emitter", *no_area = "no area light (rect light or emissive triangles)";
    int n = 0, ao = m == VOXGI_RENDER_SSAO || m == VOXGI_RENDER_VAO, layers = f.maps && c->translucent;
    switch (m) {
    case VOXGI_RENDER_REFERENCE:
        n = plan_expect_add(e, n, VOXGI_PLAN_PATH_TRACING, f.lit, "the lights' and emitters' light along paths", dark);
        break;
    case VOXGI_RENDER_VCT:
        n = plan_expect_add(e, n, VOXGI_PLAN_ALBEDO, f.gi, "what the voxels reflect", f.no_gi);
        n = plan_expect_add(e, n, VOXGI_PLAN_NORMAL, f.gi, "the voxels' light and mips face it", f.no_gi);
        n = plan_expect_add(e, n, VOXGI_PLAN_EMISSION, c->everything, all,
                            c->emitters ? "emitters light the voxels as area lights and the pixels directly" : "no emissive material");
        n = plan_expect_add(e, n, VOXGI_PLAN_OPACITY, c->everything, all, c->translucent ? "the cone tracer's voxels are opaque" : "no translucent material");
        n = plan_expect_add(e, n, VOXGI_PLAN_VOXELS, f.gi, "conservative, the scene's surface", f.no_gi);
        n = plan_expect_add(e, n, VOXGI_PLAN_VOXELIZATION, f.gi, "a static scene: once (a change of lights re-injects only)", f.no_gi);
        n = plan_expect_add(e, n, VOXGI_PLAN_LIGHT_INJECTION, f.gi, "the direct light into the voxels", f.no_gi);
        n = plan_expect_add(e, n, VOXGI_PLAN_BOUNCES, f.gi && (c->everything || f.bounce_pass), "light among the voxels before the cones",
                            f.gi ? "one bounce: the cones at the pixels" : f.no_gi);
        n = plan_expect_add(e, n, VOXGI_PLAN_RADIANCE_VOLUME, f.gi, "within the budget", f.no_gi); /* no budget: the dense volume */
        n = plan_expect_add(e, n, VOXGI_PLAN_RADIANCE_OCTREE, 0, "", f.gi ? "the dense volume fits the budget (and its anisotropic mips are better)" : f.no_gi);
        n = plan_expect_add(e, n, VOXGI_PLAN_CONES, f.gi, "the indirect light at the pixels", f.no_gi);
        n = plan_expect_add(e, n, VOXGI_PLAN_DIRECT_LIGHT, f.lit, "shadow rays to the lights and emitters", dark);
        break;
    case VOXGI_RENDER_TSM: /* a map per directional light, a layer per translucent absorption (one here) */
        n = plan_expect_add(e, n, VOXGI_PLAN_SHADOW_MAPS, f.maps, "the directional and spot lights' opaque depth", "no directional or spot light");
        n = plan_expect_add(e, n, VOXGI_PLAN_TRANSMITTANCE_LAYERS, c->everything || layers, layers ? "light through translucent surfaces, a slicemap per absorption" : all,
                            !f.maps ? "no directional or spot light" : "no translucent material");
        n = plan_expect_add(e, n, VOXGI_PLAN_DIRECT_LIGHT, f.lit, "shadow rays to the other lights and emitters", dark);
        break;
    case VOXGI_RENDER_RSM:
    case VOXGI_RENDER_SH:
        if (m == VOXGI_RENDER_RSM) n = plan_expect_add(e, n, VOXGI_PLAN_REFLECTIVE_SHADOW_MAPS, f.gi, "the lit surfaces' points", f.no_gi);
        else n = plan_expect_add(e, n, VOXGI_PLAN_SH_VOLUME, f.gi, "the direct light's spherical harmonics", f.no_gi);
        n = plan_expect_add(e, n, VOXGI_PLAN_VOXELS, f.gi, "the bounce's visibility", f.no_gi); /* visibility hierarchical by default */
        n = plan_expect_add(e, n, VOXGI_PLAN_GATHERS, f.gi, "one bounce at the pixels", f.no_gi);
        n = plan_expect_add(e, n, VOXGI_PLAN_DIRECT_LIGHT, f.lit, "shadow rays to the lights and emitters", dark);
        break;
    case VOXGI_RENDER_SSAO:
    case VOXGI_RENDER_VAO: /* VAO reads desc.resolution (128 by default), SSAO does not */
        n = plan_expect_add(e, n, VOXGI_PLAN_LIGHTS, c->everything, all, "occlusion sees geometry only");
        n = plan_expect_add(e, n, VOXGI_PLAN_VOXELS, m == VOXGI_RENDER_VAO, "occlusion through the voxels", "occlusion through the depth buffer");
        n = plan_expect_add(e, n, VOXGI_PLAN_OCCLUSION, 1, "the image", "");
        break;
    case VOXGI_RENDER_SSGI:
    case VOXGI_RENDER_HYBRID: /* HYBRID reads desc.resolution (128 by default), SSGI does not */
        n = plan_expect_add(e, n, VOXGI_PLAN_VOXELS, f.gi && m == VOXGI_RENDER_HYBRID, "the bounce's visibility", f.gi ? "visibility through the depth buffer" : f.no_gi);
        n = plan_expect_add(e, n, VOXGI_PLAN_SCREEN_BOUNCE, f.gi, "one bounce from the screen", f.no_gi);
        n = plan_expect_add(e, n, VOXGI_PLAN_DIRECT_LIGHT, f.lit, "shadow rays to the lights and emitters", dark);
        break;
    case VOXGI_RENDER_LINESPACE:
        n = plan_expect_add(e, n, VOXGI_PLAN_LINE_SPACE, c->everything || f.areas > 0, "soft shadows of the area lights", no_area);
        n = plan_expect_add(e, n, VOXGI_PLAN_SOFT_SHADOWS, c->everything || f.areas > 0, "the area lights' direct light", no_area);
        break;
    default:
        break;
    }
    return plan_expect_add(e, n, VOXGI_PLAN_SEEN_EMISSION, f.seen && c->emitters && !ao, "emitters in view",
                           ao ? "occlusion sees geometry only" : !c->emitters ? "no emissive material" : "the camera sees no emitter");
}

/* Every method's plan of every case (bounces -1, 0, 1, 2 and the direct light alone; with and
   without emitters, translucent materials, a rect light, a point or directional light, albedo,
   a camera; VOXGI_PLAN_EVERYTHING or not: 960 cases, 9,600 plans): the scene's counts as built;
   the plan's items exactly the rules' (derived from what each row reads: the lights, emitters,
   reflective surfaces, the view, desc.bounces with 0 meaning one), each kept or left out as they
   say, with the reason they name; and no item's reason of the other kind (plan_reasons).
   Measured: 9,600 plans, 0 disagree, in under 0.1 s. */
static void test_plan_items_follow_rules(void)
{
    static const int bounce_cases[5][2] = {{-1, 0}, {0, 0}, {1, 0}, {2, 0}, {1, 1}}; /* bounces, direct_only */
    voxgi_context *ctx = plan_ctx();
    voxgi_camera cam;
    unsigned bits;
    static const char *const methods[VOXGI_RENDER_METHOD_COUNT] = {"reference", "vct", "tsm", "rsm", "sh", "ssao", "vao", "ssgi", "hybrid", "linespace"};
    int m, bad = 0, plans = 0;
    memset(&cam, 0, sizeof cam);
    cam.eye[1] = 0.2f;
    cam.eye[2] = -3;
    cam.target[1] = 0.6f;
    cam.fovy_degrees = 40;
    cam.width = cam.height = 16;
    TH_CHECK(ctx != NULL, "no context");
    for (bits = 0; ctx && bits < 5u * 3u * 64u && bad < 20; bits++) {
        plan_case c;
        voxgi_material mats[3];
        voxgi_light lights[3];
        voxgi_scene sc;
        voxgi_mesh mesh;
        quads q;
        unsigned b = bits / 192u, rest = bits % 192u;
        c.bounces = bounce_cases[b][0];
        c.direct_only = bounce_cases[b][1];
        c.other = (int)(rest % 3u);
        rest /= 3u;
        c.emitters = rest & 1u;
        c.translucent = rest >> 1 & 1u;
        c.area = rest >> 2 & 1u;
        c.reflective = rest >> 3 & 1u;
        c.camera = rest >> 4 & 1u;
        c.everything = rest >> 5 & 1u;
        plan_case_scene(&c, &sc, &mesh, &q, mats, lights);
        for (m = 0; m < VOXGI_RENDER_METHOD_COUNT && bad < 20; m++) {
            plan_expect e[VOXGI_PLAN_MAX_ITEMS + 1];
            voxgi_render_desc d;
            voxgi_plan_info p;
            int n = plan_case_expect((voxgi_render_method)m, &c, e), i, found = 0;
            char label[160];
            desc_of(&d, (voxgi_render_method)m, c.camera ? &cam : NULL, 0);
            d.bounces = c.bounces;
            d.direct_only = c.direct_only;
            snprintf(label, sizeof label, "%s, bounces %d%s, emitters %d, translucent %d, rect %d, other light %d, albedo %d, camera %d, everything %d",
                     methods[m], c.bounces, c.direct_only ? " (direct only)" : "", c.emitters, c.translucent, c.area, c.other, c.reflective,
                     c.camera, c.everything);
            if (voxgi_plan(ctx, &sc, &d, c.everything ? VOXGI_PLAN_EVERYTHING : 0, &p) != VOXGI_OK) {
                TH_CHECK(0, "%s: %s", label, voxgi_last_error(ctx));
                bad++;
                continue;
            }
            plans++;
            if (p.emissive_triangles != (uint64_t)(2 * c.emitters) || p.translucent_triangles != (uint64_t)(2 * c.translucent) || p.rect_lights != c.area ||
                p.area_lights != c.area + c.emitters || p.emitters_in_view != (c.emitters && c.camera)) {
                TH_CHECK(0, "%s: emissive %lu, translucent %lu, rect %d, areas %d, in view %d", label, (unsigned long)p.emissive_triangles,
                         (unsigned long)p.translucent_triangles, p.rect_lights, p.area_lights, p.emitters_in_view);
                bad++;
            }
            for (i = 0; i < p.item_count; i++) { /* every item: of the rules, in agreement with its reason */
                const voxgi_plan_item *it = &p.items[i];
                int k, keeps = plan_reason_keeps(it->why);
                for (k = 0; k < n && e[k].id != it->id; k++) continue;
                if (keeps != (it->kept != 0) || k == n || it->kept != e[k].kept || strcmp(it->why, e[k].why) != 0) {
                    TH_CHECK(0, "%s: %s %s - %s (a reason that %s); the rules: %s - %s", label, it->name, it->kept ? "kept" : "left out", it->why,
                             keeps < 0 ? "no table knows" : keeps ? "keeps" : "leaves out", k == n ? "no such item" : e[k].kept ? "kept" : "left out",
                             k == n ? "" : e[k].why);
                    bad++;
                }
                found += k < n;
            }
            if (found != n || p.item_count != n) {
                TH_CHECK(0, "%s: %d items, %d of the rules' %d", label, p.item_count, found, n);
                bad++;
            }
        }
    }
    printf("    %d plans, %d disagree\n", plans, bad);
    TH_CHECK(plans == 960 * VOXGI_RENDER_METHOD_COUNT || bad, "%d plans", plans);
    voxgi_destroy(ctx);
}

/* The warnings a context logged (keep_warnings), one a line. */
static char g_warnings[2048];

static void keep_warnings(voxgi_log_level level, const char *message, void *user)
{
    (void)user;
    if (level == VOXGI_LOG_WARNING && strlen(g_warnings) + strlen(message) + 2 < sizeof g_warnings) {
        strcat(g_warnings, message);
        strcat(g_warnings, "\n");
    }
}

/* voxgi_render's doc: a scene with no light and no emitter renders (VOXGI_OK), black, and one
   VOXGI_LOG_WARNING says so; with a directional light, or an emissive material, or for occlusion
   (SSAO, the reference's ao_radius) no warning. A floor quad (y = 0, facing up) seen from above
   at 8 x 8: unlit every pixel is 0 exactly; under a sun of irradiance 1 along -Y the floor's
   radiance is albedo / pi = 0.8 / pi everywhere (the floor fills the view; measured mean 0.2546,
   within 1e-4 of 0.25465). */
static void test_render_warns_without_light(void)
{
    static const float pos[12] = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
    static const uint32_t idx[6] = {0, 2, 1, 0, 3, 2};
    static float rgb[8 * 8 * 3];
    voxgi_desc cd;
    voxgi_context *ctx = NULL;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_light sun;
    voxgi_material mats[2];
    voxgi_render_desc d;
    double sum;
    size_t i;
    int variant;
    ctx_desc(&cd, VOXGI_BACKEND_CPU);
    cd.logger.func = keep_warnings;
    TH_CHECK(voxgi_create(&cd, &ctx) == VOXGI_OK, "context");
    if (!ctx) return;
    memset(&mesh, 0, sizeof mesh);
    mesh.positions = pos;
    mesh.vertex_count = 4;
    mesh.indices = idx;
    mesh.index_count = 6;
    memset(&sun, 0, sizeof sun);
    sun.type = VOXGI_LIGHT_DIRECTIONAL;
    sun.direction[1] = -1;
    sun.intensity[0] = sun.intensity[1] = sun.intensity[2] = 1;
    memset(mats, 0, sizeof mats);
    mats[0].albedo[0] = mats[0].albedo[1] = mats[0].albedo[2] = 0.8f;
    mats[1] = mats[0];
    mats[1].emission[0] = 1;
    for (variant = 0; variant < 5; variant++) { /* unlit, a sun, an emitter, unlit SSAO, unlit reference AO */
        memset(&sc, 0, sizeof sc);
        sc.meshes = &mesh;
        sc.mesh_count = 1;
        if (variant == 1) {
            sc.lights = &sun;
            sc.light_count = 1;
        }
        if (variant == 2) {
            sc.materials = mats;
            sc.material_count = 2;
            mesh.material = 1;
        } else mesh.material = 0;
        memset(&d, 0, sizeof d);
        d.method = variant == 3 ? VOXGI_RENDER_SSAO : VOXGI_RENDER_REFERENCE;
        d.camera.eye[0] = 0.01;
        d.camera.eye[1] = 3;
        d.camera.width = d.camera.height = 8;
        d.camera.fovy_degrees = 30;
        d.samples = 4;
        d.direct_only = 1;
        if (variant == 4) d.reference.ao_radius = 0.5f;
        g_warnings[0] = 0;
        TH_CHECK(voxgi_render(ctx, &sc, &d, rgb, sizeof rgb, NULL) == VOXGI_OK, "variant %d: %s", variant, voxgi_last_error(ctx));
        for (sum = 0, i = 0; i < sizeof rgb / sizeof rgb[0]; i++) sum += rgb[i];
        printf("    variant %d: mean %.4g, warnings: %s", variant, sum / (sizeof rgb / sizeof rgb[0]), g_warnings[0] ? g_warnings : "none\n");
        if (variant == 0)
            TH_CHECK(sum == 0 && strstr(g_warnings, "no light and no emitter") && !strchr(strchr(g_warnings, '\n') + 1, '\n'),
                     "unlit: sum %g, warnings '%s'", sum, g_warnings);
        else TH_CHECK(g_warnings[0] == 0 && (variant != 1 || fabs(sum / (sizeof rgb / sizeof rgb[0]) - 0.8 / 3.14159265358979) < 1e-4), "variant %d: sum %g, warnings '%s'", variant, sum, g_warnings);
    }
    voxgi_destroy(ctx);
}

/* voxgi_camera_frame_bounds against a projection written here: for boxes of many shapes and
   places (a flat one, a thin one, a point) and images wider and taller than square, the bounding
   sphere's every silhouette direction lies inside the image (the sphere's angular radius at most
   the narrower half field of view) and fills it to at least 90% (so not a tiny speck); the eye is in
   front (+Z), above (+Y) and right (+X) of the centre, looking at it. Measured: the angular radius
   is 1/1.05 = 95.2% of the narrower half-angle's sine in each case. */
static void test_camera_frame_bounds(void)
{
    static const double boxes[][6] = {{-1, -1, -1, 1, 1, 1}, {1, 1, 2, 24, 23, 24}, {-5, 0, -5, 5, 0, 5}, {0, 0, 0, 0.001, 100, 0.001}, {3, 4, 5, 3, 4, 5}};
    static const int sizes[][2] = {{256, 256}, {640, 360}, {200, 500}, {0, 0}};
    size_t b, z;
    for (b = 0; b < sizeof boxes / sizeof boxes[0]; b++)
        for (z = 0; z < sizeof sizes / sizeof sizes[0]; z++) {
            voxgi_camera cam;
            double c[3], r = 0, dist = 0, aspect, half_y, half_x, half, s;
            int a;
            memset(&cam, 0, sizeof cam);
            cam.width = sizes[z][0];
            cam.height = sizes[z][1];
            voxgi_camera_frame_bounds(boxes[b], boxes[b] + 3, &cam);
            for (a = 0; a < 3; a++) {
                c[a] = 0.5 * (boxes[b][a] + boxes[b][3 + a]);
                r += 0.25 * (boxes[b][3 + a] - boxes[b][a]) * (boxes[b][3 + a] - boxes[b][a]);
                dist += (cam.eye[a] - c[a]) * (cam.eye[a] - c[a]);
            }
            r = sqrt(r) > 0 ? sqrt(r) : 1;
            dist = sqrt(dist);
            aspect = cam.width > 0 ? (double)cam.width / cam.height : 1;
            half_y = cam.fovy_degrees * 3.14159265358979 / 360;
            half_x = atan(tan(half_y) * aspect);
            half = fmin(half_x, half_y);
            s = r / dist; /* the sine of the sphere's angular radius seen from the eye */
            TH_CHECK(cam.fovy_degrees == 40 && s <= sin(half) && s >= 0.9 * sin(half), "box %lu, %d x %d: sphere's sine %g, the narrower half-angle's %g",
                     (unsigned long)b, cam.width, cam.height, s, sin(half));
            TH_CHECK(!memcmp(cam.target, c, sizeof c) && cam.eye[2] - c[2] > 0.5 * dist && cam.eye[1] - c[1] > 0.2 * dist && cam.eye[0] - c[0] > 0.2 * dist,
                     "box %lu: eye %g %g %g, target %g %g %g", (unsigned long)b, cam.eye[0], cam.eye[1], cam.eye[2], cam.target[0], cam.target[1], cam.target[2]);
        }
}

/* Images follow their plans: the Cornell box with every albedo 0 has nothing to bounce, so the
   cone tracer voxelizes nothing and its image is the direct light's; the one-bounce images gather
   nothing and give the transmittance image's direct light; the log names what was left out. */
static void test_plan_images(void)
{
    voxgi_context *ctx = plan_ctx();
    voxgi_builtin_scene bs;
    voxgi_material black[16];
    voxgi_scene dark;
    voxgi_render_desc vd;
    voxgi_render_info vi;
    static float rgb[3 * 8 * 8], direct[3 * 8 * 8];
    size_t m;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    TH_CHECK(bs.scene.material_count <= 16, "%lu materials", (unsigned long)bs.scene.material_count);
    for (m = 0; m < bs.scene.material_count; m++) {
        black[m] = bs.scene.materials[m];
        black[m].albedo[0] = black[m].albedo[1] = black[m].albedo[2] = 0;
    }
    dark = bs.scene;
    dark.materials = black;
    view_of(&vd, VOXGI_RENDER_VCT, &bs, 8);
    vct_old_zeros(&vd);
    vd.resolution = 32;
    g_log[0] = 0;
    TH_CHECK(voxgi_render(ctx, &dark, &vd, rgb, sizeof rgb, &vi) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(vi.voxels == 0 && vi.bytes == 0 && kept(&vi.plan, VOXGI_PLAN_CONES) == 0, "black surfaces: %lu voxels, %lu radiance bytes, cones %d",
             (unsigned long)vi.voxels, (unsigned long)vi.bytes, kept(&vi.plan, VOXGI_PLAN_CONES));
    TH_CHECK(strstr(g_log, "plan: cones: left out - no reflective surface (every albedo is 0)") != NULL, "the log:\n%s", g_log);
    vd.direct_only = 1;
    TH_CHECK(voxgi_render(ctx, &dark, &vd, direct, sizeof direct, NULL) == VOXGI_OK && !memcmp(rgb, direct, sizeof rgb), "not the direct light's image");
    vd.direct_only = 0;
    TH_CHECK(voxgi_render(ctx, &bs.scene, &vd, rgb, sizeof rgb, &vi) == VOXGI_OK && vi.voxels > 0, "the lit box voxelized nothing");
    { /* the one-bounce images: without a reflective surface no maps, SH volume, voxels or gathers, and the image is the
         transmittance image's (the same direct light: here the emission alone); with one, they gather */
        voxgi_render_desc td, rd, hd, sd;
        voxgi_render_info ri, hi, si;
        int k;
        view_of(&td, VOXGI_RENDER_TSM, &bs, 8);
        view_of(&rd, VOXGI_RENDER_RSM, &bs, 8);
        view_of(&hd, VOXGI_RENDER_SH, &bs, 8);
        view_of(&sd, VOXGI_RENDER_HYBRID, &bs, 8); /* the old voxgi_ssgi_render through the voxels */
        td.samples = rd.samples = hd.samples = sd.samples = 4;
        td.seed = rd.seed = hd.seed = sd.seed = 7;
        rd.resolution = hd.resolution = 16;
        sd.resolution = 16;
        sd.screen.half_resolution = VOXGI_TOGGLE_OFF; /* the old zeros: full resolution, no blur, no hidden light */
        sd.screen.blur = -1;
        sd.screen.hidden_light = VOXGI_TOGGLE_OFF;
        TH_CHECK(voxgi_render(ctx, &dark, &td, direct, sizeof direct, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        for (k = 0; k < 2; k++) {
            const voxgi_scene *sc = k ? &bs.scene : &dark;
            TH_CHECK(voxgi_render(ctx, sc, &rd, rgb, sizeof rgb, &ri) == VOXGI_OK, "%s", voxgi_last_error(ctx));
            TH_CHECK(k ? ri.maps > 0 && ri.gathered > 0 : ri.maps == 0 && ri.gathered == 0 && !memcmp(rgb, direct, sizeof rgb), "rsm, %s: %d maps, %lu gathers",
                     k ? "lit" : "black", ri.maps, (unsigned long)ri.gathered);
            TH_CHECK(kept(&ri.plan, VOXGI_PLAN_REFLECTIVE_SHADOW_MAPS) == k && kept(&ri.plan, VOXGI_PLAN_GATHERS) == k, "rsm, %s: the plan's maps %d, gathers %d",
                     k ? "lit" : "black", kept(&ri.plan, VOXGI_PLAN_REFLECTIVE_SHADOW_MAPS), kept(&ri.plan, VOXGI_PLAN_GATHERS));
            TH_CHECK(voxgi_render(ctx, sc, &hd, rgb, sizeof rgb, &hi) == VOXGI_OK, "%s", voxgi_last_error(ctx));
            TH_CHECK(k ? hi.gathered > 0 : hi.gathered == 0 && !memcmp(rgb, direct, sizeof rgb), "sh, %s: %lu gathers", k ? "lit" : "black",
                     (unsigned long)hi.gathered);
            TH_CHECK(kept(&hi.plan, VOXGI_PLAN_SH_VOLUME) == k, "sh, %s: the plan's volume %d", k ? "lit" : "black", kept(&hi.plan, VOXGI_PLAN_SH_VOLUME));
            TH_CHECK(voxgi_render(ctx, sc, &sd, rgb, sizeof rgb, &si) == VOXGI_OK, "%s", voxgi_last_error(ctx));
            TH_CHECK(k ? si.gathered > 0 : si.gathered == 0 && !memcmp(rgb, direct, sizeof rgb), "ssgi, %s: %lu gathers", k ? "lit" : "black",
                     (unsigned long)si.gathered);
            TH_CHECK(kept(&si.plan, VOXGI_PLAN_SCREEN_BOUNCE) == k, "hybrid, %s: the plan's screen bounce %d", k ? "lit" : "black", kept(&si.plan, VOXGI_PLAN_SCREEN_BOUNCE));
        }
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* A static scene's light-only update: the cone tracer's voxels, made once by voxgi_render_voxelize,
   and its ray scene (voxgi_ray_scene_create) give bit for bit the image that makes its own,
   under the scene's light and under a moved and brighter one, with bounces, on the CPU and on GL
   (where the moved light's image must differ from the first: the voxels' light is re-injected,
   not kept), and with a mesh of unindexed triangles added. Voxels of another resolution, of a
   scene with other bounds or fewer triangles, or without normals are refused; so is a ray scene
   of other triangles (the Cornell box's, and the scene's own with one vertex moved). */
static void test_light_only_update(void)
{
    enum { W = 16 };
    int b;
    for (b = 0; b < 2; b++) {
        voxgi_context *ctx;
        voxgi_builtin_scene bs, box;
        voxgi_render_desc vd;
        voxgi_render_info vi;
        voxgi_voxels_info xi;
        voxgi_voxels *vox = NULL, *plain = NULL;
        voxgi_ray_scene *rays = NULL;
        voxgi_voxelize_desc xd;
        voxgi_light moved[4];
        voxgi_scene sc, fewer;
        voxgi_mesh mesh;
        voxgi_fit_desc fit;
        voxgi_grid g;
        static float fresh[W * W * 3], kept[W * W * 3], first[W * W * 3];
        if (b && !have_gl()) return;
        ctx = make_ctx(b ? VOXGI_BACKEND_GL : VOXGI_BACKEND_CPU, 0);
        voxgi_builtin_scene_create(ctx, "rsm-walls", &bs);
        voxgi_builtin_scene_create(ctx, "cornell-box", &box);
        view_of(&vd, VOXGI_RENDER_VCT, &bs, W);
        vct_old_zeros(&vd);
        vd.resolution = 24;
        vd.samples = 2;
        vd.bounces = 2;
        vd.vct.cone_stride = 2;
        TH_CHECK(voxgi_render_voxelize(ctx, &bs.scene, &vd, &vox) == VOXGI_OK, "voxelize: %s", voxgi_last_error(ctx));
        voxgi_voxels_query(vox, &xi);
        TH_CHECK(bs.scene.light_count <= 4, "rsm-walls has %lu lights", (unsigned long)bs.scene.light_count);
        memcpy(moved, bs.scene.lights, bs.scene.light_count * sizeof *moved);
        moved[0].direction[0] = -0.5f;
        moved[0].intensity[1] *= 2;
        sc = bs.scene;
        sc.lights = moved;
        TH_CHECK(voxgi_render(ctx, &bs.scene, &vd, first, sizeof first, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        vd.voxels = vox;
        TH_CHECK(voxgi_render(ctx, &bs.scene, &vd, kept, sizeof kept, &vi) == VOXGI_OK && vi.voxels == xi.voxel_count, "%s",
                 voxgi_last_error(ctx));
        TH_CHECK(!memcmp(first, kept, sizeof kept), "%s: the kept voxels' image is not the one that voxelizes", b ? "GL" : "CPU");
        TH_CHECK(voxgi_ray_scene_create(ctx, &bs.scene, &rays) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        vd.rays = rays;
        TH_CHECK(voxgi_render(ctx, &sc, &vd, kept, sizeof kept, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        vd.voxels = NULL;
        vd.rays = NULL;
        TH_CHECK(voxgi_render(ctx, &sc, &vd, fresh, sizeof fresh, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        TH_CHECK(!memcmp(fresh, kept, sizeof kept) && memcmp(fresh, first, sizeof first), "%s: the moved light's image %s", b ? "GL" : "CPU",
                 memcmp(fresh, first, sizeof first) ? "with kept voxels is not the one that voxelizes" : "did not change");
        /* voxels and rays for something else */
        vd.rays = rays;
        {
            voxgi_result r = voxgi_render(ctx, &box.scene, &vd, kept, sizeof kept, NULL);
            TH_CHECK(r == VOXGI_ERR_INVALID_ARGUMENT && strstr(voxgi_last_error(ctx), "ray scene"), "another scene's rays: %s", voxgi_last_error(ctx));
        }
        {
            voxgi_ray_scene *bent = NULL;
            voxgi_mesh m1 = bs.scene.meshes[0];
            voxgi_scene s1 = bs.scene;
            float *moved_pos = (float *)malloc(12 * m1.vertex_count);
            size_t v;
            for (v = 0; moved_pos && v < 3 * m1.vertex_count; v++) moved_pos[v] = m1.positions[v];
            if (moved_pos) moved_pos[3 * (m1.vertex_count / 2) + 1] += 1e-3f; /* one vertex moved a little */
            m1.positions = moved_pos;
            m1.position_stride = 0;
            s1.meshes = &m1;
            TH_CHECK(moved_pos && voxgi_ray_scene_create(ctx, &s1, &bent) == VOXGI_OK, "%s", voxgi_last_error(ctx));
            vd.rays = bent;
            TH_CHECK(voxgi_render(ctx, &bs.scene, &vd, kept, sizeof kept, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "a ray scene with a vertex moved taken");
            voxgi_ray_scene_destroy(ctx, bent);
            free(moved_pos);
        }
        vd.rays = NULL;
        vd.voxels = vox;
        vd.resolution = 32;
        TH_CHECK(voxgi_render(ctx, &bs.scene, &vd, kept, sizeof kept, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "another resolution taken");
        vd.resolution = 24;
        TH_CHECK(voxgi_render(ctx, &box.scene, &vd, kept, sizeof kept, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "another scene taken");
        fewer = bs.scene; /* its first triangle left out: the same bounds, one triangle fewer */
        mesh = bs.scene.meshes[0];
        mesh.indices += 3;
        mesh.index_count -= 3;
        fewer.meshes = &mesh;
        memset(&fit, 0, sizeof fit);
        fit.res = 24;
        fit.padding = 1;
        TH_CHECK(voxgi_fit_grid(ctx, &fewer, &fit, &g) == VOXGI_OK && !memcmp(g.origin, xi.grid.origin, sizeof g.origin) && g.voxel_size == xi.grid.voxel_size && !memcmp(g.res, xi.grid.res, sizeof g.res), "the first triangle set the bounds");
        {
            voxgi_result r = voxgi_render(ctx, &fewer, &vd, kept, sizeof kept, NULL);
            TH_CHECK(r == VOXGI_ERR_INVALID_ARGUMENT && strstr(voxgi_last_error(ctx), "desc.voxels"), "fewer triangles: %s (%s)", voxgi_result_string(r),
                     voxgi_last_error(ctx));
        }
        { /* a second mesh, unindexed: one triangle inside the walls */
            static const float inside[9] = {0.1f, 0.2f, 0.1f, 0.3f, 0.2f, 0.1f, 0.1f, 0.4f, 0.2f};
            voxgi_mesh two[2];
            voxgi_voxels *v2 = NULL;
            two[0] = bs.scene.meshes[0];
            memset(&two[1], 0, sizeof two[1]);
            two[1].positions = inside;
            two[1].vertex_count = 3;
            sc = bs.scene;
            sc.meshes = two;
            sc.mesh_count = 2;
            vd.voxels = NULL;
            TH_CHECK(voxgi_render_voxelize(ctx, &sc, &vd, &v2) == VOXGI_OK && voxgi_render(ctx, &sc, &vd, fresh, sizeof fresh, NULL) == VOXGI_OK, "%s",
                     voxgi_last_error(ctx));
            vd.voxels = v2;
            TH_CHECK(voxgi_render(ctx, &sc, &vd, kept, sizeof kept, NULL) == VOXGI_OK && !memcmp(fresh, kept, sizeof kept), "unindexed: %s",
                     voxgi_last_error(ctx));
            voxgi_voxels_destroy(ctx, v2);
            vd.voxels = vox;
        }
        memset(&xd, 0, sizeof xd);
        xd.grid = xi.grid;
        xd.attributes = VOXGI_ATTRIBUTE_ALBEDO;
        TH_CHECK(voxgi_voxelize(ctx, &bs.scene, &xd, &plain) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        vd.voxels = plain;
        TH_CHECK(voxgi_render(ctx, &bs.scene, &vd, kept, sizeof kept, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "voxels without normals taken");
        voxgi_voxels_destroy(ctx, plain);
        voxgi_voxels_destroy(ctx, vox);
        voxgi_ray_scene_destroy(ctx, rays);
        voxgi_builtin_scene_destroy(ctx, &box);
        voxgi_builtin_scene_destroy(ctx, &bs);
        voxgi_destroy(ctx);
    }
}

/* Whether two grids are the same, field by field (a struct's padding is not). */
static int same_grid(const voxgi_grid *a, const voxgi_grid *b)
{
    return a->origin[0] == b->origin[0] && a->origin[1] == b->origin[1] && a->origin[2] == b->origin[2] && a->voxel_size == b->voxel_size &&
           a->res[0] == b->res[0] && a->res[1] == b->res[1] && a->res[2] == b->res[2];
}

/* Renders bs's scene with desc.voxels = offered: the API promises VOXGI_ERR_INVALID_ARGUMENT naming
   desc.voxels for voxels made for other geometry or another grid. Were they taken, the message
   gives how far the image is from the fresh render (relative RMS). */
static void expect_voxels_refused(voxgi_context *ctx, const voxgi_scene *scene, voxgi_render_desc vd, const voxgi_voxels *offered, const float *fresh,
                                  size_t floats, const char *what)
{
    float *img = (float *)calloc(floats, sizeof *img);
    voxgi_result r;
    if (!img) { TH_CHECK(0, "no memory"); return; }
    vd.voxels = offered;
    r = voxgi_render(ctx, scene, &vd, img, floats * sizeof *img, NULL);
    if (r == VOXGI_OK) {
        double d2 = 0, f2 = 0;
        size_t i;
        for (i = 0; i < floats; i++) { d2 += (img[i] - fresh[i]) * (double)(img[i] - fresh[i]); f2 += fresh[i] * (double)fresh[i]; }
        TH_CHECK(0, "%s: taken, the image %.2f%% (relative RMS) from the fresh render", what, f2 > 0 ? 100 * sqrt(d2 / f2) : -1.0);
    } else {
        TH_CHECK(r == VOXGI_ERR_INVALID_ARGUMENT && strstr(voxgi_last_error(ctx), "desc.voxels"), "%s: %s (%s)", what, voxgi_result_string(r),
                 voxgi_last_error(ctx));
    }
    free(img);
}

/* Each field of the kept voxels' check refuses on its own (rsm-walls, 16 x 16, 24 voxels, CPU):
   the voxels of the scene translated by 0.5 along x (the same 24^3 grid of the same voxel size and
   as many triangles: only the origin differs); the scene's own grid with the voxel size 1.1 x, or
   2 more voxels along y; the scene without its first triangle (the same bounds and grid, one
   triangle fewer); the thin instead of the conservative method, or albedo or normal alone, on the
   same grid (test_gl_raster_kept_voxels_backend_checked: the CPU's voxels offered to a GL
   context). The scene's own voxels give the fresh render bit for bit, so the refusals are not of
   everything. With one check dropped the image is off by (relative RMS) 10.3% translated, 2.8% of
   1.1 x voxels, 6.0% a triangle fewer, 0.9% thin; 0.00% with 2 more voxels along y and on GL,
   where only the refusal tells. */
static void test_light_only_update_checks_each_field(void)
{
    enum { W = 16 };
    static float fresh[W * W * 3], kept_img[W * W * 3];
    voxgi_context *ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    voxgi_builtin_scene bs;
    voxgi_render_desc vd;
    voxgi_voxels *own = NULL, *other = NULL;
    voxgi_voxels_info own_info, oi;
    voxgi_voxelize_desc xd;
    voxgi_scene sc;
    voxgi_mesh meshes[8];
    float *moved[8];
    size_t m, v;
    int field;
    voxgi_builtin_scene_create(ctx, "rsm-walls", &bs);
    view_of(&vd, VOXGI_RENDER_VCT, &bs, W);
    vct_old_zeros(&vd);
    vd.resolution = 24;
    vd.samples = 2;
    vd.vct.cone_stride = 2;
    TH_CHECK(voxgi_render(ctx, &bs.scene, &vd, fresh, sizeof fresh, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(voxgi_render_voxelize(ctx, &bs.scene, &vd, &own) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    voxgi_voxels_query(own, &own_info);
    vd.voxels = own;
    TH_CHECK(voxgi_render(ctx, &bs.scene, &vd, kept_img, sizeof kept_img, NULL) == VOXGI_OK && !memcmp(fresh, kept_img, sizeof fresh),
             "the scene's own voxels: %s", voxgi_last_error(ctx));
    vd.voxels = NULL;
    /* origin: every vertex 0.5 further along x */
    TH_CHECK(bs.scene.mesh_count <= 8, "%lu meshes", (unsigned long)bs.scene.mesh_count);
    sc = bs.scene;
    sc.meshes = meshes;
    memset(moved, 0, sizeof moved);
    for (m = 0; m < bs.scene.mesh_count && m < 8; m++) {
        const voxgi_mesh *src = &bs.scene.meshes[m];
        size_t stride = src->position_stride ? src->position_stride : 12;
        meshes[m] = *src;
        moved[m] = (float *)malloc(12 * src->vertex_count + 1);
        TH_CHECK(moved[m] && src->positions && !src->positions_double, "mesh %lu: float positions expected", (unsigned long)m);
        if (!moved[m] || !src->positions) continue;
        for (v = 0; v < src->vertex_count; v++) {
            const float *p = (const float *)(const void *)((const char *)src->positions + v * stride);
            moved[m][3 * v] = p[0] + 0.5f;
            moved[m][3 * v + 1] = p[1];
            moved[m][3 * v + 2] = p[2];
        }
        meshes[m].positions = moved[m];
        meshes[m].position_stride = 0;
    }
    TH_CHECK(voxgi_render_voxelize(ctx, &sc, &vd, &other) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    if (other) {
        voxgi_voxels_query(other, &oi);
        TH_CHECK(oi.grid.voxel_size == own_info.grid.voxel_size && !memcmp(oi.grid.res, own_info.grid.res, sizeof oi.grid.res) &&
                 oi.triangle_count == own_info.triangle_count && oi.grid.origin[0] != own_info.grid.origin[0] &&
                 oi.grid.origin[1] == own_info.grid.origin[1] && oi.grid.origin[2] == own_info.grid.origin[2],
                 "the translated grid differs in more than its origin's x (%.17g vs %.17g)", oi.grid.voxel_size, own_info.grid.voxel_size);
        expect_voxels_refused(ctx, &bs.scene, vd, other, fresh, W * W * 3, "the scene's voxels translated by 0.5");
        voxgi_voxels_destroy(ctx, other);
        other = NULL;
    }
    for (m = 0; m < 8; m++) free(moved[m]);
    /* triangle count: the first triangle left out, the bounds kept */
    sc = bs.scene;
    meshes[0] = bs.scene.meshes[0];
    meshes[0].indices += 3;
    meshes[0].index_count -= 3;
    sc.meshes = meshes;
    TH_CHECK(bs.scene.meshes[0].indices && voxgi_render_voxelize(ctx, &sc, &vd, &other) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    if (other) {
        voxgi_voxels_query(other, &oi);
        TH_CHECK(same_grid(&oi.grid, &own_info.grid) && oi.triangle_count + 1 == own_info.triangle_count,
                 "without the first triangle: another grid, or %lu triangles", (unsigned long)oi.triangle_count);
        expect_voxels_refused(ctx, &bs.scene, vd, other, fresh, W * W * 3, "one triangle fewer");
        voxgi_voxels_destroy(ctx, other);
        other = NULL;
    }
    /* the grid's voxel size, its resolution, the method and the attributes, one at a time */
    for (field = 0; field < 5; field++) {
        static const char *const what[5] = {"voxel size 1.1 x", "2 more voxels along y", "the thin method", "albedo alone", "normal alone"};
        memset(&xd, 0, sizeof xd);
        xd.grid = own_info.grid;
        xd.attributes = field == 3 ? VOXGI_ATTRIBUTE_ALBEDO : field == 4 ? VOXGI_ATTRIBUTE_NORMAL : VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL;
        if (field == 0) xd.grid.voxel_size *= 1.1;
        if (field == 1) xd.grid.res[1] += 2;
        if (field == 2) xd.method = VOXGI_METHOD_THIN;
        TH_CHECK(voxgi_voxelize(ctx, &bs.scene, &xd, &other) == VOXGI_OK, "%s: %s", what[field], voxgi_last_error(ctx));
        if (other) expect_voxels_refused(ctx, &bs.scene, vd, other, fresh, W * W * 3, what[field]);
        voxgi_voxels_destroy(ctx, other);
        other = NULL;
    }
    voxgi_voxels_destroy(ctx, own);
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* The kept voxels' backend field (test_light_only_update_checks_each_field's last): the CPU's
   voxels of rsm-walls, offered to a GL context's render of the same view, are refused. */
static void test_gl_raster_kept_voxels_backend_checked(void)
{
    enum { W = 16 };
    static float fresh[W * W * 3];
    voxgi_context *ctx, *gl;
    voxgi_builtin_scene bs;
    voxgi_render_desc vd;
    voxgi_voxels *own = NULL;
    if (!have_gl()) return;
    ctx = make_ctx(VOXGI_BACKEND_CPU, 0);
    gl = make_ctx(VOXGI_BACKEND_GL, 0);
    voxgi_builtin_scene_create(ctx, "rsm-walls", &bs);
    view_of(&vd, VOXGI_RENDER_VCT, &bs, W);
    vct_old_zeros(&vd);
    vd.resolution = 24;
    vd.samples = 2;
    vd.vct.cone_stride = 2;
    TH_CHECK(voxgi_render_voxelize(ctx, &bs.scene, &vd, &own) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(voxgi_render(gl, &bs.scene, &vd, fresh, sizeof fresh, NULL) == VOXGI_OK, "GL: %s", voxgi_last_error(gl));
    if (own) expect_voxels_refused(gl, &bs.scene, vd, own, fresh, W * W * 3, "the CPU's voxels on GL");
    voxgi_voxels_destroy(ctx, own);
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(gl);
    voxgi_destroy(ctx);
}

/* ---------------------------------------------------------------- the G-buffer */

/* voxgi's own G-buffer rasterized on GL against the CPU's ray cast (the Cornell box, 64 x 48,
   the view's aspect stretched): the same triangle at all but 1 in 500 pixels (a shared edge or a
   silhouette may go to the neighbour; a projective depth test loses the lamp 0.1 mm below the
   ceiling at 17 pixels), there the same normal and the position within float interpolation; no
   surface where the CPU finds none. */
static void test_gl_raster_gbuffer(void)
{
    enum { W = 64, H = 48 };
    voxgi_context *ctx[2];
    voxgi_builtin_scene bs;
    voxgi_camera cam;
    static float pos[2][3 * W * H], nrm[2][3 * W * H];
    static uint32_t tri[2][W * H];
    int b, i, a, same = 0, hits = 0;
    double worst_p = 0, worst_n = 0;
    if (!have_gl()) return;
    ctx[0] = make_ctx(VOXGI_BACKEND_CPU, 0);
    ctx[1] = make_ctx(VOXGI_BACKEND_GL, 0);
    voxgi_builtin_scene_create(ctx[0], "cornell-box", &bs);
    cam = bs.camera;
    cam.width = W;
    cam.height = H;
    for (b = 0; b < 2; b++)
        TH_CHECK(voxgi_gbuffer_render(ctx[b], &bs.scene, &cam, pos[b], nrm[b], tri[b]) == VOXGI_OK, "%s: %s", b ? "GL" : "CPU", voxgi_last_error(ctx[b]));
    for (i = 0; i < W * H; i++) {
        hits += tri[0][i] != UINT32_MAX;
        if (tri[0][i] != tri[1][i]) continue;
        same++;
        for (a = 0; a < 3; a++) {
            worst_p = fmax(worst_p, fabs(pos[0][3 * i + a] - pos[1][3 * i + a]));
            worst_n = fmax(worst_n, fabs(nrm[0][3 * i + a] - nrm[1][3 * i + a]));
        }
    }
    printf("    G-buffer: %d of %d pixels on the same triangle (%d surfaces), positions within %.3g m, normals within %.3g\n", same, W * H, hits, worst_p,
           worst_n);
    TH_CHECK(hits > W * H / 2 && same >= W * H - W * H / 500 && worst_p < 1e-4 && worst_n < 1e-6, "G-buffers differ");
    voxgi_builtin_scene_destroy(ctx[0], &bs);
    voxgi_destroy(ctx[0]);
    voxgi_destroy(ctx[1]);
}

int main(void)
{
    gl_open();
    TH_RUN(test_plan_counts);
    TH_RUN(test_plan_emitters_in_view);
    TH_RUN(test_plan_bytes);
    TH_RUN(test_render_defaults);
    TH_RUN(test_plan_vct_settings);
    TH_RUN(test_plan_follows_request);
    TH_RUN(test_plan_items_follow_rules);
    TH_RUN(test_plan_images);
    TH_RUN(test_render_warns_without_light);
    TH_RUN(test_camera_frame_bounds);
    TH_RUN(test_light_only_update);
    TH_RUN(test_light_only_update_checks_each_field);
    TH_RUN(test_gl_raster_kept_voxels_backend_checked);
    TH_RUN(test_gl_raster_gbuffer);
    gl_close();
    return th_finish();
}
