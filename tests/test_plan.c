/* The planner against what is known: the scene's counts on a scene built for them, each item kept
   or left out where the scene has or lacks what it needs, its bytes against what the passes then
   allocate (exactly where the formula is the pass's, within a factor where it is an estimate from
   the surface), what the camera sees, the grid and cones from an error, the octree under a budget;
   and the images following their plans (no voxels where nothing can bounce, no line space without
   an area light), logging what they leave out. */
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

static int kept(const voxgi_plan_info *p, const char *name)
{
    const voxgi_plan_item *it = voxgi_plan_find(p, name);
    if (!it) printf("    no item %s\n", name);
    return it ? it->kept : -1;
}

static voxgi_result plan_of(voxgi_context *ctx, const voxgi_scene *sc, voxgi_plan_method m, const voxgi_camera *cam, int res, voxgi_plan_info *p)
{
    voxgi_plan_request q;
    memset(&q, 0, sizeof q);
    q.method = m;
    q.camera = cam;
    q.resolution = res;
    return voxgi_plan(ctx, sc, &q, p);
}

/* A floor, an emissive quad, a translucent triangle, a black triangle; a point, a directional and a
   rect light: every count exact. */
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
    TH_CHECK(ctx && plan_of(ctx, &sc, VOXGI_PLAN_VCT, NULL, 32, &p) == VOXGI_OK, "%s", ctx ? voxgi_last_error(ctx) : "no context");
    TH_CHECK(p.triangles == 8 && p.emissive_triangles == 2 && p.translucent_triangles == 2 && p.reflective_triangles == 4,
             "triangles %lu, emissive %lu, translucent %lu, reflective %lu", (unsigned long)p.triangles, (unsigned long)p.emissive_triangles,
             (unsigned long)p.translucent_triangles, (unsigned long)p.reflective_triangles);
    TH_CHECK(p.point_lights == 1 && p.directional_lights == 1 && p.rect_lights == 1 && p.spot_lights == 0 && p.area_lights == 2,
             "lights %d %d %d %d, areas %d", p.point_lights, p.directional_lights, p.rect_lights, p.spot_lights, p.area_lights);
    TH_CHECK(fabs(p.surface_area - (4 + 0.16 + 0.3 + 0.3)) < 1e-6, "surface %.9g", p.surface_area);
    TH_CHECK(p.emitters_in_view == -1 && p.resolution == 32, "in view %d without a camera, resolution %d", p.emitters_in_view, p.resolution);
    TH_CHECK(!kept(&p, "emission") && !kept(&p, "opacity") && kept(&p, "cones") == 1 && kept(&p, "direct light") == 1, "vct's items");
    TH_CHECK(!strcmp(voxgi_plan_find(&p, "opacity")->why, "the cone tracer's voxels are opaque"), "opacity: %s", voxgi_plan_find(&p, "opacity")->why);
    TH_CHECK(plan_of(ctx, &sc, VOXGI_PLAN_TSM, NULL, 0, &p) == VOXGI_OK && kept(&p, "transmittance layers") == 1 && kept(&p, "shadow maps") == 1, "tsm's items");
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
    TH_CHECK(plan_of(ctx, &bs.scene, VOXGI_PLAN_REFERENCE, &bs.camera, 0, &p) == VOXGI_OK && p.emitters_in_view == 1 && kept(&p, "seen emission") == 1,
             "the camera's view: %d", p.emitters_in_view);
    away = bs.camera;
    away.target[1] = bs.camera.eye[1] - 10 * (bs.camera.target[1] - bs.camera.eye[1]) - 1000; /* down at the floor from the eye */
    away.target[0] = bs.camera.eye[0];
    away.target[2] = bs.camera.eye[2] + 1;
    away.fovy_degrees = 20;
    TH_CHECK(plan_of(ctx, &bs.scene, VOXGI_PLAN_REFERENCE, &away, 0, &p) == VOXGI_OK && p.emitters_in_view == 0 && kept(&p, "seen emission") == 0,
             "looking down: %d", p.emitters_in_view);
    TH_CHECK(!strcmp(voxgi_plan_find(&p, "seen emission")->why, "the camera sees no emitter"), "%s", voxgi_plan_find(&p, "seen emission")->why);
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
        TH_CHECK(plan_of(ctx, &bs.scene, VOXGI_PLAN_REFERENCE, &away, 0, &p) == VOXGI_OK && p.emitters_in_view == 0, "the light's back: %d", p.emitters_in_view);
        away.eye[1] = c[1] - 0.5 * fabs(bs.camera.eye[2] - c[2]);
        TH_CHECK(plan_of(ctx, &bs.scene, VOXGI_PLAN_REFERENCE, &away, 0, &p) == VOXGI_OK && p.emitters_in_view == 1, "under the light: %d", p.emitters_in_view);
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* Bytes: the dense radiance volume and the transmittance maps by their own formulas (exact, but
   for the radiance volume's few region labels), the set voxels and the line space estimated. */
static void test_plan_bytes(void)
{
    voxgi_context *ctx = plan_ctx();
    voxgi_builtin_scene bs;
    voxgi_plan_info p;
    voxgi_vct_desc vd;
    voxgi_vct_info vi;
    voxgi_tsm_image_desc td;
    voxgi_tsm_image_info ti;
    voxgi_linespace *L = NULL;
    voxgi_linespace_desc ld;
    voxgi_linespace_info li;
    static float rgb[3 * 8 * 8];
    const char *names[2] = {"rsm-walls", "foliage"};
    int k;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    TH_CHECK(plan_of(ctx, &bs.scene, VOXGI_PLAN_VCT, &bs.camera, 40, &p) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    vct_view(&vd, &bs, 8);
    vd.resolution = 40;
    vd.cones.cones = 4;
    TH_CHECK(voxgi_vct_render(ctx, &bs.scene, &vd, rgb, sizeof rgb, &vi) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    {
        double dense = (double)voxgi_plan_find(&p, "radiance volume")->bytes, ratio = (double)p.voxels / (double)vi.voxels;
        TH_CHECK(fabs(dense - (double)vi.radiance_bytes) <= 1e-3 * (double)vi.radiance_bytes, "radiance volume: planned %.0f, allocated %lu", dense,
                 (unsigned long)vi.radiance_bytes);
        TH_CHECK(ratio > 0.5 && ratio < 2, "set voxels: estimated %lu, voxelized %lu", (unsigned long)p.voxels, (unsigned long)vi.voxels);
        printf("    cornell-box at 40: voxels estimated %lu, voxelized %lu; radiance %.0f planned, %lu allocated\n", (unsigned long)p.voxels,
               (unsigned long)vi.voxels, dense, (unsigned long)vi.radiance_bytes);
    }
    memset(&ld, 0, sizeof ld);
    TH_CHECK(plan_of(ctx, &bs.scene, VOXGI_PLAN_LINESPACE, NULL, 0, &p) == VOXGI_OK && voxgi_linespace_create(ctx, &bs.scene, &ld, &L) == VOXGI_OK, "%s",
             voxgi_last_error(ctx));
    voxgi_linespace_query(L, &li);
    {
        double ratio = (double)voxgi_plan_find(&p, "line space")->bytes / (double)li.bytes;
        TH_CHECK(ratio > 0.5 && ratio < 2, "line space: estimated %lu, built %lu", (unsigned long)voxgi_plan_find(&p, "line space")->bytes, (unsigned long)li.bytes);
    }
    voxgi_linespace_destroy(ctx, L);
    voxgi_builtin_scene_destroy(ctx, &bs);
    for (k = 0; k < 2; k++) { /* a sun over opaque walls: maps without layers; the foliage's leaves: with them */
        TH_CHECK(voxgi_builtin_scene_create(ctx, names[k], &bs) == VOXGI_OK, "%s", names[k]);
        TH_CHECK(plan_of(ctx, &bs.scene, VOXGI_PLAN_TSM, NULL, 0, &p) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        memset(&td, 0, sizeof td);
        td.camera = bs.camera;
        td.camera.width = td.camera.height = 8;
        TH_CHECK(voxgi_tsm_render(ctx, &bs.scene, &td, rgb, sizeof rgb, &ti) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        TH_CHECK(kept(&p, "transmittance layers") == k && voxgi_plan_find(&p, "shadow maps")->bytes + voxgi_plan_find(&p, "transmittance layers")->bytes == ti.bytes,
                 "%s: layers %d, planned %lu + %lu, allocated %lu", names[k], kept(&p, "transmittance layers"),
                 (unsigned long)voxgi_plan_find(&p, "shadow maps")->bytes, (unsigned long)voxgi_plan_find(&p, "transmittance layers")->bytes,
                 (unsigned long)ti.bytes);
        voxgi_builtin_scene_destroy(ctx, &bs);
    }
    voxgi_destroy(ctx);
}

/* The cone tracer's settings from an error (the measured front), and the octree under a budget. */
static void test_plan_vct_settings(void)
{
    voxgi_context *ctx = plan_ctx();
    voxgi_builtin_scene bs;
    voxgi_plan_request q;
    voxgi_plan_info p;
    uint64_t dense;
    TH_CHECK(ctx && voxgi_builtin_scene_create(ctx, "cornell-box", &bs) == VOXGI_OK, "cornell-box");
    memset(&q, 0, sizeof q);
    q.error = 0.10;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, &p) == VOXGI_OK && p.resolution == 64 && p.cones == 32 && p.cone_stride == 6 && p.error_reachable,
             "10%%: %d^3, %d cones, stride %d", p.resolution, p.cones, p.cone_stride);
    q.error = 0.08;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, &p) == VOXGI_OK && p.resolution == 96 && p.cones == 24 && p.expected_error <= 0.08 && p.error_reachable,
             "8%%: %d^3, %d cones (%.4f)", p.resolution, p.cones, p.expected_error);
    q.error = 0.05;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, &p) == VOXGI_OK && !p.error_reachable && p.resolution == 96 && p.cones == 32, "5%%: reachable %d, %d^3",
             p.error_reachable, p.resolution);
    q.error = 0;
    q.resolution = 64;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, &p) == VOXGI_OK && !p.octree && kept(&p, "radiance volume") == 1, "no budget: dense");
    dense = voxgi_plan_find(&p, "radiance volume")->bytes;
    q.memory_budget = dense - 1;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, &p) == VOXGI_OK && p.octree && kept(&p, "radiance octree") == 1 && !kept(&p, "radiance volume"),
             "a budget under the dense volume's %lu bytes: octree %d", (unsigned long)dense, p.octree);
    q.memory_budget = 1000;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, &p) == VOXGI_OK && !p.octree, "a budget neither fits: the dense volume stays");
    q.memory_budget = 0;
    q.everything = 1;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, &p) == VOXGI_OK && kept(&p, "emission") == 1 && kept(&p, "bounces") == 1, "everything kept");
    q.everything = 0;
    q.method = (voxgi_plan_method)99;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, &p) == VOXGI_ERR_INVALID_ARGUMENT, "method 99 accepted");
    q.method = VOXGI_PLAN_VCT;
    q.error = -1;
    TH_CHECK(voxgi_plan(ctx, &bs.scene, &q, &p) == VOXGI_ERR_INVALID_ARGUMENT, "a negative error accepted");
    q.error = 0;
    TH_CHECK(voxgi_plan(ctx, NULL, &q, &p) == VOXGI_ERR_INVALID_ARGUMENT && voxgi_plan(ctx, &bs.scene, NULL, &p) == VOXGI_ERR_INVALID_ARGUMENT &&
                 voxgi_plan(ctx, &bs.scene, &q, NULL) == VOXGI_ERR_INVALID_ARGUMENT && voxgi_plan(NULL, &bs.scene, &q, &p) == VOXGI_ERR_INVALID_ARGUMENT,
             "NULL accepted");
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
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
    voxgi_vct_desc vd;
    voxgi_vct_info vi;
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
    vct_view(&vd, &bs, 8);
    vd.resolution = 32;
    g_log[0] = 0;
    TH_CHECK(voxgi_vct_render(ctx, &dark, &vd, rgb, sizeof rgb, &vi) == VOXGI_OK, "%s", voxgi_last_error(ctx));
    TH_CHECK(vi.voxels == 0 && vi.radiance_bytes == 0, "black surfaces: %lu voxels, %lu radiance bytes", (unsigned long)vi.voxels, (unsigned long)vi.radiance_bytes);
    TH_CHECK(strstr(g_log, "plan: cones: left out - no reflective surface (every albedo is 0)") != NULL, "the log:\n%s", g_log);
    vd.no_gi = 1;
    TH_CHECK(voxgi_vct_render(ctx, &dark, &vd, direct, sizeof direct, NULL) == VOXGI_OK && !memcmp(rgb, direct, sizeof rgb), "not the direct light's image");
    vd.no_gi = 0;
    TH_CHECK(voxgi_vct_render(ctx, &bs.scene, &vd, rgb, sizeof rgb, &vi) == VOXGI_OK && vi.voxels > 0, "the lit box voxelized nothing");
    { /* the one-bounce images: without a reflective surface no maps, SH volume, voxels or gathers, and the image is the
         transmittance image's (the same direct light: here the emission alone); with one, they gather */
        voxgi_tsm_image_desc td;
        voxgi_rsm_image_desc rd;
        voxgi_rsm_image_info ri;
        voxgi_sh_image_desc hd;
        voxgi_sh_image_info hi;
        voxgi_ssgi_image_desc sd;
        voxgi_ssgi_image_info si;
        int k;
        memset(&td, 0, sizeof td);
        memset(&rd, 0, sizeof rd);
        memset(&hd, 0, sizeof hd);
        memset(&sd, 0, sizeof sd);
        td.camera = rd.camera = hd.camera = sd.camera = vd.camera;
        td.samples = rd.samples = hd.samples = sd.samples = 4;
        td.seed = rd.seed = hd.seed = sd.seed = 7;
        rd.resolution = hd.resolution = 16;
        sd.method = VOXGI_AO_VOXELS;
        sd.resolution = 16;
        TH_CHECK(voxgi_tsm_render(ctx, &dark, &td, direct, sizeof direct, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        for (k = 0; k < 2; k++) {
            const voxgi_scene *sc = k ? &bs.scene : &dark;
            TH_CHECK(voxgi_rsm_render(ctx, sc, &rd, rgb, sizeof rgb, &ri) == VOXGI_OK, "%s", voxgi_last_error(ctx));
            TH_CHECK(k ? ri.maps > 0 && ri.gathered > 0 : ri.maps == 0 && ri.gathered == 0 && !memcmp(rgb, direct, sizeof rgb), "rsm, %s: %d maps, %lu gathers",
                     k ? "lit" : "black", ri.maps, (unsigned long)ri.gathered);
            TH_CHECK(voxgi_sh_render(ctx, sc, &hd, rgb, sizeof rgb, &hi) == VOXGI_OK, "%s", voxgi_last_error(ctx));
            TH_CHECK(k ? hi.gathered > 0 : hi.gathered == 0 && !memcmp(rgb, direct, sizeof rgb), "sh, %s: %lu gathers", k ? "lit" : "black",
                     (unsigned long)hi.gathered);
            TH_CHECK(voxgi_ssgi_render(ctx, sc, &sd, rgb, sizeof rgb, &si) == VOXGI_OK, "%s", voxgi_last_error(ctx));
            TH_CHECK(k ? si.gathered > 0 : si.gathered == 0 && !memcmp(rgb, direct, sizeof rgb), "ssgi, %s: %lu gathers", k ? "lit" : "black",
                     (unsigned long)si.gathered);
        }
    }
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_destroy(ctx);
}

/* A static scene's light-only update: the cone tracer's voxels, made once by voxgi_vct_voxelize,
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
        voxgi_vct_desc vd;
        voxgi_vct_info vi;
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
        vct_view(&vd, &bs, W);
        vd.resolution = 24;
        vd.samples = 2;
        vd.bounces = 2;
        vd.cone_stride = 2;
        TH_CHECK(voxgi_vct_voxelize(ctx, &bs.scene, &vd, &vox) == VOXGI_OK, "voxelize: %s", voxgi_last_error(ctx));
        voxgi_voxels_query(vox, &xi);
        TH_CHECK(bs.scene.light_count <= 4, "rsm-walls has %lu lights", (unsigned long)bs.scene.light_count);
        memcpy(moved, bs.scene.lights, bs.scene.light_count * sizeof *moved);
        moved[0].direction[0] = -0.5f;
        moved[0].intensity[1] *= 2;
        sc = bs.scene;
        sc.lights = moved;
        TH_CHECK(voxgi_vct_render(ctx, &bs.scene, &vd, first, sizeof first, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        vd.voxels = vox;
        TH_CHECK(voxgi_vct_render(ctx, &bs.scene, &vd, kept, sizeof kept, &vi) == VOXGI_OK && vi.voxels == xi.voxel_count, "%s",
                 voxgi_last_error(ctx));
        TH_CHECK(!memcmp(first, kept, sizeof kept), "%s: the kept voxels' image is not the one that voxelizes", b ? "GL" : "CPU");
        TH_CHECK(voxgi_ray_scene_create(ctx, &bs.scene, &rays) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        vd.rays = rays;
        TH_CHECK(voxgi_vct_render(ctx, &sc, &vd, kept, sizeof kept, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        vd.voxels = NULL;
        vd.rays = NULL;
        TH_CHECK(voxgi_vct_render(ctx, &sc, &vd, fresh, sizeof fresh, NULL) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        TH_CHECK(!memcmp(fresh, kept, sizeof kept) && memcmp(fresh, first, sizeof first), "%s: the moved light's image %s", b ? "GL" : "CPU",
                 memcmp(fresh, first, sizeof first) ? "with kept voxels is not the one that voxelizes" : "did not change");
        /* voxels and rays for something else */
        vd.rays = rays;
        {
            voxgi_result r = voxgi_vct_render(ctx, &box.scene, &vd, kept, sizeof kept, NULL);
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
            TH_CHECK(voxgi_vct_render(ctx, &bs.scene, &vd, kept, sizeof kept, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "a ray scene with a vertex moved taken");
            voxgi_ray_scene_destroy(ctx, bent);
            free(moved_pos);
        }
        vd.rays = NULL;
        vd.voxels = vox;
        vd.resolution = 32;
        TH_CHECK(voxgi_vct_render(ctx, &bs.scene, &vd, kept, sizeof kept, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "another resolution taken");
        vd.resolution = 24;
        TH_CHECK(voxgi_vct_render(ctx, &box.scene, &vd, kept, sizeof kept, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "another scene taken");
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
            voxgi_result r = voxgi_vct_render(ctx, &fewer, &vd, kept, sizeof kept, NULL);
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
            TH_CHECK(voxgi_vct_voxelize(ctx, &sc, &vd, &v2) == VOXGI_OK && voxgi_vct_render(ctx, &sc, &vd, fresh, sizeof fresh, NULL) == VOXGI_OK, "%s",
                     voxgi_last_error(ctx));
            vd.voxels = v2;
            TH_CHECK(voxgi_vct_render(ctx, &sc, &vd, kept, sizeof kept, NULL) == VOXGI_OK && !memcmp(fresh, kept, sizeof kept), "unindexed: %s",
                     voxgi_last_error(ctx));
            voxgi_voxels_destroy(ctx, v2);
            vd.voxels = vox;
        }
        memset(&xd, 0, sizeof xd);
        xd.grid = xi.grid;
        xd.attributes = VOXGI_ATTRIBUTE_ALBEDO;
        TH_CHECK(voxgi_voxelize(ctx, &bs.scene, &xd, &plain) == VOXGI_OK, "%s", voxgi_last_error(ctx));
        vd.voxels = plain;
        TH_CHECK(voxgi_vct_render(ctx, &bs.scene, &vd, kept, sizeof kept, NULL) == VOXGI_ERR_INVALID_ARGUMENT, "voxels without normals taken");
        voxgi_voxels_destroy(ctx, plain);
        voxgi_voxels_destroy(ctx, vox);
        voxgi_ray_scene_destroy(ctx, rays);
        voxgi_builtin_scene_destroy(ctx, &box);
        voxgi_builtin_scene_destroy(ctx, &bs);
        voxgi_destroy(ctx);
    }
}

int main(void)
{
    gl_open();
    TH_RUN(test_plan_counts);
    TH_RUN(test_plan_emitters_in_view);
    TH_RUN(test_plan_bytes);
    TH_RUN(test_plan_vct_settings);
    TH_RUN(test_plan_images);
    TH_RUN(test_light_only_update);
    gl_close();
    return th_finish();
}
