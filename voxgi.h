/* voxgi.h - v0.9.0 - exact voxelization and voxel-based lighting, OpenGL 4.5 and CPU. MIT licence at the end.

   voxgi voxelizes triangle scenes and computes voxel-based lighting from them. Every GPU
   pass has a CPU twin that computes the same result, so the library works where no GL 4.5
   context exists, and the CPU twin is the oracle the GPU pass is tested against.

   USAGE
     In exactly one C or C++ file:
         #define VOXGI_IMPLEMENTATION
         #include "voxgi.h"
     Everywhere else just #include "voxgi.h". The GL backend also needs shaders.h (generated from
     the GLSL files in shaders/) next to voxgi.h; define VOXGI_NO_GL to build without it.

     voxgi_desc desc = {0};                 // zero means default; C++: voxgi_desc desc = {};
     desc.backend = VOXGI_BACKEND_CPU;      // or AUTO / GL (then set desc.gl_get_proc_address)
     voxgi_context *ctx;
     if (voxgi_create(&desc, &ctx) != VOXGI_OK) return 1;

     voxgi_mesh mesh = {0};
     mesh.positions = xyz; mesh.vertex_count = nv;     // floats; position_stride 0 = tightly packed
     mesh.indices = tri; mesh.index_count = 3 * nt;    // uint32; NULL = non-indexed
     voxgi_scene scene = {0};
     scene.meshes = &mesh; scene.mesh_count = 1;

     voxgi_voxelize_desc vd = {0};
     voxgi_fit_desc fit = {0}; fit.res = 128;          // longest axis 128 voxels
     voxgi_fit_grid(ctx, &scene, &fit, &vd.grid);
     voxgi_voxels *vox;
     if (voxgi_voxelize(ctx, &scene, &vd, &vox) == VOXGI_OK) {
         voxgi_voxels_info info; voxgi_voxels_query(vox, &info);   // info.voxel_count, info.ms, ...
         size_t bytes; voxgi_voxels_read(ctx, vox, NULL, 0, &bytes); // size query, then read
         voxgi_voxels_destroy(ctx, vox);
     } else fprintf(stderr, "%s\n", voxgi_last_error(ctx));
     voxgi_destroy(ctx);

   CONTENTS
     The header reads top to bottom in layers: each part uses only the parts above it. The
     declarations and the implementation follow the same numbered parts (a part with nothing
     public has no banner among the declarations). A helper that two parts need moves down
     into the lower one; inside a part the CPU twin comes first and its GL twin right after it.
     One exception, declared where it is used: creating a context (2) sets up the GL core (4).
       1. config          version, linkage; allocator, assertion, thread and atomic macros
       2. core            results, the context, memory, logging, progress; numbers (bit counts,
                          Morton codes, random numbers, frames); the worker pool
       3. scene           validation and flattening, materials per triangle, grids, the BVH and
                          ray casting (the reference renderer's; the ray core: voxgi_ray_scene),
                          lights and direct light, cameras
       4. GL core         GL types and the loader table, programs from the embedded shaders,
                          buffers, dispatches, raster state (absent with VOXGI_NO_GL)
       5. voxelization    exact arithmetic and triangle tests, attributes, one sub-part per
                          method (CPU, then GL), running a voxelization, OR mipmaps, segments
                          through the voxels (voxel visibility: 3D-DDA and hierarchical)
       6. volumes and mips    dense attribute volumes, isotropic and anisotropic mips, sampling
       7. octree          the sparse voxel octree: half floats, build, lookups, bricks, sampling
       8. cone tracing    cones gathering from a radiance volume or octree (below injection,
                          whose further bounces gather with cones)
       9. light injection the direct light into the voxels, and its bounces among them
      10. light-space passes  a light's view; transmittance shadow maps; reflective shadow maps;
                          the spherical-harmonics volume
      11. screen-space passes  low-discrepancy points; ambient occlusion and one bounce from the
                          screen through the depth buffer or the voxels; the edge-aware filter
      12. line space      the N-tree of line spaces: shafts between the patches of a node's faces;
                          shadow rays through it (exact, fast; per ray, packets); area lights'
                          soft shadows (rect lights, emitters paired into parallelograms)
      13. reference renderer  the path tracer every image is measured against
      14. planner and images  one image by any method (voxgi_render over a table of methods),
                          what a scene and a desc need (voxgi_plan), voxgi's own G-buffer
      15. built-in scenes and files
     Parts 7 to 13 can be left out (CONFIGURATION); voxgi_render then refuses their methods.

   METHODS: conservative (default), thin (6-separating), solid (parity / vote / flood), slicemap
   (raster), atlas and atlas-compute (texture atlas points), geometry (conservative by geometry
   shader), volume buffer (M1, M2); see voxgi_method. Conservative, thin, geometry and volume
   buffer also blend per-voxel attributes (voxgi_attribute, voxgi_blend). voxgi_voxels_reduce
   builds OR mipmaps; voxgi_volume_create builds attribute volumes with mipmaps,
   voxgi_volume_sample samples them; voxgi_svo_create builds sparse voxel octrees.

   IMAGES: voxgi_render makes an image by any method through one call (voxgi_render_desc: a head
     every method reads and a part per method; zero fields are each method's measured defaults,
     and voxgi_render_info.used reports what ran): REFERENCE (the path tracer), VCT (voxel cone
     tracing), TSM (transmittance shadow maps), RSM (reflective shadow maps), SH (an SH volume of
     the direct light), SSAO and VAO (ambient occlusion through the depth buffer or the voxels),
     SSGI and HYBRID (one bounce from the screen), LINESPACE (area lights' soft shadows through
     the line space). voxgi_plan says what an image keeps and leaves out, and why.
       voxgi_render_desc d = {0};  d.method = VOXGI_RENDER_VCT;  d.camera = cam;
       voxgi_render(ctx, &scene, &d, rgb, w * h * 12, &info);   // info.used.vct.cones.cones == 24
   LIGHTING, the lower-level calls for engines that own their frame: voxgi_inject_light puts the
   direct light into the voxels (a RADIANCE volume); voxgi_cone_trace (diffuse gathers at points),
   voxgi_cone_trace_each (single glossy or shadow cones) and voxgi_cone_trace_gl (the caller's
   G-buffer textures) gather it from a radiance source: the volume's mips or an octree of it.
   voxgi_tsm_create / voxgi_tsm_transmittance give the light through translucent surfaces;
   voxgi_rsm_create / voxgi_rsm_irradiance one bounce from reflective shadow maps through the voxels
   (voxgi_voxels_occluded); voxgi_sh_create / voxgi_sh_irradiance one bounce from an SH volume;
   voxgi_ao ambient occlusion and voxgi_ssgi one bounce at a G-buffer's pixels; voxgi_linespace_light
   soft shadows of an area light at points.

   SEMANTICS (exact; see the part banners below for each capability)
     Grid: origin o (double[3]), voxel size s (double > 0), resolution n (int[3]). Voxel (i,j,k) is
     the CLOSED box [o+(i,j,k)s, o+(i+1,j+1,k+1)s]; its linear index is i + n.x*(j + n.y*k) in
     64 bits, and bit grids store voxel L at bit (L & 31) of 32-bit word L >> 5.
     Conservative voxelization sets a voxel exactly when its closed box meets the closed triangle
     (touching counts), evaluated exactly in rational arithmetic on the float vertices and the
     double grid, so results never depend on where in the world a scene sits. Degenerate
     triangles are the segments or points they are.

   CONFIGURATION (define before the implementation)
     VOXGI_STATIC          all functions static (private copy per translation unit)
     VOXGI_NO_GL           no GL code or GL types at all; CPU backend only
     VOXGI_NO_THREADS      the CPU backend runs on the calling thread only
     VOXGI_MALLOC(sz)/VOXGI_FREE(p)   default allocator when desc.allocator is not set (both or none)
     VOXGI_ASSERT(x)       internal assertions (default: assert)
     VOXGI_NO_SIMD         no SSE or AVX2 code: the scalar code, which computes the same
     Do not compile the implementation with -ffast-math: exactness needs IEEE double arithmetic.
   Parts a program does not need, left out of the implementation: code and shaders (the declarations
   stay, so struct layouts never depend on these; the bytes they save: docs/configuration.md):
     VOXGI_NO_OCTREE           no octree (part 7): cones gather from volumes only
     VOXGI_NO_CONE_TRACING     no cone tracing (8) nor its images; with light injection (its bounces use cones): #error
     VOXGI_NO_LIGHT_INJECTION  no light injection (9), no cone-traced images, no SSGI images' hidden_light
     VOXGI_NO_LIGHT_SPACE      no tsm, rsm, SH volume (10) nor their images
     VOXGI_NO_SCREEN_SPACE     no screen-space passes (11) nor their images
     VOXGI_NO_LINE_SPACE       no line space (12) nor its images
     VOXGI_NO_REFERENCE        no reference renderer (13)

   GL LOADER (desc.gl_get_proc_address is called only while the GL 4.5 context is current)
     EGL:    desc.gl_get_proc_address = (voxgi_gl_loader)eglGetProcAddress;
     GLFW:   desc.gl_get_proc_address = (voxgi_gl_loader)glfwGetProcAddress;
     SDL2:   desc.gl_get_proc_address = (voxgi_gl_loader)SDL_GL_GetProcAddress;
     OSMesa: desc.gl_get_proc_address = (voxgi_gl_loader)OSMesaGetProcAddress;
     glad:   desc.gl_get_proc_address = (voxgi_gl_loader)glfwGetProcAddress; (the one glad used), or
             desc.gl_get_proc_address_user + desc.gl_user for loaders that take a user pointer.
     voxgi keeps its own table of exactly the GL functions it calls and its own GL typedefs, so no
     GL header is needed and none can clash; voxgi never opens libGL itself.

   VERSION HISTORY
     0.1.0  context, scenes, grids, exact conservative, thin and solid voxelization, raster
            slicemap, OR mipmaps (CPU and GL), binvox.
     0.2.0  texture atlas, geometry-shader and Volume Buffer voxelization; per-voxel attributes
            with blend modes; attribute volumes with isotropic and anisotropic mipmaps and
            sampling; materials validated.
     0.3.0  sparse voxel octree on the CPU and GL (float32 or float16 values, neighbour
            pointers, bricks), GLSL octree sampling, footprint lods, octree progress.
     0.4.0  reference path tracer, built-in scenes, light injection (shadow rays; GL distance
            maps), cone tracing (diffuse, occlusion, glossy and shadow cones, more bounces) over
            dense mips and octrees on the CPU and GL, the caller's G-buffer textures, voxgi's own
            G-buffer, cone-traced images with exact unshadowed area light.
     0.4.1  cone-traced images: each ray takes the indirect light of its own surface (edges);
            CPU injection writes its volume's level 0 in place, six-direction level 1 in one pass.
     0.5.0  the header in numbered layers with a table of contents. Cone tracing is one API over a
            radiance source (voxgi_radiance_source: a volume or an octree): voxgi_cone_trace,
            voxgi_cone_trace_each (was voxgi_trace_cones) and voxgi_cone_trace_gl replace the six
            entry points (voxgi_cone_trace_svo, voxgi_trace_cones_svo and voxgi_cone_trace_svo_gl
            are gone: set source.octree). Cone-traced images report progress at each stage.
     0.6.0  the ray core (voxgi_ray_scene): packets of coherent rays, eight-wide nodes with AVX2,
            one closest hit whatever the order (ties to the lower triangle); the raster slicemap
            exact on both backends; transmittance shadow maps (voxgi_tsm, directional and spot
            lights, GL lookups) and images with them (voxgi_tsm_render); shadow rays through
            translucent surfaces; the foliage scene; reflective shadow maps (voxgi_rsm: lights,
            area lights and emitters) and the SH volume (voxgi_sh), images with a gather stride;
            the built-in scene two-spheres is now rsm-walls (the source's name for it); GL
            gathers; screen-space ambient occlusion (voxgi_ao: depth buffer and voxels) and the
            reference renderer's AO mode.
     0.7.0  the cascaded line space (voxgi_linespace: exact and fast shadow rays, per ray and in
            packets, area lights' soft shadows, CPU and GL); the planner (voxgi_plan) that every
            image follows; one VOXGI_NO_<PART> per capability part; double-precision positions
            with a scene origin (voxgi_mesh.positions_double, voxgi_scene.origin); full global
            illumination adds the geometric tail of the bounces still to come; a cone wider than
            its height above the surface strides by that height.
     0.8.0  a static scene's light-only update (voxgi_vct_voxelize, voxgi_vct_desc.voxels and
            .rays: the cone tracer re-injects the light into kept voxels, its shadow rays walk a
            kept BVH); the line space's rays start past their point's float rounding and run in
            the tree's centred frame (scenes far from the origin in float); its rays on GL
            (voxgi_linespace_occluded), and line spaces beyond a GL storage block in parts; GL's
            screen-space rays relative to the eye.
     0.8.1  the line space's per-ray walk keeps the level it walks in registers and reads a
            crossing's bit through a table of face pairs: the same answers, 1.3-1.7x the rays;
            voxgi_linespace_desc.depth 0 is the scene's (2 under 256 triangles, else 3; was 3).
     0.9.0  one image API: voxgi_render over a table of methods (voxgi_render_desc, _info with the
            settings used and each stage's time) replaces voxgi_vct_render, voxgi_tsm_render,
            voxgi_rsm_render, voxgi_sh_render, voxgi_ssgi_render, voxgi_ao_render,
            voxgi_linespace_render and voxgi_reference_render and their descs (voxgi_vct_voxelize
            is voxgi_render_voxelize). A zero field is the method's measured default, the one the
            tool runs (VCT: 96 voxels, 24 cones at every 6th pixel, anisotropic mips; the
            reference 64 samples; the screen passes' blur and half resolution; the line space's
            4 shadow rays on 2 x 2 points); a zero camera views the scene's bounds. voxgi_plan
            plans a render desc (flags DYNAMIC, EVERYTHING; items by typed id), and the image
            follows it (VCT's octree where the volume is over the budget). Public struct layouts
            no longer depend on VOXGI_NO_*: a left-out part keeps its declarations, and its
            methods give VOXGI_ERR_UNSUPPORTED. Voxel visibility (voxgi_voxels_occluded) moved
            to part 5; the reference renderer is part 13, below the images. One traversal
            enum: voxgi_traversal (HIERARCHICAL = 0, DDA, NONE) replaces voxgi_visibility, so
            the hierarchy (the same answers in half the time) is every zero default. One
            budget rule: 0 is the context's (voxgi_linespace_desc.memory_budget was 1 GiB;
            voxgi_render_desc.memory_budget is a size_t). voxgi_ssgi_desc.hidden_light is
            hidden_radiance (the images' hidden_light is the toggle that builds it).
            voxgi_render_stage_ms reads a stage's time by name. Each method is one row of the
            images' table (defaults, plan, settings line, build, gather): voxgi_plan and
            voxgi_render_resolve refuse a left-out method as voxgi_render does
            (VOXGI_ERR_UNSUPPORTED). The maps' and the SH volume's seeds 0 are the image's.
            The bounces' geometric tail never takes a voxel's light below zero. Closed spaces:
            a surface's voxel belongs to the region its light goes into (unseen at level 0
            where it does not border it), every region closes the mips to the others, the
            labels come from the direct light and serve every bounce, and the bounces' groups
            keep to one region (two closed rooms sharing a zero-thickness wall are black with
            full GI). A voxel of surfaces facing apart (a bottom resting on a floor) takes its
            nearest surface's normal. Full GI keeps vct.bounce_block and .bounce_cones.
*/
#ifndef VOXGI_H
#define VOXGI_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* ===================================================================== 1. config */
#define VOXGI_VERSION_MAJOR 0
#define VOXGI_VERSION_MINOR 8
#define VOXGI_VERSION_PATCH 1
#define VOXGI_VERSION (VOXGI_VERSION_MAJOR * 10000 + VOXGI_VERSION_MINOR * 100 + VOXGI_VERSION_PATCH)
#define VOXGI_VERSION_STRING "0.8.1"

#ifndef VOXGI_API
#ifdef VOXGI_STATIC
#if defined(__GNUC__) || defined(__clang__)
#define VOXGI_API static __attribute__((unused)) /* a private copy need not use every function */
#else
#define VOXGI_API static
#endif
#else
#define VOXGI_API extern
#endif
#endif

/* Parts left out (CONFIGURATION): a part may not go while another that needs it stays. */
#if defined(VOXGI_NO_CONE_TRACING) && !defined(VOXGI_NO_LIGHT_INJECTION)
#error "voxgi: VOXGI_NO_CONE_TRACING needs VOXGI_NO_LIGHT_INJECTION too: light injection's bounces gather with cones"
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ===================================================================== 2. core */

typedef enum voxgi_result {
    VOXGI_OK = 0,
    VOXGI_ERR_INVALID_ARGUMENT,    /* NULL where an object is needed, unknown enum value, ... */
    VOXGI_ERR_INVALID_SCENE,       /* non-finite vertex, index out of range, bad stride, ... */
    VOXGI_ERR_EMPTY_SCENE,         /* no triangles at all */
    VOXGI_ERR_INVALID_GRID,        /* zero/negative resolution or voxel size, non-finite origin */
    VOXGI_ERR_TOO_LARGE,           /* sizes overflow, exceed a limit or the memory budget */
    VOXGI_ERR_OUT_OF_MEMORY,       /* the allocator returned NULL */
    VOXGI_ERR_BUFFER_TOO_SMALL,    /* caller memory smaller than the size query said */
    VOXGI_ERR_UNSUPPORTED,         /* compiled out, or not available on this backend */
    VOXGI_ERR_GL_UNAVAILABLE,      /* no GL 4.5 context or no loader */
    VOXGI_ERR_GL_MISSING_FUNCTION, /* the loader did not return a needed entry point */
    VOXGI_ERR_GL_SHADER,           /* a shader failed to compile or link (log in voxgi_last_error) */
    VOXGI_ERR_GL,                  /* a GL call failed */
    VOXGI_ERR_CANCELLED,           /* the progress callback asked to stop */
    VOXGI_ERR_IO,                  /* a file could not be read or written */
    VOXGI_ERR_FORMAT,              /* a file is malformed */
    VOXGI_RESULT_COUNT_
} voxgi_result;

typedef enum voxgi_backend { VOXGI_BACKEND_AUTO = 0, VOXGI_BACKEND_CPU, VOXGI_BACKEND_GL } voxgi_backend;
typedef enum voxgi_log_level { VOXGI_LOG_ERROR = 0, VOXGI_LOG_WARNING, VOXGI_LOG_INFO, VOXGI_LOG_DEBUG } voxgi_log_level;

typedef struct voxgi_context voxgi_context;
typedef void (*voxgi_gl_proc)(void);
typedef voxgi_gl_proc (*voxgi_gl_loader)(const char *name);
typedef voxgi_gl_proc (*voxgi_gl_loader_user)(const char *name, void *user);

typedef struct voxgi_allocator {
    void *(*alloc)(size_t size, void *user);   /* both or neither; NULL = VOXGI_MALLOC */
    void (*free)(void *ptr, void *user);
    void *user;
} voxgi_allocator;
typedef struct voxgi_logger {
    void (*func)(voxgi_log_level level, const char *message, void *user); /* NULL = silent */
    void *user;
} voxgi_logger;
typedef struct voxgi_progress {
    /* Called from the calling thread during long work, with the share of the named stage done
       (stages nest: voxgi_render's voxelization reports its own); every voxgi_render reports at
       least "<method>: built" between its structures and its image. Return non-zero to cancel:
       the call then returns VOXGI_ERR_CANCELLED, whichever report it was (the last, at 1, too),
       and makes nothing */
    int (*func)(double fraction, const char *stage, void *user);
    void *user;
} voxgi_progress;

typedef struct voxgi_desc {
    voxgi_backend backend;                     /* AUTO: GL when usable and not a software
                                                  rasterizer (voxgi_info.gl_software), else
                                                  CPU (logged) */
    voxgi_gl_loader gl_get_proc_address;       /* GL loader, or ... */
    voxgi_gl_loader_user gl_get_proc_address_user; /* ... one that takes gl_user */
    void *gl_user;
    int thread_count;                          /* CPU workers; 0 = one per core */
    size_t memory_budget;                      /* bytes a single result may use; 0 = no limit */
    voxgi_allocator allocator;
    voxgi_logger logger;
    voxgi_progress progress;
} voxgi_desc;

typedef struct voxgi_info {
    voxgi_backend backend;     /* the backend in use */
    int thread_count;          /* resolved CPU worker count */
    const char *gl_version;    /* GL_VERSION / GL_RENDERER of the current context, or "" */
    const char *gl_renderer;   /* (also when AUTO turned that GL down for the CPU) */
    int gl_software;           /* non-zero: gl_renderer rasterizes on the CPU's own cores
                                  (llvmpipe, SwiftShader, ...), so AUTO picked the CPU */
    const char *capabilities;  /* compiled-in capabilities, space separated */
} voxgi_info;

/* Creates a context. With backend GL (or AUTO picking GL), the GL 4.5 context that is current now
   is the one voxgi uses; every later call on this voxgi context must run with it current. Threads:
   a context and what it made are used by one thread at a time; contexts share nothing, so
   threads with a context each (on GL, a GL context each) run at once (tests/test_threads.c, under
   ThreadSanitizer too). */
VOXGI_API voxgi_result voxgi_create(const voxgi_desc *desc, voxgi_context **out);
VOXGI_API void voxgi_destroy(voxgi_context *ctx);
VOXGI_API voxgi_desc voxgi_query_desc(const voxgi_context *ctx);   /* with defaults resolved */
VOXGI_API void voxgi_query_info(const voxgi_context *ctx, voxgi_info *out);
VOXGI_API const char *voxgi_result_string(voxgi_result r);
VOXGI_API const char *voxgi_backend_name(voxgi_backend b);
/* Detail of the last failed call on ctx (which input was bad and why, GLSL log, ...); "" if none. */
VOXGI_API const char *voxgi_last_error(const voxgi_context *ctx);

/* ===================================================================== 3. scene */

typedef struct voxgi_material {
    float albedo[3];        /* Lambertian reflectance */
    float emission[3];      /* emitted radiance, front face only */
    float transparency;     /* 1 - opacity (zero = opaque, so zero-initialised materials are opaque) */
} voxgi_material;

typedef struct voxgi_mesh {
    const float *positions;      /* x y z floats, in the scene's frame */
    size_t position_stride;      /* bytes between vertices (any: values are read unaligned); 0 = 12 (floats) or 24 (doubles) */
    size_t vertex_count;
    const uint32_t *indices;     /* 3 per triangle; NULL = vertices taken three at a time */
    size_t index_count;
    const float *normals;        /* optional, per vertex */
    size_t normal_stride;        /* 0 = 12 */
    const float *uvs;            /* optional, per vertex */
    size_t uv_stride;            /* 0 = 8 (any, as position_stride) */
    const uint32_t *material_ids;/* optional, one per triangle */
    uint32_t material;           /* material of every triangle when material_ids is NULL */
    const double *positions_double; /* instead of positions: x y z doubles in world units, taken into the
                                     scene's frame by subtracting voxgi_scene.origin in double (large worlds) */
} voxgi_mesh;

/* Lights beside emissive materials. Intensities per colour channel:
   POINT and SPOT: radiant intensity I (irradiance I cos / d^2 at distance d); SPOT scales it by 1
   inside spot_inner (half-angle, radians) falling smoothly to 0 at spot_outer;
   DIRECTIONAL: irradiance on a surface facing it, travelling along direction;
   RECT: radiance, emitted from the parallelogram position + s edge_u + t edge_v (s, t in [0,1])
   to the side edge_u x edge_v points to. */
typedef enum voxgi_light_type { VOXGI_LIGHT_POINT = 0, VOXGI_LIGHT_SPOT, VOXGI_LIGHT_DIRECTIONAL, VOXGI_LIGHT_RECT } voxgi_light_type;
typedef struct voxgi_light {
    voxgi_light_type type;
    float position[3];            /* POINT, SPOT; RECT: a corner */
    float direction[3];           /* SPOT: its axis; DIRECTIONAL: where the light travels */
    float intensity[3];
    float edge_u[3], edge_v[3];   /* RECT */
    float spot_inner, spot_outer; /* SPOT */
} voxgi_light;

/* Every coordinate voxgi takes or gives (float positions, lights, grids, cameras, rays, images'
   points) is in the scene's frame. A large world keeps its precision by giving positions as
   doubles (voxgi_mesh.positions_double) and a frame's origin near them: float32 holds about 7
   digits, so at 1e6 a vertex is only good to 0.06 and a 0.1 mm gap closes before voxgi sees it;
   origin - positions_double is taken in double and rounded once. */
typedef struct voxgi_scene {
    const voxgi_mesh *meshes;
    size_t mesh_count;
    const voxgi_material *materials;   /* may be NULL when no mesh names a material other than 0;
                                          material 0 is then albedo 0.8, no emission, opaque */
    size_t material_count;
    const voxgi_light *lights;
    size_t light_count;
    double origin[3];             /* where the frame's zero lies in world units (for positions_double) */
} voxgi_scene;

/* Checks a scene; the message names the mesh, triangle and what is wrong. */
VOXGI_API voxgi_result voxgi_validate_scene(voxgi_context *ctx, const voxgi_scene *scene);

/* A camera for the renderers and images (gluLookAt, up +Y). */

typedef struct voxgi_camera {
    double eye[3], target[3];     /* gluLookAt with up +Y */
    double fovy_degrees;          /* vertical field of view */
    int width, height;            /* pixels */
} voxgi_camera;
/* A view that shows the whole box [lo, hi]: its bounding sphere from a three-quarter view above
   the front (+Z toward the viewer, +Y up: the eye 30 degrees toward +X and 25 degrees above the
   centre), just inside the narrower side of the image. Reads cam's fovy_degrees (0 = 40) and
   width x height (0 = square) and sets eye, target and fovy_degrees. Turn a model whose up is
   another axis into +Y first (a voxgi_camera is always +Y up). */
VOXGI_API void voxgi_camera_frame_bounds(const double lo[3], const double hi[3], voxgi_camera *cam);

/* ----- ray casting
   A scene made ready for rays (voxgi_ray_scene_create: a 4-wide BVH) answers closest hits and
   occlusion for batches of rays on the context's workers; every ray's answer depends on it alone,
   whatever the thread count. The triangle test is watertight: a ray through an edge or a vertex
   that triangles share hits one of them. Triangles are numbered as the scene lists them (mesh by
   mesh, each mesh's triangles in order). */
typedef struct voxgi_ray_scene voxgi_ray_scene;
typedef struct voxgi_ray {
    float origin[3], tmin;        /* world units; a hit counts at t in (tmin, tmax) */
    float direction[3], tmax;     /* need not be unit (t is in units of its length); zero: no hit */
} voxgi_ray;
typedef struct voxgi_ray_hit {
    float t, u, v;                /* the hit: origin + t direction = (1 - u - v) v0 + u v1 + v v2 */
    uint32_t triangle;            /* UINT32_MAX: none */
} voxgi_ray_hit;
VOXGI_API voxgi_result voxgi_ray_scene_create(voxgi_context *ctx, const voxgi_scene *scene, voxgi_ray_scene **out);
VOXGI_API void voxgi_ray_scene_destroy(voxgi_context *ctx, voxgi_ray_scene *rs);
/* The closest hit of each ray. */
VOXGI_API voxgi_result voxgi_ray_intersect(voxgi_context *ctx, const voxgi_ray_scene *rs, size_t count, const voxgi_ray *rays,
                                           voxgi_ray_hit *hits);
/* Whether each ray hits anything (1) or not (0), stopping at the first hit found. */
VOXGI_API voxgi_result voxgi_ray_occluded(voxgi_context *ctx, const voxgi_ray_scene *rs, size_t count, const voxgi_ray *rays,
                                          unsigned char *occluded);

/* ----- grids */
typedef struct voxgi_grid {
    double origin[3];       /* world position of voxel (0,0,0)'s minimum corner */
    double voxel_size;      /* edge length of the cubic voxels */
    int res[3];             /* voxels per axis, each >= 1 */
} voxgi_grid;

typedef struct voxgi_fit_desc {
    int res;                /* voxels along the longest axis of the scene; 0 = 64 */
    int per_axis;           /* 0: res^3 grid; non-zero: each axis just long enough for the scene */
    double padding;         /* empty voxels kept around the scene on each side; 0 = none */
} voxgi_fit_desc;

#define VOXGI_MAX_RES 65536
VOXGI_API voxgi_result voxgi_validate_grid(voxgi_context *ctx, const voxgi_grid *grid);
VOXGI_API voxgi_result voxgi_fit_grid(voxgi_context *ctx, const voxgi_scene *scene,
                                      const voxgi_fit_desc *fit, voxgi_grid *out);
VOXGI_API uint64_t voxgi_grid_voxel_count(const voxgi_grid *grid);

/* ===================================================================== 5. voxelization */

typedef enum voxgi_method {
    VOXGI_METHOD_CONSERVATIVE = 0,  /* voxel set <=> closed box meets closed triangle (26-separating) */
    VOXGI_METHOD_THIN,              /* 6-separating (Schwarz & Seidel 2010): every test of the
                                       conservative one with the box replaced by its inscribed
                                       octahedron (plane) and diamonds (projections) */
    VOXGI_METHOD_SOLID,             /* interior: see voxgi_solid_mode */
    VOXGI_METHOD_SLICEMAP,          /* raster slicemap (Eisemann & Decoret 2006): along the axis,
                                       every pixel centre a triangle covers (GL fill rule) sets
                                       the slice floor(depth) of the triangle's plane there */
    VOXGI_METHOD_ATLAS,             /* texture atlas points (Thiedemann et al. 2011), drawn as GL
                                       points: every atlas texel whose centre a triangle's chart
                                       covers (GL fill rule) is a point of that triangle (same
                                       barycentrics), and sets the voxel floor(point) */
    VOXGI_METHOD_ATLAS_COMPUTE,     /* the same points, one compute invocation each: the same set */
    VOXGI_METHOD_GEOMETRY,          /* the conservative set (bit for bit), by rasterization: the
                                       geometry shader projects each triangle along its dominant
                                       axis and grows it conservatively (Crassin & Green); each
                                       fragment runs the exact tests of its voxel column */
    VOXGI_METHOD_VOLUME_BUFFER,     /* Volume Buffer (Gaitatzes et al. 2011): each triangle drawn
                                       once, along its dominant axis (largest |normal| component,
                                       the lowest axis on ties), corners rounded to the 1/256
                                       subpixel grid; every pixel centre it covers (GL fill rule)
                                       sets the voxel holding the plane's depth there. On GL one
                                       layered draw per axis, attributes blended in float render
                                       targets (see voxgi_blend), then merged */
    VOXGI_METHOD_COUNT_
} voxgi_method;
VOXGI_API const char *voxgi_method_name(voxgi_method m);

typedef enum voxgi_axis { VOXGI_AXIS_DEFAULT = 0, VOXGI_AXIS_X, VOXGI_AXIS_Y, VOXGI_AXIS_Z } voxgi_axis;

/* Solid voxelization. PARITY: a voxel is set when its centre has an odd number of surface
   crossings at or below it along the axis (default z): a column centre belongs to a triangle's
   projection when strictly inside, or on an edge whose CCW-normalised direction d has d_b < 0,
   or d_b == 0 and d_a > 0 ((a, b) = the axes after the solid axis, cyclically), so shared edges
   and vertices of a closed mesh count once; triangles seen edge-on count never. Needs a closed
   mesh. VOTE: parity along x, y and z, voxel set when at least two agree: holes that do not
   face all three axes are outvoted. FLOOD: the conservative surface, plus every voxel that the
   grid's boundary cannot reach through empty voxels (6-connected): holes smaller than a voxel
   are closed by the surface itself. */
typedef enum voxgi_solid_mode { VOXGI_SOLID_PARITY = 0, VOXGI_SOLID_VOTE, VOXGI_SOLID_FLOOD } voxgi_solid_mode;

/* Texture atlas charts. AUTO: voxgi's own atlas, one chart per triangle at one scale for all
   (area-proportional), longest edge on a row of texel centres, packed on shelves at the largest
   scale that fits; a triangle whose chart would be under 1.25 texels long gets a chart whose
   centroid is a texel centre, so every triangle has at least one point. MESH: the meshes' own
   uvs (texel = uv * atlas_size); where charts overlap, the triangle drawn last (the highest
   index) owns the texel, as in GL. Chart corners are rounded to 1/256 texel, the rasterizer's
   subpixel grid, so GL and CPU see the same triangles. */
typedef enum voxgi_atlas_uv { VOXGI_ATLAS_AUTO = 0, VOXGI_ATLAS_MESH } voxgi_atlas_uv;

/* Attributes: per set voxel, a blend (voxgi_blend; by default the mean) over the triangles that
   set it (fragments, for the Volume Buffer) of each one's value. ALBEDO and EMISSION come from the material (3 floats each), OPACITY is 1 - transparency (1
   float), NORMAL is the triangle's unit geometric normal, front = counter-clockwise (3 floats;
   the mean is not renormalised: its length tells how much the normals agree). Values enter as
   24-bit fixed point of their channel's range ([0,1]; [-1,1] for normals; for emission, the
   scene's largest emitted component rounded up to a power of two) and are summed in 64-bit
   integers (a maximum keeps the largest), so a result is the same for any triangle order, thread
   count and backend, and a mean lies within half a unit (range * 2^-25) of the exact mean before
   its rounding to float. The Volume Buffer on GL blends in float render targets instead. */
typedef enum voxgi_attribute {
    VOXGI_ATTRIBUTE_ALBEDO = 1,
    VOXGI_ATTRIBUTE_NORMAL = 2,
    VOXGI_ATTRIBUTE_EMISSION = 4,
    VOXGI_ATTRIBUTE_OPACITY = 8,
    VOXGI_ATTRIBUTE_RADIANCE = 16, /* volumes and octrees only: the light voxels send out (voxgi_inject_light), stored
                                     premultiplied (radiance x alpha, alpha) so that plain linear
                                     filtering, a GPU's included, is the alpha-weighted mean; the
                                     side the voxel's mean normal faces */
    VOXGI_ATTRIBUTE_RADIANCE_BACK = 32, /* the same for the other side (a zero-thickness wall's inner face) */
    VOXGI_ATTRIBUTE_RADIANCE_SIDE = 64  /* which side a point sees: (alpha n, alpha n.c), n the unit mean normal, c the
                                     voxel's centre in grid units; always isotropic, the plain mean in the mips,
                                     so a point o lies on the back side of a (mipped) voxel where n.o < n.c */
} voxgi_attribute;

/* How a voxel combines the values of the triangles (fragments) that set it, per attribute:
   AVERAGE (the default) the mean; MAX the component-wise maximum (the Volume Buffer's GL_MAX,
   order-free); ADD the sum (for light: several sources add up). */
typedef enum voxgi_blend { VOXGI_BLEND_AVERAGE = 0, VOXGI_BLEND_MAX, VOXGI_BLEND_ADD } voxgi_blend;

typedef struct voxgi_voxelize_desc {
    voxgi_grid grid;
    voxgi_method method;
    voxgi_axis axis;              /* SOLID parity: the counting axis; SLICEMAP: the slicing axis; 0 = z */
    voxgi_solid_mode solid_mode;  /* SOLID: 0 = PARITY */
    int atomic;                   /* SLICEMAP, ATLAS on GL: 0 = logic-op OR into RGBA32UI targets, 1 = imageAtomicOr */
    int atlas_size;               /* ATLAS*: texels per side (at most 16384); 0 = from the grid: the
                                     size that holds AUTO charts at 2 texels per voxel edge, at most 8192 */
    voxgi_atlas_uv atlas_uv;      /* ATLAS*: 0 = AUTO */
    unsigned attributes;          /* CONSERVATIVE, THIN, GEOMETRY, VOLUME_BUFFER: voxgi_attribute bits; 0 = none */
    voxgi_blend blend[4];         /* per attribute (albedo, normal, emission, opacity); 0 = AVERAGE */
    int volume_slicing;           /* VOLUME_BUFFER on GL: 0 or 2 = M2 (fragment clipping), 1 = M1 (triangle slicing) */
} voxgi_voxelize_desc;

typedef struct voxgi_voxels voxgi_voxels;
typedef struct voxgi_voxels_info {
    voxgi_grid grid;
    voxgi_method method;
    voxgi_backend backend;      /* where the bits live */
    uint64_t voxel_count;       /* set voxels */
    uint64_t triangle_count;    /* triangles in the scene */
    uint64_t exact_tests; /* tests the double filter could not decide (resolved exactly) */
    uint64_t exact_triangles;   /* GL only: triangles handed whole to the exact CPU path */
    double ms;                  /* wall time of voxgi_voxelize */
    size_t bytes;               /* size of the bit grid */
    int atlas_size;             /* ATLAS*: texels per side */
    double atlas_scale;         /* ATLAS* with AUTO charts: texels per voxel edge */
    uint64_t atlas_points;      /* ATLAS*: covered texels */
    unsigned attributes;        /* voxgi_attribute bits held */
    uint64_t attribute_pairs;   /* (triangle, voxel) pairs averaged */
    uint64_t big_triangles;     /* VOLUME_BUFFER on GL: triangles drawn again by the 32-invocation pass */
    uint64_t lost_slices;       /* VOLUME_BUFFER on GL: triangle slices beyond the geometry
                                   shader's output budget (holes): 32 invocations x 56 slices (M2) or x 33
                                   (M1) per triangle, never reached below 896^3 (M2) or 528^3 (M1) */
} voxgi_voxels_info;

VOXGI_API voxgi_result voxgi_voxelize(voxgi_context *ctx, const voxgi_scene *scene,
                                      const voxgi_voxelize_desc *desc, voxgi_voxels **out);
VOXGI_API void voxgi_voxels_destroy(voxgi_context *ctx, voxgi_voxels *voxels);
VOXGI_API void voxgi_voxels_query(const voxgi_voxels *voxels, voxgi_voxels_info *out);
/* Copies the bit grid into dst (32-bit words, layout above). dst == NULL: only *needed is set. */
VOXGI_API voxgi_result voxgi_voxels_read(voxgi_context *ctx, const voxgi_voxels *voxels,
                                         uint32_t *dst, size_t dst_bytes, size_t *needed);
/* One attribute of every set voxel, in the order of the bit grid (linear index): 3 floats per
   voxel (ALBEDO, NORMAL, EMISSION) or 1 (OPACITY). dst == NULL: only *needed is set. */
VOXGI_API voxgi_result voxgi_voxels_read_attribute(voxgi_context *ctx, const voxgi_voxels *voxels, voxgi_attribute which,
                                                   float *dst, size_t dst_bytes, size_t *needed);
/* GL backend: the name of the GL shader storage buffer holding the bit grid (owned by voxels). */
VOXGI_API voxgi_result voxgi_voxels_gl_buffer(voxgi_context *ctx, const voxgi_voxels *voxels,
                                              unsigned int *gl_buffer_name);

/* OR-reduction (mipmaps of occupancy): a new voxel grid on the same backend whose voxel (i,j,k)
   is set when any voxel of the block [f*i, f*i + f) of the source is (f = factor per axis, 1 or
   2; the last block of an odd axis is clipped). factor {2,2,2} is the next level of 3D occupancy
   mips; {2,2,1} is the next level of Buchacher's OR-mipmap over columns along z. The result's
   grid keeps the origin, doubles the voxel size along reduced axes only when all are reduced
   (otherwise voxel_size is kept: the grid is then no longer cubic and is described by res). */
VOXGI_API voxgi_result voxgi_voxels_reduce(voxgi_context *ctx, const voxgi_voxels *src, const int factor[3],
                                           voxgi_voxels **out);

/* Bit helpers over a caller-held bit grid. */
static inline int voxgi_bit_get(const uint32_t *bits, uint64_t index)
{ return (int)((bits[index >> 5] >> (index & 31u)) & 1u); }

/* Voxel visibility: whether segments pass occupied voxels, by 3D-DDA (Amanatides and Woo 1987:
   voxel by voxel, in the order the segment enters them) or hierarchically (after Thiedemann
   2011, in 3D): at each voxel the coarsest empty cell of the occupancy's OR mipmaps that holds
   it is skipped whole. One rule where a segment leaves the grid: what the grid does not hold does
   not block (the segment is cut to the grid's box first; the seed's two traversals disagreed
   there). A voxel counts when the closed segment meets its box in more than a point's width of
   the traversal's rounding; both traversals compute each boundary crossing afresh from the
   segment (no sums of steps), so they agree. The voxels of the endpoints count too: a caller
   testing between two surfaces moves the ends off them first. steps (may be NULL): voxels (DDA)
   or cells (hierarchical) visited, summed. Segments (3 floats from, 3 to, per segment), not the
   voxgi_ray of the ray and line-space calls: visibility between two surfaces asks about the closed
   segment between exact points, where a ray's far end (origin + tmax direction) is rounded and its
   interval open. The two traversals give the same answers; the hierarchy takes half the time
   (voxgi report rsm), hence the default. NONE: no visibility, where a caller may leave it out
   (the images' gathers); the calls that test segments refuse it. */
typedef enum voxgi_traversal { VOXGI_TRAVERSAL_HIERARCHICAL = 0, VOXGI_TRAVERSAL_DDA, VOXGI_TRAVERSAL_NONE } voxgi_traversal;
VOXGI_API voxgi_result voxgi_voxels_occluded(voxgi_context *ctx, const voxgi_voxels *voxels, voxgi_traversal how, size_t count, const float *from,
                                             const float *to, unsigned char *occluded, uint64_t *steps);


/* ===================================================================== 6. volumes and mips */

/* Dense volumes of the attributes a voxelization averaged, with a mip chain, for the lighting
   passes to sample. Every voxel holds (value, alpha): alpha is the voxel's opacity when the
   voxels hold OPACITY, else 1 for set voxels; empty voxels are all zero. ALBEDO, NORMAL and
   EMISSION volumes hold RGBA (value in rgb), the OPACITY volume alpha alone. Level k has
   ceil(n / 2^k) voxels per axis, down to one voxel; a parent covers its 2x2x2 children, those
   beyond the grid counting as empty.
   ISOTROPIC: alpha = the children's mean alpha; value = their alpha-weighted mean (empty
   children do not darken it; a lone voxel keeps its colour at every level).
   ANISOTROPIC: six volumes per attribute, one per direction of travel (+x -x +y -y +z -z):
   each pair of children along the direction is composited front to back (premultiplied:
   c = c_near a_near + (1 - a_near) c_far a_far, a = a_near + (1 - a_near) a_far), the four
   pairs averaged, the value un-premultiplied; level 0 is the same in every direction.
   RADIANCE (voxgi_inject_light) is stored premultiplied, (radiance x alpha, alpha), and mipped by
   the same filters without the un-premultiplying: an isotropic parent is then the plain mean of
   its children, and a GPU's linear filtering of the texture is the alpha-weighted mean.
   RADIANCE_BACK is mipped as RADIANCE; RADIANCE_SIDE has one isotropic chain (direction 0) in
   either kind of volume, each parent the plain mean of its children. */
typedef enum voxgi_mip_filter { VOXGI_MIPS_ISOTROPIC = 0, VOXGI_MIPS_ANISOTROPIC } voxgi_mip_filter;
typedef enum voxgi_direction { VOXGI_DIR_POS_X = 0, VOXGI_DIR_NEG_X, VOXGI_DIR_POS_Y, VOXGI_DIR_NEG_Y, VOXGI_DIR_POS_Z, VOXGI_DIR_NEG_Z } voxgi_direction;

typedef struct voxgi_volume_desc {
    unsigned attributes;          /* voxgi_attribute bits to build (0 = all the voxels hold) */
    voxgi_mip_filter filter;
    int levels;                   /* mip levels including the base; 0 = down to one voxel */
} voxgi_volume_desc;

typedef struct voxgi_volume voxgi_volume;
typedef struct voxgi_volume_info {
    voxgi_grid grid;              /* level 0 */
    voxgi_backend backend;        /* GL: 3D textures (RGBA32F / R32F with mips); CPU: arrays */
    unsigned attributes;
    voxgi_mip_filter filter;
    int levels;
    size_t bytes;                 /* every level of every volume */
    int gl_size[3];               /* GL: the textures' base size, res rounded up to a multiple of
                                     2^(levels-1) so GL's mip chain holds every level; the padding is empty */
    double ms;
} voxgi_volume_info;

VOXGI_API voxgi_result voxgi_volume_create(voxgi_context *ctx, const voxgi_voxels *voxels, const voxgi_volume_desc *desc,
                                           voxgi_volume **out);
/* The same from dense data the caller holds: base[a] is level 0 of attribute 1 << a (albedo,
   normal, emission: 4 floats per voxel, value and alpha; opacity: 1), x fastest, or NULL. */
VOXGI_API voxgi_result voxgi_volume_create_dense(voxgi_context *ctx, const voxgi_grid *grid, const voxgi_volume_desc *desc,
                                                 const float *const base[4], voxgi_volume **out);
VOXGI_API void voxgi_volume_destroy(voxgi_context *ctx, voxgi_volume *volume);
VOXGI_API void voxgi_volume_query(const voxgi_volume *volume, voxgi_volume_info *out);
/* One level of one attribute's volume (direction: 0 for ISOTROPIC and RADIANCE_SIDE), x fastest then y then z,
   4 floats per voxel (1 for OPACITY). dst == NULL: only *needed is set. */
VOXGI_API voxgi_result voxgi_volume_read(voxgi_context *ctx, const voxgi_volume *volume, voxgi_attribute which,
                                         voxgi_direction direction, int level, float *dst, size_t dst_bytes, size_t *needed);
/* Samples one attribute at `count` points: positions in grid units (voxel (i,j,k) spans
   [i, i+1] per axis), lod >= 0 in levels (fractional: linear between the two levels around it,
   clamped to the chain), trilinear between each level's voxel centres, beyond the grid empty.
   out: 4 floats per point (1 for OPACITY). On GL a compute pass samples the textures with
   shaders/volume_sample.glsl's voxgi_sample_volume (hardware filtering), on the CPU the same in C. */
VOXGI_API voxgi_result voxgi_volume_sample(voxgi_context *ctx, const voxgi_volume *volume, voxgi_attribute which,
                                           voxgi_direction direction, size_t count, const float *positions, const float *lods,
                                           float *out);
/* The lod at which one voxel is as wide as a footprint of `diameter` voxels of level 0 (a
   cone's width where it samples): log2(diameter), 0 below one voxel. The same in GLSL:
   voxgi_lod_from_footprint (shaders/sampling.glsl). */
VOXGI_API float voxgi_lod_from_footprint(float diameter);
/* GL backend: the 3D texture of one attribute (and direction), all levels (owned by volume);
   filtering LINEAR_MIPMAP_LINEAR, clamped to an empty border, texture coordinates p / gl_size. */
VOXGI_API voxgi_result voxgi_volume_gl_texture(voxgi_context *ctx, const voxgi_volume *volume, voxgi_attribute which,
                                               voxgi_direction direction, unsigned int *gl_texture_name);

/* ===================================================================== 7. octree */

/* The voxels of a grid in an octree over the cube of 2^depth voxels (depth = ceil(log2 of the
   largest resolution), at least 1). Levels 0..depth: level 0 is the root, level depth the voxels
   themselves; a node at level l covers 2^(depth - l) voxels per axis. Children come in tiles of
   8 (child c = x + 2y + 4z of the node's halves); a node's child pointer is 1 + its tile's index,
   which leaves 0 free to mean "no children" (never also "the root"). Nodes at level depth - 1 point
   to leaf tiles: the voxel values, which carry no pointers. Every node and leaf slot holds the
   attributes as the attribute volumes do (RGBA value and alpha, opacity alone), inner nodes the
   isotropic mip of their children, so a lookup at level l equals the dense volume's level
   depth - l at the same place. An octree of a two-sided radiance (voxgi_inject_light) also holds
   RADIANCE_BACK and RADIANCE_SIDE and, where its empty space has enclosed regions, their labels
   per slot (4 bytes a node or leaf slot), so that cones keep to their region as in the volume. */
typedef struct voxgi_svo voxgi_svo;
/* How node and leaf values are stored: FLOAT32 (RGBA32F, R32F) or FLOAT16 (RGBA16F, R16F; each
   value rounded to the nearest half, ties to even; a parent is the mip of its children's stored
   values, as a GPU builds the mips of a half-float texture). */
typedef enum voxgi_svo_format { VOXGI_SVO_FLOAT32 = 0, VOXGI_SVO_FLOAT16 } voxgi_svo_format;
typedef struct voxgi_svo_desc {
    unsigned attributes;          /* voxgi_attribute bits (0 = all the voxels hold; RADIANCE alone: only the radiance) */
    int neighbours;               /* 1: also the six neighbour pointers of every node (24 bytes per node slot) */
    int bricks;                   /* 1: also a brick per inner node (64 values per node) */
    voxgi_svo_format format;
    const voxgi_volume *radiance; /* a RADIANCE volume on the voxels' grid (voxgi_inject_light), or NULL: the
                                     octree also holds RADIANCE, premultiplied as in the volume: its level 0 at
                                     the set voxels, the nodes the plain mean of their children (so sampling
                                     equals the isotropic volume's), for cone tracing (voxgi_radiance_source);
                                     a two-sided volume's RADIANCE_BACK and RADIANCE_SIDE alike, and its regions */
} voxgi_svo_desc;
typedef struct voxgi_svo_info {
    voxgi_grid grid;
    voxgi_backend backend;        /* where the octree lives */
    unsigned attributes;
    voxgi_svo_format format;
    int depth;                    /* leaves at level depth */
    uint64_t leaf_voxels;         /* set voxels */
    uint64_t nodes;               /* node slots: the root and 8 per inner tile */
    uint64_t leaf_slots;          /* 8 per leaf tile (empty slots included) */
    uint64_t level_nodes[17];     /* nodes that exist at each level 0..depth (at depth: the leaf voxels) */
    size_t structure_bytes;       /* child pointers */
    size_t neighbour_bytes;       /* neighbour pointers, when built */
    size_t brick_bytes;           /* bricks, when built */
    size_t bytes;                 /* everything: structure, neighbours, values and regions */
    size_t dense_bytes;           /* the dense equivalent: level 0 of the same attributes in the same format */
    double ms, ms_sort, ms_nodes, ms_values, ms_neighbours; /* whole build, then its passes */
} voxgi_svo_info;

VOXGI_API voxgi_result voxgi_svo_create(voxgi_context *ctx, const voxgi_voxels *voxels, const voxgi_svo_desc *desc, voxgi_svo **out);
VOXGI_API void voxgi_svo_destroy(voxgi_context *ctx, voxgi_svo *svo);
VOXGI_API void voxgi_svo_query(const voxgi_svo *svo, voxgi_svo_info *out);
/* Point lookups: the value of the node at `level` (0..depth) containing voxel coords[3i..3i+2]
   (level-depth voxel coordinates), 4 floats per point (1 for OPACITY); empty where no node is. */
VOXGI_API voxgi_result voxgi_svo_lookup(voxgi_context *ctx, const voxgi_svo *svo, voxgi_attribute which, int level, size_t count,
                                        const uint32_t *coords, float *out);
/* The node slot at `level` (1..depth-1: inner nodes) containing voxel coord, 0 where there is
   none (level 0: the root, slot 0). */
VOXGI_API voxgi_result voxgi_svo_node(voxgi_context *ctx, const voxgi_svo *svo, int level, const uint32_t coord[3], uint32_t *slot);
/* A node's neighbour slots in the order of voxgi_direction (+x -x +y -y +z -z), each at the same
   level, 0 where there is none (the root is nobody's neighbour, so 0 is free); needs desc.neighbours. */
VOXGI_API voxgi_result voxgi_svo_neighbours(voxgi_context *ctx, const voxgi_svo *svo, uint32_t slot, uint32_t out[6]);
/* Bricks (desc.bricks): inner node N at level l holds the 4x4x4 values of level l + 1 at
   2N - 1 .. 2N + 2 per axis (its children and a border one child wide, empty where no node is),
   x fastest, 4 floats per value (1 for OPACITY). A border value is the same value its neighbour
   holds inside, so a trilinear sample anywhere in N's box at level l + 1 reads N's brick alone.
   The brick of the node at `level` (0..depth-1) holding voxel coord; all empty where none is. */
VOXGI_API voxgi_result voxgi_svo_brick(voxgi_context *ctx, const voxgi_svo *svo, voxgi_attribute which, int level, const uint32_t coord[3],
                                       float *out);
/* Sampling as voxgi_volume_sample does (lod 0 = the voxels, lod depth = the root): equal to
   sampling the dense isotropic volume. With bricks, a sample whose node exists reads its brick
   after one descent (else eight lookups), with the same result bit for bit. */
VOXGI_API voxgi_result voxgi_svo_sample(voxgi_context *ctx, const voxgi_svo *svo, voxgi_attribute which, size_t count,
                                        const float *positions, const float *lods, float *out);
/* Octree files (docs/volumes-and-octrees.md, "Octree files"): a versioned little-endian format with
   the grid, depth, attributes, value format, child pointers, neighbours, values, bricks and region
   labels, so a read octree answers every query and traces every cone as the written one did.
   The core works on memory (a file is the same bytes): write with data == NULL (or capacity too
   small: VOXGI_ERR_BUFFER_TOO_SMALL) sets *size to the bytes needed. A GL octree is read back from
   its buffers; read makes an octree on the context's backend (on GL, its buffers), so a file written
   on either backend is read on either. A bad file gives VOXGI_ERR_FORMAT (truncated, wrong magic, unknown version,
   counts that disagree with the size, pointers or labels out of range) with the byte offset in
   voxgi_last_error, before anything larger than the file is allocated. */
VOXGI_API voxgi_result voxgi_svo_write_memory(voxgi_context *ctx, const voxgi_svo *svo, void *data, size_t capacity, size_t *size);
VOXGI_API voxgi_result voxgi_svo_read_memory(voxgi_context *ctx, const void *data, size_t size, voxgi_svo **out);
VOXGI_API voxgi_result voxgi_svo_write(voxgi_context *ctx, const voxgi_svo *svo, const char *path);
VOXGI_API voxgi_result voxgi_svo_read(voxgi_context *ctx, const char *path, voxgi_svo **out);

/* ===================================================================== 8. cone tracing */

/* Where cones gather from: the RADIANCE of a volume (voxgi_inject_light) or of an octree
   (voxgi_svo_desc.radiance), made on the context's backend; exactly one of the two is set. An
   octree is marched step for step as the volume is, over its isotropic mips (lod 0 = the voxels,
   up to the root), through its bricks where it has them (one-sided; a two-sided octree's three
   values and labels are read by lookups): a float32 octree gives what the isotropic volume it was
   built from gives, bit for bit on the CPU, one-sided or two-sided; on GL the march runs over the
   octree's buffers (shaders/cone_svo.glsl). */
typedef struct voxgi_radiance_source {
    const voxgi_volume *volume;
    const voxgi_svo *octree;
} voxgi_radiance_source;

/* How cones are traced (voxgi_cone_trace and its relatives, below). */
typedef struct voxgi_cone_desc {
    int cones;                    /* 0 = 16 */
    float half_angle;             /* radians; 0 = acos(1 - 1 / cones) */
    float step;                   /* fraction of the diameter per step, 0.01..4; 0 = 0.5 */
    float offset;                 /* start, in voxels along the normal; 0 = 1.5 */
    float max_distance;           /* in voxels; 0 = the grid's diagonal */
    int seen_from_eye;            /* 1: every point is a surface seen from `eye` (a camera's pixels), so the
                                     empty voxels on the line to the eye tell which closed space its cones
                                     start in, where its voxel's neighbours leave that open (a corner) */
    double eye[3];                /* with seen_from_eye: world units */
} voxgi_cone_desc;

/* Diffuse cone tracing: the irradiance at points (world positions, unit normals) gathered from a
   radiance source, and the ambient occlusion. The cones split the cosine-weighted hemisphere
   into `cones` equal parts (directions on a Fibonacci spiral of the projected disc, weight
   pi / cones each; the default half-angle acos(1 - 1/cones) gives each cone its share of the
   solid angle, so the set leaves no gaps), each marched from `offset` voxels along the normal:
   at distance t its diameter is d = max(1, 2 t tan(half-angle)) voxels, sampled at lod log2(d)
   (a cone at angle theta from the normal narrows to tan = cos(theta) / 3, so that no sample
   reaches back to the surface's own voxels: an open plane occludes nothing)
   every step * d (the radiance is stored premultiplied by alpha, so that empty space thins a
   sample without darkening it); a sample's alpha a at level L is read as the coverage of the
   cone's cross-section: isotropic a 2^L (a surface one voxel thick covers it while filling 2^-L
   of the voxel), so thin walls do not leak; anisotropic 2 a (its alpha is the coverage along
   the axis already, so walls parallel to the cone do not stop it; x 2 undoes trilinear
   filtering's halving of a one-voxel wall), at most 1; opacity corrected for the step
   (a' = 1 - (1 - a)^(step)), composited front to
   back (c += (1 - A) a' L, A += (1 - A) a') until A reaches 0.99 or max_distance. Anisotropic
   volumes are sampled along the cone's direction (the three axis volumes weighted by the
   squared direction components). A two-sided volume (voxgi_inject_light) gives each level's side
   facing the cone's origin, and a cone from an enclosed region of its empty space keeps to that
   region: nothing from outside a closed room reaches into it (docs/cone-tracing.md#light-leaking).
   irradiance: 3 floats per point (sum of pi / cones x the cones'
   radiance); occlusion: 1 per point (mean A), or NULL. A GL source is traced on GL
   (shaders/cone_trace.glsl, a compute pass with the textures' filtering): on llvmpipe within
   1e-4 of the CPU's irradiance (relative to its mean) and occlusion; a GPU with 8-bit filter
   weights differs by up to about 1%. */
VOXGI_API voxgi_result voxgi_cone_trace(voxgi_context *ctx, const voxgi_radiance_source *source, const voxgi_cone_desc *desc,
                                        size_t count, const float *positions, const float *normals, float *irradiance,
                                        float *occlusion);

/* GL: the diffuse gather over the caller's G-buffer textures, written into the caller's texture:
   positions (world units, rgb of any float 2D texture), normals (rgb, need not be unit; zero:
   no surface, written 0), optionally albedo (rgb); out (RGBA16F or RGBA32F, width x height):
   the irradiance and the occlusion in alpha, or with albedo the reflected radiance albedo / pi x
   irradiance. The same march as voxgi_cone_trace (which takes CPU arrays on either backend). */
typedef struct voxgi_gl_gbuffer {
    unsigned int position_texture, normal_texture, albedo_texture; /* albedo: 0 = none */
    int width, height;
    unsigned int irradiance_texture;
    int irradiance_rgba16f;       /* 1: irradiance_texture is RGBA16F; 0: RGBA32F */
} voxgi_gl_gbuffer;
VOXGI_API voxgi_result voxgi_cone_trace_gl(voxgi_context *ctx, const voxgi_radiance_source *source, const voxgi_cone_desc *desc,
                                           const voxgi_gl_gbuffer *gbuffer);

/* Single cones, each from its own origin along its own direction: a specular reflection is one
   cone along the mirror direction with voxgi_specular_half_angle(roughness), a soft shadow one
   cone toward a light as wide as the light seen from the point (visibility 1 - A). Each is marched
   as a diffuse cone from a surface of the given normal (from desc->offset voxels along it,
   narrowed near the surface and kept clear of it, desc->step, coverage and opacity correction
   as above); radiance_opacity: 4 floats per cone, the composited radiance and the opacity A it
   gathered. */
typedef struct voxgi_cone {
    float origin[3];              /* world position (a surface point: the march starts desc->offset voxels out) */
    float direction[3];           /* not zero; need not be unit */
    float normal[3];              /* the surface's normal at the origin, or zero: the direction */
    float half_angle;             /* radians, in (0, 1.5) */
    float max_distance;           /* world units; 0 = the grid's diagonal (e.g. the distance to a light) */
} voxgi_cone;
VOXGI_API voxgi_result voxgi_cone_trace_each(voxgi_context *ctx, const voxgi_radiance_source *source, const voxgi_cone_desc *desc,
                                             size_t count, const voxgi_cone *cones, float *radiance_opacity);
/* The half-angle of a cone covering a glossy lobe of roughness alpha (GGX-style, 0..1): its
   Phong exponent n = 2 / alpha^2 - 2, the angle where the lobe falls to 0.244 of its peak,
   acos(0.244^(1 / (n + 1))) (a fit common among voxel cone tracers), at least 0.005. */
VOXGI_API float voxgi_specular_half_angle(float roughness);

/* ===================================================================== 9. light injection */

/* Light injection: the radiance the voxels send out, for the cone tracer to gather. Per set
   voxel: L = albedo / pi * E + emission (alpha = opacity, 1 when the voxels hold none), E the
   irradiance on the voxel's mean normal at its centre moved half a voxel diagonal along that
   normal (off its own surface), from the scene's lights and emissive triangles; area lights and
   emitters take `samples` points. CPU: exact shadow rays, the points stratified per voxel (a 2D
   Kronecker sequence, randomly shifted). GL: distance
   maps drawn from each light (one orthographic layer for a directional light, six cube faces for
   every point, spot, and stratified point on an area light or emitter: the same points for all
   voxels), gathered per voxel with the same analytic irradiance and the point's map texel for
   the visibility (a gather: no voxel is missed where texels are sparser than voxels). The voxels must
   hold ALBEDO and NORMAL. Both sides of a surface are lit on their own: a voxel's back side
   (RADIANCE_BACK) gathers at the mirror point behind it, c - off n, on the normal -n, and emits
   nothing (an emitter's light leaves its front), so the inner face of a closed box's wall lit
   from outside stays dark; RADIANCE_SIDE tells a cone which side it sees. A voxel without a
   normal sends its front's light both ways. The result is a volume of RADIANCE, RADIANCE_BACK
   and RADIANCE_SIDE (RADIANCE alone with one_sided) with desc.volume's mips, and the regions of
   its empty space for the cones where it has enclosed regions (4 bytes a voxel over all levels). With bounces B > 1 the light then bounces among the voxels: each
   gathers the irradiance at its centre on its normal from the volume so far (voxgi_cone_trace,
   on the context's backend) and sends out its direct light plus albedo / pi x that, B - 1
   times, each side gathering on its own normal. Checks: a plane under a directional light of irradiance E gets albedo E
   cos / pi exactly; GL and CPU agree in total power within 0.1% (two spheres under the sun) and
   0.2% (the Cornell box's emitter), voxel by voxel to 1e-4 on 88% of the two spheres' voxels
   (the rest lie within a map texel or two of a shadow's edge). */
/* bounces = -1 stops at the bounce adding less than this share of the voxels' light (the
   Cornell box: 7 bounces, docs/cone-tracing.md). */
#define VOXGI_CONVERGED_BOUNCE 0.01
typedef struct voxgi_inject_desc {
    voxgi_volume_desc volume;     /* filter and levels (attributes: ignored) */
    int samples;                  /* points per area light and on the emitters (CPU: per voxel); 0 = 16 */
    uint64_t seed;
    int shadow_rays;              /* GL context: 1 = the CPU's exact shadow rays instead of the maps */
    int bounces;                  /* 0 or 1: direct light; B > 1: B - 1 more bounces, each voxel gathering
                                     with `gather` cones from the last volume; -1: full global illumination,
                                     bounces until those still to come (their geometric tail, estimated from
                                     the last two) add less than VOXGI_CONVERGED_BOUNCE of the light, at most
                                     64; then that tail is added */
    voxgi_cone_desc gather;       /* cones 0 = 4: the bounces' light is smooth, and more cones do not
                                     change the image (docs/cone-tracing.md) */
    int gather_block;             /* the bounces gather once per group of voxels: those in one block of
                                     gather_block^3 voxels whose normals face the same way (the same
                                     dominant axis and sign), at their mean centre on their mean normal;
                                     0 = 4; 1 = every voxel on its own */
    int one_sided;                /* 1: the front's light alone, sent both ways (the volume holds RADIANCE only: 2.6 times
                                     less memory anisotropic, 3 times isotropic, and light passes through closed walls
                                     of zero thickness) */
} voxgi_inject_desc;
VOXGI_API voxgi_result voxgi_inject_light(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_voxels *voxels,
                                          const voxgi_inject_desc *desc, voxgi_volume **out);

/* ===================================================================== 10. light-space passes */

/* Transmittance shadow maps (Buchacher 2014, section 4): the light's view of the scene's
   translucent surfaces as raster slicemaps, and an ordinary shadow map of its opaque ones. A
   point's light is 0 where an opaque surface lies before it (the shadow map, checked first),
   else the product over the translucent materials of (1 - sigma)^n, n the occupied slices of
   that material's slicemap strictly between the light and the point (its own slice never
   counts), sigma = 1 - transparency (surfaces of one slice count once: the method's artifact).
   A DIRECTIONAL light looks along its direction with an orthographic map over the scene's
   bounds: square texels, `slices` slices of equal depth between the scene's nearest and
   farthest point. A SPOT light looks along its axis with a perspective map of its outer cone's
   square, slices uniform in 1 / depth between the scene's nearest point ahead of it (at least
   1/1000 of the farthest) and its farthest: the map is projective, so triangles stay triangles
   (cut at the near plane) and the slicemap applies; a point before the near plane is lit.
   The slicemaps are voxgi_voxelize's raster slicemap (VOXGI_METHOD_SLICEMAP) of the scene in
   the light's frame, on the context's backend: GL and CPU give the same bits. The shadow map
   holds, per texel, the least depth of an opaque triangle at its centre (the same rasterizer's
   coverage, on the CPU). On a GL context the lookups run on GL too (shaders/tsm_lookup.glsl:
   double precision in the CPU's order, the same answers on llvmpipe). Lookups move a point 1.5
   texels along its normal toward the light (normal-offset shadow mapping) and let an opaque
   depth within half a texel of its own pass. */
typedef struct voxgi_tsm_desc {
    size_t light;                 /* the scene's light: DIRECTIONAL or SPOT */
    int size;                     /* texels across the square map; 0 = 512 */
    int slices;                   /* slices along the light; 0 = 64 (the front of voxgi report tsm) */
    float sigma;                  /* > 0: this absorption for every translucent material instead of its
                                     1 - transparency */
} voxgi_tsm_desc;
typedef struct voxgi_tsm voxgi_tsm;
typedef struct voxgi_tsm_info {
    int materials;                /* translucent absorptions, one slicemap each */
    uint64_t voxels;              /* occupied slices over them all */
    size_t bytes;                 /* the maps' memory */
    double ms;                    /* wall time of voxgi_tsm_create */
} voxgi_tsm_info;
VOXGI_API voxgi_result voxgi_tsm_create(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_tsm_desc *desc, voxgi_tsm **out);
VOXGI_API void voxgi_tsm_query(const voxgi_tsm *tsm, voxgi_tsm_info *info);
/* The light's share reaching each point (0..1): count points (xyz), their unit normals (NULL: no
   offset, the bare definition) into out[count]. */
VOXGI_API voxgi_result voxgi_tsm_transmittance(voxgi_context *ctx, const voxgi_tsm *tsm, size_t count, const float *points, const float *normals,
                                               float *out);
VOXGI_API void voxgi_tsm_destroy(voxgi_context *ctx, voxgi_tsm *tsm);

/* Reflective shadow maps (Dachsbacher and Stamminger 2005, with voxel visibility after Buchacher
   2014): every texel of a light's view (voxgi_tsm_desc says how it looks: orthographic for a
   DIRECTIONAL light, perspective for a SPOT) holds the surface the light meets there, by ray
   casting: its position, its unit normal facing the light, and the flux it reflects, a small
   Lambertian reflector (directional: albedo E texel^2; spot: albedo I falloff times the texel's
   solid angle). A RECT light or the scene's emitters (picked by power) become `points` stratified
   points, each a Lambertian point (intensity P cos, P = radiance x area / points) with a map of
   its whole hemisphere by the concentric map (Shirley and Chiu) lifted to the hemisphere: every
   texel the same cosine-weighted solid angle, flux albedo P pi / texels. The one-bounce
   irradiance at a point gathers, from every map, `samples` texels of a fixed pattern around the
   point's own texel (a point behind a hemisphere map: the rim toward it), offsets r xi1 (sin 2 pi xi2, cos 2 pi xi2), r = radius x size,
   weighted xi1 / sum xi1 (the unbiased weight of that pattern, whose density falls as 1 / xi1;
   the seed's xi1^2 over-counts the rim), each texel p adding pi r^2 w Phi_p max(0, n_p.(x - x_p))
   max(0, n.(x_p - x)) / (pi |x - x_p|^4) (the seed's equation 5 with the Lambertian 1 / pi it
   folds into the flux; |x - x_p| at least a texel's width where the texel lies: the
   singularity), when the voxels (if given)
   let it through: the segment between the two, each end moved 1.5 voxels along its normal off
   its own surface (clear of the surface's conservative voxels), by voxgi_voxels_occluded. */
typedef struct voxgi_rsm_desc {
    size_t light;                 /* the scene's light: DIRECTIONAL, SPOT or RECT */
    int size;                     /* texels across; 0 = 256 */
    int samples;                  /* texels gathered per point and map; 0 = 100 (the seed's) for a light's map,
                                     200 for an area's points (voxgi report rsm) */
    float radius;                 /* of the sample disc, as a share of the map's width (up to 2); 0 = 0.3 for a
                                     light's map, 1 for an area's points (their whole hemisphere): voxgi report rsm */
    uint64_t seed;                /* of the sample pattern */
    int emitters;                 /* 1: the scene's emissive triangles instead of a light */
    int points;                   /* a RECT light or the emitters: points on it, one map each; 0 = 4 */
} voxgi_rsm_desc;
typedef struct voxgi_rsm voxgi_rsm;
typedef struct voxgi_rsm_info {
    int maps, size, samples;      /* maps (1, or the points of an area), texels across each, samples per map */
    size_t bytes;                 /* the maps' and the pattern's memory */
    double ms;                    /* wall time of voxgi_rsm_create */
} voxgi_rsm_info;
VOXGI_API voxgi_result voxgi_rsm_create(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_rsm_desc *desc, voxgi_rsm **out);
VOXGI_API void voxgi_rsm_query(const voxgi_rsm *rsm, voxgi_rsm_info *info);
/* The texels, map after map of size x size rows from the map's v axis up: positions, normals
   (xyz each) and reflected flux (rgb), any may be NULL; a texel that sees nothing has flux 0. */
VOXGI_API voxgi_result voxgi_rsm_texels(voxgi_context *ctx, const voxgi_rsm *rsm, float *positions, float *normals, float *flux);
/* The sample pattern: offsets (2 per sample, texels) and weights (summing to 1), either may be NULL. */
VOXGI_API voxgi_result voxgi_rsm_pattern(voxgi_context *ctx, const voxgi_rsm *rsm, float *offsets, float *weights);
/* The one-bounce irradiance (rgb) at count points with unit normals; voxels NULL: no visibility.
   On a GL context the gather runs on GL (shaders/rsm_gather.glsl, voxel_traverse.glsl: in float,
   the maps as the CPU made them), within 1e-4 of the CPU's double. */
VOXGI_API voxgi_result voxgi_rsm_irradiance(voxgi_context *ctx, const voxgi_rsm *rsm, const voxgi_voxels *voxels, voxgi_traversal how, size_t count,
                                            const float *points, const float *normals, float *irradiance);
VOXGI_API void voxgi_rsm_destroy(voxgi_context *ctx, voxgi_rsm *rsm);

/* A spherical-harmonics volume of the direct light (after Gaitatzes et al. 2011's SH channel):
   per voxel and colour band, the L0 + L1 SH (4 coefficients: Y00, Y1-1, Y10, Y11, the real basis
   with Y00 = 1 / (2 sqrt pi), Y1m = sqrt(3 / (4 pi)) (y, z, x)) of the radiant intensity its
   surfaces reflect: every triangle is cut to the voxels (exactly, in double), and each piece's
   sides, lit at its centroid by every light (exact shadow rays; area lights and emitters through
   `samples` stratified points), add the projection of albedo E A / pi max(0, n.w), that is
   albedo E A / pi (pi Y00, 2 pi / 3 Y1(n)); lights add (the seed's MAX does not). Emission is left
   out (it is direct light). Coarser levels sum 2x2x2 cells, each cell also keeping its
   intensity-weighted centroid. The estimator (voxgi_sh_irradiance) is a Barnes-Hut sum: from the
   coarsest level, a cell whose size is at most `opening` times its centroid's distance acts as one
   point at its centroid (else its children do), adding I(w) max(0, n.d) / |d|^2 (I its SH toward
   the point, clamped at 0; |d| at least a voxel; cells within a voxel left out), each through the
   voxels if given (from 1.5 voxels off the point's surface toward the centroid, up to half a
   voxel before the cell: a cell's own surfaces do not hide its light; voxgi_voxels_occluded's
   rule). Memory: 64 bytes a cell over all levels (dense). */
typedef struct voxgi_sh_desc {
    int samples;                  /* points per area light and on the emitters for each piece; 0 = 16 */
    uint64_t seed;
} voxgi_sh_desc;
typedef struct voxgi_sh voxgi_sh;
typedef struct voxgi_sh_info {
    int levels;                   /* level 0 the grid's voxels, the last one cell */
    uint64_t voxels;              /* voxels holding a piece */
    size_t pieces;                /* triangle pieces lit */
    size_t bytes;
    double ms;                    /* wall time of voxgi_sh_create */
} voxgi_sh_info;
VOXGI_API voxgi_result voxgi_sh_create(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_grid *grid, const voxgi_sh_desc *desc, voxgi_sh **out);
VOXGI_API void voxgi_sh_query(const voxgi_sh *sh, voxgi_sh_info *info);
/* One level's cells (x fastest): 16 floats each, rgb x 4 coefficients, then the weighted centroid
   (w x, w y, w z, w). res (may be NULL): the level's cells per axis; cells NULL: res alone. */
VOXGI_API voxgi_result voxgi_sh_read(voxgi_context *ctx, const voxgi_sh *sh, int level, float *cells, size_t cells_bytes, int res[3]);
/* The one-bounce irradiance (rgb) at count points with unit normals; voxels (NULL: no visibility)
   on the SH volume's grid; opening 0 = 0.5. On a GL context the gather runs on GL
   (shaders/sh_gather.glsl: in float, the volume as the CPU made it), within 1e-4 of the CPU's. */
VOXGI_API voxgi_result voxgi_sh_irradiance(voxgi_context *ctx, const voxgi_sh *sh, const voxgi_voxels *voxels, voxgi_traversal how, float opening,
                                           size_t count, const float *points, const float *normals, float *irradiance);
VOXGI_API void voxgi_sh_destroy(voxgi_context *ctx, voxgi_sh *sh);



/* ===================================================================== 11. screen-space passes */

/* Low-discrepancy points (Thiedemann 2009's sampler, the one the screen-space passes share): the
   radical inverse of i in base b >= 2 (its digits mirrored about the radix point: Phi_2(1), (2),
   (3) = 1/2, 1/4, 3/4; Phi_3(1) = 1/3), and point i of the n-point 2D Hammersley set
   (i / n, Phi_2(i)) shifted by rot modulo 1 (Cranley-Patterson rotation: one rot per pixel turns
   the set's structure into noise; rot NULL: none). */
VOXGI_API double voxgi_radical_inverse(uint32_t base, uint64_t i);
VOXGI_API void voxgi_hammersley(uint32_t i, uint32_t n, const double rot[2], double out[2]);

/* Ambient occlusion at the pixels of a G-buffer (the caller's, or voxgi_gbuffer_render's): the
   occluded share (0 open, 1 closed) of the cosine-weighted hemisphere within `radius` of each
   pixel's surface, from `rays` directions (the Hammersley set, rotated per pixel by the seed):
   SCREEN (Thiedemann 2009's ray marching) steps along each ray at t = (j + xi) / steps x radius,
   j = 0 .. steps - 1 (xi a per-pixel jitter), and the ray is blocked at the first step behind
   the G-buffer's surface: the surface of the step's pixel, taken as its plane (its position and
   normal), meets the eye's ray through the step nearer the eye than the step (by more than
   radius / 1000), within radius of the pixel's own surface (the radius check); steps off the
   screen, behind the eye or over no surface block nothing: one depth layer sees nothing hidden
   or off screen. (The plane, not the pixel centre's depth: a flat surface then never hides
   points above itself, however grazing the view.)
   VOXELS: the segment from 1.5 voxels off the surface along its normal to radius along the ray,
   through the voxels (voxgi_voxels_occluded): view-independent, sees what the camera does not.
   The reference renderer's AO mode (voxgi_render_desc.reference.ao_radius) is the exact definition. */
typedef enum voxgi_ao_method { VOXGI_AO_SCREEN = 0, VOXGI_AO_VOXELS } voxgi_ao_method;
typedef struct voxgi_ao_desc {
    voxgi_camera camera;          /* the G-buffer's view and size */
    const float *positions;       /* per pixel, rows from the top: the world position of its surface (xyz) */
    const float *normals;         /* per pixel: the unit normal facing the camera; (0, 0, 0): no surface (AO 0) */
    voxgi_ao_method method;
    const voxgi_voxels *voxels;   /* VOXELS: what blocks the rays */
    voxgi_traversal traversal;    /* VOXELS: the hierarchy (0) or DDA, the same answers */
    int rays;                     /* per pixel; 0 = 16 */
    int steps;                    /* SCREEN: per ray; 0 = 16 */
    float radius;                 /* world units, > 0 */
    uint64_t seed;
    int point_sampling;           /* SCREEN: 1 = one point per ray at distance Phi_3 x radius (3D Hammersley) tested
                                     against the depth buffer instead of the march: each ray then counts
                                     (1 - d / radius) of a hit at d (linear falloff, obscurance), not 1 */
} voxgi_ao_desc;
/* ao: width x height floats. On a GL context the rays run on GL (shaders/screen_rays.glsl, in
   float, the random numbers the CPU's): within 1e-4 of the CPU's. */
VOXGI_API voxgi_result voxgi_ao(voxgi_context *ctx, const voxgi_ao_desc *desc, float *ao, size_t ao_bytes);

/* One bounce of diffuse light at the pixels of a G-buffer from the light the screen's surfaces
   send (Thiedemann 2009): irradiance = pi / rays x the sum of the radiance met along `rays`
   cosine-distributed Hammersley directions within `radius`. SCREEN (SSGI): the first step behind
   the depth buffer as voxgi_ao finds it, the radiance of its pixel. VOXELS (Hybrid-GI): the
   first occupied voxel along the ray (from 1.5 voxels off the surface), the radiance of the pixel
   showing the point where the ray enters it, when that point lies within 2 voxels of the plane of
   that pixel's surface; a hit hidden from the camera or off the screen blocks the ray and sends nothing
   (the one rule for both: only the screen has light), or with hidden_radiance the light of the voxel
   it met (an extension of the source's method: the light the screen cannot see, from the voxels).
   Misses send nothing (no environment). */
typedef struct voxgi_ssgi_desc {
    voxgi_camera camera;          /* the G-buffer's view and size */
    const float *positions, *normals; /* as voxgi_ao_desc's */
    const float *radiance;        /* per pixel: the radiance its surface sends (rgb), e.g. the direct light it reflects */
    voxgi_ao_method method;       /* SCREEN: SSGI; VOXELS: Hybrid-GI */
    const voxgi_voxels *voxels;   /* VOXELS */
    voxgi_traversal traversal;
    int rays, steps;              /* 0 = 16 each */
    float radius;                 /* world units, > 0 */
    uint64_t seed;
    const voxgi_volume *hidden_radiance; /* VOXELS: NULL, or the light the voxels send (voxgi_inject_light on the voxels'
                                     grid, from voxels without EMISSION, as emitters' light is the direct light's),
                                     read at the centre of the voxel a hidden hit meets: RADIANCE, or RADIANCE_BACK
                                     where the ray meets the side its RADIANCE_SIDE normal turns away */
} voxgi_ssgi_desc;
/* irradiance: 3 floats per pixel; on a GL context on GL, as voxgi_ao. */
VOXGI_API voxgi_result voxgi_ssgi(voxgi_context *ctx, const voxgi_ssgi_desc *desc, float *irradiance, size_t irradiance_bytes);

/* The edge-aware blur and upsampling of a screen pass's result (Thiedemann 2009 after Reinbothe et
   al. and Kopf et al.: a joint bilateral filter, run as a row pass then a column pass): each
   pixel with a surface takes the weighted mean of the values within `radius` pixels across, then
   down, each weighted by
       exp(-d^2 / (2 sigma^2)) x max(0, n . n_s)^8 x exp(-(((p_s - p) . n) / t)^2)
   (d the distance in pixels, sigma = max(radius, 1) / 2; n, p the pixel's normal and position,
   n_s, p_s the sample's; t = the width of two pixels at the pixel's distance): the same plane
   weighs fully, another surface (an edge, a step in depth) next to nothing. No weight on the
   values themselves: what the filter removes is their noise. With half_resolution the values are
   an image of (w + 1) / 2 x (h + 1) / 2 pixels, its pixel (X, Y) computed at the full pixel
   (2X, 2Y), and the same weights against those pixels' surfaces upsample it (radius at least 1).
   A pass whose weights sum below 1e-3 has no sample on the pixel's surface: out is 0 there and
   unsupported (if not NULL, a byte per pixel) 1, for the caller to compute on its own. */
typedef struct voxgi_screen_filter_desc {
    voxgi_camera camera;          /* the full-resolution G-buffer's view and size */
    const float *positions, *normals; /* full resolution, as voxgi_ao_desc's */
    int channels;                 /* values per pixel, 1..4 */
    int half_resolution;          /* 1: values at half resolution, upsampled */
    int radius;                   /* pixels (full resolution) each side, 0..64; 0 at full resolution: a copy */
} voxgi_screen_filter_desc;
/* out: channels floats per full-resolution pixel. On a GL context on GL (shaders/screen_filter.glsl). */
VOXGI_API voxgi_result voxgi_screen_filter(voxgi_context *ctx, const voxgi_screen_filter_desc *desc, const float *values, float *out, size_t out_bytes,
                                           unsigned char *unsupported);



/* ===================================================================== 12. line space */

/* The cascaded line space (Klee 2016, after Keul, Lemke and Mueller): an N-tree over the scene
   (a cube, each filled node split into N^3 children down to `depth` levels below the root; the
   leaves hold the triangles meeting them, by an exact closed triangle-box test) whose every node
   with children holds a line space: one bit per pair of patches on two different faces of the
   node (each face split into N x N patches, one per child face), set when the shaft between
   them (the convex hull of the two patches) meets a filled child. The shaft test is exact on
   closed sets (the hull is the union over t in [0, 1] of the boxes (1 - t) S + t E, so a cell
   meets it when six linear bounds in t leave an interval), so a segment between the two patches
   through a filled child always finds its bit set. Each unordered pair is stored once:
   15 N^4 bits per line space. Deterministic whatever the threads. Made on a GL context, it also
   keeps its arrays in GL storage buffers for its rays on GL (where they fit: the bits in up to four
   of GL's largest storage blocks, each other array in one; info.bytes counts the CPU's copy). */
typedef struct voxgi_linespace voxgi_linespace;
typedef struct voxgi_linespace_desc {
    int n;                        /* children per axis of a split node, 2..16; 0 = 4 */
    int depth;                    /* levels below the root, 1..8 (the leaves' level); 0 = from the scene: 2 under 256
                                     triangles, else 3 */
    size_t memory_budget;         /* bytes the tree, its line spaces and triangle lists may take; 0: the context's
                                     (voxgi_desc.memory_budget) */
} voxgi_linespace_desc;
typedef struct voxgi_linespace_info {
    int n, depth;
    double origin[3], size;       /* the root cube */
    size_t nodes;                 /* every node: the root and the children of every split node */
    size_t line_spaces;           /* nodes with children, one line space each */
    size_t leaves, triangle_refs; /* filled nodes at the leaves' level, and their triangle references */
    size_t triangles;
    size_t bytes;                 /* held: 8 x nodes + 15 N^4 / 8 x line_spaces + 4 x triangle_refs + 8 x leaves + 36 x triangles */
    size_t allocated;             /* measured: what its arrays take as allocated (their growth's slack included) */
    double ms;
} voxgi_linespace_info;
VOXGI_API voxgi_result voxgi_linespace_create(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_linespace_desc *desc, voxgi_linespace **out);
VOXGI_API void voxgi_linespace_destroy(voxgi_context *ctx, voxgi_linespace *ls);
VOXGI_API void voxgi_linespace_query(const voxgi_linespace *ls, voxgi_linespace_info *out);

/* Shadow rays through the line space. EXACT: the line spaces skip empty shafts and the leaves'
   triangles decide (the ray core's watertight test): the answer is the triangles'. FAST: a set
   bit at the last line-space level counts as a hit (Klee's method: never lighter than EXACT,
   darker where a shaft holds geometry the ray misses). In both, the nodes holding the segment's
   ends, and in FAST those within 3 leaves' edges of them (voxgi_linespace_light_desc.exact_ends),
   are walked to their leaves and their triangles decide, so a surface never shadows itself. */
typedef enum voxgi_linespace_mode { VOXGI_LINESPACE_EXACT = 0, VOXGI_LINESPACE_FAST } voxgi_linespace_mode;

/* Whether each ray meets something at t in (tmin, tmax): 1 or 0, each ray walking alone, on the
   context's backend (GL: shaders/linespace_rays.glsl, the CPU's float arithmetic: the same answers;
   a line space made on a CPU context goes up to GL for the call). */
VOXGI_API voxgi_result voxgi_linespace_occluded(voxgi_context *ctx, const voxgi_linespace *ls, voxgi_linespace_mode mode, size_t count, const voxgi_ray *rays,
                                                unsigned char *occluded);

/* An area light seen from points: per point the S samples' rays to the light (the light split
   into nu x nv cells, nu = ceil(sqrt(S)), nv = ceil(S / nu), a point jittered in each from
   (seed, point, sample) alone). A ray leaves the point a hair (2^-18 of the root's edge) along
   its normal and stops 2^-16 of the way short of the light; a sample behind the point's surface
   (normal . direction <= 0) is blocked without a ray. */
typedef struct voxgi_linespace_light_desc {
    voxgi_linespace_mode mode;
    int samples;                  /* S per point, 1..4096; 0 = 16 */
    int packets;                  /* 1: a point's rays walk the tree together, slice by slice (coherent grid traversal);
                                     0: each alone (3D DDA). The same answers, another cost. CPU only: on GL each ray
                                     walks alone */
    double corner[3], edge_u[3], edge_v[3]; /* the light: corner + s edge_u + t edge_v, s and t in [0, 1]; it shines to edge_u x edge_v */
    int triangle;                 /* 1: the triangle s + t <= 1 (samples beyond it folded in) */
    uint32_t seed;
    int exact_ends;               /* FAST: the triangles decide within this many leaves' edges of each end of a
                                     segment (more: closer to EXACT, slower); 0 = 3 */
} voxgi_linespace_light_desc;
typedef struct voxgi_linespace_stats {
    uint64_t rays, nodes, bits, triangle_tests; /* rays traced; split nodes entered, bits read, triangles tested (the
                                                   last three are counted on the CPU only: 0 on GL) */
    int samples;                  /* nu x nv */
    double ms;
} voxgi_linespace_stats;
/* points and normals: 3 floats each per point (a zero normal: no rays, 0 out). visible (or NULL):
   the share of the nu x nv samples whose rays are not blocked; weighted (or NULL): the same share
   weighted by cos_point cos_light / r^2, which times the light's unshadowed irradiance is its
   shadowed irradiance (0 where no sample has weight). On a GL context the rays run on GL
   (shaders/linespace_light.glsl), each the CPU's ray with the CPU's answer, so visible is the CPU's;
   weighted sums its weights in float there (within 1e-5 of the CPU's). A line space made on a
   CPU context goes up to GL for the call; one too large for GL's storage blocks (its bits over
   four, another array over one) gives VOXGI_ERR_TOO_LARGE (use a CPU context). */
VOXGI_API voxgi_result voxgi_linespace_light(voxgi_context *ctx, const voxgi_linespace *ls, const voxgi_linespace_light_desc *desc, size_t count,
                                             const float *points, const float *normals, float *visible, float *weighted, voxgi_linespace_stats *stats);


/* ===================================================================== 13. reference renderer */

/* Ground truth for the lighting passes: Monte Carlo path tracing of the scene on the CPU, through
   the ray core (voxgi_ray_scene: watertight, hit points refined in double). Surfaces are Lambertian (albedo) and emit
   their material's emission from their front faces; the scene's lights add point, spot,
   directional and rectangular light; there is no environment (misses are black) and
   transparency is ignored (every surface is opaque). Paths gather direct light at every vertex
   (next-event estimation towards the lights and the emissive triangles) and count emission seen
   directly from the camera. A pixel is the mean radiance over its square (uniformly jittered
   samples). Sample s of pixel p draws its random numbers from (seed, p, s) alone, so the image
   is the same for any thread count; the progress callback sees each pass and may cancel.
   It is voxgi_render's VOXGI_RENDER_REFERENCE (part 14). */


/* ===================================================================== 14. planner and images */

/* ----- one image, any method
   voxgi_render makes an image of a scene by any of the methods above through one call. Inside,
   each method is one row of a table: its plan (voxgi_plan), what it builds from the scene (the
   voxels, the radiance, maps, a line space), the gathers at the camera's pixels that make the
   image, and the freeing of what it built. The desc has a head every method reads (the view,
   samples, seed, grid, what to leave out of the image) and a part per method; every zero field
   means that method's default, the setting its report measured best (docs/ of each method), and
   info.used gives back every setting that ran, defaults resolved. A method whose part was left
   out of the build (VOXGI_NO_*) gives VOXGI_ERR_UNSUPPORTED. */
typedef enum voxgi_render_method {
    VOXGI_RENDER_REFERENCE = 0,   /* path tracing (part 13): the ground truth the others are measured against */
    VOXGI_RENDER_VCT,             /* direct light through shadow rays and the indirect light of voxel cone tracing */
    VOXGI_RENDER_TSM,             /* direct light, directional and spot lights through transmittance shadow maps */
    VOXGI_RENDER_RSM,             /* direct light and one bounce from reflective shadow maps */
    VOXGI_RENDER_SH,              /* direct light and one bounce from a spherical-harmonics volume of it */
    VOXGI_RENDER_SSAO,            /* ambient occlusion through the depth buffer */
    VOXGI_RENDER_VAO,             /* ambient occlusion through the voxels */
    VOXGI_RENDER_SSGI,            /* direct light and one bounce from the screen, visibility through the depth buffer */
    VOXGI_RENDER_HYBRID,          /* the same, visibility through the voxels (Hybrid-GI) */
    VOXGI_RENDER_LINESPACE,       /* the area lights' direct light, soft shadows through the line space */
    VOXGI_RENDER_METHOD_COUNT
} voxgi_render_method;

/* A setting that is on or off, 0 leaving it to the method. */
typedef enum voxgi_toggle { VOXGI_TOGGLE_DEFAULT = 0, VOXGI_TOGGLE_ON, VOXGI_TOGGLE_OFF } voxgi_toggle;

/* What cone tracing's cones gather from. */
typedef enum voxgi_vct_radiance {
    VOXGI_VCT_RADIANCE_DEFAULT = 0, /* the anisotropic volume, or the octree where the plan finds the volume over the memory budget */
    VOXGI_VCT_ANISOTROPIC,        /* a volume with six-direction mips */
    VOXGI_VCT_ISOTROPIC,          /* a volume with one mip chain (less memory, more light through thin walls) */
    VOXGI_VCT_OCTREE              /* a sparse voxel octree of the radiance (isotropic mips) */
} voxgi_vct_radiance;

typedef struct voxgi_render_vct {
    voxgi_vct_radiance radiance;
    voxgi_cone_desc cones;        /* the pixels' diffuse cones; cones 0 = 24, the rest voxgi_cone_desc's defaults */
    int cone_stride;              /* s > 1: cones at every s-th pixel across and down (and the last row and column); a
                                     pixel between takes the bilinear mean of the four around it that share its surface
                                     (normals within 26 degrees, on its plane within a voxel), or traces its own where none
                                     does. 0 = 6; 1: every pixel */
    int inject_samples;           /* points per area light and on the emitters for each voxel's light; 0: 4 on the CPU,
                                     stratified per voxel; 16 on GL, the same points for every voxel */
    int shadow_rays;              /* GL: inject through exact shadow rays (voxgi_inject_desc) */
    int sampled_direct;           /* 1: the area lights' and emitters' direct light from the rays alone; 0: where the scene
                                     has up to 64 emissive triangles, their and the rect lights' unshadowed irradiance
                                     exactly (Lambert's polygon formula) times the rays' visible share, and a pixel whose
                                     first half of rays all meet the centre's triangle, lit alike, stops there */
    int one_sided;                /* 1: one-sided radiance (voxgi_inject_desc.one_sided) */
    voxgi_cone_desc bounce_cones; /* bounces > 1: the gathers among the voxels (voxgi_inject_desc.gather) */
    int bounce_block;             /* bounces > 1: one gather per block of this many voxels a side; 0 = 4 */
    voxgi_svo_format octree_format; /* OCTREE */
    int octree_bricks;            /* OCTREE: 1 = sampled through bricks */
} voxgi_render_vct;

typedef struct voxgi_render_tsm {
    voxgi_tsm_desc maps;          /* every directional and spot light's map: size 0 = 512, slices 0 = 64, sigma (light: ignored) */
} voxgi_render_tsm;

typedef struct voxgi_render_rsm {
    voxgi_rsm_desc maps;          /* every light's map but point lights' (which bounce nowhere), and the emitters':
                                     size, samples, radius, points as voxgi_rsm_desc's; seed 0: the image's (light: ignored) */
    voxgi_traversal visibility;   /* of each gather, through the grid's conservative voxels */
    int gather_stride;            /* gathers at every s-th pixel across and down, the pixels between interpolated from the
                                     anchors around them that share their surface where at least three of four do; 0 = 4 */
} voxgi_render_rsm;

typedef struct voxgi_render_sh {
    voxgi_sh_desc volume;         /* samples as voxgi_sh_desc's; seed 0: the image's */
    voxgi_traversal visibility;
    float opening;                /* a cell counts as one point where its size is at most this times its distance; 0 = 0.5 */
    int gather_stride;            /* as rsm's; 0 = 4 */
} voxgi_render_sh;

/* SSAO, VAO, SSGI and HYBRID: the rays from the pixels' surfaces (voxgi_ao, voxgi_ssgi). */
typedef struct voxgi_render_screen {
    int rays, steps;              /* per pixel, and along each ray; 0 = 16 each */
    float radius;                 /* the rays' reach; 0: AO a tenth of the scene's longest side, GI sqrt(3) times it */
    int point_sampling;           /* SSAO: one point per ray instead of the march (occlusion falling off linearly) */
    voxgi_toggle half_resolution; /* rays at every other pixel across and down, upsampled by voxgi_screen_filter; default off
                                     for AO, on for GI */
    int blur;                     /* voxgi_screen_filter's radius in pixels, 1..64; 0: AO 2, GI 8; -1: none */
    voxgi_toggle hidden_light;    /* HYBRID: builds voxgi_ssgi_desc.hidden_radiance: rays meeting a voxel the camera does not
                                     see take the direct light injected into it (voxgi_inject_light, without emission);
                                     default on (off: they send nothing) */
    int inject_samples;           /* hidden_light: voxgi_inject_desc.samples; 0 = as VCT's */
} voxgi_render_screen;

typedef struct voxgi_render_linespace {
    const voxgi_linespace *ls;    /* the scene's line space, kept while the geometry stands still, or NULL: built from tree */
    voxgi_linespace_desc tree;    /* n 0 = 4, depth 0 = the scene's, memory_budget */
    voxgi_linespace_mode mode;
    int samples;                  /* shadow rays per shading point and light (voxgi_linespace_light_desc); 0 = 4 */
    int packets;                  /* 1: a point's rays walk the tree together (CPU); the same image */
    int exact_ends;               /* FAST: as voxgi_linespace_light_desc's; 0 = 3 */
    int supersample;              /* k x k shading points per pixel (the G-buffer k times the size), their mean: the pixel's
                                     square as the reference integrates it; 0 = 2, 1: the pixel's centre */
    float *visible;               /* NULL, or width x height floats out: per pixel the lights' mean visible share */
} voxgi_render_linespace;

typedef struct voxgi_render_reference {
    float ao_radius;              /* > 0: ambient occlusion within this radius instead of light (voxgi_ao's exact definition) */
    int screen_light_only;        /* 1 (one bounce): the bounce takes light only from surfaces the camera sees (the most
                                     one bounce from the screen can find) */
} voxgi_render_reference;

typedef struct voxgi_render_desc {
    voxgi_render_method method;
    voxgi_camera camera;          /* width x height 0 = 256 x 256; fovy 0 = 40 degrees; eye = target (a zero camera):
                                     the scene's bounds from in front and a little above */
    int samples;                  /* camera rays per pixel: REFERENCE paths (0 = 64), VCT, RSM, SH, SSGI and HYBRID the direct
                                     light's rays (0 = 24), TSM (0 = 4); the others take none (their pixel centres) */
    uint64_t seed;                /* every random number comes from (seed, pixel, sample): the same seed, the same image */
    int resolution;               /* the method's grid, voxels along the scene's longest side: VCT 0 = 96, RSM and SH 64,
                                     VAO and HYBRID 128; the other methods have none */
    int bounces;                  /* REFERENCE, VCT: indirect bounces; 0 = 1; -1: until they converge (full GI) */
    int direct_only;              /* 1: no indirect light (REFERENCE: bounces 0; VCT, RSM, SH, SSGI, HYBRID: no bounce) */
    int hide_emitters;            /* 1: leave out the emission the camera sees directly (to compare the lighting alone) */
    double error;                 /* VCT, > 0: the relative RMSE wanted: the grid, cones and stride not given come from the
                                     measured front (docs/planner.md); the other methods refuse it */
    size_t memory_budget;         /* bytes the plan may keep; 0: the context's (voxgi_desc.memory_budget) */
    const voxgi_voxels *voxels;   /* VCT: the static scene's voxels from voxgi_render_voxelize: the light is re-injected into
                                     them and nothing voxelized (a light-only update) */
    const voxgi_ray_scene *rays;  /* the static scene's ray scene (voxgi_ray_scene_create of this scene): no BVH built */
    voxgi_render_vct vct;
    voxgi_render_tsm tsm;
    voxgi_render_rsm rsm;
    voxgi_render_sh sh;
    voxgi_render_screen screen;   /* SSAO, VAO, SSGI, HYBRID */
    voxgi_render_linespace linespace;
    voxgi_render_reference reference;
} voxgi_render_desc;

/* ----- the planner
   voxgi_plan looks at a scene and at what a render desc asks of it and decides which channels,
   structures and passes can contribute: it names each one it keeps or leaves out and why, and
   what the kept ones cost in memory, before anything is allocated. voxgi_render follows its plan
   and returns it. */
typedef enum voxgi_plan_kind { VOXGI_PLAN_CHANNEL = 0, VOXGI_PLAN_STRUCTURE, VOXGI_PLAN_PASS } voxgi_plan_kind;
typedef enum voxgi_plan_item_id {
    VOXGI_PLAN_ALBEDO = 0, VOXGI_PLAN_NORMAL, VOXGI_PLAN_EMISSION, VOXGI_PLAN_OPACITY, VOXGI_PLAN_LIGHTS,   /* channels */
    VOXGI_PLAN_VOXELS, VOXGI_PLAN_RADIANCE_VOLUME, VOXGI_PLAN_RADIANCE_OCTREE, VOXGI_PLAN_SHADOW_MAPS,      /* structures */
    VOXGI_PLAN_TRANSMITTANCE_LAYERS, VOXGI_PLAN_REFLECTIVE_SHADOW_MAPS, VOXGI_PLAN_SH_VOLUME, VOXGI_PLAN_LINE_SPACE,
    VOXGI_PLAN_VOXELIZATION, VOXGI_PLAN_LIGHT_INJECTION, VOXGI_PLAN_BOUNCES, VOXGI_PLAN_CONES, VOXGI_PLAN_GATHERS, /* passes */
    VOXGI_PLAN_SCREEN_BOUNCE, VOXGI_PLAN_OCCLUSION, VOXGI_PLAN_SOFT_SHADOWS, VOXGI_PLAN_PATH_TRACING, VOXGI_PLAN_DIRECT_LIGHT,
    VOXGI_PLAN_SEEN_EMISSION,
    VOXGI_PLAN_ITEM_COUNT
} voxgi_plan_item_id;
typedef struct voxgi_plan_item {
    voxgi_plan_item_id id;
    const char *name;             /* "emission", "transmittance maps", "cones", ... */
    voxgi_plan_kind kind;
    int kept;
    const char *why;              /* why it is kept or left out */
    uint64_t bytes;               /* its memory when kept; 0: none to speak of */
    int estimated;                /* 1: bytes from the estimated set voxels (below), 0: the formula it is allocated by */
} voxgi_plan_item;
#define VOXGI_PLAN_MAX_ITEMS 16
typedef struct voxgi_plan_info {
    uint64_t triangles, emissive_triangles, translucent_triangles, reflective_triangles; /* reflective: albedo > 0 */
    int point_lights, spot_lights, directional_lights, rect_lights;
    int area_lights;              /* rect lights and the emissive triangles' parallelograms (the line space's); -1: over 64 */
    int emitters_in_view;         /* 1: an emissive front face may be in view, 0: none is */
    double surface_area;
    voxgi_grid grid;              /* the method's grid (voxgi_fit_grid of the resolution used, a voxel of padding); zero: none */
    uint64_t voxels;              /* estimated set voxels: the sum over triangles of area x (|nx| + |ny| + |nz|) /
                                     voxel size^2, at most the grid's */
    double occupancy;             /* voxels / the grid's voxels */
    double expected_error;        /* VCT with error: what the chosen settings measured on the Cornell box */
    int error_reachable;          /* 0: no measured setting reaches the error asked for (the closest is chosen) */
    int item_count;
    voxgi_plan_item items[VOXGI_PLAN_MAX_ITEMS];
    uint64_t bytes;               /* the kept items' */
} voxgi_plan_info;
enum { VOXGI_PLAN_DYNAMIC = 1, VOXGI_PLAN_EVERYTHING = 2 }; /* voxgi_plan's flags */
/* The plan of voxgi_render(ctx, scene, desc): flags DYNAMIC (the geometry moves every frame: what
   re-runs), EVERYTHING (keep every item the method has, to measure what the plan saves). */
VOXGI_API voxgi_result voxgi_plan(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_render_desc *desc, unsigned flags, voxgi_plan_info *plan);
/* The plan's item of that id, or NULL when the method has none. */
VOXGI_API const voxgi_plan_item *voxgi_plan_find(const voxgi_plan_info *plan, voxgi_plan_item_id id);

/* ----- rendering */
#define VOXGI_RENDER_MAX_STAGES 6
typedef struct voxgi_render_stage {
    const char *name;             /* "voxelize", "inject", "cones", "direct", "maps", "gather", ... */
    double ms;                    /* wall time (GL work included: each stage waits for its GL work) */
} voxgi_render_stage;
typedef struct voxgi_render_info {
    voxgi_render_desc used;       /* the settings that ran: every default resolved */
    voxgi_plan_info plan;
    double ms;                    /* all */
    int stage_count;
    voxgi_render_stage stages[VOXGI_RENDER_MAX_STAGES]; /* the passes in the order they ran, each with its time */
    size_t bytes;                 /* what was built from the scene: VCT the radiance the cones gather from; TSM, RSM the
                                     maps; SH its volume; the voxels of visibility and their OR mipmaps; the hidden light */
    uint64_t voxels;              /* VCT: the voxels set */
    size_t gathered;              /* pixels that gathered (cones, bounces, occlusion; the rest interpolated) */
    int maps;                     /* TSM, RSM: the maps made */
    int lights;                   /* LINESPACE: the area lights */
    uint64_t rays;                /* REFERENCE: every ray cast (camera, bounce, shadow) */
    size_t triangles, bvh_nodes;  /* REFERENCE: the scene's ray scene */
    voxgi_linespace_info tree;    /* LINESPACE: the line space */
    voxgi_linespace_stats shadow_rays; /* LINESPACE: its rays over all lights */
} voxgi_render_info;
/* The image into rgb (3 floats per pixel, linear radiance, rows from the top; SSAO and VAO: the
   occluded share, grey, 0 where the camera sees nothing; rgb_bytes at least width x height x 12);
   info may be NULL. On a GL context each method runs its passes on GL where it has them (the
   direct light's and the reference's rays stay on the CPU). A scene with no light and no emissive
   material is rendered, black as it is (VOXGI_OK: a light switched off is a scene too), and a
   VOXGI_LOG_WARNING through the context's logger says so; occlusion (SSAO, VAO, the reference's
   ao_radius) needs no light and gives none. */
VOXGI_API voxgi_result voxgi_render(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_render_desc *desc, float *rgb, size_t rgb_bytes,
                                    voxgi_render_info *info);
/* A stage's time in an image's info by its name ("cones", "gather", ...); 0 when it did not run. */
VOXGI_API double voxgi_render_stage_ms(const voxgi_render_info *info, const char *name);
/* The settings voxgi_render would run with, every default resolved for this scene (what
   info.used reports), without rendering. */
VOXGI_API voxgi_result voxgi_render_resolve(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_render_desc *desc, voxgi_render_desc *used);
/* A method's name ("reference", "vct", "tsm", "rsm", "sh", "ssao", "vao", "ssgi", "hybrid",
   "linespace"), or NULL; voxgi_render_method_find: the method of a name, or -1. */
VOXGI_API const char *voxgi_render_method_name(voxgi_render_method method);
VOXGI_API int voxgi_render_method_find(const char *name);
/* One line naming the method and every setting of `used` it reads (as voxgi_render_resolve or
   info.used give them), into buf (snprintf's rules); its length. */
VOXGI_API int voxgi_render_describe(const voxgi_render_desc *used, char *buf, size_t size);
/* The voxels voxgi_render makes of the scene for VCT with desc's resolution (its grid, albedo
   and normal), to keep while the geometry stands still: an image given them as desc.voxels is
   bit for bit the one that voxelizes, whatever its lights. Images with another resolution, or of a
   scene with other bounds or another triangle count, refuse them (VOXGI_ERR_INVALID_ARGUMENT);
   geometry moved within the same bounds is the caller's to notice. */
VOXGI_API voxgi_result voxgi_render_voxelize(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_render_desc *desc, voxgi_voxels **out);

/* The G-buffer voxgi renders for its own images: per pixel the surface the ray through the
   pixel's centre meets first: its position (world units), its normal facing the camera, its
   triangle (in the scene's order: meshes, then triangles; UINT32_MAX and zeros where nothing
   is). CPU: ray cast, exact. GL: rasterized with a depth test (positions interpolated in float
   relative to the eye; at shared edges and silhouettes the rasterizer may pick the neighbour).
   Each output holds width x height entries (positions and normals 3 floats), rows from the top;
   any may be NULL. */
VOXGI_API voxgi_result voxgi_gbuffer_render(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_camera *camera, float *positions, float *normals,
                                            uint32_t *triangles);


/* ===================================================================== 15. built-in scenes and files */

/* Scenes that need no files, each with its usual view (256 x 256):
   "cornell-box"  the Cornell box (the published geometry in metres, the light 0.1 mm below the
                  ceiling; albedos white 0.725 0.71 0.68, red 0.63 0.065 0.05, green 0.14 0.45
                  0.091; the light's radiance 17 12 4);
   "rsm-walls"    two white spheres before a red and a blue wall with a grey divider between
                  them, lit by a directional light (Buchacher 2014's visibility test scene);
   "leak-box"     a closed box with the camera inside and every light outside: the exact image
                  is black, so anything else is light leaking through the walls;
   "leak-room"    a closed room (2 m, walls facing in, albedo 0.5) with a closed box of
                  zero-thickness faces (0.6 x 0.5 x 0.6 m, albedo 0.5) on its floor and a 0.4 m
                  square lamp (radiance 10) 1.45 m above the box's top, the camera inside the
                  box: black again, with the light bouncing around the box's outer faces;
   "furnace"      a closed sphere of albedo 0.5 and emission 1 seen from inside: radiance 2
                  everywhere (E / (1 - albedo));
   "foliage"      a tree under the sun: an opaque trunk, a canopy of 1200 small leaf quads of
                  transparency 0.7 (Buchacher 2014's transmittance shadow map scene), a ground. */
typedef struct voxgi_builtin_scene {
    voxgi_scene scene;            /* points into memory the struct owns */
    voxgi_camera camera;
    const char *name;
    void *storage;
} voxgi_builtin_scene;
VOXGI_API voxgi_result voxgi_builtin_scene_create(voxgi_context *ctx, const char *name, voxgi_builtin_scene *out);
VOXGI_API void voxgi_builtin_scene_destroy(voxgi_context *ctx, voxgi_builtin_scene *scene);
VOXGI_API const char *voxgi_builtin_scene_names(void); /* space separated */

/* ----- binvox files */
/* binvox: "dim" lists x z y extents (binvox's depth, height, width), data runs with y fastest,
   then z, then x; translate = grid origin, scale = voxel_size * max(res). */
VOXGI_API voxgi_result voxgi_binvox_write(FILE *f, const voxgi_grid *grid, const uint32_t *bits);
/* Reads a binvox file: call with bits == NULL to learn the grid and *needed bytes, then again.
   VOXGI_ERR_FORMAT for a malformed file, and for one whose grid voxgi_validate_grid refuses (a
   translate beyond 1e30 or not finite, a voxel size outside [1e-30, 1e30]). */
VOXGI_API voxgi_result voxgi_binvox_read(FILE *f, voxgi_grid *grid, uint32_t *bits,
                                         size_t bits_bytes, size_t *needed);

#ifdef __cplusplus
}
#endif
#endif /* VOXGI_H */

/* ************************************************************************************************
   IMPLEMENTATION
   ************************************************************************************************ */
#ifdef VOXGI_IMPLEMENTATION
#ifndef VOXGI__IMPLEMENTED
#define VOXGI__IMPLEMENTED
#if defined(__FAST_MATH__)
#error "voxgi: the implementation needs IEEE double arithmetic; compile it without -ffast-math"
#endif

#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <stdarg.h>
#include <float.h>
#include <limits.h>
#include <errno.h>

/* ===================================================================== 1. config */

#if defined(VOXGI_MALLOC) != defined(VOXGI_FREE)
#error "voxgi: define both VOXGI_MALLOC and VOXGI_FREE, or neither"
#endif
#ifndef VOXGI_MALLOC
#define VOXGI_MALLOC(sz) malloc(sz)
#define VOXGI_FREE(p) free(p)
#define VOXGI__CALLOC(n, sz) calloc(n, sz) /* zeroed by the system as pages are first touched: a volume's empty space costs nothing */
#endif
#ifndef VOXGI_ASSERT
#include <assert.h>
#define VOXGI_ASSERT(x) assert(x)
#endif
#if defined(_WIN32) && !defined(VOXGI_NO_THREADS)
#define VOXGI_NO_THREADS /* the worker pool is written against pthreads */
#endif
#ifndef VOXGI_NO_THREADS
#include <pthread.h>
#include <unistd.h>
#endif
#include <time.h>
#ifndef _WIN32
#include <sys/time.h>
#endif
/* SSE where the compiler targets it (the ray core tests four boxes at once); VOXGI_NO_SIMD: the
   scalar code, which computes the same, everywhere. */
#if !defined(VOXGI_NO_SIMD) && (defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2))
#include <emmintrin.h>
#define VOXGI__SSE 1
#endif
/* AVX2 where the compiler targets it (-mavx2, -march=native): the ray core's nodes hold eight
   children, tested at once; else four. */
#if defined(VOXGI__SSE) && defined(__AVX2__)
#include <immintrin.h>
#define VOXGI__AVX2 1
#define VOXGI__BVH_WIDTH 8
#else
#define VOXGI__BVH_WIDTH 4
#endif
#if defined(__GNUC__) || defined(__clang__)
#define VOXGI__HOT_INLINE __inline__ __attribute__((always_inline)) /* small functions on the hottest paths */
#elif defined(_MSC_VER)
#define VOXGI__HOT_INLINE __forceinline
#else
#define VOXGI__HOT_INLINE
#endif

#if defined(__GNUC__) || defined(__clang__)
#define VOXGI__ATOMIC_OR_U32(p, v) __atomic_fetch_or((p), (v), __ATOMIC_RELAXED)
#define VOXGI__ATOMIC_ADD_SIZE(p, v) __atomic_fetch_add((p), (v), __ATOMIC_RELAXED)
#define VOXGI__ATOMIC_LOAD_INT(p) __atomic_load_n((p), __ATOMIC_RELAXED)
#define VOXGI__ATOMIC_STORE_INT(p, v) __atomic_store_n((p), (v), __ATOMIC_RELAXED)
#define VOXGI__ATOMIC_LOAD_U32(p) __atomic_load_n((p), __ATOMIC_RELAXED)
#define VOXGI__ATOMIC_CAS_U32(p, expected, v) __atomic_compare_exchange_n((p), (expected), (v), 1, __ATOMIC_RELAXED, __ATOMIC_RELAXED)
#define VOXGI__ATOMIC_LOAD_U64(p) __atomic_load_n((p), __ATOMIC_RELAXED)
#define VOXGI__ATOMIC_CAS_U64(p, expected, v) __atomic_compare_exchange_n((p), (expected), (v), 1, __ATOMIC_RELAXED, __ATOMIC_RELAXED)
#else
#ifndef VOXGI_NO_THREADS
#define VOXGI_NO_THREADS
#endif
#define VOXGI__ATOMIC_OR_U32(p, v) (*(p) |= (v))
#define VOXGI__ATOMIC_ADD_SIZE(p, v) ((*(p) += (v)) - (v))
#define VOXGI__ATOMIC_LOAD_INT(p) (*(p))
#define VOXGI__ATOMIC_STORE_INT(p, v) (*(p) = (v))
#define VOXGI__ATOMIC_LOAD_U32(p) (*(p))
#define VOXGI__ATOMIC_CAS_U32(p, expected, v) (*(p) = (v), 1) /* single-threaded: no one else writes */
#define VOXGI__ATOMIC_LOAD_U64(p) (*(p))
#define VOXGI__ATOMIC_CAS_U64(p, expected, v) (*(p) = (v), 1)
#endif

#define VOXGI__MIN(a, b) ((a) < (b) ? (a) : (b))
#define VOXGI__MAX(a, b) ((a) > (b) ? (a) : (b))
#define VOXGI__PI 3.14159265358979323846

/* ===================================================================== 2. core */

/* ----- 2.1 the context, errors and memory */

#ifndef VOXGI_NO_GL
typedef struct voxgi__gl voxgi__gl;
/* The one reach upward: a context on GL sets up the GL core (part 4) when it is created. */
static voxgi_result voxgi__gl_init(voxgi_context *ctx);
static void voxgi__gl_shutdown(voxgi_context *ctx);
#endif

struct voxgi_context {
    voxgi_desc desc;               /* resolved */
    voxgi_backend backend;
    char error[4096];
    char gl_version[160], gl_renderer[160];
    int gl_software;               /* voxgi__gl_is_software(gl_renderer) */
#ifndef VOXGI_NO_GL
    voxgi__gl *gl;
#endif
};

static double voxgi__now_ms(void)
{
#if defined(CLOCK_MONOTONIC) && !defined(_WIN32)
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
#elif !defined(_WIN32)
    struct timeval tv;
    gettimeofday(&tv, NULL);
    return (double)tv.tv_sec * 1e3 + (double)tv.tv_usec * 1e-3;
#else
    return (double)clock() * 1e3 / (double)CLOCKS_PER_SEC;
#endif
}

static void voxgi__log(const voxgi_context *ctx, voxgi_log_level level, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    if (!ctx || !ctx->desc.logger.func) return;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    ctx->desc.logger.func(level, msg, ctx->desc.logger.user);
}

/* Records why a call failed (voxgi_last_error), logs it, and returns the result code. */
static voxgi_result voxgi__fail(voxgi_context *ctx, voxgi_result r, const char *fmt, ...)
{
    va_list ap;
    if (!ctx) return r;
    va_start(ap, fmt);
    vsnprintf(ctx->error, sizeof ctx->error, fmt, ap);
    va_end(ap);
    voxgi__log(ctx, VOXGI_LOG_ERROR, "%s: %s", voxgi_result_string(r), ctx->error);
    return r;
}

static void *voxgi__alloc(voxgi_context *ctx, size_t size)
{
    if (size == 0) size = 1;
    if (ctx->desc.allocator.alloc) return ctx->desc.allocator.alloc(size, ctx->desc.allocator.user);
    return VOXGI_MALLOC(size);
}
static void voxgi__free(voxgi_context *ctx, void *p)
{
    if (!p) return;
    if (ctx->desc.allocator.free) ctx->desc.allocator.free(p, ctx->desc.allocator.user);
    else VOXGI_FREE(p);
}
/* Allocates count*size bytes, failing cleanly on overflow; zeroed when asked. */
static void *voxgi__alloc_array(voxgi_context *ctx, size_t count, size_t size, int zero)
{
    void *p;
    if (size && count > (size_t)-1 / size) return NULL;
#ifdef VOXGI__CALLOC
    if (zero && !ctx->desc.allocator.alloc) return VOXGI__CALLOC(count ? count : 1, size ? size : 1);
#endif
    p = voxgi__alloc(ctx, count * size);
    if (p && zero) memset(p, 0, count * size);
    return p;
}

/* Calls the progress hook; non-zero means the caller cancelled. */
static int voxgi__progress(voxgi_context *ctx, double fraction, const char *stage)
{
    return ctx->desc.progress.func ? ctx->desc.progress.func(fraction, stage, ctx->desc.progress.user) : 0;
}

#if !defined(VOXGI_NO_OCTREE) || !defined(VOXGI_NO_CONE_TRACING) || !defined(VOXGI_NO_LIGHT_INJECTION) /* the parts that can be cancelled */
/* Reports progress at `stage`; non-zero when the caller cancelled (the error then says where). */
static int voxgi__cancelled(voxgi_context *ctx, double fraction, const char *what, const char *stage)
{
    if (!voxgi__progress(ctx, fraction, stage)) return 0;
    voxgi__fail(ctx, VOXGI_ERR_CANCELLED, "%s cancelled by the progress callback (%s)", what, stage);
    return 1;
}
#endif

static int voxgi__core_count(void)
{
#if !defined(VOXGI_NO_THREADS) && defined(_SC_NPROCESSORS_ONLN)
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : (n > 256 ? 256 : (int)n);
#else
    return 1;
#endif
}

/* Every default lives here: zero in a desc means "use this". */
static voxgi_desc voxgi__desc_defaults(const voxgi_desc *in)
{
    voxgi_desc d = *in;
    if (d.thread_count <= 0) d.thread_count = voxgi__core_count();
#ifdef VOXGI_NO_THREADS
    d.thread_count = 1;
#endif
    if (!d.allocator.alloc || !d.allocator.free) { d.allocator.alloc = NULL; d.allocator.free = NULL; }
    return d;
}

VOXGI_API const char *voxgi_result_string(voxgi_result r)
{
    static const char *names[VOXGI_RESULT_COUNT_] = {
        "VOXGI_OK", "VOXGI_ERR_INVALID_ARGUMENT", "VOXGI_ERR_INVALID_SCENE", "VOXGI_ERR_EMPTY_SCENE",
        "VOXGI_ERR_INVALID_GRID", "VOXGI_ERR_TOO_LARGE", "VOXGI_ERR_OUT_OF_MEMORY",
        "VOXGI_ERR_BUFFER_TOO_SMALL", "VOXGI_ERR_UNSUPPORTED", "VOXGI_ERR_GL_UNAVAILABLE",
        "VOXGI_ERR_GL_MISSING_FUNCTION", "VOXGI_ERR_GL_SHADER", "VOXGI_ERR_GL", "VOXGI_ERR_CANCELLED",
        "VOXGI_ERR_IO", "VOXGI_ERR_FORMAT"};
    return ((unsigned)r < VOXGI_RESULT_COUNT_) ? names[r] : "VOXGI_ERR_UNKNOWN";
}

VOXGI_API const char *voxgi_backend_name(voxgi_backend b)
{
    switch (b) {
    case VOXGI_BACKEND_AUTO: return "auto";
    case VOXGI_BACKEND_CPU: return "cpu";
    case VOXGI_BACKEND_GL: return "gl";
    }
    return "unknown";
}

VOXGI_API voxgi_result voxgi_create(const voxgi_desc *desc, voxgi_context **out)
{
    voxgi_desc d;
    voxgi_context *ctx;
    if (!out) return VOXGI_ERR_INVALID_ARGUMENT;
    *out = NULL;
    if (!desc) return VOXGI_ERR_INVALID_ARGUMENT;
    if ((unsigned)desc->backend > (unsigned)VOXGI_BACKEND_GL) return VOXGI_ERR_INVALID_ARGUMENT;
    d = voxgi__desc_defaults(desc);
    ctx = (voxgi_context *)(d.allocator.alloc ? d.allocator.alloc(sizeof *ctx, d.allocator.user)
                                              : VOXGI_MALLOC(sizeof *ctx));
    if (!ctx) return VOXGI_ERR_OUT_OF_MEMORY;
    memset(ctx, 0, sizeof *ctx);
    ctx->desc = d;
    ctx->backend = VOXGI_BACKEND_CPU;
    if (d.backend != VOXGI_BACKEND_CPU) {
#ifdef VOXGI_NO_GL
        if (d.backend == VOXGI_BACKEND_GL) {
            voxgi__log(ctx, VOXGI_LOG_ERROR, "the GL backend is compiled out (VOXGI_NO_GL)");
            voxgi_destroy(ctx);
            return VOXGI_ERR_UNSUPPORTED;
        }
        voxgi__log(ctx, VOXGI_LOG_INFO, "backend auto: CPU, because GL is compiled out (VOXGI_NO_GL)");
#else
        voxgi_result r = voxgi__gl_init(ctx);
        if (r == VOXGI_OK && d.backend == VOXGI_BACKEND_AUTO && ctx->gl_software) {
            voxgi__gl_shutdown(ctx); /* gl_version and gl_renderer stay, for voxgi_query_info */
            voxgi__log(ctx, VOXGI_LOG_INFO, "backend auto: CPU, because the GL renderer %s is a software rasterizer on "
                       "the CPU's own cores, where the CPU backend is faster (VOXGI_BACKEND_GL uses it anyway)", ctx->gl_renderer);
        } else if (r == VOXGI_OK) {
            ctx->backend = VOXGI_BACKEND_GL;
            voxgi__log(ctx, VOXGI_LOG_INFO, "backend %s: GL, %s, %s%s", voxgi_backend_name(d.backend), ctx->gl_version, ctx->gl_renderer,
                       ctx->gl_software ? " (a software rasterizer on the CPU's own cores: VOXGI_BACKEND_CPU is usually faster)" : "");
        } else if (d.backend == VOXGI_BACKEND_GL) {
            voxgi_destroy(ctx);
            return r;
        } else {
            voxgi__log(ctx, VOXGI_LOG_INFO, "backend auto: CPU, because GL is not usable: %s", ctx->error);
            ctx->error[0] = 0;
        }
#endif
    }
    *out = ctx;
    return VOXGI_OK;
}

VOXGI_API void voxgi_destroy(voxgi_context *ctx)
{
    voxgi_allocator a;
    if (!ctx) return;
#ifndef VOXGI_NO_GL
    voxgi__gl_shutdown(ctx);
#endif
    a = ctx->desc.allocator;
    if (a.free) a.free(ctx, a.user);
    else VOXGI_FREE(ctx);
}

VOXGI_API voxgi_desc voxgi_query_desc(const voxgi_context *ctx)
{
    voxgi_desc d;
    memset(&d, 0, sizeof d);
    return ctx ? ctx->desc : d;
}

VOXGI_API void voxgi_query_info(const voxgi_context *ctx, voxgi_info *out)
{
    if (!out) return;
    memset(out, 0, sizeof *out);
    out->capabilities = "cpu"
#ifndef VOXGI_NO_GL
                        " gl"
#endif
#ifndef VOXGI_NO_THREADS
                        " threads"
#endif
                        " conservative binvox"
#ifndef VOXGI_NO_OCTREE
                        " octree"
#endif
#ifndef VOXGI_NO_CONE_TRACING
                        " cone-tracing"
#endif
#ifndef VOXGI_NO_LIGHT_INJECTION
                        " light-injection"
#endif
#ifndef VOXGI_NO_LIGHT_SPACE
                        " light-space"
#endif
#ifndef VOXGI_NO_SCREEN_SPACE
                        " screen-space"
#endif
#ifndef VOXGI_NO_LINE_SPACE
                        " line-space"
#endif
#ifndef VOXGI_NO_REFERENCE
                        " reference"
#endif
                        ;
    out->gl_version = ctx ? ctx->gl_version : "";
    out->gl_renderer = ctx ? ctx->gl_renderer : "";
    if (!ctx) return;
    out->gl_software = ctx->gl_software;
    out->backend = ctx->backend;
    out->thread_count = ctx->desc.thread_count;
}

VOXGI_API const char *voxgi_last_error(const voxgi_context *ctx) { return ctx ? ctx->error : ""; }

/* ----- 2.2 numbers: bit counts, Morton codes, random numbers, frames */

static uint32_t voxgi__popcount32(uint32_t x)
{
    x = x - ((x >> 1) & 0x55555555u);
    x = (x & 0x33333333u) + ((x >> 2) & 0x33333333u);
    return (((x + (x >> 4)) & 0x0F0F0F0Fu) * 0x01010101u) >> 24;
}

/* The lowest set bit's index (x != 0). */
static VOXGI__HOT_INLINE int voxgi__ctz32(uint32_t x)
{
#if defined(__GNUC__) || defined(__clang__)
    return __builtin_ctz(x);
#else
    return (int)voxgi__popcount32((x & (0u - x)) - 1u);
#endif
}

static VOXGI__HOT_INLINE int voxgi__ctz64(uint64_t x)
{
    return (uint32_t)x ? voxgi__ctz32((uint32_t)x) : 32 + voxgi__ctz32((uint32_t)(x >> 32));
}

#if !defined(VOXGI_NO_OCTREE) || !defined(VOXGI_NO_LIGHT_INJECTION) /* the octree's and the bounces' orders */
/* Spreads the low 21 bits of v to every third bit. */
static uint64_t voxgi__spread3(uint64_t v)
{
    v &= 0x1FFFFFu;
    v = (v | v << 32) & 0x1F00000000FFFFull;
    v = (v | v << 16) & 0x1F0000FF0000FFull;
    v = (v | v << 8) & 0x100F00F00F00F00Full;
    v = (v | v << 4) & 0x10C30C30C30C30C3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
}

/* The Morton code: x in bit 0 of every octal digit, y in bit 1, z in bit 2. */
static uint64_t voxgi__morton(uint32_t x, uint32_t y, uint32_t z)
{
    return voxgi__spread3(x) | voxgi__spread3(y) << 1 | voxgi__spread3(z) << 2;
}

/* Sorts codes (with their payloads) ascending: LSD radix over the bytes the codes use. */
static voxgi_result voxgi__sort_codes(voxgi_context *ctx, uint64_t *code, uint32_t *payload, size_t n, int bits)
{
    uint64_t *c2 = (uint64_t *)voxgi__alloc_array(ctx, n ? n : 1, sizeof *c2, 0);
    uint32_t *p2 = (uint32_t *)voxgi__alloc_array(ctx, n ? n : 1, sizeof *p2, 0);
    size_t i, count[256];
    int shift;
    if (!c2 || !p2) { voxgi__free(ctx, c2); voxgi__free(ctx, p2); return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory to sort"); }
    for (shift = 0; shift < bits; shift += 8) {
        size_t sum = 0;
        memset(count, 0, sizeof count);
        for (i = 0; i < n; i++) count[(code[i] >> shift) & 255u]++;
        for (i = 0; i < 256; i++) { size_t k = count[i]; count[i] = sum; sum += k; }
        for (i = 0; i < n; i++) {
            size_t at = count[(code[i] >> shift) & 255u]++;
            c2[at] = code[i];
            p2[at] = payload[i];
        }
        memcpy(code, c2, n * sizeof *code);
        memcpy(payload, p2, n * sizeof *payload);
    }
    voxgi__free(ctx, c2);
    voxgi__free(ctx, p2);
    return VOXGI_OK;
}
#endif

/* Random numbers: one PCG32 stream per (seed, pixel, sample), seeded through splitmix64. */
typedef struct voxgi__rng { uint64_t state, inc; } voxgi__rng;

static uint64_t voxgi__splitmix(uint64_t *x)
{
    uint64_t z = (*x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static void voxgi__rng_seed(voxgi__rng *g, uint64_t seed, uint64_t pixel, uint64_t sample)
{
    uint64_t x = seed ^ voxgi__splitmix(&pixel) ^ (voxgi__splitmix(&sample) << 1);
    g->state = voxgi__splitmix(&x);
    g->inc = voxgi__splitmix(&x) | 1u;
}

static uint32_t voxgi__rng_u32(voxgi__rng *g)
{
    uint64_t old = g->state;
    uint32_t xs, rot;
    g->state = old * 6364136223846793005ull + g->inc;
    xs = (uint32_t)(((old >> 18) ^ old) >> 27);
    rot = (uint32_t)(old >> 59);
    return (xs >> rot) | (xs << ((32u - rot) & 31u));
}

static double voxgi__rng_unit(voxgi__rng *g) /* [0, 1) with 53 bits */
{
    uint64_t hi = voxgi__rng_u32(g) >> 5, lo = voxgi__rng_u32(g) >> 6;
    return (double)(hi * 67108864u + lo) / 9007199254740992.0;
}

#if !defined(VOXGI_NO_LIGHT_INJECTION) || !defined(VOXGI_NO_LIGHT_SPACE) || !defined(VOXGI_NO_SCREEN_SPACE) /* their stratified samples */
/* Point k (from 0) of the 2D or 4D Kronecker sequence shifted by rot: frac(rot + (k + 1) alpha),
   alpha the powers of 1 / phi_d (phi_d the root of x^(d+1) = x + 1), evenly spread in any prefix:
   the stratified samples of light injection, light casters and images. */
static void voxgi__kronecker(int dims, int k, const double *rot, double *u)
{
    static const double alpha2[2] = {0.7548776662466927, 0.5698402909980532};
    static const double alpha4[4] = {0.8566748838545029, 0.7338918566271260, 0.6287067210378087, 0.5385972572236101};
    const double *alpha = dims == 2 ? alpha2 : alpha4;
    int a;
    for (a = 0; a < dims; a++) {
        u[a] = rot[a] + (k + 1) * alpha[a];
        u[a] -= floor(u[a]);
    }
}
#endif

/* An orthonormal basis (t, b) around unit n. */
static void voxgi__basis(const double n[3], double t[3], double b[3])
{
    double sgn = n[2] >= 0 ? 1.0 : -1.0, a = -1.0 / (sgn + n[2]), c = n[0] * n[1] * a;
    t[0] = 1 + sgn * n[0] * n[0] * a; t[1] = sgn * c; t[2] = -sgn * n[0];
    b[0] = c; b[1] = sgn + n[1] * n[1] * a; b[2] = -n[1];
}

/* ----- 2.3 the worker pool: a parallel loop on the calling thread and helpers */

/* ----- a parallel loop over items [0, count) in chunks, on the calling thread and
   (thread_count - 1) helpers; fn must be safe to run concurrently on disjoint ranges. */
typedef void (*voxgi__range_fn)(void *user, size_t first, size_t end);
typedef struct voxgi__loop { voxgi__range_fn fn; void *user; size_t count, chunk, next; } voxgi__loop;

static void *voxgi__loop_work(void *p)
{
    voxgi__loop *l = (voxgi__loop *)p;
    for (;;) {
        size_t first = VOXGI__ATOMIC_ADD_SIZE(&l->next, l->chunk);
        if (first >= l->count) break;
        l->fn(l->user, first, VOXGI__MIN(first + l->chunk, l->count));
    }
    return NULL;
}

static void voxgi__parallel(voxgi_context *ctx, size_t count, size_t chunk, voxgi__range_fn fn, void *user)
{
    voxgi__loop l;
    int started = 0;
#ifndef VOXGI_NO_THREADS
    pthread_t threads[256];
    int i, want = ctx->desc.thread_count - 1;
    if ((size_t)want > count / chunk) want = (int)(count / chunk);
#else
    (void)ctx;
#endif
    l.fn = fn;
    l.user = user;
    l.count = count;
    l.chunk = chunk ? chunk : 1;
    l.next = 0;
#ifndef VOXGI_NO_THREADS
    for (i = 0; i < want && i < 256; i++) {
        if (pthread_create(&threads[i], NULL, voxgi__loop_work, &l) != 0) break;
        started++;
    }
#endif
    voxgi__loop_work(&l);
#ifndef VOXGI_NO_THREADS
    for (i = 0; i < started; i++) pthread_join(threads[i], NULL);
#else
    (void)started;
#endif
}

/* ===================================================================== 3. scene */

/* ----- 3.1 validation and flattening */

/* Vertex i of mesh m in the scene's frame: its floats, or its doubles less the frame's origin.
   Copied out byte by byte: a stride need not keep the values aligned. */
static void voxgi__vertex(const voxgi_scene *scene, const voxgi_mesh *m, size_t i, float out[3])
{
    if (m->positions_double) {
        double d[3];
        int a;
        memcpy(d, (const unsigned char *)m->positions_double + i * (m->position_stride ? m->position_stride : 24), sizeof d);
        for (a = 0; a < 3; a++) out[a] = (float)(d[a] - scene->origin[a]);
    } else
        memcpy(out, (const unsigned char *)m->positions + i * (m->position_stride ? m->position_stride : 12), 3 * sizeof(float));
}
static size_t voxgi__mesh_triangles(const voxgi_mesh *m)
{
    return m->indices ? m->index_count / 3 : m->vertex_count / 3;
}
static uint32_t voxgi__mesh_index(const voxgi_mesh *m, size_t t, int corner)
{
    return m->indices ? m->indices[3 * t + (size_t)corner] : (uint32_t)(3 * t + (size_t)corner);
}
static int voxgi__finite3(const float *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

/* Counts the triangles and checks every input a voxelizer or renderer reads. */
static voxgi_result voxgi__validate(voxgi_context *ctx, const voxgi_scene *scene, size_t *triangles_out,
                                    size_t *vertices_out)
{
    size_t mi, t, total_tris = 0, total_verts = 0;
    if (!scene) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "scene is NULL");
    if (scene->mesh_count && !scene->meshes)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE, "scene.meshes is NULL but mesh_count is %lu",
                           (unsigned long)scene->mesh_count);
    if (scene->material_count && !scene->materials)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE, "scene.materials is NULL but material_count is %lu",
                           (unsigned long)scene->material_count);
    if (!isfinite(scene->origin[0]) || !isfinite(scene->origin[1]) || !isfinite(scene->origin[2]))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE, "scene.origin is not finite");
    for (mi = 0; mi < scene->material_count; mi++) {
        const voxgi_material *mat = &scene->materials[mi];
        int c, ok = isfinite(mat->transparency) && mat->transparency >= 0 && mat->transparency <= 1;
        for (c = 0; c < 3; c++)
            ok = ok && isfinite(mat->albedo[c]) && mat->albedo[c] >= 0 && mat->albedo[c] <= 1 && isfinite(mat->emission[c]) &&
                 mat->emission[c] >= 0;
        if (!ok)
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE, "material %lu: albedo and transparency must lie in [0,1], "
                               "emission must be finite and >= 0", (unsigned long)mi);
    }
    if (scene->light_count && !scene->lights)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE, "scene.lights is NULL but light_count is %lu", (unsigned long)scene->light_count);
    for (mi = 0; mi < scene->light_count; mi++) {
        const voxgi_light *L = &scene->lights[mi];
        double dir = 0, cross = 0;
        int c, ok = L->type >= VOXGI_LIGHT_POINT && L->type <= VOXGI_LIGHT_RECT && isfinite(L->spot_inner) && isfinite(L->spot_outer);
        for (c = 0; c < 3; c++) {
            double x = (double)L->edge_u[(c + 1) % 3] * L->edge_v[(c + 2) % 3] - (double)L->edge_u[(c + 2) % 3] * L->edge_v[(c + 1) % 3];
            ok = ok && isfinite(L->position[c]) && isfinite(L->direction[c]) && isfinite(L->intensity[c]) && L->intensity[c] >= 0 &&
                 isfinite(L->edge_u[c]) && isfinite(L->edge_v[c]);
            dir += (double)L->direction[c] * L->direction[c];
            cross += x * x;
        }
        if ((L->type == VOXGI_LIGHT_SPOT || L->type == VOXGI_LIGHT_DIRECTIONAL) && !(dir > 0)) ok = 0;
        if (L->type == VOXGI_LIGHT_RECT && !(cross > 0)) ok = 0;
        if (L->type == VOXGI_LIGHT_SPOT && !(L->spot_inner >= 0 && L->spot_inner <= L->spot_outer && L->spot_outer <= 3.14159265f)) ok = 0;
        if (!ok)
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE, "light %lu: a known type, finite values, intensity >= 0, a direction for spot and "
                               "directional lights, two independent edges for a rect light, 0 <= spot_inner <= spot_outer <= pi", (unsigned long)mi);
    }
    for (mi = 0; mi < scene->mesh_count; mi++) {
        const voxgi_mesh *m = &scene->meshes[mi];
        size_t nt;
        if (m->position_stride && m->position_stride < (m->positions_double ? 3 * sizeof(double) : 3 * sizeof(float)))
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE, "mesh %lu: position_stride %lu is less than a vertex (%d bytes)",
                               (unsigned long)mi, (unsigned long)m->position_stride, m->positions_double ? 24 : 12);
        if (m->positions && m->positions_double)
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE, "mesh %lu: both positions and positions_double are set", (unsigned long)mi);
        if ((m->normal_stride && m->normal_stride < 3 * sizeof(float)) || (m->uv_stride && m->uv_stride < 2 * sizeof(float)))
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE, "mesh %lu: normal or uv stride too small", (unsigned long)mi);
        if (m->vertex_count && !m->positions && !m->positions_double)
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE, "mesh %lu: positions is NULL but vertex_count is %lu",
                               (unsigned long)mi, (unsigned long)m->vertex_count);
        if (m->vertex_count > (size_t)UINT32_MAX)
            return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "mesh %lu: %lu vertices exceed the 32-bit index range",
                               (unsigned long)mi, (unsigned long)m->vertex_count);
        if (m->vertex_count > (size_t)-1 / (m->position_stride ? m->position_stride : 24))
            return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "mesh %lu: vertex_count * stride overflows", (unsigned long)mi);
        if (m->indices == NULL && m->index_count)
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE, "mesh %lu: indices is NULL but index_count is %lu",
                               (unsigned long)mi, (unsigned long)m->index_count);
        if (m->indices && m->index_count % 3)
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE, "mesh %lu: index_count %lu is not a multiple of 3",
                               (unsigned long)mi, (unsigned long)m->index_count);
        if (!m->indices && m->vertex_count % 3)
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE,
                               "mesh %lu: non-indexed mesh with vertex_count %lu, not a multiple of 3",
                               (unsigned long)mi, (unsigned long)m->vertex_count);
        nt = voxgi__mesh_triangles(m);
        for (t = 0; t < nt; t++) {
            int c;
            for (c = 0; c < 3; c++) {
                uint32_t vi = voxgi__mesh_index(m, t, c);
                if ((size_t)vi >= m->vertex_count)
                    return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE,
                                       "mesh %lu, triangle %lu: index %lu out of range (vertex_count %lu)",
                                       (unsigned long)mi, (unsigned long)t, (unsigned long)vi,
                                       (unsigned long)m->vertex_count);
                float p[3];
                voxgi__vertex(scene, m, vi, p);
                if (!voxgi__finite3(p))
                    return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE,
                                       "mesh %lu, triangle %lu: vertex %lu is not finite (NaN or infinity, or beyond float in the scene's frame)",
                                       (unsigned long)mi, (unsigned long)t, (unsigned long)vi);
            }
            {
                uint32_t mat = m->material_ids ? m->material_ids[t] : m->material;
                if (mat && (size_t)mat >= scene->material_count)
                    return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE,
                                       "mesh %lu, triangle %lu: material %lu out of range (material_count %lu)",
                                       (unsigned long)mi, (unsigned long)t, (unsigned long)mat,
                                       (unsigned long)scene->material_count);
            }
        }
        if (total_tris + nt < total_tris || total_tris + nt > (size_t)INT32_MAX ||
            total_verts + m->vertex_count > (size_t)UINT32_MAX)
            return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "the scene has more than 2^31 triangles or 2^32 vertices");
        total_tris += nt;
        total_verts += m->vertex_count;
    }
    if (total_tris == 0) return voxgi__fail(ctx, VOXGI_ERR_EMPTY_SCENE, "the scene has no triangles");
    if (triangles_out) *triangles_out = total_tris;
    if (vertices_out) *vertices_out = total_verts;
    return VOXGI_OK;
}

VOXGI_API voxgi_result voxgi_validate_scene(voxgi_context *ctx, const voxgi_scene *scene)
{
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    return voxgi__validate(ctx, scene, NULL, NULL);
}

/* The scene as one tight vertex array and one index array, so later passes need no strides. */
typedef struct voxgi__flat {
    size_t vertex_count, triangle_count;
    float *pos;        /* 3 per vertex */
    uint32_t *tri;     /* 3 per triangle, into pos */
    float *uv;         /* 2 per vertex, when asked for */
    uint32_t *mat;     /* 1 per triangle, when asked for */
    const voxgi_material *materials;
    size_t material_count;
} voxgi__flat;

static void voxgi__flat_free(voxgi_context *ctx, voxgi__flat *f)
{
    voxgi__free(ctx, f->pos);
    voxgi__free(ctx, f->tri);
    voxgi__free(ctx, f->uv);
    voxgi__free(ctx, f->mat);
    memset(f, 0, sizeof *f);
}

/* One vertex and index array for the whole scene; with want_uv, every mesh must have finite uvs. */
static voxgi_result voxgi__flatten(voxgi_context *ctx, const voxgi_scene *scene, int want_uv, int want_mat, voxgi__flat *f)
{
    size_t mi, t, v, nt = 0, nv = 0, tri_at = 0, vert_at = 0;
    voxgi_result r = voxgi__validate(ctx, scene, &nt, &nv);
    memset(f, 0, sizeof *f);
    if (r != VOXGI_OK) return r;
    f->pos = (float *)voxgi__alloc_array(ctx, nv, 3 * sizeof(float), 0);
    f->tri = (uint32_t *)voxgi__alloc_array(ctx, nt, 3 * sizeof(uint32_t), 0);
    if (want_uv) f->uv = (float *)voxgi__alloc_array(ctx, nv, 2 * sizeof(float), 0);
    if (want_mat) f->mat = (uint32_t *)voxgi__alloc_array(ctx, nt, sizeof(uint32_t), 0);
    if (!f->pos || !f->tri || (want_uv && !f->uv) || (want_mat && !f->mat)) {
        voxgi__flat_free(ctx, f);
        return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu triangles", (unsigned long)nt);
    }
    for (mi = 0; mi < scene->mesh_count; mi++) {
        const voxgi_mesh *m = &scene->meshes[mi];
        size_t mt = voxgi__mesh_triangles(m);
        for (v = 0; v < m->vertex_count; v++) voxgi__vertex(scene, m, v, f->pos + 3 * (vert_at + v));
        if (want_uv && m->vertex_count && !m->uvs) {
            voxgi__flat_free(ctx, f);
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE, "mesh %lu has no uvs, and its own uvs were asked for", (unsigned long)mi);
        }
        for (v = 0; want_uv && v < m->vertex_count; v++) {
            float uv[2];
            memcpy(uv, (const unsigned char *)m->uvs + v * (m->uv_stride ? m->uv_stride : 8), sizeof uv); /* as voxgi__vertex: unaligned */
            if (!isfinite(uv[0]) || !isfinite(uv[1])) {
                voxgi__flat_free(ctx, f);
                return voxgi__fail(ctx, VOXGI_ERR_INVALID_SCENE, "mesh %lu, vertex %lu: the uv is not finite", (unsigned long)mi, (unsigned long)v);
            }
            memcpy(f->uv + 2 * (vert_at + v), uv, 2 * sizeof(float));
        }
        for (t = 0; t < mt; t++) {
            int c;
            for (c = 0; c < 3; c++) f->tri[3 * (tri_at + t) + (size_t)c] = (uint32_t)(vert_at + voxgi__mesh_index(m, t, c));
            if (want_mat) f->mat[tri_at + t] = m->material_ids ? m->material_ids[t] : m->material;
        }
        tri_at += mt;
        vert_at += m->vertex_count;
    }
    f->vertex_count = nv;
    f->triangle_count = nt;
    f->materials = scene->materials;
    f->material_count = scene->material_count;
    return VOXGI_OK;
}

/* Triangle t's material (material 0 without a table: albedo 0.8, no emission, opaque). */
static const voxgi_material *voxgi__tri_material(const voxgi__flat *f, size_t t)
{
    static const voxgi_material fallback = {{0.8f, 0.8f, 0.8f}, {0, 0, 0}, 0};
    return f->material_count ? &f->materials[f->mat[t]] : &fallback;
}

/* Triangle t's unit geometric normal (counter-clockwise front), in double from the float
   vertices; zero for a degenerate triangle. */
static void voxgi__tri_unit_normal(const voxgi__flat *f, size_t t, double n[3])
{
    const float *p0 = f->pos + 3 * (size_t)f->tri[3 * t], *p1 = f->pos + 3 * (size_t)f->tri[3 * t + 1], *p2 = f->pos + 3 * (size_t)f->tri[3 * t + 2];
    double e[3], g[3], len;
    int a;
    for (a = 0; a < 3; a++) { e[a] = (double)p1[a] - p0[a]; g[a] = (double)p2[a] - p0[a]; }
    for (a = 0; a < 3; a++) n[a] = e[(a + 1) % 3] * g[(a + 2) % 3] - e[(a + 2) % 3] * g[(a + 1) % 3];
    len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (a = 0; a < 3; a++) n[a] = len > 0 ? n[a] / len : 0;
}

/* ----- 3.2 grids */

VOXGI_API uint64_t voxgi_grid_voxel_count(const voxgi_grid *g)
{
    if (!g || g->res[0] < 1 || g->res[1] < 1 || g->res[2] < 1) return 0;
    return (uint64_t)g->res[0] * (uint64_t)g->res[1] * (uint64_t)g->res[2];
}

static uint64_t voxgi__grid_words(const voxgi_grid *g) { return (voxgi_grid_voxel_count(g) + 31u) / 32u; }

VOXGI_API voxgi_result voxgi_validate_grid(voxgi_context *ctx, const voxgi_grid *g)
{
    int a;
    uint64_t bytes;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!g) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "grid is NULL");
    for (a = 0; a < 3; a++) {
        if (g->res[a] < 1 || g->res[a] > VOXGI_MAX_RES)
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_GRID, "grid resolution %d on axis %c is outside 1..%d",
                               g->res[a], "xyz"[a], VOXGI_MAX_RES);
        /* the range keeps every exact product of coordinates far from overflow and underflow */
        if (!isfinite(g->origin[a]) || fabs(g->origin[a]) > 1e30)
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_GRID, "grid origin %c = %g is not finite or beyond 1e30",
                               "xyz"[a], g->origin[a]);
    }
    if (!(g->voxel_size >= 1e-30 && g->voxel_size <= 1e30))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_GRID, "voxel size %g is not in [1e-30, 1e30]", g->voxel_size);
    bytes = voxgi__grid_words(g) * 4u;
    if (bytes > (uint64_t)((size_t)-1 / 2))
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "a %dx%dx%d bit grid does not fit in this address space",
                           g->res[0], g->res[1], g->res[2]);
    if (ctx->desc.memory_budget && bytes > (uint64_t)ctx->desc.memory_budget)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "a %dx%dx%d bit grid needs %llu bytes, over the budget of %llu",
                           g->res[0], g->res[1], g->res[2], (unsigned long long)bytes,
                           (unsigned long long)ctx->desc.memory_budget);
    return VOXGI_OK;
}

/* Every default of a voxgi_fit_desc: zero res is 64. */
static voxgi_fit_desc voxgi__fit_defaults(const voxgi_fit_desc *in)
{
    voxgi_fit_desc d = *in;
    if (!d.res) d.res = 64;
    return d;
}

VOXGI_API voxgi_result voxgi_fit_grid(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_fit_desc *fit_in,
                                      voxgi_grid *out)
{
    voxgi_fit_desc resolved, *fit = &resolved;
    double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX}, ext = 0, s, pad;
    size_t mi, t;
    int a, res;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!fit_in || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "fit or out is NULL");
    r = voxgi__validate(ctx, scene, NULL, NULL);
    if (r != VOXGI_OK) return r;
    resolved = voxgi__fit_defaults(fit_in);
    res = fit->res;
    pad = fit->padding;
    if (res < 1 || res > VOXGI_MAX_RES || !(pad >= 0) || 2 * pad >= res)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_GRID, "fit: res %d with padding %g leaves no room for the scene", res, pad);
    for (mi = 0; mi < scene->mesh_count; mi++) {
        const voxgi_mesh *m = &scene->meshes[mi];
        size_t nt = voxgi__mesh_triangles(m);
        for (t = 0; t < nt; t++) {
            int c;
            for (c = 0; c < 3; c++) {
                float p[3];
                voxgi__vertex(scene, m, voxgi__mesh_index(m, t, c), p);
                for (a = 0; a < 3; a++) {
                    lo[a] = VOXGI__MIN(lo[a], (double)p[a]);
                    hi[a] = VOXGI__MAX(hi[a], (double)p[a]);
                }
            }
        }
    }
    for (a = 0; a < 3; a++) ext = VOXGI__MAX(ext, hi[a] - lo[a]);
    /* a flat or point scene still gets a usable voxel size */
    s = ext > 0 ? ext / ((double)res - 2 * pad) : VOXGI__MAX(1e-6 * VOXGI__MAX(fabs(lo[0]), VOXGI__MAX(fabs(lo[1]), fabs(lo[2]))), 1e-6);
    /* one ulp of slack so the far side of the scene never lands exactly outside the last voxel */
    s *= 1.0 + 4 * DBL_EPSILON;
    out->voxel_size = s;
    for (a = 0; a < 3; a++) {
        double n = fit->per_axis ? ceil((hi[a] - lo[a]) / s + 2 * pad) : (double)res;
        if (n < 1) n = 1;
        if (n > res) n = res;
        out->res[a] = (int)n;
        out->origin[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * n * s;
    }
    return voxgi_validate_grid(ctx, out);
}

/* ----- 3.3 the BVH build

   A binary BVH by the surface area heuristic (binned), over float boxes that hold the float
   vertices exactly; the ray core (3.4) collapses it to four children a node. */
#define VOXGI__BVH_DEPTH 200 /* deeper ranges stay leaves, so traversal stacks are bounded */
typedef struct voxgi__bvh_node {
    float lo[3], hi[3];
    uint32_t first, count;        /* leaf: triangles [first, first + count) of the order; inner
                                     (count 0): left child next in the array, right child at first */
} voxgi__bvh_node;

typedef struct voxgi__bvh_build {
    const float *cmin, *cmax;     /* per flat triangle: its box */
    uint32_t *order;
    voxgi__bvh_node *nodes;
    size_t count;
    size_t leaf;                  /* ranges this small stay leaves (the ray core's: a pack of four) */
} voxgi__bvh_build;

static void voxgi__box_area(const float lo[3], const float hi[3], double *area)
{
    double d[3];
    int a;
    for (a = 0; a < 3; a++) d[a] = hi[a] > lo[a] ? (double)hi[a] - lo[a] : 0;
    *area = 2 * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0]);
}

/* Node nd over the ordered triangles [first, end): its box, and where a binned SAH split
   partitions them (mid), or 0 when it stays a leaf (nd->first, nd->count set). */
static size_t voxgi__bvh_partition(voxgi__bvh_build *b, voxgi__bvh_node *nd, size_t first, size_t end, int depth)
{
    enum { BINS = 12 };
    float clo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, chi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    size_t i, n = end - first, mid;
    int a, axis = 0, best_bin = -1;
    double best = DBL_MAX, leaf_area;
    for (a = 0; a < 3; a++) { nd->lo[a] = FLT_MAX; nd->hi[a] = -FLT_MAX; }
    for (i = first; i < end; i++) {
        uint32_t t = b->order[i];
        for (a = 0; a < 3; a++) {
            float c = 0.5f * (b->cmin[3 * t + a] + b->cmax[3 * t + a]);
            nd->lo[a] = VOXGI__MIN(nd->lo[a], b->cmin[3 * t + a]);
            nd->hi[a] = VOXGI__MAX(nd->hi[a], b->cmax[3 * t + a]);
            clo[a] = VOXGI__MIN(clo[a], c);
            chi[a] = VOXGI__MAX(chi[a], c);
        }
    }
    for (a = 1; a < 3; a++)
        if (chi[a] - clo[a] > chi[axis] - clo[axis]) axis = a;
    nd->first = (uint32_t)first;
    nd->count = (uint32_t)n;
    /* a leaf also where the centroids' span is not finite: coordinates near FLT_MAX sum to infinity */
    if (n <= b->leaf || !(chi[axis] > clo[axis]) || !isfinite((double)chi[axis] - clo[axis]) || depth >= VOXGI__BVH_DEPTH) return 0;
    {   /* binned SAH along the widest centroid axis */
        size_t cnt[BINS];
        float blo[BINS][3], bhi[BINS][3];
        double scale = BINS / ((double)chi[axis] - clo[axis]);
        int k;
        for (k = 0; k < BINS; k++) { cnt[k] = 0; for (a = 0; a < 3; a++) { blo[k][a] = FLT_MAX; bhi[k][a] = -FLT_MAX; } }
        for (i = first; i < end; i++) {
            uint32_t t = b->order[i];
            double c = 0.5 * ((double)b->cmin[3 * t + axis] + b->cmax[3 * t + axis]);
            k = VOXGI__MIN((int)((c - clo[axis]) * scale), BINS - 1);
            cnt[k]++;
            for (a = 0; a < 3; a++) { blo[k][a] = VOXGI__MIN(blo[k][a], b->cmin[3 * t + a]); bhi[k][a] = VOXGI__MAX(bhi[k][a], b->cmax[3 * t + a]); }
        }
        for (k = 1; k < BINS; k++) { /* split between bins k - 1 and k */
            float llo[3] = {FLT_MAX, FLT_MAX, FLT_MAX}, lhi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX}, rlo[3] = {FLT_MAX, FLT_MAX, FLT_MAX},
                  rhi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
            size_t nl = 0, nr = 0;
            double al, ar, cost;
            int j;
            for (j = 0; j < BINS; j++) {
                float *lo = j < k ? llo : rlo, *hi = j < k ? lhi : rhi;
                if (!cnt[j]) continue;
                if (j < k) nl += cnt[j]; else nr += cnt[j];
                for (a = 0; a < 3; a++) { lo[a] = VOXGI__MIN(lo[a], blo[j][a]); hi[a] = VOXGI__MAX(hi[a], bhi[j][a]); }
            }
            if (!nl || !nr) continue;
            voxgi__box_area(llo, lhi, &al);
            voxgi__box_area(rlo, rhi, &ar);
            cost = al * (double)nl + ar * (double)nr;
            if (cost < best) { best = cost; best_bin = k; }
        }
        voxgi__box_area(nd->lo, nd->hi, &leaf_area);
        if (best_bin < 0 || (n <= 8 && best >= leaf_area * (double)(n - 1))) return 0; /* splitting does not pay */
        for (i = mid = first; i < end; i++) { /* partition */
            uint32_t t = b->order[i];
            double c = 0.5 * ((double)b->cmin[3 * t + axis] + b->cmax[3 * t + axis]);
            if (VOXGI__MIN((int)((c - clo[axis]) * scale), BINS - 1) < best_bin) { b->order[i] = b->order[mid]; b->order[mid++] = t; }
        }
    }
    nd->count = 0;
    return mid;
}

/* The subtree of `node` over [first, end): the left child is the next node, the right one
   follows the left's subtree (b->count: the next free node). */
static void voxgi__bvh_split(voxgi__bvh_build *b, size_t node, size_t first, size_t end, int depth)
{
    size_t mid = voxgi__bvh_partition(b, &b->nodes[node], first, end, depth), left, right;
    if (!mid) return;
    left = b->count++;
    voxgi__bvh_split(b, left, first, mid, depth + 1);
    right = b->count++;
    b->nodes[node].first = (uint32_t)right;
    voxgi__bvh_split(b, right, mid, end, depth + 1);
}

/* The same tree on the workers: the top levels split here until ranges hold at most `grain`
   triangles (a count that depends on the scene alone), each such range's subtree built on its
   own into nodes of its own (the ranges' parts of b->order are disjoint), then all laid out as the
   serial build lays them out. So the tree is the serial one whatever the thread count. */
#define VOXGI__BVH_TOP 64 /* ranges built on the workers, at most */
typedef struct voxgi__bvh_top {
    voxgi__bvh_node node;
    int left, right, task;        /* task >= 0: the subtree is that task's */
} voxgi__bvh_top;
typedef struct voxgi__bvh_task {
    voxgi__bvh_build b;
    size_t first, end;
    int depth;
} voxgi__bvh_task;
typedef struct voxgi__bvh_plan {
    voxgi__bvh_build *b;
    voxgi__bvh_top top[2 * VOXGI__BVH_TOP];
    voxgi__bvh_task task[VOXGI__BVH_TOP];
    int ntop, ntask;
    size_t grain;
} voxgi__bvh_plan;

/* Top node me over [first, end): split here while the range is big and there is room for both
   children (2 VOXGI__BVH_TOP - 1 top nodes hold at most VOXGI__BVH_TOP ranges), else a task. */
static void voxgi__bvh_plan_node(voxgi__bvh_plan *P, int me, size_t first, size_t end, int depth)
{
    size_t mid;
    P->top[me].task = -1;
    if (end - first > P->grain && P->ntop + 2 <= 2 * VOXGI__BVH_TOP - 1) {
        if (!(mid = voxgi__bvh_partition(P->b, &P->top[me].node, first, end, depth))) return; /* a leaf already */
        P->top[me].left = P->ntop++;
        P->top[me].right = P->ntop++;
        voxgi__bvh_plan_node(P, P->top[me].left, first, mid, depth + 1);
        voxgi__bvh_plan_node(P, P->top[me].right, mid, end, depth + 1);
        return;
    }
    P->top[me].task = P->ntask;
    P->task[P->ntask].first = first;
    P->task[P->ntask].end = end;
    P->task[P->ntask++].depth = depth;
}

static void voxgi__bvh_task_run(void *user, size_t first, size_t end)
{
    voxgi__bvh_plan *P = (voxgi__bvh_plan *)user;
    size_t i;
    for (i = first; i < end; i++) {
        voxgi__bvh_task *T = &P->task[i];
        T->b.count = 1;
        voxgi__bvh_split(&T->b, 0, T->first, T->end, T->depth);
    }
}

/* Lays out top node t and what lies below it from node `at` on; returns the next free node. */
static size_t voxgi__bvh_lay_out(const voxgi__bvh_plan *P, int t, voxgi__bvh_node *out, size_t at)
{
    const voxgi__bvh_top *tp = &P->top[t];
    size_t i, next;
    if (tp->task >= 0) { /* a task's nodes, its inner nodes' right children moved with them */
        const voxgi__bvh_build *tb = &P->task[tp->task].b;
        for (i = 0; i < tb->count; i++) {
            out[at + i] = tb->nodes[i];
            if (!out[at + i].count) out[at + i].first += (uint32_t)at;
        }
        return at + tb->count;
    }
    out[at] = tp->node;
    if (tp->node.count) return at + 1;
    next = voxgi__bvh_lay_out(P, tp->left, out, at + 1);
    out[at].first = (uint32_t)next;
    return voxgi__bvh_lay_out(P, tp->right, out, next);
}

/* b->nodes[0..] the tree over b->order[0, n), built on the context's workers; b->count set. */
static voxgi_result voxgi__bvh_build_tree(voxgi_context *ctx, voxgi__bvh_build *b, size_t n)
{
    voxgi__bvh_plan *P = (voxgi__bvh_plan *)voxgi__alloc_array(ctx, 1, sizeof *P, 1);
    voxgi_result r = VOXGI_OK;
    int i;
    if (!P) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the BVH build");
    P->b = b;
    P->grain = VOXGI__MAX((size_t)4096, n / VOXGI__BVH_TOP);
    P->ntop = 1;
    voxgi__bvh_plan_node(P, 0, 0, n, 0);
    for (i = 0; i < P->ntask && r == VOXGI_OK; i++) {
        voxgi__bvh_task *T = &P->task[i];
        T->b = *b;
        if (!(T->b.nodes = (voxgi__bvh_node *)voxgi__alloc_array(ctx, 2 * (T->end - T->first) + 1, sizeof *T->b.nodes, 1)))
            r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the BVH of %lu triangles", (unsigned long)n);
    }
    if (r == VOXGI_OK) {
        voxgi__parallel(ctx, (size_t)P->ntask, 1, voxgi__bvh_task_run, P);
        b->count = voxgi__bvh_lay_out(P, 0, b->nodes, 0);
    }
    for (i = 0; i < P->ntask; i++) voxgi__free(ctx, P->task[i].b.nodes);
    voxgi__free(ctx, P);
    return r;
}

/* ----- 3.4 the ray core: a 4- or 8-wide BVH in float (voxgi_ray_scene)

   The binary SAH build above, collapsed to VOXGI__BVH_WIDTH children per node (a node opens its
   largest inner child until it has that many), over the triangles in float relative to the
   scene's box centre: a scene far from the origin keeps the precision of its extent, and the
   boxes, made from the very floats the triangle test reads, hold every triangle exactly. A
   node's boxes are tested at once (SSE or AVX2 where the compiler targets it, else lane by
   lane), each slab's far end widened by 2^-21 against rounding (Ize 2013), children visited
   nearest first. The triangle test is Woop, Benthin and Wald's (2013): vertices sheared into the
   ray's frame in float, edge functions in double, where the products of floats are exact and the
   sign of each difference is right, so a ray through a shared edge or vertex never slips between
   triangles, whatever the compiler does with fused multiply-adds. */
#define VOXGI__W VOXGI__BVH_WIDTH
#define VOXGI__W_ALL ((1 << VOXGI__W) - 1)
typedef struct voxgi__node {
    float lo[3][VOXGI__W], hi[3][VOXGI__W];    /* the children's boxes (an unused lane: empty, lo = +inf, hi = -inf) */
    uint32_t child[VOXGI__W], count[VOXGI__W]; /* count 0: inner node `child`; else the packs [child, child + count) */
} voxgi__node;

/* A node's lanes as one vector: AVX2's eight or SSE's four. */
#if defined(VOXGI__AVX2)
typedef __m256 voxgi__wide;
#define VOXGI__WIDE_SET1 _mm256_set1_ps
#define VOXGI__WIDE_LOAD _mm256_load_ps
#define VOXGI__WIDE_STORE _mm256_storeu_ps
#define VOXGI__WIDE_SUB _mm256_sub_ps
#define VOXGI__WIDE_MUL _mm256_mul_ps
#define VOXGI__WIDE_MIN _mm256_min_ps
#define VOXGI__WIDE_MAX _mm256_max_ps
#define VOXGI__WIDE_LE(a, b) _mm256_movemask_ps(_mm256_cmp_ps((a), (b), _CMP_LE_OS))
#define VOXGI__WIDE_GT(a, b) _mm256_movemask_ps(_mm256_cmp_ps((a), (b), _CMP_GT_OS))
#define VOXGI__WIDE_ZERO_U32(p) _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_loadu_si256((const __m256i *)(const void *)(p)), _mm256_setzero_si256())))
#elif defined(VOXGI__SSE)
typedef __m128 voxgi__wide;
#define VOXGI__WIDE_SET1 _mm_set1_ps
#define VOXGI__WIDE_LOAD _mm_load_ps
#define VOXGI__WIDE_STORE _mm_storeu_ps
#define VOXGI__WIDE_SUB _mm_sub_ps
#define VOXGI__WIDE_MUL _mm_mul_ps
#define VOXGI__WIDE_MIN _mm_min_ps
#define VOXGI__WIDE_MAX _mm_max_ps
#define VOXGI__WIDE_LE(a, b) _mm_movemask_ps(_mm_cmple_ps((a), (b)))
#define VOXGI__WIDE_GT(a, b) _mm_movemask_ps(_mm_cmpgt_ps((a), (b)))
#define VOXGI__WIDE_ZERO_U32(p) _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(_mm_loadu_si128((const __m128i *)(const void *)(p)), _mm_setzero_si128())))
#endif

/* A leaf's triangles four at a time, by lanes: row 3 k + a holds vertex k's coordinate a of each
   (relative to the centre); a lane without a triangle is a point, which nothing hits. */
typedef struct voxgi__tri4 {
    float v[9][4];
    uint32_t tri[4];              /* the scene's triangle, UINT32_MAX: none */
} voxgi__tri4;

struct voxgi_ray_scene {
    voxgi__node *nodes;           /* on 64-byte boundaries: a node is two or four cache lines */
    void *node_block;             /* what was allocated for them */
    voxgi__tri4 *packs;
    size_t node_count, pack_count, triangles;
    double centre[3];
    double reach;                 /* the largest coordinate relative to the centre: sets the float rounding */
};

/* Node `me` from binary node `node` (inner) and the subtrees below; returns the next free node. */
static size_t voxgi__collapse(voxgi__node *out, size_t me, size_t next, const voxgi__bvh_node *bin, uint32_t node)
{
    uint32_t kids[VOXGI__W];
    int n = 2, i, a;
    kids[0] = node + 1;
    kids[1] = bin[node].first;
    while (n < VOXGI__W) { /* open the inner child of the largest box */
        int best = -1;
        double best_area = -1, area;
        for (i = 0; i < n; i++)
            if (!bin[kids[i]].count) {
                voxgi__box_area(bin[kids[i]].lo, bin[kids[i]].hi, &area);
                if (area > best_area) { best_area = area; best = i; }
            }
        if (best < 0) break;
        a = (int)kids[best];
        kids[best] = (uint32_t)a + 1;
        kids[n++] = bin[a].first;
    }
    for (i = 0; i < VOXGI__W; i++) {
        const voxgi__bvh_node *c = i < n ? &bin[kids[i]] : NULL;
        for (a = 0; a < 3; a++) {
            out[me].lo[a][i] = c ? c->lo[a] : INFINITY;
            out[me].hi[a][i] = c ? c->hi[a] : -INFINITY;
        }
        out[me].child[i] = c && c->count ? c->first : 0;
        out[me].count[i] = c ? c->count : 0;
    }
    for (i = 0; i < n; i++)
        if (!bin[kids[i]].count) {
            out[me].child[i] = (uint32_t)next;
            next = voxgi__collapse(out, next, next + 1, bin, kids[i]);
        }
    return next;
}

static void voxgi__ray_scene_free(voxgi_context *ctx, voxgi_ray_scene *rs)
{
    if (!rs) return;
    voxgi__free(ctx, rs->node_block);
    voxgi__free(ctx, rs->packs);
    voxgi__free(ctx, rs);
}

/* The ray scene of a flattened scene (its triangles in its order). */
static voxgi_result voxgi__ray_scene_build(voxgi_context *ctx, const voxgi__flat *flat, voxgi_ray_scene **out)
{
    voxgi__bvh_build b;
    voxgi__bvh_node *bin = NULL;
    voxgi_ray_scene *rs;
    uint32_t *order = NULL;
    float *local = NULL, *boxes = NULL;
    double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
    size_t t, nt, i;
    int a, k;
    voxgi_result r = VOXGI_OK;
    *out = NULL;
    nt = flat->triangle_count;
    if (nt > (size_t)1 << 30) return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%lu triangles", (unsigned long)nt);
    rs = (voxgi_ray_scene *)voxgi__alloc_array(ctx, 1, sizeof *rs, 1);
    local = (float *)voxgi__alloc_array(ctx, flat->vertex_count, 3 * sizeof(float), 0);
    boxes = (float *)voxgi__alloc_array(ctx, nt, 6 * sizeof(float), 0);
    bin = (voxgi__bvh_node *)voxgi__alloc_array(ctx, 2 * nt + 1, sizeof *bin, 1);
    if (rs) {
        rs->triangles = nt;
        rs->packs = (voxgi__tri4 *)voxgi__alloc_array(ctx, nt, sizeof *rs->packs, 0); /* at most one a triangle */
        rs->node_block = voxgi__alloc_array(ctx, 2 * nt + 2, sizeof *rs->nodes, 1);
        rs->nodes = (voxgi__node *)(void *)(((uintptr_t)rs->node_block + 63) & ~(uintptr_t)63);
    }
    order = (uint32_t *)voxgi__alloc_array(ctx, nt, 4, 0);
    if (!rs || !local || !boxes || !bin || !order || !rs->packs || !rs->node_block) {
        r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the BVH of %lu triangles", (unsigned long)nt);
        goto done;
    }
    for (i = 0; i < flat->vertex_count; i++)
        for (a = 0; a < 3; a++) { lo[a] = VOXGI__MIN(lo[a], (double)flat->pos[3 * i + a]); hi[a] = VOXGI__MAX(hi[a], (double)flat->pos[3 * i + a]); }
    for (a = 0; a < 3; a++) rs->centre[a] = 0.5 * (lo[a] + hi[a]);
    for (i = 0; i < 3 * flat->vertex_count; i++) {
        local[i] = (float)((double)flat->pos[i] - rs->centre[i % 3]);
        rs->reach = VOXGI__MAX(rs->reach, fabs((double)local[i]));
    }
    for (t = 0; t < nt; t++) { /* boxes of the local floats */
        order[t] = (uint32_t)t;
        for (a = 0; a < 3; a++) {
            boxes[3 * t + a] = INFINITY;
            boxes[3 * nt + 3 * t + a] = -INFINITY;
            for (k = 0; k < 3; k++) {
                float c = local[3 * (size_t)flat->tri[3 * t + (size_t)k] + (size_t)a];
                boxes[3 * t + a] = VOXGI__MIN(boxes[3 * t + a], c);
                boxes[3 * nt + 3 * t + a] = VOXGI__MAX(boxes[3 * nt + 3 * t + a], c);
            }
        }
    }
    b.cmin = boxes;
    b.cmax = boxes + 3 * nt;
    b.order = order;
    b.nodes = bin;
    b.count = 1;
    b.leaf = 4;
    if ((r = voxgi__bvh_build_tree(ctx, &b, nt)) != VOXGI_OK) goto done; /* a scene has triangles (voxgi__flatten) */
    if (bin[0].count) { /* one leaf: the root's one lane */
        for (a = 0; a < 3; a++)
            for (k = 0; k < VOXGI__W; k++) { rs->nodes[0].lo[a][k] = k ? INFINITY : bin[0].lo[a]; rs->nodes[0].hi[a][k] = k ? -INFINITY : bin[0].hi[a]; }
        rs->nodes[0].count[0] = (uint32_t)nt;
        rs->node_count = 1;
    } else
        rs->node_count = voxgi__collapse(rs->nodes, 0, 1, bin, 0);
    for (i = 0; i < rs->node_count; i++) /* each leaf's triangles into packs of four */
        for (k = 0; k < VOXGI__W; k++) {
            voxgi__node *nd = &rs->nodes[i];
            uint32_t first = nd->child[k], n = nd->count[k], j;
            if (!n) continue;
            nd->child[k] = (uint32_t)rs->pack_count;
            nd->count[k] = (n + 3) / 4;
            for (j = 0; j < 4 * nd->count[k]; j++) {
                voxgi__tri4 *pk = &rs->packs[rs->pack_count + j / 4];
                uint32_t src = order[first + VOXGI__MIN(j, n - 1)]; /* a lane without a triangle: the last one's first vertex */
                int r;
                pk->tri[j % 4] = j < n ? src : UINT32_MAX;
                for (r = 0; r < 9; r++) pk->v[r][j % 4] = local[3 * (size_t)flat->tri[3 * (size_t)src + (size_t)(j < n ? r / 3 : 0)] + (size_t)(r % 3)];
            }
            rs->pack_count += nd->count[k];
        }
    *out = rs;
    rs = NULL;
done:
    voxgi__free(ctx, order);
    voxgi__free(ctx, local);
    voxgi__free(ctx, boxes);
    voxgi__free(ctx, bin);
    voxgi__ray_scene_free(ctx, rs);
    return r;
}

VOXGI_API voxgi_result voxgi_ray_scene_create(voxgi_context *ctx, const voxgi_scene *scene, voxgi_ray_scene **out)
{
    voxgi__flat flat;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!scene || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "scene or out is NULL");
    *out = NULL;
    if ((r = voxgi__flatten(ctx, scene, 0, 0, &flat)) != VOXGI_OK) return r;
    r = voxgi__ray_scene_build(ctx, &flat, out);
    voxgi__flat_free(ctx, &flat);
    return r;
}

VOXGI_API void voxgi_ray_scene_destroy(voxgi_context *ctx, voxgi_ray_scene *rs)
{
    if (ctx) voxgi__ray_scene_free(ctx, rs);
}

/* A ray in the scene's frame, ready for the boxes, and for the triangles once sheared (on its
   first leaf: a ray that meets no leaf never needs the shear). */
typedef struct voxgi__ray4 {
#ifdef VOXGI__SSE
    voxgi__wide o4[3], inv4[3], inv_far4[3]; /* o, inv and inv_far in every lane */
#endif
    float o[3], d[3], inv[3], inv_far[3], tmin;
    int neg[3];                   /* the direction's sign per axis: which of lo and hi is near, */
    size_t near_at[3], far_at[3]; /* and so their byte offsets in a node */
    int sheared;                  /* the shear below is set */
    int kx, ky, kz;               /* the shear: kz the largest component */
    float sx, sy, sz;
    uint32_t skip;                /* the triangle the ray leaves, never hit (UINT32_MAX: none) */
} voxgi__ray4;

/* Which of a node's lo and hi is near along each axis, as byte offsets. */
static void voxgi__ray4_planes(const int neg[3], size_t near_at[3], size_t far_at[3])
{
    int a;
    for (a = 0; a < 3; a++) {
        near_at[a] = (neg[a] ? offsetof(voxgi__node, hi) : offsetof(voxgi__node, lo)) + 4 * VOXGI__W * (size_t)a;
        far_at[a] = (neg[a] ? offsetof(voxgi__node, lo) : offsetof(voxgi__node, hi)) + 4 * VOXGI__W * (size_t)a;
    }
}

/* The ray from o along direction, world units, for the boxes; 0 for a zero direction. */
static int voxgi__ray4_setup(const voxgi_ray_scene *rs, const double o[3], const double direction[3], float tmin, uint32_t skip, voxgi__ray4 *r)
{
    int a;
    for (a = 0; a < 3; a++) {
        r->d[a] = (float)direction[a];
        r->o[a] = (float)(o[a] - rs->centre[a]);
        r->neg[a] = r->d[a] < 0;
        /* a zero component: a tiny one of its sign, so that no slab sees 0 x inf */
        r->inv[a] = 1.0f / (fabsf(r->d[a]) > 1e-30f ? r->d[a] : (r->neg[a] ? -1e-30f : 1e-30f));
        r->inv_far[a] = r->inv[a] * (1.0f + 4.76837158e-7f);
#ifdef VOXGI__SSE
        r->o4[a] = VOXGI__WIDE_SET1(r->o[a]);
        r->inv4[a] = VOXGI__WIDE_SET1(r->inv[a]);
        r->inv_far4[a] = VOXGI__WIDE_SET1(r->inv_far[a]);
#endif
    }
    if (r->d[0] == 0 && r->d[1] == 0 && r->d[2] == 0) return 0;
    voxgi__ray4_planes(r->neg, r->near_at, r->far_at);
    r->sheared = 0;
    r->tmin = tmin;
    r->skip = skip;
    return 1;
}

/* The shear of ray r's triangle test (Woop et al.): its largest direction component becomes z. */
/* The shear of direction d (nonzero) for the watertight triangle test (Woop et al.): its largest
   component becomes z (axes kx, ky, kz), sx, sy, sz the shear. The ray core and the line space share it. */
static void voxgi__shear(const float d[3], int k[3], float s[3])
{
    int a, kz = 0;
    for (a = 1; a < 3; a++)
        if (fabsf(d[a]) > fabsf(d[kz])) kz = a;
    k[2] = kz;
    k[0] = (kz + 1) % 3;
    k[1] = (k[0] + 1) % 3;
    if (d[kz] < 0) { int tmp = k[0]; k[0] = k[1]; k[1] = tmp; } /* keep the winding */
    s[0] = d[k[0]] / d[kz];
    s[1] = d[k[1]] / d[kz];
    s[2] = 1.0f / d[kz];
}

static void voxgi__ray4_shear(voxgi__ray4 *r)
{
    int k[3];
    float sh[3];
    voxgi__shear(r->d, k, sh);
    r->kx = k[0]; r->ky = k[1]; r->kz = k[2];
    r->sx = sh[0]; r->sy = sh[1]; r->sz = sh[2];
    r->sheared = 1;
}

/* The boxes of nd against the ray between tmin and tmax: the lanes hit (bits), and where each
   is entered. */
static VOXGI__HOT_INLINE int voxgi__node_hits(const voxgi__node *nd, const voxgi__ray4 *r, float tmax, float tnear[VOXGI__W])
{
#ifdef VOXGI__SSE
#define VOXGI__SLAB(a)                                                                                                                                    \
    tn = VOXGI__WIDE_MAX(tn, VOXGI__WIDE_MUL(VOXGI__WIDE_SUB(VOXGI__WIDE_LOAD((const float *)(const void *)((const char *)nd + r->near_at[a])), r->o4[a]), r->inv4[a])); \
    tf = VOXGI__WIDE_MIN(tf, VOXGI__WIDE_MUL(VOXGI__WIDE_SUB(VOXGI__WIDE_LOAD((const float *)(const void *)((const char *)nd + r->far_at[a])), r->o4[a]), r->inv_far4[a]))
    voxgi__wide tn = VOXGI__WIDE_SET1(r->tmin), tf = VOXGI__WIDE_SET1(tmax);
    VOXGI__SLAB(0);
    VOXGI__SLAB(1);
    VOXGI__SLAB(2);
#undef VOXGI__SLAB
    VOXGI__WIDE_STORE(tnear, tn);
    return VOXGI__WIDE_LE(tn, tf);
#else
    int a, i, mask = 0;
    for (i = 0; i < VOXGI__W; i++) {
        float tn = r->tmin, tf = tmax;
        for (a = 0; a < 3; a++) {
            float near_plane = r->neg[a] ? nd->hi[a][i] : nd->lo[a][i], far_plane = r->neg[a] ? nd->lo[a][i] : nd->hi[a][i];
            float t0 = (near_plane - r->o[a]) * r->inv[a], t1 = (far_plane - r->o[a]) * r->inv_far[a];
            tn = t0 > tn ? t0 : tn;
            tf = t1 < tf ? t1 : tf;
        }
        tnear[i] = tn;
        mask |= (tn <= tf) << i;
    }
    return mask;
#endif
}

/* The children of nd that are leaves (bits). */
static VOXGI__HOT_INLINE int voxgi__node_leaves(const voxgi__node *nd)
{
#ifdef VOXGI__SSE
    return ~VOXGI__WIDE_ZERO_U32(nd->count) & VOXGI__W_ALL;
#else
    int i, leaves = 0;
    for (i = 0; i < VOXGI__W; i++) leaves |= (nd->count[i] != 0) << i;
    return leaves;
#endif
}

/* Lane l of pack pk against the ray for a hit in (tmin, tmax], the edge functions in double: 1
   and its t, u, v. */
static int voxgi__tri_lane_exact(const voxgi__tri4 *pk, int l, const voxgi__ray4 *r, float tmax, float *t_out, float *u_out, float *v_out)
{
    float az = pk->v[r->kz][l] - r->o[r->kz], bz = pk->v[3 + r->kz][l] - r->o[r->kz], cz = pk->v[6 + r->kz][l] - r->o[r->kz];
    float ax = pk->v[r->kx][l] - r->o[r->kx] - r->sx * az, ay = pk->v[r->ky][l] - r->o[r->ky] - r->sy * az;
    float bx = pk->v[3 + r->kx][l] - r->o[r->kx] - r->sx * bz, by = pk->v[3 + r->ky][l] - r->o[r->ky] - r->sy * bz;
    float cx = pk->v[6 + r->kx][l] - r->o[r->kx] - r->sx * cz, cy = pk->v[6 + r->ky][l] - r->o[r->ky] - r->sy * cz;
    double u = (double)cx * by - (double)cy * bx, w = (double)ax * cy - (double)ay * cx, x = (double)bx * ay - (double)by * ax, det, tt;
    if ((u < 0 || w < 0 || x < 0) && (u > 0 || w > 0 || x > 0)) return 0;
    det = u + w + x;
    if (det == 0) return 0;
    tt = (u * az + w * bz + x * cz) * (double)r->sz / det;
    if (!(tt > r->tmin && tt <= tmax)) return 0;
    *t_out = (float)tt;
    *u_out = (float)(w / det);
    *v_out = (float)(x / det);
    return 1;
}

/* An edge function in float, e = p - q, whose sign may not be the exact one of the sheared floats:
   within 2^-21 (|p| + |q|) of 0 (its rounding is below 2^-23 of that). */
#define VOXGI__EDGE_NEAR_ZERO 4.76837158e-7f

/* The closest hit in pack pk before tmax, or at tmax on a triangle below tie (the hit so far: of
   two hits at one t the lower triangle wins, so the closest hit is the same in any order of
   traversal): its lane (-1: none) and t, u, v. The four lanes' edge functions in float at once
   (SSE, or lane by lane in the same arithmetic); a lane whose edge function lies within rounding
   of 0 is tested again with them in double, so every sign is the exact one and no ray slips
   between triangles that share an edge or a vertex. */
static VOXGI__HOT_INLINE int voxgi__ray4_pack(const voxgi__tri4 *pk, const voxgi__ray4 *r, float tmax, uint32_t tie, float *t_out, float *u_out,
                                              float *v_out)
{
    float tf[4], wf[4], xf[4], det[4];
    int near_zero = 0, hits = 0, l, best = -1;
#ifdef VOXGI__SSE
    {
        const __m128 sign = _mm_set1_ps(-0.0f), eps = _mm_set1_ps(VOXGI__EDGE_NEAR_ZERO);
        __m128 okx = _mm_set1_ps(r->o[r->kx]), oky = _mm_set1_ps(r->o[r->ky]), okz = _mm_set1_ps(r->o[r->kz]), sx = _mm_set1_ps(r->sx), sy = _mm_set1_ps(r->sy);
        __m128 az = _mm_sub_ps(_mm_loadu_ps(pk->v[r->kz]), okz), bz = _mm_sub_ps(_mm_loadu_ps(pk->v[3 + r->kz]), okz), cz = _mm_sub_ps(_mm_loadu_ps(pk->v[6 + r->kz]), okz);
        __m128 ax = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(pk->v[r->kx]), okx), _mm_mul_ps(sx, az));
        __m128 ay = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(pk->v[r->ky]), oky), _mm_mul_ps(sy, az));
        __m128 bx = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(pk->v[3 + r->kx]), okx), _mm_mul_ps(sx, bz));
        __m128 by = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(pk->v[3 + r->ky]), oky), _mm_mul_ps(sy, bz));
        __m128 cx = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(pk->v[6 + r->kx]), okx), _mm_mul_ps(sx, cz));
        __m128 cy = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(pk->v[6 + r->ky]), oky), _mm_mul_ps(sy, cz));
        __m128 p0 = _mm_mul_ps(cx, by), q0 = _mm_mul_ps(cy, bx), p1 = _mm_mul_ps(ax, cy), q1 = _mm_mul_ps(ay, cx), p2 = _mm_mul_ps(bx, ay), q2 = _mm_mul_ps(by, ax);
        __m128 u = _mm_sub_ps(p0, q0), w = _mm_sub_ps(p1, q1), x = _mm_sub_ps(p2, q2), d = _mm_add_ps(_mm_add_ps(u, w), x);
        __m128 nz = _mm_or_ps(_mm_cmple_ps(_mm_andnot_ps(sign, u), _mm_mul_ps(eps, _mm_add_ps(_mm_andnot_ps(sign, p0), _mm_andnot_ps(sign, q0)))),
                              _mm_cmple_ps(_mm_andnot_ps(sign, w), _mm_mul_ps(eps, _mm_add_ps(_mm_andnot_ps(sign, p1), _mm_andnot_ps(sign, q1)))));
        nz = _mm_or_ps(nz, _mm_cmple_ps(_mm_andnot_ps(sign, x), _mm_mul_ps(eps, _mm_add_ps(_mm_andnot_ps(sign, p2), _mm_andnot_ps(sign, q2)))));
        __m128 zero = _mm_setzero_ps(), t;
        __m128 inside = _mm_or_ps(_mm_and_ps(_mm_and_ps(_mm_cmpge_ps(u, zero), _mm_cmpge_ps(w, zero)), _mm_cmpge_ps(x, zero)),
                                  _mm_and_ps(_mm_and_ps(_mm_cmple_ps(u, zero), _mm_cmple_ps(w, zero)), _mm_cmple_ps(x, zero)));
        int real = ~_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(_mm_loadu_si128((const __m128i *)(const void *)pk->tri), _mm_set1_epi32(-1))));
        near_zero = _mm_movemask_ps(nz) & real; /* a lane without a triangle is a point: every edge function 0 */
        hits = _mm_movemask_ps(_mm_and_ps(inside, _mm_cmpneq_ps(d, zero))) & ~near_zero & real;
        if (!(hits | near_zero)) return -1; /* the usual case: nothing here */
        t = _mm_div_ps(_mm_mul_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(u, az), _mm_mul_ps(w, bz)), _mm_mul_ps(x, cz)), _mm_set1_ps(r->sz)), d);
        hits &= _mm_movemask_ps(_mm_and_ps(_mm_cmpgt_ps(t, _mm_set1_ps(r->tmin)), _mm_cmple_ps(t, _mm_set1_ps(tmax))));
        if (!(hits | near_zero)) return -1;
        _mm_storeu_ps(tf, t);
        _mm_storeu_ps(wf, w);
        _mm_storeu_ps(xf, x);
        _mm_storeu_ps(det, d);
    }
#else
    for (l = 0; l < 4 && pk->tri[l] != UINT32_MAX; l++) { /* the lanes without a triangle come last */
        float az = pk->v[r->kz][l] - r->o[r->kz], bz = pk->v[3 + r->kz][l] - r->o[r->kz], cz = pk->v[6 + r->kz][l] - r->o[r->kz];
        float ax = pk->v[r->kx][l] - r->o[r->kx] - r->sx * az, ay = pk->v[r->ky][l] - r->o[r->ky] - r->sy * az;
        float bx = pk->v[3 + r->kx][l] - r->o[r->kx] - r->sx * bz, by = pk->v[3 + r->ky][l] - r->o[r->ky] - r->sy * bz;
        float cx = pk->v[6 + r->kx][l] - r->o[r->kx] - r->sx * cz, cy = pk->v[6 + r->ky][l] - r->o[r->ky] - r->sy * cz;
        float p0 = cx * by, q0 = cy * bx, p1 = ax * cy, q1 = ay * cx, p2 = bx * ay, q2 = by * ax, u = p0 - q0;
        wf[l] = p1 - q1;
        xf[l] = p2 - q2;
        det[l] = u + wf[l] + xf[l];
        tf[l] = (u * az + wf[l] * bz + xf[l] * cz) * r->sz / det[l];
        if (fabsf(u) <= VOXGI__EDGE_NEAR_ZERO * (fabsf(p0) + fabsf(q0)) || fabsf(wf[l]) <= VOXGI__EDGE_NEAR_ZERO * (fabsf(p1) + fabsf(q1)) ||
            fabsf(xf[l]) <= VOXGI__EDGE_NEAR_ZERO * (fabsf(p2) + fabsf(q2)))
            near_zero |= 1 << l;
        else if (((u >= 0 && wf[l] >= 0 && xf[l] >= 0) || (u <= 0 && wf[l] <= 0 && xf[l] <= 0)) && det[l] != 0 && tf[l] > r->tmin && tf[l] <= tmax)
            hits |= 1 << l;
    }
#endif
    for (l = 0; l < 4; l++) {
        float t, u, v;
        if (pk->tri[l] == r->skip) continue;
        if (near_zero >> l & 1) {
            if (!voxgi__tri_lane_exact(pk, l, r, tmax, &t, &u, &v)) continue;
        } else {
            if (!(hits >> l & 1)) continue;
            t = tf[l];
            u = wf[l] / det[l];
            v = xf[l] / det[l];
        }
        if (!(t < tmax || (t == tmax && pk->tri[l] < tie))) continue;
        tmax = t;
        tie = pk->tri[l];
        best = l;
        *t_out = t;
        *u_out = u;
        *v_out = v;
    }
    return best;
}

/* Ray r's closest hit before tmax (any = 0) or any hit (any = 1); 1 when there is one. A node's
   leaves first, then on into its nearest inner child, the others on the stack. */
static int voxgi__ray4_cast(const voxgi_ray_scene *rs, voxgi__ray4 *r, float tmax, int any, voxgi_ray_hit *hit)
{
    struct { uint32_t node; float t; } stack[(VOXGI__W - 1) * VOXGI__BVH_DEPTH + 8];
    uint32_t node = 0, tie = 0; /* tie: no hit at the ray's own tmax counts */
    int sp = 0, found = 0;
    hit->triangle = UINT32_MAX;
    hit->t = hit->u = hit->v = 0;
    for (;;) {
        const voxgi__node *nd = &rs->nodes[node];
        float tn[VOXGI__W];
        int mask = voxgi__node_hits(nd, r, tmax, tn), leaves = mask & voxgi__node_leaves(nd), inner = mask & ~leaves, i;
        if (leaves && !r->sheared) voxgi__ray4_shear(r);
        while (leaves) {
            uint32_t k, end;
            i = voxgi__ctz32((uint32_t)leaves);
            leaves &= leaves - 1;
            for (k = nd->child[i], end = k + nd->count[i]; k < end; k++) {
                float tt = 0, u = 0, v = 0;
                int lane = voxgi__ray4_pack(&rs->packs[k], r, tmax, tie, &tt, &u, &v);
                if (lane < 0) continue;
                tmax = tt;
                tie = rs->packs[k].tri[lane];
                found = 1;
                hit->t = tt;
                hit->u = u;
                hit->v = v;
                hit->triangle = tie;
                if (any) return 1;
            }
        }
        if (inner) {
            i = voxgi__ctz32((uint32_t)inner);
            inner &= inner - 1;
            if (inner) { /* two or more: the nearest on, the others pushed farthest deepest (occlusion: any order) */
                uint32_t ids[VOXGI__W];
                float ts[VOXGI__W];
                int n = 1, j;
                ids[0] = nd->child[i];
                ts[0] = tn[i];
                do {
                    i = voxgi__ctz32((uint32_t)inner);
                    inner &= inner - 1;
                    for (j = n; !any && j > 0 && ts[j - 1] < tn[i]; j--) { ids[j] = ids[j - 1]; ts[j] = ts[j - 1]; }
                    ids[j] = nd->child[i];
                    ts[j] = tn[i];
                    n++;
                } while (inner);
                for (j = 0; j < n - 1; j++) {
                    stack[sp].node = ids[j];
                    stack[sp].t = ts[j];
                    sp++;
                }
                node = ids[n - 1];
                if (any || ts[n - 1] <= tmax) continue;
            } else if (tn[i] <= tmax) { /* a leaf of this node may have come nearer */
                node = nd->child[i];
                continue;
            }
        }
        while (sp && stack[sp - 1].t > tmax) sp--; /* behind a hit already found */
        if (!sp) break;
        node = stack[--sp].node;
    }
    return found;
}

typedef struct voxgi__ray_job {
    const voxgi_ray_scene *rs;
    const voxgi_ray *rays;
    voxgi_ray_hit *hits;
    unsigned char *occluded;
    int bad;                      /* set when a ray is not finite (checked where it is cast, while in the cache) */
} voxgi__ray_job;

static int voxgi__ray_finite(const voxgi_ray *ray)
{
    int a, ok = !isnan(ray->tmin) && !isnan(ray->tmax);
    for (a = 0; a < 3; a++) ok &= isfinite(ray->origin[a]) && isfinite(ray->direction[a]);
    return ok;
}

#ifdef VOXGI__SSE
/* Packets: sixteen consecutive rays whose directions share their signs traced together, a node's
   boxes tested against four rays at a time and a child visited when any ray enters it, nearest
   first by its nearest ray. Each ray tests the triangles with its own shear and keeps its own tmax
   and tie, so it finds exactly the hit it finds alone: the packet saves the set-up and the
   traversal's bookkeeping, which coherent rays (a camera's tile) share. */
#define VOXGI__PACKET 16
typedef struct voxgi__packet {
    __m128 o[3][4], inv[3][4], inv_far[3][4], tmin[4];
    float tmax[VOXGI__PACKET];    /* on a 16-byte boundary: read as four vectors */
    float lane[13][VOXGI__PACKET]; /* by ray: o, d, tmin, inv, inv_far */
    uint32_t tie[VOXGI__PACKET];
    int sheared, boxed;           /* the rays (bits) whose ray[] has its shear, its vectors for the boxes */
    size_t near_at[3], far_at[3];
    voxgi__wide o_lo[3], o_hi[3], inv_lo[3], inv_hi[3], far_lo[3], far_hi[3], tmin_lo, tmax_hi; /* the rays' bounds, in every lane */
    voxgi_ray_hit *hits;
    voxgi__ray4 ray[VOXGI__PACKET];
} voxgi__packet;

/* The rays of P in `active` (bits) that enter child c of nd, and the nearest entry among them;
   first_only: those of the first group of four with one. */
static VOXGI__HOT_INLINE int voxgi__packet_child(const voxgi__packet *P, const voxgi__node *nd, int c, int active, int first_only, float *t_near)
{
    __m128 near_plane[3], far_plane[3], nearest = _mm_set1_ps(INFINITY);
    int a, g, hits = 0;
    for (a = 0; a < 3; a++) {
        near_plane[a] = _mm_set1_ps(((const float *)(const void *)((const char *)nd + P->near_at[a]))[c]);
        far_plane[a] = _mm_set1_ps(((const float *)(const void *)((const char *)nd + P->far_at[a]))[c]);
    }
    for (g = 0; g < 4; g++) {
        __m128 tn, tf, in;
        int m;
        if (!(active >> 4 * g & 15)) continue;
        tn = P->tmin[g];
        tf = _mm_load_ps(P->tmax + 4 * g);
        for (a = 0; a < 3; a++) {
            tn = _mm_max_ps(tn, _mm_mul_ps(_mm_sub_ps(near_plane[a], P->o[a][g]), P->inv[a][g]));
            tf = _mm_min_ps(tf, _mm_mul_ps(_mm_sub_ps(far_plane[a], P->o[a][g]), P->inv_far[a][g]));
        }
        in = _mm_cmple_ps(tn, tf);
        m = _mm_movemask_ps(in) & (active >> 4 * g & 15);
        if (!m) continue;
        hits |= m << 4 * g;
        nearest = _mm_min_ps(nearest, _mm_or_ps(_mm_and_ps(in, tn), _mm_andnot_ps(in, _mm_set1_ps(INFINITY))));
        if (first_only) break;
    }
    nearest = _mm_min_ps(nearest, _mm_shuffle_ps(nearest, nearest, _MM_SHUFFLE(2, 3, 0, 1)));
    nearest = _mm_min_ps(nearest, _mm_shuffle_ps(nearest, nearest, _MM_SHUFFLE(1, 0, 3, 2)));
    *t_near = _mm_cvtss_f32(nearest);
    return hits;
}

/* Ray i of P as a ray of its own, with its shear, and with its vectors for the boxes when asked. */
static voxgi__ray4 *voxgi__packet_ray(voxgi__packet *P, int i, int boxes)
{
    voxgi__ray4 *r = &P->ray[i];
    int a;
    if (!(P->sheared >> i & 1)) {
        for (a = 0; a < 3; a++) { r->o[a] = P->lane[a][i]; r->d[a] = P->lane[3 + a][i]; }
        r->tmin = P->lane[6][i];
        r->skip = UINT32_MAX;
        voxgi__ray4_shear(r);
        P->sheared |= 1 << i;
    }
    if (boxes && !(P->boxed >> i & 1)) {
        for (a = 0; a < 3; a++) {
            r->inv[a] = P->lane[7 + a][i];
            r->inv_far[a] = P->lane[10 + a][i];
            r->o4[a] = VOXGI__WIDE_SET1(r->o[a]);
            r->inv4[a] = VOXGI__WIDE_SET1(r->inv[a]);
            r->inv_far4[a] = VOXGI__WIDE_SET1(r->inv_far[a]);
            r->near_at[a] = P->near_at[a];
            r->far_at[a] = P->far_at[a];
        }
        P->boxed |= 1 << i;
    }
    return r;
}

/* The children of nd that some ray of P may enter (bits), from the bounds of the rays' origins and
   inverse directions: each slab's entry is monotonic in both, so its least and greatest over the
   rays lie at corners of those bounds, rounding included. */
static VOXGI__HOT_INLINE int voxgi__packet_bounds(const voxgi__packet *P, const voxgi__node *nd)
{
    voxgi__wide lo = P->tmin_lo, hi = P->tmax_hi;
    int a;
    for (a = 0; a < 3; a++) {
        voxgi__wide n = VOXGI__WIDE_LOAD((const float *)(const void *)((const char *)nd + P->near_at[a]));
        voxgi__wide f = VOXGI__WIDE_LOAD((const float *)(const void *)((const char *)nd + P->far_at[a]));
        voxgi__wide n0 = VOXGI__WIDE_SUB(n, P->o_lo[a]), n1 = VOXGI__WIDE_SUB(n, P->o_hi[a]), f0 = VOXGI__WIDE_SUB(f, P->o_lo[a]), f1 = VOXGI__WIDE_SUB(f, P->o_hi[a]);
        lo = VOXGI__WIDE_MAX(lo, VOXGI__WIDE_MIN(VOXGI__WIDE_MIN(VOXGI__WIDE_MUL(n0, P->inv_lo[a]), VOXGI__WIDE_MUL(n0, P->inv_hi[a])),
                                                 VOXGI__WIDE_MIN(VOXGI__WIDE_MUL(n1, P->inv_lo[a]), VOXGI__WIDE_MUL(n1, P->inv_hi[a]))));
        hi = VOXGI__WIDE_MIN(hi, VOXGI__WIDE_MAX(VOXGI__WIDE_MAX(VOXGI__WIDE_MUL(f0, P->far_lo[a]), VOXGI__WIDE_MUL(f0, P->far_hi[a])),
                                                 VOXGI__WIDE_MAX(VOXGI__WIDE_MUL(f1, P->far_lo[a]), VOXGI__WIDE_MUL(f1, P->far_hi[a]))));
    }
    return VOXGI__WIDE_LE(lo, hi);
}

/* The closest hits of the packet's rays in `all` (bits), into P->hits. Ranged traversal (Wald,
   Boulos and Shirley 2007): a node carries the first ray that entered it, the rays before it
   having missed it and so its children; a child the first ray enters is entered with it, else the
   bounds of all rays may rule it out, else the first ray that enters it is looked for. Leaves
   test exactly which rays enter them. */
static void voxgi__packet_cast(const voxgi_ray_scene *rs, voxgi__packet *P, int all)
{
    struct { uint32_t node; int first; } stack[(VOXGI__W - 1) * VOXGI__BVH_DEPTH + 8];
    uint32_t node = 0;
    int sp = 0, first = voxgi__ctz32((uint32_t)all);
    for (;;) {
        const voxgi__node *nd = &rs->nodes[node];
        uint32_t ids[VOXGI__W];
        int firsts[VOXGI__W], n = 0, c, j, leaves = voxgi__node_leaves(nd), mine, maybe;
        float ts[VOXGI__W], tn[VOXGI__W];
        voxgi__ray4 *one = voxgi__packet_ray(P, first, 1);
        mine = voxgi__node_hits(nd, one, P->tmax[first], tn);
        maybe = mine;
        if ((mine | VOXGI__WIDE_GT(VOXGI__WIDE_LOAD(nd->lo[0]), VOXGI__WIDE_LOAD(nd->hi[0]))) != VOXGI__W_ALL) /* a child the first ray misses */
            maybe |= voxgi__packet_bounds(P, nd);
        for (c = 0; c < VOXGI__W; c++) {
            int f = first, m;
            float t = tn[c];
            if (!(maybe >> c & 1)) continue;
            if (leaves >> c & 1) { /* a leaf: each ray that enters it, against its packs */
                uint32_t k, end = nd->child[c] + nd->count[c];
                m = voxgi__packet_child(P, nd, c, (int)((unsigned)all & (0xFFFFu << first)), 0, &t);
                while (m) {
                    int i = voxgi__ctz32((uint32_t)m);
                    const voxgi__ray4 *r = voxgi__packet_ray(P, i, 0);
                    m &= m - 1;
                    for (k = nd->child[c]; k < end; k++) {
                        float tt = 0, u = 0, v = 0;
                        int lane = voxgi__ray4_pack(&rs->packs[k], r, P->tmax[i], P->tie[i], &tt, &u, &v);
                        if (lane < 0) continue;
                        P->tmax[i] = tt;
                        P->tie[i] = rs->packs[k].tri[lane];
                        P->hits[i].t = tt;
                        P->hits[i].u = u;
                        P->hits[i].v = v;
                        P->hits[i].triangle = P->tie[i];
                    }
                }
                continue;
            }
            if (!(mine >> c & 1)) { /* the first ray misses it: the first one that does not */
                m = voxgi__packet_child(P, nd, c, (int)((unsigned)all & (0xFFFFu << (first + 1))), 1, &t);
                if (!m) continue;
                f = voxgi__ctz32((uint32_t)m);
            }
            for (j = n; j > 0 && ts[j - 1] < t; j--) { ids[j] = ids[j - 1]; ts[j] = ts[j - 1]; firsts[j] = firsts[j - 1]; }
            ids[j] = nd->child[c];
            ts[j] = t;
            firsts[j] = f;
            n++;
        }
        if (n) { /* on into the nearest; the others on the stack, farthest deepest */
            for (j = 0; j < n - 1; j++) {
                stack[sp].node = ids[j];
                stack[sp].first = firsts[j];
                sp++;
            }
            node = ids[n - 1];
            first = firsts[n - 1];
            continue;
        }
        if (!sp) break;
        --sp;
        node = stack[sp].node;
        first = stack[sp].first;
    }
}

/* Rays [first, first + n) of J (n <= 16) into P, four at a time with the arithmetic of
   voxgi__ray4_setup: the rays to cast (bits), 0 where their signs differ (each then goes alone);
   hits cleared, rays not finite flagged. */
static int voxgi__packet_load(voxgi__ray_job *J, size_t first, size_t n, voxgi__packet *P)
{
    const __m128 zero = _mm_setzero_ps(), sign = _mm_set1_ps(-0.0f), tiny = _mm_set1_ps(1e-30f);
    voxgi_ray pad[VOXGI__PACKET];
    const voxgi_ray *in = J->rays + first;
    size_t k;
    int g, a, cast = 0, neg[3] = {0, 0, 0};
    if (n < VOXGI__PACKET) { /* a short packet: the first ray again in the lanes left */
        memcpy(pad, in, n * sizeof *in);
        for (k = n; k < VOXGI__PACKET; k++) pad[k] = in[0];
        in = pad;
    }
    P->hits = J->hits + first;
    for (k = 0; k < n; k++) {
        P->hits[k].triangle = UINT32_MAX;
        P->hits[k].t = P->hits[k].u = P->hits[k].v = 0;
    }
    for (g = 0; g < 4; g++) {
        const voxgi_ray *q = in + 4 * g;
        __m128 o[4], d[4], ok, some;
        int m;
        for (k = 0; k < 4; k++) { /* origin, tmin; direction, tmax */
            o[k] = _mm_loadu_ps((const float *)(const void *)&q[k]);
            d[k] = _mm_loadu_ps((const float *)(const void *)((const char *)&q[k] + offsetof(voxgi_ray, direction)));
        }
        _MM_TRANSPOSE4_PS(o[0], o[1], o[2], o[3]); /* x, y, z, tmin of the four */
        _MM_TRANSPOSE4_PS(d[0], d[1], d[2], d[3]); /* x, y, z, tmax */
        ok = _mm_and_ps(_mm_cmpord_ps(o[3], o[3]), _mm_cmpord_ps(d[3], d[3]));
        some = zero;
        for (a = 0; a < 3; a++) {
            __m128d c = _mm_set1_pd(J->rs->centre[a]);
            __m128 negative = _mm_cmplt_ps(d[a], zero), nonzero;
            ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpeq_ps(_mm_sub_ps(o[a], o[a]), zero), _mm_cmpeq_ps(_mm_sub_ps(d[a], d[a]), zero)));
            some = _mm_or_ps(some, _mm_cmpneq_ps(d[a], zero));
            _mm_storeu_ps(P->lane[3 + a] + 4 * g, d[a]);
            o[a] = _mm_movelh_ps(_mm_cvtpd_ps(_mm_sub_pd(_mm_cvtps_pd(o[a]), c)), _mm_cvtpd_ps(_mm_sub_pd(_mm_cvtps_pd(_mm_movehl_ps(o[a], o[a])), c)));
            _mm_storeu_ps(P->lane[a] + 4 * g, o[a]);
            P->o[a][g] = o[a];
            nonzero = _mm_cmpgt_ps(_mm_andnot_ps(sign, d[a]), tiny);
            nonzero = _mm_or_ps(_mm_and_ps(nonzero, d[a]), _mm_andnot_ps(nonzero, _mm_or_ps(tiny, _mm_and_ps(negative, sign))));
            P->inv[a][g] = _mm_div_ps(_mm_set1_ps(1.0f), nonzero);
            P->inv_far[a][g] = _mm_mul_ps(P->inv[a][g], _mm_set1_ps(1.0f + 4.76837158e-7f));
            _mm_storeu_ps(P->lane[7 + a] + 4 * g, P->inv[a][g]);
            _mm_storeu_ps(P->lane[10 + a] + 4 * g, P->inv_far[a][g]);
            neg[a] |= _mm_movemask_ps(negative) << 4 * g;
        }
        _mm_storeu_ps(P->lane[6] + 4 * g, o[3]);
        P->tmin[g] = o[3];
        m = _mm_movemask_ps(ok);
        if (m != 15)
            for (k = 0; k < 4; k++)
                if (!(m >> k & 1) && 4 * g + k < n) VOXGI__ATOMIC_STORE_INT(&J->bad, 1);
        m &= _mm_movemask_ps(some);
        _mm_store_ps(P->tmax + 4 * g, _mm_or_ps(_mm_and_ps(_mm_castsi128_ps(_mm_set_epi32(-(m >> 3 & 1), -(m >> 2 & 1), -(m >> 1 & 1), -(m & 1))), d[3]),
                                                _mm_andnot_ps(_mm_castsi128_ps(_mm_set_epi32(-(m >> 3 & 1), -(m >> 2 & 1), -(m >> 1 & 1), -(m & 1))),
                                                              _mm_set1_ps(-INFINITY))));
        cast |= m << 4 * g;
    }
    cast &= (int)((1u << n) - 1u);
    for (a = 0; a < 3; a++) {
        int s = neg[a] & cast;
        if (s != 0 && s != cast) return 0;
        P->ray[0].neg[a] = s != 0;
    }
    voxgi__ray4_planes(P->ray[0].neg, P->near_at, P->far_at);
    memset(P->tie, 0, sizeof P->tie);
    P->sheared = P->boxed = 0;
    { /* the rays' bounds, in every lane: the rays cast, the others left out */
        static const int rows[11] = {0, 1, 2, 6, 7, 8, 9, 10, 11, 12, 13}; /* o, tmin, inv, inv_far; 13: tmax */
        const __m128 inf = _mm_set1_ps(INFINITY), minus_inf = _mm_set1_ps(-INFINITY);
        __m128 valid[4], lo[14], hi[14];
        int k;
        for (g = 0; g < 4; g++) valid[g] = _mm_castsi128_ps(_mm_set_epi32(-(cast >> (4 * g + 3) & 1), -(cast >> (4 * g + 2) & 1), -(cast >> (4 * g + 1) & 1), -(cast >> 4 * g & 1)));
        for (k = 0; k < 11; k++) {
            int row = rows[k];
            const float *v = row < 13 ? P->lane[row] : P->tmax;
            __m128 l = inf, h = minus_inf;
            for (g = 0; g < 4; g++) {
                __m128 x = _mm_loadu_ps(v + 4 * g);
                if (cast == 0xFFFF) {
                    l = _mm_min_ps(l, x);
                    h = _mm_max_ps(h, x);
                } else {
                    l = _mm_min_ps(l, _mm_or_ps(_mm_and_ps(valid[g], x), _mm_andnot_ps(valid[g], inf)));
                    h = _mm_max_ps(h, _mm_or_ps(_mm_and_ps(valid[g], x), _mm_andnot_ps(valid[g], minus_inf)));
                }
            }
            l = _mm_min_ps(l, _mm_shuffle_ps(l, l, _MM_SHUFFLE(2, 3, 0, 1)));
            lo[row] = _mm_min_ps(l, _mm_shuffle_ps(l, l, _MM_SHUFFLE(1, 0, 3, 2)));
            h = _mm_max_ps(h, _mm_shuffle_ps(h, h, _MM_SHUFFLE(2, 3, 0, 1)));
            hi[row] = _mm_max_ps(h, _mm_shuffle_ps(h, h, _MM_SHUFFLE(1, 0, 3, 2)));
        }
        for (a = 0; a < 3; a++) {
            P->o_lo[a] = VOXGI__WIDE_SET1(_mm_cvtss_f32(lo[a]));
            P->o_hi[a] = VOXGI__WIDE_SET1(_mm_cvtss_f32(hi[a]));
            P->inv_lo[a] = VOXGI__WIDE_SET1(_mm_cvtss_f32(lo[7 + a]));
            P->inv_hi[a] = VOXGI__WIDE_SET1(_mm_cvtss_f32(hi[7 + a]));
            P->far_lo[a] = VOXGI__WIDE_SET1(_mm_cvtss_f32(lo[10 + a]));
            P->far_hi[a] = VOXGI__WIDE_SET1(_mm_cvtss_f32(hi[10 + a]));
        }
        P->tmin_lo = VOXGI__WIDE_SET1(_mm_cvtss_f32(lo[6]));
        P->tmax_hi = VOXGI__WIDE_SET1(_mm_cvtss_f32(hi[13]));
    }
    return cast;
}
#endif

/* Ray i of the job set up in r (0: not cast; its hit cleared, not finite ones flagged). */
static int voxgi__ray_job_setup(voxgi__ray_job *J, size_t i, voxgi__ray4 *r)
{
    const voxgi_ray *ray = &J->rays[i];
    double o[3], d[3];
    int a;
    for (a = 0; a < 3; a++) { o[a] = ray->origin[a]; d[a] = ray->direction[a]; }
    if (!voxgi__ray_finite(ray)) VOXGI__ATOMIC_STORE_INT(&J->bad, 1);
    else if (voxgi__ray4_setup(J->rs, o, d, ray->tmin, UINT32_MAX, r)) return 1;
    if (J->hits) {
        J->hits[i].triangle = UINT32_MAX;
        J->hits[i].t = J->hits[i].u = J->hits[i].v = 0;
    } else
        J->occluded[i] = 0;
    return 0;
}

static void voxgi__ray_range(void *user, size_t first, size_t end)
{
    voxgi__ray_job *J = (voxgi__ray_job *)user;
    size_t i;
    voxgi__ray4 r;
    voxgi_ray_hit h;
#ifdef VOXGI__SSE
    if (J->hits) { /* closest hits: by packets where their signs agree */
        voxgi__packet P;
        for (i = first; i < end; i += VOXGI__PACKET) {
            size_t k, n = VOXGI__MIN(end - i, (size_t)VOXGI__PACKET);
            int cast = n == VOXGI__PACKET ? voxgi__packet_load(J, i, n, &P) : 0;
            if (cast) {
                voxgi__packet_cast(J->rs, &P, cast);
                continue;
            }
            for (k = i; k < i + n; k++)
                if (voxgi__ray_job_setup(J, k, &r)) voxgi__ray4_cast(J->rs, &r, J->rays[k].tmax, 0, &J->hits[k]);
        }
        return;
    }
#endif
    for (i = first; i < end; i++)
        if (voxgi__ray_job_setup(J, i, &r)) {
            int found = voxgi__ray4_cast(J->rs, &r, J->rays[i].tmax, !J->hits, J->hits ? &J->hits[i] : &h);
            if (!J->hits) J->occluded[i] = (unsigned char)found;
        }
}

static voxgi_result voxgi__rays_run(voxgi_context *ctx, const voxgi_ray_scene *rs, size_t count, const voxgi_ray *rays, voxgi_ray_hit *hits,
                                    unsigned char *occluded)
{
    voxgi__ray_job J;
    size_t i;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!rs || (count && (!rays || (!hits && !occluded)))) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the ray scene, rays or results are NULL");
    J.rs = rs;
    J.rays = rays;
    J.hits = hits;
    J.occluded = occluded;
    J.bad = 0;
    voxgi__parallel(ctx, count, 256, voxgi__ray_range, &J);
    for (i = 0; J.bad && i < count; i++)
        if (!voxgi__ray_finite(&rays[i])) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "ray %lu is not finite", (unsigned long)i);
    return VOXGI_OK;
}

VOXGI_API voxgi_result voxgi_ray_intersect(voxgi_context *ctx, const voxgi_ray_scene *rs, size_t count, const voxgi_ray *rays, voxgi_ray_hit *hits)
{
    return voxgi__rays_run(ctx, rs, count, rays, hits, NULL);
}

VOXGI_API voxgi_result voxgi_ray_occluded(voxgi_context *ctx, const voxgi_ray_scene *rs, size_t count, const voxgi_ray *rays, unsigned char *occluded)
{
    return voxgi__rays_run(ctx, rs, count, rays, NULL, occluded);
}

/* ----- 3.5 the renderers' tracer

   The renderers' side of the core: the scene's triangles in double beside its ray scene, and hits
   with their point, triangle and side. The core rounds origins and vertices to floats relative to
   the centre, within 2^-24 of the reach each; a ray leaving a surface therefore starts a hair off
   it (2^-18 of the reach, 16 times what both roundings can move a point off a plane), never hits
   the triangle it leaves, and a shadow ray stops two hairs short of its target. */
typedef struct voxgi__tracer {
    voxgi__flat flat;
    double *v;                    /* 9 per triangle, in the scene's order */
    double *n;                    /* unit geometric normal (front: counter-clockwise) per triangle */
    voxgi_ray_scene *rs;
    int caller_rs;                /* rs is the caller's (kept across images of a static scene): not freed here */
    double hair;                  /* world units */
    int translucent;              /* a material lets light through (transparency > 0) */
} voxgi__tracer;

typedef struct voxgi__hit { double t, p[3]; uint32_t prim; int front; } voxgi__hit;

static void voxgi__tracer_free(voxgi_context *ctx, voxgi__tracer *tr)
{
    voxgi__flat_free(ctx, &tr->flat);
    voxgi__free(ctx, tr->v);
    voxgi__free(ctx, tr->n);
    if (!tr->caller_rs) voxgi__ray_scene_free(ctx, tr->rs);
    memset(tr, 0, sizeof *tr);
}

/* Whether rs was made of exactly these triangles (its centre, and every triangle's local floats
   in its packs): a ray scene of other geometry would answer for that geometry. */
static int voxgi__ray_scene_is_of(const voxgi_ray_scene *rs, const voxgi__flat *flat)
{
    double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
    size_t i, seen = 0;
    int a, j, r;
    if (rs->triangles != flat->triangle_count) return 0;
    for (i = 0; i < flat->vertex_count; i++)
        for (a = 0; a < 3; a++) { lo[a] = VOXGI__MIN(lo[a], (double)flat->pos[3 * i + a]); hi[a] = VOXGI__MAX(hi[a], (double)flat->pos[3 * i + a]); }
    for (a = 0; a < 3; a++)
        if (rs->centre[a] != 0.5 * (lo[a] + hi[a])) return 0;
    for (i = 0; i < rs->pack_count; i++)
        for (j = 0; j < 4; j++) {
            uint32_t t = rs->packs[i].tri[j];
            if (t == UINT32_MAX) continue;
            if (t >= flat->triangle_count) return 0;
            for (r = 0; r < 9; r++)
                if (rs->packs[i].v[r][j] != (float)((double)flat->pos[3 * (size_t)flat->tri[3 * (size_t)t + (size_t)(r / 3)] + (size_t)(r % 3)] - rs->centre[r % 3]))
                    return 0;
            seen++;
        }
    return seen == flat->triangle_count;
}

/* The tracer of the scene, its BVH the caller's `rays` (made by voxgi_ray_scene_create of this
   scene: checked) or built here (NULL). */
static voxgi_result voxgi__tracer_build_with(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_ray_scene *rays, voxgi__tracer *tr)
{
    size_t t, nt;
    voxgi_result r;
    memset(tr, 0, sizeof *tr);
    if ((r = voxgi__flatten(ctx, scene, 0, 1, &tr->flat)) != VOXGI_OK) return r;
    nt = tr->flat.triangle_count;
    tr->v = (double *)voxgi__alloc_array(ctx, nt, 9 * sizeof(double), 0);
    tr->n = (double *)voxgi__alloc_array(ctx, nt, 3 * sizeof(double), 0);
    if (!tr->v || !tr->n) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu triangles", (unsigned long)nt);
    if (r == VOXGI_OK && rays) {
        tr->rs = (voxgi_ray_scene *)(uintptr_t)rays; /* read only: the tracer never writes its BVH */
        tr->caller_rs = 1;
        if (!voxgi__ray_scene_is_of(rays, &tr->flat)) r = voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the ray scene given was made of other triangles");
    } else if (r == VOXGI_OK)
        r = voxgi__ray_scene_build(ctx, &tr->flat, &tr->rs);
    if (r != VOXGI_OK) {
        voxgi__tracer_free(ctx, tr);
        return r;
    }
    tr->hair = ldexp(tr->rs->reach, -18);
    for (t = 0; t < tr->flat.material_count; t++) tr->translucent |= tr->flat.materials[t].transparency > 0;
    for (t = 0; t < nt; t++) {
        double *v = tr->v + 9 * t, *n = tr->n + 3 * t, e1[3], e2[3], len;
        int k, a;
        for (k = 0; k < 3; k++)
            for (a = 0; a < 3; a++) v[3 * k + a] = tr->flat.pos[3 * (size_t)tr->flat.tri[3 * t + (size_t)k] + (size_t)a];
        for (a = 0; a < 3; a++) { e1[a] = v[3 + a] - v[a]; e2[a] = v[6 + a] - v[a]; }
        for (a = 0; a < 3; a++) n[a] = e1[(a + 1) % 3] * e2[(a + 2) % 3] - e1[(a + 2) % 3] * e2[(a + 1) % 3];
        len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (a = 0; a < 3; a++) n[a] = len > 0 ? n[a] / len : 0;
    }
    return VOXGI_OK;
}

static voxgi_result voxgi__tracer_build(voxgi_context *ctx, const voxgi_scene *scene, voxgi__tracer *tr)
{
    return voxgi__tracer_build_with(ctx, scene, NULL, tr);
}

/* The nearest hit of the ray from o along d (world units) before tmax, never triangle skip
   (UINT32_MAX: none); any = 1 stops at the first hit (shadow rays). The core finds the triangle;
   where the ray meets its plane is then computed in double (the core's t holds float rounding
   of the whole scene's extent, which a point near the eye on a large triangle would show). */
static int voxgi__trace(const voxgi__tracer *tr, const double o[3], const double d[3], double tmax, uint32_t skip, int any, voxgi__hit *hit)
{
    voxgi__ray4 r;
    voxgi_ray_hit h;
    const double *v, *n;
    double along, to_plane;
    int a;
    if (!voxgi__ray4_setup(tr->rs, o, d, 0, skip, &r) || !voxgi__ray4_cast(tr->rs, &r, tmax < FLT_MAX ? (float)tmax : INFINITY, any, &h)) return 0;
    v = tr->v + 9 * (size_t)h.triangle;
    n = tr->n + 3 * (size_t)h.triangle;
    along = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
    to_plane = n[0] * (v[0] - o[0]) + n[1] * (v[1] - o[1]) + n[2] * (v[2] - o[2]);
    hit->t = along != 0 ? to_plane / along : h.t;
    hit->prim = h.triangle;
    for (a = 0; a < 3; a++) hit->p[a] = o[a] + hit->t * d[a];
    hit->front = along < 0;
    return 1;
}

/* The direct light (this and 3.6) serves light injection, the light-space passes, the
   screen-space images and the reference renderer: it goes when they all do. */
#if !defined(VOXGI_NO_LIGHT_INJECTION) || !defined(VOXGI_NO_LIGHT_SPACE) || !defined(VOXGI_NO_SCREEN_SPACE) || !defined(VOXGI_NO_REFERENCE)
#define VOXGI__DIRECT_LIGHT
#endif

#ifdef VOXGI__DIRECT_LIGHT
/* Where a ray leaving the surface at p (unit normal ns, on the side it leaves) starts. */
static void voxgi__leave(const voxgi__tracer *tr, const double p[3], const double ns[3], double o[3])
{
    int a;
    for (a = 0; a < 3; a++) o[a] = p[a] + tr->hair * ns[a];
}
#endif

/* ----- 3.6 lights: direct light and the exact area light */

/* What direct light needs: the scene's lights and its emissive triangles, picked by power. */
typedef struct voxgi__lights {
    const voxgi__tracer *tr;
    const voxgi_scene *scene;
    uint32_t *emitters;           /* triangles with emission, front faces */
    double *emitter_cdf;          /* by area x mean emission */
    double *emitter_pdf;          /* per triangle: the area density of picking a point on it */
    size_t emitter_count;
} voxgi__lights;

#ifdef VOXGI__DIRECT_LIGHT
static const voxgi_material *voxgi__prim_material(const voxgi__tracer *tr, uint32_t prim)
{
    return voxgi__tri_material(&tr->flat, prim);
}

static void voxgi__lights_free(voxgi_context *ctx, voxgi__lights *Ls)
{
    voxgi__free(ctx, Ls->emitters);
    voxgi__free(ctx, Ls->emitter_cdf);
    voxgi__free(ctx, Ls->emitter_pdf);
    memset(Ls, 0, sizeof *Ls);
}

static voxgi_result voxgi__lights_build(voxgi_context *ctx, const voxgi_scene *scene, const voxgi__tracer *tr, voxgi__lights *Ls)
{
    size_t i, nt = tr->flat.triangle_count;
    int a;
    memset(Ls, 0, sizeof *Ls);
    Ls->tr = tr;
    Ls->scene = scene;
    Ls->emitters = (uint32_t *)voxgi__alloc_array(ctx, nt ? nt : 1, 4, 0);
    Ls->emitter_cdf = (double *)voxgi__alloc_array(ctx, nt ? nt : 1, sizeof(double), 0);
    Ls->emitter_pdf = (double *)voxgi__alloc_array(ctx, nt ? nt : 1, sizeof(double), 1);
    if (!Ls->emitters || !Ls->emitter_cdf || !Ls->emitter_pdf) {
        voxgi__lights_free(ctx, Ls);
        return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the emitter table");
    }
    for (i = 0; i < nt; i++) { /* emitters, weighted by area x mean emission */
        const voxgi_material *m = voxgi__prim_material(tr, (uint32_t)i);
        const double *v = tr->v + 9 * i;
        double power = ((double)m->emission[0] + m->emission[1] + m->emission[2]) / 3, c[3], e1[3], e2[3];
        for (a = 0; a < 3; a++) { e1[a] = v[3 + a] - v[a]; e2[a] = v[6 + a] - v[a]; }
        for (a = 0; a < 3; a++) c[a] = e1[(a + 1) % 3] * e2[(a + 2) % 3] - e1[(a + 2) % 3] * e2[(a + 1) % 3];
        Ls->emitter_pdf[i] = power; /* / the total power, below: the area density */
        power *= 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        if (!(power > 0)) { Ls->emitter_pdf[i] = 0; continue; }
        Ls->emitters[Ls->emitter_count] = (uint32_t)i;
        Ls->emitter_cdf[Ls->emitter_count] = (Ls->emitter_count ? Ls->emitter_cdf[Ls->emitter_count - 1] : 0) + power;
        Ls->emitter_count++;
    }
    for (i = 0; i < nt; i++) Ls->emitter_pdf[i] /= Ls->emitter_count ? Ls->emitter_cdf[Ls->emitter_count - 1] : 1;
    return VOXGI_OK;
}
#endif

#if (!defined(VOXGI_NO_LIGHT_INJECTION) && !defined(VOXGI_NO_GL)) || !defined(VOXGI_NO_LIGHT_SPACE) /* GL's light maps, the reflective shadow maps */
/* Point k of n on a rectangular light L, or (L NULL) on the emitters picked by power, stratified
   (a 2D Kronecker sequence; on a triangle, the pick's remainder and the second coordinate): its
   position q, the unit normal n it shines along, and the radiance x area it stands for (power,
   rgb), so that it sends the intensity power cos(theta) into its hemisphere (power pi in all);
   *prim: its emissive triangle (UINT32_MAX on a light). How area light becomes point light. */
static void voxgi__area_point(const voxgi__lights *Ls, const voxgi_light *L, int k, int n, double q[3], double nrm[3], double power[3], uint32_t *prim)
{
    static const double unshifted[2] = {0.5, 0.5}; /* the same points for every caller */
    const voxgi__tracer *tr = Ls->tr;
    double uv[2];
    int a;
    voxgi__kronecker(2, k, unshifted, uv);
    if (L) {
        double area;
        for (a = 0; a < 3; a++) nrm[a] = (double)L->edge_u[(a + 1) % 3] * L->edge_v[(a + 2) % 3] - (double)L->edge_u[(a + 2) % 3] * L->edge_v[(a + 1) % 3];
        area = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        for (a = 0; a < 3; a++) {
            q[a] = L->position[a] + uv[0] * L->edge_u[a] + uv[1] * L->edge_v[a];
            nrm[a] = area > 0 ? nrm[a] / area : 0;
            power[a] = L->intensity[a] * area / n;
        }
        *prim = UINT32_MAX;
    } else {
        double total = Ls->emitter_cdf[Ls->emitter_count - 1], u = uv[0] * total, below, r1, b1, b2;
        size_t lo = 0, hi = Ls->emitter_count - 1;
        const double *v, *tn;
        const voxgi_material *m;
        while (lo < hi) { size_t mid = (lo + hi) / 2; if (Ls->emitter_cdf[mid] <= u) lo = mid + 1; else hi = mid; }
        *prim = Ls->emitters[lo];
        below = lo ? Ls->emitter_cdf[lo - 1] : 0;
        r1 = sqrt(VOXGI__MIN(1.0, VOXGI__MAX(0.0, (u - below) / (Ls->emitter_cdf[lo] - below))));
        b1 = 1 - r1;
        b2 = r1 * uv[1];
        v = tr->v + 9 * (size_t)*prim;
        tn = tr->n + 3 * (size_t)*prim;
        m = voxgi__prim_material(tr, *prim);
        for (a = 0; a < 3; a++) {
            q[a] = v[a] + b1 * (v[3 + a] - v[a]) + b2 * (v[6 + a] - v[a]);
            nrm[a] = tn[a];
            power[a] = m->emission[a] / (Ls->emitter_pdf[*prim] * n);
        }
    }
}
#endif

#ifdef VOXGI__DIRECT_LIGHT
/* Nothing between p (on triangle skip, unit normal ns on the side the ray leaves) and the
   point dist away along dir? (short of it, so the light's own triangle does not count) */
/* The share of light arriving at p along dir from dist away: 0 behind an opaque surface, else the
   product of the transparencies of the surfaces on the way (each surface once: the ray goes on a
   hair past each one it crosses). Shadow rays alone see through surfaces; camera rays and bounces
   meet them as they are. */
static double voxgi__visible(const voxgi__tracer *tr, const double p[3], const double ns[3], const double dir[3], double dist, uint32_t skip,
                             uint64_t *rays)
{
    voxgi__hit h;
    double o[3], left, light = 1;
    int a, crossed;
    ++*rays;
    voxgi__leave(tr, p, ns, o);
    left = dist - 2 * tr->hair;
    if (left <= 0 || !voxgi__trace(tr, o, dir, left, skip, 1, &h)) return 1;
    if (!tr->translucent) return 0;
    for (crossed = 0; crossed < 256; crossed++) { /* through the translucent surfaces one by one */
        const voxgi_material *m;
        if (!voxgi__trace(tr, o, dir, left, skip, 0, &h)) return light;
        m = voxgi__tri_material(&tr->flat, h.prim);
        if (!(m->transparency > 0)) return 0;
        light *= VOXGI__MIN(m->transparency, 1.0f);
        ++*rays;
        for (a = 0; a < 3; a++) o[a] = h.p[a] + tr->hair * dir[a];
        left -= h.t + tr->hair;
        skip = h.prim;
        if (left <= 0) return light;
    }
    return 0; /* a wall of 256 leaves */
}

/* A spot light's share toward the unit direction dir from the lit point to the light: a
   smoothstep from the outer cone (0) to the inner one (1). */
static double voxgi__spot_share(const voxgi_light *L, const double dir[3])
{
    double len = sqrt((double)L->direction[0] * L->direction[0] + (double)L->direction[1] * L->direction[1] + (double)L->direction[2] * L->direction[2]);
    double c = -(dir[0] * L->direction[0] + dir[1] * L->direction[1] + dir[2] * L->direction[2]) / len;
    double ci = cos((double)L->spot_inner), co = cos((double)L->spot_outer), x = ci > co ? (c - co) / (ci - co) : (c >= ci ? 1 : 0);
    x = x < 0 ? 0 : (x > 1 ? 1 : x);
    return x * x * (3 - 2 * x);
}

/* Irradiance E at p (unit normal ns facing the arriving ray; leaving triangle prim, or
   UINT32_MAX) from every light and one sampled point on the emissive triangles; the reflected
   radiance is albedo / pi * E. With mis, the emitters' share carries the power-heuristic weight
   against a cosine-sampled bounce finding them (the path tracer's other half), which keeps the
   variance finite where emitters meet at concave edges. xi: a 2D sample in [0,1)^2 for the
   points on area lights and emitters (stratified callers), or NULL to draw from g. area (or
   NULL): the rect lights' and emitters' share of e in area[0..2], what it would be without
   the shadow rays in area[3..5] (their visible share, for voxgi__area_irradiance), and the
   shadow rays traced and blocked added to area[6] and area[7]. */
static void voxgi__direct(const voxgi__lights *R, const double p[3], const double ns[3], uint32_t prim, voxgi__rng *g, int mis_weighted,
                          const double *xi, uint64_t *rays, double e[3], double *area_share)
{
    const voxgi__tracer *tr = R->tr;
    size_t li;
    int a;
    e[0] = e[1] = e[2] = 0;
    for (li = 0; li < R->scene->light_count; li++) {
        const voxgi_light *L = &R->scene->lights[li];
        double dir[3], dist = DBL_MAX, cos_s, w = 0, q[3], seen;
        if (L->type == VOXGI_LIGHT_DIRECTIONAL) {
            double len = sqrt((double)L->direction[0] * L->direction[0] + (double)L->direction[1] * L->direction[1] + (double)L->direction[2] * L->direction[2]);
            for (a = 0; a < 3; a++) dir[a] = -L->direction[a] / len;
            w = 1;
        } else {
            double area = 1, cos_l = 1;
            if (L->type == VOXGI_LIGHT_RECT) {
                double u = xi ? xi[0] : voxgi__rng_unit(g), v = xi ? xi[1] : voxgi__rng_unit(g), n[3];
                for (a = 0; a < 3; a++) q[a] = L->position[a] + u * L->edge_u[a] + v * L->edge_v[a];
                for (a = 0; a < 3; a++) n[a] = (double)L->edge_u[(a + 1) % 3] * L->edge_v[(a + 2) % 3] - (double)L->edge_u[(a + 2) % 3] * L->edge_v[(a + 1) % 3];
                area = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
                for (a = 0; a < 3; a++) dir[a] = q[a] - p[a];
                dist = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
                if (dist <= 0) continue;
                for (a = 0; a < 3; a++) dir[a] /= dist;
                cos_l = -(dir[0] * n[0] + dir[1] * n[1] + dir[2] * n[2]) / area;
                if (cos_l <= 0) continue;
            } else {
                for (a = 0; a < 3; a++) { q[a] = L->position[a]; dir[a] = q[a] - p[a]; }
                dist = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
                if (dist <= 0) continue;
                for (a = 0; a < 3; a++) dir[a] /= dist;
                if (L->type == VOXGI_LIGHT_SPOT && (cos_l = voxgi__spot_share(L, dir)) <= 0) continue;
            }
            w = cos_l * area / (dist * dist);
        }
        cos_s = dir[0] * ns[0] + dir[1] * ns[1] + dir[2] * ns[2];
        if (cos_s <= 0) continue;
        if (area_share && L->type == VOXGI_LIGHT_RECT) for (a = 0; a < 3; a++) area_share[3 + a] += L->intensity[a] * w * cos_s;
        if (area_share) area_share[6] += 1;
        seen = voxgi__visible(tr, p, ns, dir, dist, prim, rays);
        if (seen <= 0) {
            if (area_share) area_share[7] += 1;
            continue;
        }
        for (a = 0; a < 3; a++) {
            e[a] += L->intensity[a] * w * cos_s * seen;
            if (area_share && L->type == VOXGI_LIGHT_RECT) area_share[a] += L->intensity[a] * w * cos_s * seen;
        }
    }
    if (R->emitter_count) { /* one emissive triangle by power, one uniform point on it */
        double u = (xi ? xi[0] : voxgi__rng_unit(g)) * R->emitter_cdf[R->emitter_count - 1], b1, b2, r1, q[3], dir[3], dist2, dist, cos_s, cos_l, below;
        size_t lo = 0, hi = R->emitter_count - 1;
        uint32_t k;
        const double *v, *n;
        const voxgi_material *m;
        while (lo < hi) { size_t mid = (lo + hi) / 2; if (R->emitter_cdf[mid] <= u) lo = mid + 1; else hi = mid; }
        k = R->emitters[lo];
        v = tr->v + 9 * (size_t)k;
        n = tr->n + 3 * (size_t)k;
        below = lo ? R->emitter_cdf[lo - 1] : 0; /* with xi, the pick's remainder is the first coordinate on the triangle */
        r1 = sqrt(xi ? VOXGI__MIN(1.0, VOXGI__MAX(0.0, (u - below) / (R->emitter_cdf[lo] - below))) : voxgi__rng_unit(g));
        b1 = 1 - r1;
        b2 = r1 * (xi ? xi[1] : voxgi__rng_unit(g));
        for (a = 0; a < 3; a++) {
            q[a] = v[a] + b1 * (v[3 + a] - v[a]) + b2 * (v[6 + a] - v[a]);
            dir[a] = q[a] - p[a];
        }
        dist2 = dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2];
        dist = sqrt(dist2);
        if (dist > 0 && k != prim) {
            for (a = 0; a < 3; a++) dir[a] /= dist;
            cos_s = dir[0] * ns[0] + dir[1] * ns[1] + dir[2] * ns[2];
            cos_l = -(dir[0] * n[0] + dir[1] * n[1] + dir[2] * n[2]);
            if (cos_s > 0 && cos_l > 0) {
                double pdf_light = R->emitter_pdf[k] * dist2 / cos_l, pdf_bsdf = cos_s / VOXGI__PI; /* per solid angle */
                double mis = mis_weighted ? pdf_light * pdf_light / (pdf_light * pdf_light + pdf_bsdf * pdf_bsdf) : 1;
                double seen = voxgi__visible(tr, p, ns, dir, dist, prim, rays);
                if (area_share) { area_share[6] += 1; area_share[7] += seen <= 0; }
                m = voxgi__prim_material(tr, k);
                for (a = 0; a < 3; a++) {
                    double c = mis * m->emission[a] * cos_s / pdf_light;
                    if (area_share) area_share[3 + a] += c;
                    if (seen <= 0) continue;
                    e[a] += c * seen;
                    if (area_share) area_share[a] += c * seen;
                }
            }
        }
    }
}
#endif

#if (!defined(VOXGI_NO_CONE_TRACING) && !defined(VOXGI_NO_LIGHT_INJECTION)) || !defined(VOXGI_NO_LINE_SPACE) /* for their images */
/* Lambert's formula: the irradiance at p on unit normal n from a convex polygon q[0..nq-1]
   (nq <= 4) of radiance 1 whose front (the side fn faces) p sees, clipped to p's upper
   half-space: half the sum over its edges of the angle each subtends at p times the cosine
   between n and the normal of the plane through p and the edge. Unoccluded, exact. */
static double voxgi__polygon_irradiance(const double q[][3], int nq, const double fn[3], const double p[3], const double n[3])
{
    double c[6][3], d[4], side = 0, sum = 0;
    int k, m = 0, a;
    for (a = 0; a < 3; a++) side += (p[a] - q[0][a]) * fn[a];
    if (!(side > 0)) return 0; /* behind it: emitters shine from their fronts */
    for (k = 0; k < nq; k++) {
        d[k] = 0;
        for (a = 0; a < 3; a++) d[k] += (q[k][a] - p[a]) * n[a];
    }
    for (k = 0; k < nq; k++) { /* clipped against n.(x - p) >= 0 (Sutherland-Hodgman), relative to p */
        int j = (k + 1) % nq;
        if (d[k] >= 0) { for (a = 0; a < 3; a++) c[m][a] = q[k][a] - p[a]; m++; }
        if ((d[k] >= 0) != (d[j] >= 0)) {
            double t = d[k] / (d[k] - d[j]);
            for (a = 0; a < 3; a++) c[m][a] = q[k][a] - p[a] + t * (q[j][a] - q[k][a]);
            m++;
        }
    }
    for (k = 0; k < m; k++) {
        double len = sqrt(c[k][0] * c[k][0] + c[k][1] * c[k][1] + c[k][2] * c[k][2]);
        if (!(len > 0)) return 0; /* p on the polygon */
        for (a = 0; a < 3; a++) c[k][a] /= len;
    }
    for (k = 0; m >= 3 && k < m; k++) {
        const double *u = c[k], *v = c[(k + 1) % m];
        double x[3], len;
        x[0] = u[1] * v[2] - u[2] * v[1];
        x[1] = u[2] * v[0] - u[0] * v[2];
        x[2] = u[0] * v[1] - u[1] * v[0];
        len = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        if (len > 0) sum += atan2(len, u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) * (x[0] * n[0] + x[1] * n[1] + x[2] * n[2]) / len;
    }
    return fabs(sum) / 2;
}
#endif

/* At most this many emissive triangles are summed analytically per shading point. */
#define VOXGI__ANALYTIC_EMITTERS 64

#if !defined(VOXGI_NO_CONE_TRACING) && !defined(VOXGI_NO_LIGHT_INJECTION) /* for the cone-traced images */
/* The unshadowed irradiance at p (unit normal ns, on triangle prim or UINT32_MAX) from the rect
   lights and the emissive triangles, exactly (voxgi__polygon_irradiance): what voxgi__direct's
   area[3..5] estimates. Times the shadow rays' visible share area[0..2] / area[3..5], the
   shadowed irradiance without the noise of where on the lights the rays went (the ratio
   estimator of Heitz et al. 2018): exact wherever a point sees all or none of the lights. */
static void voxgi__area_irradiance(const voxgi__lights *R, const double p[3], const double ns[3], uint32_t prim, double e[3])
{
    const voxgi__tracer *tr = R->tr;
    size_t i;
    int a, k;
    e[0] = e[1] = e[2] = 0;
    for (i = 0; i < R->scene->light_count; i++) {
        const voxgi_light *L = &R->scene->lights[i];
        double q[4][3], fn[3], f;
        if (L->type != VOXGI_LIGHT_RECT) continue;
        for (a = 0; a < 3; a++) {
            q[0][a] = L->position[a];
            q[1][a] = (double)L->position[a] + L->edge_u[a];
            q[2][a] = (double)L->position[a] + L->edge_u[a] + L->edge_v[a];
            q[3][a] = (double)L->position[a] + L->edge_v[a];
            fn[a] = (double)L->edge_u[(a + 1) % 3] * L->edge_v[(a + 2) % 3] - (double)L->edge_u[(a + 2) % 3] * L->edge_v[(a + 1) % 3];
        }
        f = voxgi__polygon_irradiance((const double(*)[3])q, 4, fn, p, ns);
        for (a = 0; a < 3; a++) e[a] += L->intensity[a] * f;
    }
    for (i = 0; i < R->emitter_count; i++) {
        uint32_t t = R->emitters[i];
        double q[3][3], f;
        const voxgi_material *m;
        if (t == prim) continue;
        for (k = 0; k < 3; k++)
            for (a = 0; a < 3; a++) q[k][a] = tr->v[9 * (size_t)t + 3 * (size_t)k + (size_t)a];
        f = voxgi__polygon_irradiance((const double(*)[3])q, 3, tr->n + 3 * (size_t)t, p, ns);
        m = voxgi__prim_material(tr, t);
        for (a = 0; a < 3; a++) e[a] += m->emission[a] * f;
    }
}
#endif

/* ----- 3.7 cameras */

VOXGI_API void voxgi_camera_frame_bounds(const double lo[3], const double hi[3], voxgi_camera *cam)
{
    /* the unit direction from the centre to the eye: front +Z turned 30 degrees toward +X, 25 up */
    const double yaw = 30 * VOXGI__PI / 180, pitch = 25 * VOXGI__PI / 180;
    double dir[3], c[3], r2 = 0, r, half_y, half, dist;
    int a;
    dir[0] = sin(yaw) * cos(pitch);
    dir[1] = sin(pitch);
    dir[2] = cos(yaw) * cos(pitch);
    for (a = 0; a < 3; a++) {
        c[a] = 0.5 * (lo[a] + hi[a]);
        r2 += 0.25 * (hi[a] - lo[a]) * (hi[a] - lo[a]);
    }
    r = sqrt(r2) > 0 ? sqrt(r2) : 1; /* a point: a unit sphere around it */
    if (!(cam->fovy_degrees > 0 && cam->fovy_degrees < 180)) cam->fovy_degrees = 40;
    half_y = cam->fovy_degrees * VOXGI__PI / 360;
    half = half_y;
    if (cam->width > 0 && cam->height > 0 && cam->width < cam->height) half = atan(tan(half_y) * cam->width / cam->height);
    dist = 1.05 * r / sin(half); /* the sphere touches the narrower half-angle's cone, with 5% to spare */
    for (a = 0; a < 3; a++) {
        cam->target[a] = c[a];
        cam->eye[a] = c[a] + dist * dir[a];
    }
}

/* The camera's frame (gluLookAt, up +Y); fails where the view is along +-Y. */
static voxgi_result voxgi__camera_frame(voxgi_context *ctx, const voxgi_camera *cam, double eye[3], double forward[3], double right[3],
                                        double up[3], double *tan_half)
{
    double len;
    int a;
    if (cam->width < 1 || cam->height < 1 || cam->width > 65536 || cam->height > 65536)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "image %d x %d: each side must be 1..65536", cam->width, cam->height);
    if (!(cam->fovy_degrees > 0 && cam->fovy_degrees < 180)) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "fovy %g: it must lie in (0, 180) degrees", cam->fovy_degrees);
    for (a = 0; a < 3; a++) {
        if (!isfinite(cam->eye[a]) || !isfinite(cam->target[a])) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the camera is not finite");
        eye[a] = cam->eye[a];
        forward[a] = cam->target[a] - cam->eye[a];
    }
    len = sqrt(forward[0] * forward[0] + forward[1] * forward[1] + forward[2] * forward[2]);
    if (!(len > 0) || sqrt(forward[0] * forward[0] + forward[2] * forward[2]) <= 1e-12 * len)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the camera looks along +-Y or at its own eye: up +Y leaves no view");
    for (a = 0; a < 3; a++) forward[a] /= len;
    right[0] = -forward[2]; right[1] = 0; right[2] = forward[0]; /* forward x (0, 1, 0) */
    len = sqrt(right[0] * right[0] + right[2] * right[2]);
    right[0] /= len; right[2] /= len;
    up[0] = right[1] * forward[2] - right[2] * forward[1];
    up[1] = right[2] * forward[0] - right[0] * forward[2];
    up[2] = right[0] * forward[1] - right[1] * forward[0];
    *tan_half = tan(cam->fovy_degrees * VOXGI__PI / 360);
    return VOXGI_OK;
}

/* The unit ray direction through image point (sx, sy) in pixels. */
static void voxgi__camera_ray(const voxgi_camera *cam, const double forward[3], const double right[3], const double up[3], double tan_half,
                              double sx, double sy, double d[3])
{
    double x = (2 * sx / cam->width - 1) * tan_half * cam->width / cam->height, y = (1 - 2 * sy / cam->height) * tan_half, len;
    int a;
    for (a = 0; a < 3; a++) d[a] = forward[a] + x * right[a] + y * up[a];
    len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (a = 0; a < 3; a++) d[a] /= len;
}

/* ===================================================================== 4. GL core */

#ifndef VOXGI_NO_GL

/* GL loader and shaders
   voxgi's own GL types and enums (no GL header needed, none can clash) and a table of exactly
   the functions voxgi calls, filled from the caller's loader; the first missing name is
   reported. voxgi binds programs, shader storage buffers 0..VOXGI__GL_STORAGE_BINDINGS-1, the
   dispatch-indirect buffer, texture units 0..8, image units 0..1, a vertex array and a
   framebuffer while it works and leaves all of them unbound (0) afterwards; the raster passes
   also set the viewport and turn off depth, stencil and scissor tests, culling, blending,
   multisampling and rasterizer discard, and restore each of them. It assumes the default polygon mode (fill) and colour masks. */
#if defined(_WIN32) && !defined(_WIN64) && !defined(__MINGW64__)
#define VOXGI__APIENTRY __stdcall
#else
#define VOXGI__APIENTRY
#endif
#define VOXGI__GL_RENDERER 0x1F01
#define VOXGI__GL_VERSION 0x1F02
#define VOXGI__GL_MAJOR_VERSION 0x821B
#define VOXGI__GL_MINOR_VERSION 0x821C
#define VOXGI__GL_COMPUTE_SHADER 0x91B9
#define VOXGI__GL_VERTEX_SHADER 0x8B31
#define VOXGI__GL_FRAGMENT_SHADER 0x8B30
#define VOXGI__GL_GEOMETRY_SHADER 0x8DD9
#define VOXGI__GL_COMPILE_STATUS 0x8B81
#define VOXGI__GL_LINK_STATUS 0x8B82
#define VOXGI__GL_INFO_LOG_LENGTH 0x8B84
#define VOXGI__GL_SHADER_STORAGE_BUFFER 0x90D2
#define VOXGI__GL_DISPATCH_INDIRECT_BUFFER 0x90EE
#define VOXGI__GL_MAX_SHADER_STORAGE_BLOCK_SIZE 0x90DE
#define VOXGI__GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS 0x90DB
#define VOXGI__GL_DYNAMIC_COPY 0x88EA
#define VOXGI__GL_STATIC_DRAW 0x88E4
#define VOXGI__GL_SHADER_STORAGE_BARRIER_BIT 0x2000
#define VOXGI__GL_COMMAND_BARRIER_BIT 0x0040
#define VOXGI__GL_BUFFER_UPDATE_BARRIER_BIT 0x0200
#define VOXGI__GL_R32UI 0x8236
#define VOXGI__GL_READ_ONLY 0x88B8
#define VOXGI__GL_MAX_ARRAY_TEXTURE_LAYERS 0x88FF
#define VOXGI__GL_RED_INTEGER 0x8D94
#define VOXGI__GL_UNSIGNED_INT 0x1405
#define VOXGI__GL_OUT_OF_MEMORY 0x0505
#define VOXGI__GL_TEXTURE_2D_ARRAY 0x8C1A
#define VOXGI__GL_TEXTURE_MIN_FILTER 0x2801
#define VOXGI__GL_TEXTURE_MAG_FILTER 0x2800
#define VOXGI__GL_NEAREST 0x2600
#define VOXGI__GL_RGBA32UI 0x8D70
#define VOXGI__GL_RGBA_INTEGER 0x8D99
#define VOXGI__GL_RGBA 0x1908
#define VOXGI__GL_RED 0x1903
#define VOXGI__GL_FLOAT 0x1406
#define VOXGI__GL_RGBA32F 0x8814
#define VOXGI__GL_RGBA16F 0x881A
#define VOXGI__GL_DEPTH_COMPONENT32F 0x8CAC
#define VOXGI__GL_DEPTH_COMPONENT 0x1902
#define VOXGI__GL_DEPTH_ATTACHMENT 0x8D00
#define VOXGI__GL_DEPTH_FUNC 0x0B74
#define VOXGI__GL_DEPTH_WRITEMASK 0x0B72
#define VOXGI__GL_LESS 0x0201
#define VOXGI__GL_R32F 0x822E
#define VOXGI__GL_TEXTURE_3D 0x806F
#define VOXGI__GL_TEXTURE_WRAP_S 0x2802
#define VOXGI__GL_TEXTURE_WRAP_T 0x2803
#define VOXGI__GL_TEXTURE_WRAP_R 0x8072
#define VOXGI__GL_CLAMP_TO_BORDER 0x812D
#define VOXGI__GL_TEXTURE_BORDER_COLOR 0x1004
#define VOXGI__GL_LINEAR 0x2601
#define VOXGI__GL_LINEAR_MIPMAP_LINEAR 0x2703
#define VOXGI__GL_WRITE_ONLY 0x88B9
#define VOXGI__GL_TEXTURE_UPDATE_BARRIER_BIT 0x0100
#define VOXGI__GL_MAX_3D_TEXTURE_SIZE 0x8073
#define VOXGI__GL_ONE 1
#define VOXGI__GL_FUNC_ADD 0x8006
#define VOXGI__GL_MAX 0x8008
#define VOXGI__GL_BLEND_SRC_RGB 0x80C9
#define VOXGI__GL_BLEND_DST_RGB 0x80C8
#define VOXGI__GL_BLEND_SRC_ALPHA 0x80CB
#define VOXGI__GL_BLEND_DST_ALPHA 0x80CA
#define VOXGI__GL_BLEND_EQUATION_RGB 0x8009
#define VOXGI__GL_BLEND_EQUATION_ALPHA 0x883D
#define VOXGI__GL_FRAMEBUFFER 0x8D40
#define VOXGI__GL_COLOR_ATTACHMENT0 0x8CE0
#define VOXGI__GL_FRAMEBUFFER_COMPLETE 0x8CD5
#define VOXGI__GL_FRAMEBUFFER_DEFAULT_WIDTH 0x9310
#define VOXGI__GL_FRAMEBUFFER_DEFAULT_HEIGHT 0x9311
#define VOXGI__GL_FRAMEBUFFER_DEFAULT_LAYERS 0x9312
#define VOXGI__GL_COLOR_LOGIC_OP 0x0BF2
#define VOXGI__GL_OR 0x1507
#define VOXGI__GL_TRIANGLES 0x0004
#define VOXGI__GL_POINTS 0x0000
#define VOXGI__GL_PROGRAM_POINT_SIZE 0x8642
#define VOXGI__GL_TEXTURE_2D 0x0DE1
#define VOXGI__GL_READ_WRITE 0x88BA
#define VOXGI__GL_VIEWPORT 0x0BA2
#define VOXGI__GL_MAX_DRAW_BUFFERS 0x8824
#define VOXGI__GL_MAX_TEXTURE_SIZE 0x0D33
#define VOXGI__GL_MAX_FRAMEBUFFER_WIDTH 0x9315
#define VOXGI__GL_DEPTH_TEST 0x0B71
#define VOXGI__GL_CULL_FACE 0x0B44
#define VOXGI__GL_BLEND 0x0BE2
#define VOXGI__GL_SCISSOR_TEST 0x0C11
#define VOXGI__GL_STENCIL_TEST 0x0B90
#define VOXGI__GL_RASTERIZER_DISCARD 0x8C89
#define VOXGI__GL_MULTISAMPLE 0x809D
#define VOXGI__GL_SHADER_IMAGE_ACCESS_BARRIER_BIT 0x0020
#define VOXGI__GL_TEXTURE_FETCH_BARRIER_BIT 0x0008
#define VOXGI__GL_FRAMEBUFFER_BARRIER_BIT 0x0400

/* X(return type, name without the gl prefix, parameters) */
#define VOXGI__GL_FUNCS(X)                                                                               \
    X(const unsigned char *, GetString, (unsigned int name))                                             \
    X(void, GetIntegerv, (unsigned int pname, int *data))                                                \
    X(void, GetInteger64v, (unsigned int pname, int64_t *data))                                          \
    X(unsigned int, GetError, (void))                                                                    \
    X(unsigned int, CreateShader, (unsigned int type))                                                   \
    X(void, ShaderSource, (unsigned int shader, int count, const char *const *string, const int *length)) \
    X(void, CompileShader, (unsigned int shader))                                                        \
    X(void, GetShaderiv, (unsigned int shader, unsigned int pname, int *params))                         \
    X(void, GetShaderInfoLog, (unsigned int shader, int size, int *length, char *log))                   \
    X(unsigned int, CreateProgram, (void))                                                               \
    X(void, AttachShader, (unsigned int program, unsigned int shader))                                   \
    X(void, LinkProgram, (unsigned int program))                                                         \
    X(void, GetProgramiv, (unsigned int program, unsigned int pname, int *params))                       \
    X(void, GetProgramInfoLog, (unsigned int program, int size, int *length, char *log))                 \
    X(void, DeleteShader, (unsigned int shader))                                                         \
    X(void, DeleteProgram, (unsigned int program))                                                       \
    X(void, UseProgram, (unsigned int program))                                                          \
    X(void, ProgramUniform1i, (unsigned int program, int location, int v0))                              \
    X(void, ProgramUniform1ui, (unsigned int program, int location, unsigned int v0))                    \
    X(void, ProgramUniform3i, (unsigned int program, int location, int v0, int v1, int v2))              \
    X(void, ProgramUniform1f, (unsigned int program, int location, float v0))                            \
    X(void, ProgramUniform3f, (unsigned int program, int location, float v0, float v1, float v2))        \
    X(void, ProgramUniform2f, (unsigned int program, int location, float v0, float v1))                  \
    X(void, DepthFunc, (unsigned int func))                                                              \
    X(void, DepthMask, (unsigned char flag))                                                             \
    X(void, ProgramUniform2i, (unsigned int program, int location, int v0, int v1))                     \
    X(void, ProgramUniform4i, (unsigned int program, int location, int v0, int v1, int v2, int v3))     \
    X(void, ProgramUniform1d, (unsigned int program, int location, double v0))                           \
    X(void, ProgramUniform3d, (unsigned int program, int location, double v0, double v1, double v2))     \
    X(void, CreateBuffers, (int n, unsigned int *buffers))                                               \
    X(void, DeleteBuffers, (int n, const unsigned int *buffers))                                         \
    X(void, NamedBufferData, (unsigned int buffer, ptrdiff_t size, const void *data, unsigned int usage)) \
    X(void, NamedBufferSubData, (unsigned int buffer, ptrdiff_t offset, ptrdiff_t size, const void *data)) \
    X(void, GetNamedBufferSubData, (unsigned int buffer, ptrdiff_t offset, ptrdiff_t size, void *data))  \
    X(void, ClearNamedBufferData, (unsigned int buffer, unsigned int internalformat, unsigned int format, \
                                   unsigned int type, const void *data))                                 \
    X(void, BindBufferBase, (unsigned int target, unsigned int index, unsigned int buffer))              \
    X(void, BindBuffer, (unsigned int target, unsigned int buffer))                                      \
    X(void, DispatchCompute, (unsigned int x, unsigned int y, unsigned int z))                           \
    X(void, DispatchComputeIndirect, (ptrdiff_t indirect))                                               \
    X(void, CopyNamedBufferSubData, (unsigned int read, unsigned int write, ptrdiff_t read_offset,        \
                                     ptrdiff_t write_offset, ptrdiff_t size))                            \
    X(void, Finish, (void))                                                                              \
    X(void, MemoryBarrier, (unsigned int barriers))                                                      \
    X(void, CreateVertexArrays, (int n, unsigned int *arrays))                                           \
    X(void, DeleteVertexArrays, (int n, const unsigned int *arrays))                                     \
    X(void, BindVertexArray, (unsigned int array))                                                       \
    X(void, CreateFramebuffers, (int n, unsigned int *framebuffers))                                     \
    X(void, DeleteFramebuffers, (int n, const unsigned int *framebuffers))                               \
    X(void, BindFramebuffer, (unsigned int target, unsigned int framebuffer))                            \
    X(void, NamedFramebufferTextureLayer, (unsigned int fb, unsigned int attachment, unsigned int texture, \
                                           int level, int layer))                                        \
    X(void, NamedFramebufferDrawBuffers, (unsigned int fb, int n, const unsigned int *buffers))          \
    X(void, NamedFramebufferParameteri, (unsigned int fb, unsigned int pname, int param))                \
    X(unsigned int, CheckNamedFramebufferStatus, (unsigned int fb, unsigned int target))                 \
    X(void, CreateTextures, (unsigned int target, int n, unsigned int *textures))                        \
    X(void, DeleteTextures, (int n, const unsigned int *textures))                                       \
    X(void, TextureStorage3D, (unsigned int texture, int levels, unsigned int format, int w, int h, int d)) \
    X(void, TextureSubImage3D, (unsigned int texture, int level, int x, int y, int z, int w, int h, int d,  \
                                unsigned int format, unsigned int type, const void *pixels))            \
    X(void, GetTextureSubImage, (unsigned int texture, int level, int x, int y, int z, int w, int h, int d, \
                                 unsigned int format, unsigned int type, int size, void *pixels))       \
    X(void, TextureStorage2D, (unsigned int texture, int levels, unsigned int format, int w, int h))       \
    X(void, NamedFramebufferTexture, (unsigned int fb, unsigned int attachment, unsigned int texture, int level)) \
    X(void, ClearTexImage, (unsigned int texture, int level, unsigned int format, unsigned int type,      \
                            const void *data))                                                           \
    X(void, BindImageTexture, (unsigned int unit, unsigned int texture, int level, unsigned char layered, \
                               int layer, unsigned int access, unsigned int format))                     \
    X(void, BindTextureUnit, (unsigned int unit, unsigned int texture))                                  \
    X(void, TextureParameteri, (unsigned int texture, unsigned int pname, int param))                    \
    X(void, TextureParameterfv, (unsigned int texture, unsigned int pname, const float *params))          \
    X(void, Viewport, (int x, int y, int width, int height))                                             \
    X(void, Enable, (unsigned int cap))                                                                  \
    X(void, Enablei, (unsigned int cap, unsigned int index))                                             \
    X(void, Disablei, (unsigned int cap, unsigned int index))                                            \
    X(unsigned char, IsEnabledi, (unsigned int cap, unsigned int index))                                 \
    X(void, GetIntegeri_v, (unsigned int pname, unsigned int index, int *data))                          \
    X(void, BlendFuncSeparatei, (unsigned int buf, unsigned int src_rgb, unsigned int dst_rgb,           \
                                 unsigned int src_alpha, unsigned int dst_alpha))                        \
    X(void, BlendEquationSeparatei, (unsigned int buf, unsigned int mode_rgb, unsigned int mode_alpha))  \
    X(void, Disable, (unsigned int cap))                                                                 \
    X(unsigned char, IsEnabled, (unsigned int cap))                                                      \
    X(void, LogicOp, (unsigned int opcode))                                                              \
    X(void, DrawArrays, (unsigned int mode, int first, int count))

/* Every program voxgi builds: X(name, stages, its embedded shader files in order). Stages:
   COMPUTE; RASTER (vertex + fragment); GEOMETRY (vertex + geometry + fragment). Each file is
   compiled once per stage, with VOXGI_COMPUTE, VOXGI_VERTEX, ... defined for the stage. A part
   left out takes its rows with it (VOXGI__GL_WITH_<part>: the rows, or nothing), as shaders.h
   its files ("embedded unless" in each). */
#ifndef VOXGI_NO_OCTREE
#define VOXGI__GL_WITH_OCTREE(rows) rows
#else
#define VOXGI__GL_WITH_OCTREE(rows)
#endif
#ifndef VOXGI_NO_CONE_TRACING
#define VOXGI__GL_WITH_CONE_TRACING(rows) rows
#else
#define VOXGI__GL_WITH_CONE_TRACING(rows)
#endif
#ifndef VOXGI_NO_LIGHT_INJECTION
#define VOXGI__GL_WITH_LIGHT_INJECTION(rows) rows
#else
#define VOXGI__GL_WITH_LIGHT_INJECTION(rows)
#endif
#ifndef VOXGI_NO_LIGHT_SPACE
#define VOXGI__GL_WITH_LIGHT_SPACE(rows) rows
#else
#define VOXGI__GL_WITH_LIGHT_SPACE(rows)
#endif
#ifndef VOXGI_NO_SCREEN_SPACE
#define VOXGI__GL_WITH_SCREEN_SPACE(rows) rows
#else
#define VOXGI__GL_WITH_SCREEN_SPACE(rows)
#endif
#ifndef VOXGI_NO_LINE_SPACE
#define VOXGI__GL_WITH_LINE_SPACE(rows) rows
#else
#define VOXGI__GL_WITH_LINE_SPACE(rows)
#endif
#define VOXGI__GL_PROGRAMS(X)                                                                                        \
    X(voxelize_conservative, COMPUTE, "scene.glsl triangle.glsl conservative.glsl voxelize_conservative.glsl")      \
    X(voxelize_geometry, GEOMETRY, "scene.glsl triangle.glsl conservative.glsl voxelize_geometry.glsl")            \
    X(voxelize_solid, COMPUTE, "scene.glsl triangle.glsl voxelize_solid.glsl")                                     \
    X(solid_prefix, COMPUTE, "solid_prefix.glsl")                                                                  \
    X(flood, COMPUTE, "flood.glsl")                                                                                \
    X(bits_majority, COMPUTE, "bits_majority.glsl")                                                                \
    X(popcount, COMPUTE, "popcount.glsl")                                                                          \
    X(slicemap, RASTER, "scene.glsl slice_targets.glsl slicemap.glsl")                                             \
    X(slicemap_unpack, COMPUTE, "slicemap_unpack.glsl")                                                            \
    X(volume_buffer, GEOMETRY, "scene.glsl volume_buffer.glsl")                                                    \
    X(volume_buffer_big, GEOMETRY, "scene.glsl volume_buffer_big.glsl volume_buffer.glsl")                         \
    X(volume_merge, COMPUTE, "scene.glsl volume_merge.glsl")                                                       \
    X(atlas_fill, RASTER, "scene.glsl atlas.glsl atlas_fill.glsl")                                                 \
    X(atlas_list, COMPUTE, "scene.glsl atlas.glsl atlas_list.glsl")                                                \
    X(atlas_points, RASTER, "scene.glsl atlas.glsl slice_targets.glsl atlas_points.glsl")                          \
    X(atlas_compute, COMPUTE, "scene.glsl atlas.glsl atlas_compute.glsl")                                          \
    X(reduce, COMPUTE, "reduce.glsl")                                                                              \
    X(volume_mip, COMPUTE, "volume_mip.glsl")                                                                      \
    X(volume_sample, COMPUTE, "sampling.glsl volume_sample.glsl")                                                  \
    VOXGI__GL_WITH_OCTREE(                                                                                         \
        X(svo_build, COMPUTE, "svo.glsl svo_build.glsl")                                                           \
        X(svo_sample, COMPUTE, "sampling.glsl svo.glsl svo_sample.glsl"))                                          \
    VOXGI__GL_WITH_CONE_TRACING(                                                                                   \
        X(cone_trace, COMPUTE, "sampling.glsl cone_trace.glsl cone_trace_buffers.glsl")                            \
        VOXGI__GL_WITH_OCTREE(X(cone_trace_svo, COMPUTE,                                                           \
          "sampling.glsl cone_svo.glsl svo.glsl cone_trace.glsl cone_trace_buffers.glsl"))                         \
        X(cone_trace_images16, COMPUTE, "sampling.glsl cone_trace.glsl out_rgba16f.glsl cone_trace_images.glsl")   \
        X(cone_trace_images32, COMPUTE, "sampling.glsl cone_trace.glsl out_rgba32f.glsl cone_trace_images.glsl")   \
        VOXGI__GL_WITH_OCTREE(X(cone_trace_svo_images16, COMPUTE,                                                  \
          "sampling.glsl cone_svo.glsl svo.glsl cone_trace.glsl out_rgba16f.glsl cone_trace_images.glsl")          \
                              X(cone_trace_svo_images32, COMPUTE,                                                  \
          "sampling.glsl cone_svo.glsl svo.glsl cone_trace.glsl out_rgba32f.glsl cone_trace_images.glsl")))        \
    VOXGI__GL_WITH_LIGHT_INJECTION(                                                                                \
        X(light_map_draw, RASTER, "sampling.glsl light_maps.glsl light_map_draw.glsl")                             \
        X(inject, COMPUTE, "sampling.glsl light_maps.glsl inject.glsl"))                                           \
    X(gbuffer, RASTER, "gbuffer.glsl")                                                                             \
    VOXGI__GL_WITH_LIGHT_SPACE(X(tsm_lookup, COMPUTE, "tsm_lookup.glsl")                                           \
                               X(rsm_gather, COMPUTE, "voxel_traverse.glsl point_gather.glsl rsm_gather.glsl")     \
                               X(sh_gather, COMPUTE, "voxel_traverse.glsl point_gather.glsl sh_gather.glsl"))      \
    VOXGI__GL_WITH_SCREEN_SPACE(X(screen_rays, COMPUTE, "voxel_traverse.glsl screen_rays.glsl")                    \
                                X(screen_filter, COMPUTE, "screen_filter.glsl"))                                   \
    VOXGI__GL_WITH_LINE_SPACE(X(linespace, COMPUTE, "linespace.glsl linespace_light.glsl")                         \
                              X(linespace_rays, COMPUTE, "linespace.glsl linespace_rays.glsl"))

enum { VOXGI__GL_COMPUTE = 0, VOXGI__GL_RASTER = 1, VOXGI__GL_GEOMETRY = 2 };
typedef enum voxgi__gl_program_id {
#define VOXGI__GL_PROGRAM_ID(name, stages, files) VOXGI__GL_PROGRAM_##name,
    VOXGI__GL_PROGRAMS(VOXGI__GL_PROGRAM_ID)
#undef VOXGI__GL_PROGRAM_ID
    VOXGI__GL_PROGRAM_COUNT
} voxgi__gl_program_id;

/* Every uniform a shader declares, by name: its location is its place in this list, the same
   in every program (explicit locations, GL 4.3), given to the shaders as VOXGI_LOC_<name> in the
   prelude, so that no location is looked up by name at run time. */
#define VOXGI__GL_UNIFORMS(X) \
    X(u_anisotropic) X(u_atomic) X(u_attr) X(u_attributes) X(u_axis) X(u_back_coverage) X(u_bias) X(u_big)       \
    X(u_bits_part) X(u_blend) X(u_caster) X(u_casters) X(u_cell_levels) X(u_cells) X(u_centre) X(u_channels) X(u_cones) X(u_corner) X(u_count) X(u_depth) \
    X(u_dir) X(u_dst_dims) X(u_dst_res) X(u_edge_u) X(u_edge_v) X(u_eye)                                              \
    X(u_face) X(u_factor) X(u_far) X(u_fast) X(u_first) X(u_first_slice) X(u_forward) X(u_gather) X(u_hair) X(u_half) X(u_half_tan) \
    X(u_has_albedo) X(u_hidden)                                                                                       \
    X(u_hierarchical) X(u_image) X(u_inv_s) X(u_level) X(u_levels) X(u_light_normal) X(u_lookup) X(u_maps) X(u_max_channels) \
    X(u_max_distance) X(u_max_lod) X(u_n)                                                                             \
    X(u_near) X(u_near_ends) X(u_offset) X(u_op) X(u_opening) X(u_origin) X(u_pair_capacity) X(u_pass) X(u_per_layer) X(u_point_sampling) X(u_premultiplied) X(u_radius) X(u_rays)     \
    X(u_regions) X(u_res) X(u_right) X(u_samples) X(u_scale) X(u_seed) X(u_seen_from_eye) X(u_single) X(u_size) X(u_slicing) X(u_solid_axis) X(u_src_dims) \
    X(u_src_level)                                                                                                    \
    X(u_src_res) X(u_step) X(u_steps) X(u_svo_bricks) X(u_svo_depth) X(u_svo_format) X(u_svo_inner_tiles) X(u_svo_leaf_first) \
    X(u_svo_nodes) X(u_svo_single) X(u_tan) X(u_thin) X(u_through_voxels) X(u_triangle) X(u_tri_count) X(u_tri_offset) X(u_two_sided) X(u_up) \
    X(u_view) X(u_voxel_size) X(u_with_values) X(u_words)
enum {
#define VOXGI__GL_UNIFORM_LOCATION(name) VOXGI__LOC_##name,
    VOXGI__GL_UNIFORMS(VOXGI__GL_UNIFORM_LOCATION)
#undef VOXGI__GL_UNIFORM_LOCATION
    VOXGI__GL_UNIFORM_COUNT
};

/* The storage bindings of the shader snippets several programs share (scene.glsl, triangle.glsl,
   conservative.glsl, svo.glsl), by role: given to the shaders as VOXGI_BINDING_<role> in the
   prelude, used by name in C. A program's own buffers are numbered in its file, clear of these. */
#define VOXGI__GL_BINDINGS(X)                                                                                 \
    X(VERTICES, 0) X(TRIANGLES, 1) X(BITS, 2) X(CONTROL, 3) X(PAIRS, 4) X(FLAGS, 5) X(BIG, 6)                  \
    X(RANK, 7) X(RECORDS, 8) X(SUMS, 9) X(SVO_CHILD, 0) X(SVO_VALUES, 1) X(SVO_BACK_VALUES, 2)     \
    X(SVO_SIDE_VALUES, 6)
enum {
#define VOXGI__GL_BINDING_NUMBER(role, number) VOXGI__BINDING_##role = number,
    VOXGI__GL_BINDINGS(VOXGI__GL_BINDING_NUMBER)
#undef VOXGI__GL_BINDING_NUMBER
    VOXGI__GL_BINDING_ROLES_END
};

struct voxgi__gl {
#define VOXGI__GL_MEMBER(ret, name, args) ret(VOXGI__APIENTRY *name) args;
    VOXGI__GL_FUNCS(VOXGI__GL_MEMBER)
#undef VOXGI__GL_MEMBER
#define VOXGI__GL_PROGRAM_MEMBER(name, stages, files) unsigned int prog_##name;
    VOXGI__GL_PROGRAMS(VOXGI__GL_PROGRAM_MEMBER)
#undef VOXGI__GL_PROGRAM_MEMBER
    int64_t max_ssbo_bytes;
    int max_compute_ssbo_blocks;  /* storage blocks a compute shader may use */
    char prelude_names[VOXGI__GL_UNIFORM_COUNT * 48 + 1024]; /* "#define VOXGI_LOC_<uniform> <location>" and
                                                               "#define VOXGI_BINDING_<role> <binding>" lines */
};

/* where the compiler can tell (C23, C++17, GCC 5 and Clang before them), a missing shaders.h says what to do */
#if defined(__has_include)
#if __has_include("shaders.h")
#include "shaders.h"
#else
#error "voxgi.h: shaders.h (the embedded GLSL) is not beside voxgi.h: copy shaders.h next to voxgi.h (or run make shaders.h), or define VOXGI_NO_GL to build the CPU backend alone"
#endif
#else
#include "shaders.h"
#endif

static voxgi_gl_proc voxgi__gl_lookup(voxgi_context *ctx, const char *name)
{
    if (ctx->desc.gl_get_proc_address_user) return ctx->desc.gl_get_proc_address_user(name, ctx->desc.gl_user);
    return ctx->desc.gl_get_proc_address(name);
}

/* 1 when a GL_RENDERER string names a software rasterizer: one that runs on the CPU's own cores,
   where voxgi's CPU backend does the same work several times faster (AUTO then picks the CPU).
   Matched case-insensitively anywhere in the string: Mesa's llvmpipe, softpipe and swrast
   ("Software Rasterizer"), Google's SwiftShader, and WARP ("Microsoft Basic Render Driver",
   e.g. under Mesa's D3D12 driver). GL_VENDOR adds nothing: these vendors also ship GPUs. */
static int voxgi__gl_is_software(const char *renderer)
{
    static const char *const names[] = {"llvmpipe", "softpipe", "swrast", "software rasterizer", "swiftshader",
                                        "microsoft basic render driver"};
    size_t k, i, j;
    for (k = 0; k < sizeof names / sizeof names[0]; k++)
        for (i = 0; renderer[i]; i++) {
            for (j = 0; names[k][j]; j++) {
                char c = renderer[i + j]; /* ASCII lower case, whatever the locale */
                if ((c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c) != names[k][j]) break;
            }
            if (!names[k][j]) return 1;
        }
    return 0;
}

static voxgi_result voxgi__gl_init(voxgi_context *ctx)
{
    static const char *const uniforms[VOXGI__GL_UNIFORM_COUNT] = {
#define VOXGI__GL_UNIFORM_NAME(name) #name,
        VOXGI__GL_UNIFORMS(VOXGI__GL_UNIFORM_NAME)
#undef VOXGI__GL_UNIFORM_NAME
    };
    voxgi__gl *gl;
    int major = 0, minor = 0, u;
    size_t at = 0;
    const char *s;
    if (!ctx->desc.gl_get_proc_address && !ctx->desc.gl_get_proc_address_user)
        return voxgi__fail(ctx, VOXGI_ERR_GL_UNAVAILABLE, "no GL loader given (desc.gl_get_proc_address)");
    gl = (voxgi__gl *)voxgi__alloc_array(ctx, 1, sizeof *gl, 1);
    if (!gl) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the GL state");
    ctx->gl = gl;
#define VOXGI__GL_LOAD(ret, name, args)                                                                   \
    gl->name = (ret(VOXGI__APIENTRY *) args)voxgi__gl_lookup(ctx, "gl" #name);                            \
    if (!gl->name) return voxgi__fail(ctx, VOXGI_ERR_GL_MISSING_FUNCTION, "the GL loader has no gl" #name);
    VOXGI__GL_FUNCS(VOXGI__GL_LOAD)
#undef VOXGI__GL_LOAD
    s = (const char *)gl->GetString(VOXGI__GL_VERSION);
    if (!s) return voxgi__fail(ctx, VOXGI_ERR_GL_UNAVAILABLE, "no GL context is current (glGetString returned NULL)");
    snprintf(ctx->gl_version, sizeof ctx->gl_version, "%s", s);
    s = (const char *)gl->GetString(VOXGI__GL_RENDERER);
    snprintf(ctx->gl_renderer, sizeof ctx->gl_renderer, "%s", s ? s : "");
    ctx->gl_software = voxgi__gl_is_software(ctx->gl_renderer);
    gl->GetIntegerv(VOXGI__GL_MAJOR_VERSION, &major);
    gl->GetIntegerv(VOXGI__GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45)
        return voxgi__fail(ctx, VOXGI_ERR_GL_UNAVAILABLE, "GL %d.%d is current, voxgi needs 4.5 (%s)", major, minor, ctx->gl_version);
    gl->GetInteger64v(VOXGI__GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &gl->max_ssbo_bytes);
    gl->GetIntegerv(VOXGI__GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, &gl->max_compute_ssbo_blocks);
    for (u = 0; u < VOXGI__GL_UNIFORM_COUNT; u++)
        at += (size_t)snprintf(gl->prelude_names + at, sizeof gl->prelude_names - at, "#define VOXGI_LOC_%s %d\n", uniforms[u], u);
#define VOXGI__GL_BINDING_DEFINE(role, number) \
    at += (size_t)snprintf(gl->prelude_names + at, sizeof gl->prelude_names - at, "#define VOXGI_BINDING_" #role " %d\n", number);
    VOXGI__GL_BINDINGS(VOXGI__GL_BINDING_DEFINE)
#undef VOXGI__GL_BINDING_DEFINE
    while (gl->GetError() != 0) {}
    return VOXGI_OK; /* voxgi_create logs the backend it picks */
}

static void voxgi__gl_shutdown(voxgi_context *ctx)
{
    voxgi__gl *gl = ctx->gl;
    if (!gl) return;
    if (gl->DeleteProgram) {
#define VOXGI__GL_PROGRAM_DELETE(name, stages, files) if (gl->prog_##name) gl->DeleteProgram(gl->prog_##name);
        VOXGI__GL_PROGRAMS(VOXGI__GL_PROGRAM_DELETE)
#undef VOXGI__GL_PROGRAM_DELETE
    }
    voxgi__free(ctx, gl);
    ctx->gl = NULL;
}

/* Each file of a program starts at line 10000 * (its position + 1) + 1 (#line), which every
   driver reports whatever it does with source-string numbers. This rewrites the locations
   "0:LINE(COL)" (Mesa) or "0(LINE)" (others) at the start of each log line as "file.glsl:LINE". */
#define VOXGI__GL_LINES_PER_FILE 10000
static void voxgi__gl_map_log(const char *log, int count, const char *const *files, char *out, size_t out_size)
{
    size_t n = 0;
    int line_start = 1;
    while (*log && n + 1 < out_size) {
        if (line_start && *log >= '0' && *log <= '9') {
            const char *p = log;
            int line = -1;
            while (*p >= '0' && *p <= '9') p++;
            if (*p == ':' && p[1] >= '0' && p[1] <= '9') { /* N:LINE(COL) */
                line = atoi(p + 1);
                for (p++; *p >= '0' && *p <= '9'; p++) {}
                if (*p == '(') { while (*p && *p != ')') p++; if (*p) p++; }
            } else if (*p == '(' && p[1] >= '0' && p[1] <= '9') { /* N(LINE) */
                line = atoi(p + 1);
                while (*p && *p != ')') p++;
                if (*p) p++;
            }
            if (line >= 0) {
                int k = line / VOXGI__GL_LINES_PER_FILE - 1, w;
                if (k >= 0 && k < count) w = snprintf(out + n, out_size - n, "%s:%d", files[k], line - (k + 1) * VOXGI__GL_LINES_PER_FILE);
                else w = snprintf(out + n, out_size - n, "(prelude):%d", line);
                n = w < 0 ? n : VOXGI__MIN(out_size - 1, n + (size_t)w);
                log = p;
                line_start = 0;
                continue;
            }
        }
        line_start = *log == '\n';
        out[n++] = *log++;
    }
    out[n] = 0;
}

/* Compiles and attaches one stage: the runtime prelude (#version, defines, the stage's
   VOXGI_COMPUTE / VOXGI_VERTEX / VOXGI_FRAGMENT), then the files in order. */
static voxgi_result voxgi__gl_stage(voxgi_context *ctx, unsigned int prog, unsigned int type, const char *define, int count,
                                    const char *const *files, const char *const *texts)
{
    voxgi__gl *gl = ctx->gl;
    const char *src[2 * 8 + 3];
    char lines[8][32];
    unsigned int sh;
    int ok = 0, len = 0, k;
    src[0] = "#version 450 core\n"
             "#define VOXGI_LOCAL_SIZE 64\n"
             "#define VOXGI_SMALL_COLUMNS 64\n"; /* columns one invocation handles alone */
    src[1] = gl->prelude_names;
    src[2] = define;
    for (k = 0; k < count; k++) {
        snprintf(lines[k], sizeof lines[k], "\n#line %d\n", (k + 1) * VOXGI__GL_LINES_PER_FILE + 1);
        src[3 + 2 * k] = lines[k];
        src[4 + 2 * k] = texts[k];
    }
    sh = gl->CreateShader(type);
    gl->ShaderSource(sh, 3 + 2 * count, src, NULL);
    gl->CompileShader(sh);
    gl->GetShaderiv(sh, VOXGI__GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[3000], mapped[3600];
        gl->GetShaderInfoLog(sh, (int)sizeof log, &len, log);
        log[VOXGI__MIN(VOXGI__MAX(len, 0), (int)sizeof log - 1)] = 0;
        gl->DeleteShader(sh);
        voxgi__gl_map_log(log, count, files, mapped, sizeof mapped);
        return voxgi__fail(ctx, VOXGI_ERR_GL_SHADER, "%s", mapped);
    }
    gl->AttachShader(prog, sh);
    gl->DeleteShader(sh); /* freed with the program */
    return VOXGI_OK;
}

/* A compute program, or (graphics) a vertex + fragment program, from the given files. */
static voxgi_result voxgi__gl_program(voxgi_context *ctx, int graphics, int count, const char *const *files,
                                      const char *const *texts, unsigned int *out)
{
    voxgi__gl *gl = ctx->gl;
    unsigned int prog;
    int ok = 0, len = 0;
    voxgi_result r;
    if (count < 1 || count > 8) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "a program has 1 to 8 files");
    prog = gl->CreateProgram();
    if (graphics) {
        r = voxgi__gl_stage(ctx, prog, VOXGI__GL_VERTEX_SHADER, "#define VOXGI_VERTEX\n", count, files, texts);
        if (r == VOXGI_OK && graphics == 2)
            r = voxgi__gl_stage(ctx, prog, VOXGI__GL_GEOMETRY_SHADER, "#define VOXGI_GEOMETRY\n", count, files, texts);
        if (r == VOXGI_OK) r = voxgi__gl_stage(ctx, prog, VOXGI__GL_FRAGMENT_SHADER, "#define VOXGI_FRAGMENT\n", count, files, texts);
    } else r = voxgi__gl_stage(ctx, prog, VOXGI__GL_COMPUTE_SHADER, "#define VOXGI_COMPUTE\n", count, files, texts);
    if (r != VOXGI_OK) { gl->DeleteProgram(prog); return r; }
    gl->LinkProgram(prog);
    gl->GetProgramiv(prog, VOXGI__GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[3000];
        gl->GetProgramInfoLog(prog, (int)sizeof log, &len, log);
        log[VOXGI__MIN(VOXGI__MAX(len, 0), (int)sizeof log - 1)] = 0;
        gl->DeleteProgram(prog);
        return voxgi__fail(ctx, VOXGI_ERR_GL_SHADER, "%s: link failed: %s", files[count - 1], log);
    }
    *out = prog;
    return VOXGI_OK;
}

/* Program `id` of the table, compiled and linked on first use (the name is kept in the
   context's prog_<name>, which the passes then read). */
static voxgi_result voxgi__gl_get_program(voxgi_context *ctx, voxgi__gl_program_id id)
{
    static const struct { int stages; const char *files; size_t member; } table[VOXGI__GL_PROGRAM_COUNT] = {
#define VOXGI__GL_PROGRAM_ROW(name, stages, files) {VOXGI__GL_##stages, files, offsetof(voxgi__gl, prog_##name)},
        VOXGI__GL_PROGRAMS(VOXGI__GL_PROGRAM_ROW)
#undef VOXGI__GL_PROGRAM_ROW
    };
    unsigned int *prog = (unsigned int *)(void *)((char *)ctx->gl + table[id].member);
    const char *files[8], *texts[8];
    char names[8][64];
    int count = 0, i;
    const char *p = table[id].files;
    if (*prog) return VOXGI_OK;
    while (*p && count < 8) {
        size_t len = strcspn(p, " ");
        if (len >= sizeof names[0]) len = sizeof names[0] - 1;
        memcpy(names[count], p, len);
        names[count][len] = 0;
        files[count] = names[count];
        texts[count] = NULL;
        for (i = 0; i < VOXGI__GLSL_FILE_COUNT; i++)
            if (strcmp(voxgi__glsl_files[i].name, names[count]) == 0) texts[count] = (const char *)voxgi__glsl_files[i].text;
        if (!texts[count])
            return voxgi__fail(ctx, VOXGI_ERR_GL_SHADER, "%s is not among the embedded shaders (shaders.h is stale)", names[count]);
        count++;
        p += strcspn(p, " ");
        while (*p == ' ') p++;
    }
    return voxgi__gl_program(ctx, table[id].stages, count, files, texts, prog);
}

static unsigned int voxgi__gl_buffer(voxgi_context *ctx, size_t bytes, const void *data)
{
    unsigned int b = 0;
    ctx->gl->CreateBuffers(1, &b);
    ctx->gl->NamedBufferData(b, (ptrdiff_t)(bytes ? bytes : 4), data, VOXGI__GL_DYNAMIC_COPY);
    return b;
}

static void voxgi__gl_delete_buffer(voxgi_context *ctx, unsigned int buffer)
{
    if (ctx->gl && buffer) ctx->gl->DeleteBuffers(1, &buffer);
}

static voxgi_result voxgi__gl_check(voxgi_context *ctx, const char *what)
{
    unsigned int e = ctx->gl->GetError(), first = e;
    while (e != 0) e = ctx->gl->GetError();
    if (first == VOXGI__GL_OUT_OF_MEMORY) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "GL out of memory in %s", what);
    if (first != 0) return voxgi__fail(ctx, VOXGI_ERR_GL, "GL error 0x%04x in %s", first, what);
    return VOXGI_OK;
}

static voxgi_result voxgi__gl_read_buffer(voxgi_context *ctx, unsigned int buffer, void *dst, size_t bytes)
{
    ctx->gl->MemoryBarrier(VOXGI__GL_BUFFER_UPDATE_BARRIER_BIT);
    ctx->gl->GetNamedBufferSubData(buffer, 0, (ptrdiff_t)bytes, dst);
    return voxgi__gl_check(ctx, "reading a buffer back");
}

/* The shader storage bindings the passes use (the attribute pass and the volume merge use 8
   and 9: VOXGI__BINDING_SUMS is the highest); voxgi__gl_unbind clears them all. */
#define VOXGI__GL_STORAGE_BINDINGS (VOXGI__BINDING_SUMS + 1)

static void voxgi__gl_unbind(voxgi__gl *gl)
{
    int i;
    gl->UseProgram(0);
    gl->BindBuffer(VOXGI__GL_DISPATCH_INDIRECT_BUFFER, 0);
    for (i = 0; i < VOXGI__GL_STORAGE_BINDINGS; i++) gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, (unsigned)i, 0);
}

/* A zeroed buffer of the grid's words. */
static unsigned int voxgi__gl_grid_buffer(voxgi_context *ctx, size_t bytes)
{
    unsigned int b = voxgi__gl_buffer(ctx, bytes, NULL), zero = 0;
    ctx->gl->ClearNamedBufferData(b, VOXGI__GL_R32UI, VOXGI__GL_RED_INTEGER, VOXGI__GL_UNSIGNED_INT, &zero);
    return b;
}

/* Runs `program` with one invocation per item (grid-sized dispatch in slices of 65535 groups is
   not needed: callers keep items below 65535 * 64). */
static void voxgi__gl_dispatch_items(voxgi__gl *gl, uint64_t items)
{
    gl->DispatchCompute((unsigned)((items + 63) / 64), 1, 1);
    gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT);
}

/* One invocation per item, in rows of at most 65535 work groups (the shaders' item index is
   x + y * the row's invocations); the barrier covers storage and indirect commands. */
static void voxgi__gl_dispatch_rows(voxgi__gl *gl, uint64_t items)
{
    uint64_t groups = (items + 63) / 64;
    if (groups) gl->DispatchCompute((unsigned)VOXGI__MIN(groups, (uint64_t)65535), (unsigned)((groups + 65534) / 65535), 1);
    gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT | VOXGI__GL_COMMAND_BARRIER_BIT);
}

/* The GL state a raster pass changes (capabilities off, the viewport), saved by begin and given
   back to the caller by end. */
static const unsigned int voxgi__gl_raster_caps[9] = {VOXGI__GL_DEPTH_TEST, VOXGI__GL_STENCIL_TEST, VOXGI__GL_SCISSOR_TEST,
                                                      VOXGI__GL_CULL_FACE, VOXGI__GL_BLEND, VOXGI__GL_MULTISAMPLE,
                                                      VOXGI__GL_RASTERIZER_DISCARD, VOXGI__GL_COLOR_LOGIC_OP, VOXGI__GL_PROGRAM_POINT_SIZE};
typedef struct voxgi__gl_raster_state { unsigned char enabled[9]; int viewport[4]; } voxgi__gl_raster_state;

static void voxgi__gl_raster_begin(voxgi__gl *gl, voxgi__gl_raster_state *st)
{
    int i;
    gl->GetIntegerv(VOXGI__GL_VIEWPORT, st->viewport);
    for (i = 0; i < 9; i++) {
        st->enabled[i] = gl->IsEnabled(voxgi__gl_raster_caps[i]);
        gl->Disable(voxgi__gl_raster_caps[i]);
    }
}

static void voxgi__gl_raster_end(voxgi__gl *gl, const voxgi__gl_raster_state *st)
{
    int i;
    gl->Viewport(st->viewport[0], st->viewport[1], st->viewport[2], st->viewport[3]);
    for (i = 0; i < 9; i++)
        if (st->enabled[i]) gl->Enable(voxgi__gl_raster_caps[i]);
        else gl->Disable(voxgi__gl_raster_caps[i]);
}
#endif /* VOXGI_NO_GL */

/* ===================================================================== 5. voxelization */

VOXGI_API const char *voxgi_method_name(voxgi_method m)
{
    switch (m) {
    case VOXGI_METHOD_CONSERVATIVE: return "conservative";
    case VOXGI_METHOD_THIN: return "thin";
    case VOXGI_METHOD_SOLID: return "solid";
    case VOXGI_METHOD_SLICEMAP: return "slicemap";
    case VOXGI_METHOD_ATLAS: return "atlas";
    case VOXGI_METHOD_ATLAS_COMPUTE: return "atlas-compute";
    case VOXGI_METHOD_GEOMETRY: return "geometry";
    case VOXGI_METHOD_VOLUME_BUFFER: return "volume-buffer";
    case VOXGI_METHOD_COUNT_: break;
    }
    return "unknown";
}

/* ----- 5.1 exact arithmetic and exact triangle tests */

/* exact arithmetic
   Floating-point expansions (Priest; Shewchuk 1997): a real number held exactly as a sum of
   non-overlapping doubles, smallest first. Sums and products of a few float coordinates and the
   double grid are exact in this form, so the rare tests the double filter cannot decide are
   decided here. Every routine drops zero components, so the sign is that of the last one. */
typedef struct voxgi__xp { int n; double c[512]; } voxgi__xp;

static void voxgi__two_sum(double a, double b, double *s, double *e)
{
    double x = a + b, bv = x - a, av = x - bv;
    *s = x;
    *e = (a - av) + (b - bv);
}
static void voxgi__two_prod(double a, double b, double *p, double *e)
{
    *p = a * b;
    *e = fma(a, b, -*p);
}
/* h = e + b (h may alias e). */
static void voxgi__xp_add1(voxgi__xp *h, const voxgi__xp *e, double b)
{
    double q = b, hh;
    int i, n = 0, en = e->n;
    for (i = 0; i < en; i++) {
        voxgi__two_sum(q, e->c[i], &q, &hh);
        if (hh != 0.0) h->c[n++] = hh;
    }
    if (q != 0.0 || n == 0) h->c[n++] = q;
    h->n = n;
}
/* h += f */
static void voxgi__xp_add(voxgi__xp *h, const voxgi__xp *f)
{
    int i;
    for (i = 0; i < f->n; i++) voxgi__xp_add1(h, h, f->c[i]);
}
/* h = e * b */
static void voxgi__xp_scale(voxgi__xp *h, const voxgi__xp *e, double b)
{
    double q, hh, p1, p0, sum;
    int i, n = 0;
    voxgi__two_prod(e->c[0], b, &q, &hh);
    if (hh != 0.0) h->c[n++] = hh;
    for (i = 1; i < e->n; i++) {
        voxgi__two_prod(e->c[i], b, &p1, &p0);
        voxgi__two_sum(q, p0, &sum, &hh);
        if (hh != 0.0) h->c[n++] = hh;
        voxgi__two_sum(p1, sum, &q, &hh);
        if (hh != 0.0) h->c[n++] = hh;
    }
    if (q != 0.0 || n == 0) h->c[n++] = q;
    h->n = n;
}
/* h = e * f (h must not alias either) */
static void voxgi__xp_mul(voxgi__xp *h, const voxgi__xp *e, const voxgi__xp *f)
{
    voxgi__xp t;
    int j;
    h->n = 1; h->c[0] = 0.0;
    for (j = 0; j < f->n; j++) {
        voxgi__xp_scale(&t, e, f->c[j]);
        voxgi__xp_add(h, &t);
    }
}
static void voxgi__xp_neg(voxgi__xp *e)
{
    int i;
    for (i = 0; i < e->n; i++) e->c[i] = -e->c[i];
}
static int voxgi__xp_sign(const voxgi__xp *e)
{
    double top = e->c[e->n - 1];
    return (top > 0.0) - (top < 0.0);
}
/* x = a - b exactly */
static void voxgi__xp_diff(voxgi__xp *x, double a, double b)
{
    double s, e;
    voxgi__two_sum(a, -b, &s, &e);
    x->n = 0;
    if (e != 0.0) x->c[x->n++] = e;
    x->c[x->n++] = s;
    if (x->n == 2 && s == 0.0) x->n = 1;
}
/* x = o + k*s - w exactly: a grid plane's coordinate minus a vertex coordinate */
static void voxgi__xp_plane_minus(voxgi__xp *x, double o, double k, double s, double w)
{
    double p, e;
    voxgi__two_prod(k, s, &p, &e);
    x->n = 1; x->c[0] = e;
    voxgi__xp_add1(x, x, p);
    voxgi__xp_add1(x, x, o);
    voxgi__xp_add1(x, x, -w);
}

/* voxelization: exact triangle tests
   Conservative: a voxel is set exactly when its closed box meets the closed triangle. The test
   is Schwarz and Seidel's (2010): bounding ranges, the triangle's plane against the box, and
   the triangle's three axis-aligned projections against the box's squares, each an
   edge-function sign test at a critical corner. Thin, solid and slicemap reuse the same forms. Every sign is first computed in double with a rigorous forward error bound
   (voxel units, relative to the triangle's own corner, so magnitudes stay small); a sign the
   bound cannot certify is recomputed exactly from the float vertices and the double grid. When
   all coordinates sit on a coarse binary lattice (integer or dyadic voxel coordinates, as in
   axis-aligned models) the double arithmetic is itself exact and is used as such. */
#define VOXGI__U (DBL_EPSILON * 0.5)
#define VOXGI__GAMMA(k) ((k) * VOXGI__U / (1.0 - (k) * VOXGI__U))
#define VOXGI__UNKNOWN 2

typedef struct voxgi__vprep {
    double q[3];           /* (v - o) / s in double: the vertex in voxel units */
    int32_t lo[3], hi[3];  /* exact range of voxel indices whose closed box holds the coordinate */
    int32_t frac_bits;     /* every q is exact with at most this many fraction bits, or -1 */
    int32_t exact_axes;    /* bit a: q[a] is exact with at most 30 fraction bits */
} voxgi__vprep;

/* Exact sign of x - (o + k s): where a coordinate lies against a grid plane. */
static int voxgi__cmp_grid_plane(double x, double o, double k, double s)
{
    double ks = k * s, d = (x - o) - ks, bound = 4 * VOXGI__U * (fabs(x) + fabs(o) + fabs(ks));
    voxgi__xp e;
    if (d > bound) return 1;
    if (d < -bound) return -1;
    voxgi__xp_plane_minus(&e, o, k, s, x);
    return -voxgi__xp_sign(&e);
}

/* Fraction bits of x's binary expansion: 0 for integers, up to 1074. */
static int voxgi__fraction_bits(double x)
{
    uint64_t b, mant;
    int e, tz = 0;
    if (x == floor(x)) return 0;
    memcpy(&b, &x, sizeof b);
    e = (int)((b >> 52) & 0x7ff);
    mant = (b & ((1ull << 52) - 1)) | (e ? 1ull << 52 : 0);
    while (!(mant & 1u)) { mant >>= 1; tz++; }
    return 1075 - (e ? e : 1) - tz; /* x = mant * 2^(e - 1075) */
}

static void voxgi__prep_vertex(const float *v, const voxgi_grid *g, voxgi__vprep *out)
{
    int a, frac = 0;
    out->exact_axes = 0;
    for (a = 0; a < 3; a++) {
        double x = v[a], o = g->origin[a], s = g->voxel_size, d = x - o, q = d / s, k;
        out->q[a] = q;
        if (!(q > -4.0)) { /* far below the grid (or not finite; such vertices are never used) */
            out->lo[a] = out->hi[a] = -4;
            frac = -1;
            continue;
        }
        if (!(q < (double)g->res[a] + 4.0)) {
            out->lo[a] = out->hi[a] = g->res[a] + 4;
            frac = -1;
            continue;
        }
        k = floor(q);
        while (voxgi__cmp_grid_plane(x, o, k + 1, s) >= 0) k += 1;
        while (voxgi__cmp_grid_plane(x, o, k, s) < 0) k -= 1;
        out->hi[a] = (int32_t)k;
        out->lo[a] = (int32_t)k - (voxgi__cmp_grid_plane(x, o, k, s) == 0);
        /* q is a lattice value when x - o and the division were exact and few fraction bits remain */
        {
            int f = voxgi__fraction_bits(q);
            double se, pe, pp;
            voxgi__two_sum(x, -o, &pp, &se);
            voxgi__two_prod(q, s, &pp, &pe);
            if (f > 30 || fabs(q) > 4194304.0 || se != 0.0 || pp != d || pe != 0.0) frac = -1;
            else {
                out->exact_axes |= 1 << a;
                if (frac >= 0) frac = VOXGI__MAX(frac, f);
            }
        }
    }
    out->frac_bits = frac;
}

/* A test value that is linear in the voxel index: v = v0[side] + k . rel, where rel is the voxel
   index relative to the triangle's range and side picks the box corner minimising (0) or
   maximising (1) the function. err bounds |computed - exact| for every voxel of the range. */
typedef struct voxgi__lin {
    double k[3], dk[3], v0[2], vc, err; /* vc: the constant at the voxel centre (thin tests) */
    int8_t off[2][3];    /* corner offsets per side */
    int8_t vertex;       /* the vertex the function is measured from */
    int8_t plane;        /* -1: the triangle's plane; else the projection normal to this axis */
    int8_t edge;         /* edge (from this vertex) of a projection test */
    int8_t orient;       /* +-1: one-sided (max corner >= 0); 0: two-sided (min <= 0 <= max) */
} voxgi__lin;

typedef struct voxgi__tri {
    int32_t lo[3], hi[3];      /* exact voxel range of the triangle, clipped to the grid */
    int one_slice[3];          /* the unclipped range is a single voxel thick on this axis */
    double r[3][3], dr[3][3];  /* vertices relative to lo (voxel units), error bounds */
    double e[3][3], de[3][3];  /* edges v0->v1, v1->v2, v2->v0, error bounds */
    double n[3], dn[3];        /* normal (v1-v0)x(v2-v0), error bounds */
    int sig[3];                /* exact sign of the normal per axis, or VOXGI__UNKNOWN */
    int exact;                 /* all double arithmetic of the tests is exact */
    uint32_t v[3];             /* vertex indices */
    voxgi__lin plane;          /* valid when the normal is not zero */
    voxgi__lin proj[3][3];     /* [axis][i]: the projection normal to axis: 3 oriented edges, */
    int proj_count[3];         /* 1 two-sided line (segment-shaped projection), or 0 (a point) */
} voxgi__tri;

/* What one worker counted: tests decided by exact arithmetic, and bits it set; and the
   triangle it works on (whose attributes a voxel receives). */
typedef struct voxgi__stats { uint64_t exact_tests, voxels; uint32_t tri; } voxgi__stats;

/* Attribute sums (see voxgi_attribute): each triangle's values in fixed point; per set voxel a
   count and 64-bit sums, at the voxel's rank among the set bits. */
#define VOXGI__MAX_CHANNELS 10
typedef struct voxgi__attr {
    int channels;                       /* values per triangle and per voxel */
    double unit[VOXGI__MAX_CHANNELS];   /* what one fixed-point unit of a channel is worth */
    double zero[VOXGI__MAX_CHANNELS];   /* the value fixed point 0 stands for */
    unsigned char max_op[VOXGI__MAX_CHANNELS]; /* 1: the channel keeps the maximum, else the sum */
    voxgi_blend blend[4];               /* per attribute (albedo, normal, emission, opacity) */
    float *values;                      /* when set (GL Volume Buffer): the final values, channels per set voxel */
    uint32_t *rec;                      /* channels per triangle */
    uint32_t *rank;                     /* per word of the bit grid: set voxels in the words before */
    uint32_t *count;                    /* per set voxel: triangles added */
    uint64_t *sum;                      /* channels per set voxel */
} voxgi__attr;

/* Adds triangle t's values to set voxel idx. */
static void voxgi__attr_add(const voxgi__attr *at, const uint32_t *bits, uint64_t idx, uint32_t t)
{
    uint64_t slot = at->rank[idx >> 5] + voxgi__popcount32(bits[idx >> 5] & ((1u << (idx & 31u)) - 1u));
    int c;
    VOXGI__ATOMIC_ADD_SIZE(&at->count[slot], 1u);
    for (c = 0; c < at->channels; c++) {
        uint64_t *sum = &at->sum[slot * (uint64_t)at->channels + (uint64_t)c], v = at->rec[(size_t)t * (size_t)at->channels + (size_t)c];
        if (at->max_op[c]) {
            uint64_t old = VOXGI__ATOMIC_LOAD_U64(sum);
            while (old < v && !VOXGI__ATOMIC_CAS_U64(sum, &old, v)) {}
        } else VOXGI__ATOMIC_ADD_SIZE(sum, v);
    }
}

/* Read-only state shared by all workers of one voxelization. */
typedef struct voxgi__vox_shared {
    const voxgi_grid *grid;
    const float *pos;
    const uint32_t *tri;
    const voxgi__vprep *vp;
    uint32_t *bits;
    double inv_s;
    int thin;              /* VOXGI_METHOD_THIN: every set voxel also passes the thin tests */
    int solid_axis;        /* solid parity along this axis, else -1 */
    int slice_axis;        /* raster slicemap along this axis, else -1 */
    int volume_buffer;     /* VOLUME_BUFFER: each triangle along its dominant axis */
    const voxgi__attr *attr; /* attribute pass: bits are final, set voxels receive attributes */
} voxgi__vox_shared;

/* Shared state for the CPU's exact tests over the scene (the GL passes' referee and the CPU twin). */
static void voxgi__vox_shared_init(voxgi__vox_shared *vs, const voxgi_grid *g, const voxgi__flat *f, const voxgi__vprep *vp,
                                   voxgi_method method, uint32_t *bits)
{
    memset(vs, 0, sizeof *vs);
    vs->grid = g;
    vs->pos = f->pos;
    vs->tri = f->tri;
    vs->vp = vp;
    vs->bits = bits;
    vs->inv_s = 1.0 / g->voxel_size;
    vs->thin = method == VOXGI_METHOD_THIN;
    vs->solid_axis = vs->slice_axis = -1;
}

/* Fills the triangle's range, coordinates, edges and normal; returns 0 when it misses the grid. */
static int voxgi__tri_setup(const voxgi__vox_shared *vs, size_t ti, voxgi__tri *t)
{
    const voxgi_grid *g = vs->grid;
    const voxgi__vprep *p[3];
    int a, k, c;
    double m = 0;
    for (k = 0; k < 3; k++) {
        t->v[k] = vs->tri[3 * ti + (size_t)k];
        p[k] = &vs->vp[t->v[k]];
    }
    for (a = 0; a < 3; a++) {
        int32_t lo = VOXGI__MIN(p[0]->lo[a], VOXGI__MIN(p[1]->lo[a], p[2]->lo[a]));
        int32_t hi = VOXGI__MAX(p[0]->hi[a], VOXGI__MAX(p[1]->hi[a], p[2]->hi[a]));
        /* solid parity counts crossings below the grid too: keep such triangles, at slice 0 */
        if (a == vs->solid_axis && hi < 0) lo = hi = 0;
        t->lo[a] = VOXGI__MAX(0, lo);
        t->hi[a] = VOXGI__MIN(g->res[a] - 1, hi);
        if (t->lo[a] > t->hi[a]) return 0;
        t->one_slice[a] = lo == hi;
    }
    for (k = 0; k < 3; k++)
        for (a = 0; a < 3; a++) {
            double q = p[k]->q[a];
            t->r[k][a] = q - (double)t->lo[a];
            t->dr[k][a] = (p[k]->exact_axes >> a) & 1 ? 0.0 : 2.01 * VOXGI__U * fabs(q) + VOXGI__U * fabs(t->r[k][a]);
            m = VOXGI__MAX(m, VOXGI__MAX(fabs(t->r[k][a]), (double)(t->hi[a] - t->lo[a] + 1)));
        }
    /* Exact mode: numerators (in units of 2^-fb) of edges and offsets need at most B bits, so
       every intermediate of the tests, up to 3B+4 bits, is exact in double when B <= 16. */
    t->exact = 0;
    if (p[0]->frac_bits >= 0 && p[1]->frac_bits >= 0 && p[2]->frac_bits >= 0) {
        int fb = VOXGI__MAX(p[0]->frac_bits, VOXGI__MAX(p[1]->frac_bits, p[2]->frac_bits)), bits = 0;
        while (bits < 20 && (double)(1 << bits) < 2 * m + 1) bits++;
        t->exact = bits + fb <= 16;
    }
    for (k = 0; k < 3; k++) {
        int j = (k + 1) % 3;
        for (a = 0; a < 3; a++) {
            if (t->exact) {
                t->e[k][a] = t->r[j][a] - t->r[k][a];
                t->de[k][a] = 0;
            } else {
                /* from the floats themselves: exactly zero for equal coordinates, relative error 3u */
                const float *wk = vs->pos + 3 * (size_t)t->v[k], *wj = vs->pos + 3 * (size_t)t->v[j];
                t->e[k][a] = ((double)wj[a] - (double)wk[a]) * vs->inv_s;
                t->de[k][a] = 3.01 * VOXGI__U * fabs(t->e[k][a]);
            }
        }
    }
    for (c = 0; c < 3; c++) {
        int a1 = (c + 1) % 3, b1 = (c + 2) % 3;
        /* n = e0 x f with f = v2 - v0 = -e2 */
        double e0a = t->e[0][a1], e0b = t->e[0][b1], fa = -t->e[2][a1], fb = -t->e[2][b1];
        double p1 = e0a * fb, p2 = e0b * fa;
        t->n[c] = p1 - p2;
        t->dn[c] = t->exact ? 0.0
                            : (fabs(e0a) * t->de[2][b1] + fabs(fb) * t->de[0][a1] + t->de[0][a1] * t->de[2][b1] +
                               fabs(e0b) * t->de[2][a1] + fabs(fa) * t->de[0][b1] + t->de[0][b1] * t->de[2][a1] +
                               VOXGI__GAMMA(2) * (fabs(p1) + fabs(p2))) * 1.001;
        if (t->n[c] > t->dn[c]) t->sig[c] = 1;
        else if (t->n[c] < -t->dn[c]) t->sig[c] = -1;
        else t->sig[c] = t->dn[c] == 0.0 ? 0 : VOXGI__UNKNOWN;
    }
    return 1;
}

/* Builds v(rel) = sum_a k_a (rel_a + off_a - r_a) for coefficients k (bounds dk) about vertex vk. */
static void voxgi__lin_make(const voxgi__tri *t, voxgi__lin *L, const double k[3], const double dk[3], int vk)
{
    double s = 0, mag = 0;
    int a, side;
    for (side = 0; side < 2; side++) {
        L->v0[side] = 0;
        for (a = 0; a < 3; a++) {
            L->off[side][a] = (int8_t)(side ? k[a] > 0 : k[a] < 0);
            L->v0[side] += k[a] * ((double)L->off[side][a] - t->r[vk][a]);
        }
    }
    L->vertex = (int8_t)vk;
    L->vc = 0;
    for (a = 0; a < 3; a++) L->vc += k[a] * (0.5 - t->r[vk][a]);
    for (a = 0; a < 3; a++) {
        /* |rel + off - r| <= T over the whole range */
        double T = fabs(t->r[vk][a]) + 1 + (double)(t->hi[a] - t->lo[a] + 1);
        L->k[a] = k[a];
        L->dk[a] = dk[a];
        s += fabs(k[a]) * t->dr[vk][a] + T * dk[a] + dk[a] * t->dr[vk][a];
        mag += fabs(k[a]) * T;
    }
    /* the inputs' errors, then the roundings of at most 8 operations in any order */
    L->err = t->exact ? 0.0 : (s + VOXGI__GAMMA(8) * mag * 1.01) * 1.001;
}

/* Builds the plane and projection tests once every sign the tests rely on is known. */
static void voxgi__tri_forms(voxgi__tri *t)
{
    int c, k;
    const double zero[3] = {0, 0, 0};
    voxgi__lin_make(t, &t->plane, t->n, t->dn, 0);
    t->plane.plane = -1;
    t->plane.orient = 0;
    for (c = 0; c < 3; c++) {
        int a = (c + 1) % 3, b = (c + 2) % 3, best = -1;
        double len = 0, m[3], dm[3];
        t->proj_count[c] = 0;
        if (t->sig[c] == VOXGI__UNKNOWN) continue;
        for (k = 0; k < 3; k++) {
            double l = fabs(t->e[k][a]) + fabs(t->e[k][b]);
            if (l > len) { len = l; best = k; }
        }
        for (k = 0; k < 3; k++) {
            int o = t->sig[c];
            /* oriented: the inward normal o*(-e_b, e_a) of each edge; a segment-shaped
               projection (o == 0): the line through its longest edge, tested on both sides */
            if (o == 0 && k != best) continue;
            memcpy(m, zero, sizeof m);
            memcpy(dm, zero, sizeof dm);
            m[a] = -t->e[k][b] * (o ? o : 1);
            m[b] = t->e[k][a] * (o ? o : 1);
            dm[a] = t->de[k][b];
            dm[b] = t->de[k][a];
            voxgi__lin_make(t, &t->proj[c][t->proj_count[c]], m, dm, k);
            t->proj[c][t->proj_count[c]].plane = (int8_t)c;
            t->proj[c][t->proj_count[c]].edge = (int8_t)k;
            t->proj[c][t->proj_count[c]].orient = (int8_t)o;
            t->proj_count[c]++;
        }
    }
}

static int voxgi__sign_within(double v, double err)
{
    if (v > err) return 1;
    if (v < -err) return -1;
    return err == 0.0 ? 0 : VOXGI__UNKNOWN;
}

/* ----- exact fallbacks: world floats and the double grid, no rounding anywhere */
static void voxgi__exact_normal(const voxgi__vox_shared *vs, const voxgi__tri *t, int c, voxgi__xp *n)
{
    const float *w0 = vs->pos + 3 * (size_t)t->v[0], *w1 = vs->pos + 3 * (size_t)t->v[1], *w2 = vs->pos + 3 * (size_t)t->v[2];
    int a = (c + 1) % 3, b = (c + 2) % 3;
    voxgi__xp ea, eb, fa, fb, p;
    voxgi__xp_diff(&ea, w1[a], w0[a]);
    voxgi__xp_diff(&eb, w1[b], w0[b]);
    voxgi__xp_diff(&fa, w2[a], w0[a]);
    voxgi__xp_diff(&fb, w2[b], w0[b]);
    voxgi__xp_mul(n, &ea, &fb);
    voxgi__xp_mul(&p, &eb, &fa);
    voxgi__xp_neg(&p);
    voxgi__xp_add(n, &p);
}

/* Exact sign of a linear form in world units at grid coordinates g (a voxel index plus 0, 1/2
   or 1 per axis, exact in double), plus sgn * s/2 * |K_j| when j >= 0: the thin tests' radius.
   K is the form's world coefficient vector: the normal (v1-v0)x(v2-v0), or orient * (-d_b, d_a)
   for an edge d of a projection. */
static int voxgi__exact_form(const voxgi__vox_shared *vs, const voxgi__tri *t, const voxgi__lin *L, const double g[3], int j,
                             int sgn)
{
    const float *w = vs->pos + 3 * (size_t)t->v[(int)L->vertex];
    voxgi__xp k[3], x, prod, sum;
    int a;
    if (L->plane < 0) {
        for (a = 0; a < 3; a++) voxgi__exact_normal(vs, t, a, &k[a]);
    } else {
        int c = L->plane, pa = (c + 1) % 3, pb = (c + 2) % 3;
        const float *wj = vs->pos + 3 * (size_t)t->v[(L->edge + 1) % 3];
        k[c].n = 1; k[c].c[0] = 0;
        voxgi__xp_diff(&k[pa], w[pb], wj[pb]); /* -d_b */
        voxgi__xp_diff(&k[pb], wj[pa], w[pa]); /* d_a */
        if (L->orient < 0) { voxgi__xp_neg(&k[pa]); voxgi__xp_neg(&k[pb]); }
    }
    sum.n = 1; sum.c[0] = 0;
    for (a = 0; a < 3; a++) {
        if (k[a].n == 1 && k[a].c[0] == 0) continue;
        voxgi__xp_plane_minus(&x, vs->grid->origin[a], g[a], vs->grid->voxel_size, w[a]);
        voxgi__xp_mul(&prod, &k[a], &x);
        voxgi__xp_add(&sum, &prod);
    }
    if (j >= 0) {
        voxgi__xp_scale(&prod, &k[j], 0.5 * vs->grid->voxel_size * sgn * voxgi__xp_sign(&k[j]));
        voxgi__xp_add(&sum, &prod);
    }
    return voxgi__xp_sign(&sum);
}

/* Makes every sign of the normal exact (CPU only; the GL pass hands such triangles over). */
static void voxgi__tri_resolve_signs(const voxgi__vox_shared *vs, voxgi__tri *t, voxgi__stats *st)
{
    int c;
    for (c = 0; c < 3; c++)
        if (t->sig[c] == VOXGI__UNKNOWN) {
            voxgi__xp n;
            voxgi__exact_normal(vs, t, c, &n);
            t->sig[c] = voxgi__xp_sign(&n);
            st->exact_tests++;
        }
}

/* Second opinion on a sign the range-wide bound left open: sum k_a t_a with t_a = rel_a + off_a
   - r_a and a bound for this voxel alone, so exact ties (a face on a voxel boundary) cost no
   exact arithmetic: there t_a and its error are both zero. */
static int voxgi__sign_tight(const voxgi__tri *t, const voxgi__lin *L, int side, const int32_t rel[3])
{
    double v = 0, e = 0, g = 0;
    int a;
    for (a = 0; a < 3; a++) {
        double ta = (double)(rel[a] + L->off[side][a]) - t->r[L->vertex][a];
        double dt = t->dr[L->vertex][a] + VOXGI__U * fabs(ta);
        v += L->k[a] * ta;
        e += fabs(L->k[a]) * dt + L->dk[a] * fabs(ta) + L->dk[a] * dt;
        g += fabs(L->k[a] * ta);
    }
    return voxgi__sign_within(v, (e + VOXGI__GAMMA(3) * g * 1.01) * 1.001);
}

/* One linear test at voxel rel (relative to t->lo): 1 pass, 0 fail; undecided signs exactly. */
static int voxgi__test_lin(const voxgi__vox_shared *vs, const voxgi__tri *t, const voxgi__lin *L, const int32_t rel[3],
                           voxgi__stats *st)
{
    int side;
    for (side = L->orient ? 1 : 0; side < 2; side++) {
        double v = L->v0[side] + L->k[0] * (double)rel[0] + L->k[1] * (double)rel[1] + L->k[2] * (double)rel[2];
        int s = voxgi__sign_within(v, L->err);
        if (s == VOXGI__UNKNOWN) s = voxgi__sign_tight(t, L, side, rel);
        if (s == VOXGI__UNKNOWN) {
            double g[3];
            int a;
            for (a = 0; a < 3; a++) g[a] = (double)((int64_t)t->lo[a] + rel[a] + L->off[side][a]);
            s = voxgi__exact_form(vs, t, L, g, -1, 0);
            st->exact_tests++;
        }
        if (side == 0 ? s > 0 : s < 0) return 0;
    }
    return 1;
}

/* Per-voxel decision of a thin test side: side 1 asks whether v + |k_j|/2 >= 0 for some j,
   side 0 whether v - |k_j|/2 <= 0 for some j (the maximum as an OR). Each candidate is summed
   as k_j (t_j +- 1/2) + the other terms, so a face exactly on the octahedron's vertex cancels
   without rounding and needs no exact arithmetic. */
static int voxgi__sign_thin_tight(const voxgi__tri *t, const voxgi__lin *L, int side, const int32_t rel[3])
{
    int j, a, known = 0;
    for (j = 0; j < 3; j++) {
        double v = 0, e = 0, gm = 0, sj = L->k[j] > 0 ? 1 : -1;
        for (a = 0; a < 3; a++) {
            /* t_a = rel + 1/2 - r, shifted by +-1/2 on axis j: a whole number minus r */
            double off = a == j ? 0.5 + (side ? 0.5 : -0.5) * sj : 0.5;
            double ta = ((double)rel[a] + off) - t->r[(int)L->vertex][a];
            double dt = t->dr[(int)L->vertex][a] + VOXGI__U * fabs(ta);
            v += L->k[a] * ta;
            e += fabs(L->k[a]) * dt + L->dk[a] * fabs(ta) + L->dk[a] * dt;
            gm += fabs(L->k[a] * ta);
        }
        if (fabs(L->k[j]) <= L->dk[j]) e += L->dk[j]; /* |k_j|'s sign may be the wrong one */
        e += VOXGI__GAMMA(3) * gm * 1.01;
        switch (voxgi__sign_within(v, e == 0 ? 0.0 : e * 1.001)) {
        case 0: return 0;
        case 1: if (side) return 1; known++; break;
        case -1: if (!side) return -1; known++; break;
        default: break;
        }
    }
    return known == 3 ? (side ? -1 : 1) : VOXGI__UNKNOWN;
}

/* The same form against the voxel's inscribed octahedron (plane) or diamond (projection),
   whose support is half the largest |k_j|: one-sided v_centre + T >= 0, or two-sided
   |v_centre| <= T. Undecided signs are decided exactly, T's maximum as an OR over j. */
static int voxgi__test_lin_thin(const voxgi__vox_shared *vs, const voxgi__tri *t, const voxgi__lin *L, const int32_t rel[3],
                                voxgi__stats *st)
{
    double vc = L->vc + L->k[0] * (double)rel[0] + L->k[1] * (double)rel[1] + L->k[2] * (double)rel[2];
    double T = 0.5 * VOXGI__MAX(fabs(L->k[0]), VOXGI__MAX(fabs(L->k[1]), fabs(L->k[2])));
    double dT = 0.5 * VOXGI__MAX(L->dk[0], VOXGI__MAX(L->dk[1], L->dk[2]));
    int side;
    for (side = L->orient ? 1 : 0; side < 2; side++) {
        double w = side ? vc + T : vc - T;
        int s = voxgi__sign_within(w, L->err == 0 && dT == 0 ? 0.0 : (L->err + dT + VOXGI__U * fabs(w)) * 1.001);
        if (s == VOXGI__UNKNOWN) s = voxgi__sign_thin_tight(t, L, side, rel);
        if (s == VOXGI__UNKNOWN) {
            double g[3];
            int a, j;
            for (a = 0; a < 3; a++) g[a] = (double)((int64_t)t->lo[a] + rel[a]) + 0.5;
            /* side 1: max over j of v + |K_j|/2; side 0: min over j of v - |K_j|/2 */
            s = side ? -1 : 1;
            for (j = 0; j < 3; j++) {
                int sj = voxgi__exact_form(vs, t, L, g, j, side ? 1 : -1);
                s = side ? VOXGI__MAX(s, sj) : VOXGI__MIN(s, sj);
            }
            st->exact_tests++;
        }
        if (side == 0 ? s > 0 : s < 0) return 0;
    }
    return 1;
}

/* The thin (6-separating) test of a voxel the conservative tests accepted: every form the
   triangle uses, against the octahedron or diamonds. */
static int voxgi__test_thin(const voxgi__vox_shared *vs, const voxgi__tri *t, const int32_t rel[3], voxgi__stats *st)
{
    int c, i;
    if ((t->sig[0] | t->sig[1] | t->sig[2]) != 0 && !voxgi__test_lin_thin(vs, t, &t->plane, rel, st)) return 0;
    for (c = 0; c < 3; c++)
        for (i = 0; i < t->proj_count[c]; i++)
            if (!voxgi__test_lin_thin(vs, t, &t->proj[c][i], rel, st)) return 0;
    return 1;
}

/* The projection of the triangle onto the plane normal to axis c against the voxel's square. */
static int voxgi__test_projection(const voxgi__vox_shared *vs, const voxgi__tri *t, int c, const int32_t rel[3],
                                  voxgi__stats *st)
{
    int i;
    for (i = 0; i < t->proj_count[c]; i++)
        if (!voxgi__test_lin(vs, t, &t->proj[c][i], rel, st)) return 0;
    return 1;
}

#ifndef VOXGI_NO_GL
/* The complete exact test of one voxel (any triangle, degenerate or not): the GL pass's referee. */
static int voxgi__test_voxel(const voxgi__vox_shared *vs, const voxgi__tri *t, const int32_t rel[3], voxgi__stats *st)
{
    int a;
    for (a = 0; a < 3; a++)
        if (rel[a] < 0 || rel[a] > t->hi[a] - t->lo[a]) return 0;
    if ((t->sig[0] | t->sig[1] | t->sig[2]) != 0 && !voxgi__test_lin(vs, t, &t->plane, rel, st)) return 0;
    for (a = 0; a < 3; a++)
        if (!voxgi__test_projection(vs, t, a, rel, st)) return 0;
    return 1;
}
#endif

/* ----- 5.2 voxels and their attributes */

struct voxgi_voxels {
    voxgi_voxels_info info;
    uint32_t *bits;            /* CPU backend */
    unsigned int gl_buffer;    /* GL backend */
    voxgi__attr attr;          /* with attributes: counts and sums per set voxel (on the CPU for both backends) */
};

/* The attributes a voxelization blends (RADIANCE comes later, from light injection). */
#define VOXGI__VOXEL_ATTRIBUTES (VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL | VOXGI_ATTRIBUTE_EMISSION | VOXGI_ATTRIBUTE_OPACITY)

/* Each triangle's attribute values in fixed point, channels in the order albedo, normal,
   emission, opacity (those asked for). */
static voxgi_result voxgi__attr_prepare(voxgi_context *ctx, const voxgi__flat *f, unsigned mask, const voxgi_blend blend[4],
                                        voxgi__attr *at)
{
    double emax = 0, erange = 1, v[VOXGI__MAX_CHANNELS];
    size_t t;
    int c;
    memset(at, 0, sizeof *at);
    at->channels = (mask & VOXGI_ATTRIBUTE_ALBEDO ? 3 : 0) + (mask & VOXGI_ATTRIBUTE_NORMAL ? 3 : 0) +
                   (mask & VOXGI_ATTRIBUTE_EMISSION ? 3 : 0) + (mask & VOXGI_ATTRIBUTE_OPACITY ? 1 : 0);
    for (t = 0; t < f->triangle_count; t++)
        for (c = 0; c < 3; c++) emax = VOXGI__MAX(emax, (double)voxgi__tri_material(f, t)->emission[c]);
    while (erange < emax) erange *= 2;
    while (erange / 2 >= emax && emax > 0) erange /= 2;
    for (c = 0; c < 4; c++) at->blend[c] = blend[c];
    {   /* channel -> attribute: the channels of each asked-for attribute in order */
        int k = 0, a, n;
        for (a = 0; a < 4; a++) {
            if (!(mask & (1u << a))) continue;
            for (n = 0; n < (a == 3 ? 1 : 3); n++) at->max_op[k++] = (unsigned char)(blend[a] == VOXGI_BLEND_MAX);
        }
    }
    at->rec = (uint32_t *)voxgi__alloc_array(ctx, f->triangle_count ? f->triangle_count : 1, (size_t)at->channels * 4, 0);
    if (!at->rec) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the triangles' attributes");
    for (t = 0; t < f->triangle_count; t++) {
        const voxgi_material *m = voxgi__tri_material(f, t);
        double step[VOXGI__MAX_CHANNELS]; /* v / step is the fixed-point value: v in [0,1], normals n + 1 in [0,2] */
        int k = 0, a;
        if (mask & VOXGI_ATTRIBUTE_ALBEDO)
            for (a = 0; a < 3; a++, k++) { v[k] = m->albedo[a]; step[k] = ldexp(1.0, -24); at->zero[k] = 0; at->unit[k] = step[k]; }
        if (mask & VOXGI_ATTRIBUTE_NORMAL) {
            double n[3];
            voxgi__tri_unit_normal(f, t, n);
            for (a = 0; a < 3; a++, k++) { v[k] = n[a] + 1; step[k] = ldexp(1.0, -23); at->zero[k] = -1; at->unit[k] = step[k]; }
        }
        if (mask & VOXGI_ATTRIBUTE_EMISSION)
            for (a = 0; a < 3; a++, k++) { v[k] = m->emission[a] / erange; step[k] = ldexp(1.0, -24); at->zero[k] = 0; at->unit[k] = erange * step[k]; }
        if (mask & VOXGI_ATTRIBUTE_OPACITY) { v[k] = 1.0 - m->transparency; step[k] = ldexp(1.0, -24); at->zero[k] = 0; at->unit[k] = step[k]; k++; }
        for (c = 0; c < k; c++) /* round to nearest: no truncation bias */
            at->rec[t * (size_t)at->channels + (size_t)c] = (uint32_t)floor(VOXGI__MIN(VOXGI__MAX(v[c], 0.0), 2.0) / step[c] + 0.5);
    }
    return VOXGI_OK;
}

/* After the bits are final: ranks, counts and sums for the attribute pass. */
static voxgi_result voxgi__attr_alloc(voxgi_context *ctx, voxgi__attr *at, const uint32_t *bits, uint64_t words, uint64_t voxels)
{
    uint64_t w, before = 0;
    uint64_t need = voxels * (4u + 8u * (uint64_t)at->channels) + words * 4u;
    if (voxels > (uint64_t)UINT32_MAX) return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "attributes hold at most 2^32 voxels");
    if (ctx->desc.memory_budget && need > (uint64_t)ctx->desc.memory_budget)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "the attributes of %llu voxels need %llu bytes, more than the memory budget %llu",
                           (unsigned long long)voxels, (unsigned long long)need, (unsigned long long)ctx->desc.memory_budget);
    at->rank = (uint32_t *)voxgi__alloc_array(ctx, (size_t)words, 4, 0);
    at->count = (uint32_t *)voxgi__alloc_array(ctx, (size_t)(voxels ? voxels : 1), 4, 1);
    at->sum = (uint64_t *)voxgi__alloc_array(ctx, (size_t)(voxels ? voxels : 1), (size_t)at->channels * 8, 1);
    if (!at->rank || !at->count || !at->sum)
        return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the attributes of %llu voxels", (unsigned long long)voxels);
    for (w = 0; w < words; w++) {
        at->rank[w] = (uint32_t)before;
        before += voxgi__popcount32(bits[w]);
    }
    return VOXGI_OK;
}

static void voxgi__attr_free(voxgi_context *ctx, voxgi__attr *at)
{
    voxgi__free(ctx, at->rec);
    voxgi__free(ctx, at->rank);
    voxgi__free(ctx, at->count);
    voxgi__free(ctx, at->sum);
    voxgi__free(ctx, at->values);
    memset(at, 0, sizeof *at);
}

VOXGI_API voxgi_result voxgi_voxels_read_attribute(voxgi_context *ctx, const voxgi_voxels *v, voxgi_attribute which, float *dst,
                                                   size_t dst_bytes, size_t *needed)
{
    int first = 0, width = which == VOXGI_ATTRIBUTE_OPACITY ? 1 : 3, c;
    voxgi_blend blend;
    uint64_t i, n;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!v) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "voxels is NULL");
    if ((which != VOXGI_ATTRIBUTE_ALBEDO && which != VOXGI_ATTRIBUTE_NORMAL && which != VOXGI_ATTRIBUTE_EMISSION &&
         which != VOXGI_ATTRIBUTE_OPACITY) || !(v->info.attributes & (unsigned)which))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "attribute %d was not voxelized (held: 0x%x)", (int)which, v->info.attributes);
    n = v->info.voxel_count;
    if (needed) *needed = (size_t)(n * (uint64_t)width * 4);
    if (!dst) return needed ? VOXGI_OK : voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "dst and needed are both NULL");
    if (dst_bytes < n * (uint64_t)width * 4)
        return voxgi__fail(ctx, VOXGI_ERR_BUFFER_TOO_SMALL, "the attribute needs %llu bytes, dst has %lu",
                           (unsigned long long)(n * (uint64_t)width * 4), (unsigned long)dst_bytes);
    if ((unsigned)which > VOXGI_ATTRIBUTE_ALBEDO && (v->info.attributes & VOXGI_ATTRIBUTE_ALBEDO)) first += 3;
    if ((unsigned)which > VOXGI_ATTRIBUTE_NORMAL && (v->info.attributes & VOXGI_ATTRIBUTE_NORMAL)) first += 3;
    if ((unsigned)which > VOXGI_ATTRIBUTE_EMISSION && (v->info.attributes & VOXGI_ATTRIBUTE_EMISSION)) first += 3;
    blend = v->attr.blend[which == VOXGI_ATTRIBUTE_ALBEDO ? 0 : (which == VOXGI_ATTRIBUTE_NORMAL ? 1 : (which == VOXGI_ATTRIBUTE_EMISSION ? 2 : 3))];
    for (i = 0; i < n; i++)
        for (c = 0; c < width; c++) {
            int ch = first + c;
            double q = (double)v->attr.sum[i * (uint64_t)v->attr.channels + (uint64_t)ch], k = (double)v->attr.count[i], out;
            if (v->attr.values) out = v->attr.values[i * (uint64_t)v->attr.channels + (uint64_t)ch];
            else if (blend == VOXGI_BLEND_AVERAGE) out = v->attr.zero[ch] + q / k * v->attr.unit[ch];
            else if (blend == VOXGI_BLEND_ADD) out = k * v->attr.zero[ch] + q * v->attr.unit[ch];
            else out = v->attr.zero[ch] + q * v->attr.unit[ch];
            dst[i * (uint64_t)width + (uint64_t)c] = (float)out;
        }
    return VOXGI_OK;
}

VOXGI_API void voxgi_voxels_query(const voxgi_voxels *v, voxgi_voxels_info *out)
{
    if (!out) return;
    if (!v) { memset(out, 0, sizeof *out); return; }
    *out = v->info;
}

/* ----- 5.3 conservative, thin and solid (the GL triangle pass serves all three): CPU, then GL */

/* ----- CPU conservative voxelizer */
static void voxgi__set_voxel(const voxgi__vox_shared *vs, voxgi__stats *st, int64_t i, int64_t j, int64_t k)
{
    const voxgi_grid *g = vs->grid;
    uint64_t idx = (uint64_t)i + (uint64_t)g->res[0] * ((uint64_t)j + (uint64_t)g->res[1] * (uint64_t)k);
    uint32_t *w = vs->bits + (idx >> 5), mask = 1u << (idx & 31u);
    if (vs->attr) { voxgi__attr_add(vs->attr, vs->bits, idx, st->tri); return; }
    /* the old word tells whether this call set the bit, so counting costs nothing; read atomically,
       as other workers set bits of the same word */
    if (!(VOXGI__ATOMIC_LOAD_U32(w) & mask) && !(VOXGI__ATOMIC_OR_U32(w, mask) & mask)) st->voxels++;
}

/* Sets a voxel the conservative tests accepted (rel relative to t->lo), after the thin tests in thin mode. */
static void voxgi__emit(const voxgi__vox_shared *vs, voxgi__stats *st, const voxgi__tri *t, const int32_t rel[3])
{
    if (vs->thin && !voxgi__test_thin(vs, t, rel, st)) return;
    voxgi__set_voxel(vs, st, (int64_t)t->lo[0] + rel[0], (int64_t)t->lo[1] + rel[1], (int64_t)t->lo[2] + rel[2]);
}

static void voxgi__fill_range(const voxgi__vox_shared *vs, voxgi__stats *st, const int32_t lo[3], const int32_t hi[3])
{
    int32_t i, j, k;
    for (k = lo[2]; k <= hi[2]; k++)
        for (j = lo[1]; j <= hi[1]; j++)
            for (i = lo[0]; i <= hi[0]; i++) voxgi__set_voxel(vs, st, i, j, k);
}

/* Index range [ceil(lo)-1, floor(hi)] of closed unit cells meeting [lo, hi], clipped to [0, max]. */
static void voxgi__cell_range(double lo, double hi, int32_t max, int32_t *first, int32_t *last)
{
    double f = ceil(lo) - 1, l = floor(hi);
    *first = f < 0 ? 0 : (f > max ? max + 1 : (int32_t)f);
    *last = l > max ? max : (l < 0 ? -1 : (int32_t)l);
}

/* Degenerate triangles are the union of their edges: each edge is voxelized as a segment, slab
   by slab along its longest axis, with the exact line tests of all three projections. */
static void voxgi__voxelize_segment(const voxgi__vox_shared *vs, voxgi__tri *t, int k, voxgi__stats *st)
{
    const voxgi__vprep *p = &vs->vp[t->v[k]], *q = &vs->vp[t->v[(k + 1) % 3]];
    int32_t lo[3], hi[3], rel[3];
    int a, b, c, ax = 0;
    double m = 1e-3, len;
    for (a = 0; a < 3; a++) {
        /* the segment's own exact range, relative to the triangle's */
        lo[a] = VOXGI__MAX(t->lo[a], VOXGI__MIN(p->lo[a], q->lo[a])) - t->lo[a];
        hi[a] = VOXGI__MIN(t->hi[a], VOXGI__MAX(p->hi[a], q->hi[a])) - t->lo[a];
        if (lo[a] > hi[a]) return;
        if (fabs(t->e[k][a]) > fabs(t->e[k][ax])) ax = a;
        m += 1e-6 * (fabs(t->r[k][a]) + fabs(t->e[k][a]));
    }
    len = t->e[k][ax];
    if (len == 0) return; /* a point: the other edges cover it */
    /* this edge's line tests in the three projections */
    for (c = 0; c < 3; c++) {
        double mm[3] = {0, 0, 0}, dm[3] = {0, 0, 0};
        int pa = (c + 1) % 3, pb = (c + 2) % 3;
        t->proj_count[c] = 0;
        if (t->e[k][pa] == 0 && t->e[k][pb] == 0) continue;
        mm[pa] = -t->e[k][pb]; dm[pa] = t->de[k][pb];
        mm[pb] = t->e[k][pa]; dm[pb] = t->de[k][pa];
        voxgi__lin_make(t, &t->proj[c][0], mm, dm, k);
        t->proj[c][0].plane = (int8_t)c;
        t->proj[c][0].edge = (int8_t)k;
        t->proj[c][0].orient = 0;
        t->proj_count[c] = 1;
    }
    b = (ax + 1) % 3;
    c = (ax + 2) % 3;
    for (rel[ax] = lo[ax]; rel[ax] <= hi[ax]; rel[ax]++) {
        double t0 = ((double)rel[ax] - m - t->r[k][ax]) / len, t1 = ((double)rel[ax] + 1 + m - t->r[k][ax]) / len;
        int32_t b0, b1, c0, c1;
        if (t0 > t1) { double s = t0; t0 = t1; t1 = s; }
        t0 = VOXGI__MAX(t0, 0.0);
        t1 = VOXGI__MIN(t1, 1.0);
        if (t0 > t1) continue;
        {
            double ub0 = t->r[k][b] + t0 * t->e[k][b], ub1 = t->r[k][b] + t1 * t->e[k][b];
            double uc0 = t->r[k][c] + t0 * t->e[k][c], uc1 = t->r[k][c] + t1 * t->e[k][c];
            voxgi__cell_range(VOXGI__MIN(ub0, ub1) - m, VOXGI__MAX(ub0, ub1) + m, hi[b], &b0, &b1);
            voxgi__cell_range(VOXGI__MIN(uc0, uc1) - m, VOXGI__MAX(uc0, uc1) + m, hi[c], &c0, &c1);
        }
        for (rel[c] = VOXGI__MAX(c0, lo[c]); rel[c] <= c1; rel[c]++)
            for (rel[b] = VOXGI__MAX(b0, lo[b]); rel[b] <= b1; rel[b]++)
                if (voxgi__test_projection(vs, t, 0, rel, st) && voxgi__test_projection(vs, t, 1, rel, st) &&
                    voxgi__test_projection(vs, t, 2, rel, st))
                    voxgi__emit(vs, st, t, rel);
    }
}

/* The columns [first, last] of row rel[b] that can pass the oriented projection tests of axis c
   (a superset: each column is still tested exactly). */
static void voxgi__row_span(const voxgi__tri *t, int c, int32_t rel_b, int32_t ext_a, int32_t *first, int32_t *last)
{
    int a = (c + 1) % 3, b = (c + 2) % 3, i;
    double lo = 0, hi = (double)ext_a - 1;
    for (i = 0; i < t->proj_count[c] && t->proj[c][i].orient; i++) {
        const voxgi__lin *L = &t->proj[c][i];
        double g = L->v0[1] + L->k[b] * (double)rel_b + L->err, ka = L->k[a];
        /* need g + ka * A >= 0 (within the bound); one column of slack for the division */
        if (ka > 0) lo = VOXGI__MAX(lo, floor(-g / ka) - 1);
        else if (ka < 0) hi = VOXGI__MIN(hi, ceil(-g / ka) + 1);
        else if (g < 0) hi = -1;
    }
    *first = lo > hi ? 1 : (int32_t)lo;
    *last = lo > hi ? 0 : (int32_t)hi;
}

/* A triangle ready for its column loop: columns along axis c, rows along b = (c + 2) % 3. */
typedef struct voxgi__prepared {
    voxgi__tri t;
    int c, single;
    int32_t ext[3];
} voxgi__prepared;

/* Everything before the column loop. Returns 0 when the triangle is already done (outside the
   grid, a column or voxel, a segment or point), else 1 with its rows still to visit. */
static int voxgi__tri_prepare(const voxgi__vox_shared *vs, size_t ti, voxgi__prepared *P, voxgi__stats *st)
{
    voxgi__tri *t = &P->t;
    int a, thin = 0;
    if (!voxgi__tri_setup(vs, ti, t)) return 0;
    P->single = -1;
    for (a = 0; a < 3; a++) {
        P->ext[a] = t->hi[a] - t->lo[a] + 1;
        if (t->one_slice[a]) { thin++; P->single = a; }
    }
    /* a single column or voxel: every voxel of the exact range meets the triangle (the thin
       tests still need the column loop) */
    if (thin >= 2 && !vs->thin) { voxgi__fill_range(vs, st, t->lo, t->hi); return 0; }
    voxgi__tri_resolve_signs(vs, t, st);
    if ((t->sig[0] | t->sig[1] | t->sig[2]) == 0) {
        if (t->e[0][0] == 0 && t->e[0][1] == 0 && t->e[0][2] == 0 && t->e[1][0] == 0 && t->e[1][1] == 0 && t->e[1][2] == 0) {
            voxgi__fill_range(vs, st, t->lo, t->hi); /* a point */
            return 0;
        }
        for (a = 0; a < 3; a++) voxgi__voxelize_segment(vs, t, a, st);
        return 0;
    }
    voxgi__tri_forms(t);
    /* Columns along c: a single slice's own axis (then its projection decides alone), else the
       dominant normal axis, where the plane crosses each column in at most three voxels. */
    if (P->single >= 0) P->c = P->single;
    else {
        P->c = -1;
        for (a = 0; a < 3; a++)
            if (t->sig[a] != 0 && (P->c < 0 || fabs(t->n[a]) > fabs(t->n[P->c]))) P->c = a;
    }
    return 1;
}

/* The column loop over rows [row_first, row_last] (relative to the range). */
static void voxgi__tri_rows(const voxgi__vox_shared *vs, const voxgi__prepared *P, int32_t row_first, int32_t row_last,
                            voxgi__stats *st)
{
    const voxgi__tri *t = &P->t;
    const int32_t *ext = P->ext;
    int c = P->c, single = P->single, a = (c + 1) % 3, b = (c + 2) % 3;
    int32_t rel[3];
    for (rel[b] = row_first; rel[b] <= row_last; rel[b]++) {
        int32_t first = 0, last = ext[a] - 1;
        if (t->sig[c] != 0) voxgi__row_span(t, c, rel[b], ext[a], &first, &last);
        for (rel[a] = first; rel[a] <= last; rel[a]++) {
            int32_t k0, k1;
            rel[c] = 0;
            if (!voxgi__test_projection(vs, t, c, rel, st)) continue;
            if (single >= 0) {
                voxgi__emit(vs, st, t, rel);
                continue;
            }
            {
                double nc = t->n[c], dsum = t->dn[0] + t->dn[1] + t->dn[2];
                if (fabs(nc) <= 4 * dsum) { k0 = 0; k1 = ext[c] - 1; } /* slopes unreliable: whole range */
                else {
                    double ka = -t->n[a] / nc, kb = -t->n[b] / nc;
                    double Da = fabs((double)rel[a] - t->r[0][a]) + 1, Db = fabs((double)rel[b] - t->r[0][b]) + 1;
                    double z0 = t->r[0][c] + ka * ((double)rel[a] - t->r[0][a]) + kb * ((double)rel[b] - t->r[0][b]);
                    double dka = (t->dn[a] + fabs(ka) * t->dn[c]) / (fabs(nc) - t->dn[c]);
                    double dkb = (t->dn[b] + fabs(kb) * t->dn[c]) / (fabs(nc) - t->dn[c]);
                    double m = 2 * (dka * Da + dkb * Db) + 2 * (t->dr[0][c] + fabs(ka) * t->dr[0][a] + fabs(kb) * t->dr[0][b]) +
                               1e-9 * (1 + fabs(z0) + fabs(ka) * Da + fabs(kb) * Db);
                    double zmin = z0 + VOXGI__MIN(ka, 0.0) + VOXGI__MIN(kb, 0.0), zmax = z0 + VOXGI__MAX(ka, 0.0) + VOXGI__MAX(kb, 0.0);
                    voxgi__cell_range(zmin - m, zmax + m, ext[c] - 1, &k0, &k1);
                }
            }
            for (rel[c] = k0; rel[c] <= k1; rel[c]++)
                if (voxgi__test_lin(vs, t, &t->plane, rel, st) && voxgi__test_projection(vs, t, a, rel, st) &&
                    voxgi__test_projection(vs, t, b, rel, st))
                    voxgi__emit(vs, st, t, rel);
        }
    }
}

#ifndef VOXGI_NO_GL
/* One whole triangle on the calling thread: the GL pass's referee for triangles it hands over. */
static void voxgi__vox_conservative_cpu(const voxgi__vox_shared *vs, size_t ti, voxgi__stats *st)
{
    voxgi__prepared P;
    if (voxgi__tri_prepare(vs, ti, &P, st)) voxgi__tri_rows(vs, &P, 0, P.ext[(P.c + 2) % 3] - 1, st);
}
#endif

/* ----- CPU solid voxelization: each triangle toggles, in every column whose centre it owns,
   the first voxel whose centre lies at or above it; a prefix XOR along the axis then turns the
   toggles into parity. */

/* Exact sign of form L at rel + off (off: 0, 1/2 or 1 per axis), per-voxel bound first. */
static int voxgi__form_sign(const voxgi__vox_shared *vs, const voxgi__tri *t, const voxgi__lin *L, const int32_t rel[3],
                            const double off[3], voxgi__stats *st)
{
    double v = 0, e = 0, gm = 0, g[3];
    int a, s;
    for (a = 0; a < 3; a++) {
        double ta = ((double)rel[a] + off[a]) - t->r[(int)L->vertex][a];
        double dt = t->dr[(int)L->vertex][a] + VOXGI__U * fabs(ta);
        v += L->k[a] * ta;
        e += fabs(L->k[a]) * dt + L->dk[a] * fabs(ta) + L->dk[a] * dt;
        gm += fabs(L->k[a] * ta);
    }
    e += VOXGI__GAMMA(3) * gm * 1.01;
    s = voxgi__sign_within(v, e == 0 ? 0.0 : e * 1.001);
    if (s != VOXGI__UNKNOWN) return s;
    for (a = 0; a < 3; a++) g[a] = (double)((int64_t)t->lo[a] + rel[a]) + off[a];
    st->exact_tests++;
    return voxgi__exact_form(vs, t, L, g, -1, 0);
}

/* Does the centre of column rel belong to the triangle's projection along A (with ties)? */
static int voxgi__owns_centre(const voxgi__vox_shared *vs, const voxgi__tri *t, int A, const int32_t rel[3], voxgi__stats *st)
{
    static const double centre[3] = {0.5, 0.5, 0.5};
    int i, a = (A + 1) % 3, b = (A + 2) % 3;
    for (i = 0; i < t->proj_count[A]; i++) {
        const voxgi__lin *L = &t->proj[A][i];
        int s = voxgi__form_sign(vs, t, L, rel, centre, st);
        if (s < 0) return 0;
        if (s == 0) { /* on the edge: owned by the side the CCW direction's perturbation picks */
            double da = L->orient * t->e[(int)L->edge][a], db = L->orient * t->e[(int)L->edge][b];
            if (!(db < 0 || (db == 0 && da > 0))) return 0;
        }
    }
    return 1;
}

static void voxgi__toggle_voxel(const voxgi__vox_shared *vs, int64_t i, int64_t j, int64_t k)
{
    const voxgi_grid *g = vs->grid;
    uint64_t idx = (uint64_t)i + (uint64_t)g->res[0] * ((uint64_t)j + (uint64_t)g->res[1] * (uint64_t)k);
#if defined(__GNUC__) || defined(__clang__)
    __atomic_fetch_xor(vs->bits + (idx >> 5), 1u << (idx & 31u), __ATOMIC_RELAXED);
#else
    vs->bits[idx >> 5] ^= 1u << (idx & 31u);
#endif
}

/* One column of a solid triangle (rel[a], rel[b] relative to t->lo): when the triangle owns its
   centre, toggle the first voxel whose centre lies at or above the triangle. */
static void voxgi__solid_column(const voxgi__vox_shared *vs, const voxgi__tri *t, int32_t rel[3], voxgi__stats *st)
{
    static const double centre[3] = {0.5, 0.5, 0.5};
    int A = vs->solid_axis, a = (A + 1) % 3, b = (A + 2) % 3;
    int32_t k, kmax = vs->grid->res[A] - 1 - t->lo[A]; /* the last slice, relative */
    double zc;
    rel[A] = 0;
    if (!voxgi__owns_centre(vs, t, A, rel, st)) return;
    /* estimate the first centre at or above the plane, then step with exact signs */
    zc = ceil(t->r[0][A] - (t->n[a] * ((double)rel[a] + 0.5 - t->r[0][a]) + t->n[b] * ((double)rel[b] + 0.5 - t->r[0][b])) / t->n[A] - 0.5);
    if (!(zc >= -t->lo[A])) k = -t->lo[A]; /* also when the rounded normal lost the axis */
    else k = zc > kmax + 1 ? kmax + 1 : (int32_t)zc;
    for (;;) {
        rel[A] = k - 1;
        if (k <= -t->lo[A] || t->sig[A] * voxgi__form_sign(vs, t, &t->plane, rel, centre, st) < 0) break;
        k--;
    }
    for (;;) {
        rel[A] = k;
        if (k > kmax || t->sig[A] * voxgi__form_sign(vs, t, &t->plane, rel, centre, st) >= 0) break;
        k++;
    }
    if (k <= kmax) {
        int64_t v[3];
        v[a] = (int64_t)t->lo[a] + rel[a];
        v[b] = (int64_t)t->lo[b] + rel[b];
        v[A] = (int64_t)t->lo[A] + k;
        voxgi__toggle_voxel(vs, v[0], v[1], v[2]);
    }
}

/* Sets up a triangle for the solid pass along vs->solid_axis; 0 when it owns no centre. */
static int voxgi__solid_setup(const voxgi__vox_shared *vs, size_t ti, voxgi__tri *t, voxgi__stats *st)
{
    if (!voxgi__tri_setup(vs, ti, t)) return 0;
    voxgi__tri_resolve_signs(vs, t, st);
    if (t->sig[vs->solid_axis] == 0) return 0; /* seen edge-on (or degenerate) */
    voxgi__tri_forms(t);
    return 1;
}

static void voxgi__vox_solid_cpu(const voxgi__vox_shared *vs, size_t ti, voxgi__stats *st)
{
    voxgi__tri t;
    int A = vs->solid_axis, a = (A + 1) % 3, b = (A + 2) % 3;
    int32_t rel[3];
    if (!voxgi__solid_setup(vs, ti, &t, st)) return;
    for (rel[b] = 0; rel[b] <= t.hi[b] - t.lo[b]; rel[b]++) {
        int32_t first, last;
        voxgi__row_span(&t, A, rel[b], t.hi[a] - t.lo[a] + 1, &first, &last);
        for (rel[a] = first; rel[a] <= last; rel[a]++) voxgi__solid_column(vs, &t, rel, st);
    }
}

/* XOR of bit ranges: dst[db .. db+n) ^= src[sb .. sb+n), any alignment (dst after src). */
static void voxgi__xor_bit_range(uint32_t *bits, uint64_t db, uint64_t sb, uint64_t n)
{
    while (n) {
        uint32_t chunk = (uint32_t)VOXGI__MIN(n, (uint64_t)(32 - (db & 31)));
        uint64_t s0 = sb >> 5;
        uint32_t so = (uint32_t)(sb & 31), word = bits[s0] >> so, mask;
        if (so && so + chunk > 32) word |= bits[s0 + 1] << (32 - so);
        mask = chunk == 32 ? 0xffffffffu : ((1u << chunk) - 1u);
        bits[db >> 5] ^= (word & mask) << (db & 31);
        db += chunk;
        sb += chunk;
        n -= chunk;
    }
}

/* Turns toggles into parity: every voxel becomes the XOR of itself and all below it on axis A. */
static void voxgi__prefix_xor(uint32_t *bits, const voxgi_grid *g, int A)
{
    uint64_t nx = (uint64_t)g->res[0], ny = (uint64_t)g->res[1], nz = (uint64_t)g->res[2], i, j, k;
    if (A == 2) {
        for (k = 1; k < nz; k++) voxgi__xor_bit_range(bits, k * nx * ny, (k - 1) * nx * ny, nx * ny);
    } else if (A == 1) {
        for (k = 0; k < nz; k++)
            for (j = 1; j < ny; j++) voxgi__xor_bit_range(bits, (k * ny + j) * nx, (k * ny + j - 1) * nx, nx);
    } else {
        for (k = 0; k < nz; k++)
            for (j = 0; j < ny; j++) {
                uint32_t parity = 0;
                for (i = 0; i < nx; i++) {
                    uint64_t l = i + nx * (j + ny * k);
                    parity ^= (bits[l >> 5] >> (l & 31)) & 1u;
                    bits[l >> 5] = (bits[l >> 5] & ~(1u << (l & 31))) | (parity << (l & 31));
                }
            }
    }
}

static uint64_t voxgi__vox_count_cpu(const uint32_t *w, uint64_t n)
{
    uint64_t i, c = 0;
    for (i = 0; i < n; i++) {
        uint32_t x = w[i];
        x = x - ((x >> 1) & 0x55555555u);
        x = (x & 0x33333333u) + ((x >> 2) & 0x33333333u);
        c += (((x + (x >> 4)) & 0x0F0F0F0Fu) * 0x01010101u) >> 24;
    }
    return c;
}

/* Flood fill from the grid's boundary through empty voxels (6-connected), by sweeps along
   every line of each axis in both directions until nothing changes; returns the solid: what the
   flood does not reach. Lines run in parallel (a bit set by another line late is seen by the
   next sweep; the fixed point does not depend on the order). */
typedef struct voxgi__flood_job {
    const voxgi_grid *g;
    const uint32_t *bits;
    uint32_t *out;
    int axis, changed;
} voxgi__flood_job;

#define VOXGI__GET(b, l) (((b)[(l) >> 5] >> ((l) & 31)) & 1u)

static void voxgi__flood_lines(void *user, size_t first, size_t end)
{
    voxgi__flood_job *job = (voxgi__flood_job *)user;
    uint64_t n[3], len, stride, line, t;
    int axis = job->axis, changed = 0, d;
    n[0] = (uint64_t)job->g->res[0]; n[1] = (uint64_t)job->g->res[1]; n[2] = (uint64_t)job->g->res[2];
    len = n[axis];
    stride = axis == 0 ? 1 : (axis == 1 ? n[0] : n[0] * n[1]);
    for (line = first; line < end; line++) {
        uint64_t c[3], base;
        c[axis] = 0;
        c[(axis + 1) % 3] = line % n[(axis + 1) % 3];
        c[(axis + 2) % 3] = line / n[(axis + 1) % 3];
        base = c[0] + n[0] * (c[1] + n[1] * c[2]);
        for (d = 0; d < 2; d++) {
            int reach = 0;
            for (t = 0; t < len; t++) {
                uint64_t l = base + stride * (d ? len - 1 - t : t);
                if (VOXGI__GET(job->bits, l)) reach = 0;
                else if ((VOXGI__ATOMIC_LOAD_U32(&job->out[l >> 5]) >> (l & 31)) & 1u) reach = 1;
                else if (reach) { VOXGI__ATOMIC_OR_U32(&job->out[l >> 5], 1u << (l & 31)); changed = 1; }
            }
        }
    }
    if (changed) VOXGI__ATOMIC_STORE_INT(&job->changed, 1);
}

static voxgi_result voxgi__vox_flood_cpu(voxgi_context *ctx, const voxgi_grid *g, uint32_t *bits)
{
    uint64_t nx = (uint64_t)g->res[0], ny = (uint64_t)g->res[1], nz = (uint64_t)g->res[2], words = voxgi__grid_words(g);
    uint64_t i, j, k;
    voxgi__flood_job job;
    if (!(job.out = (uint32_t *)voxgi__alloc_array(ctx, (size_t)words, 4, 1))) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the flood fill");
    job.g = g;
    job.bits = bits;
    /* seeds: empty voxels on the boundary */
    for (k = 0; k < nz; k++)
        for (j = 0; j < ny; j++)
            for (i = 0; i < nx; i++) {
                uint64_t l = i + nx * (j + ny * k);
                if ((i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1) && !VOXGI__GET(bits, l))
                    job.out[l >> 5] |= 1u << (l & 31);
            }
    do {
        job.changed = 0;
        for (job.axis = 0; job.axis < 3; job.axis++) {
            uint64_t n[3];
            n[0] = nx; n[1] = ny; n[2] = nz;
            voxgi__parallel(ctx, (size_t)(n[(job.axis + 1) % 3] * n[(job.axis + 2) % 3]), 64, voxgi__flood_lines, &job);
        }
    } while (job.changed);
    for (i = 0; i < words; i++) bits[i] = ~job.out[i];
    if (voxgi_grid_voxel_count(g) % 32) bits[words - 1] &= (1u << (voxgi_grid_voxel_count(g) % 32)) - 1u;
    voxgi__free(ctx, job.out);
    return VOXGI_OK;
}
#undef VOXGI__GET

#ifndef VOXGI_NO_GL

/* GL voxelizers
   The twins of the CPU parts above, one GL pass per method (GLSL in shaders/). The CPU prepares
   each vertex (voxel coordinates and exact ranges, O(vertices)); the GPU does everything per
   triangle, fragment and voxel; what an exact pass's filter cannot decide comes back here and is
   decided exactly, so the bits equal the CPU's. */
typedef struct voxgi__vox_vprep_gl { double q[4]; int32_t lo[4], hi[4]; float w[4], pad[4]; } voxgi__vox_vprep_gl; /* std430 */

#define VOXGI__GL_PAIR_CAPACITY 65536u

/* Uploads the prepared vertices (binding 0) and the triangles (binding 1). */
static void voxgi__vox_scene_buffers_gl(voxgi_context *ctx, const voxgi__flat *f, const voxgi__vprep *vp, unsigned int *verts,
                                    unsigned int *tris, voxgi_result *r)
{
    voxgi__vox_vprep_gl *gv = (voxgi__vox_vprep_gl *)voxgi__alloc_array(ctx, f->vertex_count, sizeof *gv, 1);
    size_t v;
    int i;
    *verts = *tris = 0;
    if (!gv) { *r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu vertices", (unsigned long)f->vertex_count); return; }
    for (v = 0; v < f->vertex_count; v++)
        for (i = 0; i < 3; i++) gv[v].q[i] = vp[v].q[i];
    *verts = voxgi__gl_buffer(ctx, f->vertex_count * sizeof *gv, gv);
    *tris = voxgi__gl_buffer(ctx, f->triangle_count * 3 * sizeof(uint32_t), f->tri);
    voxgi__free(ctx, gv);
    ctx->gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, VOXGI__BINDING_VERTICES, *verts);
    ctx->gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, VOXGI__BINDING_TRIANGLES, *tris);
}

/* Pass 0 over all triangles (in slices of at most 65535 work groups), then pass 1 over the big
   ones it listed, sized on the GPU; the program's other uniforms are set by the caller. */
static void voxgi__vox_dispatch_triangles_gl(voxgi__gl *gl, unsigned int p, size_t nt, unsigned int control)
{
    size_t t0;
    gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, 0);
    for (t0 = 0; t0 < nt; t0 += 65535u * 64u) {
        gl->ProgramUniform1ui(p, VOXGI__LOC_u_tri_offset, (unsigned)t0);
        gl->DispatchCompute((unsigned)VOXGI__MIN((nt - t0 + 63) / 64, (size_t)65535), 1, 1);
    }
    gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT | VOXGI__GL_COMMAND_BARRIER_BIT);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, 1);
    gl->BindBuffer(VOXGI__GL_DISPATCH_INDIRECT_BUFFER, control);
    gl->DispatchComputeIndirect(0);
    gl->BindBuffer(VOXGI__GL_DISPATCH_INDIRECT_BUFFER, 0);
    gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT | VOXGI__GL_BUFFER_UPDATE_BARRIER_BIT);
}

/* The geometry-shader voxelizer's draw: every triangle once into an attachment-less
   framebuffer of view x view pixels (voxel columns); the caller's GL state is restored. */
static void voxgi__vox_draw_geometry_gl(voxgi__gl *gl, unsigned int p, size_t nt, int view)
{
    voxgi__gl_raster_state state;
    unsigned int fbo = 0, vao = 0;
    voxgi__gl_raster_begin(gl, &state);
    gl->CreateVertexArrays(1, &vao);
    gl->CreateFramebuffers(1, &fbo);
    gl->NamedFramebufferParameteri(fbo, VOXGI__GL_FRAMEBUFFER_DEFAULT_WIDTH, view);
    gl->NamedFramebufferParameteri(fbo, VOXGI__GL_FRAMEBUFFER_DEFAULT_HEIGHT, view);
    gl->BindFramebuffer(VOXGI__GL_FRAMEBUFFER, fbo);
    gl->BindVertexArray(vao);
    gl->Viewport(0, 0, view, view);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_view, view);
    gl->DrawArrays(VOXGI__GL_TRIANGLES, 0, (int)(3 * nt));
    gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT | VOXGI__GL_BUFFER_UPDATE_BARRIER_BIT);
    gl->BindFramebuffer(VOXGI__GL_FRAMEBUFFER, 0);
    gl->BindVertexArray(0);
    gl->DeleteFramebuffers(1, &fbo);
    gl->DeleteVertexArrays(1, &vao);
    voxgi__gl_raster_end(gl, &state);
}

/* Runs the conservative tests of every triangle: compute dispatches, or the geometry draw. */
static void voxgi__vox_conservative_gl(voxgi__gl *gl, const voxgi_voxelize_desc *d, unsigned int p, size_t nt, unsigned int control)
{
    if (d->method == VOXGI_METHOD_GEOMETRY)
        voxgi__vox_draw_geometry_gl(gl, p, nt, VOXGI__MAX(d->grid.res[0], VOXGI__MAX(d->grid.res[1], d->grid.res[2])));
    else voxgi__vox_dispatch_triangles_gl(gl, p, nt, control);
}

/* The attribute pass after the conservative (or thin) bits are final in buf[VOXGI__BINDING_BITS]: the same
   triangles again, each set voxel receiving its triangles' values on the GPU; the triangles the
   bit pass flagged (buf[VOXGI__BINDING_FLAGS]) and the pairs its filter could not decide are added here, exactly.
   pair_capacity: the bit pass's pair count, which this pass cannot exceed. */
static voxgi_result voxgi__vox_attributes_gl(voxgi_context *ctx, const voxgi__flat *f, const voxgi__vprep *vp,
                                             const voxgi_voxelize_desc *d, const unsigned int *buf, uint32_t pair_capacity,
                                             voxgi__attr *attr)
{
    voxgi__gl *gl = ctx->gl;
    const voxgi_grid *g = &d->grid;
    uint64_t words = voxgi__grid_words(g), voxels = 0, w, stride = 1 + 2 * (uint64_t)attr->channels, s;
    size_t nt = f->triangle_count, flag_words = (nt + 31) / 32, k;
    unsigned int control_buf = 0, pairs_buf = 0, rank_buf = 0, rec_buf = 0, sums_buf = 0, zero = 0;
    unsigned int p = d->method == VOXGI_METHOD_GEOMETRY ? gl->prog_voxelize_geometry : gl->prog_voxelize_conservative;
    uint32_t control[8], *bits = (uint32_t *)voxgi__alloc_array(ctx, (size_t)words, 4, 0), *sums = NULL, *flags = NULL, *pairs = NULL;
    voxgi_result r = VOXGI_OK;
    if (!bits) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the attribute pass");
    r = voxgi__gl_read_buffer(ctx, buf[VOXGI__BINDING_BITS], bits, (size_t)words * 4);
    for (w = 0; w < words; w++) voxels += voxgi__popcount32(bits[w]);
    if (r == VOXGI_OK && voxels * stride * 4 > (uint64_t)gl->max_ssbo_bytes)
        r = voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "the attribute sums of %llu voxels exceed GL_MAX_SHADER_STORAGE_BLOCK_SIZE; "
                        "use the CPU backend", (unsigned long long)voxels);
    if (r == VOXGI_OK) r = voxgi__attr_alloc(ctx, attr, bits, words, voxels);
    if (r == VOXGI_OK) {
        memset(control, 0, sizeof control);
        control[1] = control[2] = 1;
        control_buf = voxgi__gl_buffer(ctx, sizeof control, control);
        pairs_buf = voxgi__gl_buffer(ctx, (size_t)VOXGI__MAX(pair_capacity, 1u) * 16, NULL);
        rank_buf = voxgi__gl_buffer(ctx, (size_t)words * 4, attr->rank);
        rec_buf = voxgi__gl_buffer(ctx, nt * (size_t)attr->channels * 4, attr->rec);
        sums_buf = voxgi__gl_buffer(ctx, (size_t)(voxels * stride * 4), NULL);
        gl->ClearNamedBufferData(sums_buf, VOXGI__GL_R32UI, VOXGI__GL_RED_INTEGER, VOXGI__GL_UNSIGNED_INT, &zero);
        r = voxgi__gl_check(ctx, "allocating the attribute buffers");
    }
    if (r == VOXGI_OK) {
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, VOXGI__BINDING_CONTROL, control_buf);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, VOXGI__BINDING_PAIRS, pairs_buf);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, VOXGI__BINDING_RANK, rank_buf);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, VOXGI__BINDING_RECORDS, rec_buf);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, VOXGI__BINDING_SUMS, sums_buf);
        gl->UseProgram(p);
        gl->ProgramUniform1ui(p, VOXGI__LOC_u_pair_capacity, pair_capacity);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_attr, 1);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_channels, attr->channels);
        {
            unsigned int max_channels = 0;
            int c;
            for (c = 0; c < attr->channels; c++) max_channels |= (unsigned)attr->max_op[c] << c;
            gl->ProgramUniform1ui(p, VOXGI__LOC_u_max_channels, max_channels);
        }
        voxgi__vox_conservative_gl(gl, d, p, nt, control_buf);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_attr, 0);
        for (k = VOXGI__BINDING_RANK; k <= VOXGI__BINDING_SUMS; k++) gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, (unsigned)k, 0);
        r = voxgi__gl_read_buffer(ctx, control_buf, control, sizeof control);
        if (r == VOXGI_OK && control[4] > pair_capacity)
            r = voxgi__fail(ctx, VOXGI_ERR_GL, "the attribute pass found %u undecided pairs, the bit pass %u", control[4], pair_capacity);
    }
    if (r == VOXGI_OK) { /* the GPU's sums, then the CPU's share */
        sums = (uint32_t *)voxgi__alloc_array(ctx, (size_t)(voxels ? voxels * stride : 1), 4, 0);
        flags = (uint32_t *)voxgi__alloc_array(ctx, flag_words ? flag_words : 1, 4, 0);
        pairs = (uint32_t *)voxgi__alloc_array(ctx, (size_t)VOXGI__MAX(control[4], 1u), 16, 0);
        if (!sums || !flags || !pairs) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory to read the attribute sums");
        if (r == VOXGI_OK) r = voxgi__gl_read_buffer(ctx, sums_buf, sums, (size_t)(voxels * stride * 4));
        if (r == VOXGI_OK) r = voxgi__gl_read_buffer(ctx, buf[VOXGI__BINDING_FLAGS], flags, flag_words * 4);
        if (r == VOXGI_OK && control[4]) r = voxgi__gl_read_buffer(ctx, pairs_buf, pairs, (size_t)control[4] * 16);
    }
    if (r == VOXGI_OK) {
        voxgi__vox_shared vs;
        voxgi__stats st = {0, 0, 0};
        int c, i;
        for (s = 0; s < voxels; s++) {
            attr->count[s] = sums[s * stride];
            for (c = 0; c < attr->channels; c++)
                attr->sum[s * (uint64_t)attr->channels + (uint64_t)c] =
                    (uint64_t)sums[s * stride + 1 + 2 * (uint64_t)c] | ((uint64_t)sums[s * stride + 2 + 2 * (uint64_t)c] << 32);
        }
        voxgi__vox_shared_init(&vs, g, f, vp, d->method, bits);
        vs.attr = attr;
        for (k = 0; k < nt; k++)
            if (flags[k >> 5] & (1u << (k & 31u))) {
                st.tri = (uint32_t)k;
                voxgi__vox_conservative_cpu(&vs, k, &st);
            }
        for (k = 0; k < control[4]; k++) {
            voxgi__tri t;
            const uint32_t *pr = pairs + 4 * k;
            int32_t rel[3];
            st.tri = pr[0];
            if (!voxgi__tri_setup(&vs, pr[0], &t)) continue;
            voxgi__tri_resolve_signs(&vs, &t, &st);
            voxgi__tri_forms(&t);
            for (i = 0; i < 3; i++) rel[i] = (int32_t)pr[1 + i] - t.lo[i];
            if (voxgi__test_voxel(&vs, &t, rel, &st)) voxgi__emit(&vs, &st, &t, rel);
        }
    }
    voxgi__gl_delete_buffer(ctx, control_buf);
    voxgi__gl_delete_buffer(ctx, pairs_buf);
    voxgi__gl_delete_buffer(ctx, rank_buf);
    voxgi__gl_delete_buffer(ctx, rec_buf);
    voxgi__gl_delete_buffer(ctx, sums_buf);
    voxgi__free(ctx, bits);
    voxgi__free(ctx, sums);
    voxgi__free(ctx, flags);
    voxgi__free(ctx, pairs);
    return r;
}

/* The triangle pass: conservative/thin voxels (solid_axis < 0) or solid toggles along
   solid_axis, into a new buffer *bits_out. What the GPU's filter cannot decide is decided here
   exactly and written back. */

static voxgi_result voxgi__vox_triangles_gl(voxgi_context *ctx, const voxgi__flat *f, const voxgi__vprep *vp,
                                            const voxgi_voxelize_desc *d, int solid_axis, unsigned int *bits_out,
                                            voxgi_voxels_info *info, voxgi__attr *attr)
{
    voxgi__gl *gl = ctx->gl;
    const voxgi_grid *g = &d->grid;
    size_t bytes = (size_t)voxgi__grid_words(g) * 4, v, nt = f->triangle_count, flag_words = (nt + 31) / 32;
    unsigned int buf[VOXGI__BINDING_BIG + 1] = {0, 0, 0, 0, 0, 0, 0}, zero = 0, capacity = VOXGI__GL_PAIR_CAPACITY; /* by binding */
    uint32_t control[8];
    voxgi__vox_vprep_gl *gv;
    uint32_t *copy = NULL, *flags = NULL, *pairs = NULL;
    unsigned int p = solid_axis >= 0 ? gl->prog_voxelize_solid
                     : (d->method == VOXGI_METHOD_GEOMETRY ? gl->prog_voxelize_geometry : gl->prog_voxelize_conservative);
    voxgi_result r;
    int i, attempt;
    gv = (voxgi__vox_vprep_gl *)voxgi__alloc_array(ctx, f->vertex_count, sizeof *gv, 1);
    if (!gv) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu vertices", (unsigned long)f->vertex_count);
    for (v = 0; v < f->vertex_count; v++) {
        for (i = 0; i < 3; i++) {
            gv[v].q[i] = vp[v].q[i];
            gv[v].lo[i] = vp[v].lo[i];
            gv[v].hi[i] = vp[v].hi[i];
            gv[v].w[i] = f->pos[3 * v + (size_t)i];
        }
        gv[v].q[3] = vp[v].frac_bits;
        gv[v].lo[3] = vp[v].exact_axes;
    }
    buf[VOXGI__BINDING_VERTICES] = voxgi__gl_buffer(ctx, f->vertex_count * sizeof *gv, gv);
    buf[VOXGI__BINDING_TRIANGLES] = voxgi__gl_buffer(ctx, nt * 3 * sizeof(uint32_t), f->tri);
    buf[VOXGI__BINDING_BIG] = voxgi__gl_buffer(ctx, nt * 4, NULL);
    voxgi__free(ctx, gv);
    /* a solid pass whose pair list overflowed runs again with room for all of them: toggles
       cannot be patched the way set bits can */
    for (attempt = 0; attempt < 2; attempt++) {
        memset(control, 0, sizeof control);
        control[1] = 1; /* work groups per big triangle: raised by pass 0 */
        control[2] = 1;
        buf[VOXGI__BINDING_BITS] = voxgi__gl_grid_buffer(ctx, bytes);
        buf[VOXGI__BINDING_CONTROL] = voxgi__gl_buffer(ctx, sizeof control, control);
        buf[VOXGI__BINDING_PAIRS] = voxgi__gl_buffer(ctx, (size_t)capacity * 16, NULL);
        buf[VOXGI__BINDING_FLAGS] = voxgi__gl_buffer(ctx, flag_words * 4, NULL);
        gl->ClearNamedBufferData(buf[VOXGI__BINDING_FLAGS], VOXGI__GL_R32UI, VOXGI__GL_RED_INTEGER, VOXGI__GL_UNSIGNED_INT, &zero);
        r = voxgi__gl_check(ctx, "allocating the voxelization buffers");
        if (r != VOXGI_OK) break;
        for (i = 0; i <= VOXGI__BINDING_BIG; i++) gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, (unsigned)i, buf[i]);
        gl->UseProgram(p);
        gl->ProgramUniform3i(p, VOXGI__LOC_u_res, g->res[0], g->res[1], g->res[2]);
        gl->ProgramUniform1ui(p, VOXGI__LOC_u_tri_count, (unsigned)nt);
        gl->ProgramUniform1d(p, VOXGI__LOC_u_inv_s, 1.0 / g->voxel_size);
        gl->ProgramUniform1ui(p, VOXGI__LOC_u_pair_capacity, capacity);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_solid_axis, solid_axis);
        if (solid_axis < 0) { /* the solid program has no thin test and no attributes */
            gl->ProgramUniform1i(p, VOXGI__LOC_u_thin, d->method == VOXGI_METHOD_THIN);
            gl->ProgramUniform1i(p, VOXGI__LOC_u_attr, 0);
        }
        voxgi__vox_conservative_gl(gl, d, p, nt, buf[VOXGI__BINDING_CONTROL]);
        r = voxgi__gl_read_buffer(ctx, buf[VOXGI__BINDING_CONTROL], control, sizeof control);
        if (r != VOXGI_OK || solid_axis < 0 || control[4] <= capacity) break;
        capacity = control[4];
        for (i = 2; i < 6; i++) { voxgi__gl_delete_buffer(ctx, buf[i]); buf[i] = 0; }
    }
    /* the undecided: control[4] pairs, control[5] flagged triangles */
    if (r == VOXGI_OK && (control[4] || control[5])) {
        size_t np = VOXGI__MIN((size_t)control[4], (size_t)capacity), k;
        copy = (uint32_t *)voxgi__alloc(ctx, bytes);
        flags = (uint32_t *)voxgi__alloc_array(ctx, flag_words, 4, 0);
        pairs = (uint32_t *)voxgi__alloc_array(ctx, np, 16, 0);
        if (!copy || !flags || !pairs) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory to resolve the GL pass's undecided tests");
        if (r == VOXGI_OK) r = voxgi__gl_read_buffer(ctx, buf[VOXGI__BINDING_BITS], copy, bytes);
        if (r == VOXGI_OK) r = voxgi__gl_read_buffer(ctx, buf[VOXGI__BINDING_FLAGS], flags, flag_words * 4);
        if (r == VOXGI_OK && np) r = voxgi__gl_read_buffer(ctx, buf[VOXGI__BINDING_PAIRS], pairs, np * 16);
        if (r == VOXGI_OK) {
            voxgi__vox_shared vs;
            voxgi__stats st = {0, 0, 0};
            voxgi__vox_shared_init(&vs, g, f, vp, d->method, copy);
            vs.solid_axis = solid_axis;
            for (k = 0; k < nt; k++)
                if (flags[k >> 5] & (1u << (k & 31u))) {
                    if (solid_axis >= 0) voxgi__vox_solid_cpu(&vs, k, &st);
                    else voxgi__vox_conservative_cpu(&vs, k, &st);
                    info->exact_triangles++;
                }
            for (k = 0; k < np; k++) {
                voxgi__tri t;
                const uint32_t *pr = pairs + 4 * k;
                int32_t rel[3];
                if (solid_axis >= 0) {
                    if (!voxgi__solid_setup(&vs, pr[0], &t, &st)) continue;
                    for (i = 0; i < 3; i++) rel[i] = (int32_t)pr[1 + i] - t.lo[i];
                    voxgi__solid_column(&vs, &t, rel, &st);
                } else if (voxgi__tri_setup(&vs, pr[0], &t)) {
                    voxgi__tri_resolve_signs(&vs, &t, &st);
                    voxgi__tri_forms(&t);
                    for (i = 0; i < 3; i++) rel[i] = (int32_t)pr[1 + i] - t.lo[i];
                    if (voxgi__test_voxel(&vs, &t, rel, &st)) voxgi__emit(&vs, &st, &t, rel);
                }
            }
            info->exact_tests += st.exact_tests;
            gl->NamedBufferSubData(buf[VOXGI__BINDING_BITS], 0, (ptrdiff_t)bytes, copy);
            r = voxgi__gl_check(ctx, "uploading the exact decisions");
        }
    }
    if (r == VOXGI_OK && attr) r = voxgi__vox_attributes_gl(ctx, f, vp, d, buf, control[4], attr);
    voxgi__gl_unbind(gl);
    for (i = 0; i < 7; i++)
        if (i != 2) voxgi__gl_delete_buffer(ctx, buf[i]);
    voxgi__free(ctx, copy);
    voxgi__free(ctx, flags);
    voxgi__free(ctx, pairs);
    if (r != VOXGI_OK) { voxgi__gl_delete_buffer(ctx, buf[VOXGI__BINDING_BITS]); return r; }
    *bits_out = buf[VOXGI__BINDING_BITS];
    return VOXGI_OK;
}

/* Counts the set bits of a grid buffer on the GPU. */
static voxgi_result voxgi__vox_count_gl(voxgi_context *ctx, unsigned int buffer, uint64_t words, uint64_t *count)
{
    voxgi__gl *gl = ctx->gl;
    unsigned int p, count_buf;
    uint32_t c = 0;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_popcount);
    if (r != VOXGI_OK) return r;
    p = gl->prog_popcount;
    count_buf = voxgi__gl_buffer(ctx, 4, &c);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 0, buffer);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 1, count_buf);
    gl->UseProgram(p);
    gl->ProgramUniform1ui(p, VOXGI__LOC_u_words, (unsigned)words);
    gl->DispatchCompute((unsigned)VOXGI__MIN((words + 63) / 64, (uint64_t)1024), 1, 1);
    gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT);
    voxgi__gl_unbind(gl);
    r = voxgi__gl_read_buffer(ctx, count_buf, &c, 4);
    voxgi__gl_delete_buffer(ctx, count_buf);
    *count = c;
    return r;
}

/* Solid parity along axis A: toggles, then one walk per line. */
static voxgi_result voxgi__vox_solid_gl(voxgi_context *ctx, const voxgi__flat *f, const voxgi__vprep *vp,
                                           const voxgi_voxelize_desc *d, int A, unsigned int *solid, voxgi_voxels_info *info)
{
    voxgi__gl *gl = ctx->gl;
    const voxgi_grid *g = &d->grid;
    unsigned int toggles = 0, p = gl->prog_solid_prefix;
    voxgi_result r = voxgi__vox_triangles_gl(ctx, f, vp, d, A, &toggles, info, NULL);
    if (r != VOXGI_OK) return r;
    *solid = voxgi__gl_grid_buffer(ctx, (size_t)voxgi__grid_words(g) * 4);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 0, toggles);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 1, *solid);
    gl->UseProgram(p);
    gl->ProgramUniform3i(p, VOXGI__LOC_u_res, g->res[0], g->res[1], g->res[2]);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_axis, A);
    voxgi__gl_dispatch_items(gl, (uint64_t)g->res[(A + 1) % 3] * (uint64_t)g->res[(A + 2) % 3]);
    voxgi__gl_unbind(gl);
    voxgi__gl_delete_buffer(ctx, toggles);
    return voxgi__gl_check(ctx, "the solid parity pass");
}

/* Solid by flooding the outside of the conservative surface, sweeping until nothing grows. */
static voxgi_result voxgi__vox_flood_gl(voxgi_context *ctx, const voxgi__flat *f, const voxgi__vprep *vp,
                                          const voxgi_voxelize_desc *d, unsigned int *solid, voxgi_voxels_info *info)
{
    voxgi__gl *gl = ctx->gl;
    const voxgi_grid *g = &d->grid;
    voxgi_voxelize_desc cd = *d;
    size_t bytes = (size_t)voxgi__grid_words(g) * 4;
    unsigned int surface = 0, outside, changed_buf, p = gl->prog_flood;
    uint32_t changed = 1;
    voxgi_result r;
    int axis;
    cd.method = VOXGI_METHOD_CONSERVATIVE;
    r = voxgi__vox_triangles_gl(ctx, f, vp, &cd, -1, &surface, info, NULL);
    if (r != VOXGI_OK) return r;
    outside = voxgi__gl_grid_buffer(ctx, bytes);
    changed_buf = voxgi__gl_buffer(ctx, 4, &changed);
    *solid = voxgi__gl_grid_buffer(ctx, bytes);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 0, surface);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 1, outside);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 2, changed_buf);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 3, *solid);
    gl->UseProgram(p);
    gl->ProgramUniform3i(p, VOXGI__LOC_u_res, g->res[0], g->res[1], g->res[2]);
    gl->ProgramUniform1ui(p, VOXGI__LOC_u_words, (unsigned)(bytes / 4));
    gl->ProgramUniform1i(p, VOXGI__LOC_u_op, 0);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_axis, 2);
    voxgi__gl_dispatch_items(gl, (uint64_t)g->res[0] * (uint64_t)g->res[1]);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_op, 1);
    while (changed && r == VOXGI_OK) {
        changed = 0;
        gl->NamedBufferSubData(changed_buf, 0, 4, &changed);
        for (axis = 0; axis < 3; axis++) {
            gl->ProgramUniform1i(p, VOXGI__LOC_u_axis, axis);
            voxgi__gl_dispatch_items(gl, (uint64_t)g->res[(axis + 1) % 3] * (uint64_t)g->res[(axis + 2) % 3]);
        }
        r = voxgi__gl_read_buffer(ctx, changed_buf, &changed, 4);
    }
    gl->ProgramUniform1i(p, VOXGI__LOC_u_op, 2);
    voxgi__gl_dispatch_items(gl, bytes / 4);
    voxgi__gl_unbind(gl);
    voxgi__gl_delete_buffer(ctx, surface);
    voxgi__gl_delete_buffer(ctx, outside);
    voxgi__gl_delete_buffer(ctx, changed_buf);
    if (r == VOXGI_OK) r = voxgi__gl_check(ctx, "the flood fill");
    if (r != VOXGI_OK) voxgi__gl_delete_buffer(ctx, *solid);
    return r;
}
#endif /* VOXGI_NO_GL */

/* ----- 5.4 the rasterizer's coverage and the raster slicemap: CPU, then GL */

/* Rounds to the rasterizer's subpixel grid (1/256 pixel), half up. */
static double voxgi__snap256(double x) { return floor(x * 256.0 + 0.5) / 256.0; }

/* ----- the rasterizer's coverage, exactly: every pixel centre (i + 1/2, j + 1/2) in [0,w)x[0,h)
   that a triangle with corners on the 1/256 subpixel grid covers: strictly inside, or on an
   edge the fill rule gives it (Mesa's, measured: the CCW edge direction d has d_y < 0, or
   d_y == 0 and d_x > 0). Exact in double while coordinates stay below 2^17 pixels. */
typedef void (*voxgi__pixel_fn)(void *user, uint32_t tri, int i, int j);

static void voxgi__vox_raster_cpu(const double xin[3], const double yin[3], int w, int h, voxgi__pixel_fn fn, void *user,
                                  uint32_t tri)
{
    double x[3], y[3], area;
    int k, i0, i1, j0, j1, i, j;
    for (k = 0; k < 3; k++) { x[k] = xin[k]; y[k] = yin[k]; }
    area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    if (area == 0) return; /* no fragments */
    if (area < 0) { /* make it CCW: the fill rule speaks of CCW edges */
        double tx = x[1], ty = y[1];
        x[1] = x[2]; y[1] = y[2]; x[2] = tx; y[2] = ty;
    }
    i0 = (int)VOXGI__MAX(ceil(VOXGI__MIN(x[0], VOXGI__MIN(x[1], x[2])) - 0.5), 0.0);
    i1 = (int)VOXGI__MIN(floor(VOXGI__MAX(x[0], VOXGI__MAX(x[1], x[2])) - 0.5), (double)w - 1);
    j0 = (int)VOXGI__MAX(ceil(VOXGI__MIN(y[0], VOXGI__MIN(y[1], y[2])) - 0.5), 0.0);
    j1 = (int)VOXGI__MIN(floor(VOXGI__MAX(y[0], VOXGI__MAX(y[1], y[2])) - 0.5), (double)h - 1);
    for (j = j0; j <= j1; j++)
        for (i = i0; i <= i1; i++) {
            double px = i + 0.5, py = j + 0.5;
            int inside = 1;
            for (k = 0; k < 3 && inside; k++) {
                double dx = x[(k + 1) % 3] - x[k], dy = y[(k + 1) % 3] - y[k];
                double e = dx * (py - y[k]) - dy * (px - x[k]);
                inside = e > 0 || (e == 0 && (dy < 0 || (dy == 0 && dx > 0)));
            }
            if (inside) fn(user, tri, i, j);
        }
}

/* ----- CPU raster slicemap: the rasterizer's sampling, exactly. The triangle's projected
   corners are rounded to the rasterizer's subpixel grid (1/256 pixel) as the GL twin hands them
   to it (shaders/slicemap.glsl: on that grid, the rasterizer's own snapping changes nothing); a
   pixel centre is covered when strictly inside the rounded triangle, or on an edge the fill rule
   gives it (voxgi__vox_raster_cpu); the slice is floor of the unrounded plane's depth there,
   computed in double in the same order as the fragment shader. So GL sets the same voxels. */
static double voxgi__slicemap_depth(const double q0[3], const double q1[3], const double q2[3], int A, double ca, double cb)
{
    int a = (A + 1) % 3, b = (A + 2) % 3;
    double e1a = q1[a] - q0[a], e1b = q1[b] - q0[b], e1A = q1[A] - q0[A];
    double fa = q2[a] - q0[a], fb = q2[b] - q0[b], fA = q2[A] - q0[A];
    double na = e1b * fA - e1A * fb, nb = e1A * fa - e1a * fA, nA = e1a * fb - e1b * fa;
    return q0[A] - (na * (ca - q0[a]) + nb * (cb - q0[b])) / nA;
}

/* A covered pixel (i, j) of a triangle drawn along axis c: the voxel of floor(depth) there. */
typedef struct voxgi__vox_column_job { const voxgi__vox_shared *vs; voxgi__stats *st; const double *q[3]; int c; } voxgi__vox_column_job;

static void voxgi__vox_column_pixel(void *user, uint32_t tri, int i, int j)
{
    voxgi__vox_column_job *job = (voxgi__vox_column_job *)user;
    int c = job->c, a = (c + 1) % 3, b = (c + 2) % 3;
    double z = floor(voxgi__slicemap_depth(job->q[0], job->q[1], job->q[2], c, (double)i + 0.5, (double)j + 0.5));
    (void)tri;
    if (z >= 0 && z < (double)job->vs->grid->res[c]) {
        int64_t v[3];
        v[a] = i;
        v[b] = j;
        v[c] = (int64_t)z;
        voxgi__set_voxel(job->vs, job->st, v[0], v[1], v[2]);
    }
}

/* Triangle ti drawn along axis c: its corners on the subpixel grid, its covered pixel centres. */
static void voxgi__vox_draw_along(const voxgi__vox_shared *vs, size_t ti, int c, voxgi__stats *st)
{
    voxgi__vox_column_job job;
    double x[3], y[3];
    int k, a = (c + 1) % 3, b = (c + 2) % 3;
    for (k = 0; k < 3; k++) job.q[k] = vs->vp[vs->tri[3 * ti + (size_t)k]].q;
    job.vs = vs;
    job.st = st;
    job.c = c;
    for (k = 0; k < 3; k++) { x[k] = voxgi__snap256(job.q[k][a]); y[k] = voxgi__snap256(job.q[k][b]); }
    voxgi__vox_raster_cpu(x, y, vs->grid->res[a], vs->grid->res[b], voxgi__vox_column_pixel, &job, (uint32_t)ti);
}

static void voxgi__vox_slicemap_cpu(const voxgi__vox_shared *vs, size_t ti, voxgi__stats *st)
{
    voxgi__vox_draw_along(vs, ti, vs->slice_axis, st);
}

#ifndef VOXGI_NO_GL

/* Draws `count` vertices as `mode` with `program` (its buffers bound by the caller) into
   slicemap textures along axis A (128 slices per RGBA32UI layer, up to 8 layers per draw
   through MRT, ORed by the logic op; or 32 slices per R32UI layer with imageAtomicOr), then
   unpacks them into a new bit grid *bits_out. The caller's GL state is restored. */
static voxgi_result voxgi__vox_raster_gl(voxgi_context *ctx, const voxgi_grid *g, int A, int atomic, unsigned int p,
                                           unsigned int mode, uint64_t count, unsigned int *bits_out)
{
    voxgi__gl *gl = ctx->gl;
    voxgi__gl_raster_state state;
    int a = (A + 1) % 3, b = (A + 2) % 3, per_layer = atomic ? 32 : 128;
    int layers = (g->res[A] + per_layer - 1) / per_layer, max_targets = 1, max_size = 0, i, first, vw = 1, vh = 1;
    unsigned int tex = 0, fbo = 0, vao = 0, zero[4] = {0, 0, 0, 0};
    size_t bytes = (size_t)voxgi__grid_words(g) * 4;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_slicemap_unpack);
    *bits_out = 0;
    if (r != VOXGI_OK) return r;
    gl->GetIntegerv(VOXGI__GL_MAX_DRAW_BUFFERS, &max_targets);
    gl->GetIntegerv(VOXGI__GL_MAX_TEXTURE_SIZE, &max_size);
    max_targets = VOXGI__MIN(max_targets, 8);
    if (g->res[a] > max_size || g->res[b] > max_size)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "a %dx%d slicemap exceeds GL_MAX_TEXTURE_SIZE %d", g->res[a], g->res[b], max_size);
    if (count > (uint64_t)INT32_MAX) return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%llu vertices exceed one draw", (unsigned long long)count);
    gl->CreateTextures(VOXGI__GL_TEXTURE_2D_ARRAY, 1, &tex);
    gl->TextureStorage3D(tex, 1, atomic ? VOXGI__GL_R32UI : VOXGI__GL_RGBA32UI, g->res[a], g->res[b], layers);
    /* integer textures are incomplete with the default linear filters: texelFetch would read 0 */
    gl->TextureParameteri(tex, VOXGI__GL_TEXTURE_MIN_FILTER, VOXGI__GL_NEAREST);
    gl->TextureParameteri(tex, VOXGI__GL_TEXTURE_MAG_FILTER, VOXGI__GL_NEAREST);
    gl->ClearTexImage(tex, 0, atomic ? VOXGI__GL_RED_INTEGER : VOXGI__GL_RGBA_INTEGER, VOXGI__GL_UNSIGNED_INT, zero);
    gl->CreateVertexArrays(1, &vao);
    gl->CreateFramebuffers(1, &fbo);
    voxgi__gl_raster_begin(gl, &state);
    gl->Enable(VOXGI__GL_PROGRAM_POINT_SIZE); /* points are one pixel whatever glPointSize says */
    gl->UseProgram(p);
    gl->ProgramUniform3i(p, VOXGI__LOC_u_res, g->res[0], g->res[1], g->res[2]);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_axis, A);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_atomic, atomic);
    gl->BindVertexArray(vao);
    gl->BindFramebuffer(VOXGI__GL_FRAMEBUFFER, fbo);
    while (vw < g->res[a]) vw *= 2; /* powers of two: clip coordinates on the subpixel grid reach the window exactly */
    while (vh < g->res[b]) vh *= 2;
    gl->ProgramUniform2i(p, VOXGI__LOC_u_view, vw, vh);
    gl->Viewport(0, 0, vw, vh); /* beyond the targets' size: no fragments */
    if (atomic) { /* no colour outputs: an attachment-less framebuffer (texels beyond the image: no writes) */
        gl->NamedFramebufferParameteri(fbo, VOXGI__GL_FRAMEBUFFER_DEFAULT_WIDTH, vw);
        gl->NamedFramebufferParameteri(fbo, VOXGI__GL_FRAMEBUFFER_DEFAULT_HEIGHT, vh);
        gl->BindImageTexture(0, tex, 0, 1, 0, VOXGI__GL_READ_WRITE, VOXGI__GL_R32UI);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_first_slice, 0);
        gl->DrawArrays(mode, 0, (int)count);
    } else {
        gl->Enable(VOXGI__GL_COLOR_LOGIC_OP);
        gl->LogicOp(VOXGI__GL_OR);
        for (first = 0; first < layers && r == VOXGI_OK; first += max_targets) {
            unsigned int bufs[8];
            int n = VOXGI__MIN(max_targets, layers - first);
            for (i = 0; i < 8; i++) {
                gl->NamedFramebufferTextureLayer(fbo, VOXGI__GL_COLOR_ATTACHMENT0 + (unsigned)i, i < n ? tex : 0, 0, i < n ? first + i : 0);
                bufs[i] = i < n ? VOXGI__GL_COLOR_ATTACHMENT0 + (unsigned)i : 0;
            }
            gl->NamedFramebufferDrawBuffers(fbo, 8, bufs);
            if (gl->CheckNamedFramebufferStatus(fbo, VOXGI__GL_FRAMEBUFFER) != VOXGI__GL_FRAMEBUFFER_COMPLETE)
                r = voxgi__fail(ctx, VOXGI_ERR_GL, "the slicemap framebuffer is incomplete");
            else {
                gl->ProgramUniform1i(p, VOXGI__LOC_u_first_slice, first * per_layer);
                gl->DrawArrays(mode, 0, (int)count);
            }
        }
    }
    gl->BindFramebuffer(VOXGI__GL_FRAMEBUFFER, 0);
    gl->BindVertexArray(0);
    voxgi__gl_raster_end(gl, &state);
    gl->MemoryBarrier(VOXGI__GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | VOXGI__GL_TEXTURE_FETCH_BARRIER_BIT | VOXGI__GL_FRAMEBUFFER_BARRIER_BIT);
    if (r == VOXGI_OK) { /* slicemap columns -> the linear bit grid */
        *bits_out = voxgi__gl_grid_buffer(ctx, bytes);
        p = gl->prog_slicemap_unpack;
        gl->UseProgram(p);
        gl->ProgramUniform3i(p, VOXGI__LOC_u_res, g->res[0], g->res[1], g->res[2]);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_axis, A);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_per_layer, per_layer);
        gl->BindTextureUnit(0, tex);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 0, *bits_out);
        voxgi__gl_dispatch_items(gl, (uint64_t)g->res[a] * (uint64_t)g->res[b]);
        gl->BindTextureUnit(0, 0);
    }
    gl->BindImageTexture(0, 0, 0, 0, 0, VOXGI__GL_READ_WRITE, VOXGI__GL_R32UI);
    voxgi__gl_unbind(gl);
    gl->DeleteTextures(1, &tex);
    gl->DeleteFramebuffers(1, &fbo);
    gl->DeleteVertexArrays(1, &vao);
    if (r == VOXGI_OK) r = voxgi__gl_check(ctx, "the raster slicemap");
    if (r != VOXGI_OK && *bits_out) { voxgi__gl_delete_buffer(ctx, *bits_out); *bits_out = 0; }
    return r;
}

/* The raster slicemap: the triangles drawn along the axis. */
static voxgi_result voxgi__vox_slicemap_gl(voxgi_context *ctx, const voxgi__flat *f, const voxgi__vprep *vp,
                                       const voxgi_voxelize_desc *d, unsigned int *bits_out)
{
    unsigned int verts = 0, tris = 0;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_slicemap);
    if (r == VOXGI_OK) voxgi__vox_scene_buffers_gl(ctx, f, vp, &verts, &tris, &r);
    if (r == VOXGI_OK)
        r = voxgi__vox_raster_gl(ctx, &d->grid, (int)d->axis - 1, d->atomic, ctx->gl->prog_slicemap,
                                   VOXGI__GL_TRIANGLES, 3 * (uint64_t)f->triangle_count, bits_out);
    voxgi__gl_delete_buffer(ctx, verts);
    voxgi__gl_delete_buffer(ctx, tris);
    return r;
}
#endif /* VOXGI_NO_GL */

/* ----- 5.5 Volume Buffer: CPU, then GL */

/* ----- CPU Volume Buffer (Gaitatzes et al. 2011): each triangle along its dominant axis c
   (largest |normal| component of (q1-q0)x(q2-q0) in double, the lowest axis on ties), its
   corners rounded to the 1/256 subpixel grid in the (c+1, c+2) plane; each covered pixel centre
   sets the voxel floor(depth) of the unrounded plane there (voxgi__slicemap_depth). The same
   arithmetic as shaders/volume_buffer.glsl, so GL sets the same voxels. */
static int voxgi__dominant_axis(const double *q0, const double *q1, const double *q2, double n[3])
{
    double e[3], f[3];
    int a, c = 0;
    for (a = 0; a < 3; a++) { e[a] = q1[a] - q0[a]; f[a] = q2[a] - q0[a]; }
    n[0] = e[1] * f[2] - f[1] * e[2]; /* GLSL's cross(): the same products and order */
    n[1] = e[2] * f[0] - f[2] * e[0];
    n[2] = e[0] * f[1] - f[0] * e[1];
    for (a = 1; a < 3; a++)
        if (fabs(n[a]) > fabs(n[c])) c = a;
    return c;
}

static void voxgi__vox_volume_buffer_cpu(const voxgi__vox_shared *vs, size_t ti, voxgi__stats *st)
{
    double n[3];
    const double *q[3];
    int k, c;
    for (k = 0; k < 3; k++) q[k] = vs->vp[vs->tri[3 * ti + (size_t)k]].q;
    c = voxgi__dominant_axis(q[0], q[1], q[2], n);
    if (n[c] == 0) return; /* no area in any projection */
    voxgi__vox_draw_along(vs, ti, c, st);
}

#ifndef VOXGI_NO_GL

/* The Volume Buffer: three layered draws (one per sweep axis, each triangle in the sweep of its
   dominant axis) into float 3D targets blended per attribute, then merged into the bit grid and,
   with attributes, each set voxel's values (on the CPU afterwards, as floats). */
/* Each triangle's values as the Volume Buffer's targets take them: albedo, normal (stored as
   n / 2 + 1/2 under MAX blending, so that the maximum of the stored values is the component
   wise maximum), emission, opacity; 10 floats per triangle. */
static float *voxgi__vox_volume_buffer_values(voxgi_context *ctx, const voxgi__flat *f, const voxgi_voxelize_desc *d)
{
    float *tv = (float *)voxgi__alloc_array(ctx, f->triangle_count ? f->triangle_count : 1, 10 * sizeof(float), 1);
    unsigned int attrs = d->attributes;
    size_t t;
    int k;
    if (!tv) return NULL;
    for (t = 0; t < f->triangle_count && attrs; t++) {
        const voxgi_material *m = voxgi__tri_material(f, t);
        double n[3];
        voxgi__tri_unit_normal(f, t, n);
        for (k = 0; k < 3; k++) {
            tv[10 * t + (size_t)k] = m->albedo[k];
            tv[10 * t + 3 + (size_t)k] = (float)(d->blend[1] == VOXGI_BLEND_MAX ? n[k] * 0.5 + 0.5 : n[k]);
            tv[10 * t + 6 + (size_t)k] = m->emission[k];
        }
        tv[10 * t + 9] = 1.0f - m->transparency;
    }
    return tv;
}

/* The GL blend state of draw buffers 0-2, which the Volume Buffer's sweeps change. */
typedef struct voxgi__gl_blend_state { unsigned char enabled[3]; int value[3][6]; } voxgi__gl_blend_state;
static const unsigned int voxgi__gl_blend_names[6] = {VOXGI__GL_BLEND_SRC_RGB, VOXGI__GL_BLEND_DST_RGB, VOXGI__GL_BLEND_SRC_ALPHA,
                                                      VOXGI__GL_BLEND_DST_ALPHA, VOXGI__GL_BLEND_EQUATION_RGB, VOXGI__GL_BLEND_EQUATION_ALPHA};

/* The three sweeps (one per axis c, into 3D targets tex[c][0..2]: the fragment count and
   albedo, normal and opacity, emission), each triangle drawn once with the small program, then
   the ones the geometry shader listed as spanning many slices with the big one. */
static voxgi_result voxgi__vox_volume_buffer_sweeps_gl(voxgi_context *ctx, const voxgi__flat *f, const voxgi_voxelize_desc *d,
                                                       unsigned int tex[3][3], unsigned int values_buf, unsigned int lost_buf,
                                                       voxgi_voxels_info *info)
{
    voxgi__gl *gl = ctx->gl;
    const voxgi_grid *g = &d->grid;
    voxgi__gl_raster_state state;
    voxgi__gl_blend_state blend;
    unsigned int attrs = d->attributes, fbo = 0, vao = 0, p, zero = 0, eq[3][2];
    int c, k, i;
    voxgi_result r = VOXGI_OK;
    gl->CreateVertexArrays(1, &vao);
    gl->CreateFramebuffers(1, &fbo);
    for (i = 0; i < 3; i++) { /* saved first: restored last */
        blend.enabled[i] = gl->IsEnabledi(VOXGI__GL_BLEND, (unsigned)i);
        for (k = 0; k < 6; k++) gl->GetIntegeri_v(voxgi__gl_blend_names[k], (unsigned)i, &blend.value[i][k]);
    }
    voxgi__gl_raster_begin(gl, &state);
    /* per target: rgb and alpha by their attributes' blend mode (the fragment count always adds) */
    eq[0][0] = d->blend[0] == VOXGI_BLEND_MAX ? VOXGI__GL_MAX : VOXGI__GL_FUNC_ADD;
    eq[0][1] = VOXGI__GL_FUNC_ADD;
    eq[1][0] = d->blend[1] == VOXGI_BLEND_MAX ? VOXGI__GL_MAX : VOXGI__GL_FUNC_ADD;
    eq[1][1] = d->blend[3] == VOXGI_BLEND_MAX ? VOXGI__GL_MAX : VOXGI__GL_FUNC_ADD;
    eq[2][0] = d->blend[2] == VOXGI_BLEND_MAX ? VOXGI__GL_MAX : VOXGI__GL_FUNC_ADD;
    eq[2][1] = VOXGI__GL_FUNC_ADD;
    for (i = 0; i < 3; i++) {
        gl->Enablei(VOXGI__GL_BLEND, (unsigned)i);
        gl->BlendFuncSeparatei((unsigned)i, VOXGI__GL_ONE, VOXGI__GL_ONE, VOXGI__GL_ONE, VOXGI__GL_ONE);
        gl->BlendEquationSeparatei((unsigned)i, eq[i][0], eq[i][1]);
    }
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 2, values_buf);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 3, lost_buf);
    for (i = 0; i < 2; i++) {
        p = i ? gl->prog_volume_buffer_big : gl->prog_volume_buffer;
        gl->ProgramUniform3i(p, VOXGI__LOC_u_res, g->res[0], g->res[1], g->res[2]);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_slicing, d->volume_slicing);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_with_values, attrs != 0);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_big, i);
    }
    gl->BindVertexArray(vao);
    gl->BindFramebuffer(VOXGI__GL_FRAMEBUFFER, fbo);
    for (c = 0; c < 3 && r == VOXGI_OK; c++) {
        int a = (c + 1) % 3, b = (c + 2) % 3, vw = 1, vh = 1;
        unsigned int bufs[3];
        float zeros[4] = {0, 0, 0, 0};
        for (k = 0; k < 3; k++) {
            bufs[k] = 0;
            if (k == 1 && !(attrs & (VOXGI_ATTRIBUTE_NORMAL | VOXGI_ATTRIBUTE_OPACITY))) continue;
            if (k == 2 && !(attrs & VOXGI_ATTRIBUTE_EMISSION)) continue;
            gl->CreateTextures(VOXGI__GL_TEXTURE_3D, 1, &tex[c][k]);
            gl->TextureStorage3D(tex[c][k], 1, k == 0 && !attrs ? VOXGI__GL_R32F : VOXGI__GL_RGBA32F, g->res[a], g->res[b], g->res[c]);
            gl->TextureParameteri(tex[c][k], VOXGI__GL_TEXTURE_MIN_FILTER, VOXGI__GL_NEAREST);
            gl->TextureParameteri(tex[c][k], VOXGI__GL_TEXTURE_MAG_FILTER, VOXGI__GL_NEAREST);
            gl->ClearTexImage(tex[c][k], 0, k == 0 && !attrs ? VOXGI__GL_RED : VOXGI__GL_RGBA, VOXGI__GL_FLOAT, zeros);
            gl->NamedFramebufferTexture(fbo, VOXGI__GL_COLOR_ATTACHMENT0 + (unsigned)k, tex[c][k], 0);
            bufs[k] = VOXGI__GL_COLOR_ATTACHMENT0 + (unsigned)k;
        }
        for (k = 0; k < 3; k++)
            if (!bufs[k]) gl->NamedFramebufferTexture(fbo, VOXGI__GL_COLOR_ATTACHMENT0 + (unsigned)k, 0, 0);
        gl->NamedFramebufferDrawBuffers(fbo, 3, bufs);
        if (gl->CheckNamedFramebufferStatus(fbo, VOXGI__GL_FRAMEBUFFER) != VOXGI__GL_FRAMEBUFFER_COMPLETE) {
            r = voxgi__fail(ctx, VOXGI_ERR_GL, "the Volume Buffer's framebuffer is incomplete");
            break;
        }
        while (vw < g->res[a]) vw *= 2;
        while (vh < g->res[b]) vh *= 2;
        gl->Viewport(0, 0, vw, vh);
        for (i = 0; i < 2 && r == VOXGI_OK; i++) { /* every triangle; then the listed ones spanning many layers */
            uint32_t big = 0;
            p = i ? gl->prog_volume_buffer_big : gl->prog_volume_buffer;
            gl->UseProgram(p);
            gl->ProgramUniform2i(p, VOXGI__LOC_u_view, vw, vh);
            gl->ProgramUniform1i(p, VOXGI__LOC_u_axis, c);
            if (i == 0) gl->DrawArrays(VOXGI__GL_TRIANGLES, 0, (int)(3 * f->triangle_count));
            else {
                gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT | VOXGI__GL_BUFFER_UPDATE_BARRIER_BIT);
                gl->GetNamedBufferSubData(lost_buf, 4, 4, &big);
                if (big) gl->DrawArrays(VOXGI__GL_TRIANGLES, 0, (int)(3 * big));
                gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT);
                gl->NamedBufferSubData(lost_buf, 4, 4, &zero);
                info->big_triangles += big;
            }
        }
    }
    gl->BindFramebuffer(VOXGI__GL_FRAMEBUFFER, 0);
    gl->BindVertexArray(0);
    voxgi__gl_raster_end(gl, &state);
    for (i = 0; i < 3; i++) {
        gl->BlendFuncSeparatei((unsigned)i, (unsigned)blend.value[i][0], (unsigned)blend.value[i][1], (unsigned)blend.value[i][2],
                               (unsigned)blend.value[i][3]);
        gl->BlendEquationSeparatei((unsigned)i, (unsigned)blend.value[i][4], (unsigned)blend.value[i][5]);
        if (blend.enabled[i]) gl->Enablei(VOXGI__GL_BLEND, (unsigned)i);
        else gl->Disablei(VOXGI__GL_BLEND, (unsigned)i);
    }
    gl->DeleteFramebuffers(1, &fbo);
    gl->DeleteVertexArrays(1, &vao);
    return r;
}

/* The merge (shaders/volume_merge.glsl): a voxel is set where any sweep's target counted a
   fragment; with attributes, each set voxel's values at its rank, blended over the sweeps. */
static voxgi_result voxgi__vox_volume_buffer_merge_gl(voxgi_context *ctx, const voxgi_voxelize_desc *d, unsigned int tex[3][3],
                                                      unsigned int *bits_out, voxgi__attr *attr)
{
    voxgi__gl *gl = ctx->gl;
    const voxgi_grid *g = &d->grid;
    unsigned int attrs = d->attributes, p = gl->prog_volume_merge;
    uint64_t words = voxgi__grid_words(g), nvox = voxgi_grid_voxel_count(g);
    int c, k;
    voxgi_result r;
    *bits_out = voxgi__gl_grid_buffer(ctx, (size_t)words * 4);
    gl->UseProgram(p);
    for (c = 0; c < 3; c++)
        for (k = 0; k < 3; k++) gl->BindTextureUnit((unsigned)(3 * k + c), tex[c][k]);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 4, *bits_out);
    gl->ProgramUniform3i(p, VOXGI__LOC_u_res, g->res[0], g->res[1], g->res[2]);
    gl->ProgramUniform1ui(p, VOXGI__LOC_u_attributes, attrs);
    gl->ProgramUniform4i(p, VOXGI__LOC_u_blend, (int)d->blend[0], (int)d->blend[1], (int)d->blend[2], (int)d->blend[3]);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_channels, attr ? attr->channels : 0);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, 0);
    voxgi__gl_dispatch_rows(gl, nvox);
    r = voxgi__gl_check(ctx, "the Volume Buffer");
    if (r == VOXGI_OK && attr) {
        uint32_t *bits = (uint32_t *)voxgi__alloc_array(ctx, (size_t)words, 4, 0);
        unsigned int rank_buf = 0, out_buf = 0, count_buf = 0;
        uint64_t voxels = 0, w;
        if (!bits) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the Volume Buffer's merge");
        if (r == VOXGI_OK) r = voxgi__gl_read_buffer(ctx, *bits_out, bits, (size_t)words * 4);
        for (w = 0; r == VOXGI_OK && w < words; w++) voxels += voxgi__popcount32(bits[w]);
        if (r == VOXGI_OK) r = voxgi__attr_alloc(ctx, attr, bits, words, voxels);
        if (r == VOXGI_OK && !(attr->values = (float *)voxgi__alloc_array(ctx, (size_t)(voxels ? voxels : 1), (size_t)attr->channels * 4, 0)))
            r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the attributes of %llu voxels", (unsigned long long)voxels);
        if (r == VOXGI_OK) {
            rank_buf = voxgi__gl_buffer(ctx, (size_t)words * 4, attr->rank);
            out_buf = voxgi__gl_buffer(ctx, (size_t)voxels * (size_t)attr->channels * 4, NULL);
            count_buf = voxgi__gl_buffer(ctx, (size_t)voxels * 4, NULL);
            gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 7, rank_buf);
            gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 8, out_buf);
            gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 9, count_buf);
            gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, 1);
            voxgi__gl_dispatch_rows(gl, nvox);
            r = voxgi__gl_read_buffer(ctx, out_buf, attr->values, (size_t)voxels * (size_t)attr->channels * 4);
            if (r == VOXGI_OK) r = voxgi__gl_read_buffer(ctx, count_buf, attr->count, (size_t)voxels * 4);
        }
        voxgi__gl_delete_buffer(ctx, rank_buf);
        voxgi__gl_delete_buffer(ctx, out_buf);
        voxgi__gl_delete_buffer(ctx, count_buf);
        voxgi__free(ctx, bits);
    }
    return r;
}

static voxgi_result voxgi__vox_volume_buffer_gl(voxgi_context *ctx, const voxgi__flat *f, const voxgi__vprep *vp,
                                                const voxgi_voxelize_desc *d, unsigned int *bits_out, voxgi__attr *attr,
                                                voxgi_voxels_info *info)
{
    voxgi__gl *gl = ctx->gl;
    const voxgi_grid *g = &d->grid;
    unsigned int attrs = d->attributes, tex[3][3], verts = 0, tris = 0, values_buf = 0, lost_buf = 0, zero = 0;
    int max3d = 0, c, k, i, targets = 1 + ((attrs & (VOXGI_ATTRIBUTE_NORMAL | VOXGI_ATTRIBUTE_OPACITY)) ? 1 : 0) +
                                      ((attrs & VOXGI_ATTRIBUTE_EMISSION) ? 1 : 0);
    uint64_t nvox = voxgi_grid_voxel_count(g), bytes_per_voxel = attrs ? 16u * (uint64_t)targets : 4u;
    float *tv;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_volume_buffer);
    if (r == VOXGI_OK) r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_volume_buffer_big);
    if (r == VOXGI_OK) r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_volume_merge);
    if (r != VOXGI_OK) return r;
    gl->GetIntegerv(VOXGI__GL_MAX_3D_TEXTURE_SIZE, &max3d);
    if (g->res[0] > max3d || g->res[1] > max3d || g->res[2] > max3d)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "the Volume Buffer's 3D targets stop at GL_MAX_3D_TEXTURE_SIZE %d", max3d);
    if (3 * nvox * bytes_per_voxel > ((uint64_t)1 << 30))
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "the Volume Buffer's three %dx%dx%d sweeps need %llu MiB of float targets "
                           "(at most 1024 here); ask for fewer attributes or a smaller grid", g->res[0], g->res[1], g->res[2],
                           (unsigned long long)(3 * nvox * bytes_per_voxel >> 20));
    if (!(tv = voxgi__vox_volume_buffer_values(ctx, f, d))) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the triangles' values");
    voxgi__vox_scene_buffers_gl(ctx, f, vp, &verts, &tris, &r);
    values_buf = voxgi__gl_buffer(ctx, f->triangle_count * 10 * sizeof(float), tv);
    lost_buf = voxgi__gl_buffer(ctx, 8 + 4 * f->triangle_count, NULL); /* lost, big_count, big_list */
    gl->ClearNamedBufferData(lost_buf, VOXGI__GL_R32UI, VOXGI__GL_RED_INTEGER, VOXGI__GL_UNSIGNED_INT, &zero);
    voxgi__free(ctx, tv);
    memset(tex, 0, sizeof tex);
    if (r == VOXGI_OK) r = voxgi__vox_volume_buffer_sweeps_gl(ctx, f, d, tex, values_buf, lost_buf, info);
    gl->MemoryBarrier(VOXGI__GL_TEXTURE_FETCH_BARRIER_BIT | VOXGI__GL_FRAMEBUFFER_BARRIER_BIT | VOXGI__GL_SHADER_STORAGE_BARRIER_BIT);
    if (r == VOXGI_OK) {
        uint32_t lost = 0;
        r = voxgi__gl_read_buffer(ctx, lost_buf, &lost, 4);
        info->lost_slices = lost;
    }
    if (r == VOXGI_OK) r = voxgi__vox_volume_buffer_merge_gl(ctx, d, tex, bits_out, attr);
    for (i = 0; i < 9; i++) gl->BindTextureUnit((unsigned)i, 0);
    voxgi__gl_unbind(gl);
    for (c = 0; c < 3; c++)
        for (k = 0; k < 3; k++)
            if (tex[c][k]) gl->DeleteTextures(1, &tex[c][k]);
    voxgi__gl_delete_buffer(ctx, verts);
    voxgi__gl_delete_buffer(ctx, tris);
    voxgi__gl_delete_buffer(ctx, values_buf);
    voxgi__gl_delete_buffer(ctx, lost_buf);
    if (r == VOXGI_OK) r = voxgi__gl_check(ctx, "the Volume Buffer");
    if (r != VOXGI_OK && *bits_out) { voxgi__gl_delete_buffer(ctx, *bits_out); *bits_out = 0; }
    return r;
}
#endif /* VOXGI_NO_GL */

/* ----- 5.6 texture atlas: CPU, then GL */

/* voxelization: texture atlas
   Thiedemann et al. 2011, Buchacher's methods B (atlas points drawn as GL points) and D (one
   compute invocation per point). The atlas is rasterized once: each texel whose centre a chart
   covers (the GL fill rule: strictly inside, or on an edge whose CCW direction d has d_y < 0, or
   d_y == 0 and d_x > 0) holds that triangle (the last one drawn, where charts overlap). Every
   such texel is a point: the texel centre's barycentrics in the chart, applied to the triangle in
   voxel coordinates, in double, in one fixed order that shaders/atlas.glsl repeats; it sets the
   voxel floor(point) when that lies in the grid. Chart corners are multiples of 1/256 texel
   below 2^14, so coverage is decided exactly in double on both sides. The result lies within
   one voxel of the conservative set (a point computed in double may round across a face). */
#define VOXGI__ATLAS_MAX 16384
#define VOXGI__ATLAS_MAX_DEFAULT 8192
#define VOXGI__ATLAS_TEXELS_PER_VOXEL 2.0
#define VOXGI__ATLAS_TINY 1.25 /* charts shorter than this (texels) are centred on a texel centre */

typedef struct voxgi__atlas {
    int size;         /* texels per side */
    int view;         /* power of two >= size: the raster viewport, so texel coordinates map
                         to window coordinates without rounding */
    double scale;     /* AUTO: texels per voxel edge */
    float *uv;        /* 6 per triangle: the chart's corners in texels */
} voxgi__atlas;

static int voxgi__is_atlas(voxgi_method m) { return m == VOXGI_METHOD_ATLAS || m == VOXGI_METHOD_ATLAS_COMPUTE; }

/* A triangle's chart before scaling: its longest edge (from corner `first`) along u. */
typedef struct voxgi__chart { double len, apex_u, height; uint32_t tri; int first; } voxgi__chart;

static void voxgi__chart_shape(const voxgi__vprep *vp, const uint32_t *tri, uint32_t t, voxgi__chart *c)
{
    double best = -1;
    int k, a;
    c->tri = t;
    c->first = 0;
    for (k = 0; k < 3; k++) { /* the longest edge */
        const double *p = vp[tri[3 * t + (uint32_t)k]].q, *q = vp[tri[3 * t + (uint32_t)(k + 1) % 3]].q;
        double l2 = 0;
        for (a = 0; a < 3; a++) l2 += (q[a] - p[a]) * (q[a] - p[a]);
        if (l2 > best) { best = l2; c->first = k; }
    }
    c->len = sqrt(best);
    c->apex_u = c->height = 0;
    if (c->len > 0) {
        const double *A = vp[tri[3 * t + (uint32_t)c->first]].q, *B = vp[tri[3 * t + (uint32_t)(c->first + 1) % 3]].q,
                     *C = vp[tri[3 * t + (uint32_t)(c->first + 2) % 3]].q;
        double e[3], f[3], x[3], along = 0, cross2 = 0;
        for (a = 0; a < 3; a++) { e[a] = B[a] - A[a]; f[a] = C[a] - A[a]; }
        for (a = 0; a < 3; a++) {
            x[a] = e[(a + 1) % 3] * f[(a + 2) % 3] - e[(a + 2) % 3] * f[(a + 1) % 3];
            along += e[a] * f[a];
            cross2 += x[a] * x[a];
        }
        c->apex_u = VOXGI__MIN(VOXGI__MAX(along / c->len, 0.0), c->len);
        c->height = sqrt(cross2) / c->len;
    }
}

/* The chart's box in texels at `scale`: the corners lie at least half a texel inside it, so no
   texel centre is shared by two charts. */
static void voxgi__chart_box(const voxgi__chart *c, double scale, double *w, double *h)
{
    if (c->len * scale < VOXGI__ATLAS_TINY) { *w = *h = 3; return; }
    *w = ceil(c->len * scale + 1.3);
    *h = ceil(VOXGI__MAX(c->height * scale, 1.0 / 32) + 1.05);
}

/* Writes the chart's corners (texels, CCW: A, B on a row of texel centres, apex above) into uv. */
static void voxgi__chart_place(const voxgi__chart *c, double scale, double x, double y, float *uv)
{
    double u[3], v[3], ox, oy;
    int k;
    if (c->len * scale < VOXGI__ATLAS_TINY) { /* tiny: a chart at least 1/16 texel wide and high, centroid on (x+1.5, y+1.5) */
        u[0] = 0;
        u[1] = VOXGI__MAX(voxgi__snap256(c->len * scale), 1.0 / 16);
        u[2] = VOXGI__MIN(voxgi__snap256(c->apex_u * scale), u[1]);
        v[0] = v[1] = 0;
        v[2] = VOXGI__MAX(voxgi__snap256(c->height * scale), 1.0 / 16);
        ox = voxgi__snap256(x + 1.5 - (u[1] + u[2]) / 3);
        oy = voxgi__snap256(y + 1.5 - v[2] / 3);
    } else {
        u[0] = 0;
        u[1] = voxgi__snap256(c->len * scale);
        u[2] = voxgi__snap256(c->apex_u * scale);
        v[0] = v[1] = 0;
        v[2] = voxgi__snap256(VOXGI__MAX(c->height * scale, 1.0 / 32));
        ox = x + 0.75;
        oy = y + 0.5;
    }
    for (k = 0; k < 3; k++) {
        int corner = (c->first + k) % 3;
        uv[2 * corner] = (float)(ox + u[k]);
        uv[2 * corner + 1] = (float)(oy + v[k]);
    }
}

/* Shelf packing in the charts' order; 1 when all fit into size x size. With uv, places them. */
static int voxgi__atlas_pack(const voxgi__chart *charts, size_t n, double scale, int size, float *uv)
{
    double x = 0, y = 0, shelf = 0;
    size_t i;
    for (i = 0; i < n; i++) {
        double w, h;
        voxgi__chart_box(&charts[i], scale, &w, &h);
        if (w > size || h > size) return 0;
        if (x + w > size) { y += shelf; x = 0; shelf = 0; }
        if (y + h > size) return 0;
        if (uv) voxgi__chart_place(&charts[i], scale, x, y, uv + 6 * (size_t)charts[i].tri);
        x += w;
        shelf = VOXGI__MAX(shelf, h);
    }
    return 1;
}

/* Orders the charts by decreasing height, then triangle (a stable LSD radix sort on 64-bit keys:
   the height's float bits, which order like the heights, inverted; then the index). */
static voxgi_result voxgi__charts_by_height(voxgi_context *ctx, voxgi__chart *charts, size_t n)
{
    uint64_t *key = (uint64_t *)voxgi__alloc_array(ctx, n ? 2 * n : 1, sizeof(uint64_t), 0), *tmp = key + n;
    voxgi__chart *sorted = (voxgi__chart *)voxgi__alloc_array(ctx, n ? n : 1, sizeof *sorted, 0);
    size_t i, count[256];
    int pass;
    if (!key || !sorted) {
        voxgi__free(ctx, key);
        voxgi__free(ctx, sorted);
        return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory to sort %lu charts", (unsigned long)n);
    }
    for (i = 0; i < n; i++) {
        float h = (float)charts[i].height;
        uint32_t bits;
        memcpy(&bits, &h, 4);
        key[i] = ((uint64_t)(~bits) << 32) | charts[i].tri; /* heights are >= 0: their bits grow with them */
    }
    for (pass = 0; pass < 8; pass++) {
        size_t sum = 0;
        memset(count, 0, sizeof count);
        for (i = 0; i < n; i++) count[(key[i] >> (8 * pass)) & 255u]++;
        for (i = 0; i < 256; i++) { size_t c = count[i]; count[i] = sum; sum += c; }
        for (i = 0; i < n; i++) tmp[count[(key[i] >> (8 * pass)) & 255u]++] = key[i];
        memcpy(key, tmp, n * sizeof *key);
    }
    for (i = 0; i < n; i++) sorted[i] = charts[(uint32_t)key[i]]; /* charts[t].tri == t before sorting */
    memcpy(charts, sorted, n * sizeof *charts);
    voxgi__free(ctx, key);
    voxgi__free(ctx, sorted);
    return VOXGI_OK;
}

/* Builds the atlas: its size, and every triangle's chart corners. */
static voxgi_result voxgi__atlas_build(voxgi_context *ctx, const voxgi__flat *f, const voxgi__vprep *vp,
                                       const voxgi_voxelize_desc *d, voxgi__atlas *at)
{
    size_t n = f->triangle_count, i;
    memset(at, 0, sizeof *at);
    if (d->atlas_size < 0 || d->atlas_size > VOXGI__ATLAS_MAX)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "atlas_size %d is outside 1..%d (0 = default)", d->atlas_size, VOXGI__ATLAS_MAX);
    if ((unsigned)d->atlas_uv > (unsigned)VOXGI_ATLAS_MESH)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "unknown atlas_uv %d", (int)d->atlas_uv);
    at->uv = (float *)voxgi__alloc_array(ctx, n ? n : 1, 6 * sizeof(float), 1);
    if (!at->uv) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu atlas charts", (unsigned long)n);
    if (d->atlas_uv == VOXGI_ATLAS_MESH) {
        at->size = d->atlas_size ? d->atlas_size : 1024;
        for (i = 0; i < 3 * n; i++) {
            const float *uv = f->uv + 2 * (size_t)f->tri[i];
            at->uv[2 * i] = (float)voxgi__snap256(VOXGI__MIN(VOXGI__MAX((double)uv[0], 0.0), 1.0) * at->size);
            at->uv[2 * i + 1] = (float)voxgi__snap256(VOXGI__MIN(VOXGI__MAX((double)uv[1], 0.0), 1.0) * at->size);
        }
    } else {
        voxgi__chart *charts = (voxgi__chart *)voxgi__alloc_array(ctx, n ? n : 1, sizeof *charts, 0);
        double lo = 0, hi;
        int steps;
        if (!charts) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu atlas charts", (unsigned long)n);
        for (i = 0; i < n; i++) voxgi__chart_shape(vp, f->tri, (uint32_t)i, &charts[i]);
        if (voxgi__charts_by_height(ctx, charts, n) != VOXGI_OK) { voxgi__free(ctx, charts); return VOXGI_ERR_OUT_OF_MEMORY; }
        at->size = d->atlas_size;
        if (!at->size) { /* the side that holds the charts at 2 texels per voxel, and at least
                              every chart at its smallest (3x3), with 10% to spare for shelves */
            double area = 0, w, h;
            for (i = 0; i < n; i++) {
                voxgi__chart_box(&charts[i], VOXGI__ATLAS_TEXELS_PER_VOXEL, &w, &h);
                area += w * h;
            }
            area = VOXGI__MAX(area, 9.0 * (double)n);
            at->size = (int)VOXGI__MIN(ceil(sqrt(area * 1.1) / 64) * 64, (double)VOXGI__ATLAS_MAX_DEFAULT);
            at->size = VOXGI__MAX(at->size, 64);
        }
        if (!voxgi__atlas_pack(charts, n, 0, at->size, NULL)) {
            voxgi__free(ctx, charts);
            return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "a %dx%d atlas cannot hold %lu charts of 3x3 texels; raise atlas_size",
                               at->size, at->size, (unsigned long)n);
        }
        /* the largest scale that fits: a bracket around the area estimate (boxes hold twice
           their triangle), then bisection to a thousandth */
        {
            double area = 0, guess;
            for (i = 0; i < n; i++) area += charts[i].len * charts[i].height;
            guess = area > 0 ? sqrt((double)at->size * at->size / area) : 1.0;
            for (hi = guess, steps = 0; steps < 80 && voxgi__atlas_pack(charts, n, hi, at->size, NULL); steps++) { lo = hi; hi *= 2; }
            for (steps = 0; steps < 80 && lo == 0; steps++) {
                double try_lo = hi / 2;
                if (voxgi__atlas_pack(charts, n, try_lo, at->size, NULL)) lo = try_lo;
                else hi = try_lo;
            }
        }
        for (steps = 0; steps < 10; steps++) {
            double mid = 0.5 * (lo + hi);
            if (voxgi__atlas_pack(charts, n, mid, at->size, NULL)) lo = mid;
            else hi = mid;
        }
        at->scale = lo;
        voxgi__atlas_pack(charts, n, lo, at->size, at->uv);
        voxgi__free(ctx, charts);
        if (!d->atlas_size && lo < VOXGI__ATLAS_TEXELS_PER_VOXEL)
            voxgi__log(ctx, VOXGI_LOG_INFO, "the default atlas stops at %dx%d: %.3g texels per voxel edge, expect holes",
                       at->size, at->size, lo);
    }
    for (at->view = 1; at->view < at->size; at->view *= 2) {}
    if (ctx->desc.memory_budget && (uint64_t)at->size * (uint64_t)at->size * 4u > (uint64_t)ctx->desc.memory_budget)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "a %dx%d atlas needs %llu bytes, more than the memory budget %llu", at->size,
                           at->size, (unsigned long long)((uint64_t)at->size * (uint64_t)at->size * 4u),
                           (unsigned long long)ctx->desc.memory_budget);
    return VOXGI_OK;
}

/* The triangle (index + 1) each texel centre belongs to; 0 = none. Concurrent writers keep the
   highest index, which is the one GL draws last. */
typedef struct voxgi__atlas_job {
    const voxgi__atlas *at;
    const voxgi__vox_shared *vs;
    uint32_t *texels;
    uint64_t points;
} voxgi__atlas_job;

static void voxgi__atlas_texel(void *user, uint32_t t, int i, int j)
{
    voxgi__atlas_job *job = (voxgi__atlas_job *)user;
    uint32_t *texel = job->texels + (size_t)j * (size_t)job->at->size + (size_t)i, old = VOXGI__ATOMIC_LOAD_U32(texel);
    while (old < t + 1 && !VOXGI__ATOMIC_CAS_U32(texel, &old, t + 1)) {}
}

static void voxgi__atlas_raster(void *user, size_t first, size_t end)
{
    voxgi__atlas_job *job = (voxgi__atlas_job *)user;
    size_t t;
    for (t = first; t < end; t++) {
        const float *c = job->at->uv + 6 * t;
        double x[3], y[3];
        int k;
        for (k = 0; k < 3; k++) { x[k] = c[2 * k]; y[k] = c[2 * k + 1]; }
        voxgi__vox_raster_cpu(x, y, job->at->size, job->at->size, voxgi__atlas_texel, job, (uint32_t)t);
    }
}

/* The voxel of atlas point (texel i, j) of triangle t; 0 when it lies outside the grid. The
   arithmetic and its order are those of atlas_point_voxel in shaders/atlas.glsl. */
static int voxgi__atlas_point(const voxgi__atlas *at, const voxgi__vox_shared *vs, uint32_t t, int i, int j, int64_t v[3])
{
    const float *c = at->uv + 6 * (size_t)t;
    const double *q0 = vs->vp[vs->tri[3 * t]].q, *q1 = vs->vp[vs->tri[3 * t + 1]].q, *q2 = vs->vp[vs->tri[3 * t + 2]].q;
    double px = (double)i + 0.5 - c[0], py = (double)j + 0.5 - c[1];
    double e1x = (double)c[2] - c[0], e1y = (double)c[3] - c[1], e2x = (double)c[4] - c[0], e2y = (double)c[5] - c[1];
    double den = e1x * e2y - e1y * e2x, n1 = px * e2y - py * e2x, n2 = e1x * py - e1y * px; /* exact */
    int a;
    for (a = 0; a < 3; a++) {
        double p = q0[a] + (n1 * (q1[a] - q0[a]) + n2 * (q2[a] - q0[a])) / den, k = floor(p);
        if (!(k >= 0 && k < (double)vs->grid->res[a])) return 0;
        v[a] = (int64_t)k;
    }
    return 1;
}

static void voxgi__atlas_points(void *user, size_t first, size_t end)
{
    voxgi__atlas_job *job = (voxgi__atlas_job *)user;
    voxgi__stats st = {0, 0, 0};
    uint64_t points = 0;
    size_t row, size = (size_t)job->at->size;
    for (row = first; row < end; row++) {
        size_t i;
        for (i = 0; i < size; i++) {
            uint32_t t = job->texels[row * size + i];
            int64_t v[3];
            if (!t) continue;
            points++;
            if (voxgi__atlas_point(job->at, job->vs, t - 1, (int)i, (int)row, v)) voxgi__set_voxel(job->vs, &st, v[0], v[1], v[2]);
        }
    }
    VOXGI__ATOMIC_ADD_SIZE(&job->points, points);
}

/* The CPU twin of both atlas methods. */
static voxgi_result voxgi__vox_atlas_cpu(voxgi_context *ctx, const voxgi__vox_shared *vs, size_t triangle_count,
                                     const voxgi__atlas *at, uint64_t *points)
{
    voxgi__atlas_job job;
    job.at = at;
    job.vs = vs;
    job.points = 0;
    job.texels = (uint32_t *)voxgi__alloc_array(ctx, (size_t)at->size * (size_t)at->size, 4, 1);
    if (!job.texels) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for a %dx%d atlas", at->size, at->size);
    voxgi__parallel(ctx, triangle_count, 256, voxgi__atlas_raster, &job);
    voxgi__parallel(ctx, (size_t)at->size, 16, voxgi__atlas_points, &job);
    voxgi__free(ctx, job.texels);
    *points = job.points;
    return VOXGI_OK;
}

#ifndef VOXGI_NO_GL

/* The texture atlas: the charts drawn into an R32UI atlas, its covered texels listed as
   points, then the points either drawn into slicemap targets (ATLAS) or each set by one
   compute invocation (ATLAS_COMPUTE). */
static voxgi_result voxgi__vox_atlas_gl(voxgi_context *ctx, const voxgi__flat *f, const voxgi__vprep *vp,
                                    const voxgi_voxelize_desc *d, const voxgi__atlas *at, unsigned int *bits_out,
                                    voxgi_voxels_info *info)
{
    voxgi__gl *gl = ctx->gl;
    const voxgi_grid *g = &d->grid;
    voxgi__gl_raster_state state;
    unsigned int verts = 0, tris = 0, charts = 0, points = 0, tex = 0, fbo = 0, vao = 0, zero = 0, p, drawbuf = VOXGI__GL_COLOR_ATTACHMENT0;
    uint32_t count = 0;
    int max_size = 0;
    uint64_t texels = (uint64_t)at->size * (uint64_t)at->size;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_atlas_fill);
    if (r == VOXGI_OK) r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_atlas_list);
    if (r == VOXGI_OK && d->method == VOXGI_METHOD_ATLAS)
        r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_atlas_points);
    if (r == VOXGI_OK && d->method == VOXGI_METHOD_ATLAS_COMPUTE)
        r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_atlas_compute);
    if (r != VOXGI_OK) return r;
    gl->GetIntegerv(VOXGI__GL_MAX_TEXTURE_SIZE, &max_size);
    if (at->view > max_size)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "a %dx%d atlas (viewport %d) exceeds GL_MAX_TEXTURE_SIZE %d", at->size, at->size,
                           at->view, max_size);
    voxgi__vox_scene_buffers_gl(ctx, f, vp, &verts, &tris, &r);
    if (r != VOXGI_OK) return r;
    charts = voxgi__gl_buffer(ctx, f->triangle_count * 6 * sizeof(float), at->uv);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 2, charts);
    /* 1. the charts into the atlas */
    gl->CreateTextures(VOXGI__GL_TEXTURE_2D, 1, &tex);
    gl->TextureStorage2D(tex, 1, VOXGI__GL_R32UI, at->size, at->size);
    gl->TextureParameteri(tex, VOXGI__GL_TEXTURE_MIN_FILTER, VOXGI__GL_NEAREST);
    gl->TextureParameteri(tex, VOXGI__GL_TEXTURE_MAG_FILTER, VOXGI__GL_NEAREST);
    gl->ClearTexImage(tex, 0, VOXGI__GL_RED_INTEGER, VOXGI__GL_UNSIGNED_INT, &zero);
    gl->CreateFramebuffers(1, &fbo);
    gl->NamedFramebufferTexture(fbo, VOXGI__GL_COLOR_ATTACHMENT0, tex, 0);
    gl->NamedFramebufferDrawBuffers(fbo, 1, &drawbuf);
    gl->CreateVertexArrays(1, &vao);
    voxgi__gl_raster_begin(gl, &state);
    if (gl->CheckNamedFramebufferStatus(fbo, VOXGI__GL_FRAMEBUFFER) != VOXGI__GL_FRAMEBUFFER_COMPLETE)
        r = voxgi__fail(ctx, VOXGI_ERR_GL, "the atlas framebuffer is incomplete");
    else {
        p = gl->prog_atlas_fill;
        gl->UseProgram(p);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_view, at->view);
        gl->BindVertexArray(vao);
        gl->BindFramebuffer(VOXGI__GL_FRAMEBUFFER, fbo);
        gl->Viewport(0, 0, at->view, at->view); /* beyond the atlas: the corners map to window coordinates exactly */
        gl->DrawArrays(VOXGI__GL_TRIANGLES, 0, (int)(3 * f->triangle_count));
        gl->BindFramebuffer(VOXGI__GL_FRAMEBUFFER, 0);
        gl->BindVertexArray(0);
    }
    voxgi__gl_raster_end(gl, &state);
    gl->MemoryBarrier(VOXGI__GL_TEXTURE_FETCH_BARRIER_BIT | VOXGI__GL_FRAMEBUFFER_BARRIER_BIT);
    /* 2. the covered texels: count, then list */
    if (r == VOXGI_OK) {
        points = voxgi__gl_buffer(ctx, 8, NULL);
        gl->ClearNamedBufferData(points, VOXGI__GL_R32UI, VOXGI__GL_RED_INTEGER, VOXGI__GL_UNSIGNED_INT, &zero);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 3, points);
        gl->BindTextureUnit(0, tex);
        p = gl->prog_atlas_list;
        gl->UseProgram(p);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_size, at->size);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, 0);
        voxgi__gl_dispatch_rows(gl, texels);
        r = voxgi__gl_read_buffer(ctx, points, &count, 4);
    }
    if (r == VOXGI_OK) {
        voxgi__gl_delete_buffer(ctx, points);
        points = voxgi__gl_buffer(ctx, 8 + 8 * (size_t)count, NULL);
        gl->ClearNamedBufferData(points, VOXGI__GL_R32UI, VOXGI__GL_RED_INTEGER, VOXGI__GL_UNSIGNED_INT, &zero);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 3, points);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, 1);
        voxgi__gl_dispatch_rows(gl, texels);
        gl->BindTextureUnit(0, 0);
        info->atlas_points = count;
        r = voxgi__gl_check(ctx, "the atlas");
    }
    gl->DeleteTextures(1, &tex);
    gl->DeleteFramebuffers(1, &fbo);
    gl->DeleteVertexArrays(1, &vao);
    /* 3. the points into voxels */
    if (r == VOXGI_OK && d->method == VOXGI_METHOD_ATLAS)
        r = voxgi__vox_raster_gl(ctx, g, (int)d->axis - 1, d->atomic, gl->prog_atlas_points, VOXGI__GL_POINTS,
                                   count, bits_out);
    else if (r == VOXGI_OK) {
        *bits_out = voxgi__gl_grid_buffer(ctx, (size_t)voxgi__grid_words(g) * 4);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 4, *bits_out);
        p = gl->prog_atlas_compute;
        gl->UseProgram(p);
        gl->ProgramUniform3i(p, VOXGI__LOC_u_res, g->res[0], g->res[1], g->res[2]);
        voxgi__gl_dispatch_rows(gl, count);
        r = voxgi__gl_check(ctx, "the atlas points");
    }
    voxgi__gl_unbind(gl);
    voxgi__gl_delete_buffer(ctx, verts);
    voxgi__gl_delete_buffer(ctx, tris);
    voxgi__gl_delete_buffer(ctx, charts);
    voxgi__gl_delete_buffer(ctx, points);
    if (r != VOXGI_OK && *bits_out) { voxgi__gl_delete_buffer(ctx, *bits_out); *bits_out = 0; }
    return r;
}
#endif /* VOXGI_NO_GL */

/* ----- 5.7 running a voxelization: the CPU workers, the GL passes, the API */

/* Phase 1 hands out triangles in chunks and lists the big ones (more than
   VOXGI__BIG_COLUMNS columns); phase 2 hands out blocks of their rows, so a few huge triangles
   keep every core busy too. OR is order-free: the bits do not depend on threads or schedule. */
#define VOXGI__CHUNK 64
#define VOXGI__BIG_COLUMNS 4096
#define VOXGI__ROWS_PER_ITEM 8

typedef struct voxgi__vox_job {
    const voxgi__vox_shared *vs;
    size_t triangle_count, next;
    int phase, cancel;
    uint64_t exact_tests, voxels;
    uint32_t *big;             /* phase 1 output: big triangles */
    size_t big_count;
    size_t *big_first_item;    /* phase 2: prefix sums of row blocks, big_count + 1 entries */
} voxgi__vox_job;

static void voxgi__vox_work(voxgi__vox_job *job, voxgi_context *ctx_for_progress)
{
    voxgi__stats st = {0, 0, 0};
    voxgi__prepared P;
    int reported = 0; /* the calling thread reports its first piece of work, or the phase's end if the workers took all */
    for (;;) {
        size_t first = VOXGI__ATOMIC_ADD_SIZE(&job->next, job->phase ? (size_t)1 : (size_t)VOXGI__CHUNK), t, end;
        double fraction;
        int due;
        if (VOXGI__ATOMIC_LOAD_INT(&job->cancel)) break;
        if (job->phase == 0) {
            if (first >= job->triangle_count) break;
            end = VOXGI__MIN(first + VOXGI__CHUNK, job->triangle_count);
            for (t = first; t < end; t++) {
                st.tri = (uint32_t)t;
                if (job->vs->solid_axis >= 0) { voxgi__vox_solid_cpu(job->vs, t, &st); continue; }
                if (job->vs->slice_axis >= 0) { voxgi__vox_slicemap_cpu(job->vs, t, &st); continue; }
                if (job->vs->volume_buffer) { voxgi__vox_volume_buffer_cpu(job->vs, t, &st); continue; }
                if (!voxgi__tri_prepare(job->vs, t, &P, &st)) continue;
                if ((int64_t)P.ext[(P.c + 1) % 3] * P.ext[(P.c + 2) % 3] > VOXGI__BIG_COLUMNS)
                    job->big[VOXGI__ATOMIC_ADD_SIZE(&job->big_count, (size_t)1)] = (uint32_t)t;
                else voxgi__tri_rows(job->vs, &P, 0, P.ext[(P.c + 2) % 3] - 1, &st);
            }
            fraction = (double)end / (double)job->triangle_count;
            due = (first / VOXGI__CHUNK) % 64 == 0;
        } else {
            size_t lo = 0, hi = job->big_count, item = first;
            int32_t row0;
            if (item >= job->big_first_item[job->big_count]) break;
            while (hi - lo > 1) { /* the big triangle whose blocks hold this item */
                size_t mid = (lo + hi) / 2;
                if (job->big_first_item[mid] <= item) lo = mid;
                else hi = mid;
            }
            st.tri = job->big[lo];
            voxgi__tri_prepare(job->vs, job->big[lo], &P, &st);
            row0 = (int32_t)(item - job->big_first_item[lo]) * VOXGI__ROWS_PER_ITEM;
            voxgi__tri_rows(job->vs, &P, row0, VOXGI__MIN(row0 + VOXGI__ROWS_PER_ITEM, P.ext[(P.c + 2) % 3]) - 1, &st);
            fraction = (double)(item + 1) / (double)job->big_first_item[job->big_count];
            due = item % 64 == 0;
        }
        if (ctx_for_progress && (due || !reported)) {
            reported = 1;
            if (voxgi__progress(ctx_for_progress, fraction, job->phase ? "voxelize large triangles" : "voxelize")) VOXGI__ATOMIC_STORE_INT(&job->cancel, 1);
        }
    }
    if (ctx_for_progress && !reported && voxgi__progress(ctx_for_progress, 1.0, job->phase ? "voxelize large triangles" : "voxelize"))
        VOXGI__ATOMIC_STORE_INT(&job->cancel, 1); /* the workers took every piece: the caller still hears of the phase */
    VOXGI__ATOMIC_ADD_SIZE(&job->exact_tests, st.exact_tests);
    VOXGI__ATOMIC_ADD_SIZE(&job->voxels, st.voxels);
}

#ifndef VOXGI_NO_THREADS
static void *voxgi__vox_thread(void *p)
{
    voxgi__vox_work((voxgi__vox_job *)p, NULL);
    return NULL;
}
#endif

/* Runs one phase of the job on the calling thread and (thread_count - 1) helpers. */
static void voxgi__vox_phase(voxgi_context *ctx, voxgi__vox_job *job, size_t items)
{
    int started = 0;
#ifndef VOXGI_NO_THREADS
    pthread_t threads[256];
    int i, want = ctx->desc.thread_count - 1;
    if ((size_t)want > items) want = (int)items;
    for (i = 0; i < want && i < 256; i++) {
        if (pthread_create(&threads[i], NULL, voxgi__vox_thread, job) != 0) break;
        started++;
    }
#else
    (void)items;
#endif
    voxgi__vox_work(job, ctx); /* the calling thread works too, and reports progress */
#ifndef VOXGI_NO_THREADS
    for (i = 0; i < started; i++) pthread_join(threads[i], NULL);
#else
    (void)started;
#endif
}

/* Runs the CPU voxelizer over all triangles into vs->bits (which the caller zeroed). */
static voxgi_result voxgi__vox_workers_cpu(voxgi_context *ctx, const voxgi__vox_shared *vs, size_t triangle_count,
                                            voxgi__stats *st)
{
    voxgi__vox_job job;
    size_t i;
    memset(&job, 0, sizeof job);
    job.vs = vs;
    job.triangle_count = triangle_count;
    job.big = (uint32_t *)voxgi__alloc_array(ctx, triangle_count, sizeof *job.big, 0);
    if (!job.big) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu triangles", (unsigned long)triangle_count);
    voxgi__vox_phase(ctx, &job, triangle_count / VOXGI__CHUNK);
    if (job.big_count && !job.cancel) {
        job.big_first_item = (size_t *)voxgi__alloc_array(ctx, job.big_count + 1, sizeof(size_t), 0);
        if (!job.big_first_item) {
            voxgi__free(ctx, job.big);
            return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the large-triangle list");
        }
        job.big_first_item[0] = 0;
        for (i = 0; i < job.big_count; i++) {
            voxgi__prepared P;
            voxgi__stats unused = {0, 0, 0};
            voxgi__tri_prepare(vs, job.big[i], &P, &unused);
            job.big_first_item[i + 1] = job.big_first_item[i] +
                                        (size_t)(P.ext[(P.c + 2) % 3] + VOXGI__ROWS_PER_ITEM - 1) / VOXGI__ROWS_PER_ITEM;
        }
        job.phase = 1;
        job.next = 0;
        voxgi__vox_phase(ctx, &job, job.big_first_item[job.big_count]);
    }
    voxgi__free(ctx, job.big);
    voxgi__free(ctx, job.big_first_item);
    st->exact_tests += job.exact_tests;
    st->voxels += job.voxels;
    if (job.cancel) return voxgi__fail(ctx, VOXGI_ERR_CANCELLED, "voxelization cancelled by the progress callback");
    return VOXGI_OK;
}

static voxgi_result voxgi__prep_vertices(voxgi_context *ctx, const voxgi__flat *f, const voxgi_grid *g, voxgi__vprep **out)
{
    size_t v;
    voxgi__vprep *vp = (voxgi__vprep *)voxgi__alloc_array(ctx, f->vertex_count, sizeof *vp, 0);
    *out = vp;
    if (!vp) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu vertices", (unsigned long)f->vertex_count);
    for (v = 0; v < f->vertex_count; v++) voxgi__prep_vertex(f->pos + 3 * v, g, &vp[v]);
    return VOXGI_OK;
}

/* The CPU twin of every method, into vox->bits. */
static voxgi_result voxgi__vox_run_cpu(voxgi_context *ctx, const voxgi__flat *flat, const voxgi__vprep *vp,
                                       const voxgi_voxelize_desc *desc, const voxgi__atlas *atlas, voxgi_voxels *vox)
{
    voxgi__vox_shared vs;
    voxgi__stats st = {0, 0, 0};
    size_t words = (size_t)voxgi__grid_words(&desc->grid), i;
    uint32_t *extra[2] = {NULL, NULL};
    voxgi_result r = VOXGI_OK;
    int pass, passes = 1, solid = desc->method == VOXGI_METHOD_SOLID;
    vox->bits = (uint32_t *)voxgi__alloc_array(ctx, words, 4, 1);
    if (!vox->bits)
        return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for a %dx%dx%d bit grid (%lu bytes)", desc->grid.res[0],
                           desc->grid.res[1], desc->grid.res[2], (unsigned long)vox->info.bytes);
    if (solid && desc->solid_mode == VOXGI_SOLID_VOTE) {
        passes = 3;
        for (i = 0; i < 2; i++)
            if (!(extra[i] = (uint32_t *)voxgi__alloc_array(ctx, words, 4, 1))) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the vote");
    }
    voxgi__vox_shared_init(&vs, &desc->grid, flat, vp, desc->method, vox->bits);
    vs.slice_axis = desc->method == VOXGI_METHOD_SLICEMAP ? ((int)desc->axis - 1) : -1;
    vs.volume_buffer = desc->method == VOXGI_METHOD_VOLUME_BUFFER;
    if (atlas) {
        vs.bits = vox->bits;
        r = voxgi__vox_atlas_cpu(ctx, &vs, flat->triangle_count, atlas, &vox->info.atlas_points);
        passes = 0;
    }
    for (pass = 0; pass < passes && r == VOXGI_OK; pass++) {
        vs.bits = pass ? extra[pass - 1] : vox->bits;
        vs.solid_axis = -1;
        if (solid && desc->solid_mode != VOXGI_SOLID_FLOOD)
            vs.solid_axis = passes == 3 ? pass : ((int)desc->axis - 1);
        r = voxgi__vox_workers_cpu(ctx, &vs, flat->triangle_count, &st);
        if (r == VOXGI_OK && vs.solid_axis >= 0) voxgi__prefix_xor(vs.bits, &desc->grid, vs.solid_axis);
    }
    if (r == VOXGI_OK && passes == 3) /* majority of three */
        for (i = 0; i < words; i++) {
            uint32_t x = vox->bits[i], y = extra[0][i], z = extra[1][i];
            vox->bits[i] = (x & y) | (y & z) | (x & z);
        }
    if (r == VOXGI_OK && solid && desc->solid_mode == VOXGI_SOLID_FLOOD) r = voxgi__vox_flood_cpu(ctx, &desc->grid, vox->bits);
    if (r == VOXGI_OK && vox->attr.rec) { /* the attribute pass: the same tests again, now adding to the set voxels */
        voxgi__stats ast = {0, 0, 0};
        r = voxgi__attr_alloc(ctx, &vox->attr, vox->bits, words, st.voxels);
        vs.bits = vox->bits;
        vs.attr = &vox->attr;
        if (r == VOXGI_OK) r = voxgi__vox_workers_cpu(ctx, &vs, flat->triangle_count, &ast);
    }
    voxgi__free(ctx, extra[0]);
    voxgi__free(ctx, extra[1]);
    vox->info.exact_tests = st.exact_tests;
    vox->info.voxel_count = solid || atlas ? voxgi__vox_count_cpu(vox->bits, words) : st.voxels;
    return r;
}

#ifndef VOXGI_NO_GL

static voxgi_result voxgi__vox_run_gl(voxgi_context *ctx, const voxgi__flat *f, const voxgi__vprep *vp,
                                       const voxgi_voxelize_desc *d, const voxgi__atlas *atlas, voxgi_voxels *out)
{
    voxgi__gl *gl = ctx->gl;
    const voxgi_grid *g = &d->grid;
    uint64_t nvox = voxgi_grid_voxel_count(g), words = voxgi__grid_words(g);
    size_t bytes = (size_t)words * 4;
    unsigned int result = 0;
    voxgi_result r;
    if (nvox > (uint64_t)UINT32_MAX)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "GL grids hold at most 2^32 voxels (32-bit bit indices in GLSL); "
                           "%dx%dx%d needs the CPU backend", g->res[0], g->res[1], g->res[2]);
    if ((int64_t)bytes > gl->max_ssbo_bytes)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "a %dx%dx%d bit grid needs %lu bytes, more than this GL's "
                           "GL_MAX_SHADER_STORAGE_BLOCK_SIZE (%lld); use the CPU backend", g->res[0], g->res[1], g->res[2],
                           (unsigned long)bytes, (long long)gl->max_ssbo_bytes);
    if ((uint64_t)g->res[0] * g->res[1] > 65535u * 64u || (uint64_t)g->res[1] * g->res[2] > 65535u * 64u ||
        (uint64_t)g->res[0] * g->res[2] > 65535u * 64u)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "GL grid slices hold at most 65535*64 lines; use the CPU backend");
    r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_voxelize_conservative);
    if (r == VOXGI_OK) r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_voxelize_solid);
    if (r == VOXGI_OK && d->method == VOXGI_METHOD_GEOMETRY) {
        int max_view = 0;
        gl->GetIntegerv(VOXGI__GL_MAX_FRAMEBUFFER_WIDTH, &max_view);
        if (VOXGI__MAX(g->res[0], VOXGI__MAX(g->res[1], g->res[2])) > max_view)
            return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "the geometry voxelizer draws into %d pixels, more than this GL's "
                               "GL_MAX_FRAMEBUFFER_WIDTH %d", VOXGI__MAX(g->res[0], VOXGI__MAX(g->res[1], g->res[2])), max_view);
        r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_voxelize_geometry);
    }
    if (r == VOXGI_OK) r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_solid_prefix);
    if (r == VOXGI_OK) r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_flood);
    if (r == VOXGI_OK) r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_bits_majority);
    if (r != VOXGI_OK) return r;
    if (d->method == VOXGI_METHOD_SLICEMAP) r = voxgi__vox_slicemap_gl(ctx, f, vp, d, &result);
    else if (atlas) r = voxgi__vox_atlas_gl(ctx, f, vp, d, atlas, &result, &out->info);
    else if (d->method == VOXGI_METHOD_VOLUME_BUFFER)
        r = voxgi__vox_volume_buffer_gl(ctx, f, vp, d, &result, out->attr.rec ? &out->attr : NULL, &out->info);
    else if (d->method != VOXGI_METHOD_SOLID)
        r = voxgi__vox_triangles_gl(ctx, f, vp, d, -1, &result, &out->info, out->attr.rec ? &out->attr : NULL);
    else if (d->solid_mode == VOXGI_SOLID_PARITY)
        r = voxgi__vox_solid_gl(ctx, f, vp, d, (int)d->axis - 1, &result, &out->info);
    else if (d->solid_mode == VOXGI_SOLID_FLOOD) r = voxgi__vox_flood_gl(ctx, f, vp, d, &result, &out->info);
    else { /* vote: parity along x, y and z, then the majority into the last */
        unsigned int axes[3] = {0, 0, 0}, p = gl->prog_bits_majority;
        int a;
        for (a = 0; a < 3 && r == VOXGI_OK; a++) r = voxgi__vox_solid_gl(ctx, f, vp, d, a, &axes[a], &out->info);
        if (r == VOXGI_OK) {
            for (a = 0; a < 3; a++) gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, (unsigned)a, axes[a]);
            gl->UseProgram(p);
            gl->ProgramUniform1ui(p, VOXGI__LOC_u_words, (unsigned)words);
            voxgi__gl_dispatch_items(gl, words);
            voxgi__gl_unbind(gl);
            result = axes[2];
            axes[2] = 0;
        }
        for (a = 0; a < 3; a++) voxgi__gl_delete_buffer(ctx, axes[a]);
    }
    if (r != VOXGI_OK) return r;
    r = voxgi__vox_count_gl(ctx, result, words, &out->info.voxel_count); /* count the set voxels on the GPU */
    if (r != VOXGI_OK) { voxgi__gl_delete_buffer(ctx, result); return r; }
    out->gl_buffer = result;
    return voxgi__gl_check(ctx, "voxelization");
}
#endif /* VOXGI_NO_GL */

/* Every default of a voxgi_voxelize_desc the twins read: the axis (z) and the Volume Buffer's
   slicing (M2). The atlas size left at 0 is sized from the grid by voxgi__atlas_build. */
static voxgi_voxelize_desc voxgi__voxelize_defaults(const voxgi_voxelize_desc *in)
{
    voxgi_voxelize_desc d = *in;
    if (d.axis == VOXGI_AXIS_DEFAULT) d.axis = VOXGI_AXIS_Z;
    if (!d.volume_slicing) d.volume_slicing = 2;
    return d;
}

VOXGI_API voxgi_result voxgi_voxelize(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_voxelize_desc *desc_in,
                                      voxgi_voxels **out)
{
    voxgi_voxelize_desc resolved;
    const voxgi_voxelize_desc *desc = desc_in;
    voxgi__flat flat;
    voxgi__vprep *vp = NULL;
    voxgi__atlas atlas;
    voxgi_voxels *vox;
    voxgi_result r;
    double t0 = voxgi__now_ms();
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!desc || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "desc or out is NULL");
    *out = NULL;
    if ((unsigned)desc->method >= (unsigned)VOXGI_METHOD_COUNT_)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "unknown voxelization method %d", (int)desc->method);
    if ((unsigned)desc->axis > (unsigned)VOXGI_AXIS_Z || (unsigned)desc->solid_mode > (unsigned)VOXGI_SOLID_FLOOD)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "unknown axis %d or solid mode %d", (int)desc->axis, (int)desc->solid_mode);
    if (desc->attributes & ~VOXGI__VOXEL_ATTRIBUTES)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "unknown attribute bits 0x%x", desc->attributes & ~VOXGI__VOXEL_ATTRIBUTES);
    if ((unsigned)desc->blend[0] > VOXGI_BLEND_ADD || (unsigned)desc->blend[1] > VOXGI_BLEND_ADD ||
        (unsigned)desc->blend[2] > VOXGI_BLEND_ADD || (unsigned)desc->blend[3] > VOXGI_BLEND_ADD ||
        desc->volume_slicing < 0 || desc->volume_slicing > 2)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "unknown blend mode or volume_slicing %d", desc->volume_slicing);
    if (desc->attributes && desc->method != VOXGI_METHOD_CONSERVATIVE && desc->method != VOXGI_METHOD_THIN &&
        desc->method != VOXGI_METHOD_GEOMETRY && desc->method != VOXGI_METHOD_VOLUME_BUFFER)
        return voxgi__fail(ctx, VOXGI_ERR_UNSUPPORTED, "attributes come from the conservative, thin, geometry and volume-buffer methods, not %s",
                           voxgi_method_name(desc->method));
    resolved = voxgi__voxelize_defaults(desc_in);
    desc = &resolved;
    r = voxgi_validate_grid(ctx, &desc->grid);
    if (r != VOXGI_OK) return r;
    r = voxgi__flatten(ctx, scene, voxgi__is_atlas(desc->method) && desc->atlas_uv == VOXGI_ATLAS_MESH, desc->attributes != 0, &flat);
    if (r != VOXGI_OK) return r;
    vox = (voxgi_voxels *)voxgi__alloc_array(ctx, 1, sizeof *vox, 1);
    if (!vox) { voxgi__flat_free(ctx, &flat); return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the result"); }
    vox->info.grid = desc->grid;
    vox->info.method = desc->method;
    vox->info.backend = ctx->backend;
    vox->info.triangle_count = flat.triangle_count;
    vox->info.bytes = (size_t)(voxgi__grid_words(&desc->grid) * 4u);
    r = voxgi__prep_vertices(ctx, &flat, &desc->grid, &vp);
    if (r == VOXGI_OK && desc->attributes) {
        r = voxgi__attr_prepare(ctx, &flat, desc->attributes, desc->blend, &vox->attr);
        vox->info.attributes = desc->attributes;
    }
    memset(&atlas, 0, sizeof atlas);
    if (r == VOXGI_OK && voxgi__is_atlas(desc->method)) {
        r = voxgi__atlas_build(ctx, &flat, vp, desc, &atlas);
        vox->info.atlas_size = atlas.size;
        vox->info.atlas_scale = atlas.scale;
    }
    if (r == VOXGI_OK && ctx->backend == VOXGI_BACKEND_CPU)
        r = voxgi__vox_run_cpu(ctx, &flat, vp, desc, voxgi__is_atlas(desc->method) ? &atlas : NULL, vox);
#ifndef VOXGI_NO_GL
    else if (r == VOXGI_OK) {
        r = voxgi__vox_run_gl(ctx, &flat, vp, desc, voxgi__is_atlas(desc->method) ? &atlas : NULL, vox);
        if (r == VOXGI_OK && voxgi__progress(ctx, 1.0, "voxelize")) /* one report, as the CPU's last */
            r = voxgi__fail(ctx, VOXGI_ERR_CANCELLED, "voxelization cancelled by the progress callback (voxelize)");
    }
#endif
    voxgi__free(ctx, atlas.uv);
    voxgi__free(ctx, vp);
    voxgi__free(ctx, vox->attr.rec); /* what stays: counts and sums */
    voxgi__free(ctx, vox->attr.rank);
    vox->attr.rec = vox->attr.rank = NULL;
    if (r == VOXGI_OK && vox->attr.count) {
        uint64_t i;
        for (i = 0; i < vox->info.voxel_count; i++) vox->info.attribute_pairs += vox->attr.count[i];
    }
    voxgi__flat_free(ctx, &flat);
    if (r != VOXGI_OK) { voxgi_voxels_destroy(ctx, vox); return r; }
    vox->info.ms = voxgi__now_ms() - t0;
    *out = vox;
    return VOXGI_OK;
}

VOXGI_API void voxgi_voxels_destroy(voxgi_context *ctx, voxgi_voxels *v)
{
    if (!ctx || !v) return;
#ifndef VOXGI_NO_GL
    if (v->gl_buffer) voxgi__gl_delete_buffer(ctx, v->gl_buffer);
#endif
    voxgi__free(ctx, v->bits);
    voxgi__attr_free(ctx, &v->attr);
    voxgi__free(ctx, v);
}

VOXGI_API voxgi_result voxgi_voxels_read(voxgi_context *ctx, const voxgi_voxels *v, uint32_t *dst, size_t dst_bytes,
                                         size_t *needed)
{
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!v) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "voxels is NULL");
    if (needed) *needed = v->info.bytes;
    if (!dst) return needed ? VOXGI_OK : voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "dst and needed are both NULL");
    if (dst_bytes < v->info.bytes)
        return voxgi__fail(ctx, VOXGI_ERR_BUFFER_TOO_SMALL, "the bit grid needs %lu bytes, dst has %lu",
                           (unsigned long)v->info.bytes, (unsigned long)dst_bytes);
    if (v->bits) { memcpy(dst, v->bits, v->info.bytes); return VOXGI_OK; }
#ifndef VOXGI_NO_GL
    if (v->gl_buffer) return voxgi__gl_read_buffer(ctx, v->gl_buffer, dst, v->info.bytes);
#endif
    return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "voxels hold no data");
}

VOXGI_API voxgi_result voxgi_voxels_gl_buffer(voxgi_context *ctx, const voxgi_voxels *v, unsigned int *name)
{
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!v || !name) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "voxels or name is NULL");
    if (!v->gl_buffer) return voxgi__fail(ctx, VOXGI_ERR_UNSUPPORTED, "these voxels live on the CPU, not in a GL buffer");
    *name = v->gl_buffer;
    return VOXGI_OK;
}

/* ----- 5.8 OR mipmaps: GL, then the API */

#ifndef VOXGI_NO_GL

static voxgi_result voxgi__vox_reduce_gl(voxgi_context *ctx, const voxgi_voxels *src, const int f[3], voxgi_voxels *dst)
{
    voxgi__gl *gl = ctx->gl;
    const voxgi_grid *sg = &src->info.grid, *dg = &dst->info.grid;
    unsigned int p, out;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_reduce);
    if (r != VOXGI_OK) return r;
    p = gl->prog_reduce;
    out = voxgi__gl_grid_buffer(ctx, dst->info.bytes);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 0, src->gl_buffer);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 1, out);
    gl->UseProgram(p);
    gl->ProgramUniform3i(p, VOXGI__LOC_u_src_res, sg->res[0], sg->res[1], sg->res[2]);
    gl->ProgramUniform3i(p, VOXGI__LOC_u_dst_res, dg->res[0], dg->res[1], dg->res[2]);
    gl->ProgramUniform3i(p, VOXGI__LOC_u_factor, f[0], f[1], f[2]);
    /* one invocation per destination line along x, in work-group slices */
    gl->DispatchCompute((unsigned)(((uint64_t)dg->res[1] * (uint64_t)dg->res[2] + 63) / 64), 1, 1);
    gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT);
    voxgi__gl_unbind(gl);
    dst->gl_buffer = out;
    r = voxgi__gl_check(ctx, "the OR reduction");
    if (r == VOXGI_OK) r = voxgi__vox_count_gl(ctx, out, dst->info.bytes / 4, &dst->info.voxel_count);
    return r;
}
#endif /* VOXGI_NO_GL */

VOXGI_API voxgi_result voxgi_voxels_reduce(voxgi_context *ctx, const voxgi_voxels *src, const int factor[3], voxgi_voxels **out)
{
    voxgi_voxels *dst;
    const voxgi_grid *sg;
    voxgi_result r = VOXGI_OK;
    double t0 = voxgi__now_ms();
    int a;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!src || !factor || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "src, factor or out is NULL");
    *out = NULL;
    for (a = 0; a < 3; a++)
        if (factor[a] != 1 && factor[a] != 2) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "reduction factors are 1 or 2");
    dst = (voxgi_voxels *)voxgi__alloc_array(ctx, 1, sizeof *dst, 1);
    if (!dst) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the result");
    sg = &src->info.grid;
    dst->info = src->info;
    dst->info.exact_tests = dst->info.exact_triangles = 0;
    for (a = 0; a < 3; a++) dst->info.grid.res[a] = (sg->res[a] + factor[a] - 1) / factor[a];
    if (factor[0] == 2 && factor[1] == 2 && factor[2] == 2) dst->info.grid.voxel_size = 2 * sg->voxel_size;
    dst->info.bytes = (size_t)(voxgi__grid_words(&dst->info.grid) * 4u);
    if (src->bits) {
        const voxgi_grid *dg = &dst->info.grid;
        uint64_t i, j, k;
        dst->bits = (uint32_t *)voxgi__alloc_array(ctx, dst->info.bytes / 4, 4, 1);
        if (!dst->bits) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the reduced grid");
        else
            for (k = 0; k < (uint64_t)sg->res[2]; k++)
                for (j = 0; j < (uint64_t)sg->res[1]; j++)
                    for (i = 0; i < (uint64_t)sg->res[0]; i++) {
                        uint64_t l = i + (uint64_t)sg->res[0] * (j + (uint64_t)sg->res[1] * k), d;
                        if (!voxgi_bit_get(src->bits, l)) continue;
                        d = i / (uint64_t)factor[0] + (uint64_t)dg->res[0] * (j / (uint64_t)factor[1] + (uint64_t)dg->res[1] * (k / (uint64_t)factor[2]));
                        dst->bits[d >> 5] |= 1u << (d & 31u);
                    }
        if (r == VOXGI_OK) dst->info.voxel_count = voxgi__vox_count_cpu(dst->bits, dst->info.bytes / 4);
    }
#ifndef VOXGI_NO_GL
    else r = voxgi__vox_reduce_gl(ctx, src, factor, dst);
#endif
    if (r != VOXGI_OK) { voxgi_voxels_destroy(ctx, dst); return r; }
    dst->info.ms = voxgi__now_ms() - t0;
    *out = dst;
    return VOXGI_OK;
}

/* ----- segments through the voxels: 3D-DDA and hierarchical traversal of the OR mipmaps (voxel visibility) */

/* A grid's occupancy and its OR mipmaps (level l: ceil(res / 2^l) per axis, cell set when any of
   its voxels is), up to one cell. */
#define VOXGI__MAX_OCC_LEVELS 24
typedef struct voxgi__occupancy {
    int levels;
    int res[VOXGI__MAX_OCC_LEVELS][3];
    uint32_t *bits[VOXGI__MAX_OCC_LEVELS];
} voxgi__occupancy;

static int voxgi__occ_get(const voxgi__occupancy *O, int l, const int64_t c[3])
{
    const int *r = O->res[l];
    return voxgi_bit_get(O->bits[l], (uint64_t)c[0] + (uint64_t)r[0] * ((uint64_t)c[1] + (uint64_t)r[1] * (uint64_t)c[2]));
}

static void voxgi__occ_free(voxgi_context *ctx, voxgi__occupancy *O)
{
    int l;
    for (l = 0; l < O->levels; l++) voxgi__free(ctx, O->bits[l]);
    memset(O, 0, sizeof *O);
}

#if defined(VOXGI__DIRECT_LIGHT) || !defined(VOXGI_NO_LINE_SPACE) /* the images' memory */
/* The occupancy's memory, every level. */
static size_t voxgi__occ_bytes(const voxgi__occupancy *O)
{
    size_t n = 0;
    int l;
    for (l = 0; l < O->levels; l++) n += ((size_t)O->res[l][0] * (size_t)O->res[l][1] * (size_t)O->res[l][2] + 31) / 32 * 4;
    return n;
}
#endif

static voxgi_result voxgi__occ_build(voxgi_context *ctx, const voxgi_voxels *vox, int mips, voxgi__occupancy *O)
{
    const voxgi_grid *g = &vox->info.grid;
    int l, a;
    memset(O, 0, sizeof *O);
    O->levels = 1;
    for (a = 0; a < 3; a++) O->res[0][a] = g->res[a];
    O->bits[0] = (uint32_t *)voxgi__alloc_array(ctx, 1, vox->info.bytes, 0);
    if (!O->bits[0]) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the occupancy");
    if (voxgi_voxels_read(ctx, vox, O->bits[0], vox->info.bytes, NULL) != VOXGI_OK) { voxgi__occ_free(ctx, O); return VOXGI_ERR_GL; }
    while (mips && O->levels < VOXGI__MAX_OCC_LEVELS && (O->res[O->levels - 1][0] > 1 || O->res[O->levels - 1][1] > 1 || O->res[O->levels - 1][2] > 1)) {
        const int *r = O->res[O->levels - 1];
        int *q = O->res[O->levels];
        int64_t c[3], k[3];
        l = O->levels;
        for (a = 0; a < 3; a++) q[a] = (r[a] + 1) / 2;
        O->bits[l] = (uint32_t *)voxgi__alloc_array(ctx, ((size_t)q[0] * (size_t)q[1] * (size_t)q[2] + 31) / 32, 4, 1);
        if (!O->bits[l]) { voxgi__occ_free(ctx, O); return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the occupancy's mips"); }
        O->levels++;
        for (c[2] = 0; c[2] < r[2]; c[2]++) /* each set cell sets its parent */
            for (c[1] = 0; c[1] < r[1]; c[1]++)
                for (c[0] = 0; c[0] < r[0]; c[0]++)
                    if (voxgi__occ_get(O, l - 1, c)) {
                        for (a = 0; a < 3; a++) k[a] = c[a] >> 1;
                        uint64_t at = (uint64_t)k[0] + (uint64_t)q[0] * ((uint64_t)k[1] + (uint64_t)q[1] * (uint64_t)k[2]);
                        O->bits[l][at >> 5] |= 1u << (at & 31u);
                    }
    }
    return VOXGI_OK;
}

/* Where a cell of `size` voxels at integer cell c is left along the segment o + t d (voxel
   units): the exit t and the axis (the lowest on ties). */
static double voxgi__cell_exit(const double o[3], const double d[3], const int64_t c[3], int64_t size, int *axis)
{
    double best = INFINITY;
    int a;
    *axis = 0;
    for (a = 0; a < 3; a++) {
        double t;
        if (d[a] == 0) continue;
        t = ((double)((c[a] + (d[a] > 0)) * size) - o[a]) / d[a];
        if (t < best) { best = t; *axis = a; }
    }
    return best;
}

/* The segment o + t d, t in [0, 1] (voxel units), cut to the grid's box: its t range, or 0. */
static int voxgi__segment_in_grid(const int res[3], const double o[3], const double d[3], double *t0, double *t1)
{
    int a;
    *t0 = 0;
    *t1 = 1;
    for (a = 0; a < 3; a++) {
        if (d[a] == 0) {
            if (!(o[a] >= 0 && o[a] <= res[a])) return 0;
            continue;
        }
        {
            double ta = (0 - o[a]) / d[a], tb = ((double)res[a] - o[a]) / d[a];
            if (ta > tb) { double x = ta; ta = tb; tb = x; }
            *t0 = VOXGI__MAX(*t0, ta);
            *t1 = VOXGI__MIN(*t1, tb);
        }
    }
    return *t0 <= *t1;
}

/* The voxel holding the point at t, each axis clamped into [lo, hi]. */
static void voxgi__voxel_at(const double o[3], const double d[3], double t, const int64_t lo[3], const int64_t hi[3], int64_t v[3])
{
    int a;
    for (a = 0; a < 3; a++) {
        double x = floor(o[a] + t * d[a]);
        v[a] = x < (double)lo[a] ? lo[a] : (x > (double)hi[a] ? hi[a] : (int64_t)x);
    }
}

/* 1 when the segment meets an occupied voxel; visited voxels (DDA) or cells (the hierarchical
   traversal, from the coarsest level: an occupied cell is looked into one level finer, an empty
   one skipped and the next looked at one level coarser) counted into *steps. visit (or NULL):
   each voxel the DDA enters, in order. */
static int voxgi__traverse(const voxgi__occupancy *O, int hierarchical, const double o[3], const double d[3], uint64_t *steps,
                           void (*visit)(void *user, const int64_t v[3]), void *user)
{
    int64_t v[3], lo[3] = {0, 0, 0}, hi[3];
    double t0, t1, t;
    int a, l = hierarchical ? O->levels - 1 : 0;
    for (a = 0; a < 3; a++) hi[a] = O->res[0][a] - 1;
    if (!voxgi__segment_in_grid(O->res[0], o, d, &t0, &t1)) return 0;
    voxgi__voxel_at(o, d, t0, lo, hi, v);
    for (;;) { /* at voxel v, looking at its cell of level l: occupied, finer (or hit at 0); empty, past it and one coarser */
        int64_t cell[3], size = (int64_t)1 << l, clo[3], chi[3];
        int axis;
        ++*steps;
        for (a = 0; a < 3; a++) cell[a] = v[a] >> l;
        if (voxgi__occ_get(O, l, cell)) {
            if (l == 0) {
                if (visit) visit(user, v);
                return 1;
            }
            l--;
            continue;
        }
        if (visit) visit(user, v);
        t = voxgi__cell_exit(o, d, cell, size, &axis);
        if (!(t <= t1)) return 0;
        for (a = 0; a < 3; a++) { /* the next voxel: across the exit plane, inside the cell's extent on the other axes */
            clo[a] = cell[a] * size;
            chi[a] = VOXGI__MIN(clo[a] + size - 1, hi[a]);
        }
        voxgi__voxel_at(o, d, t, clo, chi, v);
        v[axis] = d[axis] > 0 ? (cell[axis] + 1) * size : cell[axis] * size - 1;
        if (v[axis] < 0 || v[axis] > hi[axis]) return 0;
        if (hierarchical && l < O->levels - 1) l++;
    }
}

VOXGI_API voxgi_result voxgi_voxels_occluded(voxgi_context *ctx, const voxgi_voxels *voxels, voxgi_traversal how, size_t count, const float *from,
                                             const float *to, unsigned char *occluded, uint64_t *steps)
{
    voxgi__occupancy O;
    const voxgi_grid *g;
    uint64_t n = 0;
    size_t i;
    int a;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!voxels || (count && (!from || !to || !occluded))) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "voxels, from, to or occluded is NULL");
    if (how != VOXGI_TRAVERSAL_DDA && how != VOXGI_TRAVERSAL_HIERARCHICAL) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "traversal %d", (int)how);
    for (i = 0; i < 3 * count; i++)
        if (!isfinite(from[i]) || !isfinite(to[i])) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "segment %lu is not finite", (unsigned long)(i / 3));
    if ((r = voxgi__occ_build(ctx, voxels, how == VOXGI_TRAVERSAL_HIERARCHICAL, &O)) != VOXGI_OK) return r;
    g = &voxels->info.grid;
    for (i = 0; i < count; i++) {
        double o[3], d[3];
        for (a = 0; a < 3; a++) {
            o[a] = ((double)from[3 * i + (size_t)a] - g->origin[a]) / g->voxel_size;
            d[a] = ((double)to[3 * i + (size_t)a] - g->origin[a]) / g->voxel_size - o[a];
        }
        occluded[i] = (unsigned char)voxgi__traverse(&O, how == VOXGI_TRAVERSAL_HIERARCHICAL, o, d, &n, NULL, NULL);
    }
    voxgi__occ_free(ctx, &O);
    if (steps) *steps = n;
    return VOXGI_OK;
}

#if !defined(VOXGI_NO_GL) && (!defined(VOXGI_NO_LIGHT_SPACE) || !defined(VOXGI_NO_SCREEN_SPACE)) /* their gathers on GL */
/* The occupancy for the GL traversal (shaders/voxel_traverse.glsl): every level's words one
   after another in *bits, and per level its cells per axis and first word in *levels. */
static void voxgi__occ_upload(voxgi_context *ctx, const voxgi__occupancy *O, unsigned int *bits, unsigned int *levels)
{
    uint32_t info[4 * VOXGI__MAX_OCC_LEVELS];
    size_t words = 0, n[VOXGI__MAX_OCC_LEVELS];
    int l;
    for (l = 0; l < O->levels; l++) {
        info[4 * l] = (uint32_t)O->res[l][0];
        info[4 * l + 1] = (uint32_t)O->res[l][1];
        info[4 * l + 2] = (uint32_t)O->res[l][2];
        info[4 * l + 3] = (uint32_t)words;
        n[l] = ((size_t)O->res[l][0] * (size_t)O->res[l][1] * (size_t)O->res[l][2] + 31) / 32;
        words += n[l];
    }
    *bits = voxgi__gl_buffer(ctx, words * 4, NULL);
    for (l = 0; l < O->levels; l++) ctx->gl->NamedBufferSubData(*bits, (ptrdiff_t)(info[4 * l + 3] * 4u), (ptrdiff_t)(n[l] * 4), O->bits[l]);
    *levels = voxgi__gl_buffer(ctx, (size_t)O->levels * 16, info);
}

/* Runs `program` (bound by the caller, with its buffers) over count points in batches of 2^20
   (u_first, u_count). */
static void voxgi__gl_dispatch_points(voxgi__gl *gl, unsigned int program, size_t count)
{
    size_t first;
    for (first = 0; first < count; first += (size_t)1 << 20) {
        size_t n = VOXGI__MIN(count - first, (size_t)1 << 20);
        gl->ProgramUniform1ui(program, VOXGI__LOC_u_first, (unsigned)first);
        gl->ProgramUniform1ui(program, VOXGI__LOC_u_count, (unsigned)n);
        voxgi__gl_dispatch_items(gl, (uint64_t)n);
    }
}
#endif


/* ===================================================================== 6. volumes and mips */

/* attribute volumes and mipmaps
   CPU: float arrays, level after level; GL: 3D textures whose base level is uploaded from the
   same dense data and whose levels a compute pass builds (shaders/volume_mip.glsl) with the same
   formulas in float, so the two agree to float rounding. */
#define VOXGI__MAX_LEVELS 17

#define VOXGI__VOLUME_SLOTS 7 /* the four voxel attributes, the radiance of either side, and the side */
#define VOXGI__RADIANCE_SLOT 4 /* voxgi__attr_index(VOXGI_ATTRIBUTE_RADIANCE) */
#define VOXGI__BACK_SLOT 5
#define VOXGI__SIDE_SLOT 6
#define VOXGI__RADIANCE_FAMILY ((unsigned)(VOXGI_ATTRIBUTE_RADIANCE | VOXGI_ATTRIBUTE_RADIANCE_BACK | VOXGI_ATTRIBUTE_RADIANCE_SIDE))
struct voxgi_volume {
    voxgi_volume_info info;
    int dims[VOXGI__MAX_LEVELS][3];
    size_t first[VOXGI__MAX_LEVELS];   /* voxel offset of each level in a CPU array */
    size_t voxels;                     /* all levels */
    float *cpu[VOXGI__VOLUME_SLOTS][6]; /* [attribute bit][direction]: direction 0 every level, the others (anisotropic)
                                           levels 1.. only: level 0 is the same in every direction and kept once */
    unsigned int tex[VOXGI__VOLUME_SLOTS][6];
    uint32_t *regions;                 /* two-sided radiance: the empty space's regions, level after level, */
    uint32_t *region_boxes;            /* and their bounds (voxgi__volume_regions) */
    size_t region_count;               /* labels, 0 and OPEN included */
    unsigned int region_buffer;        /* GL: both in one storage buffer */
    int regions_given;                 /* taken from the volume of the light before the bounces (voxgi__volume_take_regions) */
};

static int voxgi__attr_index(voxgi_attribute a)
{
    return a == VOXGI_ATTRIBUTE_ALBEDO ? 0 : (a == VOXGI_ATTRIBUTE_NORMAL ? 1 : (a == VOXGI_ATTRIBUTE_EMISSION ? 2 :
           (a == VOXGI_ATTRIBUTE_OPACITY ? 3 : (a == VOXGI_ATTRIBUTE_RADIANCE ? 4 : (a == VOXGI_ATTRIBUTE_RADIANCE_BACK ? 5 :
           (a == VOXGI_ATTRIBUTE_RADIANCE_SIDE ? 6 : -1))))));
}

/* Directions slot a is kept in: six for an anisotropic volume's, one for the side's. */
static int voxgi__slot_dirs(const voxgi_volume *vol, int a)
{
    return vol->info.filter == VOXGI_MIPS_ANISOTROPIC && a != VOXGI__SIDE_SLOT ? 6 : 1;
}

/* Level k of attribute slot a, direction d, of a CPU volume. */
static float *voxgi__volume_level(const voxgi_volume *vol, int a, int d, int k)
{
    size_t w = a == 3 ? 1u : 4u;
    return k == 0 || d == 0 ? vol->cpu[a][0] + vol->first[k] * w : vol->cpu[a][d] + (vol->first[k] - vol->first[1]) * w;
}

/* A parent's value from its 8 children c[k] (k = x + 2y + 4z; alpha in c[k][3]); dir < 0:
   isotropic, else anisotropic along dir; w: floats per voxel stored (4, or 1 for alpha alone).
   premultiplied: the values are stored multiplied by alpha (RADIANCE); the same filter, without
   the division and multiplication by alpha. */
static void voxgi__mip_combine(float c[8][4], int w, int dir, int premultiplied, float *dst)
{
    float asum = 0, vsum[3] = {0, 0, 0}, pairs = 8;
    int k, ch;
    if (dir < 0) { /* isotropic: mean alpha, alpha-weighted value */
        for (k = 0; k < 8; k++) {
            asum += c[k][3];
            for (ch = 0; ch < 3; ch++) vsum[ch] += premultiplied ? c[k][ch] : c[k][ch] * c[k][3];
        }
    } else { /* anisotropic: the four pairs along the axis, front to back, averaged */
        int bit = 1 << (dir / 2);
        pairs = 0;
        for (k = 0; k < 8; k++) {
            const float *nr, *fr;
            if (k & bit) continue;
            nr = (dir & 1) ? c[k | bit] : c[k]; /* +dir travels from low to high */
            fr = (dir & 1) ? c[k] : c[k | bit];
            asum += nr[3] + (1 - nr[3]) * fr[3];
            for (ch = 0; ch < 3; ch++) vsum[ch] += premultiplied ? nr[ch] + (1 - nr[3]) * fr[ch] : nr[ch] * nr[3] + (1 - nr[3]) * fr[ch] * fr[3];
            pairs += 1;
        }
    }
    if (w == 1) { dst[0] = asum / pairs; return; }
    for (ch = 0; ch < 3; ch++) dst[ch] = premultiplied ? vsum[ch] / pairs : (asum > 0 ? vsum[ch] / asum : 0);
    dst[3] = asum / pairs;
}

/* Loads one stored voxel (w floats) as (value, alpha). */
static void voxgi__mip_load(const float *s, int w, float c[4])
{
    int ch;
    for (ch = 0; ch < 4; ch++) c[ch] = 0;
    if (!s) return;
    if (w == 1) c[3] = s[0];
    else for (ch = 0; ch < 4; ch++) c[ch] = s[ch];
}

/* Parent p of level l from level l - 1 of the same direction's array; w: floats per voxel (4 or 1).
   dir -2: all six directions at once from a level 0 they share, into dst6[0..5]. Empty children
   give an empty parent without the filter. */
static void voxgi__mip_voxel(const float *src, const int sd[3], float *dst, float *const *dst6, int w, int dir, int premultiplied, const int p[3])
{
    float c[8][4];
    int k, any = 0;
    for (k = 0; k < 8; k++) { /* children in x-fastest order; beyond the grid: empty */
        int v[3], a;
        v[0] = 2 * p[0] + (k & 1); v[1] = 2 * p[1] + ((k >> 1) & 1); v[2] = 2 * p[2] + ((k >> 2) & 1);
        for (a = 0; a < 3 && v[a] < sd[a]; a++) {}
        voxgi__mip_load(a == 3 ? src + ((size_t)v[0] + (size_t)sd[0] * ((size_t)v[1] + (size_t)sd[1] * (size_t)v[2])) * (size_t)w : NULL, w, c[k]);
        any |= c[k][0] != 0 || c[k][1] != 0 || c[k][2] != 0 || c[k][3] != 0;
    }
    if (!any) return; /* the levels start zeroed: empty space stays untouched (and, from calloc, unpaged) */
    if (dir != -2) {
        voxgi__mip_combine(c, w, dir, premultiplied, dst);
        return;
    }
    for (k = 0; k < 6; k++) voxgi__mip_combine(c, w, k, premultiplied, dst6[k]);
}

/* Level 0 of every asked-for attribute, dense, from the voxels' bits and attribute means. */
static voxgi_result voxgi__volume_base(voxgi_context *ctx, const voxgi_voxels *vx, voxgi_volume *vol, float *base[VOXGI__VOLUME_SLOTS])
{
    const voxgi_grid *g = &vx->info.grid;
    uint64_t n = voxgi_grid_voxel_count(g), l, slot = 0;
    size_t need = 0;
    uint32_t *bits = NULL;
    float *vals[4] = {NULL, NULL, NULL, NULL};
    int a;
    voxgi_result r = voxgi_voxels_read(ctx, vx, NULL, 0, &need);
    if (r == VOXGI_OK && !(bits = (uint32_t *)voxgi__alloc(ctx, need))) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the bits");
    if (r == VOXGI_OK) r = voxgi_voxels_read(ctx, vx, bits, need, NULL);
    for (a = 0; a < 4 && r == VOXGI_OK; a++) {
        voxgi_attribute which = (voxgi_attribute)(1 << a);
        if (!(vx->info.attributes & (unsigned)which) || (a < 3 && !(vol->info.attributes & (unsigned)which))) continue;
        r = voxgi_voxels_read_attribute(ctx, vx, which, NULL, 0, &need);
        if (r == VOXGI_OK && !(vals[a] = (float *)voxgi__alloc(ctx, need ? need : 4))) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory");
        if (r == VOXGI_OK) r = voxgi_voxels_read_attribute(ctx, vx, which, vals[a], need, NULL);
    }
    for (l = 0; r == VOXGI_OK && l < n; l++) {
        float alpha;
        if (!voxgi_bit_get(bits, l)) continue;
        alpha = vals[3] ? vals[3][slot] : 1.0f;
        for (a = 0; a < 4; a++) {
            float *o;
            if (!base[a]) continue;
            if (a == 3) { base[3][l] = alpha; continue; }
            o = base[a] + 4 * l;
            o[0] = vals[a][3 * slot];
            o[1] = vals[a][3 * slot + 1];
            o[2] = vals[a][3 * slot + 2];
            o[3] = alpha;
        }
        slot++;
    }
    voxgi__free(ctx, bits);
    for (a = 0; a < 4; a++) voxgi__free(ctx, vals[a]);
    return r;
}

/* A volume's level sizes down to one voxel or `levels` levels (0: all): their count, vol->dims,
   vol->first and vol->voxels set. */
static int voxgi__volume_levels(voxgi_volume *vol, const voxgi_grid *g, int levels)
{
    int a, k, count = 0;
    vol->voxels = 0;
    for (k = 0; k < VOXGI__MAX_LEVELS; k++) { /* the chain down to one voxel, or as asked */
        for (a = 0; a < 3; a++) vol->dims[k][a] = k ? (vol->dims[k - 1][a] + 1) / 2 : g->res[a];
        vol->first[k] = vol->voxels;
        vol->voxels += (size_t)vol->dims[k][0] * (size_t)vol->dims[k][1] * (size_t)vol->dims[k][2];
        count = k + 1;
        if ((levels && k + 1 == levels) || (vol->dims[k][0] == 1 && vol->dims[k][1] == 1 && vol->dims[k][2] == 1)) break;
    }
    return count;
}

/* The bytes of a volume's values (vol's levels, filter and attributes set) on the CPU (level 0
   once, the mips per direction) or on GL (a full texture per direction): what voxgi_volume_info
   reports, before a two-sided radiance volume's regions. */
static uint64_t voxgi__volume_bytes(const voxgi_volume *vol, int gl)
{
    size_t base_voxels = (size_t)vol->dims[0][0] * (size_t)vol->dims[0][1] * (size_t)vol->dims[0][2];
    uint64_t bytes = 0;
    int a;
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++)
        if (vol->info.attributes & (1u << a)) {
            uint64_t dirs = (uint64_t)voxgi__slot_dirs(vol, a);
            bytes += ((uint64_t)vol->voxels * (gl ? dirs : 1u) + (gl ? 0u : (dirs - 1) * (vol->voxels - base_voxels))) * (a == 3 ? 4u : 16u);
        }
    return bytes;
}

/* The volume's levels and sizes, for `attributes` (already checked). */
static voxgi_result voxgi__volume_new(voxgi_context *ctx, const voxgi_grid *g, const voxgi_volume_desc *desc, unsigned attributes,
                                      voxgi_volume **out)
{
    voxgi_volume *vol;
    uint64_t bytes;
    *out = NULL;
    if ((unsigned)desc->filter > VOXGI_MIPS_ANISOTROPIC || desc->levels < 0 || desc->levels > VOXGI__MAX_LEVELS)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "unknown mip filter %d or levels %d", (int)desc->filter, desc->levels);
    if (!attributes || (attributes & ~127u)) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "attributes 0x%x", attributes);
    vol = (voxgi_volume *)voxgi__alloc_array(ctx, 1, sizeof *vol, 1);
    if (!vol) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the volume");
    vol->info.grid = *g;
    vol->info.backend = ctx->backend;
    vol->info.attributes = attributes;
    vol->info.filter = desc->filter;
    vol->info.levels = voxgi__volume_levels(vol, g, desc->levels);
    bytes = voxgi__volume_bytes(vol, ctx->backend == VOXGI_BACKEND_GL);
    vol->info.bytes = (size_t)bytes;
    if (ctx->desc.memory_budget && bytes > (uint64_t)ctx->desc.memory_budget) {
        voxgi__free(ctx, vol);
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "the volumes need %llu bytes, more than the memory budget %llu",
                           (unsigned long long)bytes, (unsigned long long)ctx->desc.memory_budget);
    }
    *out = vol;
    return VOXGI_OK;
}

typedef struct voxgi__mip_job { const voxgi_volume *vol; const float *src; float *dst, *dst6[6]; int w, dir, premultiplied, k; } voxgi__mip_job;

/* Rows [first, end) (y + dims.y z) of level k from level k - 1. */
static void voxgi__mip_rows(void *user, size_t first, size_t end)
{
    const voxgi__mip_job *M = (const voxgi__mip_job *)user;
    const int *dk = M->vol->dims[M->k];
    size_t row;
    for (row = first; row < end; row++) {
        int p[3];
        p[1] = (int)(row % (size_t)dk[1]);
        p[2] = (int)(row / (size_t)dk[1]);
        for (p[0] = 0; p[0] < dk[0]; p[0]++) {
            size_t at = ((size_t)p[0] + (size_t)dk[0] * row) * (size_t)M->w;
            float *dst6[6];
            int d;
            for (d = 0; d < 6 && M->dir == -2; d++) dst6[d] = M->dst6[d] + at;
            voxgi__mip_voxel(M->src, M->vol->dims[M->k - 1], M->dst ? M->dst + at : NULL, dst6, M->w, M->dir, M->premultiplied, p);
        }
    }
}

/* Every level of every volume from the dense base levels (each level's rows on the workers). */
/* regions of empty space
   A two-sided radiance volume also labels the empty voxels of level 0 by the region they
   belong to (6-connected; the surfaces' voxels separate them): VOXGI__REGION_OPEN for every
   region that reaches the grid's faces, 2, 3, ... for the enclosed ones, 0 on the surfaces.
   Nothing outside an enclosed region reaches a point in it but through what lies inside it, so a
   cone from there ends where it enters a region that is not inside its own, and samples no level
   whose voxels reach into one (voxgi__cone_march). Region b lies inside region a when a is open
   or b's bounds (level-0 voxels) lie within a's: a pocket such as a closed box on a room's floor
   lies inside the room, the room not inside the box. A surface's voxel of level 0 belongs to the
   region its light goes into: each side's is that of the first empty voxel along the side's
   normal (voxgi__regions_of_sides; where that normal runs along other surfaces' voxels, the one
   lit region ahead of the side, voxgi__region_lit_ahead), and a region is lit where a side with
   light goes into it from a voxel beside it. A voxel whose lit sides' regions are one region holds VOXGI__REGION_BORDER |
   that region, and VOXGI__REGION_UNSEEN besides where it does not border it (the outer of two
   voxels a wall on a voxel boundary fills, the outer layer of a curved shell); where a side's
   region is unknown, the one lit region it borders (the ground beside a box's corner). A cone
   from another region, not outside it, leaves it out of its samples of level 0, and an unseen
   voxel from every region. Level k > 0 holds its children's outermost region where one holds all
   the others (a surface's voxel counting as its region), VOXGI__REGION_MIXED where none does, 0
   where they have none: a cone keeps within its enclosure whether light lies beyond it or not
   (through a closed sphere's shell, mips that reached the dark outside lost light a bounce). The
   labels come from the direct light and serve every bounce (voxgi__volume_take_regions): a
   closed region is lit only by what its surfaces receive directly. They, then each enclosed
   region's bounds (6 per label, from label 0), are kept while they fit the storage buffer every
   GL 4.5 has (2^27 bytes: a 300^3 grid), on both backends alike. */
#define VOXGI__REGION_OPEN 1u
#define VOXGI__REGION_MIXED 0xFFFFFFFFu
#define VOXGI__REGION_BORDER 0x80000000u
#define VOXGI__REGION_UNSEEN 0x20000000u
#define VOXGI__REGION_OF(label) ((label) & ~(VOXGI__REGION_BORDER | VOXGI__REGION_UNSEEN))
#define VOXGI__REGION_BYTES ((size_t)1 << 27)

/* Whether region b lies inside region a (box: the bounds, 6 per label). */
static int voxgi__region_inside(const uint32_t *box, uint32_t a, uint32_t b)
{
    const uint32_t *pa = box + 6 * (size_t)a, *pb = box + 6 * (size_t)b;
    if (a == VOXGI__REGION_OPEN) return 1;
    if (b == VOXGI__REGION_OPEN || a == VOXGI__REGION_MIXED || b == VOXGI__REGION_MIXED) return 0;
    return pb[0] >= pa[0] && pb[1] >= pa[1] && pb[2] >= pa[2] && pb[3] <= pa[3] && pb[4] <= pa[4] && pb[5] <= pa[5];
}

/* The root of provisional label l (union-find, halving the path as it goes). */
static uint32_t voxgi__region_root(uint32_t *parent, uint32_t l)
{
    while (parent[l] != l) l = parent[l] = parent[parent[l]];
    return l;
}

/* One region of the two labels' (the smaller root holds both); that root. */
static uint32_t voxgi__region_unite(uint32_t *parent, uint32_t a, uint32_t b)
{
    a = voxgi__region_root(parent, a);
    b = voxgi__region_root(parent, b);
    if (a < b) parent[b] = a;
    else parent[a] = b;
    return a < b ? a : b;
}

/* The region of the first empty voxel from the centre of voxel c along unit n (level-0 labels
   lab of a grid of dm voxels), within four voxels; 0 where n leaves the grid first, MIXED where
   there is none. */
static uint32_t voxgi__region_along(const int *dm, const uint32_t *lab, const int c[3], const double n[3])
{
    int s, a;
    for (s = 0; s < 5; s++) {
        double t = s ? 0.5 + (double)s : 0.8660254037844386;
        int v[3], ok = 1;
        uint32_t r;
        for (a = 0; a < 3; a++) {
            v[a] = (int)floor((double)c[a] + 0.5 + t * n[a]);
            ok = ok && v[a] >= 0 && v[a] < dm[a];
        }
        if (!ok) return 0;
        r = lab[(size_t)v[0] + (size_t)dm[0] * ((size_t)v[1] + (size_t)dm[1] * (size_t)v[2])];
        if (r && !(r & VOXGI__REGION_BORDER)) return r;
    }
    return VOXGI__REGION_MIXED;
}

/* The region each side of surface voxel c (front, back) sends its light into: that of the first
   empty voxel from the centre along the side's normal (voxgi__region_along); MIXED where the
   voxel has no side plane. A wall on a voxel boundary fills two voxels, and the one on the far
   side of the wall from the light holds the light all the same (its lookup point lies across the
   wall): its light is the lit room's, not the room it borders. (side: its RADIANCE_SIDE.) */
static void voxgi__regions_of_sides(const int *dm, const uint32_t *lab, const int c[3], const float *side, uint32_t out[2])
{
    double len = sqrt((double)side[0] * side[0] + (double)side[1] * side[1] + (double)side[2] * side[2]), n[3];
    int sd, a;
    for (sd = 0; sd < 2; sd++) {
        for (a = 0; a < 3; a++) n[a] = len > 0 ? (sd ? -side[a] : side[a]) / len : 0;
        out[sd] = len > 0 ? voxgi__region_along(dm, lab, c, n) : VOXGI__REGION_MIXED;
    }
}

/* Where a side's normal finds no empty voxel (it runs along another wall's voxels, as a long
   wall's does at the foot of a wall meeting it): the one lit region with an empty voxel within
   two voxels of c in front of the side (centre offset . n > 0); 0 where none is lit, MIXED where
   two are. */
static uint32_t voxgi__region_lit_ahead(const int *dm, const uint32_t *lab, const unsigned char *lit, const int c[3], const double n[3])
{
    uint32_t found = 0;
    int e[3];
    for (e[2] = c[2] - 2; e[2] <= c[2] + 2; e[2]++)
        for (e[1] = c[1] - 2; e[1] <= c[1] + 2; e[1]++)
            for (e[0] = c[0] - 2; e[0] <= c[0] + 2; e[0]++) {
                uint32_t r;
                if (e[0] < 0 || e[1] < 0 || e[2] < 0 || e[0] >= dm[0] || e[1] >= dm[1] || e[2] >= dm[2] ||
                    !((e[0] - c[0]) * n[0] + (e[1] - c[1]) * n[1] + (e[2] - c[2]) * n[2] > 0))
                    continue;
                r = lab[(size_t)e[0] + (size_t)dm[0] * ((size_t)e[1] + (size_t)dm[1] * (size_t)e[2])];
                if (r && !(r & VOXGI__REGION_BORDER) && lit[r] && r != found) found = found ? VOXGI__REGION_MIXED : r;
            }
    return found;
}

/* Whether voxel c has an empty neighbour (of six) in region r. */
static int voxgi__region_beside(const int *dm, const uint32_t *lab, const int c[3], uint32_t r)
{
    int q, v[3];
    for (q = 0; q < 6; q++) {
        memcpy(v, c, sizeof v);
        v[q >> 1] += q & 1 ? 1 : -1;
        if (v[q >> 1] >= 0 && v[q >> 1] < dm[q >> 1] && lab[(size_t)v[0] + (size_t)dm[0] * ((size_t)v[1] + (size_t)dm[1] * (size_t)v[2])] == r) return 1;
    }
    return 0;
}

static voxgi_result voxgi__volume_regions(voxgi_context *ctx, voxgi_volume *vol, const float *const base[VOXGI__VOLUME_SLOTS])
{
    const float *radiance0 = base[VOXGI__RADIANCE_SLOT], *back0 = base[VOXGI__BACK_SLOT], *side0 = base[VOXGI__SIDE_SLOT];
    const int *dm = vol->dims[0];
    size_t nx = (size_t)dm[0], nxy = nx * (size_t)dm[1], n = nxy * (size_t)dm[2], i, kept = 2;
    uint32_t *lab, *parent = NULL, *box = NULL, next = 2, l, root_of_l = 0;
    unsigned char *open_flags = NULL, *lit = NULL;
    int x, y, z, k, a, q;
    if (!radiance0 || !back0 || !side0 || vol->voxels > VOXGI__REGION_BYTES / 4) return VOXGI_OK;
    lab = (uint32_t *)voxgi__alloc_array(ctx, vol->voxels, 4, 1);
    parent = (uint32_t *)voxgi__alloc_array(ctx, n + 2, 4, 0);
    open_flags = (unsigned char *)voxgi__alloc_array(ctx, n + 2, 1, 1);
    if (!lab || !parent || !open_flags) goto no_memory;
    for (z = 0, i = 0; z < dm[2]; z++) /* provisional labels in one pass, joined where they meet (-x, -y, -z) */
        for (y = 0; y < dm[1]; y++)
            for (x = 0; x < dm[0]; x++, i++) {
                if (radiance0[4 * i + 3] > 0) continue;
                int left = x > 0 && lab[i - 1] != 0;
                l = left ? lab[i - 1] : 0;
                /* a neighbour whose own -x neighbour is empty was joined to lab[i - 1] through it already */
                if (y > 0 && lab[i - nx] && !(left && lab[i - nx - 1]))
                    l = l ? voxgi__region_unite(parent, l, lab[i - nx]) : lab[i - nx];
                if (z > 0 && lab[i - nxy] && !(left && lab[i - nxy - 1]))
                    l = l ? voxgi__region_unite(parent, l, lab[i - nxy]) : lab[i - nxy];
                if (!l) { l = next++; parent[l] = l; }
                lab[i] = l;
            }
    for (z = 0, i = 0, l = 0; z < dm[2]; z++) /* each voxel its region's root; a region with a voxel on the grid's faces is open */
        for (y = 0; y < dm[1]; y++)
            for (x = 0; x < dm[0]; x++, i++)
                if (lab[i]) {
                    uint32_t root = lab[i] == l ? root_of_l : voxgi__region_root(parent, lab[i]); /* runs share their label */
                    l = lab[i];
                    root_of_l = lab[i] = root;
                    if (x == 0 || x + 1 == dm[0] || y == 0 || y + 1 == dm[1] || z == 0 || z + 1 == dm[2]) open_flags[lab[i]] = 1;
                }
    for (l = 2; l < next; l++) /* the roots renumbered, in the order the scan met them: open 1, enclosed 2, 3, ... */
        if (parent[l] == l) parent[l] = open_flags[l] ? VOXGI__REGION_OPEN : (uint32_t)kept++;
    voxgi__free(ctx, open_flags);
    open_flags = NULL;
    if (kept == 2 || (vol->voxels + 6 * kept) * 4 > VOXGI__REGION_BYTES) { /* nothing enclosed (the cones need no labels), or too big */
        voxgi__free(ctx, lab);
        voxgi__free(ctx, parent);
        return VOXGI_OK;
    }
    if (!(box = (uint32_t *)voxgi__alloc_array(ctx, 6 * kept, 4, 0)) || !(lit = (unsigned char *)voxgi__alloc_array(ctx, kept, 1, 1))) goto no_memory;
    for (i = 0; i < kept; i++)
        for (a = 0; a < 3; a++) { box[6 * i + (size_t)a] = UINT32_MAX; box[6 * i + 3 + (size_t)a] = 0; }
    for (z = 0, i = 0; z < dm[2]; z++) /* the final labels and the enclosed regions' bounds */
        for (y = 0; y < dm[1]; y++)
            for (x = 0; x < dm[0]; x++, i++) {
                uint32_t v[3];
                if (!lab[i]) continue;
                l = lab[i] = parent[lab[i]];
                v[0] = (uint32_t)x; v[1] = (uint32_t)y; v[2] = (uint32_t)z;
                for (a = 0; a < 3; a++) {
                    box[6 * l + (size_t)a] = VOXGI__MIN(box[6 * l + (size_t)a], v[a]);
                    box[6 * l + 3 + (size_t)a] = VOXGI__MAX(box[6 * l + 3 + (size_t)a], v[a]);
                }
            }
    voxgi__free(ctx, parent);
    parent = NULL;
    for (k = 0; k < 2; k++) /* 0: the regions the surfaces light; 1: a surface's voxel whose light goes into one lit region takes it, marked
                               (voxgi__regions_of_sides; where that is unknown, one lit region beside it alone) */
        for (z = 0, i = 0; z < dm[2]; z++)
            for (y = 0; y < dm[1]; y++)
                for (x = 0; x < dm[0]; x++, i++) {
                    int c[3];
                    uint32_t sides[2], only = 0;
                    if (lab[i] || !(radiance0[4 * i + 3] > 0)) continue;
                    c[0] = x; c[1] = y; c[2] = z;
                    voxgi__regions_of_sides(dm, lab, c, side0 + 4 * i, sides);
                    for (q = 0; k == 1 && q < 2; q++)
                        if (sides[q] == VOXGI__REGION_MIXED && (side0[4 * i] != 0 || side0[4 * i + 1] != 0 || side0[4 * i + 2] != 0)) {
                            double n[3];
                            for (a = 0; a < 3; a++) n[a] = q ? -side0[4 * i + (size_t)a] : side0[4 * i + (size_t)a];
                            sides[q] = voxgi__region_lit_ahead(dm, lab, lit, c, n);
                        }
                    if (sides[0] != VOXGI__REGION_MIXED && sides[1] != VOXGI__REGION_MIXED) { /* where each side's light goes is known */
                        uint32_t into = 0;
                        for (q = 0; q < 2; q++) {
                            const float *l = (q ? back0 : radiance0) + 4 * i;
                            if (k == 0 && sides[q] && (l[0] > 0 || l[1] > 0 || l[2] > 0) && voxgi__region_beside(dm, lab, c, sides[q])) lit[sides[q]] = 1;
                            if (k == 1 && sides[q] && lit[sides[q]]) into = !into || into == sides[q] ? sides[q] : VOXGI__REGION_MIXED;
                        }
                        if (k == 0) continue;
                        if (into) {
                            if (into != VOXGI__REGION_MIXED)
                                lab[i] = VOXGI__REGION_BORDER | into | (voxgi__region_beside(dm, lab, c, into) ? 0u : VOXGI__REGION_UNSEEN);
                            continue;
                        }
                    }
                    for (q = 0; q < 6; q++) { /* else: the regions beside it (a corner's ground, below a wall) */
                        int ax = q >> 1, up = q & 1;
                        size_t j = ax == 0 ? 1 : (ax == 1 ? nx : nxy);
                        float facing = up ? side0[4 * i + (size_t)ax] : -side0[4 * i + (size_t)ax];
                        const float *rad = facing > 0 ? radiance0 : back0;
                        if (up ? c[ax] + 1 == dm[ax] : c[ax] == 0) continue;
                        j = up ? i + j : i - j;
                        if (!lab[j] || (lab[j] & VOXGI__REGION_BORDER)) continue;
                        if (k == 0 && !lit[lab[j]] && facing != 0) /* by the side facing it; a neighbour along the surface is on neither */
                            lit[lab[j]] = rad[4 * i] > 0 || rad[4 * i + 1] > 0 || rad[4 * i + 2] > 0;
                        if (k == 1 && lit[lab[j]] && lab[j] != only) only = only ? VOXGI__REGION_MIXED : lab[j];
                    }
                    if (k == 1 && only && only != VOXGI__REGION_MIXED) lab[i] = VOXGI__REGION_BORDER | only;
                }
    for (k = 1; k < vol->info.levels; k++) { /* each level from its children: the outermost region */
        const int *pd = vol->dims[k - 1], *cd = vol->dims[k];
        const uint32_t *src = lab + vol->first[k - 1];
        uint32_t *dst = lab + vol->first[k];
        int c;
        for (z = 0; z < cd[2]; z++)
            for (y = 0; y < cd[1]; y++)
                for (x = 0; x < cd[0]; x++) {
                    uint32_t v = 0;
                    for (c = 0; c < 8; c++) {
                        int cx = 2 * x + (c & 1), cy = 2 * y + (c >> 1 & 1), cz = 2 * z + (c >> 2);
                        uint32_t w;
                        if (cx >= pd[0] || cy >= pd[1] || cz >= pd[2]) continue;
                        w = src[(size_t)cx + (size_t)pd[0] * ((size_t)cy + (size_t)pd[1] * (size_t)cz)];
                        if (k == 1) w = w & VOXGI__REGION_BORDER ? VOXGI__REGION_OF(w) : w; /* a surface's light is its region's */
                        if (!w || w == v) continue;
                        v = !v || voxgi__region_inside(box, w, v) ? w : (voxgi__region_inside(box, v, w) ? v : VOXGI__REGION_MIXED);
                    }
                    dst[(size_t)x + (size_t)cd[0] * ((size_t)y + (size_t)cd[1] * (size_t)z)] = v;
                }
    }
    vol->regions = lab;
    vol->region_boxes = box;
    voxgi__free(ctx, lit);
    vol->region_count = kept;
    vol->info.bytes += (vol->voxels + 6 * kept) * 4;
    return VOXGI_OK;
no_memory:
    voxgi__free(ctx, lab);
    voxgi__free(ctx, parent);
    voxgi__free(ctx, open_flags);
    voxgi__free(ctx, box);
    voxgi__free(ctx, lit);
    return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the regions of %lu voxels", (unsigned long)n);
}

/* CPU: the base level copied into each direction's chain, then each level from the one below. */
static voxgi_result voxgi__volume_build_cpu(voxgi_context *ctx, voxgi_volume *vol, const float *const base[VOXGI__VOLUME_SLOTS])
{
    voxgi_result r = VOXGI_OK;
    int a, d, k;
    size_t base_voxels = (size_t)vol->dims[0][0] * (size_t)vol->dims[0][1] * (size_t)vol->dims[0][2];
    for (a = 0; a < VOXGI__VOLUME_SLOTS && r == VOXGI_OK; a++) {
        int w = a == 3 ? 1 : 4, dirs = voxgi__slot_dirs(vol, a);
        voxgi__mip_job M;
        if (!base[a]) continue;
        memset(&M, 0, sizeof M);
        M.vol = vol;
        M.w = w;
        M.premultiplied = a >= VOXGI__RADIANCE_SLOT;
        for (d = 0; d < dirs && r == VOXGI_OK; d++) {
            size_t held = d ? vol->voxels - base_voxels : vol->voxels; /* every voxel of every level it holds is written */
            float *arr = !d && vol->cpu[a][0] ? vol->cpu[a][0] : (float *)voxgi__alloc_array(ctx, held ? held : 1, (size_t)w * 4, 1); /* zeroed (mip_voxel) */
            if (!arr) { r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the mip chain"); break; }
            vol->cpu[a][d] = arr;
            if (!d && base[a] != arr) memcpy(arr, base[a], base_voxels * (size_t)w * 4); /* or the caller wrote level 0 in place */
        }
        if (r == VOXGI_OK && dirs == 6 && vol->info.levels > 1) { /* level 1 of all six directions in one pass over level 0 */
            M.k = 1;
            M.dir = -2;
            M.src = vol->cpu[a][0];
            for (d = 0; d < 6; d++) M.dst6[d] = voxgi__volume_level(vol, a, d, 1);
            voxgi__parallel(ctx, (size_t)vol->dims[1][1] * (size_t)vol->dims[1][2], 16, voxgi__mip_rows, &M);
        }
        for (d = 0; d < dirs && r == VOXGI_OK; d++) {
            M.dir = dirs == 6 ? d : -1;
            for (k = dirs == 6 ? 2 : 1; k < vol->info.levels; k++) {
                M.k = k;
                M.src = voxgi__volume_level(vol, a, d, k - 1);
                M.dst = voxgi__volume_level(vol, a, d, k);
                voxgi__parallel(ctx, (size_t)vol->dims[k][1] * (size_t)vol->dims[k][2], 16, voxgi__mip_rows, &M);
            }
        }
    }
    return r;
}

#ifndef VOXGI_NO_GL

/* GL: the regions' labels and bounds uploaded, the base level into every direction's texture,
   then each level from the one below by shaders/volume_mip.glsl. */
static voxgi_result voxgi__volume_build_gl(voxgi_context *ctx, voxgi_volume *vol, const float *const base[VOXGI__VOLUME_SLOTS])
{
    voxgi__gl *gl = ctx->gl;
    int a, d, k, max3d = 0;
    const float zeros[4] = {0, 0, 0, 0};
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_volume_mip);
    unsigned int p = gl->prog_volume_mip;
    if (vol->regions) { /* the labels, then the bounds, in one buffer; the CPU's copy is not needed */
        size_t labels = vol->voxels * 4, bounds = vol->region_count * 24;
        vol->region_buffer = voxgi__gl_buffer(ctx, labels + bounds, NULL);
        gl->NamedBufferSubData(vol->region_buffer, 0, (ptrdiff_t)labels, vol->regions);
        gl->NamedBufferSubData(vol->region_buffer, (ptrdiff_t)labels, (ptrdiff_t)bounds, vol->region_boxes);
        voxgi__free(ctx, vol->regions);
        voxgi__free(ctx, vol->region_boxes);
        vol->regions = vol->region_boxes = NULL;
    }
    if (r != VOXGI_OK) return r;
    gl->GetIntegerv(VOXGI__GL_MAX_3D_TEXTURE_SIZE, &max3d);
    for (a = 0; a < 3; a++) { /* GL halves sizes rounding down: pad so that its chain holds ours */
        int m = 1 << (vol->info.levels - 1);
        vol->info.gl_size[a] = (vol->dims[0][a] + m - 1) / m * m;
    }
    if (vol->info.gl_size[0] > max3d || vol->info.gl_size[1] > max3d || vol->info.gl_size[2] > max3d)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "a %dx%dx%d volume texture exceeds GL_MAX_3D_TEXTURE_SIZE %d", vol->info.gl_size[0],
                           vol->info.gl_size[1], vol->info.gl_size[2], max3d);
    gl->UseProgram(p);
    for (a = 0; a < VOXGI__VOLUME_SLOTS && r == VOXGI_OK; a++) {
        int dirs = voxgi__slot_dirs(vol, a);
        if (!base[a]) continue;
        for (d = 0; d < dirs; d++) {
            unsigned int t = 0, fmt = a == 3 ? VOXGI__GL_R32F : VOXGI__GL_RGBA32F;
            gl->CreateTextures(VOXGI__GL_TEXTURE_3D, 1, &t);
            vol->tex[a][d] = t;
            gl->TextureStorage3D(t, vol->info.levels, fmt, vol->info.gl_size[0], vol->info.gl_size[1], vol->info.gl_size[2]);
            gl->TextureParameteri(t, VOXGI__GL_TEXTURE_MIN_FILTER, VOXGI__GL_NEAREST);
            gl->TextureParameteri(t, VOXGI__GL_TEXTURE_MAG_FILTER, VOXGI__GL_NEAREST);
            for (k = 0; k < vol->info.levels; k++) gl->ClearTexImage(t, k, a == 3 ? VOXGI__GL_RED : VOXGI__GL_RGBA, VOXGI__GL_FLOAT, zeros);
            gl->TextureParameteri(t, VOXGI__GL_TEXTURE_WRAP_S, VOXGI__GL_CLAMP_TO_BORDER);
            gl->TextureParameteri(t, VOXGI__GL_TEXTURE_WRAP_T, VOXGI__GL_CLAMP_TO_BORDER);
            gl->TextureParameteri(t, VOXGI__GL_TEXTURE_WRAP_R, VOXGI__GL_CLAMP_TO_BORDER);
            gl->TextureParameterfv(t, VOXGI__GL_TEXTURE_BORDER_COLOR, zeros);
            gl->TextureSubImage3D(t, 0, 0, 0, 0, vol->dims[0][0], vol->dims[0][1], vol->dims[0][2], a == 3 ? VOXGI__GL_RED : VOXGI__GL_RGBA,
                                  VOXGI__GL_FLOAT, base[a]);
            gl->ProgramUniform1i(p, VOXGI__LOC_u_single, a == 3);
            gl->ProgramUniform1i(p, VOXGI__LOC_u_dir, dirs == 6 ? d : -1);
            gl->ProgramUniform1i(p, VOXGI__LOC_u_premultiplied, a >= VOXGI__RADIANCE_SLOT);
            for (k = 1; k < vol->info.levels; k++) {
                gl->ProgramUniform3i(p, VOXGI__LOC_u_src_dims, vol->dims[k - 1][0], vol->dims[k - 1][1], vol->dims[k - 1][2]);
                gl->ProgramUniform3i(p, VOXGI__LOC_u_dst_dims, vol->dims[k][0], vol->dims[k][1], vol->dims[k][2]);
                gl->ProgramUniform1i(p, VOXGI__LOC_u_src_level, k - 1);
                gl->BindTextureUnit(0, t);
                gl->BindImageTexture(a == 3 ? 1 : 0, t, k, 1, 0, VOXGI__GL_WRITE_ONLY, fmt);
                gl->DispatchCompute((unsigned)((vol->dims[k][0] + 3) / 4), (unsigned)((vol->dims[k][1] + 3) / 4), (unsigned)((vol->dims[k][2] + 3) / 4));
                gl->MemoryBarrier(VOXGI__GL_TEXTURE_FETCH_BARRIER_BIT | VOXGI__GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            }
        }
    }
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++) /* ready for sampling: trilinear between levels */
        for (d = 0; d < 6; d++)
            if (vol->tex[a][d]) {
                gl->TextureParameteri(vol->tex[a][d], VOXGI__GL_TEXTURE_MIN_FILTER, VOXGI__GL_LINEAR_MIPMAP_LINEAR);
                gl->TextureParameteri(vol->tex[a][d], VOXGI__GL_TEXTURE_MAG_FILTER, VOXGI__GL_LINEAR);
            }
    gl->BindTextureUnit(0, 0);
    gl->BindImageTexture(0, 0, 0, 0, 0, VOXGI__GL_READ_WRITE, VOXGI__GL_RGBA32F);
    gl->BindImageTexture(1, 0, 0, 0, 0, VOXGI__GL_READ_WRITE, VOXGI__GL_R32F);
    voxgi__gl_unbind(gl);
    return voxgi__gl_check(ctx, "the volume mipmaps");
}
#endif /* VOXGI_NO_GL */

/* The regions (two-sided radiance) on the CPU, then the mip chains where the volume lives. */
static voxgi_result voxgi__volume_build(voxgi_context *ctx, voxgi_volume *vol, const float *const base[VOXGI__VOLUME_SLOTS])
{
    voxgi_result r = VOXGI_OK;
    if ((vol->info.attributes & VOXGI_ATTRIBUTE_RADIANCE_SIDE) && !vol->regions_given) r = voxgi__volume_regions(ctx, vol, base);
    if (r != VOXGI_OK) return r;
#ifndef VOXGI_NO_GL
    if (ctx->backend == VOXGI_BACKEND_GL) return voxgi__volume_build_gl(ctx, vol, base);
#endif
    return voxgi__volume_build_cpu(ctx, vol, base);
}

VOXGI_API voxgi_result voxgi_volume_create(voxgi_context *ctx, const voxgi_voxels *vx, const voxgi_volume_desc *desc, voxgi_volume **out)
{
    voxgi_volume *vol = NULL;
    float *base[VOXGI__VOLUME_SLOTS] = {NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    voxgi_result r;
    double t0 = voxgi__now_ms();
    int a;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!vx || !desc || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "voxels, desc or out is NULL");
    *out = NULL;
    if (!vx->info.attributes) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "these voxels hold no attributes (voxgi_voxelize_desc.attributes)");
    if (desc->attributes & ~vx->info.attributes)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "attributes 0x%x asked for, the voxels hold 0x%x", desc->attributes, vx->info.attributes);
    r = voxgi__volume_new(ctx, &vx->info.grid, desc, desc->attributes ? desc->attributes : vx->info.attributes, &vol);
    for (a = 0; a < 4 && r == VOXGI_OK; a++) { /* level 0, dense, on the CPU for both backends */
        if (!(vol->info.attributes & (1u << a))) continue;
        base[a] = (float *)voxgi__alloc_array(ctx, (size_t)voxgi_grid_voxel_count(&vx->info.grid), a == 3 ? 4 : 16, 1);
        if (!base[a]) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for a %dx%dx%d volume", vol->dims[0][0], vol->dims[0][1], vol->dims[0][2]);
    }
    if (r == VOXGI_OK) r = voxgi__volume_base(ctx, vx, vol, base);
    if (r == VOXGI_OK) r = voxgi__volume_build(ctx, vol, (const float *const *)base);
    for (a = 0; a < 4; a++) voxgi__free(ctx, base[a]);
    if (r != VOXGI_OK) { voxgi_volume_destroy(ctx, vol); return r; }
    vol->info.ms = voxgi__now_ms() - t0;
    *out = vol;
    return VOXGI_OK;
}

VOXGI_API voxgi_result voxgi_volume_create_dense(voxgi_context *ctx, const voxgi_grid *grid, const voxgi_volume_desc *desc,
                                                 const float *const base[4], voxgi_volume **out)
{
    voxgi_volume *vol = NULL;
    voxgi_result r;
    double t0 = voxgi__now_ms();
    const float *slots[VOXGI__VOLUME_SLOTS] = {NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    unsigned attributes = 0;
    int a;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!grid || !desc || !base || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "grid, desc, base or out is NULL");
    *out = NULL;
    if ((r = voxgi_validate_grid(ctx, grid)) != VOXGI_OK) return r;
    for (a = 0; a < 4; a++)
        if ((slots[a] = base[a]) != NULL) attributes |= 1u << a;
    r = voxgi__volume_new(ctx, grid, desc, attributes, &vol);
    if (r == VOXGI_OK) r = voxgi__volume_build(ctx, vol, slots);
    if (r != VOXGI_OK) { voxgi_volume_destroy(ctx, vol); return r; }
    vol->info.ms = voxgi__now_ms() - t0;
    *out = vol;
    return VOXGI_OK;
}

VOXGI_API void voxgi_volume_destroy(voxgi_context *ctx, voxgi_volume *vol)
{
    int a, d;
    if (!ctx || !vol) return;
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++)
        for (d = 0; d < 6; d++) {
            voxgi__free(ctx, vol->cpu[a][d]);
#ifndef VOXGI_NO_GL
            if (vol->tex[a][d] && ctx->gl) ctx->gl->DeleteTextures(1, &vol->tex[a][d]);
#endif
        }
    voxgi__free(ctx, vol->regions);
    voxgi__free(ctx, vol->region_boxes);
#ifndef VOXGI_NO_GL
    if (vol->region_buffer && ctx->gl) voxgi__gl_delete_buffer(ctx, vol->region_buffer);
#endif
    voxgi__free(ctx, vol);
}

VOXGI_API void voxgi_volume_query(const voxgi_volume *vol, voxgi_volume_info *out)
{
    if (!out) return;
    if (!vol) { memset(out, 0, sizeof *out); return; }
    *out = vol->info;
}

static voxgi_result voxgi__volume_pick(voxgi_context *ctx, const voxgi_volume *vol, voxgi_attribute which, voxgi_direction dir,
                                       int *a, int *d)
{
    *a = voxgi__attr_index(which);
    *d = (int)dir;
    if (*a < 0 || !(vol->info.attributes & (unsigned)which))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "attribute %d is not in this volume (0x%x)", (int)which, vol->info.attributes);
    if ((unsigned)dir > VOXGI_DIR_NEG_Z || (voxgi__slot_dirs(vol, *a) == 1 && dir != 0))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "direction %d: an isotropic volume and RADIANCE_SIDE have direction 0 only", (int)dir);
    return VOXGI_OK;
}

VOXGI_API voxgi_result voxgi_volume_read(voxgi_context *ctx, const voxgi_volume *vol, voxgi_attribute which, voxgi_direction dir,
                                         int level, float *dst, size_t dst_bytes, size_t *needed)
{
    int a, d;
    size_t bytes;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!vol) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "volume is NULL");
    if ((r = voxgi__volume_pick(ctx, vol, which, dir, &a, &d)) != VOXGI_OK) return r;
    if (level < 0 || level >= vol->info.levels) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "level %d of %d", level, vol->info.levels);
    bytes = (size_t)vol->dims[level][0] * (size_t)vol->dims[level][1] * (size_t)vol->dims[level][2] * (a == 3 ? 4u : 16u);
    if (needed) *needed = bytes;
    if (!dst) return needed ? VOXGI_OK : voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "dst and needed are both NULL");
    if (dst_bytes < bytes) return voxgi__fail(ctx, VOXGI_ERR_BUFFER_TOO_SMALL, "level %d needs %lu bytes, dst has %lu", level, (unsigned long)bytes, (unsigned long)dst_bytes);
    if (vol->cpu[a][0]) { memcpy(dst, voxgi__volume_level(vol, a, d, level), bytes); return VOXGI_OK; }
#ifndef VOXGI_NO_GL
    if (vol->tex[a][d]) {
        ctx->gl->MemoryBarrier(VOXGI__GL_TEXTURE_UPDATE_BARRIER_BIT);
        ctx->gl->GetTextureSubImage(vol->tex[a][d], level, 0, 0, 0, vol->dims[level][0], vol->dims[level][1], vol->dims[level][2],
                                    a == 3 ? VOXGI__GL_RED : VOXGI__GL_RGBA, VOXGI__GL_FLOAT, (int)bytes, dst);
        return voxgi__gl_check(ctx, "reading a volume");
    }
#endif
    return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the volume holds no data");
}

/* Level k's stored value of voxel v into t (w floats); 0 where it is empty or beyond the grid. */
typedef int (*voxgi__fetch_fn)(const void *source, int k, const int v[3], float t[4]);

/* Trilinear sample of level k at p (grid units of level 0) between the voxel centres. */
/* A trilinear sample of level k at p (grid units of level 0): the lowest corner i0 and the
   weights of the 8 corners (corner = x + 2y + 4z), in float. Every CPU trilinear sample takes
   them from here and sums corner by corner in float, so that an octree's samples and a volume's
   are the same bit for bit. */
static void voxgi__corner_weights(const float p[3], int k, int i0[3], float wt[8])
{
    const float scale = 1.0f / (float)(1 << k); /* a power of two: p scaled exactly */
    float f[3], wxy[4];
    int a, corner;
    for (a = 0; a < 3; a++) {
        float c = VOXGI__MIN(VOXGI__MAX(p[a] * scale - 0.5f, -1e9f), 1e9f); /* far outside stays far outside, in int range */
        i0[a] = (int)c - ((float)(int)c > c);                          /* floor */
        f[a] = c - (float)i0[a];
    }
    wxy[0] = (1 - f[0]) * (1 - f[1]);
    wxy[1] = f[0] * (1 - f[1]);
    wxy[2] = (1 - f[0]) * f[1];
    wxy[3] = f[0] * f[1];
    for (corner = 0; corner < 4; corner++) {
        wt[corner] = wxy[corner] * (1 - f[2]);
        wt[corner + 4] = wxy[corner] * f[2];
    }
}

/* The corners' values by their weights: corner c's 4 floats at base + 4 at[c] (none where at[c]
   < 0), summed in one fixed order, pairs and then pairs of pairs (SSE where the compiler targets
   it, else channel by channel in the same arithmetic). Every CPU trilinear sample sums so. */
static VOXGI__HOT_INLINE void voxgi__corner_sum(const float *base, const ptrdiff_t at[8], const float wt[8], float out[4])
{
#ifdef VOXGI__SSE
    __m128 s[8];
    int c;
    for (c = 0; c < 8; c++) s[c] = at[c] < 0 ? _mm_setzero_ps() : _mm_mul_ps(_mm_set1_ps(wt[c]), _mm_loadu_ps(base + 4 * at[c]));
    _mm_storeu_ps(out, _mm_add_ps(_mm_add_ps(_mm_add_ps(s[0], s[1]), _mm_add_ps(s[2], s[3])), _mm_add_ps(_mm_add_ps(s[4], s[5]), _mm_add_ps(s[6], s[7]))));
#else
    float s[8];
    int c, ch;
    for (ch = 0; ch < 4; ch++) {
        for (c = 0; c < 8; c++) s[c] = at[c] < 0 ? 0.0f : wt[c] * base[4 * at[c] + ch];
        out[ch] = ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
    }
#endif
}

static void voxgi__trilinear(voxgi__fetch_fn fetch, const void *source, int w, int k, const float p[3], float out[4])
{
    float wt[8], t[8][4], sum[4];
    ptrdiff_t at[8];
    int i0[3], a, corner, ch;
    voxgi__corner_weights(p, k, i0, wt);
    for (corner = 0; corner < 8; corner++) {
        int c[3];
        for (a = 0; a < 3; a++) c[a] = i0[a] + ((corner >> a) & 1);
        for (ch = 0; ch < 4; ch++) t[corner][ch] = 0;
        at[corner] = wt[corner] != 0 && fetch(source, k, c, t[corner]) ? corner : -1; /* -1: empty */
    }
    voxgi__corner_sum(t[0], at, wt, sum);
    for (ch = 0; ch < 4; ch++) out[ch] = ch < w ? sum[ch] : 0;
}

/* A faster trilinear sample of level k with the same result, or 0 where it cannot tell. */
typedef int (*voxgi__fast_trilinear_fn)(const void *source, int w, int k, const float p[3], float out[4]);

/* Linear between the levels around lod (clamped to 0..levels-1) of trilinear samples. */
static void voxgi__sample_lod(voxgi__fetch_fn fetch, voxgi__fast_trilinear_fn fast, const void *source, int w, int levels, const float p[3],
                              float lod_in, float *out)
{
    float lod = lod_in < 0 ? 0 : (lod_in > (float)(levels - 1) ? (float)(levels - 1) : lod_in), s0[4], s1[4], t;
    int k0 = (int)floor(lod), ch;
    t = lod - (float)k0;
    if (!fast || !fast(source, w, k0, p, s0)) voxgi__trilinear(fetch, source, w, k0, p, s0);
    if (t > 0 && (!fast || !fast(source, w, k0 + 1, p, s1))) voxgi__trilinear(fetch, source, w, k0 + 1, p, s1);
    for (ch = 0; ch < w; ch++) out[ch] = t > 0 ? s0[ch] + t * (s1[ch] - s0[ch]) : s0[ch];
}

VOXGI_API float voxgi_lod_from_footprint(float diameter)
{
    return diameter > 1 ? log2f(diameter) : 0.0f; /* NaN: 0 */
}

typedef struct voxgi__volume_source { const voxgi_volume *vol; int a, d, w; } voxgi__volume_source;

static int voxgi__volume_fetch(const void *source, int k, const int v[3], float t[4])
{
    const voxgi__volume_source *s = (const voxgi__volume_source *)source;
    const int *d = s->vol->dims[k];
    if (v[0] < 0 || v[1] < 0 || v[2] < 0 || v[0] >= d[0] || v[1] >= d[1] || v[2] >= d[2]) return 0;
    memcpy(t, voxgi__volume_level(s->vol, s->a, s->d, k) + ((size_t)v[0] + (size_t)d[0] * ((size_t)v[1] + (size_t)d[1] * (size_t)v[2])) * (size_t)s->w,
           (size_t)s->w * sizeof(float));
    return 1;
}

/* Slot a's direction d of vol at count points (grid units) and levels of detail, trilinear
   within a level and linear between two. */
static void voxgi__volume_sample_cpu(const voxgi_volume *vol, int a, int d, size_t count, const float *pos, const float *lods, float *out)
{
    voxgi__volume_source src;
    size_t i;
    src.vol = vol;
    src.a = a;
    src.d = d;
    src.w = a == 3 ? 1 : 4;
    for (i = 0; i < count; i++)
        voxgi__sample_lod(voxgi__volume_fetch, NULL, &src, src.w, vol->info.levels, pos + 3 * i, lods[i], out + (size_t)src.w * i);
}

#ifndef VOXGI_NO_GL

/* The GLSL sampler over a batch of points (shaders/volume_sample.glsl). */
static voxgi_result voxgi__volume_sample_gl(voxgi_context *ctx, const voxgi_volume *vol, int a, int d, size_t count, const float *pos,
                                            const float *lods, float *out)
{
    voxgi__gl *gl = ctx->gl;
    unsigned int bufs[3], p;
    float *packed;
    size_t i;
    int w = a == 3 ? 1 : 4;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_volume_sample);
    if (r != VOXGI_OK) return r;
    if (!count) return VOXGI_OK;
    if (count > (size_t)65535 * 64 * 64) return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%lu points in one call", (unsigned long)count);
    packed = (float *)voxgi__alloc_array(ctx, count, 4 * sizeof(float), 0);
    if (!packed) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu points", (unsigned long)count);
    for (i = 0; i < count; i++) {
        memcpy(packed + 4 * i, pos + 3 * i, 3 * sizeof(float));
        packed[4 * i + 3] = lods[i];
    }
    bufs[0] = voxgi__gl_buffer(ctx, count * 16, packed);
    bufs[1] = voxgi__gl_buffer(ctx, count * 16, NULL);
    voxgi__free(ctx, packed);
    p = gl->prog_volume_sample;
    gl->UseProgram(p);
    gl->BindTextureUnit(0, vol->tex[a][d]);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 0, bufs[0]);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 1, bufs[1]);
    gl->ProgramUniform1ui(p, VOXGI__LOC_u_count, (unsigned)count);
    gl->ProgramUniform3f(p, VOXGI__LOC_u_size, (float)vol->info.gl_size[0], (float)vol->info.gl_size[1], (float)vol->info.gl_size[2]);
    gl->ProgramUniform1f(p, VOXGI__LOC_u_max_lod, (float)(vol->info.levels - 1));
    gl->DispatchCompute((unsigned)VOXGI__MIN((count + 63) / 64, (size_t)65535), (unsigned)((count + 65535 * 64 - 1) / (65535 * 64)), 1);
    gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT | VOXGI__GL_BUFFER_UPDATE_BARRIER_BIT);
    gl->BindTextureUnit(0, 0);
    voxgi__gl_unbind(gl);
    packed = (float *)voxgi__alloc_array(ctx, count, 4 * sizeof(float), 0);
    if (!packed) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu samples", (unsigned long)count);
    if (r == VOXGI_OK) r = voxgi__gl_read_buffer(ctx, bufs[1], packed, count * 16);
    for (i = 0; r == VOXGI_OK && i < count; i++) memcpy(out + (size_t)w * i, packed + 4 * i, (size_t)w * sizeof(float));
    voxgi__free(ctx, packed);
    voxgi__gl_delete_buffer(ctx, bufs[0]);
    voxgi__gl_delete_buffer(ctx, bufs[1]);
    if (r == VOXGI_OK) r = voxgi__gl_check(ctx, "sampling a volume");
    return r;
}
#endif /* VOXGI_NO_GL */

VOXGI_API voxgi_result voxgi_volume_sample(voxgi_context *ctx, const voxgi_volume *vol, voxgi_attribute which, voxgi_direction dir,
                                           size_t count, const float *pos, const float *lods, float *out)
{
    int a, d;
    size_t i;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!vol || (count && (!pos || !lods || !out))) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "volume, positions, lods or out is NULL");
    if ((r = voxgi__volume_pick(ctx, vol, which, dir, &a, &d)) != VOXGI_OK) return r;
    for (i = 0; i < count; i++)
        if (!isfinite(pos[3 * i]) || !isfinite(pos[3 * i + 1]) || !isfinite(pos[3 * i + 2]) || !isfinite(lods[i]))
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "point %lu is not finite", (unsigned long)i);
#ifndef VOXGI_NO_GL
    if (vol->tex[a][d]) return voxgi__volume_sample_gl(ctx, vol, a, d, count, pos, lods, out);
#endif
    voxgi__volume_sample_cpu(vol, a, d, count, pos, lods, out);
    return VOXGI_OK;
}

VOXGI_API voxgi_result voxgi_volume_gl_texture(voxgi_context *ctx, const voxgi_volume *vol, voxgi_attribute which, voxgi_direction dir,
                                               unsigned int *name)
{
    int a, d;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!vol || !name) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "volume or name is NULL");
    if ((r = voxgi__volume_pick(ctx, vol, which, dir, &a, &d)) != VOXGI_OK) return r;
    if (!vol->tex[a][d]) return voxgi__fail(ctx, VOXGI_ERR_UNSUPPORTED, "this volume lives on the CPU, not in a GL texture");
    *name = vol->tex[a][d];
    return VOXGI_OK;
}

/* ===================================================================== 7. octree */
#ifndef VOXGI_NO_OCTREE

/* sparse voxel octree
   CPU build, linear in the voxels: their Morton codes radix-sorted; the nodes of level l are the
   distinct codes >> 3 (depth - l) in Morton order, so each level's tiles are contiguous and a
   node's tile is numbered by the rank of its parent; values from the leaves up. */
struct voxgi_svo {
    voxgi_svo_info info;
    uint32_t *child;                          /* per node slot: 1 + tile index, 0 = none */
    uint32_t *neighbour;                      /* 6 per node slot: slot of the same-level neighbour, 0 = none */
    unsigned char *node_values[VOXGI__VOLUME_SLOTS], *leaf_values[VOXGI__VOLUME_SLOTS]; /* per node / leaf slot: slot_bytes[a] in info.format */
    int slot_bytes[VOXGI__VOLUME_SLOTS];
    uint64_t inner_tiles, bricks;             /* bricks: one per inner node, or 0 */
    unsigned int gl_child, gl_neighbour;      /* GL: the same arrays in buffers, */
    unsigned int gl_values[VOXGI__VOLUME_SLOTS]; /* and per attribute one buffer of the node values, then the leaf values */
    uint32_t gl_leaf_first[VOXGI__VOLUME_SLOTS]; /* from this word on */
    uint32_t *regions;                        /* two-sided radiance with enclosed regions: a label per node slot, then per leaf
                                                 slot, then the bounds (voxgi__svo_regions) */
    size_t region_count;                      /* labels, 0 and OPEN included (0: no regions) */
    unsigned int gl_regions;                  /* GL: the same array in a buffer */
};

/* half floats: the octree's FLOAT16 values */
/* float -> half, rounded to the nearest, ties to even (finite input; 65520 and beyond: infinity).
   Integer steps only, so shaders/svo.glsl rounds exactly alike. */
static uint16_t voxgi__half_from_float(float f)
{
    uint32_t x, ax, sign, h;
    memcpy(&x, &f, 4);
    sign = (x >> 16) & 0x8000u;
    ax = x & 0x7FFFFFFFu;
    if (ax >= 0x47800000u) return (uint16_t)(sign | 0x7C00u);
    if (ax < 0x38800000u) { /* below 2^-14: a subnormal half, |f| * 2^24 rounded (the scaling is exact) */
        float v = fabsf(f) * 16777216.0f, frac;
        h = (uint32_t)v;
        frac = v - (float)h;
        h += frac > 0.5f || (frac == 0.5f && (h & 1u));
        return (uint16_t)(sign | h);
    }
    ax += 0x0FFFu + ((ax >> 13) & 1u); /* round the 13 dropped bits; a carry moves into the exponent */
    h = (ax >> 13) - (112u << 10);
    return (uint16_t)(sign | (h > 0x7C00u ? 0x7C00u : h));
}

static float voxgi__float_from_half(uint16_t h)
{
    uint32_t e = (h >> 10) & 31u, m = h & 1023u;
    float v = e == 0 ? (float)m / 16777216.0f : (e == 31 ? (m ? NAN : INFINITY) : ldexpf((float)(m | 1024u), (int)e - 25));
    return (h & 0x8000u) ? -v : v;
}

/* Stores c (value, alpha) into a slot of an attribute array (opacity: alpha alone). */
static void voxgi__svo_put(const voxgi_svo *svo, int a, unsigned char *base, uint64_t slot, const float c[4])
{
    unsigned char *o = base + slot * (uint64_t)svo->slot_bytes[a];
    int ch;
    if (svo->info.format == VOXGI_SVO_FLOAT16) {
        uint16_t h[4];
        if (a == 3) h[0] = voxgi__half_from_float(c[3]);
        else for (ch = 0; ch < 4; ch++) h[ch] = voxgi__half_from_float(c[ch]);
        memcpy(o, h, (size_t)svo->slot_bytes[a]);
    } else memcpy(o, a == 3 ? c + 3 : c, (size_t)svo->slot_bytes[a]);
}

/* Loads a slot as (value, alpha). */
static void voxgi__svo_get(const voxgi_svo *svo, int a, const unsigned char *base, uint64_t slot, float c[4])
{
    const unsigned char *s = base + slot * (uint64_t)svo->slot_bytes[a];
    float f[4] = {0, 0, 0, 0};
    int ch, w = a == 3 ? 1 : 4;
    if (svo->info.format == VOXGI_SVO_FLOAT16) {
        uint16_t h[4];
        memcpy(h, s, (size_t)svo->slot_bytes[a]);
        for (ch = 0; ch < w; ch++) f[ch] = voxgi__float_from_half(h[ch]);
    } else memcpy(f, s, (size_t)svo->slot_bytes[a]);
    if (w == 1) { c[0] = c[1] = c[2] = 0; c[3] = f[0]; }
    else for (ch = 0; ch < 4; ch++) c[ch] = f[ch];
}

/* The octree's sizes from its inner tiles and info.level_nodes, and the refusals that come
   before anything is allocated: 32-bit pointers and the memory budget. */
static voxgi_result voxgi__svo_size(voxgi_context *ctx, voxgi_svo *svo, uint64_t inner_tiles, const voxgi_svo_desc *desc)
{
    uint64_t value_bytes = 0, total, bricks = 0;
    int a, lev, depth = svo->info.depth;
    for (lev = 0; lev < depth; lev++) bricks += svo->info.level_nodes[lev];
    svo->inner_tiles = inner_tiles;
    svo->bricks = desc->bricks ? bricks : 0;
    svo->info.nodes = 1 + 8 * inner_tiles;
    svo->info.leaf_slots = 8 * svo->info.level_nodes[depth - 1];
    svo->info.leaf_voxels = svo->info.level_nodes[depth];
    svo->info.structure_bytes = (size_t)(svo->info.nodes * 4);
    svo->info.neighbour_bytes = desc->neighbours ? (size_t)(svo->info.nodes * 24) : 0;
    svo->info.brick_bytes = 0;
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++)
        if (svo->info.attributes & (1u << a)) {
            value_bytes += (svo->info.nodes + svo->info.leaf_slots) * (uint64_t)svo->slot_bytes[a];
            svo->info.brick_bytes += (size_t)(64 * svo->bricks * (uint64_t)svo->slot_bytes[a]);
        }
    total = svo->info.structure_bytes + svo->info.neighbour_bytes + value_bytes + svo->info.brick_bytes;
    if (svo->info.nodes + 64 * svo->bricks > (uint64_t)UINT32_MAX || svo->info.leaf_slots > (uint64_t)UINT32_MAX)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%llu node slots and %llu bricks exceed the 32-bit indices", (unsigned long long)svo->info.nodes,
                           (unsigned long long)svo->bricks);
    if (ctx->desc.memory_budget && total > (uint64_t)ctx->desc.memory_budget)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "the octree needs %llu bytes, more than the memory budget %llu", (unsigned long long)total,
                           (unsigned long long)ctx->desc.memory_budget);
    return VOXGI_OK;
}

/* A node's coordinates at its level from its Morton code. */
static void voxgi__svo_coords(uint64_t code, int lev, int64_t c[3])
{
    int b;
    c[0] = c[1] = c[2] = 0;
    for (b = 0; b < lev; b++) {
        c[0] |= (int64_t)((code >> (3 * b)) & 1u) << b;
        c[1] |= (int64_t)((code >> (3 * b + 1)) & 1u) << b;
        c[2] |= (int64_t)((code >> (3 * b + 2)) & 1u) << b;
    }
}

/* A node slot's child pointer, wherever the octree lives. */
static uint32_t voxgi__svo_child(voxgi_context *ctx, const voxgi_svo *svo, uint64_t slot)
{
#ifndef VOXGI_NO_GL
    if (svo->gl_child) {
        uint32_t ptr = 0;
        ctx->gl->MemoryBarrier(VOXGI__GL_BUFFER_UPDATE_BARRIER_BIT);
        ctx->gl->GetNamedBufferSubData(svo->gl_child, (ptrdiff_t)(4 * slot), 4, &ptr);
        return ptr;
    }
#endif
    (void)ctx;
    return svo->child[slot];
}

/* The child pointer of the node at `lev` and coordinates c (0: no node there, or outside). */
static uint32_t voxgi__svo_ptr_at(voxgi_context *ctx, const voxgi_svo *svo, int lev, const int64_t c[3])
{
    uint64_t node = 0;
    int m;
    if (c[0] < 0 || c[1] < 0 || c[2] < 0 || (c[0] >> lev) || (c[1] >> lev) || (c[2] >> lev)) return 0;
    for (m = 1; m <= lev; m++) {
        uint32_t ptr = voxgi__svo_child(ctx, svo, node);
        if (!ptr) return 0;
        node = 1 + 8 * (uint64_t)(ptr - 1) + (uint64_t)(((c[0] >> (lev - m)) & 1) | (((c[1] >> (lev - m)) & 1) << 1) | (((c[2] >> (lev - m)) & 1) << 2));
    }
    return voxgi__svo_child(ctx, svo, node);
}

/* A brick's index from its node's level and child pointer: inner tiles first, then leaf tiles;
   its values follow the node slots in node_values. */
static uint64_t voxgi__svo_brick_index(const voxgi_svo *svo, int lev, uint32_t ptr)
{
    return (lev < svo->info.depth - 1 ? 0 : svo->inner_tiles) + ptr - 1;
}

/* The brick of the node at `lev`, coordinates c, child pointer ptr, for attribute a: the stored
   values of its 27 neighbourhood's child tiles, copied. */
static void voxgi__svo_fill_brick(voxgi_context *ctx, voxgi_svo *svo, int a, int lev, const int64_t c[3], uint32_t ptr)
{
    uint32_t around[27];
    uint64_t b = (uint64_t)svo->slot_bytes[a];
    unsigned char *dst = svo->node_values[a] + (svo->info.nodes + 64 * voxgi__svo_brick_index(svo, lev, ptr)) * b;
    int d, t;
    for (d = 0; d < 27; d++) {
        int64_t q[3];
        q[0] = c[0] + d % 3 - 1; q[1] = c[1] + d / 3 % 3 - 1; q[2] = c[2] + d / 9 - 1;
        around[d] = d == 13 ? ptr : voxgi__svo_ptr_at(ctx, svo, lev, q);
    }
    for (t = 0; t < 64; t++) {
        int ax, nd = 0;
        uint32_t digit = 0, p;
        for (ax = 0; ax < 3; ax++) {
            int64_t q = 2 * c[ax] - 1 + ((t >> (2 * ax)) & 3); /* child coordinate, -1 .. 2^(lev+1) */
            nd += (int)((q + 2) / 2 - c[ax]) * (ax == 0 ? 1 : (ax == 1 ? 3 : 9)); /* floor(q / 2) - c + 1 */
            digit |= (uint32_t)(q & 1) << ax;
        }
        if (!(p = around[nd])) continue; /* stays empty */
        memcpy(dst + (uint64_t)t * b,
               lev == svo->info.depth - 1 ? svo->leaf_values[a] + (8 * (uint64_t)(p - 1) + digit) * b
                                          : svo->node_values[a] + (1 + 8 * (uint64_t)(p - 1) + digit) * b, (size_t)b);
    }
}

/* The CPU build's levels: each level's node codes (Morton order, distinct) and counts, the
   inner tiles before each level, and each leaf's index in bit order. */
typedef struct voxgi__svo_levels {
    uint64_t *codes[VOXGI__MAX_LEVELS + 1];
    size_t count[VOXGI__MAX_LEVELS + 1];
    uint64_t tiles_before[VOXGI__MAX_LEVELS + 1];
    uint32_t *order;
} voxgi__svo_levels;

/* The refusals of voxgi_svo_create, and the octree's depth. */
static voxgi_result voxgi__svo_check(voxgi_context *ctx, const voxgi_voxels *vx, const voxgi_svo_desc *desc, int *depth_out)
{
    const voxgi_grid *g = &vx->info.grid;
    int depth = 1, maxres = VOXGI__MAX(g->res[0], VOXGI__MAX(g->res[1], g->res[2]));
    if (!vx->info.attributes) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "these voxels hold no attributes (voxgi_voxelize_desc.attributes)");
    if (desc->attributes & ~vx->info.attributes & ~VOXGI__RADIANCE_FAMILY ||
        ((desc->attributes & VOXGI__RADIANCE_FAMILY) && (!desc->radiance || (desc->attributes & ~desc->radiance->info.attributes & VOXGI__RADIANCE_FAMILY))))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "attributes 0x%x asked for, the voxels hold 0x%x%s", desc->attributes, vx->info.attributes,
                           desc->radiance ? ", desc.radiance the front's alone" : " (RADIANCE: from desc.radiance)");
    while ((1 << depth) < maxres) depth++;
    if (depth > 16) return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "octrees hold grids up to 65536 voxels per axis");
    if (desc->format != VOXGI_SVO_FLOAT32 && desc->format != VOXGI_SVO_FLOAT16)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "octree value format %d", (int)desc->format);
    if (desc->radiance) {
        const voxgi_grid *rg = &desc->radiance->info.grid;
        if (!(desc->radiance->info.attributes & VOXGI_ATTRIBUTE_RADIANCE))
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "desc.radiance holds no RADIANCE (voxgi_inject_light)");
        if (rg->voxel_size != g->voxel_size || memcmp(rg->origin, g->origin, sizeof g->origin) || memcmp(rg->res, g->res, sizeof g->res))
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "desc.radiance lies on another grid than the voxels");
    }
    *depth_out = depth;
    return VOXGI_OK;
}

/* 1. The leaves: the set voxels in bit order, as Morton codes with their index (CPU) or as
   the GPU's fragment list x | y << 16, z (GL: *packed), and their values per slot: the
   attribute means and the radiance volume's level 0. */
static voxgi_result voxgi__svo_leaves(voxgi_context *ctx, const voxgi_svo *svo, const voxgi_voxels *vx, const voxgi_svo_desc *desc,
                                      voxgi__svo_levels *L, uint32_t **packed_out, float *vals[VOXGI__VOLUME_SLOTS])
{
    const voxgi_grid *g = &vx->info.grid;
    uint64_t nvox = voxgi_grid_voxel_count(g), l;
    size_t need = 0, i, n = (size_t)vx->info.voxel_count;
    uint32_t *bits = NULL, *packed = NULL;
    const uint32_t *leaf_bits = vx->bits; /* CPU voxels are used where they are, GL ones read back */
    float *radiance = NULL;
    int depth = svo->info.depth, a;
    voxgi_result r = VOXGI_OK;
    if (!leaf_bits) {
        r = voxgi_voxels_read(ctx, vx, NULL, 0, &need);
        if (r == VOXGI_OK && !(bits = (uint32_t *)voxgi__alloc(ctx, need))) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the bits");
        if (r == VOXGI_OK) r = voxgi_voxels_read(ctx, vx, bits, need, NULL);
        leaf_bits = bits;
    }
    if (r == VOXGI_OK && ctx->backend == VOXGI_BACKEND_GL) {
        if (!(packed = (uint32_t *)voxgi__alloc_array(ctx, n ? n : 1, 8, 0)))
            r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu voxel fragments", (unsigned long)n);
    } else if (r == VOXGI_OK && (!(L->codes[depth] = (uint64_t *)voxgi__alloc_array(ctx, n ? n : 1, 8, 0)) ||
                                 !(L->order = (uint32_t *)voxgi__alloc_array(ctx, n ? n : 1, 4, 0))))
        r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu leaves", (unsigned long)n);
    for (l = 0, i = 0; r == VOXGI_OK && l < (nvox + 31) / 32; l++) { /* word by word: empty space costs little */
        uint32_t word = leaf_bits[l];
        for (; word; word &= word - 1) {
            uint64_t v = 32 * l + (uint64_t)voxgi__popcount32((word & (0u - word)) - 1u);
            uint32_t x = (uint32_t)(v % (uint64_t)g->res[0]), y = (uint32_t)(v / (uint64_t)g->res[0] % (uint64_t)g->res[1]),
                     z = (uint32_t)(v / ((uint64_t)g->res[0] * (uint64_t)g->res[1]));
            if (packed) { packed[2 * i] = x | y << 16; packed[2 * i + 1] = z; }
            else { L->codes[depth][i] = voxgi__morton(x, y, z); L->order[i] = (uint32_t)i; }
            i++;
        }
    }
    for (a = 0; a < 4 && r == VOXGI_OK; a++) { /* the attribute means, in bit order */
        voxgi_attribute which = (voxgi_attribute)(1 << a);
        if (!(vx->info.attributes & (unsigned)which) || (a < 3 && !(svo->info.attributes & (unsigned)which))) continue;
        r = voxgi_voxels_read_attribute(ctx, vx, which, NULL, 0, &need);
        if (r == VOXGI_OK && !(vals[a] = (float *)voxgi__alloc(ctx, need ? need : 4))) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory");
        if (r == VOXGI_OK) r = voxgi_voxels_read_attribute(ctx, vx, which, vals[a], need, NULL);
    }
    for (a = VOXGI__RADIANCE_SLOT; a <= VOXGI__SIDE_SLOT && r == VOXGI_OK; a++) { /* the radiance volume's level 0 at the set voxels, in bit order */
        voxgi_attribute which = (voxgi_attribute)(1 << a);
        if (!(svo->info.attributes & (unsigned)which)) continue;
        r = voxgi_volume_read(ctx, desc->radiance, which, VOXGI_DIR_POS_X, 0, NULL, 0, &need);
        if (r == VOXGI_OK && (!(radiance = (float *)voxgi__alloc(ctx, need)) || !(vals[a] = (float *)voxgi__alloc_array(ctx, n ? n : 1, 16, 0))))
            r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the radiance of %lu voxels", (unsigned long)n);
        if (r == VOXGI_OK) r = voxgi_volume_read(ctx, desc->radiance, which, VOXGI_DIR_POS_X, 0, radiance, need, NULL);
        for (l = 0, i = 0; r == VOXGI_OK && l < (nvox + 31) / 32; l++) {
            uint32_t word = leaf_bits[l];
            for (; word; word &= word - 1, i++)
                memcpy(vals[a] + 4 * i, radiance + 4 * (32 * l + (uint64_t)voxgi__popcount32((word & (0u - word)) - 1u)), 16);
        }
        voxgi__free(ctx, radiance);
        radiance = NULL;
    }
    voxgi__free(ctx, bits);
    *packed_out = packed;
    return r;
}

/* 2. Each level's nodes, the distinct parent codes of the level below, tiles numbered level by
   level; the octree's sizes; child pointers: node (lev, rank) -> 1 + its tile one level down. */
static voxgi_result voxgi__svo_nodes_cpu(voxgi_context *ctx, voxgi_svo *svo, const voxgi_svo_desc *desc, size_t n, voxgi__svo_levels *L)
{
    int depth = svo->info.depth, lev;
    uint64_t tiles = 0;
    size_t i;
    voxgi_result r;
    L->count[depth] = n;
    for (lev = depth - 1; lev >= 0; lev--) {
        size_t m = 0;
        if (!(L->codes[lev] = (uint64_t *)voxgi__alloc_array(ctx, L->count[lev + 1] ? L->count[lev + 1] : 1, 8, 0)))
            return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the octree's levels");
        for (i = 0; i < L->count[lev + 1]; i++)
            if (!m || L->codes[lev][m - 1] != L->codes[lev + 1][i] >> 3) L->codes[lev][m++] = L->codes[lev + 1][i] >> 3;
        if (!n && lev == 0) L->codes[0][m++] = 0; /* an empty octree still has its root */
        L->count[lev] = m;
    }
    for (lev = 1; lev < depth; lev++) { L->tiles_before[lev] = tiles; tiles += L->count[lev - 1]; } /* inner tiles: one per node above */
    for (lev = 0; lev <= depth; lev++) svo->info.level_nodes[lev] = L->count[lev];
    if ((r = voxgi__svo_size(ctx, svo, tiles, desc)) != VOXGI_OK) return r;
    if (!(svo->child = (uint32_t *)voxgi__alloc_array(ctx, (size_t)svo->info.nodes, 4, 1)))
        return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %llu nodes", (unsigned long long)svo->info.nodes);
    for (lev = 0; lev < depth; lev++) {
        size_t parent_rank = 0; /* both levels are in Morton order: the parent only moves forward */
        for (i = 0; i < L->count[lev]; i++) {
            uint64_t slot = 0;
            if (lev > 0) { /* the node's slot: its parent's tile, at its digit */
                while (L->codes[lev - 1][parent_rank] != L->codes[lev][i] >> 3) parent_rank++;
                slot = 1 + 8 * (L->tiles_before[lev] + parent_rank) + (L->codes[lev][i] & 7u);
            }
            svo->child[slot] = (uint32_t)(1 + (lev == depth - 1 ? i : L->tiles_before[lev + 1] + i));
        }
    }
    return VOXGI_OK;
}

/* Each inner node's same-level neighbours, by binary search in the level's codes. */
static voxgi_result voxgi__svo_neighbours_cpu(voxgi_context *ctx, voxgi_svo *svo, const voxgi__svo_levels *L)
{
    int depth = svo->info.depth, lev;
    size_t i;
    if (!(svo->neighbour = (uint32_t *)voxgi__alloc_array(ctx, (size_t)svo->info.nodes, 6 * 4, 1)))
        return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the neighbour pointers");
    for (lev = 1; lev < depth; lev++) {
        size_t parent_rank = 0;
        for (i = 0; i < L->count[lev]; i++) {
            uint64_t slot, code = L->codes[lev][i];
            int64_t at[3];
            int dir;
            while (L->codes[lev - 1][parent_rank] != code >> 3) parent_rank++;
            slot = 1 + 8 * (L->tiles_before[lev] + parent_rank) + (code & 7u);
            voxgi__svo_coords(code, lev, at);
            for (dir = 0; dir < 6; dir++) {
                int64_t c[3];
                uint64_t ncode;
                size_t lo = 0, hi = L->count[lev], plo = 0, phi = L->count[lev - 1];
                memcpy(c, at, sizeof c);
                c[dir / 2] += (dir & 1) ? -1 : 1;
                if (c[dir / 2] < 0 || c[dir / 2] >= ((int64_t)1 << lev)) continue;
                ncode = voxgi__morton((uint32_t)c[0], (uint32_t)c[1], (uint32_t)c[2]);
                while (hi - lo > 1) { size_t mid = (lo + hi) / 2; if (L->codes[lev][mid] <= ncode) lo = mid; else hi = mid; }
                if (L->codes[lev][lo] != ncode) continue;
                while (phi - plo > 1) { size_t mid = (plo + phi) / 2; if (L->codes[lev - 1][mid] <= ncode >> 3) plo = mid; else phi = mid; }
                svo->neighbour[6 * slot + (uint64_t)dir] = (uint32_t)(1 + 8 * (L->tiles_before[lev] + plo) + (ncode & 7u));
            }
        }
    }
    return VOXGI_OK;
}

/* 3. Values: the leaves from the attribute means, then every node the isotropic mip of its
   tile, bottom up from the stored values; 4. bricks from the finished values. */
static voxgi_result voxgi__svo_values_cpu(voxgi_context *ctx, voxgi_svo *svo, const voxgi__svo_levels *L, size_t n,
                                          float *const vals[VOXGI__VOLUME_SLOTS])
{
    int depth = svo->info.depth, lev, a;
    uint64_t nvox = voxgi_grid_voxel_count(&svo->info.grid);
    size_t i;
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++) {
        int b = svo->slot_bytes[a];
        unsigned char *leaf, *node;
        size_t parent_rank = 0;
        if (!(svo->info.attributes & (1u << a))) continue;
        leaf = svo->leaf_values[a] = (unsigned char *)voxgi__alloc_array(ctx, (size_t)(svo->info.leaf_slots ? svo->info.leaf_slots : 1), (size_t)b, 1);
        node = svo->node_values[a] = (unsigned char *)voxgi__alloc_array(ctx, (size_t)(svo->info.nodes + 64 * svo->bricks), (size_t)b, 1);
        if (!leaf || !node) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the octree's values");
        for (i = 0; i < n; i++) { /* leaves: slot 8 * rank(parent) + digit */
            uint64_t parent = L->codes[depth][i] >> 3;
            float c[4] = {0, 0, 0, 0};
            c[3] = vals[3] ? vals[3][L->order[i]] : 1.0f;
            if (a < 3) memcpy(c, vals[a] + 3 * (size_t)L->order[i], 3 * sizeof(float));
            if (a >= VOXGI__RADIANCE_SLOT) memcpy(c, vals[a] + 4 * (size_t)L->order[i], sizeof c);
            while (L->codes[depth - 1][parent_rank] != parent) parent_rank++;
            voxgi__svo_put(svo, a, leaf, 8 * parent_rank + (L->codes[depth][i] & 7u), c);
        }
        for (lev = depth - 1; lev >= 0; lev--) { /* nodes bottom up, from the stored values of their children */
            parent_rank = 0;
            for (i = 0; i < L->count[lev]; i++) {
                uint64_t slot = 0, tile;
                float c[8][4], m[4];
                int k;
                if (lev > 0) {
                    while (L->codes[lev - 1][parent_rank] != L->codes[lev][i] >> 3) parent_rank++;
                    slot = 1 + 8 * (L->tiles_before[lev] + parent_rank) + (L->codes[lev][i] & 7u);
                }
                tile = svo->child[slot] - 1;
                for (k = 0; k < 8; k++) {
                    if (lev == depth - 1) voxgi__svo_get(svo, a, leaf, 8 * tile + (uint64_t)k, c[k]);
                    else voxgi__svo_get(svo, a, node, 1 + 8 * tile + (uint64_t)k, c[k]);
                }
                voxgi__mip_combine(c, 4, -1, a >= VOXGI__RADIANCE_SLOT, m);
                voxgi__svo_put(svo, a, node, slot, m);
            }
        }
        for (lev = 0; lev < depth && svo->bricks; lev++)
            for (i = 0; i < L->count[lev]; i++) {
                int64_t c[3];
                voxgi__svo_coords(L->codes[lev][i], lev, c);
                voxgi__svo_fill_brick(ctx, svo, a, lev, c, voxgi__svo_ptr_at(ctx, svo, lev, c));
            }
        svo->info.bytes += (size_t)((svo->info.nodes + svo->info.leaf_slots) * (uint64_t)b);
        svo->info.dense_bytes += (size_t)(nvox * (uint64_t)b);
        if (voxgi__cancelled(ctx, 0.5 + 0.125 * (a + 1), "octree build", "octree: values")) return VOXGI_ERR_CANCELLED;
    }
    return VOXGI_OK;
}

#ifndef VOXGI_NO_GL
/* GL: the octree's buffers grow level by level to the size the flag pass counted (a 4-byte
   read per level), never beyond the memory budget or the largest storage buffer. */
static voxgi_result voxgi__svo_grow_gl(voxgi_context *ctx, unsigned int *buf, uint64_t *cap, uint64_t need, const char *what)
{
    voxgi__gl *gl = ctx->gl;
    uint64_t bytes;
    unsigned int b;
    if (need <= *cap) return VOXGI_OK;
    bytes = VOXGI__MAX(need, *cap + *cap / 2);
    if ((int64_t)need > gl->max_ssbo_bytes || (ctx->desc.memory_budget && need > (uint64_t)ctx->desc.memory_budget))
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "the octree's %s need %llu bytes, beyond the storage buffer limit %lld or the budget %llu", what,
                           (unsigned long long)need, (long long)gl->max_ssbo_bytes, (unsigned long long)ctx->desc.memory_budget);
    if ((int64_t)bytes > gl->max_ssbo_bytes) bytes = need;
    b = voxgi__gl_buffer(ctx, (size_t)bytes, NULL);
    if (*buf) {
        gl->CopyNamedBufferSubData(*buf, b, 0, 0, (ptrdiff_t)*cap);
        voxgi__gl_delete_buffer(ctx, *buf);
    }
    *buf = b;
    *cap = bytes;
    return voxgi__gl_check(ctx, "growing the octree");
}

/* Binds an octree's child and value buffers of attribute a for shaders/svo.glsl. */
static void voxgi__svo_bind_gl(voxgi_context *ctx, const voxgi_svo *svo, unsigned int p, int a)
{
    voxgi__gl *gl = ctx->gl;
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, VOXGI__BINDING_SVO_CHILD, svo->gl_child);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, VOXGI__BINDING_SVO_VALUES, a >= 0 ? svo->gl_values[a] : 0);
    gl->ProgramUniform1ui(p, VOXGI__LOC_u_svo_leaf_first, a >= 0 ? svo->gl_leaf_first[a] : 0u);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_svo_depth, svo->info.depth);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_svo_format, (int)svo->info.format);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_svo_single, a == 3);
    gl->ProgramUniform1ui(p, VOXGI__LOC_u_svo_nodes, (unsigned)svo->info.nodes);
    gl->ProgramUniform1ui(p, VOXGI__LOC_u_svo_inner_tiles, (unsigned)svo->inner_tiles);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_svo_bricks, svo->bricks != 0);
}

enum { VOXGI__SVO_FLAG, VOXGI__SVO_ARGS, VOXGI__SVO_ALLOCATE, VOXGI__SVO_INIT, VOXGI__SVO_LEAVES, VOXGI__SVO_MIP, VOXGI__SVO_NEIGHBOURS, VOXGI__SVO_BRICKS };

/* The GPU build (shaders/svo_build.glsl) from the voxel fragments (x | y << 16, z) and their
   attribute means in the same order. */
static voxgi_result voxgi__svo_build_gl(voxgi_context *ctx, voxgi_svo *svo, size_t n, const uint32_t *packed, float *const vals[VOXGI__VOLUME_SLOTS],
                                        const voxgi_svo_desc *desc)
{
    voxgi__gl *gl = ctx->gl;
    int depth = svo->info.depth, m, a;
    unsigned int p, frag = 0, list = 0, counters = 0, fvals = 0;
    uint64_t child_cap = 0, list_cap = 0, tiles = depth > 1 ? 1 : 0, entries = 1, first[VOXGI__MAX_LEVELS + 1];
    uint32_t init[16], root_tile[9];
    double t0;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_svo_build);
    if (r != VOXGI_OK) return r;
    t0 = voxgi__now_ms();
    p = gl->prog_svo_build;
    memset(init, 0, sizeof init);
    memset(root_tile, 0, sizeof root_tile);
    root_tile[0] = 1; /* the root always has its tile (a leaf tile when depth is 1), as on the CPU */
    init[0] = depth > 1 ? 1u : 0u;
    init[1] = depth > 1 ? 0u : 1u;
    init[3] = 1; /* the node list holds the root */
    r = voxgi__svo_grow_gl(ctx, &svo->gl_child, &child_cap, depth > 1 ? 36 : 4, "child pointers");
    if (r == VOXGI_OK) r = voxgi__svo_grow_gl(ctx, &list, &list_cap, 16, "node list");
    if (r != VOXGI_OK) goto done;
    gl->NamedBufferSubData(svo->gl_child, 0, depth > 1 ? 36 : 4, root_tile);
    gl->NamedBufferSubData(list, 0, 16, init + 4); /* slot 0 at (0, 0, 0) */
    counters = voxgi__gl_buffer(ctx, sizeof init, init);
    frag = voxgi__gl_buffer(ctx, n * 8, packed);
    gl->UseProgram(p);
    voxgi__svo_bind_gl(ctx, svo, p, -1);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 3, frag);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 4, list);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 5, counters);
    gl->ProgramUniform1ui(p, VOXGI__LOC_u_count, (unsigned)n);
    svo->info.level_nodes[0] = 1;
    first[0] = 0;
    for (m = 1; m < depth && r == VOXGI_OK; m++) { /* level m's nodes and their tiles */
        uint32_t flagged = 0;
        gl->ProgramUniform1i(p, VOXGI__LOC_u_level, m);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, VOXGI__SVO_FLAG);
        voxgi__gl_dispatch_rows(gl, n);
        gl->GetNamedBufferSubData(counters, 8, 4, &flagged);
        svo->info.level_nodes[m] = flagged;
        first[m] = entries;
        entries += flagged;
        if (m < depth - 1) tiles += flagged;
        if (voxgi__cancelled(ctx, 0.5 * m / depth, "octree build", "octree: nodes")) { r = VOXGI_ERR_CANCELLED; break; }
        r = voxgi__svo_grow_gl(ctx, &svo->gl_child, &child_cap, 4 * (1 + 8 * tiles), "child pointers");
        if (r == VOXGI_OK) r = voxgi__svo_grow_gl(ctx, &list, &list_cap, 16 * entries, "node list");
        if (r != VOXGI_OK) break;
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 0, svo->gl_child);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 4, list);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, VOXGI__SVO_ARGS);
        gl->DispatchCompute(1, 1, 1);
        gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT | VOXGI__GL_COMMAND_BARRIER_BIT);
        gl->BindBuffer(VOXGI__GL_DISPATCH_INDIRECT_BUFFER, counters);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, VOXGI__SVO_ALLOCATE);
        gl->DispatchComputeIndirect(16);
        gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT | VOXGI__GL_COMMAND_BARRIER_BIT);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, VOXGI__SVO_INIT);
        gl->DispatchComputeIndirect(32);
        gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT | VOXGI__GL_COMMAND_BARRIER_BIT);
        gl->BindBuffer(VOXGI__GL_DISPATCH_INDIRECT_BUFFER, 0);
    }
    if (r != VOXGI_OK) goto done;
    svo->info.level_nodes[depth] = n;
    if ((r = voxgi__svo_size(ctx, svo, tiles, desc)) != VOXGI_OK) goto done; /* before the values are allocated */
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++) /* each value buffer within one storage block (so word indices stay 32-bit too) */
        if ((svo->info.attributes & (1u << a)) &&
            ((int64_t)(((svo->info.nodes + 64 * svo->bricks) * (uint64_t)svo->slot_bytes[a] + 3) / 4 * 4 + svo->info.leaf_slots * (uint64_t)svo->slot_bytes[a]) >
                 gl->max_ssbo_bytes ||
             (int64_t)(16 * (uint64_t)n) > gl->max_ssbo_bytes)) {
            r = voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "the octree's values of attribute %d exceed GL_MAX_SHADER_STORAGE_BLOCK_SIZE %lld", a,
                            (long long)gl->max_ssbo_bytes);
            goto done;
        }
    if (child_cap > svo->info.structure_bytes) { /* give back the growth's slack */
        unsigned int exact = voxgi__gl_buffer(ctx, svo->info.structure_bytes, NULL);
        gl->CopyNamedBufferSubData(svo->gl_child, exact, 0, 0, (ptrdiff_t)svo->info.structure_bytes);
        voxgi__gl_delete_buffer(ctx, svo->gl_child);
        svo->gl_child = exact;
    }
    gl->Finish();
    svo->info.ms_nodes = voxgi__now_ms() - t0;
    t0 = voxgi__now_ms();
    if (desc->neighbours) { /* levels 1 .. depth-1 */
        unsigned int zero = 0;
        svo->gl_neighbour = voxgi__gl_buffer(ctx, (size_t)svo->info.nodes * 24, NULL);
        gl->ClearNamedBufferData(svo->gl_neighbour, VOXGI__GL_R32UI, VOXGI__GL_RED_INTEGER, VOXGI__GL_UNSIGNED_INT, &zero);
        voxgi__svo_bind_gl(ctx, svo, p, -1);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 6, svo->gl_neighbour);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, VOXGI__SVO_NEIGHBOURS);
        for (m = 1; m < depth; m++) {
            gl->ProgramUniform1i(p, VOXGI__LOC_u_level, m);
            gl->ProgramUniform1ui(p, VOXGI__LOC_u_first, (unsigned)first[m]);
            gl->ProgramUniform1ui(p, VOXGI__LOC_u_count, (unsigned)svo->info.level_nodes[m]);
            voxgi__gl_dispatch_rows(gl, svo->info.level_nodes[m]);
        }
        gl->Finish();
        svo->info.ms_neighbours = voxgi__now_ms() - t0;
        t0 = voxgi__now_ms();
    }
    fvals = voxgi__gl_buffer(ctx, n * 16, NULL);
    for (a = 0; a < VOXGI__VOLUME_SLOTS && r == VOXGI_OK; a++) { /* leaves from the fragments, then the mips bottom up */
        uint64_t node_bytes = svo->info.nodes * (uint64_t)svo->slot_bytes[a], leaf_bytes = svo->info.leaf_slots * (uint64_t)svo->slot_bytes[a];
        unsigned int zero = 0;
        float *v4;
        size_t i;
        if (!(svo->info.attributes & (1u << a))) continue;
        if (!(v4 = (float *)voxgi__alloc_array(ctx, n ? n : 1, 16, 0))) { r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the fragment values"); break; }
        for (i = 0; i < n; i++) {
            if (a >= VOXGI__RADIANCE_SLOT) { memcpy(v4 + 4 * i, vals[a] + 4 * i, 16); continue; } /* radiance: as the volume holds it */
            v4[4 * i] = a < 3 ? vals[a][3 * i] : 0;
            v4[4 * i + 1] = a < 3 ? vals[a][3 * i + 1] : 0;
            v4[4 * i + 2] = a < 3 ? vals[a][3 * i + 2] : 0;
            v4[4 * i + 3] = vals[3] ? vals[3][i] : 1.0f;
        }
        gl->NamedBufferSubData(fvals, 0, (ptrdiff_t)(n * 16), v4);
        voxgi__free(ctx, v4);
        svo->gl_leaf_first[a] = (uint32_t)((node_bytes + 64 * svo->bricks * (uint64_t)svo->slot_bytes[a] + 3) / 4);
        svo->gl_values[a] = voxgi__gl_buffer(ctx, (size_t)(4 * (uint64_t)svo->gl_leaf_first[a] + (leaf_bytes + 3) / 4 * 4), NULL);
        gl->ClearNamedBufferData(svo->gl_values[a], VOXGI__GL_R32UI, VOXGI__GL_RED_INTEGER, VOXGI__GL_UNSIGNED_INT, &zero);
        voxgi__svo_bind_gl(ctx, svo, p, a);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 7, fvals);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, VOXGI__SVO_LEAVES);
        gl->ProgramUniform1ui(p, VOXGI__LOC_u_count, (unsigned)n);
        voxgi__gl_dispatch_rows(gl, n);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, VOXGI__SVO_MIP);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_premultiplied, a >= VOXGI__RADIANCE_SLOT);
        for (m = depth - 1; m >= 0; m--) {
            gl->ProgramUniform1i(p, VOXGI__LOC_u_level, m);
            gl->ProgramUniform1ui(p, VOXGI__LOC_u_first, (unsigned)first[m]);
            gl->ProgramUniform1ui(p, VOXGI__LOC_u_count, (unsigned)svo->info.level_nodes[m]);
            voxgi__gl_dispatch_rows(gl, svo->info.level_nodes[m]);
        }
        gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, VOXGI__SVO_BRICKS);
        for (m = 0; m < depth && svo->bricks; m++) { /* 64 texels per node, from the finished values */
            gl->ProgramUniform1i(p, VOXGI__LOC_u_level, m);
            gl->ProgramUniform1ui(p, VOXGI__LOC_u_first, (unsigned)first[m]);
            gl->ProgramUniform1ui(p, VOXGI__LOC_u_count, (unsigned)(64 * svo->info.level_nodes[m]));
            voxgi__gl_dispatch_rows(gl, 64 * svo->info.level_nodes[m]);
        }
        svo->info.bytes += (size_t)(node_bytes + leaf_bytes);
        svo->info.dense_bytes += (size_t)(voxgi_grid_voxel_count(&svo->info.grid) * (uint64_t)svo->slot_bytes[a]);
        r = voxgi__gl_check(ctx, "the octree's values");
        if (r == VOXGI_OK && voxgi__cancelled(ctx, 0.5 + 0.125 * (a + 1), "octree build", "octree: values")) r = VOXGI_ERR_CANCELLED;
    }
    svo->info.bytes += svo->info.structure_bytes + svo->info.neighbour_bytes + svo->info.brick_bytes;
    gl->Finish();
    svo->info.ms_values = voxgi__now_ms() - t0;
done:
    voxgi__gl_unbind(gl);
    voxgi__gl_delete_buffer(ctx, frag);
    voxgi__gl_delete_buffer(ctx, list);
    voxgi__gl_delete_buffer(ctx, counters);
    voxgi__gl_delete_buffer(ctx, fvals);
    if (r == VOXGI_OK) r = voxgi__gl_check(ctx, "building the octree");
    return r;
}
#endif

/* 5. Regions (a two-sided radiance volume with enclosed regions, voxgi__volume_regions): every
   slot's label as the volume's level holds it, so that cones keep to their region alike. A leaf
   slot holds level 0's label; a node the outermost of its children's (the same rule); an empty
   slot, which stands for every level below it, the region of its cube's voxels. The bounds
   follow. */
typedef struct voxgi__svo_region_walk {
    const voxgi_svo *svo;
    const uint32_t *child, *level0, *box; /* the child pointers, the volume's level-0 labels and bounds */
    uint32_t *out;
} voxgi__svo_region_walk;

/* Labels slot (of level lev, at c in that level's coordinates) and the slots below it; returns
   its label as its level holds it. */
static uint32_t voxgi__svo_region_slot(const voxgi__svo_region_walk *W, int lev, uint64_t slot, const int64_t c[3])
{
    const voxgi_svo *svo = W->svo;
    const int *res = svo->info.grid.res;
    int depth = svo->info.depth, k = depth - lev, d;
    uint32_t ptr, v = 0;
    if (lev == depth || !W->child[slot]) { /* a voxel, or an empty cube: the label of its first voxel */
        uint32_t r = c[0] << k < res[0] && c[1] << k < res[1] && c[2] << k < res[2]
                         ? W->level0[(size_t)(c[0] << k) + (size_t)res[0] * ((size_t)(c[1] << k) + (size_t)res[1] * (size_t)(c[2] << k))]
                         : 0;
        if (lev == depth) return W->out[svo->info.nodes + slot] = r;
        return W->out[slot] = r;
    }
    ptr = W->child[slot];
    for (d = 0; d < 8; d++) {
        int64_t cc[3];
        uint32_t w;
        cc[0] = 2 * c[0] + (d & 1); cc[1] = 2 * c[1] + (d >> 1 & 1); cc[2] = 2 * c[2] + (d >> 2);
        w = voxgi__svo_region_slot(W, lev + 1, (lev + 1 == depth ? 0u : 1u) + 8 * (uint64_t)(ptr - 1) + (uint64_t)d, cc);
        if (k == 1) w = w & VOXGI__REGION_BORDER ? VOXGI__REGION_OF(w) : w; /* as voxgi__volume_regions */
        if (!w || w == v) continue;
        v = !v || voxgi__region_inside(W->box, w, v) ? w : (voxgi__region_inside(W->box, v, w) ? v : VOXGI__REGION_MIXED);
    }
    return W->out[slot] = v;
}

static voxgi_result voxgi__svo_regions(voxgi_context *ctx, voxgi_svo *svo, const voxgi_volume *vol)
{
    voxgi__svo_region_walk W;
    size_t labels = (size_t)(svo->info.nodes + svo->info.leaf_slots);
    uint32_t *child = NULL, *read = NULL;
    int64_t root[3] = {0, 0, 0};
    voxgi_result r = VOXGI_OK;
    if (!vol || vol->region_count <= 2 || (labels + 6 * vol->region_count) * 4 > VOXGI__REGION_BYTES) return VOXGI_OK; /* nothing enclosed, or too big: none */
    if (!(svo->regions = (uint32_t *)voxgi__alloc_array(ctx, labels + 6 * vol->region_count, 4, 1)))
        return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the octree's regions");
    W.svo = svo;
    W.child = svo->child;
    W.level0 = vol->regions;
    W.box = vol->region_boxes;
    W.out = svo->regions;
#ifndef VOXGI_NO_GL
    if (!vol->regions) { /* a GL volume's and octree's: read back for the walk */
        voxgi__gl *gl = ctx->gl;
        size_t level0 = (size_t)voxgi_grid_voxel_count(&svo->info.grid);
        if (!(child = (uint32_t *)voxgi__alloc_array(ctx, (size_t)svo->info.nodes, 4, 0)) ||
            !(read = (uint32_t *)voxgi__alloc_array(ctx, level0 + 6 * vol->region_count, 4, 0)))
            r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the octree's regions");
        if (r == VOXGI_OK) {
            gl->MemoryBarrier(VOXGI__GL_BUFFER_UPDATE_BARRIER_BIT);
            gl->GetNamedBufferSubData(svo->gl_child, 0, (ptrdiff_t)(svo->info.nodes * 4), child);
            gl->GetNamedBufferSubData(vol->region_buffer, 0, (ptrdiff_t)(level0 * 4), read);
            gl->GetNamedBufferSubData(vol->region_buffer, (ptrdiff_t)(vol->voxels * 4), (ptrdiff_t)(vol->region_count * 24), read + level0);
            r = voxgi__gl_check(ctx, "reading the regions");
        }
        W.child = child;
        W.level0 = read;
        W.box = read + level0;
    }
#endif
    if (r == VOXGI_OK) {
        voxgi__svo_region_slot(&W, 0, 0, root);
        memcpy(svo->regions + labels, W.box, vol->region_count * 24);
        svo->region_count = vol->region_count;
        svo->info.bytes += (labels + 6 * vol->region_count) * 4;
    }
#ifndef VOXGI_NO_GL
    if (r == VOXGI_OK && ctx->backend == VOXGI_BACKEND_GL) { /* the buffer alone */
        svo->gl_regions = voxgi__gl_buffer(ctx, (labels + 6 * vol->region_count) * 4, svo->regions);
        voxgi__free(ctx, svo->regions);
        svo->regions = NULL;
    }
#endif
    voxgi__free(ctx, child);
    voxgi__free(ctx, read);
    return r;
}

VOXGI_API voxgi_result voxgi_svo_create(voxgi_context *ctx, const voxgi_voxels *vx, const voxgi_svo_desc *desc, voxgi_svo **out)
{
    voxgi_svo *svo;
    voxgi__svo_levels L;
    uint32_t *packed = NULL;
    float *vals[VOXGI__VOLUME_SLOTS] = {NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    size_t n;
    double t0 = voxgi__now_ms(), t1;
    int depth = 1, lev, a;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!vx || !desc || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "voxels, desc or out is NULL");
    *out = NULL;
    if ((r = voxgi__svo_check(ctx, vx, desc, &depth)) != VOXGI_OK) return r;
    svo = (voxgi_svo *)voxgi__alloc_array(ctx, 1, sizeof *svo, 1);
    if (!svo) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the octree");
    memset(&L, 0, sizeof L);
    svo->info.grid = vx->info.grid;
    svo->info.backend = ctx->backend;
    svo->info.attributes = desc->attributes ? desc->attributes : vx->info.attributes;
    svo->info.depth = depth;
    svo->info.format = desc->format;
    if (desc->radiance) svo->info.attributes |= desc->radiance->info.attributes & VOXGI__RADIANCE_FAMILY;
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++) svo->slot_bytes[a] = (a == 3 ? 4 : 16) >> (desc->format == VOXGI_SVO_FLOAT16);
    n = (size_t)vx->info.voxel_count;
    r = voxgi__svo_leaves(ctx, svo, vx, desc, &L, &packed, vals);
#ifndef VOXGI_NO_GL
    if (packed) {
        svo->info.ms_sort = voxgi__now_ms() - t0;
        if (r == VOXGI_OK) r = voxgi__svo_build_gl(ctx, svo, n, packed, vals, desc);
    } else
#endif
    {
        if (r == VOXGI_OK) r = voxgi__sort_codes(ctx, L.codes[depth], L.order, n, 3 * depth);
        if (r == VOXGI_OK && voxgi__cancelled(ctx, 0.3, "octree build", "octree: voxels sorted")) r = VOXGI_ERR_CANCELLED;
        t1 = voxgi__now_ms();
        svo->info.ms_sort = t1 - t0;
        if (r == VOXGI_OK) r = voxgi__svo_nodes_cpu(ctx, svo, desc, n, &L);
        if (r == VOXGI_OK && voxgi__cancelled(ctx, 0.5, "octree build", "octree: nodes")) r = VOXGI_ERR_CANCELLED;
        t0 = voxgi__now_ms();
        svo->info.ms_nodes = t0 - t1;
        if (r == VOXGI_OK && desc->neighbours) {
            r = voxgi__svo_neighbours_cpu(ctx, svo, &L);
            svo->info.ms_neighbours = voxgi__now_ms() - t0;
            t0 = voxgi__now_ms();
        }
        if (r == VOXGI_OK) r = voxgi__svo_values_cpu(ctx, svo, &L, n, vals);
        svo->info.bytes += svo->info.structure_bytes + svo->info.neighbour_bytes + svo->info.brick_bytes;
        svo->info.ms_values = voxgi__now_ms() - t0;
    }
    voxgi__free(ctx, packed);
    for (lev = 0; lev <= VOXGI__MAX_LEVELS; lev++) voxgi__free(ctx, L.codes[lev]);
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++) voxgi__free(ctx, vals[a]);
    voxgi__free(ctx, L.order);
    if (r == VOXGI_OK && (svo->info.attributes & VOXGI_ATTRIBUTE_RADIANCE_SIDE)) r = voxgi__svo_regions(ctx, svo, desc->radiance);
    if (r != VOXGI_OK) { voxgi_svo_destroy(ctx, svo); return r; }
    svo->info.ms = svo->info.ms_sort + svo->info.ms_nodes + svo->info.ms_neighbours + svo->info.ms_values;
    *out = svo;
    return VOXGI_OK;
}

VOXGI_API void voxgi_svo_destroy(voxgi_context *ctx, voxgi_svo *svo)
{
    int a;
    if (!ctx || !svo) return;
    voxgi__free(ctx, svo->child);
    voxgi__free(ctx, svo->neighbour);
    voxgi__free(ctx, svo->regions);
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++) { voxgi__free(ctx, svo->node_values[a]); voxgi__free(ctx, svo->leaf_values[a]); }
#ifndef VOXGI_NO_GL
    voxgi__gl_delete_buffer(ctx, svo->gl_child);
    voxgi__gl_delete_buffer(ctx, svo->gl_neighbour);
    voxgi__gl_delete_buffer(ctx, svo->gl_regions);
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++) voxgi__gl_delete_buffer(ctx, svo->gl_values[a]);
#endif
    voxgi__free(ctx, svo);
}

VOXGI_API void voxgi_svo_query(const voxgi_svo *svo, voxgi_svo_info *out)
{
    if (!out) return;
    if (!svo) { memset(out, 0, sizeof *out); return; }
    *out = svo->info;
}

#ifndef VOXGI_NO_GL
/* GL: lookups (lookup = 1; points hold the coordinates' and the level's bits) or samples (xyz,
   lod) of attribute a at `count` points by shaders/svo_sample.glsl. */
static voxgi_result voxgi__svo_points_gl(voxgi_context *ctx, const voxgi_svo *svo, int a, int lookup, size_t count, const float *points,
                                         float *out)
{
    voxgi__gl *gl = ctx->gl;
    unsigned int bufs[2], p;
    float *got;
    size_t i;
    int w = a == 3 ? 1 : 4;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_svo_sample);
    if (r != VOXGI_OK || !count) return r;
    if (count > (size_t)65535 * 65535 * 64) return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%lu points in one call", (unsigned long)count);
    if (!(got = (float *)voxgi__alloc_array(ctx, count, 16, 0))) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu samples", (unsigned long)count);
    bufs[0] = voxgi__gl_buffer(ctx, count * 16, points);
    bufs[1] = voxgi__gl_buffer(ctx, count * 16, NULL);
    p = gl->prog_svo_sample;
    gl->UseProgram(p);
    voxgi__svo_bind_gl(ctx, svo, p, a);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 3, bufs[0]);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 4, bufs[1]);
    gl->ProgramUniform1ui(p, VOXGI__LOC_u_count, (unsigned)count);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_lookup, lookup);
    voxgi__gl_dispatch_rows(gl, count);
    voxgi__gl_unbind(gl);
    r = voxgi__gl_read_buffer(ctx, bufs[1], got, count * 16);
    for (i = 0; r == VOXGI_OK && i < count; i++) memcpy(out + (size_t)w * i, got + 4 * i + (w == 1 ? 3 : 0), (size_t)w * sizeof(float));
    voxgi__free(ctx, got);
    voxgi__gl_delete_buffer(ctx, bufs[0]);
    voxgi__gl_delete_buffer(ctx, bufs[1]);
    if (r == VOXGI_OK) r = voxgi__gl_check(ctx, "sampling the octree");
    return r;
}
#endif

VOXGI_API voxgi_result voxgi_svo_lookup(voxgi_context *ctx, const voxgi_svo *svo, voxgi_attribute which, int level, size_t count,
                                        const uint32_t *coords, float *out)
{
    int a = voxgi__attr_index(which), w = which == VOXGI_ATTRIBUTE_OPACITY ? 1 : 4, depth, ch;
    size_t i;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!svo || (count && (!coords || !out))) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "svo, coords or out is NULL");
    if (a < 0 || !(svo->info.attributes & (unsigned)which))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "attribute %d is not in this octree (0x%x)", (int)which, svo->info.attributes);
    depth = svo->info.depth;
    if (level < 0 || level > depth) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "level %d of 0..%d", level, depth);
#ifndef VOXGI_NO_GL
    if (svo->gl_child) {
        uint32_t *points = (uint32_t *)voxgi__alloc_array(ctx, count ? count : 1, 16, 0);
        voxgi_result r;
        if (!points) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu points", (unsigned long)count);
        for (i = 0; i < count; i++) { /* outside the cube: a coordinate the shader sees as outside too */
            int out_of_cube = (coords[3 * i] >> depth) || (coords[3 * i + 1] >> depth) || (coords[3 * i + 2] >> depth);
            for (ch = 0; ch < 3; ch++) points[4 * i + (size_t)ch] = out_of_cube ? 0xFFFFFFFFu : coords[3 * i + (size_t)ch];
            points[4 * i + 3] = (uint32_t)level;
        }
        r = voxgi__svo_points_gl(ctx, svo, a, 1, count, (const float *)(const void *)points, out);
        voxgi__free(ctx, points);
        return r;
    }
#endif
    for (i = 0; i < count; i++) {
        const uint32_t *v = coords + 3 * i;
        float c[4] = {0, 0, 0, 0};
        int found = !(v[0] >> depth) && !(v[1] >> depth) && !(v[2] >> depth), m;
        uint64_t node = 0;
        for (m = 1; m <= level && found; m++) { /* descend from the root */
            uint32_t ptr = svo->child[node], digit = ((v[0] >> (depth - m)) & 1u) | (((v[1] >> (depth - m)) & 1u) << 1) | (((v[2] >> (depth - m)) & 1u) << 2);
            found = ptr != 0;
            node = (m == depth ? 0u : 1u) + 8 * (uint64_t)(ptr - 1) + digit;
        }
        if (found) voxgi__svo_get(svo, a, level == depth ? svo->leaf_values[a] : svo->node_values[a], node, c);
        if (w == 1) out[i] = c[3];
        else for (ch = 0; ch < 4; ch++) out[4 * i + (size_t)ch] = c[ch];
    }
    return VOXGI_OK;
}

VOXGI_API voxgi_result voxgi_svo_node(voxgi_context *ctx, const voxgi_svo *svo, int level, const uint32_t coord[3], uint32_t *slot)
{
    int depth, m;
    uint64_t node = 0;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!svo || !coord || !slot) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "svo, coord or slot is NULL");
    depth = svo->info.depth;
    if (level < 0 || level >= depth) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "level %d: inner nodes are at 0..%d", level, depth - 1);
    *slot = 0;
    if ((coord[0] >> depth) || (coord[1] >> depth) || (coord[2] >> depth)) return VOXGI_OK;
    for (m = 1; m <= level; m++) {
        uint32_t ptr = voxgi__svo_child(ctx, svo, node), digit = ((coord[0] >> (depth - m)) & 1u) | (((coord[1] >> (depth - m)) & 1u) << 1) |
                                                 (((coord[2] >> (depth - m)) & 1u) << 2);
        if (!ptr) return VOXGI_OK;
        node = 1 + 8 * (uint64_t)(ptr - 1) + digit;
    }
    /* a slot of an existing tile whose node is absent has neither children nor a value: it is no node */
    if (level > 0 && !voxgi__svo_child(ctx, svo, node)) return VOXGI_OK;
    *slot = (uint32_t)node;
    return VOXGI_OK;
}

VOXGI_API voxgi_result voxgi_svo_neighbours(voxgi_context *ctx, const voxgi_svo *svo, uint32_t slot, uint32_t out[6])
{
    int d;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!svo || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "svo or out is NULL");
    if (!svo->neighbour && !svo->gl_neighbour) return voxgi__fail(ctx, VOXGI_ERR_UNSUPPORTED, "this octree was built without neighbour pointers");
    if ((uint64_t)slot >= svo->info.nodes) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "slot %u of %llu", slot, (unsigned long long)svo->info.nodes);
#ifndef VOXGI_NO_GL
    if (svo->gl_neighbour) {
        ctx->gl->MemoryBarrier(VOXGI__GL_BUFFER_UPDATE_BARRIER_BIT);
        ctx->gl->GetNamedBufferSubData(svo->gl_neighbour, (ptrdiff_t)(24 * (uint64_t)slot), 24, out);
        return voxgi__gl_check(ctx, "reading neighbour pointers");
    }
#endif
    for (d = 0; d < 6; d++) out[d] = svo->neighbour[6 * (uint64_t)slot + (uint64_t)d];
    return VOXGI_OK;
}

/* The octree as a sampling source: level k of the dense chain is octree level depth - k. */
typedef struct voxgi__svo_source { const voxgi_svo *svo; int a, w; } voxgi__svo_source;

/* The descent from the root toward the node of level `level` holding v (in that level's
   coordinates, inside the cube): the slot it reaches (a leaf slot at level depth) and that
   slot's level, short of `level` where a node there has no children. */
static int voxgi__svo_descend(const voxgi_svo *svo, int level, const int v[3], uint64_t *slot)
{
    int depth = svo->info.depth, m;
    uint64_t node = 0;
    for (m = 1; m <= level; m++) { /* v's bits from the top */
        uint32_t ptr = svo->child[node], digit = (uint32_t)(((v[0] >> (level - m)) & 1) | (((v[1] >> (level - m)) & 1) << 1) | (((v[2] >> (level - m)) & 1) << 2));
        if (!ptr) break;
        node = (m == depth ? 0u : 1u) + 8 * (uint64_t)(ptr - 1) + digit;
    }
    *slot = node;
    return m - 1;
}

static int voxgi__svo_fetch(const void *source, int k, const int v[3], float t[4])
{
    const voxgi__svo_source *s = (const voxgi__svo_source *)source;
    const voxgi_svo *svo = s->svo;
    int depth = svo->info.depth, level = depth - k;
    uint64_t node;
    float c[4];
    if (v[0] < 0 || v[1] < 0 || v[2] < 0 || (v[0] >> level) || (v[1] >> level) || (v[2] >> level)) return 0;
    if (voxgi__svo_descend(svo, level, v, &node) < level) return 0;
    voxgi__svo_get(svo, s->a, level == depth ? svo->leaf_values[s->a] : svo->node_values[s->a], node, c);
    if (s->w == 1) t[0] = c[3];
    else memcpy(t, c, sizeof c);
    return 1;
}

/* Trilinear at level k through one descent and a brick: the level-(k+1) node around p holds
   every value the sample needs; where an ancestor is missing and the sample's corners all lie
   in its box, the sample is empty. The same corners, weights and sums as voxgi__trilinear, so
   the same result bit for bit; 0 (use the lookups) where neither holds. */
static int voxgi__svo_brick_trilinear(const void *source, int w, int k, const float p[3], float out[4])
{
    const voxgi__svo_source *s = (const voxgi__svo_source *)source;
    const voxgi_svo *svo = s->svo;
    int depth = svo->info.depth, lev = depth - k - 1, m, a, corner, ch, i0[3]; /* the brick's node level */
    float wt[8], vals[8][4], sum[4];
    ptrdiff_t at[8];
    int64_t pc[3];
    uint64_t node = 0, b = (uint64_t)svo->slot_bytes[s->a];
    uint32_t ptr = 0;
    const unsigned char *brick;
    if (lev < 0) return 0;
    voxgi__corner_weights(p, k, i0, wt);
    for (a = 0; a < 3; a++) {
        double c = floor((double)p[a] / (double)(1 << (k + 1)));
        if (!(c >= 0 && c < ldexp(1.0, lev))) return 0; /* outside the cube (however far: checked before it becomes an int) */
        pc[a] = (int64_t)c;
    }
    for (m = 0; m <= lev; m++) {
        ptr = svo->child[node];
        if (!ptr) { /* no node at level m here: its box in level-(lev+1) units */
            int sh = lev + 1 - m;
            for (a = 0; a < 3; a++)
                if (i0[a] < (pc[a] >> (lev - m)) << sh || i0[a] + 1 >= ((pc[a] >> (lev - m)) + 1) << sh) return 0;
            for (ch = 0; ch < 4; ch++) out[ch] = 0;
            return 1;
        }
        if (m < lev)
            node = 1 + 8 * (uint64_t)(ptr - 1) + (uint64_t)(((pc[0] >> (lev - m - 1)) & 1) | (((pc[1] >> (lev - m - 1)) & 1) << 1) |
                                                            (((pc[2] >> (lev - m - 1)) & 1) << 2));
    }
    brick = svo->node_values[s->a] + (svo->info.nodes + 64 * voxgi__svo_brick_index(svo, lev, ptr)) * b;
    for (corner = 0; corner < 8; corner++) {
        int t = 0;
        for (a = 0; a < 3; a++) t += (int)(i0[a] + ((corner >> a) & 1) - (2 * pc[a] - 1)) << (2 * a);
        at[corner] = wt[corner] == 0 ? -1 : corner;
        if (wt[corner] == 0) continue;
        voxgi__svo_get(svo, s->a, brick, (uint64_t)t, vals[corner]);
        if (w == 1) vals[corner][0] = vals[corner][3];
    }
    voxgi__corner_sum(vals[0], at, wt, sum);
    for (ch = 0; ch < 4; ch++) out[ch] = ch < w ? sum[ch] : 0;
    return 1;
}

VOXGI_API voxgi_result voxgi_svo_brick(voxgi_context *ctx, const voxgi_svo *svo, voxgi_attribute which, int level, const uint32_t coord[3],
                                       float *out)
{
    int a = voxgi__attr_index(which), w = which == VOXGI_ATTRIBUTE_OPACITY ? 1 : 4, depth, t, ch;
    int64_t c[3];
    uint32_t ptr;
    uint64_t first, b;
    unsigned char raw[64 * 16];
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!svo || !coord || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "svo, coord or out is NULL");
    if (a < 0 || !(svo->info.attributes & (unsigned)which))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "attribute %d is not in this octree (0x%x)", (int)which, svo->info.attributes);
    if (!svo->bricks) return voxgi__fail(ctx, VOXGI_ERR_UNSUPPORTED, "this octree was built without bricks");
    depth = svo->info.depth;
    b = (uint64_t)svo->slot_bytes[a];
    if (level < 0 || level >= depth) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "level %d: bricks are at 0..%d", level, depth - 1);
    memset(out, 0, (size_t)(64 * w) * sizeof(float));
    for (t = 0; t < 3; t++) c[t] = (int64_t)(coord[t] >> (depth - level));
    if ((coord[0] >> depth) || (coord[1] >> depth) || (coord[2] >> depth) || !(ptr = voxgi__svo_ptr_at(ctx, svo, level, c))) return VOXGI_OK;
    first = (svo->info.nodes + 64 * voxgi__svo_brick_index(svo, level, ptr)) * b;
#ifndef VOXGI_NO_GL
    if (svo->gl_child) {
        ctx->gl->MemoryBarrier(VOXGI__GL_BUFFER_UPDATE_BARRIER_BIT);
        ctx->gl->GetNamedBufferSubData(svo->gl_values[a], (ptrdiff_t)first, (ptrdiff_t)(64 * b), raw);
    } else
#endif
        memcpy(raw, svo->node_values[a] + first, (size_t)(64 * b));
    for (t = 0; t < 64; t++) {
        float v[4];
        voxgi__svo_get(svo, a, raw, (uint64_t)t, v);
        for (ch = 0; ch < w; ch++) out[w * t + ch] = w == 1 ? v[3] : v[ch];
    }
    return VOXGI_OK;
}

VOXGI_API voxgi_result voxgi_svo_sample(voxgi_context *ctx, const voxgi_svo *svo, voxgi_attribute which, size_t count,
                                        const float *pos, const float *lods, float *out)
{
    voxgi__svo_source src;
    size_t i;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!svo || (count && (!pos || !lods || !out))) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "svo, positions, lods or out is NULL");
    src.svo = svo;
    src.a = voxgi__attr_index(which);
    src.w = which == VOXGI_ATTRIBUTE_OPACITY ? 1 : 4;
    if (src.a < 0 || !(svo->info.attributes & (unsigned)which))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "attribute %d is not in this octree (0x%x)", (int)which, svo->info.attributes);
    for (i = 0; i < count; i++)
        if (!isfinite(pos[3 * i]) || !isfinite(pos[3 * i + 1]) || !isfinite(pos[3 * i + 2]) || !isfinite(lods[i]))
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "point %lu is not finite", (unsigned long)i);
#ifndef VOXGI_NO_GL
    if (svo->gl_child) {
        float *points = (float *)voxgi__alloc_array(ctx, count ? count : 1, 16, 0);
        voxgi_result r;
        if (!points) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu points", (unsigned long)count);
        for (i = 0; i < count; i++) { memcpy(points + 4 * i, pos + 3 * i, 3 * sizeof(float)); points[4 * i + 3] = lods[i]; }
        r = voxgi__svo_points_gl(ctx, svo, src.a, 0, count, points, out);
        voxgi__free(ctx, points);
        return r;
    }
#endif
    for (i = 0; i < count; i++)
        voxgi__sample_lod(voxgi__svo_fetch, svo->info.brick_bytes ? voxgi__svo_brick_trilinear : NULL, &src, src.w, svo->info.depth + 1, pos + 3 * i, lods[i], out + (size_t)src.w * i);
    return VOXGI_OK;
}

/* ----- octree files: the header (VOXGI__SVO_HEADER bytes, little-endian), then the arrays in the
   order docs/volumes-and-octrees.md lists. Values keep their stored format (half floats stay
   half), so a read octree is the written one bit for bit. */
#define VOXGI__SVO_MAGIC "VOXGISVO"
#define VOXGI__SVO_VERSION 1u
#define VOXGI__SVO_HEADER 232
#define VOXGI__SVO_NEIGHBOURS 1u
#define VOXGI__SVO_BRICKS 2u

/* Where the bytes go: memory, a file, or nowhere (counting). */
typedef struct voxgi__svo_sink {
    unsigned char *buf;
    FILE *f;
    uint64_t at;
    int failed;
} voxgi__svo_sink;

static void voxgi__svo_put_bytes(voxgi__svo_sink *w, const void *p, size_t n)
{
    if (w->buf) memcpy(w->buf + w->at, p, n);
    if (w->f && !w->failed && fwrite(p, 1, n, w->f) != n) w->failed = 1;
    w->at += n;
}

/* n words of `width` bytes (1, 2, 4 or 8) from host order to little-endian, through a staging buffer. */
static void voxgi__svo_put_words(voxgi__svo_sink *w, const void *src, uint64_t n, int width)
{
    unsigned char stage[4096];
    const unsigned char *s = (const unsigned char *)src;
    uint64_t i;
    size_t k = 0;
    for (i = 0; i < n; i++) {
        uint64_t v = 0;
        int b;
        if (width == 2) { uint16_t x; memcpy(&x, s + 2 * i, 2); v = x; }
        else if (width == 4) { uint32_t x; memcpy(&x, s + 4 * i, 4); v = x; }
        else { memcpy(&v, s + 8 * i, 8); }
        for (b = 0; b < width; b++) stage[k++] = (unsigned char)(v >> (8 * b));
        if (k + 8 > sizeof stage) { voxgi__svo_put_bytes(w, stage, k); k = 0; }
    }
    if (k) voxgi__svo_put_bytes(w, stage, k);
}

static uint64_t voxgi__svo_le(const unsigned char *p, int width)
{
    uint64_t v = 0;
    int b;
    for (b = width - 1; b >= 0; b--) v = v << 8 | p[b];
    return v;
}

/* n little-endian words of `width` bytes into host order. */
static void voxgi__svo_get_words(void *dst, const unsigned char *p, uint64_t n, int width)
{
    unsigned char *d = (unsigned char *)dst;
    uint64_t i;
    for (i = 0; i < n; i++) {
        uint64_t v = voxgi__svo_le(p + (size_t)i * (size_t)width, width);
        if (width == 2) { uint16_t x = (uint16_t)v; memcpy(d + 2 * i, &x, 2); }
        else { uint32_t x = (uint32_t)v; memcpy(d + 4 * i, &x, 4); }
    }
}

/* The arrays' sizes in bytes, from the header's counts (all below 2^40 after the header checks). */
typedef struct voxgi__svo_layout {
    uint64_t nodes, leaf_slots, bricks, region_words, total;
    int slot_bytes[VOXGI__VOLUME_SLOTS];
} voxgi__svo_layout;

static void voxgi__svo_layout_of(const voxgi_svo_info *info, uint64_t inner_tiles, unsigned flags, uint64_t region_count, voxgi__svo_layout *L)
{
    int a, lev;
    L->nodes = 1 + 8 * inner_tiles;
    L->leaf_slots = 8 * info->level_nodes[info->depth - 1];
    L->bricks = 0;
    if (flags & VOXGI__SVO_BRICKS)
        for (lev = 0; lev < info->depth; lev++) L->bricks += info->level_nodes[lev];
    L->region_words = region_count ? L->nodes + L->leaf_slots + 6 * region_count : 0;
    L->total = VOXGI__SVO_HEADER + 4 * L->nodes + (flags & VOXGI__SVO_NEIGHBOURS ? 24 * L->nodes : 0) + 4 * L->region_words;
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++) {
        L->slot_bytes[a] = (a == 3 ? 4 : 16) >> (info->format == VOXGI_SVO_FLOAT16);
        if (info->attributes & (1u << a)) L->total += (L->nodes + 64 * L->bricks + L->leaf_slots) * (uint64_t)L->slot_bytes[a];
    }
}

/* Writes the whole file to w from CPU arrays (a GL octree's are read back first). */
static void voxgi__svo_emit(voxgi__svo_sink *w, const voxgi_svo *svo, uint32_t *arrays[3], unsigned char *values[VOXGI__VOLUME_SLOTS][2])
{
    const voxgi_svo_info *info = &svo->info;
    unsigned flags = (svo->info.neighbour_bytes ? VOXGI__SVO_NEIGHBOURS : 0u) | (svo->bricks ? VOXGI__SVO_BRICKS : 0u);
    uint32_t u[7];
    uint64_t v[20];
    voxgi__svo_layout L;
    int a, width = info->format == VOXGI_SVO_FLOAT16 ? 2 : 4;
    voxgi__svo_layout_of(info, svo->inner_tiles, flags, svo->region_count, &L);
    voxgi__svo_put_bytes(w, VOXGI__SVO_MAGIC, 8);
    u[0] = VOXGI__SVO_VERSION;
    u[1] = flags;
    voxgi__svo_put_words(w, u, 2, 4);
    voxgi__svo_put_words(w, info->grid.origin, 3, 8);
    voxgi__svo_put_words(w, &info->grid.voxel_size, 1, 8);
    u[0] = (uint32_t)info->grid.res[0]; u[1] = (uint32_t)info->grid.res[1]; u[2] = (uint32_t)info->grid.res[2];
    u[3] = (uint32_t)info->depth; u[4] = info->attributes; u[5] = (uint32_t)info->format;
    voxgi__svo_put_words(w, u, 6, 4);
    v[0] = svo->inner_tiles;
    memcpy(v + 1, info->level_nodes, sizeof info->level_nodes);
    v[18] = svo->region_count;
    v[19] = L.total;
    voxgi__svo_put_words(w, v, 20, 8);
    voxgi__svo_put_words(w, arrays[0], L.nodes, 4);
    if (flags & VOXGI__SVO_NEIGHBOURS) voxgi__svo_put_words(w, arrays[1], 6 * L.nodes, 4);
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++)
        if (info->attributes & (1u << a)) {
            voxgi__svo_put_words(w, values[a][0], (L.nodes + 64 * L.bricks) * (uint64_t)L.slot_bytes[a] / (uint64_t)width, width);
            voxgi__svo_put_words(w, values[a][1], L.leaf_slots * (uint64_t)L.slot_bytes[a] / (uint64_t)width, width);
        }
    if (L.region_words) voxgi__svo_put_words(w, arrays[2], L.region_words, 4);
}

/* Writes through the sink; a GL octree's buffers are read back into temporary arrays first. */
static voxgi_result voxgi__svo_write_to(voxgi_context *ctx, const voxgi_svo *svo, voxgi__svo_sink *w)
{
    uint32_t *arrays[3];
    unsigned char *values[VOXGI__VOLUME_SLOTS][2];
    voxgi_result r = VOXGI_OK;
    int a;
    (void)ctx; /* used by the GL read-back alone */
    arrays[0] = svo->child; arrays[1] = svo->neighbour; arrays[2] = svo->regions;
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++) { values[a][0] = svo->node_values[a]; values[a][1] = svo->leaf_values[a]; }
#ifndef VOXGI_NO_GL
    if (svo->gl_child) {
        voxgi__gl *gl = ctx && ctx->backend == VOXGI_BACKEND_GL ? ctx->gl : NULL;
        voxgi__svo_layout L;
        voxgi__svo_layout_of(&svo->info, svo->inner_tiles, (svo->info.neighbour_bytes ? VOXGI__SVO_NEIGHBOURS : 0u) | (svo->bricks ? VOXGI__SVO_BRICKS : 0u),
                             svo->region_count, &L);
        memset(arrays, 0, sizeof arrays);
        memset(values, 0, sizeof values);
        if (!gl) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "a GL octree is written with its GL context");
        gl->MemoryBarrier(VOXGI__GL_BUFFER_UPDATE_BARRIER_BIT);
        if (!(arrays[0] = (uint32_t *)voxgi__alloc_array(ctx, (size_t)L.nodes, 4, 0)) ||
            (svo->gl_neighbour && !(arrays[1] = (uint32_t *)voxgi__alloc_array(ctx, (size_t)L.nodes, 24, 0))) ||
            (L.region_words && !(arrays[2] = (uint32_t *)voxgi__alloc_array(ctx, (size_t)L.region_words, 4, 0))))
            r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory to read the octree back");
        if (r == VOXGI_OK) {
            gl->GetNamedBufferSubData(svo->gl_child, 0, (ptrdiff_t)(4 * L.nodes), arrays[0]);
            if (arrays[1]) gl->GetNamedBufferSubData(svo->gl_neighbour, 0, (ptrdiff_t)(24 * L.nodes), arrays[1]);
            if (arrays[2]) gl->GetNamedBufferSubData(svo->gl_regions, 0, (ptrdiff_t)(4 * L.region_words), arrays[2]);
        }
        for (a = 0; a < VOXGI__VOLUME_SLOTS && r == VOXGI_OK; a++) { /* node values and bricks, then the leaves from gl_leaf_first */
            uint64_t node_bytes = (L.nodes + 64 * L.bricks) * (uint64_t)L.slot_bytes[a], leaf_bytes = L.leaf_slots * (uint64_t)L.slot_bytes[a];
            if (!(svo->info.attributes & (1u << a))) continue;
            if (!(values[a][0] = (unsigned char *)voxgi__alloc_array(ctx, (size_t)node_bytes, 1, 0)) ||
                !(values[a][1] = (unsigned char *)voxgi__alloc_array(ctx, (size_t)(leaf_bytes ? leaf_bytes : 1), 1, 0))) {
                r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory to read the octree back");
                break;
            }
            gl->GetNamedBufferSubData(svo->gl_values[a], 0, (ptrdiff_t)node_bytes, values[a][0]);
            if (leaf_bytes) gl->GetNamedBufferSubData(svo->gl_values[a], (ptrdiff_t)(4 * (uint64_t)svo->gl_leaf_first[a]), (ptrdiff_t)leaf_bytes, values[a][1]);
        }
        if (r == VOXGI_OK) r = voxgi__gl_check(ctx, "reading the octree back");
        if (r == VOXGI_OK) voxgi__svo_emit(w, svo, arrays, values);
        for (a = 0; a < 3; a++) voxgi__free(ctx, arrays[a]);
        for (a = 0; a < VOXGI__VOLUME_SLOTS; a++) { voxgi__free(ctx, values[a][0]); voxgi__free(ctx, values[a][1]); }
        return r;
    }
#endif
    voxgi__svo_emit(w, svo, arrays, values);
    return r;
}

VOXGI_API voxgi_result voxgi_svo_write_memory(voxgi_context *ctx, const voxgi_svo *svo, void *data, size_t capacity, size_t *size)
{
    voxgi__svo_sink w;
    voxgi__svo_layout L;
    if (!svo || !size) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "svo or size is NULL");
    voxgi__svo_layout_of(&svo->info, svo->inner_tiles, (svo->info.neighbour_bytes ? VOXGI__SVO_NEIGHBOURS : 0u) | (svo->bricks ? VOXGI__SVO_BRICKS : 0u),
                         svo->region_count, &L);
    if (L.total > (uint64_t)(size_t)-1) return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "the octree's file needs %llu bytes", (unsigned long long)L.total);
    *size = (size_t)L.total;
    if (!data) return VOXGI_OK;
    if (capacity < *size)
        return voxgi__fail(ctx, VOXGI_ERR_BUFFER_TOO_SMALL, "the octree needs %lu bytes, the buffer holds %lu", (unsigned long)*size, (unsigned long)capacity);
    memset(&w, 0, sizeof w);
    w.buf = (unsigned char *)data;
    return voxgi__svo_write_to(ctx, svo, &w);
}

VOXGI_API voxgi_result voxgi_svo_write(voxgi_context *ctx, const voxgi_svo *svo, const char *path)
{
    voxgi__svo_sink w;
    voxgi_result r;
    if (!svo || !path) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "svo or path is NULL");
    memset(&w, 0, sizeof w);
    if (!(w.f = fopen(path, "wb"))) return voxgi__fail(ctx, VOXGI_ERR_IO, "cannot write %s: %s", path, strerror(errno));
    r = voxgi__svo_write_to(ctx, svo, &w);
    if (fclose(w.f) != 0) w.failed = 1;
    if (r == VOXGI_OK && w.failed) r = voxgi__fail(ctx, VOXGI_ERR_IO, "writing %s failed after byte %llu: %s", path, (unsigned long long)w.at, strerror(errno));
    return r;
}

/* The header's refusals, against the file's length `size`: *info, the tiles, flags and region
   count on success. Nothing is allocated before this has passed, and then no more than the file. */
static voxgi_result voxgi__svo_header(voxgi_context *ctx, const unsigned char *h, uint64_t size, voxgi_svo_info *info, uint64_t *inner_tiles,
                                      unsigned *flags, uint64_t *region_count, voxgi__svo_layout *L)
{
    uint64_t tiles = 0, at;
    unsigned version, side = VOXGI_ATTRIBUTE_RADIANCE_BACK | VOXGI_ATTRIBUTE_RADIANCE_SIDE, family;
    int a, lev, depth = 1, maxres = 0;
    if (size < VOXGI__SVO_HEADER)
        return voxgi__fail(ctx, VOXGI_ERR_FORMAT, "octree file truncated at byte %llu: the header has %d bytes", (unsigned long long)size, VOXGI__SVO_HEADER);
    if (memcmp(h, VOXGI__SVO_MAGIC, 8)) return voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte 0: not a voxgi octree file (no magic \"%s\")", VOXGI__SVO_MAGIC);
    if ((version = (unsigned)voxgi__svo_le(h + 8, 4)) != VOXGI__SVO_VERSION)
        return voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte 8: octree file version %u, this library reads version %u", version, VOXGI__SVO_VERSION);
    if ((*flags = (unsigned)voxgi__svo_le(h + 12, 4)) & ~(VOXGI__SVO_NEIGHBOURS | VOXGI__SVO_BRICKS))
        return voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte 12: unknown flags 0x%x", *flags);
    memset(info, 0, sizeof *info);
    for (a = 0; a < 4; a++) {
        uint64_t bits = voxgi__svo_le(h + 16 + 8 * a, 8);
        double d;
        memcpy(&d, &bits, 8);
        if (!isfinite(d) || (a == 3 && !(d > 0))) return voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte %d: grid %s %g", 16 + 8 * a, a == 3 ? "voxel size" : "origin", d);
        if (a < 3) info->grid.origin[a] = d;
        else info->grid.voxel_size = d;
    }
    for (a = 0; a < 3; a++) {
        uint64_t r = voxgi__svo_le(h + 48 + 4 * a, 4);
        if (r < 1 || r > VOXGI_MAX_RES) return voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte %d: grid resolution %llu outside 1..%d", 48 + 4 * a, (unsigned long long)r, VOXGI_MAX_RES);
        info->grid.res[a] = (int)r;
        maxres = VOXGI__MAX(maxres, (int)r);
    }
    while ((1 << depth) < maxres) depth++;
    if (voxgi__svo_le(h + 60, 4) != (uint64_t)depth)
        return voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte 60: depth %llu, the grid's is %d", (unsigned long long)voxgi__svo_le(h + 60, 4), depth);
    info->depth = depth;
    info->attributes = (unsigned)voxgi__svo_le(h + 64, 4);
    family = info->attributes & VOXGI__RADIANCE_FAMILY;
    if (!info->attributes || info->attributes >> VOXGI__VOLUME_SLOTS || (family && family != VOXGI_ATTRIBUTE_RADIANCE && family != VOXGI__RADIANCE_FAMILY))
        return voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte 64: attributes 0x%x (none, unknown bits, or a radiance side without the rest)", info->attributes);
    if (voxgi__svo_le(h + 68, 4) > 1) return voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte 68: value format %llu", (unsigned long long)voxgi__svo_le(h + 68, 4));
    info->format = (voxgi_svo_format)voxgi__svo_le(h + 68, 4);
    *inner_tiles = voxgi__svo_le(h + 72, 8);
    for (lev = 0; lev < 17; lev++) {
        uint64_t n = voxgi__svo_le(h + 80 + 8 * lev, 8);
        /* one root; at most 8 children per node (so no count passes 2^52); nothing below the leaves */
        if ((lev == 0 && n != 1) || (lev > 0 && n > 8 * info->level_nodes[lev - 1]) || (lev > depth && n))
            return voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte %d: %llu nodes at level %d", 80 + 8 * lev, (unsigned long long)n, lev);
        info->level_nodes[lev] = n;
        if (lev < depth - 1) tiles += n;
    }
    if (*inner_tiles != tiles)
        return voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte 72: %llu inner tiles, the levels' nodes make %llu", (unsigned long long)*inner_tiles, (unsigned long long)tiles);
    if (info->level_nodes[depth] > 8 * info->level_nodes[depth - 1] || 1 + 8 * tiles > (uint64_t)UINT32_MAX || 8 * info->level_nodes[depth - 1] > (uint64_t)UINT32_MAX)
        return voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte 80: %llu node slots exceed the 32-bit indices", (unsigned long long)(1 + 8 * tiles));
    *region_count = voxgi__svo_le(h + 216, 8);
    if (*region_count && (*region_count <= 2 || (info->attributes & side) != side || *region_count > VOXGI__REGION_BYTES / 24))
        return voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte 216: %llu regions in an octree of attributes 0x%x", (unsigned long long)*region_count, info->attributes);
    voxgi__svo_layout_of(info, tiles, *flags, *region_count, L);
    if ((at = voxgi__svo_le(h + 224, 8)) != L->total)
        return voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte 224: the file claims %llu bytes, its counts make %llu", (unsigned long long)at, (unsigned long long)L->total);
    if (size != L->total)
        return voxgi__fail(ctx, VOXGI_ERR_FORMAT, size < L->total ? "octree file truncated at byte %llu of %llu" : "octree file has %llu bytes, its counts make %llu",
                           (unsigned long long)size, (unsigned long long)L->total);
    return VOXGI_OK;
}

/* The child pointers form the tree the counts say: from the root down, a node of an inner level
   points to an unused inner tile, one of level depth - 1 to an unused leaf tile, and each level
   has its number of nodes; so every descent stays in the arrays. */
static voxgi_result voxgi__svo_check_tree(voxgi_context *ctx, const voxgi_svo *svo, uint64_t child_at)
{
    const uint32_t *child = svo->child;
    int depth = svo->info.depth, lev;
    uint64_t leaf_tiles = svo->info.level_nodes[depth - 1], head = 0, tail = 0, level_end, slot, seen_leaves = 0;
    uint32_t *queue = (uint32_t *)voxgi__alloc_array(ctx, (size_t)(svo->inner_tiles ? svo->inner_tiles : 1), 4, 0);
    unsigned char *used = (unsigned char *)voxgi__alloc_array(ctx, (size_t)(svo->inner_tiles + leaf_tiles + 1), 1, 1);
    voxgi_result r = VOXGI_OK;
    if (!queue || !used) { r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory to check the octree"); goto done; }
    for (lev = 0; lev < depth && r == VOXGI_OK; lev++) {
        uint64_t found = 0;
        level_end = tail;
        for (slot = 0; ; slot++) { /* level 0: the root; below: the slots of the tiles queued by the level above */
            uint64_t s, t;
            uint32_t ptr;
            if (lev == 0) { if (slot) break; s = 0; }
            else { if (head >= level_end) break; s = 1 + 8 * (uint64_t)queue[head] + (slot & 7u); if ((slot & 7u) == 7u) head++; }
            if (!(ptr = child[s])) continue;
            found++;
            t = (uint64_t)ptr - 1;
            if (lev < depth - 1 ? t >= svo->inner_tiles || used[t] : t >= leaf_tiles || used[svo->inner_tiles + t]) {
                r = voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte %llu: child pointer %u of a level-%d node is out of range or used twice",
                                (unsigned long long)(child_at + 4 * s), ptr, lev);
                break;
            }
            if (lev < depth - 1) { used[t] = 1; queue[tail++] = (uint32_t)t; }
            else { used[svo->inner_tiles + t] = 1; seen_leaves++; }
        }
        if (r == VOXGI_OK && lev > 0 && found != svo->info.level_nodes[lev])
            r = voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte %d: %llu nodes at level %d, the child pointers make %llu", 80 + 8 * lev,
                            (unsigned long long)svo->info.level_nodes[lev], lev, (unsigned long long)found);
    }
    if (r == VOXGI_OK && (tail != svo->inner_tiles || seen_leaves != leaf_tiles))
        r = voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte %llu: the child pointers reach %llu of %llu tiles", (unsigned long long)child_at,
                        (unsigned long long)(tail + seen_leaves), (unsigned long long)(svo->inner_tiles + leaf_tiles));
done:
    voxgi__free(ctx, queue);
    voxgi__free(ctx, used);
    return r;
}

#ifndef VOXGI_NO_GL
/* A read octree onto a GL context: its arrays into the buffers a GL build makes (the same bytes, each
   attribute's leaf values from word gl_leaf_first), then the CPU arrays freed, as a GL octree holds none. */
static voxgi_result voxgi__svo_upload_gl(voxgi_context *ctx, voxgi_svo *svo, const voxgi__svo_layout *L)
{
    voxgi__gl *gl = ctx->gl;
    voxgi_result r;
    int a;
    svo->gl_child = voxgi__gl_buffer(ctx, (size_t)L->nodes * 4, svo->child);
    if (svo->neighbour) svo->gl_neighbour = voxgi__gl_buffer(ctx, (size_t)L->nodes * 24, svo->neighbour);
    if (svo->regions) svo->gl_regions = voxgi__gl_buffer(ctx, (size_t)L->region_words * 4, svo->regions);
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++) {
        uint64_t node_bytes = (L->nodes + 64 * L->bricks) * (uint64_t)L->slot_bytes[a], leaf_bytes = L->leaf_slots * (uint64_t)L->slot_bytes[a];
        if (!(svo->info.attributes & (1u << a))) continue;
        svo->gl_leaf_first[a] = (uint32_t)((node_bytes + 3) / 4);
        svo->gl_values[a] = voxgi__gl_buffer(ctx, (size_t)(4 * (uint64_t)svo->gl_leaf_first[a] + (leaf_bytes + 3) / 4 * 4), NULL);
        gl->NamedBufferSubData(svo->gl_values[a], 0, (ptrdiff_t)node_bytes, svo->node_values[a]);
        if (leaf_bytes) gl->NamedBufferSubData(svo->gl_values[a], (ptrdiff_t)(4 * (uint64_t)svo->gl_leaf_first[a]), (ptrdiff_t)leaf_bytes, svo->leaf_values[a]);
        voxgi__free(ctx, svo->node_values[a]);
        voxgi__free(ctx, svo->leaf_values[a]);
        svo->node_values[a] = svo->leaf_values[a] = NULL;
    }
    voxgi__free(ctx, svo->child);
    voxgi__free(ctx, svo->neighbour);
    voxgi__free(ctx, svo->regions);
    svo->child = svo->neighbour = svo->regions = NULL;
    svo->info.backend = VOXGI_BACKEND_GL;
    if ((r = voxgi__gl_check(ctx, "uploading the octree read")) != VOXGI_OK) return r;
    return VOXGI_OK;
}
#endif

VOXGI_API voxgi_result voxgi_svo_read_memory(voxgi_context *ctx, const void *data, size_t size, voxgi_svo **out)
{
    const unsigned char *p = (const unsigned char *)data;
    voxgi_svo_info info;
    voxgi_svo_desc desc;
    voxgi__svo_layout L;
    voxgi_svo *svo;
    uint64_t tiles, region_count, at, i;
    unsigned flags;
    voxgi_result r;
    int a, width;
    if (out) *out = NULL;
    if (!ctx || !out || (!data && size)) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "ctx, data or out is NULL");
    if ((r = voxgi__svo_header(ctx, p, size, &info, &tiles, &flags, &region_count, &L)) != VOXGI_OK) return r;
    if (!(svo = (voxgi_svo *)voxgi__alloc_array(ctx, 1, sizeof *svo, 1))) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the octree");
    svo->info = info;
    svo->info.backend = VOXGI_BACKEND_CPU;
    memset(&desc, 0, sizeof desc);
    desc.neighbours = (flags & VOXGI__SVO_NEIGHBOURS) != 0;
    desc.bricks = (flags & VOXGI__SVO_BRICKS) != 0;
    width = info.format == VOXGI_SVO_FLOAT16 ? 2 : 4;
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++) svo->slot_bytes[a] = L.slot_bytes[a];
    if ((r = voxgi__svo_size(ctx, svo, tiles, &desc)) != VOXGI_OK) goto fail; /* the 32-bit indices and the memory budget */
    at = VOXGI__SVO_HEADER;
    if (!(svo->child = (uint32_t *)voxgi__alloc_array(ctx, (size_t)L.nodes, 4, 0))) goto oom;
    voxgi__svo_get_words(svo->child, p + at, L.nodes, 4);
    if ((r = voxgi__svo_check_tree(ctx, svo, at)) != VOXGI_OK) goto fail;
    at += 4 * L.nodes;
    if (desc.neighbours) {
        if (!(svo->neighbour = (uint32_t *)voxgi__alloc_array(ctx, (size_t)L.nodes, 24, 0))) goto oom;
        voxgi__svo_get_words(svo->neighbour, p + at, 6 * L.nodes, 4);
        for (i = 0; i < 6 * L.nodes; i++)
            if (svo->neighbour[i] >= L.nodes) {
                r = voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte %llu: neighbour slot %u of %llu", (unsigned long long)(at + 4 * i), svo->neighbour[i], (unsigned long long)L.nodes);
                goto fail;
            }
        at += 24 * L.nodes;
    }
    for (a = 0; a < VOXGI__VOLUME_SLOTS; a++) {
        uint64_t b = (uint64_t)L.slot_bytes[a], node_bytes = (L.nodes + 64 * L.bricks) * b, leaf_bytes = L.leaf_slots * b;
        if (!(info.attributes & (1u << a))) continue;
        if (!(svo->node_values[a] = (unsigned char *)voxgi__alloc_array(ctx, (size_t)node_bytes, 1, 0)) ||
            !(svo->leaf_values[a] = (unsigned char *)voxgi__alloc_array(ctx, (size_t)(leaf_bytes ? leaf_bytes : b), 1, 0)))
            goto oom;
        voxgi__svo_get_words(svo->node_values[a], p + at, node_bytes / (uint64_t)width, width);
        voxgi__svo_get_words(svo->leaf_values[a], p + at + node_bytes, leaf_bytes / (uint64_t)width, width);
        at += node_bytes + leaf_bytes;
        svo->info.bytes += (size_t)((L.nodes + L.leaf_slots) * b);
        svo->info.dense_bytes += (size_t)(voxgi_grid_voxel_count(&info.grid) * b);
    }
    svo->info.bytes += svo->info.structure_bytes + svo->info.neighbour_bytes + svo->info.brick_bytes;
    if (region_count) {
        uint64_t labels = L.nodes + L.leaf_slots;
        if (!(svo->regions = (uint32_t *)voxgi__alloc_array(ctx, (size_t)L.region_words, 4, 0))) goto oom;
        voxgi__svo_get_words(svo->regions, p + at, L.region_words, 4);
        for (i = 0; i < labels; i++) { /* labels index the bounds: MIXED, or a label below the count; flags only on a voxel
                                          (a leaf slot), UNSEEN with BORDER, as voxgi__volume_regions makes them */
            uint32_t l = svo->regions[i], flags = l & (VOXGI__REGION_BORDER | VOXGI__REGION_UNSEEN);
            if (l != VOXGI__REGION_MIXED && (VOXGI__REGION_OF(l) >= region_count || (flags && (i < L.nodes || !(l & VOXGI__REGION_BORDER))))) {
                r = voxgi__fail(ctx, VOXGI_ERR_FORMAT, "byte %llu: region label 0x%x of %llu regions (%s)", (unsigned long long)(at + 4 * i), l,
                                (unsigned long long)region_count, i < L.nodes ? "a node's" : "a voxel's");
                goto fail;
            }
        }
        svo->region_count = (size_t)region_count;
        svo->info.bytes += (size_t)(4 * L.region_words);
    }
#ifndef VOXGI_NO_GL
    if (ctx->backend == VOXGI_BACKEND_GL && (r = voxgi__svo_upload_gl(ctx, svo, &L)) != VOXGI_OK) goto fail;
#endif
    *out = svo;
    return VOXGI_OK;
oom:
    r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the octree read");
fail:
    voxgi_svo_destroy(ctx, svo);
    return r;
}

VOXGI_API voxgi_result voxgi_svo_read(voxgi_context *ctx, const char *path, voxgi_svo **out)
{
    unsigned char head[VOXGI__SVO_HEADER], *all = NULL;
    voxgi_svo_info info;
    voxgi__svo_layout L;
    uint64_t tiles, region_count;
    unsigned flags;
    long length;
    size_t got;
    voxgi_result r;
    FILE *f;
    if (out) *out = NULL;
    if (!ctx || !path || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "ctx, path or out is NULL");
    if (!(f = fopen(path, "rb"))) return voxgi__fail(ctx, VOXGI_ERR_IO, "cannot read %s: %s", path, strerror(errno));
    if (fseek(f, 0, SEEK_END) != 0 || (length = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        return voxgi__fail(ctx, VOXGI_ERR_IO, "cannot find the length of %s: %s", path, strerror(errno));
    }
    /* the header against the file's length first, so that no count in it sizes an allocation */
    got = fread(head, 1, sizeof head, f);
    r = voxgi__svo_header(ctx, head, (uint64_t)length < got ? got : (uint64_t)length, &info, &tiles, &flags, &region_count, &L);
    if (r == VOXGI_OK && !(all = (unsigned char *)voxgi__alloc(ctx, (size_t)length))) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %s", path);
    if (r == VOXGI_OK) {
        memcpy(all, head, sizeof head);
        if (fread(all + sizeof head, 1, (size_t)length - sizeof head, f) != (size_t)length - sizeof head)
            r = voxgi__fail(ctx, VOXGI_ERR_IO, "reading %s failed: %s", path, ferror(f) ? strerror(errno) : "it ended early");
    }
    fclose(f);
    if (r == VOXGI_OK) r = voxgi_svo_read_memory(ctx, all, (size_t)length, out);
    voxgi__free(ctx, all);
    if (r != VOXGI_OK && r != VOXGI_ERR_IO && r != VOXGI_ERR_OUT_OF_MEMORY) { /* name the file in the message */
        size_t n = strlen(path) + 2, len = strlen(ctx->error);
        if (n + len < sizeof ctx->error) {
            memmove(ctx->error + n, ctx->error, len + 1);
            memcpy(ctx->error, path, n - 2);
            memcpy(ctx->error + n - 2, ": ", 2);
        }
    }
    return r;
}
#endif /* VOXGI_NO_OCTREE */

/* ===================================================================== 8. cone tracing */
#ifndef VOXGI_NO_CONE_TRACING

/* Cone k of n: a direction in the frame (t, b, normal), on a Fibonacci spiral of the projected
   disc (equal cosine-weighted shares). */
static void voxgi__cone_direction(int k, int n, double d[3])
{
    double r = sqrt((k + 0.5) / n), phi = 2.399963229728653 * k; /* the golden angle */
    d[0] = r * cos(phi);
    d[1] = r * sin(phi);
    d[2] = sqrt(VOXGI__MAX(0.0, 1 - r * r));
}

typedef struct voxgi__cone_job {
    const voxgi_volume *vol;      /* the radiance: a volume, */
#ifndef VOXGI_NO_OCTREE
    const voxgi_svo *svo;         /* or an octree */
#endif
    const voxgi_grid *grid;
    int levels;                   /* mip levels (an octree: depth + 1) */
    const voxgi_cone_desc *desc;
    const float *pos, *nrm;
    const voxgi_cone *list;       /* single cones, or NULL */
    float *irr, *occ;
    int cones, dirs;
    int two_sided;                /* the source holds RADIANCE_BACK and RADIANCE_SIDE */
    int enclosed;                 /* and its empty space has enclosed regions (voxgi__volume_regions), */
    const uint32_t *regions;      /* on the CPU these labels (a volume's or an octree's), */
    const uint32_t *boxes;        /* with these bounds */
    int dims[VOXGI__MAX_LEVELS][3]; /* each level's size */
    const float *level_at[3][6][VOXGI__MAX_LEVELS]; /* a volume's levels: [slot - RADIANCE_SLOT][direction][level] */
    double half_tan, step, offset, max_dist;
    int seen_from_eye;            /* desc's, and its eye in grid units (float, as GL has it) */
    float eye[3];
} voxgi__cone_job;

/* How much more a sample covers where its surfaces face away from the cone's origin: a cone
   leaving through the back of a surface is leaving a closed object or passing behind a wall, and
   a coarse level's share of a thin wall would let it through (docs/cone-tracing.md). */
#define VOXGI__BACK_COVERAGE 2.0f

#ifndef VOXGI_NO_OCTREE
/* The slot of an octree's node of level-k voxel v (a leaf slot at k = 0), -1 where there is none. */
static ptrdiff_t voxgi__svo_slot_at(const voxgi_svo *svo, int k, const int v[3])
{
    uint64_t slot;
    return voxgi__svo_descend(svo, svo->info.depth - k, v, &slot) == svo->info.depth - k ? (ptrdiff_t)slot : -1;
}
#endif

/* The 8 corners of a trilinear sample of level k at p, as voxgi__trilinear visits them: their
   voxels (v, or NULL where the caller needs none), weights in float (0 beyond the grid) and where
   their values are (-1: nowhere, or of weight 0): a volume's voxel offset within the level, an
   octree's slot. */
static void voxgi__cone_corners(const voxgi__cone_job *J, int k, const float p[3], int v_out[8][3], ptrdiff_t at[8], float wt[8])
{
    const int *dm = J->dims[k];
    int i0[3], a, corner, inside_all = 1, own[8][3];
    int (*v)[3] = v_out ? v_out : own;
    voxgi__corner_weights(p, k, i0, wt);
    for (a = 0; a < 3; a++) inside_all &= i0[a] >= 0 && i0[a] + 1 < dm[a];
#ifndef VOXGI_NO_OCTREE
    if (inside_all && !J->svo && !v_out) { /* the usual case: a volume's 2 x 2 x 2 voxels, all inside */
#else
    if (inside_all && !v_out) {
#endif
        const ptrdiff_t base = (ptrdiff_t)i0[0] + (ptrdiff_t)dm[0] * ((ptrdiff_t)i0[1] + (ptrdiff_t)dm[1] * (ptrdiff_t)i0[2]);
        const ptrdiff_t dy = dm[0], dz = (ptrdiff_t)dm[0] * dm[1];
        for (corner = 0; corner < 8; corner++)
            at[corner] = wt[corner] == 0 ? -1 : base + (corner & 1) + (corner & 2 ? dy : 0) + (corner & 4 ? dz : 0);
        return;
    }
    for (corner = 0; corner < 8; corner++) {
        int inside = 1;
        for (a = 0; a < 3; a++) {
            v[corner][a] = i0[a] + ((corner >> a) & 1);
            if (!inside_all) inside &= v[corner][a] >= 0 && v[corner][a] < dm[a];
        }
        if (!inside) wt[corner] = 0;
        at[corner] = wt[corner] == 0 ? -1
#ifndef VOXGI_NO_OCTREE
                     : J->svo ? voxgi__svo_slot_at(J->svo, k, v[corner])
#endif
                              : (ptrdiff_t)((size_t)v[corner][0] + (size_t)dm[0] * ((size_t)v[corner][1] + (size_t)dm[1] * (size_t)v[corner][2]));
    }
}

/* Slot a's trilinear sample of level k at the corners (at, wt) along unit direction d: isotropic
   the one volume, anisotropic the travel direction's axis volumes by squared components. The
   four channels at once (SSE where the compiler targets it, else one by one in the same float
   arithmetic), an octree's slots read into the same sums. */
typedef struct voxgi__cone_axes {
    float w[3];                   /* the squared components of the cone's direction */
    int dir[3];                   /* and the axis volumes it travels along (2 axis + negative) */
} voxgi__cone_axes;

static void voxgi__cone_axes_of(const double d[3], voxgi__cone_axes *X)
{
    int ax;
    for (ax = 0; ax < 3; ax++) {
        X->w[ax] = (float)(d[ax] * d[ax]);
        X->dir[ax] = 2 * ax + (d[ax] < 0);
    }
}

static void voxgi__cone_level(const voxgi__cone_job *J, int a, const voxgi__cone_axes *X, int k, const ptrdiff_t at[8], const float wt[8], float out[4])
{
    const int one_dir = J->dirs == 1 || a == VOXGI__SIDE_SLOT;
    float s[4];
#ifndef VOXGI_NO_OCTREE
    float got[8][4];
    ptrdiff_t slot[8];
    int corner;
#endif
    int ch, ax;
    for (ch = 0; ch < 4; ch++) out[ch] = 0;
    for (ax = 0; ax < (one_dir ? 1 : 3); ax++) {
        const float w = one_dir ? 1.0f : X->w[ax];
        if (w == 0) continue;
#ifndef VOXGI_NO_OCTREE
        if (J->svo) { /* an octree's slots, read into the same sum */
            for (corner = 0; corner < 8; corner++) {
                slot[corner] = at[corner] < 0 ? -1 : corner;
                if (at[corner] >= 0) voxgi__svo_get(J->svo, a, k ? J->svo->node_values[a] : J->svo->leaf_values[a], (uint64_t)at[corner], got[corner]);
            }
            voxgi__corner_sum(got[0], slot, wt, s);
        } else
#endif
            voxgi__corner_sum(J->level_at[a - VOXGI__RADIANCE_SLOT][one_dir ? 0 : X->dir[ax]][k], at, wt, s);
        for (ch = 0; ch < 4; ch++) out[ch] += w * s[ch];
    }
}

/* The share of a sample's back sides: where the cone's origin o (grid units) lies against its
   (mipped) surfaces' plane n.x = n.s: 1 behind it, 0 before it or where the normals cancel,
   linear within 1/8192 voxel of it (a G-buffer point on the edge of a closed box lies that close
   to the next face's plane; GL's and the CPU's rounding meet in the ramp, not on a jump). */
#define VOXGI__SIDE_RAMP 4096.0
static float voxgi__back_share(const float side[4], const double o[3])
{
    double len = sqrt((double)side[0] * side[0] + (double)side[1] * side[1] + (double)side[2] * side[2]), dist;
    if (!(len > 0)) return 0;
    dist = (side[0] * o[0] + side[1] * o[1] + side[2] * o[2] - side[3]) / len;
    return (float)VOXGI__MIN(1.0, VOXGI__MAX(0.0, 0.5 - VOXGI__SIDE_RAMP * dist));
}

#ifndef VOXGI_NO_OCTREE
/* The region label of an octree's level-k voxel v (inside the grid), as the volume's level k
   holds it (voxgi__svo_regions). */
static uint32_t voxgi__svo_region(const voxgi_svo *svo, int k, const int v[3])
{
    int depth = svo->info.depth, level = depth - k;
    uint64_t slot;
    if (voxgi__svo_descend(svo, level, v, &slot) == level && (level == depth || svo->child[slot])) /* a voxel's label, or a node's */
        return svo->regions[(level == depth ? svo->info.nodes : 0u) + slot];
    return svo->regions[slot]; /* v lies in the empty cube of slot */
}
#endif

/* The region label of level k's voxel v, 0 beyond the grid. */
static uint32_t voxgi__region_label(const voxgi__cone_job *J, int k, const int v[3])
{
    const int *dm = J->dims[k];
    if (v[0] < 0 || v[1] < 0 || v[2] < 0 || v[0] >= dm[0] || v[1] >= dm[1] || v[2] >= dm[2]) return 0;
#ifndef VOXGI_NO_OCTREE
    if (J->svo) return voxgi__svo_region(J->svo, k, v);
#endif
    return J->regions[J->vol->first[k] + (size_t)v[0] + (size_t)dm[0] * ((size_t)v[1] + (size_t)dm[1] * (size_t)v[2])];
}

/* The radiance volume's sample at p (grid units) and lod along unit direction d, returned as
   (radiance, alpha): the stored values are premultiplied, so empty space thins a sample's alpha
   without darkening its colour. Per level, linear between the two around lod. Two-sided: each
   level mixes the front and the back by the back share seen from the cone's origin o, the back's
   alpha VOXGI__BACK_COVERAGE times its own. An octree's two sides are sampled alike (through
   lookups, not bricks). */
static void voxgi__cone_sample(const voxgi__cone_job *J, const voxgi__cone_axes *X, const float p[3], float lod_in, const double o[3], uint32_t home,
                               float out[4])
{
    ptrdiff_t at[8];
    float wt[8];
    float lod, t, s[2][4];
    int ch, k0, lev, v[8][3];
    for (ch = 0; ch < 4; ch++) out[ch] = 0;
#ifndef VOXGI_NO_OCTREE
    if (J->svo && !J->two_sided) { /* the octree's isotropic mips, through its bricks where it has them */
        voxgi__svo_source os;
        os.svo = J->svo;
        os.a = 4;
        os.w = 4;
        voxgi__sample_lod(voxgi__svo_fetch, J->svo->bricks ? voxgi__svo_brick_trilinear : NULL, &os, 4, J->levels, p, lod_in, out);
        for (ch = 0; ch < 3; ch++) out[ch] = out[3] > 0 ? out[ch] / out[3] : 0;
        return;
    }
#endif
    lod = lod_in < 0 ? 0 : (lod_in > (float)(J->levels - 1) ? (float)(J->levels - 1) : lod_in);
    k0 = (int)floor(lod);
    t = lod - (float)k0;
    for (lev = 0; lev < (t > 0 ? 2 : 1); lev++) {
        float back = 0, b[4];
        voxgi__cone_corners(J, k0 + lev, p, home && k0 + lev == 0 ? v : NULL, at, wt);
        if (home && k0 + lev == 0)
            for (ch = 0; ch < 8; ch++) { /* a surface's voxel lit from another region only is not seen from this one */
                uint32_t r = at[ch] >= 0 ? voxgi__region_label(J, 0, v[ch]) : 0;
                if ((r & VOXGI__REGION_BORDER) && ((r & VOXGI__REGION_UNSEEN) || ((r = VOXGI__REGION_OF(r)) != home && !voxgi__region_inside(J->boxes, home, r))))
                    at[ch] = -1;
            }
        if (J->two_sided) {
            voxgi__cone_level(J, VOXGI__SIDE_SLOT, X, k0 + lev, at, wt, b);
            back = voxgi__back_share(b, o);
        }
        if (back < 1) voxgi__cone_level(J, VOXGI__RADIANCE_SLOT, X, k0 + lev, at, wt, s[lev]);
        else for (ch = 0; ch < 4; ch++) s[lev][ch] = 0;
        if (back > 0) {
            voxgi__cone_level(J, VOXGI__BACK_SLOT, X, k0 + lev, at, wt, b);
            for (ch = 0; ch < 4; ch++) s[lev][ch] = (1 - back) * s[lev][ch] + back * VOXGI__BACK_COVERAGE * b[ch];
        }
    }
    for (ch = 0; ch < 4; ch++) out[ch] = t > 0 ? s[0][ch] + t * (s[1][ch] - s[0][ch]) : s[0][ch];
    for (ch = 0; ch < 3; ch++) out[ch] = out[3] > 0 ? out[ch] / out[3] : 0;
}

/* The region of level k's voxel holding p (grid units of level 0), 0 beyond the grid. */
static uint32_t voxgi__region_at(const voxgi__cone_job *J, int k, const float p[3])
{
    const int *dm = J->dims[k];
    int v[3], a;
    for (a = 0; a < 3; a++) {
        float c = p[a] / (float)(1 << k);
        if (!(c >= 0 && c < (float)dm[a])) return 0;
        v[a] = (int)c;
    }
    return voxgi__region_label(J, k, v);
}

/* Level 0's side (RADIANCE_SIDE) at voxel v inside the grid. */
static void voxgi__side_at(const voxgi__cone_job *J, const int v[3], float side[4])
{
    const int *dm = J->dims[0];
#ifndef VOXGI_NO_OCTREE
    ptrdiff_t slot;
    if (J->svo) {
        if ((slot = voxgi__svo_slot_at(J->svo, 0, v)) >= 0) voxgi__svo_get(J->svo, VOXGI__SIDE_SLOT, J->svo->leaf_values[VOXGI__SIDE_SLOT], (uint64_t)slot, side);
        else side[0] = side[1] = side[2] = side[3] = 0;
        return;
    }
#endif
    memcpy(side, J->vol->cpu[VOXGI__SIDE_SLOT][0] + 4 * ((size_t)v[0] + (size_t)dm[0] * ((size_t)v[1] + (size_t)dm[1] * (size_t)v[2])), 16);
}

/* Voxel o + (0.5 + s) n of level 0 (in float, as GL finds it) in v; 0 where it lies beyond the grid. */
static int voxgi__along_voxel(const voxgi__cone_job *J, const double o[3], const double n[3], int s, int v[3])
{
    int a;
    for (a = 0; a < 3; a++) {
        float q = (float)o[a] + (0.5f + (float)s) * (float)n[a];
        if (!(q >= 0 && q < (float)J->dims[0][a])) return 0;
        v[a] = (int)q;
    }
    return 1;
}

/* The region of the first empty voxel along unit normal n from o within 4 voxels, 0 if there is
   none; with `no_crossing`, 0 also where a surface's voxel passed on the way has its plane between
   o + n/4 and that voxel's centre: the walk crossed a wall (a closed box a few voxels wide, seen
   from inside). */
static uint32_t voxgi__home_along(const voxgi__cone_job *J, const double o[3], const double n[3], int no_crossing)
{
    float start[3], pl[4];
    int s, k, a, v[3], w[3];
    for (a = 0; a < 3; a++) start[a] = (float)o[a] + 0.25f * (float)n[a];
    for (s = 0; s < 4; s++) {
        uint32_t r = voxgi__along_voxel(J, o, n, s, v) ? voxgi__region_label(J, 0, v) : 0;
        if (!r || (r & VOXGI__REGION_BORDER)) continue;
        for (k = 0; no_crossing && k < s; k++) {
            float at_start, at_v;
            if (!voxgi__along_voxel(J, o, n, k, w)) continue;
            voxgi__side_at(J, w, pl);
            at_start = pl[0] * start[0] + pl[1] * start[1] + pl[2] * start[2] - pl[3];
            at_v = pl[0] * ((float)v[0] + 0.5f) + pl[1] * ((float)v[1] + 0.5f) + pl[2] * ((float)v[2] + 0.5f) - pl[3];
            if ((at_start > 0 && at_v < 0) || (at_start < 0 && at_v > 0)) return 0;
        }
        return r;
    }
    return 0;
}

/* Where the eye sees o (J->seen_from_eye): the region of the first empty voxel on the segment from
   o to the eye, within four voxels, in float as GL. The segment holds no surface, so that voxel's
   region is o's, exactly; OPEN where the segment leaves the grid first, 0 where it finds none. */
static uint32_t voxgi__home_toward_eye(const voxgi__cone_job *J, const double o[3])
{
    float p[3], d[3], len;
    int s, a;
    for (a = 0; a < 3; a++) { p[a] = (float)o[a]; d[a] = J->eye[a] - p[a]; }
    len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (s = 0; s < 4 && 0.5f + (float)s < len; s++) {
        float q[3];
        uint32_t r;
        for (a = 0; a < 3; a++) {
            q[a] = p[a] + (0.5f + (float)s) / len * d[a];
            if (!(q[a] >= 0 && q[a] < (float)J->dims[0][a])) return VOXGI__REGION_OPEN;
        }
        r = voxgi__region_at(J, 0, q);
        if (r && !(r & VOXGI__REGION_BORDER)) return r;
    }
    return 0;
}

/* Whether the segment from a to b (grid units) meets voxel v's box (slabs, in float as GL). */
static int voxgi__segment_meets(const float a[3], const float b[3], const int v[3])
{
    float t0 = 0, t1 = 1;
    int ax;
    for (ax = 0; ax < 3; ax++) {
        float d = b[ax] - a[ax], lo = (float)v[ax] - a[ax], hi = (float)v[ax] + 1 - a[ax], ta, tb;
        if (d == 0) {
            if (lo > 0 || hi < 0) return 0;
            continue;
        }
        ta = lo / d;
        tb = hi / d;
        t0 = VOXGI__MAX(t0, VOXGI__MIN(ta, tb));
        t1 = VOXGI__MIN(t1, VOXGI__MAX(ta, tb));
        if (t0 > t1) return 0;
    }
    return 1;
}

/* The enclosed region the cones from o on unit normal n start in: where the eye sees o, the one
   on the way to it (voxgi__home_toward_eye); else voxgi__home_along's (for a point the eye sees,
   one not across a wall: its walk found none in a space that narrow); where there is none (o near
   a corner, the other wall's voxels all along n), that of the nearest empty voxel within 2 voxels
   of q = o + n/4 which no surface's plane in the voxels around q separates from q; where none is,
   the planes of those voxels alone that the segment between them passes (a voxel on an edge holds
   the mean plane of two surfaces, which can cut off both sides). 0 where that region is open or
   there is none. */
static uint32_t voxgi__home_region(const voxgi__cone_job *J, const double o[3], const double n[3])
{
    const int *dm = J->dims[0];
    float q[3], best_d2 = 1e30f;
    uint32_t best = J->seen_from_eye ? voxgi__home_toward_eye(J, o) : 0;
    int a, c[3], e[3], v[3], strict;
    if (!best) best = voxgi__home_along(J, o, n, J->seen_from_eye);
    if (best) return best == VOXGI__REGION_OPEN ? 0 : best;
    for (a = 0; a < 3; a++) {
        q[a] = (float)o[a] + 0.25f * (float)n[a];
        if (!(q[a] > -3.0f && q[a] < (float)dm[a] + 3.0f)) return 0; /* no voxel within 2 of q (however far: before it becomes an int) */
        c[a] = (int)floorf(q[a]);
    }
    for (strict = 1; strict >= 0 && !best; strict--)
    for (e[2] = c[2] - 2; e[2] <= c[2] + 2; e[2]++)
        for (e[1] = c[1] - 2; e[1] <= c[1] + 2; e[1]++)
            for (e[0] = c[0] - 2; e[0] <= c[0] + 2; e[0]++) {
                float ec[3], d2 = 0;
                uint32_t r;
                int ok = 1;
                if (e[0] < 0 || e[1] < 0 || e[2] < 0 || e[0] >= dm[0] || e[1] >= dm[1] || e[2] >= dm[2]) continue;
                r = voxgi__region_label(J, 0, e);
                if (!r || (r & VOXGI__REGION_BORDER)) continue;
                for (a = 0; a < 3; a++) { ec[a] = (float)e[a] + 0.5f; d2 += (ec[a] - q[a]) * (ec[a] - q[a]); }
                if (!(d2 < best_d2)) continue;
                for (v[2] = c[2] - 1; ok && v[2] <= c[2] + 1; v[2]++)
                    for (v[1] = c[1] - 1; ok && v[1] <= c[1] + 1; v[1]++)
                        for (v[0] = c[0] - 1; ok && v[0] <= c[0] + 1; v[0]++) {
                            float pl[4], at_q, at_e;
                            if (v[0] < 0 || v[1] < 0 || v[2] < 0 || v[0] >= dm[0] || v[1] >= dm[1] || v[2] >= dm[2] || (!strict && !voxgi__segment_meets(q, ec, v))) continue;
                            voxgi__side_at(J, v, pl);
                            at_q = pl[0] * q[0] + pl[1] * q[1] + pl[2] * q[2] - pl[3];
                            at_e = pl[0] * ec[0] + pl[1] * ec[1] + pl[2] * ec[2] - pl[3];
                            ok = !((at_q > 0 && at_e < 0) || (at_q < 0 && at_e > 0));
                        }
                if (ok) { best = r; best_d2 = d2; }
            }
    return best == VOXGI__REGION_OPEN ? 0 : best;
}

/* Whether level k's trilinear sample at p reads no region but home's and those inside it. */
static int voxgi__region_clear(const voxgi__cone_job *J, int k, const float p[3], uint32_t home)
{
    ptrdiff_t at[8];
    float wt[8];
    int corner, v[8][3];
    voxgi__cone_corners(J, k, p, v, at, wt);
    for (corner = 0; corner < 8; corner++) {
        uint32_t r = wt[corner] != 0 ? voxgi__region_label(J, k, v[corner]) : 0;
        if (r && r != home && !voxgi__region_inside(J->boxes, home, r)) return 0;
    }
    return 1;
}

/* One cone from o (grid units, on a surface of unit normal n) along unit d, whose cosine with n
   is lz: marched from `offset` voxels along n, narrowing tan_k, up to max_d voxels; its
   composited radiance C and opacity A. A single cone (voxgi_cone_trace_each) is the case n = d.
   From an enclosed region home (voxgi__home_region; 0: none) it ends where it leaves it and
   samples no level that reaches beyond it, nor strides wider than that level's voxels. */
static void voxgi__cone_march(const voxgi__cone_job *J, const double o[3], const double n[3], const double d[3], double lz, double tan_k, double max_d,
                              uint32_t home, double C[3], double *A_out)
{
    double t = J->offset, A = 0, start[3], from_centre = 0, half_diagonal = 0;
    float last[4] = {0, 0, 0, 0};
    voxgi__cone_axes X;
    int a;
    C[0] = C[1] = C[2] = 0;
    /* past this distance every sample lies more than a voxel of the coarsest level outside the grid, where all is empty,
       so the march ends there with what it would have gathered: a cone too narrow to widen would step on to max_d
       (1e9 voxels: 2e9 steps) */
    for (a = 0; a < 3; a++) {
        from_centre += (o[a] - 0.5 * J->dims[0][a]) * (o[a] - 0.5 * J->dims[0][a]);
        half_diagonal += 0.25 * J->dims[0][a] * J->dims[0][a];
    }
    max_d = VOXGI__MIN(max_d, sqrt(from_centre) + 2 * J->offset + sqrt(half_diagonal) + 1.7321 * ldexp(1.0, J->levels) + 1);
    voxgi__cone_axes_of(d, &X);
    for (a = 0; a < 3; a++) start[a] = o[a] + J->offset * n[a]; /* where a sample's side is seen from */
    while (t < max_d && A < 0.99) {
        double diam = VOXGI__MAX(1.0, 2 * t * tan_k), ap, h = J->offset + (t - J->offset) * lz, keep;
        float p[3], s[4];
        for (a = 0; a < 3; a++) p[a] = (float)(o[a] + J->offset * n[a] + (t - J->offset) * d[a]);
        /* both levels blended must stay clear of the surface: a level-L voxel holding it reaches 1.5 x 2^L above it,
           so lod <= log2(h / 1.5) - 1 = log2(h / 3) */
        double lod = VOXGI__MIN(log2(VOXGI__MIN(diam, h / 3)), J->levels - 1.0);
        if (home) {
            uint32_t here = voxgi__region_at(J, 0, p);
            int k;
            if (here && !(here & VOXGI__REGION_BORDER) && here != home && !voxgi__region_inside(J->boxes, home, here)) {
                for (a = 0; a < 3; a++) C[a] += (1 - A) * last[a]; /* the rest of the cone ends on the enclosure, as last seen */
                A = 1;
                break;
            }
            for (k = (int)ceil(lod); k > 0 && !voxgi__region_clear(J, k, p, home); k--) {}
            if (k < lod) diam = exp2(lod = k);
        }
        voxgi__cone_sample(J, &X, p, (float)lod, start, home, s);
        if (s[3] > 0) memcpy(last, s, sizeof last);
        /* what the cone sees is the coverage of its cross-section. Isotropic: a level-L voxel's alpha is the share
           of its volume that is filled; a surface one voxel thick fills 2^-L of it yet may cover its whole
           cross-section: alpha x 2^L. Anisotropic: alpha is already the coverage along the axis (composited front
           to back), and a surface parallel to the travel covers only its share; only the trilinear filter's
           halving of a one-voxel wall between voxel centres is undone: alpha x 2. At most 1 either way. */
        keep = 1 - VOXGI__MIN(1.0, s[3] * (J->dirs == 6 ? 2.0 : exp2(VOXGI__MAX(lod, 0.0)))); /* what one diameter lets through; */
        ap = 1 - (J->step == 0.5 ? sqrt(keep) : J->step == 1 ? keep : pow(keep, J->step)); /* a step is J->step of it */
        for (a = 0; a < 3; a++) C[a] += (1 - A) * ap * s[a];
        A += (1 - A) * ap;
        t += J->step * VOXGI__MIN(diam, VOXGI__MAX(1.0, h)); /* a cone wider than its height above the surface samples a finer
                                                                 level (above): its stride keeps to that height, or it would leap
                                                                 over what lies just above (an 86-degree cone over a ceiling) */
    }
    *A_out = A;
}

static void voxgi__cone_march_cpu(void *user, size_t first, size_t end)
{
    voxgi__cone_job *J = (voxgi__cone_job *)user;
    const voxgi_grid *g = J->grid;
    size_t i;
    int k, a;
    for (i = first; i < end; i++) {
        double o[3], n[3], t3[3], b3[3], len = 0, e[3] = {0, 0, 0}, occ = 0;
        uint32_t home;
        for (a = 0; a < 3; a++) { o[a] = (J->pos[3 * i + (size_t)a] - g->origin[a]) / g->voxel_size; n[a] = J->nrm[3 * i + (size_t)a]; len += n[a] * n[a]; }
        len = sqrt(len);
        for (a = 0; a < 3; a++) n[a] = len > 0 ? n[a] / len : (a == 1);
        voxgi__basis(n, t3, b3);
        home = J->regions ? voxgi__home_region(J, o, n) : 0;
        for (k = 0; k < J->cones; k++) {
            double l[3], d[3], A, C[3];
            voxgi__cone_direction(k, J->cones, l);
            for (a = 0; a < 3; a++) d[a] = l[0] * t3[a] + l[1] * b3[a] + l[2] * n[a];
            /* low cones narrow: each sample stays 1.5 diameters above the tangent plane */
            voxgi__cone_march(J, o, n, d, l[2], VOXGI__MIN(J->half_tan, l[2] / 3), J->max_dist, home, C, &A);
            for (a = 0; a < 3; a++) e[a] += VOXGI__PI / J->cones * C[a];
            occ += A / J->cones;
        }
        for (a = 0; a < 3; a++) J->irr[3 * i + (size_t)a] = (float)e[a];
        if (J->occ) J->occ[i] = (float)occ;
    }
}

/* A single cone's origin (grid units), unit direction, unit surface normal (the direction when
   none is given or it faces away) and their cosine. */
static void voxgi__cone_frame(const voxgi_cone *c, const voxgi_grid *g, double o[3], double d[3], double n[3], double *lz)
{
    double ld = 0, ln = 0;
    int a;
    for (a = 0; a < 3; a++) {
        o[a] = (c->origin[a] - g->origin[a]) / g->voxel_size;
        d[a] = c->direction[a];
        n[a] = c->normal[a];
        ld += d[a] * d[a];
        ln += n[a] * n[a];
    }
    ld = sqrt(ld);
    ln = sqrt(ln);
    for (a = 0; a < 3; a++) { d[a] /= ld; n[a] = ln > 0 ? n[a] / ln : 0; }
    *lz = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    if (!(*lz > 0)) { for (a = 0; a < 3; a++) n[a] = d[a]; *lz = 1; }
}

/* Single cones (voxgi_cone_trace_each): J->list in, (C, A) per cone out in J->irr (4 floats each). */
static void voxgi__cone_each_cpu(void *user, size_t first, size_t end)
{
    voxgi__cone_job *J = (voxgi__cone_job *)user;
    const voxgi_grid *g = J->grid;
    size_t i;
    int a;
    for (i = first; i < end; i++) {
        const voxgi_cone *c = &J->list[i];
        double o[3], d[3], n[3], lz;
        double A, C[3];
        voxgi__cone_frame(c, g, o, d, n, &lz);
        voxgi__cone_march(J, o, n, d, lz, lz < 1 ? VOXGI__MIN(tan((double)c->half_angle), lz / 3) : tan((double)c->half_angle), /* narrowed as diffuse cones */
                          c->max_distance > 0 ? c->max_distance / g->voxel_size : J->max_dist, J->regions ? voxgi__home_region(J, o, n) : 0, C, &A);
        for (a = 0; a < 3; a++) J->irr[4 * i + (size_t)a] = (float)C[a];
        J->irr[4 * i + 3] = (float)A;
    }
}

#ifndef VOXGI_NO_GL
/* The march's uniforms (shaders/cone_trace.glsl). */
static void voxgi__cone_uniforms(voxgi__gl *gl, unsigned int p, const voxgi__cone_job *J)
{
    if (J->vol)
        gl->ProgramUniform3f(p, VOXGI__LOC_u_size, (float)J->vol->info.gl_size[0], (float)J->vol->info.gl_size[1],
                             (float)J->vol->info.gl_size[2]);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_levels, J->levels);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_anisotropic, J->dirs == 6);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_two_sided, J->two_sided);
    /* the regions: where their bounds start (0: no enclosed region), level 0's size */
    gl->ProgramUniform1ui(p, VOXGI__LOC_u_regions, !J->enclosed ? 0u
#ifndef VOXGI_NO_OCTREE
                                                   : !J->vol ? (unsigned)(J->svo->info.nodes + J->svo->info.leaf_slots)
#endif
                                                   : (unsigned)J->vol->voxels);
    gl->ProgramUniform3i(p, VOXGI__LOC_u_res, J->dims[0][0], J->dims[0][1], J->dims[0][2]);
    gl->ProgramUniform1f(p, VOXGI__LOC_u_back_coverage, VOXGI__BACK_COVERAGE);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_cones, J->list ? 0 : J->cones);
    gl->ProgramUniform1f(p, VOXGI__LOC_u_half_tan, (float)J->half_tan);
    gl->ProgramUniform1f(p, VOXGI__LOC_u_step, (float)J->step);
    gl->ProgramUniform1f(p, VOXGI__LOC_u_offset, (float)J->offset);
    gl->ProgramUniform1f(p, VOXGI__LOC_u_max_distance, (float)J->max_dist);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_seen_from_eye, J->seen_from_eye);
    gl->ProgramUniform3f(p, VOXGI__LOC_u_eye, J->eye[0], J->eye[1], J->eye[2]);
}

/* The radiance, a volume's textures on units 0-5 (front), 9-14 (back) and 15 (side) or an
   octree's buffers (svo.glsl: the front bound, the back and the side beside it), and the regions
   on storage binding 5; bind 0 unbinds the textures (voxgi__gl_unbind the buffers). */
static void voxgi__cone_bind_gl(voxgi_context *ctx, const voxgi__cone_job *J, unsigned int p, int bind)
{
    voxgi__gl *gl = ctx->gl;
    int a;
#ifndef VOXGI_NO_OCTREE
    if (J->svo) {
        if (!bind) return;
        voxgi__svo_bind_gl(ctx, J->svo, p, VOXGI__RADIANCE_SLOT); /* the three share their layout, so u_svo_leaf_first */
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, VOXGI__BINDING_SVO_BACK_VALUES, J->two_sided ? J->svo->gl_values[VOXGI__BACK_SLOT] : 0u);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, VOXGI__BINDING_SVO_SIDE_VALUES, J->two_sided ? J->svo->gl_values[VOXGI__SIDE_SLOT] : 0u);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 5, J->enclosed ? J->svo->gl_regions : 0u);
        return;
    }
#else
    (void)p; /* an octree's buffers alone take uniforms */
#endif
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 5, bind && J->enclosed ? J->vol->region_buffer : 0u);
    for (a = 0; a < 6; a++) {
        int d = J->dirs == 6 ? a : 0;
        gl->BindTextureUnit((unsigned)a, bind ? J->vol->tex[VOXGI__RADIANCE_SLOT][d] : 0);
        gl->BindTextureUnit((unsigned)(9 + a), bind && J->two_sided ? J->vol->tex[VOXGI__BACK_SLOT][d] : 0);
    }
    gl->BindTextureUnit(15, bind && J->two_sided ? J->vol->tex[VOXGI__SIDE_SLOT][0] : 0);
}

/* The gathers of `count` points or pixels by program p (shaders/cone_trace.glsl's gather_pass):
   in slices, each in three passes: the home regions, then every cone on an invocation of its own
   (llvmpipe ends an invocation's loops after 65535 iterations in all, which a whole gather over
   an octree exceeds: its results came out short), then their sums. Single cones (J->list): one
   pass, a cone per invocation. */
static voxgi_result voxgi__cone_passes_gl(voxgi_context *ctx, const voxgi__cone_job *J, unsigned int p, size_t count)
{
    voxgi__gl *gl = ctx->gl;
    size_t cones = J->list ? 1 : (size_t)J->cones, slice = VOXGI__MIN((size_t)16384, ((size_t)1 << 20) / cones), first;
    unsigned int scratch = J->list ? 0 : voxgi__gl_buffer(ctx, (slice * cones + slice) * 16, NULL);
    int pass;
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 7, scratch);
    for (first = 0; first < count; first += slice) {
        size_t n = VOXGI__MIN(slice, count - first);
        gl->ProgramUniform1ui(p, VOXGI__LOC_u_first, (unsigned)first);
        gl->ProgramUniform1ui(p, VOXGI__LOC_u_count, (unsigned)n);
        for (pass = J->list ? 2 : 0; pass < 3; pass++) {
            gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, pass);
            gl->DispatchCompute((unsigned)(((pass == 1 ? (n + 7) / 8 * 8 * cones : n) + 63) / 64), 1, 1); /* pass 1: cones of 8 points at a time */
            gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT);
        }
        gl->Finish(); /* no one submission runs long */
    }
    voxgi__gl_delete_buffer(ctx, scratch);
    return VOXGI_OK;
}

/* The same march on GL (shaders/cone_trace.glsl): points in grid units and unit normals go up,
   (irradiance, occlusion) come back. */
static voxgi_result voxgi__cone_march_gl(voxgi_context *ctx, const voxgi__cone_job *J, size_t count)
{
    voxgi__gl *gl = ctx->gl;
    const voxgi_grid *g = J->grid;
    unsigned int bufs[2] = {0, 0}, p, *prog = &gl->prog_cone_trace;
    voxgi__gl_program_id id = VOXGI__GL_PROGRAM_cone_trace;
    float *io;
    size_t i;
    int a;
    voxgi_result r;
#ifndef VOXGI_NO_OCTREE
    if (J->svo) {
        prog = &gl->prog_cone_trace_svo;
        id = VOXGI__GL_PROGRAM_cone_trace_svo;
    }
#endif
    if ((r = voxgi__gl_get_program(ctx, id)) != VOXGI_OK || !count) return r;
    if (count > UINT32_MAX / 2) return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%lu points in one call", (unsigned long)count);
    if (!(io = (float *)voxgi__alloc_array(ctx, count, 48, 0))) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu points", (unsigned long)count);
    for (i = 0; i < count; i++) { /* points: position, unit normal; single cones: origin and tan, unit direction and reach, normal and cosine */
        float *v = io + 12 * i;
        double o[3], d[3], n[3], lz = 0, len = 0;
        if (J->list) voxgi__cone_frame(&J->list[i], g, o, d, n, &lz);
        else {
            for (a = 0; a < 3; a++) { o[a] = (J->pos[3 * i + (size_t)a] - g->origin[a]) / g->voxel_size; d[a] = J->nrm[3 * i + (size_t)a]; len += d[a] * d[a]; }
            len = sqrt(len);
            for (a = 0; a < 3; a++) n[a] = d[a] = len > 0 ? d[a] / len : (a == 1);
        }
        for (a = 0; a < 3; a++) { v[a] = (float)o[a]; v[4 + a] = (float)d[a]; v[8 + a] = (float)n[a]; }
        v[3] = J->list ? (float)tan((double)J->list[i].half_angle) : 0.0f;
        v[7] = J->list ? (float)(J->list[i].max_distance > 0 ? J->list[i].max_distance / g->voxel_size : J->max_dist) : 0.0f;
        v[11] = (float)lz;
    }
    bufs[0] = voxgi__gl_buffer(ctx, count * 48, io);
    bufs[1] = voxgi__gl_buffer(ctx, count * 16, NULL);
    p = *prog;
    gl->UseProgram(p);
    voxgi__cone_uniforms(gl, p, J);
    voxgi__cone_bind_gl(ctx, J, p, 1);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 3, bufs[0]);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 4, bufs[1]);
    voxgi__cone_passes_gl(ctx, J, p, count);
    gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT | VOXGI__GL_BUFFER_UPDATE_BARRIER_BIT);
    voxgi__cone_bind_gl(ctx, J, p, 0);
    voxgi__gl_unbind(gl);
    r = voxgi__gl_read_buffer(ctx, bufs[1], io, count * 16);
    for (i = 0; r == VOXGI_OK && i < count; i++) {
        if (J->list) { memcpy(J->irr + 4 * i, io + 4 * i, 16); continue; }
        for (a = 0; a < 3; a++) J->irr[3 * i + (size_t)a] = io[4 * i + (size_t)a];
        if (J->occ) J->occ[i] = io[4 * i + 3];
    }
    voxgi__free(ctx, io);
    voxgi__gl_delete_buffer(ctx, bufs[0]);
    voxgi__gl_delete_buffer(ctx, bufs[1]);
    if (r == VOXGI_OK) r = voxgi__gl_check(ctx, "cone tracing");
    return r;
}
#endif

/* What the cone tracers share: the checks of the radiance (a volume, or an octree when vol is
   NULL) and of desc, the job. */
static voxgi_result voxgi__cone_job_init(voxgi_context *ctx, const voxgi_radiance_source *source, const voxgi_cone_desc *desc,
                                         voxgi__cone_job *J)
{
    const voxgi_volume *vol = source->volume;
    const voxgi_grid *g = vol ? &vol->info.grid : NULL;
    const char *what = "volume", *maker = "voxgi_inject_light";
    unsigned attributes = vol ? vol->info.attributes : 0u;
    voxgi_backend backend = vol ? vol->info.backend : VOXGI_BACKEND_AUTO;
    int k, a;
    memset(J, 0, sizeof *J);
#ifndef VOXGI_NO_OCTREE
    if (!vol == !source->octree)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the radiance source sets %s: exactly one of volume and octree is needed",
                           vol ? "both a volume and an octree" : "neither a volume nor an octree");
    if (!vol) {
        const voxgi_svo *svo = J->svo = source->octree;
        what = "octree";
        maker = "voxgi_svo_desc.radiance";
        attributes = svo->info.attributes;
        backend = svo->info.backend;
        g = &svo->info.grid;
        J->levels = svo->info.depth + 1;
        J->enclosed = svo->region_count > 2; /* with two sides, below */
        J->regions = svo->regions;
        if (svo->regions) J->boxes = svo->regions + svo->info.nodes + svo->info.leaf_slots; /* the bounds follow the labels */
        for (k = 0; k < J->levels; k++)
            for (a = 0; a < 3; a++) J->dims[k][a] = (int)(((int64_t)g->res[a] + ((int64_t)1 << k) - 1) >> k);
    }
#else
    if (!vol) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the radiance source sets no volume");
#endif
    if (!(attributes & VOXGI_ATTRIBUTE_RADIANCE))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the %s holds no RADIANCE (%s)", what, maker);
    if (backend != ctx->backend)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the %s was made on another backend than the context's", what);
    /* a step below 0.01 of the diameter: millions of samples a cone, and none at all past a step that no longer moves t */
    if (desc->cones < 0 || desc->cones > 1024 || !(desc->half_angle >= 0 && desc->half_angle < 1.5f) ||
        !(desc->step == 0 || (desc->step >= 0.01f && desc->step <= 4)) || !(desc->offset >= 0) || !(desc->max_distance >= 0))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "cones %d (0..1024), half_angle %g (0..1.5), step %g (0.01..4, 0: 0.5), offset %g, max_distance %g",
                           desc->cones, desc->half_angle, desc->step, desc->offset, desc->max_distance);
    if (desc->seen_from_eye && !(isfinite(desc->eye[0]) && isfinite(desc->eye[1]) && isfinite(desc->eye[2])))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "seen_from_eye with an eye that is not finite");
    if (vol) {
        J->levels = vol->info.levels;
        J->enclosed = vol->region_count > 2;
        J->regions = vol->regions;
        J->boxes = vol->region_boxes;
        for (k = 0; k < J->levels; k++)
            for (a = 0; a < 3; a++) J->dims[k][a] = vol->dims[k][a];
    }
    J->vol = vol;
    J->grid = g;
    J->desc = desc;
    J->cones = desc->cones ? desc->cones : 16;
    J->dirs = vol && vol->info.filter == VOXGI_MIPS_ANISOTROPIC ? 6 : 1;
    J->two_sided = (attributes & (VOXGI_ATTRIBUTE_RADIANCE_BACK | VOXGI_ATTRIBUTE_RADIANCE_SIDE)) ==
                   (VOXGI_ATTRIBUTE_RADIANCE_BACK | VOXGI_ATTRIBUTE_RADIANCE_SIDE);
    J->enclosed = J->two_sided && J->enclosed;
    if (!J->enclosed) J->regions = NULL; /* the regions are read only where there are enclosed ones */
    if (!J->regions) J->boxes = NULL;
    for (a = 0; vol && a < 3; a++) /* the levels the source holds, on the CPU */
        if (vol->cpu[VOXGI__RADIANCE_SLOT + a][0]) {
            int dir;
            for (dir = 0; dir < (a == 2 ? 1 : J->dirs); dir++)
                for (k = 0; k < J->levels; k++) J->level_at[a][dir][k] = voxgi__volume_level(vol, VOXGI__RADIANCE_SLOT + a, dir, k);
        }
    J->half_tan = tan(desc->half_angle > 0 ? desc->half_angle : acos(1 - 1.0 / J->cones));
    J->step = desc->step > 0 ? desc->step : 0.5;
    J->offset = desc->offset > 0 ? desc->offset : 1.5;
    J->max_dist = desc->max_distance > 0 ? desc->max_distance
                                         : sqrt((double)g->res[0] * g->res[0] + (double)g->res[1] * g->res[1] + (double)g->res[2] * g->res[2]);
    J->seen_from_eye = desc->seen_from_eye != 0;
    for (a = 0; a < 3; a++) J->eye[a] = J->seen_from_eye ? (float)((desc->eye[a] - g->origin[a]) / g->voxel_size) : 0.0f;
    return VOXGI_OK;
}

VOXGI_API voxgi_result voxgi_cone_trace(voxgi_context *ctx, const voxgi_radiance_source *source, const voxgi_cone_desc *desc,
                                        size_t count, const float *positions, const float *normals, float *irradiance,
                                        float *occlusion)
{
    voxgi__cone_job J;
    size_t i, first, chunk = count < 4096 ? count : (count + 15) / 16;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!source || !desc || (count && (!positions || !normals || !irradiance)))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the radiance source, desc, positions, normals or irradiance is NULL");
    if ((r = voxgi__cone_job_init(ctx, source, desc, &J)) != VOXGI_OK) return r;
    for (i = 0; i < 3 * count; i++)
        if (!isfinite(positions[i]) || !isfinite(normals[i])) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "point %lu is not finite", (unsigned long)(i / 3));
    for (first = 0; r == VOXGI_OK && first < count; first += chunk) { /* in 16 parts: progress, and a cancel between them */
        size_t m = VOXGI__MIN(chunk, count - first);
        J.pos = positions + 3 * first;
        J.nrm = normals + 3 * first;
        J.irr = irradiance + 3 * first;
        J.occ = occlusion ? occlusion + first : NULL;
#ifndef VOXGI_NO_GL
        if (ctx->backend == VOXGI_BACKEND_GL) r = voxgi__cone_march_gl(ctx, &J, m);
        else
#endif
            voxgi__parallel(ctx, m, 64, voxgi__cone_march_cpu, &J);
        if (r == VOXGI_OK && voxgi__cancelled(ctx, (double)(first + m) / (double)count, "cone tracing", "cones")) r = VOXGI_ERR_CANCELLED;
    }
    return r;
}

VOXGI_API voxgi_result voxgi_cone_trace_each(voxgi_context *ctx, const voxgi_radiance_source *source, const voxgi_cone_desc *desc,
                                             size_t count, const voxgi_cone *cones, float *radiance_opacity)
{
    voxgi__cone_job J;
    size_t i;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!source || !desc || (count && (!cones || !radiance_opacity)))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the radiance source, desc, cones or out is NULL");
    if ((r = voxgi__cone_job_init(ctx, source, desc, &J)) != VOXGI_OK) return r;
    for (i = 0; i < count; i++) {
        const voxgi_cone *c = &cones[i];
        double len = (double)c->direction[0] * c->direction[0] + (double)c->direction[1] * c->direction[1] + (double)c->direction[2] * c->direction[2];
        if (!isfinite(c->origin[0]) || !isfinite(c->origin[1]) || !isfinite(c->origin[2]) || !(len > 0) || !isfinite(len) ||
            !(c->half_angle > 0 && c->half_angle < 1.5f) || !(c->max_distance >= 0) || !isfinite(c->max_distance))
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "cone %lu: origin not finite, direction zero, half_angle %g not in (0, 1.5) or max_distance %g",
                               (unsigned long)i, c->half_angle, c->max_distance);
    }
    J.list = cones;
    J.irr = radiance_opacity;
#ifndef VOXGI_NO_GL
    if (ctx->backend == VOXGI_BACKEND_GL) return voxgi__cone_march_gl(ctx, &J, count);
#endif
    voxgi__parallel(ctx, count, 64, voxgi__cone_each_cpu, &J);
    return VOXGI_OK;
}

/* The gather over the caller's G-buffer textures. */
VOXGI_API voxgi_result voxgi_cone_trace_gl(voxgi_context *ctx, const voxgi_radiance_source *source, const voxgi_cone_desc *desc,
                                           const voxgi_gl_gbuffer *gb)
{
#ifdef VOXGI_NO_GL
    (void)source; (void)desc; (void)gb;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    return voxgi__fail(ctx, VOXGI_ERR_UNSUPPORTED, "G-buffer textures need GL (this build has VOXGI_NO_GL)");
#else
    voxgi__gl *gl;
    voxgi__cone_job J;
    const voxgi_grid *g;
    unsigned int p, *prog;
    int a;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!source || !desc || !gb) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the radiance source, desc or gbuffer is NULL");
    if (ctx->backend != VOXGI_BACKEND_GL || !ctx->gl) return voxgi__fail(ctx, VOXGI_ERR_UNSUPPORTED, "G-buffer textures need a GL context");
    if (!gb->position_texture || !gb->normal_texture || !gb->irradiance_texture || gb->width < 1 || gb->height < 1)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "position, normal and irradiance textures and a size (%d x %d) are needed", gb->width, gb->height);
    if ((r = voxgi__cone_job_init(ctx, source, desc, &J)) != VOXGI_OK) return r;
    gl = ctx->gl;
    g = J.grid;
#ifndef VOXGI_NO_OCTREE
    if (J.svo) {
        prog = gb->irradiance_rgba16f ? &gl->prog_cone_trace_svo_images16 : &gl->prog_cone_trace_svo_images32;
        r = voxgi__gl_get_program(ctx, gb->irradiance_rgba16f ? VOXGI__GL_PROGRAM_cone_trace_svo_images16 : VOXGI__GL_PROGRAM_cone_trace_svo_images32);
    } else
#endif
    {
        prog = gb->irradiance_rgba16f ? &gl->prog_cone_trace_images16 : &gl->prog_cone_trace_images32;
        r = voxgi__gl_get_program(ctx, gb->irradiance_rgba16f ? VOXGI__GL_PROGRAM_cone_trace_images16 : VOXGI__GL_PROGRAM_cone_trace_images32);
    }
    if (r != VOXGI_OK) return r;
    p = *prog;
    gl->UseProgram(p);
    voxgi__cone_uniforms(gl, p, &J);
    voxgi__cone_bind_gl(ctx, &J, p, 1);
    gl->BindTextureUnit(6, gb->position_texture);
    gl->BindTextureUnit(7, gb->normal_texture);
    gl->BindTextureUnit(8, gb->albedo_texture ? gb->albedo_texture : gb->normal_texture);
    gl->BindImageTexture(0, gb->irradiance_texture, 0, 0, 0, VOXGI__GL_WRITE_ONLY, gb->irradiance_rgba16f ? VOXGI__GL_RGBA16F : VOXGI__GL_RGBA32F);
    gl->ProgramUniform2i(p, VOXGI__LOC_u_image, gb->width, gb->height);
    gl->ProgramUniform3f(p, VOXGI__LOC_u_origin, (float)g->origin[0], (float)g->origin[1], (float)g->origin[2]);
    gl->ProgramUniform1f(p, VOXGI__LOC_u_voxel_size, (float)g->voxel_size);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_has_albedo, gb->albedo_texture != 0);
    voxgi__cone_passes_gl(ctx, &J, p, (size_t)gb->width * (size_t)gb->height);
    gl->MemoryBarrier(VOXGI__GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | VOXGI__GL_TEXTURE_FETCH_BARRIER_BIT);
    for (a = 0; a < 9; a++) gl->BindTextureUnit((unsigned)a, 0);
    voxgi__cone_bind_gl(ctx, &J, p, 0);
    gl->BindImageTexture(0, 0, 0, 0, 0, VOXGI__GL_READ_WRITE, VOXGI__GL_RGBA32F);
    voxgi__gl_unbind(gl);
    return voxgi__gl_check(ctx, "cone tracing a G-buffer");
#endif
}

VOXGI_API float voxgi_specular_half_angle(float roughness)
{
    double a = VOXGI__MIN(1.0, VOXGI__MAX(0.02, (double)roughness)), n = VOXGI__MAX(0.0, 2 / (a * a) - 2); /* Phong exponent of the lobe */
    return (float)VOXGI__MAX(0.005, acos(pow(0.244, 1 / (n + 1))));
}
#endif /* VOXGI_NO_CONE_TRACING */

/* ===================================================================== 9. light injection */
#ifndef VOXGI_NO_LIGHT_INJECTION

typedef struct voxgi__inject {
    const voxgi__lights *lights;
    const voxgi_grid *g;
    const voxgi_inject_desc *desc;
    const uint64_t *index;        /* set voxel i: its linear index */
    float *const *vals;           /* attribute means, bit order */
    float *rgba;                  /* level 0 of the radiance volume */
    float *back, *side;           /* level 0 of RADIANCE_BACK and RADIANCE_SIDE, or NULL (one-sided) */
    unsigned char *own_plane;     /* set voxel i: its normal is its nearest surface's (voxgi__inject_planes), or NULL */
    size_t rays;
} voxgi__inject;

/* The i-th set voxel's lookup point: its centre moved half a voxel diagonal along its mean normal
   (off its own surface), and that unit normal; 0 when opposite surfaces cancelled the normal. */
static int voxgi__inject_point(const voxgi__inject *J, size_t i, double p[3], double nl[3])
{
    const voxgi_grid *g = J->g;
    uint64_t l = J->index[i];
    double c[3], len = 0, off = 0.8660254037844386 * g->voxel_size;
    int a;
    c[0] = g->origin[0] + ((double)(l % (uint64_t)g->res[0]) + 0.5) * g->voxel_size;
    c[1] = g->origin[1] + ((double)(l / (uint64_t)g->res[0] % (uint64_t)g->res[1]) + 0.5) * g->voxel_size;
    c[2] = g->origin[2] + ((double)(l / ((uint64_t)g->res[0] * (uint64_t)g->res[1])) + 0.5) * g->voxel_size;
    for (a = 0; a < 3; a++) { nl[a] = J->vals[1][3 * i + (size_t)a]; len += nl[a] * nl[a]; }
    len = sqrt(len);
    for (a = 0; a < 3; a++) { nl[a] = len > 0 ? nl[a] / len : 0; p[a] = c[a] + off * nl[a]; }
    return len > 0;
}

/* Two-sided voxels whose surfaces face apart (a box's bottom resting on a floor, a plate thinner
   than a voxel: their mean normal is cancelled) take the normal of the surface nearest the centre
   instead, its largest component positive (upwards for a floor): the lookup points then lie on
   either side of the surfaces, where the cancelled mean lit neither (the light through a hole in
   a resting box's top reached its inner floor as black). The surfaces are found by rays along
   the axes within half a voxel diagonal, and only where all they meet are parallel (at a wall's
   foot the mean stays). Such a voxel stores no side plane (voxgi__inject_store): a plane of its
   own, mixed by the cones' trilinear samples with a neighbouring wall foot's, turned cones from
   inside a closed box to that foot's outer, lit side. It shows its positive side's light both
   ways. */
static void voxgi__inject_planes(voxgi__inject *J, size_t n)
{
    const double reach = 0.8660254037844386 * J->g->voxel_size;
    size_t i;
    for (i = 0; i < n; i++) {
        float *m = J->vals[1] + 3 * i;
        double c[3], len = sqrt((double)m[0] * m[0] + (double)m[1] * m[1] + (double)m[2] * m[2]), best = reach, d[3];
        const double *pick = NULL, *hits[6];
        int found = 0, parallel = 1;
        uint64_t l = J->index[i];
        int q, a;
        if (len >= 0.1) continue; /* a corner's or an edge's mean (1/3 or more) is a plane between its surfaces */
        c[0] = J->g->origin[0] + ((double)(l % (uint64_t)J->g->res[0]) + 0.5) * J->g->voxel_size;
        c[1] = J->g->origin[1] + ((double)(l / (uint64_t)J->g->res[0] % (uint64_t)J->g->res[1]) + 0.5) * J->g->voxel_size;
        c[2] = J->g->origin[2] + ((double)(l / ((uint64_t)J->g->res[0] * (uint64_t)J->g->res[1])) + 0.5) * J->g->voxel_size;
        for (q = 0; q < 6; q++) {
            voxgi__hit hit;
            for (a = 0; a < 3; a++) d[a] = a == q >> 1 ? (q & 1 ? 1.0 : -1.0) : 0.0;
            if (!voxgi__trace(J->lights->tr, c, d, reach, UINT32_MAX, 0, &hit) || !(hit.t < reach)) continue;
            hits[found++] = J->lights->tr->n + 3 * (size_t)hit.prim;
            if (hit.t < best) {
                best = hit.t;
                pick = hits[found - 1];
            }
        }
        for (q = 0; q < found; q++) parallel = parallel && fabs(hits[q][0] * pick[0] + hits[q][1] * pick[1] + hits[q][2] * pick[2]) > 0.999;
        if (!pick || !parallel) continue;
        for (q = 0, a = 1; a < 3; a++)
            if (fabs(pick[a]) > fabs(pick[q])) q = a;
        q = pick[q] < 0 ? -1 : 1;
        for (a = 0; a < 3; a++) m[a] = (float)(q * pick[a]);
        J->own_plane[i] = 1;
    }
}

/* Where the surface of a voxel (centre c, unit mean normal nl, world units) crosses the line
   through c along nl: the signed distance from c of the hit nearest to it within half a voxel
   diagonal (grid units), 0 where the line misses every triangle there. */
static double voxgi__surface_offset(const voxgi__inject *J, const double c[3], const double nl[3])
{
    const double reach = 0.8660254037844386 * J->g->voxel_size;
    double d[3], best = 0, dist = reach;
    voxgi__hit hit;
    int side, a;
    for (side = 0; side < 2; side++) {
        for (a = 0; a < 3; a++) d[a] = side ? -nl[a] : nl[a];
        if (voxgi__trace(J->lights->tr, c, d, dist, UINT32_MAX, 0, &hit) && hit.t < dist) {
            dist = hit.t;
            best = side ? -hit.t : hit.t;
        }
    }
    return best / J->g->voxel_size;
}

/* The back side's lookup point of a voxel whose front looks up at p along nl: as far behind its
   surface (where it crosses the normal through the centre) as p is before the centre, so that a
   light map's bias cannot reach through the surface from it. Returns that surface's
   voxgi__surface_offset (its side plane needs it too). */
static double voxgi__back_point(const voxgi__inject *J, const double p[3], const double nl[3], double pb[3])
{
    const double off = 0.8660254037844386 * J->g->voxel_size;
    double c[3], behind, surface;
    int a;
    for (a = 0; a < 3; a++) c[a] = p[a] - off * nl[a];
    surface = voxgi__surface_offset(J, c, nl);
    behind = surface * J->g->voxel_size - off;
    for (a = 0; a < 3; a++) pb[a] = c[a] + behind * nl[a];
    return surface;
}

/* The i-th set voxel's radiance, premultiplied, from the irradiance e at its lookup point and
   e_back at the mirror point behind its surface; and its side: (alpha n, alpha n.s), s where
   its surface crosses the normal through its centre (grid units), so that a point between the
   centre and the surface is not taken for one behind it. */
/* Voxel i's light into the volume's level 0; surface: its voxgi__surface_offset where known, else NAN. */
static void voxgi__inject_store(const voxgi__inject *J, size_t i, const double e[3], const double e_back[3], double surface)
{
    const voxgi_grid *g = J->g;
    uint64_t l = J->index[i];
    float *o = J->rgba + 4 * l, *b, *sd;
    double p[3], nl[3], c[3];
    int a, has_normal, plane;
    o[3] = J->vals[3] ? J->vals[3][i] : 1.0f;
    for (a = 0; a < 3; a++)
        o[a] = o[3] * (float)(J->vals[0][3 * i + (size_t)a] / VOXGI__PI * e[a] + (J->vals[2] ? J->vals[2][3 * i + (size_t)a] : 0.0f));
    if (!J->back) return;
    has_normal = voxgi__inject_point(J, i, p, nl);
    plane = has_normal && !(J->own_plane && J->own_plane[i]); /* a voxel of surfaces facing apart has none (voxgi__inject_planes) */
    b = J->back + 4 * l;
    sd = J->side + 4 * l;
    for (a = 0; a < 3; a++) c[a] = p[a] - 0.8660254037844386 * g->voxel_size * nl[a]; /* the centre, world units */
    b[3] = o[3];
    for (a = 0; a < 3; a++) {
        b[a] = has_normal ? o[3] * (float)(J->vals[0][3 * i + (size_t)a] / VOXGI__PI * e_back[a]) : o[a];
        sd[a] = plane ? o[3] * (float)nl[a] : 0.0f;
    }
    sd[3] = plane ? o[3] * (float)(nl[0] * (c[0] - g->origin[0]) / g->voxel_size + nl[1] * (c[1] - g->origin[1]) / g->voxel_size +
                                   nl[2] * (c[2] - g->origin[2]) / g->voxel_size + (isnan(surface) ? voxgi__surface_offset(J, c, nl) : surface))
                  : 0.0f;
}

/* The irradiance at p on unit normal nl from the lights, `samples` points on area lights and
   emitters stratified (a 2D Kronecker sequence shifted per voxel and side). */
static void voxgi__inject_irradiance(const voxgi__inject *J, size_t i, int side, const double p[3], const double nl[3], uint64_t *rays, double e[3])
{
    int samples = J->desc->samples, s, a;
    voxgi__rng rng;
    double rot[2];
    voxgi__rng_seed(&rng, J->desc->seed, J->index[i], (uint64_t)side);
    rot[0] = voxgi__rng_unit(&rng);
    rot[1] = voxgi__rng_unit(&rng);
    e[0] = e[1] = e[2] = 0;
    for (s = 0; s < samples; s++) { /* the lights once per sample (delta lights give the same each time) */
        double es[3], u[2];
        voxgi__kronecker(2, s, rot, u);
        voxgi__direct(J->lights, p, nl, UINT32_MAX, &rng, 0, u, rays, es, NULL);
        for (a = 0; a < 3; a++) e[a] += es[a] / samples;
    }
}

static void voxgi__inject_cpu(void *user, size_t first, size_t end)
{
    voxgi__inject *J = (voxgi__inject *)user;
    uint64_t rays = 0;
    size_t i;
    int a;
    for (i = first; i < end; i++) {
        double p[3], nl[3], e[3] = {0, 0, 0}, eb[3] = {0, 0, 0}, surface = NAN;
        if (voxgi__inject_point(J, i, p, nl)) { /* no normal: the voxel only emits */
            voxgi__inject_irradiance(J, i, 0, p, nl, &rays, e);
            if (J->back) {
                double pb[3];
                surface = voxgi__back_point(J, p, nl, pb);
                for (a = 0; a < 3; a++) nl[a] = -nl[a];
                voxgi__inject_irradiance(J, i, 1, pb, nl, &rays, eb);
            }
        }
        voxgi__inject_store(J, i, e, eb, surface);
    }
    VOXGI__ATOMIC_ADD_SIZE(&J->rays, (size_t)rays);
}

#ifndef VOXGI_NO_GL
/* Light injection on GL from distance maps (shaders/light_maps.glsl, light_map_draw.glsl,
   inject.glsl). Each light becomes casters with maps: a directional light one orthographic
   layer, a point or spot light six cube faces, a rectangular light or the emitters `samples`
   stratified points with six faces each (their surface's cosine, area over samples). The maps
   are drawn, then every voxel gathers the irradiance at the same lookup point as the CPU's,
   visibility from its map texel instead of a shadow ray (a gather per voxel: no voxel is missed
   where the map's texels are sparser than the voxels, and the energy per voxel is the analytic
   irradiance times the visible share, so it is right wherever nothing shadows). Out: 4 floats
   per voxel, irradiance in xyz. */
typedef struct voxgi__caster { float pos[4], dir[4], power[4], param[4]; } voxgi__caster; /* std430, as Caster */

/* The casters of a scene's light, each with its map layers (power[3]: the first layer): a
   directional light one orthographic layer over a sphere around the grid and the scene, a
   point or spot light six cube faces, a rectangular light and the emitters `samples` stratified
   points with six faces each. Positions relative to the grid's origin. What light-space passes
   draw maps from. */
static voxgi_result voxgi__light_casters(voxgi_context *ctx, const voxgi__tracer *tr, const voxgi__lights *Ls, const voxgi_grid *g,
                                         int samples, voxgi__caster **out, size_t *count, int *layer_count)
{
    const voxgi_scene *scene = Ls->scene;
    size_t nt = tr->flat.triangle_count, i, nc = 0, cap;
    voxgi__caster *cs;
    double lo[3], hi[3], centre[3], radius = 0, vs = g->voxel_size;
    int a, layers = 0, f;
    voxgi_result r = VOXGI_OK;
    for (a = 0; a < 3; a++) { lo[a] = 0; hi[a] = g->res[a] * vs; } /* the grid and every triangle, relative to the origin */
    for (i = 0; i < 9 * nt; i++) {
        double c = tr->v[i] - g->origin[i % 3];
        lo[i % 3] = VOXGI__MIN(lo[i % 3], c);
        hi[i % 3] = VOXGI__MAX(hi[i % 3], c);
    }
    for (a = 0; a < 3; a++) { centre[a] = (lo[a] + hi[a]) / 2; radius += (hi[a] - lo[a]) * (hi[a] - lo[a]) / 4; }
    radius = 1.01 * sqrt(radius) + vs;
    cap = scene->light_count + (size_t)samples * (scene->light_count + 1);
    cs = (voxgi__caster *)voxgi__alloc_array(ctx, cap, sizeof *cs, 1);
    if (!cs) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the light maps");
    for (i = 0; r == VOXGI_OK && i < scene->light_count; i++) {
        const voxgi_light *L = &scene->lights[i];
        double d[3], len = sqrt((double)L->direction[0] * L->direction[0] + (double)L->direction[1] * L->direction[1] + (double)L->direction[2] * L->direction[2]);
        int k, count = L->type == VOXGI_LIGHT_RECT ? samples : 1;
        for (a = 0; a < 3; a++) d[a] = len > 0 ? L->direction[a] / len : 0;
        for (k = 0; k < count; k++) {
            voxgi__caster *c = &cs[nc++];
            for (a = 0; a < 3; a++) {
                c->pos[a] = (float)(L->position[a] - g->origin[a]);
                c->dir[a] = (float)d[a];
                c->power[a] = L->intensity[a];
            }
            c->pos[3] = L->type == VOXGI_LIGHT_DIRECTIONAL ? 0.0f : (L->type == VOXGI_LIGHT_POINT ? 1.0f : (L->type == VOXGI_LIGHT_SPOT ? 2.0f : 3.0f));
            c->power[3] = (float)layers;
            layers += L->type == VOXGI_LIGHT_DIRECTIONAL ? 1 : 6;
            if (L->type == VOXGI_LIGHT_DIRECTIONAL) {
                for (a = 0; a < 3; a++) c->pos[a] = (float)(centre[a] - radius * d[a]);
                c->dir[3] = (float)radius;
            } else if (L->type == VOXGI_LIGHT_SPOT) {
                c->param[0] = (float)cos((double)L->spot_inner);
                c->param[1] = (float)cos((double)L->spot_outer);
            } else if (L->type == VOXGI_LIGHT_RECT) {
                double q[3], nn[3], power[3];
                uint32_t own;
                voxgi__area_point(Ls, L, k, samples, q, nn, power, &own);
                for (a = 0; a < 3; a++) {
                    c->pos[a] = (float)(q[a] - g->origin[a]);
                    c->dir[a] = (float)nn[a];
                    c->power[a] = (float)power[a];
                }
            }
        }
    }
    for (f = 0; r == VOXGI_OK && Ls->emitter_count && f < samples; f++) { /* points on the emitters by power, stratified */
        voxgi__caster *c = &cs[nc++];
        double q[3], nn[3], power[3];
        uint32_t own;
        voxgi__area_point(Ls, NULL, f, samples, q, nn, power, &own);
        for (a = 0; a < 3; a++) {
            c->pos[a] = (float)(q[a] + 1e-3 * vs * nn[a] - g->origin[a]); /* just off its own triangle */
            c->dir[a] = (float)nn[a];
            c->power[a] = (float)power[a];
        }
        c->pos[3] = 3;
        c->power[3] = (float)layers;
        layers += 6;
    }
    if (r != VOXGI_OK) { voxgi__free(ctx, cs); cs = NULL; nc = 0; }
    *out = cs;
    *count = nc;
    *layer_count = layers;
    return r;
}

/* Draws the casters' distance maps (shaders/light_map_draw.glsl) into a new R32UI array
   texture of `layers` size x size layers; *caster_buffer keeps the casters for the gather. */
static voxgi_result voxgi__light_maps_gl(voxgi_context *ctx, const voxgi__tracer *tr, const voxgi_grid *g, const voxgi__caster *cs,
                                         size_t nc, int layers, int size, unsigned int *caster_buffer, unsigned int *maps_out)
{
    voxgi__gl *gl = ctx->gl;
    size_t nt = tr->flat.triangle_count, i;
    float *corners;
    double vs = g->voxel_size;
    unsigned int corner_buffer, maps = 0, fbo = 0, vao = 0;
    int f, max_layers = 0;
    voxgi__gl_raster_state state;
    const unsigned int far_bits = 0x7F7FFFFFu; /* FLT_MAX: nothing there */
    unsigned int p = gl->prog_light_map_draw;
    gl->GetIntegerv(VOXGI__GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
    if (layers > max_layers)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%d light map layers, GL_MAX_ARRAY_TEXTURE_LAYERS is %d (fewer samples or lights)", layers, max_layers);
    if ((double)size * size * 4 * layers > (ctx->desc.memory_budget ? (double)ctx->desc.memory_budget : 4e9))
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%d light maps of %d^2 texels", layers, size);
    if (!(corners = (float *)voxgi__alloc_array(ctx, nt ? 3 * nt : 1, 16, 1)))
        return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the light maps");
    for (i = 0; i < 9 * nt; i++) corners[4 * (i / 3) + i % 3] = (float)(tr->v[i] - g->origin[i % 3]);
    corner_buffer = voxgi__gl_buffer(ctx, 3 * nt * 16, corners);
    *caster_buffer = voxgi__gl_buffer(ctx, nc * sizeof *cs, cs);
    gl->CreateTextures(VOXGI__GL_TEXTURE_2D_ARRAY, 1, &maps);
    gl->TextureStorage3D(maps, 1, VOXGI__GL_R32UI, size, size, layers);
    gl->ClearTexImage(maps, 0, VOXGI__GL_RED_INTEGER, VOXGI__GL_UNSIGNED_INT, &far_bits);
    voxgi__gl_raster_begin(gl, &state);
    gl->CreateVertexArrays(1, &vao);
    gl->CreateFramebuffers(1, &fbo);
    gl->NamedFramebufferParameteri(fbo, VOXGI__GL_FRAMEBUFFER_DEFAULT_WIDTH, size);
    gl->NamedFramebufferParameteri(fbo, VOXGI__GL_FRAMEBUFFER_DEFAULT_HEIGHT, size);
    gl->BindFramebuffer(VOXGI__GL_FRAMEBUFFER, fbo);
    gl->BindVertexArray(vao);
    gl->Viewport(0, 0, size, size);
    gl->UseProgram(p);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 0, corner_buffer);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 1, *caster_buffer);
    gl->BindImageTexture(0, maps, 0, 1, 0, VOXGI__GL_READ_WRITE, VOXGI__GL_R32UI);
    gl->ProgramUniform1f(p, VOXGI__LOC_u_near, (float)(1e-4 * vs));
    for (i = 0; i < nc; i++)
        for (f = cs[i].pos[3] == 0 ? -1 : 0; f < (cs[i].pos[3] == 0 ? 0 : 6); f++) {
            gl->ProgramUniform1i(p, VOXGI__LOC_u_caster, (int)i);
            gl->ProgramUniform1i(p, VOXGI__LOC_u_face, f);
            gl->DrawArrays(VOXGI__GL_TRIANGLES, 0, (int)(3 * nt));
        }
    gl->MemoryBarrier(VOXGI__GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    gl->BindFramebuffer(VOXGI__GL_FRAMEBUFFER, 0);
    gl->BindVertexArray(0);
    gl->DeleteFramebuffers(1, &fbo);
    gl->DeleteVertexArrays(1, &vao);
    voxgi__gl_raster_end(gl, &state);
    gl->BindImageTexture(0, 0, 0, 0, 0, VOXGI__GL_READ_WRITE, VOXGI__GL_R32UI);
    voxgi__gl_unbind(gl);
    voxgi__gl_delete_buffer(ctx, corner_buffer);
    voxgi__free(ctx, corners);
    *maps_out = maps;
    return VOXGI_OK;
}

static voxgi_result voxgi__inject_gl(voxgi_context *ctx, const voxgi__tracer *tr, const voxgi__lights *Ls, const voxgi_grid *g,
                                     int samples, size_t n, const float *pts, float *irr)
{
    voxgi__gl *gl = ctx->gl;
    size_t nc = 0;
    voxgi__caster *cs = NULL;
    double vs = g->voxel_size;
    unsigned int bufs[2] = {0, 0}, casters = 0, maps = 0;
    int a, layers = 0, size, res = VOXGI__MAX(g->res[0], VOXGI__MAX(g->res[1], g->res[2]));
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_light_map_draw);
    if (r == VOXGI_OK) r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_inject);
    if (r != VOXGI_OK) return r;
    size = VOXGI__MIN(2048, VOXGI__MAX(64, 2 * res));
    r = voxgi__light_casters(ctx, tr, Ls, g, samples, &cs, &nc, &layers);
    if (r == VOXGI_OK && layers > 0) r = voxgi__light_maps_gl(ctx, tr, g, cs, nc, layers, size, &casters, &maps);
    if (r == VOXGI_OK && n) { /* the gather */
        unsigned int p = gl->prog_inject;
        bufs[0] = voxgi__gl_buffer(ctx, n * 32, pts);
        bufs[1] = voxgi__gl_buffer(ctx, n * 16, NULL);
        gl->UseProgram(p);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 0, bufs[0]);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 1, casters ? casters : bufs[1]);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 2, bufs[1]);
        if (maps) gl->BindImageTexture(0, maps, 0, 1, 0, VOXGI__GL_READ_ONLY, VOXGI__GL_R32UI);
        gl->ProgramUniform1ui(p, VOXGI__LOC_u_count, (unsigned)n);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_casters, layers > 0 ? (int)nc : 0);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_size, size);
        gl->ProgramUniform1f(p, VOXGI__LOC_u_bias, (float)(0.25 * vs));
        voxgi__gl_dispatch_rows(gl, n);
        r = voxgi__gl_read_buffer(ctx, bufs[1], irr, n * 16);
    }
    gl->BindImageTexture(0, 0, 0, 0, 0, VOXGI__GL_READ_WRITE, VOXGI__GL_R32UI);
    voxgi__gl_unbind(gl);
    for (a = 0; a < 2; a++) voxgi__gl_delete_buffer(ctx, bufs[a]);
    voxgi__gl_delete_buffer(ctx, casters);
    if (maps) gl->DeleteTextures(1, &maps);
    voxgi__free(ctx, cs);
    if (r == VOXGI_OK) r = voxgi__gl_check(ctx, "light injection");
    return r;
}
#endif

/* The bounces' gather points: the set voxels that have a normal, in groups of those in one block
   of `block`^3 voxels whose normals share their dominant axis and its sign (a wall's voxels in a
   block, apart from a floor's meeting it there). A group gathers once, at its members' mean
   centre on their mean normal; indirect light varies slowly over a block, and a block of a
   plane holds about block^2 voxels, so the bounces cost that much less. With the regions of
   empty space (labels: level 0's, or NULL), a group holds one region's voxels, by the region
   their normal points into (voxgi__region_along): a floor running under a wall between two
   closed rooms is two groups, each gathering in its own room. group[i]: voxel i's group, or
   SIZE_MAX without a normal. sides 2: the *count groups are followed by the same points on the
   reverse normals (the back sides' gathers). */
static voxgi_result voxgi__bounce_groups(voxgi_context *ctx, const voxgi__inject *J, size_t n, int block, int sides, const uint32_t *labels,
                                         size_t region_count, size_t *group, float **pos_out, float **nrm_out, size_t *count)
{
    const double off = 0.8660254037844386 * J->g->voxel_size;
    uint64_t *code = (uint64_t *)voxgi__alloc_array(ctx, n ? n : 1, 8, 0);
    uint32_t *order = (uint32_t *)voxgi__alloc_array(ctx, n ? n : 1, 4, 0);
    float *pos = (float *)voxgi__alloc_array(ctx, n ? n : 1, 12 * (size_t)sides, 0), *nrm = (float *)voxgi__alloc_array(ctx, n ? n : 1, 12 * (size_t)sides, 0);
    size_t i, lit = 0, ng = 0, k;
    voxgi_result r = VOXGI_OK;
    int a, bits = 0, shift, dm[3];
    for (a = 0; a < 3; a++) dm[a] = J->g->res[a];
    while ((1 << bits) < VOXGI__MAX(dm[0], VOXGI__MAX(dm[1], dm[2]))) bits++;
    shift = 3 + 3 * bits; /* the region goes above the block's Morton code and its class */
    if (shift + 1 + (int)floor(log2((double)region_count + 1)) > 64) labels = NULL; /* no room for it: blocks alone */
    if ((uint64_t)n > UINT32_MAX) r = voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%lu voxels: the bounces sort at most 2^32 of them", (unsigned long)n);
    else if (!code || !order || !pos || !nrm) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the bounces of %lu voxels", (unsigned long)n);
    for (i = 0; r == VOXGI_OK && i < n; i++) {
        const voxgi_grid *g = J->g;
        uint64_t l = J->index[i];
        uint32_t x = (uint32_t)(l % (uint64_t)g->res[0]), y = (uint32_t)(l / (uint64_t)g->res[0] % (uint64_t)g->res[1]),
                 z = (uint32_t)(l / ((uint64_t)g->res[0] * (uint64_t)g->res[1]));
        double p[3], nl[3];
        int axis = 0, c[3];
        uint64_t region = 0;
        group[i] = SIZE_MAX;
        if (!voxgi__inject_point(J, i, p, nl)) continue;
        c[0] = (int)x; c[1] = (int)y; c[2] = (int)z;
        if (labels && (region = voxgi__region_along(dm, labels, c, nl)) == VOXGI__REGION_MIXED) region = 0;
        for (a = 1; a < 3; a++)
            if (fabs(nl[a]) > fabs(nl[axis])) axis = a;
        code[lit] = region << shift | voxgi__morton(x / (uint32_t)block, y / (uint32_t)block, z / (uint32_t)block) << 3 | (uint64_t)(2 * axis + (nl[axis] < 0));
        order[lit++] = (uint32_t)i;
    }
    if (r == VOXGI_OK) r = voxgi__sort_codes(ctx, code, order, lit, 64);
    for (k = 0; r == VOXGI_OK && k < lit; ng++) { /* a run of equal codes is a group: its sums, in sorted order */
        double c[3] = {0, 0, 0}, nsum[3] = {0, 0, 0}, len = 0;
        size_t first = k;
        for (; k < lit && code[k] == code[first]; k++) {
            double p[3], nl[3];
            voxgi__inject_point(J, order[k], p, nl);
            for (a = 0; a < 3; a++) { c[a] += p[a] - off * nl[a]; nsum[a] += nl[a]; }
            group[order[k]] = ng;
        }
        for (a = 0; a < 3; a++) len += nsum[a] * nsum[a];
        len = sqrt(len);
        for (a = 0; a < 3; a++) {
            pos[3 * ng + (size_t)a] = (float)(c[a] / (double)(k - first));
            nrm[3 * ng + (size_t)a] = len > 0 ? (float)(nsum[a] / len) : (float)(a == 1); /* opposite normals sharing a class cannot cancel */
        }
    }
    for (k = 0; r == VOXGI_OK && sides == 2 && k < 3 * ng; k++) {
        pos[3 * ng + k] = pos[k];
        nrm[3 * ng + k] = -nrm[k];
    }
    voxgi__free(ctx, code);
    voxgi__free(ctx, order);
    if (r != VOXGI_OK) { voxgi__free(ctx, pos); voxgi__free(ctx, nrm); pos = nrm = NULL; ng = 0; }
    *pos_out = pos;
    *nrm_out = nrm;
    *count = ng;
    return r;
}

/* The regions of volume `from` moved to `to` (of the same grid): a bounce's volume keeps the
   regions of the direct light's, since a closed region's light is what its own surfaces receive
   directly; labels taken from the bounces would follow their leaks. */
static void voxgi__volume_take_regions(voxgi_volume *to, voxgi_volume *from)
{
    to->regions = from->regions;
    to->region_boxes = from->region_boxes;
    to->region_count = from->region_count;
    to->region_buffer = from->region_buffer;
    to->regions_given = 1;
    if (to->region_count) to->info.bytes += (to->voxels + 6 * to->region_count) * 4;
    from->regions = from->region_boxes = NULL;
    from->region_count = 0;
    from->region_buffer = 0;
}

/* The bounces still to come added to a voxel's light rgb: tail x its last bounce's step, per
   channel. A channel whose light fell in the last bounce (rounding: the bounces only add light)
   has no tail to come; extrapolated, it went below zero (full GI's dark voxels). */
static void voxgi__add_bounce_tail(float rgb[3], const float last_step[3], float tail)
{
    int a;
    for (a = 0; a < 3; a++) rgb[a] += tail * VOXGI__MAX(last_step[a], 0.0f);
}

/* The light's further bounces among the voxels (desc->bounces > 1, or -1: until one adds less
   than VOXGI_CONVERGED_BOUNCE of the light): each group of voxels (voxgi__bounce_groups) gathers
   from *vol, on its normal for the front and on the reverse for the back, its voxels' radiance
   becomes direct + alpha albedo / pi x that, and *vol is rebuilt. */
static voxgi_result voxgi__inject_bounces(voxgi_context *ctx, voxgi__inject *J, size_t n, const voxgi_inject_desc *desc, voxgi_volume **vol)
{
    const voxgi_grid *g = J->g;
    size_t *group = (size_t *)voxgi__alloc_array(ctx, n ? n : 1, sizeof(size_t), 0), ng = 0, i, k;
    int sides = J->back ? 2 : 1, b, a, sd, converged = 0;
    double share = 1, last_added = 0;
    float *pos = NULL, *nrm = NULL, *irr = NULL, *step = NULL, *direct = (float *)voxgi__alloc_array(ctx, n ? n : 1, 12 * (size_t)sides, 0);
    const float *slots[VOXGI__VOLUME_SLOTS] = {NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    const uint32_t *labels = (*vol)->regions;
    uint32_t *read = NULL;
    voxgi_result r = VOXGI_OK;
    if (!group || !direct) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the bounces of %lu voxels", (unsigned long)n);
    if (r == VOXGI_OK && (*vol)->region_count && !labels) { /* GL keeps the labels in its buffer: level 0's read back */
#ifndef VOXGI_NO_GL
        size_t level0 = (size_t)voxgi_grid_voxel_count(g);
        if (!(read = (uint32_t *)voxgi__alloc_array(ctx, level0, 4, 0))) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the regions' labels");
        else ctx->gl->GetNamedBufferSubData((*vol)->region_buffer, 0, (ptrdiff_t)(level0 * 4), read);
        labels = read;
#endif
    }
    if (r == VOXGI_OK) r = voxgi__bounce_groups(ctx, J, n, desc->gather_block, sides, labels, (*vol)->region_count, group, &pos, &nrm, &ng);
    voxgi__free(ctx, read);
    if (r == VOXGI_OK && !(irr = (float *)voxgi__alloc_array(ctx, ng ? ng : 1, 12 * (size_t)sides, 0)))
        r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the bounces of %lu voxels", (unsigned long)n);
    for (i = 0; r == VOXGI_OK && i < n; i++)
        for (a = 0; a < 3; a++) {
            direct[3 * i + (size_t)a] = J->rgba[4 * J->index[i] + (size_t)a];
            if (sides == 2) direct[3 * (n + i) + (size_t)a] = J->back[4 * J->index[i] + (size_t)a];
        }
    if (r == VOXGI_OK && desc->bounces < 0 && !(step = (float *)voxgi__alloc_array(ctx, n ? n : 1, 12 * (size_t)sides, 0)))
        r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the bounces of %lu voxels", (unsigned long)n);
    for (b = 1; r == VOXGI_OK && b < (desc->bounces < 0 ? 64 : desc->bounces) && !converged; b++) {
        voxgi_volume *next = NULL;
        voxgi_radiance_source source;
        double before = 0, after = 0, ratio;
        memset(&source, 0, sizeof source);
        source.volume = *vol;
        /* until convergence: how far the last bounce's share of the light has come down towards the bar */
        if (voxgi__cancelled(ctx, desc->bounces >= 0 ? (double)(b - 1) / (desc->bounces - 1)
                                                     : VOXGI__MIN(0.99, VOXGI__MAX(0.0, log(share) / log(VOXGI_CONVERGED_BOUNCE))),
                             "light injection", "bounces among the voxels"))
            r = VOXGI_ERR_CANCELLED;
        if (r == VOXGI_OK) r = voxgi_cone_trace(ctx, &source, &desc->gather, ng * (size_t)sides, pos, nrm, irr, NULL);
        for (sd = 0; r == VOXGI_OK && sd < sides; sd++) /* a voxel without a normal only emits: it keeps its direct light */
            for (i = 0; i < n; i++) {
                float *o = (sd ? J->back : J->rgba) + 4 * J->index[i];
                for (a = 0; a < 3; a++) {
                    float was = o[a];
                    k = 3 * ((size_t)sd * ng + group[i]) + (size_t)a;
                    before += o[a];
                    o[a] = direct[3 * ((size_t)sd * n + i) + (size_t)a] +
                           (group[i] != SIZE_MAX ? o[3] * (float)(J->vals[0][3 * i + (size_t)a] / VOXGI__PI * irr[k]) : 0.0f);
                    after += o[a];
                    if (step) step[3 * ((size_t)sd * n + i) + (size_t)a] = o[a] - was;
                }
            }
        /* Bounces shrink the light about geometrically, by `ratio` each: what all the bounces still
           to come add is about this bounce's light x ratio / (1 - ratio). At albedo 0.999 that tail
           is hundreds of times what 64 bounces gather, so convergence is judged by it, and the last
           round adds it to each voxel. */
        ratio = last_added > 0 ? (after - before) / last_added : 0;
        share = after > 0 && ratio < 1 ? (after - before) * (b > 1 ? ratio / (1 - ratio) : 1) / after : 1;
        last_added = after - before;
        converged = desc->bounces < 0 && !(share > VOXGI_CONVERGED_BOUNCE);
        if (step && (converged || b + 1 == 64) && b > 1 && ratio > 0 && ratio < 1) {
            float tail = (float)(ratio / (1 - ratio));
            for (sd = 0; sd < sides; sd++)
                for (i = 0; i < n; i++) {
                    voxgi__add_bounce_tail((sd ? J->back : J->rgba) + 4 * J->index[i], step + 3 * ((size_t)sd * n + i), tail);
                }
        }
        if (converged) voxgi__log(ctx, VOXGI_LOG_INFO, "light injection: the bounces still to come add about %.2g%% of the light: %d bounces and their geometric tail", 100 * share, b + 1);
        else if (desc->bounces < 0 && b + 1 == 64)
            voxgi__log(ctx, VOXGI_LOG_INFO, "light injection: after 64 bounces the rest (about %.2g%% of the light, ratio %.4f a bounce) added as a geometric tail", 100 * share, ratio);
        slots[VOXGI__RADIANCE_SLOT] = J->rgba;
        slots[VOXGI__BACK_SLOT] = J->back;
        slots[VOXGI__SIDE_SLOT] = J->side;
        if (r == VOXGI_OK) r = voxgi__volume_new(ctx, g, &desc->volume, (*vol)->info.attributes, &next);
        if (r == VOXGI_OK) voxgi__volume_take_regions(next, *vol);
        if (r == VOXGI_OK) r = voxgi__volume_build(ctx, next, slots);
        if (r == VOXGI_OK) { voxgi_volume_destroy(ctx, *vol); *vol = next; }
        else voxgi_volume_destroy(ctx, next);
    }
    voxgi__free(ctx, group);
    voxgi__free(ctx, pos);
    voxgi__free(ctx, nrm);
    voxgi__free(ctx, irr);
    voxgi__free(ctx, step);
    voxgi__free(ctx, direct);
    return r;
}

/* Every default of a voxgi_inject_desc: 16 points per area light and on the emitters, bounces
   gathered with 4 cones per 4^3 block. */
static voxgi_inject_desc voxgi__inject_defaults(const voxgi_inject_desc *in)
{
    voxgi_inject_desc d = *in;
    if (!d.samples) d.samples = 16;
    if (!d.gather_block) d.gather_block = 4;
    if (!d.gather.cones) d.gather.cones = 4;
    return d;
}

/* voxgi_inject_light through the caller's tracer and lights of the scene (NULL: its own). */
static voxgi_result voxgi__inject_light(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_voxels *vx, const voxgi_inject_desc *desc_in,
                                        const voxgi__tracer *tr_in, const voxgi__lights *Ls_in, voxgi_volume **out)
{
    voxgi_inject_desc resolved;
    const voxgi_inject_desc *desc = &resolved;
    voxgi__tracer own_tr;
    voxgi__lights own_Ls;
    const voxgi__tracer *tr = tr_in;
    const voxgi__lights *Ls = Ls_in;
    voxgi__inject J;
    voxgi_volume *vol = NULL;
    float *vals[4] = {NULL, NULL, NULL, NULL}, *level0[3] = {NULL, NULL, NULL}, *own[3] = {NULL, NULL, NULL};
    uint64_t *index = NULL, nvox, l;
    uint32_t *bits = NULL;
    size_t need = 0, n, i = 0;
    const float *slots[VOXGI__VOLUME_SLOTS] = {NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    double t0 = voxgi__now_ms();
    int a, sides;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!vx || !desc_in || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "voxels, desc or out is NULL");
    *out = NULL;
    resolved = voxgi__inject_defaults(desc_in);
    if ((vx->info.attributes & (VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL)) != (VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "light injection needs voxels with ALBEDO and NORMAL (they hold 0x%x)", vx->info.attributes);
    if (desc->samples < 0 || desc->bounces < -1 || desc->bounces > 64 || desc->gather_block < 1 || desc->gather_block > 64)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "samples %d, bounces %d (-1..64), gather block %d (1..64)", desc->samples, desc->bounces,
                           desc->gather_block);
    if ((r = voxgi__validate(ctx, scene, NULL, NULL)) != VOXGI_OK) return r;
    memset(&own_tr, 0, sizeof own_tr);
    memset(&own_Ls, 0, sizeof own_Ls);
    if (!tr) {
        if ((r = voxgi__tracer_build(ctx, scene, &own_tr)) != VOXGI_OK) return r;
        r = voxgi__lights_build(ctx, scene, &own_tr, &own_Ls);
        tr = &own_tr;
        Ls = &own_Ls;
    }
    nvox = voxgi_grid_voxel_count(&vx->info.grid);
    n = (size_t)vx->info.voxel_count;
    if (r == VOXGI_OK) r = voxgi_voxels_read(ctx, vx, NULL, 0, &need);
    sides = desc->one_sided ? 1 : 2;
    if (r == VOXGI_OK)
        r = voxgi__volume_new(ctx, &vx->info.grid, &desc->volume,
                              VOXGI_ATTRIBUTE_RADIANCE | (sides == 2 ? VOXGI_ATTRIBUTE_RADIANCE_BACK | VOXGI_ATTRIBUTE_RADIANCE_SIDE : 0u), &vol);
    for (a = 0; a < (sides == 2 ? 3 : 1) && r == VOXGI_OK; a++) {
        if (ctx->backend == VOXGI_BACKEND_CPU && desc->bounces >= 0 && desc->bounces <= 1) { /* level 0 written in place, the mips after it */
            vol->cpu[VOXGI__RADIANCE_SLOT + a][0] = (float *)voxgi__alloc_array(ctx, vol->voxels, 16, 1);
            level0[a] = vol->cpu[VOXGI__RADIANCE_SLOT + a][0];
        } else /* GL uploads it; the bounces rewrite it for each new volume */
            own[a] = level0[a] = (float *)voxgi__alloc_array(ctx, (size_t)nvox, 16, 1);
        if (!level0[a]) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the radiance of %lu voxels", (unsigned long)n);
    }
    if (r == VOXGI_OK && (!(bits = (uint32_t *)voxgi__alloc(ctx, need)) || !(index = (uint64_t *)voxgi__alloc_array(ctx, n ? n : 1, 8, 0))))
        r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the radiance of %lu voxels", (unsigned long)n);
    if (r == VOXGI_OK) r = voxgi_voxels_read(ctx, vx, bits, need, NULL);
    for (l = 0; r == VOXGI_OK && l < nvox; l++)
        if (voxgi_bit_get(bits, l)) index[i++] = l;
    for (a = 0; a < 4 && r == VOXGI_OK; a++) {
        voxgi_attribute which = (voxgi_attribute)(1 << a);
        if (!(vx->info.attributes & (unsigned)which)) continue;
        r = voxgi_voxels_read_attribute(ctx, vx, which, NULL, 0, &need);
        if (r == VOXGI_OK && !(vals[a] = (float *)voxgi__alloc(ctx, need ? need : 4))) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory");
        if (r == VOXGI_OK) r = voxgi_voxels_read_attribute(ctx, vx, which, vals[a], need, NULL);
    }
    if (r == VOXGI_OK) {
        memset(&J, 0, sizeof J);
        J.lights = Ls;
        J.g = &vx->info.grid;
        J.desc = desc;
        J.index = index;
        J.vals = vals;
        J.rgba = level0[0];
        J.back = level0[1];
        J.side = level0[2];
        J.rays = 0;
        if (sides == 2 && !(J.own_plane = (unsigned char *)voxgi__alloc_array(ctx, n ? n : 1, 1, 1)))
            r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the planes of %lu voxels", (unsigned long)n);
        if (sides == 2 && r == VOXGI_OK) voxgi__inject_planes(&J, n);
#ifndef VOXGI_NO_GL
        if (ctx->backend == VOXGI_BACKEND_GL && !desc->shadow_rays) { /* lookup points up (the backs' after the fronts'),
                                                                         irradiance down, the rest as on the CPU */
            size_t m = (size_t)sides * n;
            float *io = (float *)voxgi__alloc_array(ctx, m ? m : 1, 32, 0);
            if (!io) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu lookup points", (unsigned long)m);
            for (i = 0; r == VOXGI_OK && i < m; i++) {
                double p[3], nl[3], sgn = i < n ? 1 : -1;
                io[8 * i + 7] = (float)voxgi__inject_point(&J, i % n, p, nl);
                if (i >= n) voxgi__back_point(&J, p, nl, p);
                for (a = 0; a < 3; a++) {
                    io[8 * i + (size_t)a] = (float)(p[a] - J.g->origin[a]);
                    io[8 * i + 4 + (size_t)a] = (float)(sgn * nl[a]);
                }
                io[8 * i + 3] = 0;
            }
            if (r == VOXGI_OK) r = voxgi__inject_gl(ctx, tr, Ls, J.g, desc->samples, m, io, io);
            for (i = 0; r == VOXGI_OK && i < n; i++) {
                double e[3], eb[3] = {0, 0, 0};
                for (a = 0; a < 3; a++) {
                    e[a] = io[4 * i + (size_t)a];
                    if (sides == 2) eb[a] = io[4 * (n + i) + (size_t)a];
                }
                voxgi__inject_store(&J, i, e, eb, NAN);
            }
            voxgi__free(ctx, io);
        } else
#endif
            voxgi__parallel(ctx, n, 256, voxgi__inject_cpu, &J);
        for (a = 0; a < 3; a++) slots[VOXGI__RADIANCE_SLOT + a] = level0[a];
        if (r == VOXGI_OK) r = voxgi__volume_build(ctx, vol, slots);
        if (r == VOXGI_OK && (desc->bounces > 1 || desc->bounces < 0)) r = voxgi__inject_bounces(ctx, &J, n, desc, &vol);
        if (r == VOXGI_OK) vol->info.ms = voxgi__now_ms() - t0;
        voxgi__free(ctx, J.own_plane);
    }
    if (r != VOXGI_OK) { voxgi_volume_destroy(ctx, vol); vol = NULL; }
    for (a = 0; a < 4; a++) voxgi__free(ctx, vals[a]);
    voxgi__free(ctx, bits);
    voxgi__free(ctx, index);
    for (a = 0; a < 3; a++) voxgi__free(ctx, own[a]);
    voxgi__lights_free(ctx, &own_Ls);
    voxgi__tracer_free(ctx, &own_tr);
    *out = vol;
    return r;
}

VOXGI_API voxgi_result voxgi_inject_light(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_voxels *vx, const voxgi_inject_desc *desc,
                                          voxgi_volume **out)
{
    return voxgi__inject_light(ctx, scene, vx, desc, NULL, NULL, out);
}
#endif /* VOXGI_NO_LIGHT_INJECTION */

/* ===================================================================== 10. light-space passes */

/* The most translucent absorptions a transmittance shadow map holds (one slicemap each): the
   planner counts them even where the maps are compiled out. */
#define VOXGI__TSM_MAX_MATERIALS 8

#ifndef VOXGI_NO_LIGHT_SPACE

/* ----- 10.1 a light's view of the scene

   The maps a light makes of the scene: u, v across and w along the light, in texel units across
   and slices along, so that a map is a grid of unit voxels. A directional light's view is
   orthographic over the scene's bounds, a spot light's perspective over its outer cone's square
   with slices uniform in 1 / depth (voxgi_tsm_desc says how). */
typedef struct voxgi__light_view {
    double u[3], v[3], w[3];      /* the light's frame: across the map, and the direction light travels */
    int perspective;              /* a spot light's map (else a directional light's) */
    int hemisphere;               /* a Lambertian point's map (eye, facing w): its hemisphere by the concentric map */
    double lo[3];                 /* orthographic: the map's corner in the frame (world units) */
    double texel, slice;          /* orthographic: world units */
    double eye[3], tan_half, near_z, far_z; /* perspective: the light's position, the cone, depths along w */
    int size, slices;
} voxgi__light_view;

/* ----- 10.2 transmittance shadow maps (voxgi_tsm)

   voxgi_voxelize's raster slicemap of each translucent material's triangles along z in the
   light's view, and the opaque triangles' least depth at each texel centre drawn by the same
   rasterizer on the CPU. */

struct voxgi_tsm {
    voxgi__light_view view;
    int words;                    /* 32-slice words per column */
    int materials;
    float sigma[VOXGI__TSM_MAX_MATERIALS];
    uint32_t *columns;            /* per material, per texel (row by row), `words` words of slice bits */
    float *opaque;                /* per texel: the least depth (slices) of an opaque surface, +inf: none */
    voxgi_tsm_info info;
    unsigned int gl_columns, gl_opaque, gl_params; /* on a GL context: the same, and the frame (tsm_lookup.glsl) */
};

/* Shirley and Chiu's concentric map between the square [-1,1]^2 and the unit disk: continuous,
   area-preserving up to pi / 4, so with the disk lifted to the hemisphere above it (Malley) each
   texel of a square map holds the same cosine-weighted solid angle, pi / texels. */
static void voxgi__square_to_disk(const double sq[2], double disk[2])
{
    double r, phi;
    if (sq[0] == 0 && sq[1] == 0) { disk[0] = disk[1] = 0; return; }
    if (fabs(sq[0]) > fabs(sq[1])) { r = sq[0]; phi = VOXGI__PI / 4 * sq[1] / sq[0]; }
    else { r = sq[1]; phi = VOXGI__PI / 2 - VOXGI__PI / 4 * sq[0] / sq[1]; }
    disk[0] = r * cos(phi);
    disk[1] = r * sin(phi);
}

/* The inverse, for a direction p (frame coordinates, w = p[2] up): its point of the disk, or
   for a direction at or below the horizon the rim toward it. */
static void voxgi__disk_to_square(const double p[3], double sq[2])
{
    double len = p[2] > 0 ? sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) : sqrt(p[0] * p[0] + p[1] * p[1]), x, y, r, phi;
    if (!(len > 0)) { sq[0] = sq[1] = 0; return; }
    x = p[0] / len;
    y = p[1] / len;
    r = VOXGI__MIN(1.0, sqrt(x * x + y * y));
    phi = atan2(y, x);
    if (phi < -VOXGI__PI / 4) phi += 2 * VOXGI__PI; /* [-pi/4, 7pi/4): the four wedges in turn */
    if (phi < VOXGI__PI / 4) { sq[0] = r; sq[1] = phi * 4 / VOXGI__PI * r; }
    else if (phi < 3 * VOXGI__PI / 4) { sq[1] = r; sq[0] = -(phi - VOXGI__PI / 2) * 4 / VOXGI__PI * r; }
    else if (phi < 5 * VOXGI__PI / 4) { sq[0] = -r; sq[1] = -(phi - VOXGI__PI) * 4 / VOXGI__PI * r; }
    else { sq[1] = -r; sq[0] = (phi - 3 * VOXGI__PI / 2) * 4 / VOXGI__PI * r; }
}

/* Point x (world) in the map's frame: texels across, slices along. Perspective: across, the
   cone's square; along, slices uniform in 1 / depth between near_z (where a point nearer is
   taken to lie) and far_z: a projective map, so triangles stay triangles and planes planes. */
static void voxgi__view_point(const voxgi__light_view *T, const double x[3], double out[3])
{
    if (T->hemisphere) {
        double r[3], p[3], sq[2];
        int a;
        for (a = 0; a < 3; a++) r[a] = x[a] - T->eye[a];
        p[0] = r[0] * T->u[0] + r[1] * T->u[1] + r[2] * T->u[2];
        p[1] = r[0] * T->v[0] + r[1] * T->v[1] + r[2] * T->v[2];
        p[2] = r[0] * T->w[0] + r[1] * T->w[1] + r[2] * T->w[2];
        voxgi__disk_to_square(p, sq);
        out[0] = 0.5 * T->size * (1 + sq[0]);
        out[1] = 0.5 * T->size * (1 + sq[1]);
        out[2] = 0;
        return;
    }
    if (T->perspective) {
        double r[3], z, s = T->size;
        int a;
        for (a = 0; a < 3; a++) r[a] = x[a] - T->eye[a];
        z = VOXGI__MAX(r[0] * T->w[0] + r[1] * T->w[1] + r[2] * T->w[2], T->near_z);
        out[0] = 0.5 * s * (1 + (r[0] * T->u[0] + r[1] * T->u[1] + r[2] * T->u[2]) / (z * T->tan_half));
        out[1] = 0.5 * s * (1 + (r[0] * T->v[0] + r[1] * T->v[1] + r[2] * T->v[2]) / (z * T->tan_half));
        out[2] = T->slices * (1 / T->near_z - 1 / z) / (1 / T->near_z - 1 / T->far_z);
        return;
    }
    out[0] = ((x[0] * T->u[0] + x[1] * T->u[1] + x[2] * T->u[2]) - T->lo[0]) / T->texel;
    out[1] = ((x[0] * T->v[0] + x[1] * T->v[1] + x[2] * T->v[2]) - T->lo[1]) / T->texel;
    out[2] = ((x[0] * T->w[0] + x[1] * T->w[1] + x[2] * T->w[2]) - T->lo[2]) / T->slice;
}

/* The triangle x[0..2] (world) in the map's frame, as 0, 1 or 2 triangles into out (9 each): in
   perspective, first cut to the part in front of the near plane. */
static int voxgi__view_triangle(const voxgi__light_view *T, const double x[3][3], double *out)
{
    double poly[4][3], z[3];
    int n = 0, k, a, tris;
    if (!T->perspective) {
        for (k = 0; k < 3; k++) voxgi__view_point(T, x[k], out + 3 * k);
        return 1;
    }
    for (k = 0; k < 3; k++) z[k] = (x[k][0] - T->eye[0]) * T->w[0] + (x[k][1] - T->eye[1]) * T->w[1] + (x[k][2] - T->eye[2]) * T->w[2] - T->near_z;
    for (k = 0; k < 3; k++) { /* Sutherland-Hodgman against z >= near */
        int j = (k + 1) % 3;
        if (z[k] >= 0) memcpy(poly[n++], x[k], sizeof poly[0]);
        if ((z[k] >= 0) != (z[j] >= 0)) {
            double f = z[k] / (z[k] - z[j]);
            for (a = 0; a < 3; a++) poly[n][a] = x[k][a] + f * (x[j][a] - x[k][a]);
            n++;
        }
    }
    if (n < 3) return 0;
    tris = n - 2;
    for (k = 0; k < tris; k++) { /* a fan */
        const double *c[3];
        int m;
        c[0] = poly[0];
        c[1] = poly[k + 1];
        c[2] = poly[k + 2];
        for (m = 0; m < 3; m++) voxgi__view_point(T, c[m], out + 9 * k + 3 * m);
    }
    return tris;
}

typedef struct voxgi__tsm_depth_job { float *map; int size; const double *q[3]; } voxgi__tsm_depth_job;

static void voxgi__tsm_depth_pixel(void *user, uint32_t tri, int i, int j)
{
    voxgi__tsm_depth_job *job = (voxgi__tsm_depth_job *)user;
    double z = voxgi__slicemap_depth(job->q[0], job->q[1], job->q[2], 2, (double)i + 0.5, (double)j + 0.5);
    float *m = &job->map[(size_t)j * (size_t)job->size + (size_t)i];
    (void)tri;
    if (z < (double)*m) *m = (float)z;
}

static void voxgi__tsm_free(voxgi_context *ctx, voxgi_tsm *T)
{
    if (!T) return;
#ifndef VOXGI_NO_GL
    if (T->gl_params) {
        voxgi__gl_delete_buffer(ctx, T->gl_columns);
        voxgi__gl_delete_buffer(ctx, T->gl_opaque);
        voxgi__gl_delete_buffer(ctx, T->gl_params);
    }
#endif
    voxgi__free(ctx, T->columns);
    voxgi__free(ctx, T->opaque);
    voxgi__free(ctx, T);
}

/* Material group g's slicemap: its triangles (group[t] == g of the n in the frame, 9 doubles
   each), voxelized along z and repacked by column. */
static voxgi_result voxgi__tsm_slicemap(voxgi_context *ctx, voxgi_tsm *T, const double *soup_in, const signed char *group, size_t count, int g)
{
    voxgi_voxelize_desc vd;
    voxgi_voxels *vox = NULL;
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_voxels_info vi;
    float *soup;
    uint32_t *bits = NULL;
    size_t t, n = 0, texels = (size_t)T->view.size * (size_t)T->view.size, k;
    int c;
    voxgi_result r = VOXGI_OK;
    for (t = 0; t < count; t++) n += group[t] == g;
    soup = (float *)voxgi__alloc_array(ctx, n ? n : 1, 9 * sizeof(float), 0);
    if (!soup) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu triangles", (unsigned long)n);
    for (t = 0, n = 0; t < count; t++) {
        if (group[t] != g) continue;
        for (c = 0; c < 9; c++) soup[9 * n + (size_t)c] = (float)soup_in[9 * t + (size_t)c];
        n++;
    }
    memset(&mesh, 0, sizeof mesh);
    mesh.positions = soup;
    mesh.vertex_count = 3 * n;
    memset(&sc, 0, sizeof sc);
    sc.meshes = &mesh;
    sc.mesh_count = 1;
    memset(&vd, 0, sizeof vd);
    vd.grid.voxel_size = 1;
    vd.grid.res[0] = vd.grid.res[1] = T->view.size;
    vd.grid.res[2] = T->view.slices;
    vd.method = VOXGI_METHOD_SLICEMAP;
    vd.axis = VOXGI_AXIS_Z;
    r = voxgi_voxelize(ctx, &sc, &vd, &vox);
    if (r == VOXGI_OK) {
        voxgi_voxels_query(vox, &vi);
        T->info.voxels += vi.voxel_count;
        bits = (uint32_t *)voxgi__alloc_array(ctx, 1, vi.bytes, 0);
        if (!bits) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory to read a slicemap");
        else r = voxgi_voxels_read(ctx, vox, bits, vi.bytes, NULL);
    }
    if (r == VOXGI_OK) /* slice k of texel (i, j) is voxel i + size (j + size k) */
        for (k = 0; k < (size_t)T->view.slices; k++)
            for (t = 0; t < texels; t++) {
                uint64_t l = (uint64_t)t + (uint64_t)texels * k;
                if (bits[l >> 5] >> (l & 31) & 1u) T->columns[((size_t)g * texels + t) * (size_t)T->words + (k >> 5)] |= 1u << (k & 31);
            }
    voxgi_voxels_destroy(ctx, vox);
    voxgi__free(ctx, bits);
    voxgi__free(ctx, soup);
    return r;
}

/* Scene light `index` for a light's view (what: the pass, for the message): it must exist and be
   DIRECTIONAL or SPOT. */
static voxgi_result voxgi__view_light(voxgi_context *ctx, const voxgi_scene *scene, size_t index, const char *what, const voxgi_light **L)
{
    if (index >= scene->light_count) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "light %lu of %lu", (unsigned long)index, (unsigned long)scene->light_count);
    *L = &scene->lights[index];
    if ((*L)->type != VOXGI_LIGHT_DIRECTIONAL && (*L)->type != VOXGI_LIGHT_SPOT) return voxgi__fail(ctx, VOXGI_ERR_UNSUPPORTED, "%s take a directional or spot light", what);
    return VOXGI_OK;
}

/* Light L's (scene light `index`, DIRECTIONAL or SPOT) view of the flattened scene f, V->size
   texels across and V->slices slices along (set by the caller). */
static voxgi_result voxgi__view_setup(voxgi_context *ctx, const voxgi__flat *f, const voxgi_light *L, size_t index, voxgi__light_view *V)
{
    double hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX}, len;
    size_t i;
    int a, size = V->size, slices = V->slices;
    if (L->type == VOXGI_LIGHT_SPOT && !(L->spot_outer > 0 && L->spot_outer < 1.5))
        return voxgi__fail(ctx, VOXGI_ERR_UNSUPPORTED, "a spot light's map needs its outer angle in (0, 1.5) radians, not %g", (double)L->spot_outer);
    len = sqrt((double)L->direction[0] * L->direction[0] + (double)L->direction[1] * L->direction[1] + (double)L->direction[2] * L->direction[2]);
    if (!(len > 0) || !isfinite(len)) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "light %lu has no direction", (unsigned long)index);
    for (a = 0; a < 3; a++) V->w[a] = L->direction[a] / len;
    voxgi__basis(V->w, V->u, V->v);
    if (L->type == VOXGI_LIGHT_SPOT) { /* the cone's square; depths from the scene's nearest point ahead to its farthest */
        double nearest = DBL_MAX;
        V->perspective = 1;
        V->tan_half = tan((double)L->spot_outer);
        for (a = 0; a < 3; a++) V->eye[a] = L->position[a];
        V->far_z = 0;
        for (i = 0; i < f->vertex_count; i++) {
            double z = 0;
            for (a = 0; a < 3; a++) z += ((double)f->pos[3 * i + (size_t)a] - V->eye[a]) * V->w[a];
            V->far_z = VOXGI__MAX(V->far_z, z);
            if (z > 0) nearest = VOXGI__MIN(nearest, z);
        }
        if (!(V->far_z > 0)) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "spot light %lu faces away from the whole scene", (unsigned long)index);
        V->near_z = VOXGI__MAX(VOXGI__MIN(nearest, V->far_z), 1e-3 * V->far_z) * (1 - 1e-6);
        V->far_z *= 1 + 1e-6;
    } else {
        for (a = 0; a < 3; a++) V->lo[a] = DBL_MAX;
        for (i = 0; i < f->vertex_count; i++) { /* the scene's bounds in the frame */
            const float *p = f->pos + 3 * i;
            double x[3], s[3];
            for (a = 0; a < 3; a++) x[a] = p[a];
            s[0] = x[0] * V->u[0] + x[1] * V->u[1] + x[2] * V->u[2];
            s[1] = x[0] * V->v[0] + x[1] * V->v[1] + x[2] * V->v[2];
            s[2] = x[0] * V->w[0] + x[1] * V->w[1] + x[2] * V->w[2];
            for (a = 0; a < 3; a++) { V->lo[a] = VOXGI__MIN(V->lo[a], s[a]); hi[a] = VOXGI__MAX(hi[a], s[a]); }
        }
        { /* square texels over the larger extent, half a texel to spare on each side; slices over the depth */
            double ext = VOXGI__MAX(hi[0] - V->lo[0], hi[1] - V->lo[1]), scale = VOXGI__MAX(ext, hi[2] - V->lo[2]);
            if (!(scale > 0)) scale = VOXGI__MAX(1.0, fabs(V->lo[0]) + fabs(V->lo[1]) + fabs(V->lo[2])) * 1e-6;
            ext = VOXGI__MAX(ext, scale * 1e-6);
            V->texel = ext / (size - 1 > 0 ? size - 1 : 1);
            V->lo[0] -= 0.5 * V->texel + 0.5 * (ext - (hi[0] - V->lo[0]));
            V->lo[1] -= 0.5 * V->texel + 0.5 * (ext - (hi[1] - V->lo[1]));
            V->slice = VOXGI__MAX(hi[2] - V->lo[2], scale * 1e-6) * (1 + 1e-6) / slices;
        }
    }
    return VOXGI_OK;
}

VOXGI_API voxgi_result voxgi_tsm_create(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_tsm_desc *desc, voxgi_tsm **out)
{
    voxgi__flat f;
    voxgi_tsm *T = NULL;
    const voxgi_light *L = NULL;
    double *soup = NULL, t0 = voxgi__now_ms();
    signed char *group = NULL;
    size_t i, t, texels, count = 0;
    int a, g, size, slices;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!scene || !desc || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "scene, desc or out is NULL");
    *out = NULL;
    size = desc->size ? desc->size : 512;
    slices = desc->slices ? desc->slices : 64;
    if (size < 1 || size > 16384 || slices < 1 || slices > 4096 || !(desc->sigma >= 0 && desc->sigma <= 1))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "size %d (1..16384), slices %d (1..4096), sigma %g (0..1)", size, slices, (double)desc->sigma);
    if ((r = voxgi__view_light(ctx, scene, desc->light, "transmittance shadow maps", &L)) != VOXGI_OK) return r;
    if ((r = voxgi__flatten(ctx, scene, 0, 1, &f)) != VOXGI_OK) return r;
    texels = (size_t)size * (size_t)size;
    T = (voxgi_tsm *)voxgi__alloc_array(ctx, 1, sizeof *T, 1);
    soup = (double *)voxgi__alloc_array(ctx, 2 * f.triangle_count, 9 * sizeof(double), 0); /* a triangle cut by the near plane: two */
    group = (signed char *)voxgi__alloc_array(ctx, 2 * f.triangle_count, 1, 0);
    if (!T || !soup || !group) { r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for a transmittance shadow map"); goto done; }
    T->view.size = size;
    T->view.slices = slices;
    T->words = (slices + 31) / 32;
    if ((r = voxgi__view_setup(ctx, &f, L, desc->light, &T->view)) != VOXGI_OK) goto done;
    for (t = 0; t < f.triangle_count; t++) { /* each triangle's map (-1 the shadow map, g a slicemap, none), in the frame */
        const voxgi_material *m = voxgi__tri_material(&f, t);
        float sigma = desc->sigma > 0 ? desc->sigma : 1 - m->transparency;
        double x[3][3];
        int k, pieces;
        if (m->transparency > 0 && !(m->transparency < 1)) continue; /* lets all light through */
        g = -1;
        if (m->transparency > 0) {
            for (g = 0; g < T->materials && T->sigma[g] != sigma; g++) continue;
            if (g == T->materials) {
                if (g == VOXGI__TSM_MAX_MATERIALS) {
                    r = voxgi__fail(ctx, VOXGI_ERR_UNSUPPORTED, "more than %d translucent absorptions (set desc.sigma for one)", VOXGI__TSM_MAX_MATERIALS);
                    goto done;
                }
                T->sigma[T->materials++] = sigma;
            }
        }
        for (k = 0; k < 3; k++)
            for (a = 0; a < 3; a++) x[k][a] = f.pos[3 * (size_t)f.tri[3 * t + (size_t)k] + (size_t)a];
        pieces = voxgi__view_triangle(&T->view, (const double(*)[3])x, soup + 9 * count);
        for (k = 0; k < pieces; k++) group[count++] = (signed char)g;
    }
    T->columns = (uint32_t *)voxgi__alloc_array(ctx, (size_t)(T->materials ? T->materials : 1) * texels, (size_t)T->words * 4, 1);
    T->opaque = (float *)voxgi__alloc_array(ctx, texels, sizeof(float), 0);
    if (!T->columns || !T->opaque) { r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %dx%d maps", size, size); goto done; }
    for (g = 0; r == VOXGI_OK && g < T->materials; g++) r = voxgi__tsm_slicemap(ctx, T, soup, group, count, g);
    for (i = 0; i < texels; i++) T->opaque[i] = INFINITY;
    for (t = 0; r == VOXGI_OK && t < count; t++) { /* the shadow map: the rasterizer's coverage, the plane's depth */
        voxgi__tsm_depth_job job;
        double x[3], y[3];
        int k;
        if (group[t] != -1) continue;
        job.map = T->opaque;
        job.size = size;
        for (k = 0; k < 3; k++) {
            job.q[k] = soup + 9 * t + 3 * (size_t)k;
            x[k] = voxgi__snap256(job.q[k][0]);
            y[k] = voxgi__snap256(job.q[k][1]);
        }
        voxgi__vox_raster_cpu(x, y, size, size, voxgi__tsm_depth_pixel, &job, (uint32_t)t);
    }
    T->info.materials = T->materials;
    T->info.bytes = (size_t)T->materials * texels * (size_t)T->words * 4 + texels * sizeof(float);
#ifndef VOXGI_NO_GL
    if (r == VOXGI_OK && ctx->backend == VOXGI_BACKEND_GL) { /* the maps and the frame for the GL lookups */
        double P[34];
        memset(P, 0, sizeof P);
        for (a = 0; a < 3; a++) {
            P[a] = T->view.u[a]; P[3 + a] = T->view.v[a]; P[6 + a] = T->view.w[a]; P[9 + a] = T->view.lo[a]; P[14 + a] = T->view.eye[a];
        }
        P[12] = T->view.texel; P[13] = T->view.slice; P[17] = T->view.tan_half; P[18] = T->view.near_z; P[19] = T->view.far_z;
        P[20] = T->view.size; P[21] = T->view.slices; P[22] = T->view.perspective; P[23] = T->words; P[24] = T->materials;
        for (g = 0; g < T->materials; g++) P[26 + g] = T->sigma[g];
        T->gl_columns = voxgi__gl_buffer(ctx, (size_t)(T->materials ? T->materials : 1) * texels * (size_t)T->words * 4, T->columns);
        T->gl_opaque = voxgi__gl_buffer(ctx, texels * sizeof(float), T->opaque);
        T->gl_params = voxgi__gl_buffer(ctx, sizeof P, P);
        r = voxgi__gl_check(ctx, "the transmittance shadow map's buffers");
    }
#endif
    T->info.ms = voxgi__now_ms() - t0;
done:
    voxgi__free(ctx, soup);
    voxgi__free(ctx, group);
    voxgi__flat_free(ctx, &f);
    if (r == VOXGI_OK) *out = T;
    else voxgi__tsm_free(ctx, T);
    return r;
}

VOXGI_API void voxgi_tsm_query(const voxgi_tsm *tsm, voxgi_tsm_info *info)
{
    if (info) {
        if (tsm) *info = tsm->info;
        else memset(info, 0, sizeof *info);
    }
}

/* The light reaching point x (world), moved along unit normal n toward the light first when n is given. */
static float voxgi__tsm_point(const voxgi_tsm *T, const double x_in[3], const double *n)
{
    double x[3], p[3], bias = 0, light = 1;
    size_t texel, texels = (size_t)T->view.size * (size_t)T->view.size;
    int a, g, k, i, j;
    for (a = 0; a < 3; a++) x[a] = x_in[a];
    if (T->view.perspective) { /* before the near plane nothing was drawn, so nothing is in the way */
        double z = (x[0] - T->view.eye[0]) * T->view.w[0] + (x[1] - T->view.eye[1]) * T->view.w[1] + (x[2] - T->view.eye[2]) * T->view.w[2];
        if (!(z > T->view.near_z)) return 1;
        if (n) { /* a texel at this depth, in world units and in slices */
            double texel = 2 * z * T->view.tan_half / T->view.size, along = 0;
            for (a = 0; a < 3; a++) along += n[a] * (x[a] - T->view.eye[a]);
            for (a = 0; a < 3; a++) x[a] += (along > 0 ? -1 : 1) * 1.5 * texel * n[a];
            bias = 0.5 * texel * T->view.slices / (z * z * (1 / T->view.near_z - 1 / T->view.far_z));
        }
    } else if (n) { /* normal offset, on the side the light comes from; an opaque depth within half a texel passes */
        double side = n[0] * T->view.w[0] + n[1] * T->view.w[1] + n[2] * T->view.w[2] > 0 ? -1 : 1;
        for (a = 0; a < 3; a++) x[a] += side * 1.5 * T->view.texel * n[a];
        bias = 0.5 * T->view.texel / T->view.slice;
    }
    voxgi__view_point(&T->view, x, p);
    if (!(p[0] >= 0 && p[0] < T->view.size && p[1] >= 0 && p[1] < T->view.size)) return 1; /* beyond the scene across the light */
    i = (int)p[0];
    j = (int)p[1];
    texel = (size_t)j * (size_t)T->view.size + (size_t)i;
    if (T->opaque[texel] < p[2] - bias) return 0;
    k = p[2] <= 0 ? 0 : (p[2] >= T->view.slices ? T->view.slices : (int)p[2]); /* the slices before the point's own */
    for (g = 0; g < T->materials; g++) {
        const uint32_t *col = T->columns + ((size_t)g * texels + texel) * (size_t)T->words;
        int w, layers = 0;
        for (w = 0; w < k >> 5; w++) layers += (int)voxgi__popcount32(col[w]);
        if (k & 31) layers += (int)voxgi__popcount32(col[k >> 5] & ((1u << (k & 31)) - 1u));
        for (w = 0; w < layers; w++) light *= 1.0 - T->sigma[g]; /* a product, as on GL */
    }
    return (float)light;
}

/* voxgi__tsm_point at count points (normals may be NULL). */
static void voxgi__tsm_transmittance_cpu(const voxgi_tsm *tsm, size_t count, const float *points, const float *normals, float *out)
{
    size_t i;
    int a;
    for (i = 0; i < count; i++) {
        double x[3], n[3];
        for (a = 0; a < 3; a++) {
            x[a] = points[3 * i + (size_t)a];
            n[a] = normals ? normals[3 * i + (size_t)a] : 0;
        }
        out[i] = voxgi__tsm_point(tsm, x, normals ? n : NULL);
    }
}

#ifndef VOXGI_NO_GL
/* The same lookups on GL (shaders/tsm_lookup.glsl). */
static voxgi_result voxgi__tsm_transmittance_gl(voxgi_context *ctx, const voxgi_tsm *T, size_t count, const float *points, const float *normals,
                                                float *out)
{
    voxgi__gl *gl = ctx->gl;
    unsigned int pts, nrm = 0, light, p;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_tsm_lookup);
    double given = normals ? 1 : 0;
    if (r != VOXGI_OK) return r;
    if (count > (size_t)UINT32_MAX / 3) return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%lu points in one GL lookup", (unsigned long)count);
    p = gl->prog_tsm_lookup;
    pts = voxgi__gl_buffer(ctx, count * 12, points);
    if (normals) nrm = voxgi__gl_buffer(ctx, count * 12, normals);
    light = voxgi__gl_buffer(ctx, count * 4, NULL);
    gl->NamedBufferSubData(T->gl_params, 25 * sizeof(double), sizeof given, &given);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 0, pts);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 1, normals ? nrm : pts);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 2, T->gl_columns);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 3, T->gl_opaque);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 4, T->gl_params);
    gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 5, light);
    gl->UseProgram(p);
    gl->ProgramUniform1ui(p, VOXGI__LOC_u_count, (unsigned)count);
    voxgi__gl_dispatch_items(gl, (uint64_t)count);
    gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT | VOXGI__GL_BUFFER_UPDATE_BARRIER_BIT);
    voxgi__gl_unbind(gl);
    r = voxgi__gl_read_buffer(ctx, light, out, count * 4);
    voxgi__gl_delete_buffer(ctx, pts);
    if (nrm) voxgi__gl_delete_buffer(ctx, nrm);
    voxgi__gl_delete_buffer(ctx, light);
    if (r == VOXGI_OK) r = voxgi__gl_check(ctx, "transmittance shadow map lookups");
    return r;
}
#endif

VOXGI_API voxgi_result voxgi_tsm_transmittance(voxgi_context *ctx, const voxgi_tsm *tsm, size_t count, const float *points, const float *normals,
                                               float *out)
{
    size_t i;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!tsm || (count && (!points || !out))) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "tsm, points or out is NULL");
    for (i = 0; i < 3 * count; i++)
        if (!isfinite(points[i]) || (normals && !isfinite(normals[i])))
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "point %lu is not finite", (unsigned long)(i / 3));
#ifndef VOXGI_NO_GL
    if (ctx->backend == VOXGI_BACKEND_GL && tsm->gl_params && count) return voxgi__tsm_transmittance_gl(ctx, tsm, count, points, normals, out);
#endif
    voxgi__tsm_transmittance_cpu(tsm, count, points, normals, out);
    return VOXGI_OK;
}

VOXGI_API void voxgi_tsm_destroy(voxgi_context *ctx, voxgi_tsm *tsm)
{
    if (ctx) voxgi__tsm_free(ctx, tsm);
}
#endif /* VOXGI_NO_LIGHT_SPACE */

/* ----- 10.3 reflective shadow maps (voxgi_rsm) */
#ifndef VOXGI_NO_LIGHT_SPACE
struct voxgi_rsm {
    int maps, samples;
    voxgi__light_view *views;     /* one per map */
    float *position, *normal, *flux; /* 3 per texel, map after map */
    float *offset, *weight;       /* the sample pattern: 2 and 1 per sample */
    double radius;                /* texels */
    voxgi_rsm_info info;
};

static void voxgi__rsm_free(voxgi_context *ctx, voxgi_rsm *R)
{
    if (!R) return;
    voxgi__free(ctx, R->views);
    voxgi__free(ctx, R->position);
    voxgi__free(ctx, R->normal);
    voxgi__free(ctx, R->flux);
    voxgi__free(ctx, R->offset);
    voxgi__free(ctx, R->weight);
    voxgi__free(ctx, R);
}

typedef struct voxgi__rsm_job {
    voxgi_rsm *R;
    const voxgi__tracer *tr;
    const voxgi_light *L;         /* a directional or spot light's map */
    const double *power;          /* else per map: its point's radiance x area (rgb) */
    const uint32_t *own;          /* and its emissive triangle (UINT32_MAX: none) */
} voxgi__rsm_job;

/* Rows [first, end) of all maps' texels: the surface the light meets through each texel's centre. */
static void voxgi__rsm_rows(void *user, size_t first, size_t end)
{
    const voxgi__rsm_job *J = (const voxgi__rsm_job *)user;
    voxgi_rsm *R = J->R;
    size_t row, size = (size_t)R->info.size;
    for (row = first; row < end; row++) {
        size_t map = row / size, j = row % size;
        const voxgi__light_view *V = &R->views[map];
        int i, a;
        for (i = 0; i < V->size; i++) {
            size_t at = 3 * (row * size + (size_t)i);
            double o[3], d[3], I[3], share;
            uint32_t skip = UINT32_MAX;
            voxgi__hit h;
            if (V->hemisphere) { /* from the point through the texel's centre: each the same cosine-weighted solid angle */
                double sq[2], disk[2], z;
                sq[0] = 2 * (i + 0.5) / V->size - 1;
                sq[1] = 2 * ((double)j + 0.5) / V->size - 1;
                voxgi__square_to_disk(sq, disk);
                z = sqrt(VOXGI__MAX(0.0, 1 - disk[0] * disk[0] - disk[1] * disk[1]));
                for (a = 0; a < 3; a++) {
                    o[a] = V->eye[a];
                    d[a] = disk[0] * V->u[a] + disk[1] * V->v[a] + z * V->w[a];
                    I[a] = J->power[3 * map + (size_t)a];
                }
                share = VOXGI__PI / ((double)V->size * V->size);
                skip = J->own[map];
            } else if (V->perspective) { /* from the light through the texel's centre; its solid angle */
                double x = (2 * (i + 0.5) / V->size - 1) * V->tan_half, y = (2 * ((double)j + 0.5) / V->size - 1) * V->tan_half, to[3], len;
                for (a = 0; a < 3; a++) { o[a] = V->eye[a]; d[a] = V->w[a] + x * V->u[a] + y * V->v[a]; }
                len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                for (a = 0; a < 3; a++) { d[a] /= len; to[a] = -d[a]; }
                share = (2 * V->tan_half / V->size) * (2 * V->tan_half / V->size) / (len * len * len) * voxgi__spot_share(J->L, to);
                for (a = 0; a < 3; a++) I[a] = J->L->intensity[a];
            } else { /* along the light from before the scene; the texel's area */
                for (a = 0; a < 3; a++) {
                    o[a] = (V->lo[0] + (i + 0.5) * V->texel) * V->u[a] + (V->lo[1] + ((double)j + 0.5) * V->texel) * V->v[a] + (V->lo[2] - V->texel) * V->w[a];
                    d[a] = V->w[a];
                    I[a] = J->L->intensity[a];
                }
                share = V->texel * V->texel;
            }
            for (a = 0; a < 3; a++) R->position[at + (size_t)a] = R->normal[at + (size_t)a] = R->flux[at + (size_t)a] = 0;
            if (!voxgi__trace(J->tr, o, d, DBL_MAX, skip, 0, &h)) continue;
            {
                const voxgi_material *m = voxgi__prim_material(J->tr, h.prim);
                const double *n = J->tr->n + 3 * (size_t)h.prim;
                double side = n[0] * d[0] + n[1] * d[1] + n[2] * d[2] > 0 ? -1 : 1; /* the side facing the light */
                for (a = 0; a < 3; a++) {
                    R->position[at + (size_t)a] = (float)h.p[a];
                    R->normal[at + (size_t)a] = (float)(side * n[a]);
                    R->flux[at + (size_t)a] = (float)(m->albedo[a] * I[a] * share);
                }
            }
        }
    }
}

VOXGI_API voxgi_result voxgi_rsm_create(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_rsm_desc *desc, voxgi_rsm **out)
{
    voxgi__tracer tr;
    voxgi__lights Ls;
    voxgi__rsm_job J;
    voxgi_rsm *R = NULL;
    voxgi__rng g;
    const voxgi_light *L = NULL;
    double *power = NULL, sum = 0, t0 = voxgi__now_ms();
    uint32_t *own = NULL;
    size_t texels;
    int size, samples, points, maps = 1, k, a;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!scene || !desc || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "scene, desc or out is NULL");
    *out = NULL;
    size = desc->size ? desc->size : 256;
    points = desc->points ? desc->points : 4;
    samples = desc->samples ? desc->samples : desc->emitters || (desc->light < scene->light_count && scene->lights[desc->light].type == VOXGI_LIGHT_RECT) ? 200 : 100;
    if (size < 1 || size > 16384 || samples < 1 || samples > 65536 || points < 1 || points > 4096 || !(desc->radius >= 0 && desc->radius <= 2))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "size %d (1..16384), samples %d (1..65536), points %d (1..4096), radius %g (0..2)", size,
                           samples, points, (double)desc->radius);
    if (!desc->emitters) {
        if (desc->light >= scene->light_count)
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "light %lu of %lu", (unsigned long)desc->light, (unsigned long)scene->light_count);
        L = &scene->lights[desc->light];
        if (L->type == VOXGI_LIGHT_POINT) return voxgi__fail(ctx, VOXGI_ERR_UNSUPPORTED, "reflective shadow maps take a directional, spot or rectangular light");
        if (L->type == VOXGI_LIGHT_RECT) maps = points;
    }
    if ((r = voxgi__tracer_build(ctx, scene, &tr)) != VOXGI_OK) return r;
    if ((r = voxgi__lights_build(ctx, scene, &tr, &Ls)) != VOXGI_OK) { voxgi__tracer_free(ctx, &tr); return r; }
    if (desc->emitters) {
        if (!Ls.emitter_count) r = voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the scene has no emissive triangles");
        maps = points;
    }
    texels = (size_t)size * (size_t)size * (size_t)maps;
    if (r == VOXGI_OK && (R = (voxgi_rsm *)voxgi__alloc_array(ctx, 1, sizeof *R, 1)) != NULL) {
        R->maps = maps;
        R->views = (voxgi__light_view *)voxgi__alloc_array(ctx, (size_t)maps, sizeof *R->views, 1);
        R->position = (float *)voxgi__alloc_array(ctx, texels, 12, 0);
        R->normal = (float *)voxgi__alloc_array(ctx, texels, 12, 0);
        R->flux = (float *)voxgi__alloc_array(ctx, texels, 12, 0);
        R->offset = (float *)voxgi__alloc_array(ctx, (size_t)samples, 8, 0);
        R->weight = (float *)voxgi__alloc_array(ctx, (size_t)samples, 4, 0);
        power = (double *)voxgi__alloc_array(ctx, (size_t)maps, 3 * sizeof *power, 1);
        own = (uint32_t *)voxgi__alloc_array(ctx, (size_t)maps, sizeof *own, 1);
    }
    if (r == VOXGI_OK && (!R || !R->views || !R->position || !R->normal || !R->flux || !R->offset || !R->weight || !power || !own))
        r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %d maps of %dx%d texels", maps, size, size);
    for (k = 0; r == VOXGI_OK && k < maps; k++) {
        voxgi__light_view *V = &R->views[k];
        V->size = size;
        V->slices = 1;
        if (desc->emitters || L->type == VOXGI_LIGHT_RECT) { /* point k of the area: its hemisphere, from a hair off its surface */
            double q[3], n[3];
            voxgi__area_point(&Ls, L, k, points, q, n, power + 3 * k, &own[k]);
            V->hemisphere = 1;
            for (a = 0; a < 3; a++) V->w[a] = n[a];
            voxgi__leave(&tr, q, n, V->eye);
            voxgi__basis(V->w, V->u, V->v);
        } else
            r = voxgi__view_setup(ctx, &tr.flat, L, desc->light, V);
    }
    if (r == VOXGI_OK) {
        R->samples = samples;
        R->radius = (desc->radius > 0 ? desc->radius : maps > 1 || desc->emitters || L->type == VOXGI_LIGHT_RECT ? 1.0 : 0.3) * size;
        voxgi__rng_seed(&g, desc->seed, 0, 0);
        for (k = 0; k < samples; k++) { /* the pattern: r xi1 (sin 2 pi xi2, cos 2 pi xi2), weight xi1 */
            double x1 = voxgi__rng_unit(&g), x2 = voxgi__rng_unit(&g);
            R->offset[2 * k] = (float)(R->radius * x1 * sin(2 * VOXGI__PI * x2));
            R->offset[2 * k + 1] = (float)(R->radius * x1 * cos(2 * VOXGI__PI * x2));
            R->weight[k] = (float)x1;
            sum += x1;
        }
        for (k = 0; k < samples; k++) R->weight[k] = (float)(R->weight[k] / sum);
        R->info.maps = maps;
        R->info.size = size;
        R->info.samples = samples;
        R->info.bytes = texels * 36 + (size_t)samples * 12;
        J.R = R;
        J.tr = &tr;
        J.L = L;
        J.power = power;
        J.own = own;
        voxgi__parallel(ctx, (size_t)size * (size_t)maps, 4, voxgi__rsm_rows, &J);
        R->info.ms = voxgi__now_ms() - t0;
    }
    voxgi__free(ctx, power);
    voxgi__free(ctx, own);
    voxgi__lights_free(ctx, &Ls);
    voxgi__tracer_free(ctx, &tr);
    if (r == VOXGI_OK) *out = R;
    else voxgi__rsm_free(ctx, R);
    return r;
}

VOXGI_API void voxgi_rsm_query(const voxgi_rsm *rsm, voxgi_rsm_info *info)
{
    if (!info) return;
    if (rsm) *info = rsm->info;
    else memset(info, 0, sizeof *info);
}

VOXGI_API voxgi_result voxgi_rsm_texels(voxgi_context *ctx, const voxgi_rsm *rsm, float *positions, float *normals, float *flux)
{
    size_t bytes;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!rsm) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "rsm is NULL");
    bytes = (size_t)rsm->info.size * (size_t)rsm->info.size * (size_t)rsm->maps * 12;
    if (positions) memcpy(positions, rsm->position, bytes);
    if (normals) memcpy(normals, rsm->normal, bytes);
    if (flux) memcpy(flux, rsm->flux, bytes);
    return VOXGI_OK;
}

VOXGI_API voxgi_result voxgi_rsm_pattern(voxgi_context *ctx, const voxgi_rsm *rsm, float *offsets, float *weights)
{
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!rsm) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "rsm is NULL");
    if (offsets) memcpy(offsets, rsm->offset, (size_t)rsm->samples * 8);
    if (weights) memcpy(weights, rsm->weight, (size_t)rsm->samples * 4);
    return VOXGI_OK;
}

/* A gather at points, what the maps' and the SH volume's (10.4) share: per point its surface's
   position and normal in, the irradiance the method's point function finds there out, each
   sample's light through the voxels when O is given. A method's job holds it first. */
typedef struct voxgi__point_gather voxgi__point_gather;
struct voxgi__point_gather {
    const float *points, *normals; /* 3 per point */
    float *irradiance;            /* 3 per point */
    const voxgi__occupancy *O;    /* NULL: no visibility */
    int hierarchical;
    size_t chunk;                 /* points per CPU task */
    void (*point)(const voxgi__point_gather *G, const double x[3], const double n[3], double e[3]);
    voxgi_result (*gl)(voxgi_context *ctx, const voxgi__point_gather *G, size_t count); /* the method's GL twin */
};

static void voxgi__point_gather_cpu(void *user, size_t first, size_t end)
{
    const voxgi__point_gather *G = (const voxgi__point_gather *)user;
    size_t i;
    int a;
    for (i = first; i < end; i++) {
        double x[3], n[3], e[3] = {0, 0, 0};
        for (a = 0; a < 3; a++) { x[a] = G->points[3 * i + (size_t)a]; n[a] = G->normals[3 * i + (size_t)a]; }
        G->point(G, x, n, e);
        for (a = 0; a < 3; a++) G->irradiance[3 * i + (size_t)a] = (float)e[a];
    }
}

#ifndef VOXGI_NO_GL
/* GL: the points, normals and irradiance (buffers 0-2) and the occupancy (6, 7) beside the
   method's buffers 3-5 in buf, its uniforms set; point_gather.glsl run at every point, the
   irradiance read back, every buffer deleted. */
static voxgi_result voxgi__point_gather_gl(voxgi_context *ctx, const voxgi__point_gather *G, unsigned int p, size_t count, unsigned int buf[8], const char *what)
{
    voxgi__gl *gl = ctx->gl;
    voxgi_result r;
    size_t i;
    buf[0] = voxgi__gl_buffer(ctx, count * 12, G->points);
    buf[1] = voxgi__gl_buffer(ctx, count * 12, G->normals);
    buf[2] = voxgi__gl_buffer(ctx, count * 12, NULL);
    if (G->O) voxgi__occ_upload(ctx, G->O, &buf[6], &buf[7]);
    for (i = 0; i < 8; i++) gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, (unsigned)i, buf[i] ? buf[i] : buf[0]);
    gl->UseProgram(p);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_levels, G->O ? G->O->levels : 0);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_hierarchical, G->hierarchical);
    voxgi__gl_dispatch_points(gl, p, count);
    voxgi__gl_unbind(gl);
    r = voxgi__gl_read_buffer(ctx, buf[2], G->irradiance, count * 12);
    for (i = 0; i < 8; i++) voxgi__gl_delete_buffer(ctx, buf[i]);
    if (r == VOXGI_OK) r = voxgi__gl_check(ctx, what);
    return r;
}
#endif

/* The gather at count points on the context's backend. */
static voxgi_result voxgi__point_gather_run(voxgi_context *ctx, voxgi__point_gather *G, size_t count)
{
#ifndef VOXGI_NO_GL
    if (ctx->backend == VOXGI_BACKEND_GL) return G->gl(ctx, G, count);
#endif
    voxgi__parallel(ctx, count, G->chunk, voxgi__point_gather_cpu, G);
    return VOXGI_OK;
}

/* What voxgi_rsm_irradiance and voxgi_sh_irradiance check and set alike: the points, and with
   voxels the occupancy *O (the caller frees it) the gather sees them through. */
static voxgi_result voxgi__point_gather_begin(voxgi_context *ctx, voxgi__point_gather *G, const voxgi_voxels *voxels, voxgi_traversal how, size_t count,
                                              const float *points, const float *normals, float *irradiance, voxgi__occupancy *O)
{
    size_t i;
    voxgi_result r;
    if (count && (!points || !normals || !irradiance)) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "points, normals or irradiance is NULL");
    if (how != VOXGI_TRAVERSAL_DDA && how != VOXGI_TRAVERSAL_HIERARCHICAL) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "traversal %d", (int)how);
    for (i = 0; i < 3 * count; i++)
        if (!isfinite(points[i]) || !isfinite(normals[i])) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "point %lu is not finite", (unsigned long)(i / 3));
    G->points = points;
    G->normals = normals;
    G->irradiance = irradiance;
    if (!voxels) return VOXGI_OK;
    if ((r = voxgi__occ_build(ctx, voxels, how == VOXGI_TRAVERSAL_HIERARCHICAL, O)) != VOXGI_OK) return r;
    G->O = O;
    G->hierarchical = how == VOXGI_TRAVERSAL_HIERARCHICAL;
    return VOXGI_OK;
}

typedef struct voxgi__rsm_gather_job {
    voxgi__point_gather base;
    voxgi_rsm *const *maps;       /* their light adds up */
    size_t n;
    const voxgi_grid *grid;       /* the voxels' */
} voxgi__rsm_gather_job;

static void voxgi__rsm_point(const voxgi__point_gather *G, const double x[3], const double n[3], double e[3])
{
    const voxgi__rsm_gather_job *J = (const voxgi__rsm_gather_job *)(const void *)G;
    size_t ri;
    uint64_t steps = 0;
    int k, a, map;
    for (ri = 0; ri < J->n; ri++) {
        const voxgi_rsm *R = J->maps[ri];
        double disc = VOXGI__PI * R->radius * R->radius;
        size_t size = (size_t)R->info.size;
        for (map = 0; map < R->maps; map++) {
            const voxgi__light_view *V = &R->views[map];
            /* the singularity: x at least a texel's width from the texel, its width where the texel lies (the square of
               its distance from the light times this) */
            double st[3], spread = V->hemisphere ? VOXGI__PI / ((double)V->size * V->size) : V->perspective ? 4 * V->tan_half * V->tan_half / ((double)V->size * V->size) : 0;
            voxgi__view_point(V, x, st);
            for (k = 0; k < R->samples; k++) {
                double s = st[0] + R->offset[2 * k], t = st[1] + R->offset[2 * k + 1], d[3], dist2 = 0, cp = 0, cx = 0, f;
                size_t at;
                const float *xp, *np, *phi;
                if (!(s >= 0 && s < V->size && t >= 0 && t < V->size)) continue;
                at = 3 * (((size_t)map * size + (size_t)t) * size + (size_t)s);
                phi = R->flux + at;
                if (phi[0] == 0 && phi[1] == 0 && phi[2] == 0) continue;
                xp = R->position + at;
                np = R->normal + at;
                for (a = 0; a < 3; a++) {
                    d[a] = x[a] - xp[a];
                    dist2 += d[a] * d[a];
                    cp += np[a] * d[a];
                    cx -= n[a] * d[a];
                }
                if (cp <= 0 || cx <= 0) continue;
                if (spread > 0) {
                    double r2 = 0;
                    for (a = 0; a < 3; a++) r2 += (xp[a] - V->eye[a]) * (xp[a] - V->eye[a]);
                    dist2 = VOXGI__MAX(dist2, r2 * spread);
                } else
                    dist2 = VOXGI__MAX(dist2, V->texel * V->texel);
                if (G->O) { /* each end 1.5 voxels off its own surface */
                    double o[3], dd[3], vs = J->grid->voxel_size;
                    for (a = 0; a < 3; a++) {
                        double from = x[a] + 1.5 * vs * n[a], to = xp[a] + 1.5 * vs * np[a];
                        o[a] = (from - J->grid->origin[a]) / vs;
                        dd[a] = (to - J->grid->origin[a]) / vs - o[a];
                    }
                    if (voxgi__traverse(G->O, G->hierarchical, o, dd, &steps, NULL, NULL)) continue;
                }
                f = disc * R->weight[k] * cp * cx / (VOXGI__PI * dist2 * dist2);
                for (a = 0; a < 3; a++) e[a] += f * phi[a];
            }
        }
    }
}

#ifndef VOXGI_NO_GL
/* voxgi__rsm_point at count points on GL (shaders/rsm_gather.glsl, in float): the maps' texels,
   views and patterns uploaded as they are. */
static voxgi_result voxgi__rsm_gather_gl(voxgi_context *ctx, const voxgi__point_gather *G, size_t count)
{
    const voxgi__rsm_gather_job *J = (const voxgi__rsm_gather_job *)(const void *)G;
    voxgi__gl *gl = ctx->gl;
    size_t texels = 0, samples = 0, maps = 0, i, m, t;
    float *tx = NULL, *views = NULL, *pattern = NULL;
    unsigned int buf[8] = {0, 0, 0, 0, 0, 0, 0, 0}, p;
    int v, a;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_rsm_gather);
    if (r != VOXGI_OK) return r;
    for (i = 0; i < J->n; i++) {
        texels += (size_t)J->maps[i]->maps * (size_t)J->maps[i]->info.size * (size_t)J->maps[i]->info.size;
        samples += (size_t)J->maps[i]->samples;
        maps += (size_t)J->maps[i]->maps;
    }
    if (texels >= (size_t)1 << 24 || count > (size_t)UINT32_MAX / 3)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%lu texels (GL gathers index below 2^24) or %lu points", (unsigned long)texels, (unsigned long)count);
    tx = (float *)voxgi__alloc_array(ctx, texels ? texels : 1, 36, 0);
    views = (float *)voxgi__alloc_array(ctx, maps ? maps : 1, 24 * sizeof(float), 1);
    pattern = (float *)voxgi__alloc_array(ctx, samples ? samples : 1, 12, 0);
    if (!tx || !views || !pattern) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the GL gather");
    for (i = 0, m = 0, t = 0, samples = 0; r == VOXGI_OK && i < J->n; i++) {
        const voxgi_rsm *R = J->maps[i];
        size_t own = (size_t)R->maps * (size_t)R->info.size * (size_t)R->info.size, k;
        for (k = 0; k < own; k++)
            for (a = 0; a < 3; a++) {
                tx[9 * (t + k) + (size_t)a] = R->position[3 * k + (size_t)a];
                tx[9 * (t + k) + 3 + (size_t)a] = R->normal[3 * k + (size_t)a];
                tx[9 * (t + k) + 6 + (size_t)a] = R->flux[3 * k + (size_t)a];
            }
        for (k = 0; k < (size_t)R->samples; k++) {
            pattern[3 * (samples + k)] = R->offset[2 * k];
            pattern[3 * (samples + k) + 1] = R->offset[2 * k + 1];
            pattern[3 * (samples + k) + 2] = R->weight[k];
        }
        for (v = 0; v < R->maps; v++, m++) {
            const voxgi__light_view *V = &R->views[v];
            float *f = views + 24 * m;
            for (a = 0; a < 3; a++) {
                f[a] = (float)V->u[a];
                f[3 + a] = (float)V->v[a];
                f[6 + a] = (float)V->w[a];
                f[9 + a] = (float)V->lo[a];
                f[13 + a] = (float)V->eye[a];
            }
            f[12] = (float)V->texel;
            f[16] = (float)V->tan_half;
            f[17] = V->hemisphere ? 2.0f : (V->perspective ? 1.0f : 0.0f);
            f[18] = (float)V->size;
            f[19] = (float)R->radius;
            f[20] = (float)samples;
            f[21] = (float)R->samples;
            f[22] = (float)(t + (size_t)v * (size_t)V->size * (size_t)V->size);
            f[23] = (float)V->near_z;
        }
        t += own;
        samples += (size_t)R->samples;
    }
    if (r == VOXGI_OK) {
        p = gl->prog_rsm_gather;
        buf[3] = voxgi__gl_buffer(ctx, texels * 36, tx);
        buf[4] = voxgi__gl_buffer(ctx, maps * 24 * sizeof(float), views);
        buf[5] = voxgi__gl_buffer(ctx, samples * 12, pattern);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_maps, (int)maps);
        if (J->grid) {
            gl->ProgramUniform3f(p, VOXGI__LOC_u_origin, (float)J->grid->origin[0], (float)J->grid->origin[1], (float)J->grid->origin[2]);
            gl->ProgramUniform1f(p, VOXGI__LOC_u_voxel_size, (float)J->grid->voxel_size);
        }
        r = voxgi__point_gather_gl(ctx, G, p, count, buf, "the reflective shadow maps' gather");
    }
    voxgi__free(ctx, tx);
    voxgi__free(ctx, views);
    voxgi__free(ctx, pattern);
    return r;
}
#endif

/* A gather of the maps' light (J->maps, J->n; J->grid: the voxels', when the caller sets base.O). */
static void voxgi__rsm_gather_init(voxgi__rsm_gather_job *J)
{
    memset(J, 0, sizeof *J);
    J->base.chunk = 64;
    J->base.point = voxgi__rsm_point;
#ifndef VOXGI_NO_GL
    J->base.gl = voxgi__rsm_gather_gl;
#endif
}

VOXGI_API voxgi_result voxgi_rsm_irradiance(voxgi_context *ctx, const voxgi_rsm *rsm, const voxgi_voxels *voxels, voxgi_traversal how, size_t count,
                                            const float *points, const float *normals, float *irradiance)
{
    voxgi__rsm_gather_job J;
    voxgi__occupancy O;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!rsm) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "rsm is NULL");
    voxgi__rsm_gather_init(&J);
    if ((r = voxgi__point_gather_begin(ctx, &J.base, voxels, how, count, points, normals, irradiance, &O)) != VOXGI_OK) return r;
    J.maps = (voxgi_rsm *const *)&rsm;
    J.n = 1;
    J.grid = voxels ? &voxels->info.grid : NULL;
    r = voxgi__point_gather_run(ctx, &J.base, count);
    if (voxels) voxgi__occ_free(ctx, &O);
    return r;
}

VOXGI_API void voxgi_rsm_destroy(voxgi_context *ctx, voxgi_rsm *rsm)
{
    if (ctx) voxgi__rsm_free(ctx, rsm);
}

/* ----- 10.4 a spherical-harmonics volume of the direct light (voxgi_sh)

   Per cell: 12 coefficients (rgb x Y00, Y1-1, Y10, Y11) and the weighted centroid (w x, w y,
   w z, w), 16 floats; level l + 1 sums level l's cells two by two per axis. */
#define VOXGI__SH_Y0 0.28209479177387814 /* 1 / (2 sqrt(pi)) */
#define VOXGI__SH_Y1 0.48860251190291992 /* sqrt(3 / (4 pi)) */
struct voxgi_sh {
    voxgi_grid grid;
    int levels;
    int res[VOXGI__MAX_OCC_LEVELS][3];
    float *cells[VOXGI__MAX_OCC_LEVELS];
    voxgi_sh_info info;
};

static void voxgi__sh_free(voxgi_context *ctx, voxgi_sh *S)
{
    int l;
    if (!S) return;
    for (l = 0; l < S->levels; l++) voxgi__free(ctx, S->cells[l]);
    voxgi__free(ctx, S);
}

/* The part of triangle v (9 doubles) inside the box [lo, lo + size]^3: its area and centroid. */
static double voxgi__clip_to_box(const double *v, const double lo[3], double size, double centroid[3])
{
    double poly[2][9][3], area = 0, c[3] = {0, 0, 0};
    int n = 3, cur = 0, a, plane, i, k;
    for (i = 0; i < 3; i++) for (a = 0; a < 3; a++) poly[0][i][a] = v[3 * i + a];
    for (plane = 0; plane < 6 && n; plane++) { /* Sutherland-Hodgman against each face */
        int ax = plane >> 1, m = 0;
        double bound = lo[ax] + ((plane & 1) ? size : 0), sgn = (plane & 1) ? -1 : 1;
        for (i = 0; i < n; i++) {
            const double *p = poly[cur][i], *q = poly[cur][(i + 1) % n];
            double dp = sgn * (p[ax] - bound), dq = sgn * (q[ax] - bound);
            if (dp >= 0) memcpy(poly[!cur][m++], p, sizeof poly[0][0]);
            if ((dp >= 0) != (dq >= 0) && m < 9) {
                double t = dp / (dp - dq);
                for (a = 0; a < 3; a++) poly[!cur][m][a] = p[a] + t * (q[a] - p[a]);
                m++;
            }
        }
        n = m;
        cur = !cur;
    }
    for (k = 1; k + 1 < n; k++) { /* a fan from the first corner */
        const double *p0 = poly[cur][0], *p1 = poly[cur][k], *p2 = poly[cur][k + 1];
        double e1[3], e2[3], x[3], t;
        for (a = 0; a < 3; a++) { e1[a] = p1[a] - p0[a]; e2[a] = p2[a] - p0[a]; }
        for (a = 0; a < 3; a++) x[a] = e1[(a + 1) % 3] * e2[(a + 2) % 3] - e1[(a + 2) % 3] * e2[(a + 1) % 3];
        t = 0.5 * sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        area += t;
        for (a = 0; a < 3; a++) c[a] += t * (p0[a] + p1[a] + p2[a]) / 3;
    }
    for (a = 0; a < 3; a++) centroid[a] = area > 0 ? c[a] / area : 0;
    return area;
}

typedef struct voxgi__sh_piece { double c[3], area; uint32_t prim; uint64_t voxel; double e[6]; } voxgi__sh_piece;
typedef struct voxgi__sh_job { const voxgi__lights *Ls; voxgi__sh_piece *pieces; int samples; uint64_t seed; } voxgi__sh_job;

/* Pieces [first, end): the irradiance on both sides of each (front e[0..2], back e[3..5]) at its
   centroid, the area lights and emitters through `samples` stratified points. */
static void voxgi__sh_light_pieces(void *user, size_t first, size_t end)
{
    const voxgi__sh_job *J = (const voxgi__sh_job *)user;
    size_t i;
    uint64_t rays = 0;
    for (i = first; i < end; i++) {
        voxgi__sh_piece *P = &J->pieces[i];
        const double *n = J->Ls->tr->n + 3 * (size_t)P->prim;
        int side, s, a;
        for (side = 0; side < 2; side++) {
            double ns[3], p[3], e[3], rot[2], xi[2];
            voxgi__rng g;
            voxgi__rng_seed(&g, J->seed, i, (uint64_t)side);
            rot[0] = voxgi__rng_unit(&g);
            rot[1] = voxgi__rng_unit(&g);
            for (a = 0; a < 3; a++) { ns[a] = side ? -n[a] : n[a]; P->e[3 * side + a] = 0; }
            voxgi__leave(J->Ls->tr, P->c, ns, p);
            for (s = 0; s < J->samples; s++) {
                voxgi__kronecker(2, s, rot, xi);
                voxgi__direct(J->Ls, p, ns, P->prim, &g, 0, xi, &rays, e, NULL);
                for (a = 0; a < 3; a++) P->e[3 * side + a] += e[a] / J->samples;
            }
        }
    }
}

VOXGI_API voxgi_result voxgi_sh_create(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_grid *grid, const voxgi_sh_desc *desc, voxgi_sh **out)
{
    voxgi__tracer tr;
    voxgi__lights Ls;
    voxgi__sh_job J;
    voxgi_sh *S = NULL;
    voxgi__sh_piece *pieces = NULL;
    size_t np = 0, cap = 0, t, i;
    double t0 = voxgi__now_ms(), vs;
    int samples, a, l, area_lights = 0;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!scene || !grid || !desc || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "scene, grid, desc or out is NULL");
    *out = NULL;
    if ((r = voxgi_validate_grid(ctx, grid)) != VOXGI_OK) return r;
    if ((double)grid->res[0] * grid->res[1] * grid->res[2] * 64 * 8 / 7 > (ctx->desc.memory_budget ? (double)ctx->desc.memory_budget : 4e9))
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "a %dx%dx%d SH volume (64 bytes a cell over all levels)", grid->res[0], grid->res[1], grid->res[2]);
    if (desc->samples < 0 || desc->samples > 4096) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "samples %d (0..4096)", desc->samples);
    vs = grid->voxel_size;
    if ((r = voxgi__tracer_build(ctx, scene, &tr)) != VOXGI_OK) return r;
    if ((r = voxgi__lights_build(ctx, scene, &tr, &Ls)) != VOXGI_OK) { voxgi__tracer_free(ctx, &tr); return r; }
    for (i = 0; i < scene->light_count; i++) area_lights |= scene->lights[i].type == VOXGI_LIGHT_RECT;
    samples = area_lights || Ls.emitter_count ? (desc->samples ? desc->samples : 16) : 1; /* point-like lights need one */
    for (t = 0; r == VOXGI_OK && t < tr.flat.triangle_count; t++) { /* every triangle's pieces, voxel by voxel */
        const double *v = tr.v + 9 * t;
        const voxgi_material *m = voxgi__prim_material(&tr, (uint32_t)t);
        int64_t lo[3], hi[3], c[3];
        if (m->albedo[0] == 0 && m->albedo[1] == 0 && m->albedo[2] == 0) continue;
        for (a = 0; a < 3; a++) {
            double mn = VOXGI__MIN(v[a], VOXGI__MIN(v[3 + a], v[6 + a])), mx = VOXGI__MAX(v[a], VOXGI__MAX(v[3 + a], v[6 + a]));
            lo[a] = VOXGI__MAX((int64_t)0, (int64_t)floor((mn - grid->origin[a]) / vs));
            hi[a] = VOXGI__MIN((int64_t)grid->res[a] - 1, (int64_t)floor((mx - grid->origin[a]) / vs));
        }
        for (c[2] = lo[2]; r == VOXGI_OK && c[2] <= hi[2]; c[2]++)
            for (c[1] = lo[1]; r == VOXGI_OK && c[1] <= hi[1]; c[1]++)
                for (c[0] = lo[0]; c[0] <= hi[0]; c[0]++) {
                    double box[3], cen[3], area;
                    for (a = 0; a < 3; a++) box[a] = grid->origin[a] + (double)c[a] * vs;
                    if (!((area = voxgi__clip_to_box(v, box, vs, cen)) > 0)) continue;
                    if (np == cap) {
                        size_t nc = cap ? 2 * cap : 4096;
                        voxgi__sh_piece *grown = (voxgi__sh_piece *)voxgi__alloc_array(ctx, nc, sizeof *grown, 0);
                        if (!grown) { r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu surface pieces", (unsigned long)nc); break; }
                        if (np) memcpy(grown, pieces, np * sizeof *pieces);
                        voxgi__free(ctx, pieces);
                        pieces = grown;
                        cap = nc;
                    }
                    memcpy(pieces[np].c, cen, sizeof cen);
                    pieces[np].area = area;
                    pieces[np].prim = (uint32_t)t;
                    pieces[np].voxel = (uint64_t)c[0] + (uint64_t)grid->res[0] * ((uint64_t)c[1] + (uint64_t)grid->res[1] * (uint64_t)c[2]);
                    np++;
                }
    }
    if (r == VOXGI_OK && !(S = (voxgi_sh *)voxgi__alloc_array(ctx, 1, sizeof *S, 1))) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory");
    if (r == VOXGI_OK) { /* the levels, down to one cell */
        S->grid = *grid;
        for (a = 0; a < 3; a++) S->res[0][a] = grid->res[a];
        for (l = 0; l < VOXGI__MAX_OCC_LEVELS; l++) {
            S->cells[l] = (float *)voxgi__alloc_array(ctx, (size_t)S->res[l][0] * (size_t)S->res[l][1] * (size_t)S->res[l][2], 64, 1);
            if (!S->cells[l]) { r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the SH volume"); break; }
            S->levels = l + 1;
            if (S->res[l][0] == 1 && S->res[l][1] == 1 && S->res[l][2] == 1) break;
            for (a = 0; a < 3; a++) S->res[l + 1][a] = (S->res[l][a] + 1) / 2;
        }
    }
    if (r == VOXGI_OK) { /* each piece's light, then its reflected intensity projected into its voxel */
        J.Ls = &Ls;
        J.pieces = pieces;
        J.samples = samples;
        J.seed = desc->seed;
        voxgi__parallel(ctx, np, 16, voxgi__sh_light_pieces, &J);
        for (i = 0; i < np; i++) {
            const voxgi__sh_piece *P = &pieces[i];
            const voxgi_material *m = voxgi__prim_material(&tr, P->prim);
            const double *n = tr.n + 3 * (size_t)P->prim;
            float *cell = S->cells[0] + 16 * P->voxel;
            double w = 0;
            int side;
            for (side = 0; side < 2; side++) { /* a Lambertian side sends albedo E A / pi max(0, n.w): SH of the clamped cosine */
                double sg = side ? -1 : 1;
                for (a = 0; a < 3; a++) {
                    double k = m->albedo[a] * P->e[3 * side + a] * P->area / VOXGI__PI;
                    cell[4 * a + 0] += (float)(k * VOXGI__PI * VOXGI__SH_Y0);
                    cell[4 * a + 1] += (float)(k * 2 * VOXGI__PI / 3 * VOXGI__SH_Y1 * sg * n[1]);
                    cell[4 * a + 2] += (float)(k * 2 * VOXGI__PI / 3 * VOXGI__SH_Y1 * sg * n[2]);
                    cell[4 * a + 3] += (float)(k * 2 * VOXGI__PI / 3 * VOXGI__SH_Y1 * sg * n[0]);
                    w += k / 3;
                }
            }
            for (a = 0; a < 3; a++) cell[12 + a] += (float)(w * P->c[a]);
            cell[15] += (float)w;
        }
        for (l = 1; l < S->levels; l++) { /* each cell adds into its parent */
            const int *rc = S->res[l - 1], *rp = S->res[l];
            int64_t c[3];
            for (c[2] = 0; c[2] < rc[2]; c[2]++)
                for (c[1] = 0; c[1] < rc[1]; c[1]++)
                    for (c[0] = 0; c[0] < rc[0]; c[0]++) {
                        const float *src = S->cells[l - 1] + 16 * ((size_t)c[0] + (size_t)rc[0] * ((size_t)c[1] + (size_t)rc[1] * (size_t)c[2]));
                        float *dst = S->cells[l] + 16 * ((size_t)(c[0] >> 1) + (size_t)rp[0] * ((size_t)(c[1] >> 1) + (size_t)rp[1] * (size_t)(c[2] >> 1)));
                        int k;
                        if (src[15] == 0) continue;
                        for (k = 0; k < 16; k++) dst[k] += src[k];
                    }
        }
        for (i = 0; i < (size_t)S->res[0][0] * (size_t)S->res[0][1] * (size_t)S->res[0][2]; i++) S->info.voxels += S->cells[0][16 * i + 15] > 0;
        S->info.levels = S->levels;
        for (l = 0; l < S->levels; l++) S->info.bytes += (size_t)S->res[l][0] * (size_t)S->res[l][1] * (size_t)S->res[l][2] * 64;
        S->info.pieces = np;
        S->info.ms = voxgi__now_ms() - t0;
    }
    voxgi__free(ctx, pieces);
    voxgi__lights_free(ctx, &Ls);
    voxgi__tracer_free(ctx, &tr);
    if (r == VOXGI_OK) *out = S;
    else voxgi__sh_free(ctx, S);
    return r;
}

VOXGI_API void voxgi_sh_query(const voxgi_sh *sh, voxgi_sh_info *info)
{
    if (!info) return;
    if (sh) *info = sh->info;
    else memset(info, 0, sizeof *info);
}

VOXGI_API voxgi_result voxgi_sh_read(voxgi_context *ctx, const voxgi_sh *sh, int level, float *cells, size_t cells_bytes, int res[3])
{
    size_t bytes;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!sh || level < 0 || level >= sh->levels) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "sh is NULL or level %d is not in 0..%d", level, sh ? sh->levels - 1 : 0);
    bytes = (size_t)sh->res[level][0] * (size_t)sh->res[level][1] * (size_t)sh->res[level][2] * 64;
    if (res) memcpy(res, sh->res[level], sizeof sh->res[level]);
    if (!cells) return VOXGI_OK;
    if (cells_bytes < bytes) return voxgi__fail(ctx, VOXGI_ERR_BUFFER_TOO_SMALL, "cells holds %lu bytes, level %d needs %lu", (unsigned long)cells_bytes, level, (unsigned long)bytes);
    memcpy(cells, sh->cells[level], bytes);
    return VOXGI_OK;
}

typedef struct voxgi__sh_gather_job {
    voxgi__point_gather base;
    const voxgi_sh *S;
    double opening;
} voxgi__sh_gather_job;

/* The irradiance at x on unit normal n: every cell, from the coarsest, seen whole where its size
   over its centroid's distance is at most the opening (else its children are), as a point at its
   centroid sending its intensity's SH toward x (clamped at 0), the distance at least a voxel, the
   voxels within a voxel of x left out (its own surface). */
static void voxgi__sh_point(const voxgi__point_gather *G, const double x[3], const double n[3], double e[3])
{
    const voxgi__sh_gather_job *J = (const voxgi__sh_gather_job *)(const void *)G;
    const voxgi_sh *S = J->S;
    const voxgi_grid *g = &S->grid;
    double vs = g->voxel_size;
    int32_t stack[64 * 8][4];
    int top = 0, a;
    uint64_t steps = 0;
    stack[top][0] = S->levels - 1;
    stack[top][1] = stack[top][2] = stack[top][3] = 0;
    top++;
    while (top) {
        int32_t l, c[3];
        const float *cell;
        double p[3], d[3], dist2 = 0, dist, cr, w[3], size;
        top--;
        l = stack[top][0];
        for (a = 0; a < 3; a++) c[a] = stack[top][1 + a];
        cell = S->cells[l] + 16 * ((size_t)c[0] + (size_t)S->res[l][0] * ((size_t)c[1] + (size_t)S->res[l][1] * (size_t)c[2]));
        if (!(cell[15] > 0)) continue;
        for (a = 0; a < 3; a++) { p[a] = cell[12 + a] / cell[15]; d[a] = p[a] - x[a]; dist2 += d[a] * d[a]; }
        dist = sqrt(dist2);
        size = ldexp(vs, l);
        if (l > 0 && !(size <= J->opening * dist)) { /* too near to be one point: its children */
            int k;
            for (k = 0; k < 8; k++) {
                int32_t q[3];
                for (a = 0; a < 3; a++) q[a] = 2 * c[a] + ((k >> a) & 1);
                if (q[0] >= S->res[l - 1][0] || q[1] >= S->res[l - 1][1] || q[2] >= S->res[l - 1][2]) continue;
                stack[top][0] = l - 1;
                for (a = 0; a < 3; a++) stack[top][1 + a] = q[a];
                top++;
            }
            continue;
        }
        if (!(dist > vs)) continue; /* the point's own surface */
        for (a = 0; a < 3; a++) w[a] = -d[a] / dist; /* from the cell toward x */
        cr = (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) / dist;
        if (cr <= 0) continue;
        if (G->O) { /* from x 1.5 voxels off its surface toward the centroid, up to half a voxel before the cell (what lies
                       inside the cell is its own light's business) */
            double o[3], dd[3], enter = 0, len;
            for (a = 0; a < 3; a++) { /* voxel units */
                o[a] = (x[a] + 1.5 * vs * n[a] - g->origin[a]) / vs;
                dd[a] = (p[a] - g->origin[a]) / vs - o[a];
            }
            len = sqrt(dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2]);
            for (a = 0; a < 3; a++) {
                double lo = (double)c[a] * (double)((int64_t)1 << l), hi = lo + (double)((int64_t)1 << l), t0, t1;
                if (dd[a] == 0) continue;
                t0 = (lo - o[a]) / dd[a];
                t1 = (hi - o[a]) / dd[a];
                enter = VOXGI__MAX(enter, VOXGI__MIN(t0, t1));
            }
            enter -= 0.5 / len;
            if (enter > 0) {
                for (a = 0; a < 3; a++) dd[a] *= enter;
                if (voxgi__traverse(G->O, G->hierarchical, o, dd, &steps, NULL, NULL)) continue;
            }
        }
        for (a = 0; a < 3; a++) {
            const float *k = cell + 4 * a;
            double I = k[0] * VOXGI__SH_Y0 + VOXGI__SH_Y1 * (k[1] * w[1] + k[2] * w[2] + k[3] * w[0]);
            if (I > 0) e[a] += I * cr / dist2;
        }
    }
}

#ifndef VOXGI_NO_GL
/* voxgi__sh_point at count points on GL (shaders/sh_gather.glsl, in float): every level's cells
   uploaded one after another. */
static voxgi_result voxgi__sh_gather_gl(voxgi_context *ctx, const voxgi__point_gather *G, size_t count)
{
    const voxgi__sh_gather_job *J = (const voxgi__sh_gather_job *)(const void *)G;
    voxgi__gl *gl = ctx->gl;
    const voxgi_sh *S = J->S;
    uint32_t info[4 * VOXGI__MAX_OCC_LEVELS];
    size_t cells = 0, n[VOXGI__MAX_OCC_LEVELS];
    unsigned int buf[8] = {0, 0, 0, 0, 0, 0, 0, 0}, p;
    int l;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_sh_gather);
    if (r != VOXGI_OK) return r;
    if (count > (size_t)UINT32_MAX / 3) return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%lu points in one GL gather", (unsigned long)count);
    for (l = 0; l < S->levels; l++) {
        info[4 * l] = (uint32_t)S->res[l][0];
        info[4 * l + 1] = (uint32_t)S->res[l][1];
        info[4 * l + 2] = (uint32_t)S->res[l][2];
        info[4 * l + 3] = (uint32_t)cells;
        n[l] = (size_t)S->res[l][0] * (size_t)S->res[l][1] * (size_t)S->res[l][2];
        cells += n[l];
    }
    if (cells * 16 > (size_t)UINT32_MAX) return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%lu SH cells for one GL gather", (unsigned long)cells);
    p = gl->prog_sh_gather;
    buf[3] = voxgi__gl_buffer(ctx, cells * 64, NULL);
    for (l = 0; l < S->levels; l++) gl->NamedBufferSubData(buf[3], (ptrdiff_t)((size_t)info[4 * l + 3] * 64), (ptrdiff_t)(n[l] * 64), S->cells[l]);
    buf[4] = voxgi__gl_buffer(ctx, (size_t)S->levels * 16, info);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_cell_levels, S->levels);
    gl->ProgramUniform3f(p, VOXGI__LOC_u_origin, (float)S->grid.origin[0], (float)S->grid.origin[1], (float)S->grid.origin[2]);
    gl->ProgramUniform1f(p, VOXGI__LOC_u_voxel_size, (float)S->grid.voxel_size);
    gl->ProgramUniform1f(p, VOXGI__LOC_u_opening, (float)J->opening);
    return voxgi__point_gather_gl(ctx, G, p, count, buf, "the SH volume's gather");
}
#endif

/* A gather of the SH volume S's light, cells seen whole at `opening`. */
static void voxgi__sh_gather_init(voxgi__sh_gather_job *J, const voxgi_sh *S, double opening)
{
    memset(J, 0, sizeof *J);
    J->base.chunk = 16;
    J->base.point = voxgi__sh_point;
#ifndef VOXGI_NO_GL
    J->base.gl = voxgi__sh_gather_gl;
#endif
    J->S = S;
    J->opening = opening;
}

VOXGI_API voxgi_result voxgi_sh_irradiance(voxgi_context *ctx, const voxgi_sh *sh, const voxgi_voxels *voxels, voxgi_traversal how, float opening,
                                           size_t count, const float *points, const float *normals, float *irradiance)
{
    voxgi__sh_gather_job J;
    voxgi__occupancy O;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!sh) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "sh is NULL");
    if (!(opening >= 0 && opening <= 4)) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "opening %g (0..4)", (double)opening);
    if (voxels) {
        const voxgi_grid *a = &voxels->info.grid, *b = &sh->grid;
        if (a->voxel_size != b->voxel_size || a->origin[0] != b->origin[0] || a->origin[1] != b->origin[1] || a->origin[2] != b->origin[2] ||
            a->res[0] != b->res[0] || a->res[1] != b->res[1] || a->res[2] != b->res[2])
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the voxels' grid is not the SH volume's");
    }
    voxgi__sh_gather_init(&J, sh, opening > 0 ? opening : 0.5);
    if ((r = voxgi__point_gather_begin(ctx, &J.base, voxels, how, count, points, normals, irradiance, &O)) != VOXGI_OK) return r;
    r = voxgi__point_gather_run(ctx, &J.base, count);
    if (voxels) voxgi__occ_free(ctx, &O);
    return r;
}

VOXGI_API void voxgi_sh_destroy(voxgi_context *ctx, voxgi_sh *sh)
{
    if (ctx) voxgi__sh_free(ctx, sh);
}
#endif /* VOXGI_NO_LIGHT_SPACE */

/* ===================================================================== 11. screen-space passes */
#ifndef VOXGI_NO_SCREEN_SPACE

/* ----- 11.1 low-discrepancy points */
VOXGI_API double voxgi_radical_inverse(uint32_t base, uint64_t i)
{
    double inv = base >= 2 ? 1.0 / base : 0.5, f = inv, r = 0;
    uint64_t b = base >= 2 ? base : 2;
    while (i) {
        r += (double)(i % b) * f;
        i /= b;
        f *= inv;
    }
    return r;
}

VOXGI_API void voxgi_hammersley(uint32_t i, uint32_t n, const double rot[2], double out[2])
{
    out[0] = n ? (double)i / n : 0;
    out[1] = voxgi_radical_inverse(2, i);
    if (rot) {
        out[0] += rot[0];
        out[1] += rot[1];
        out[0] -= floor(out[0]);
        out[1] -= floor(out[1]);
    }
}

/* ----- 11.2 rays through the screen or the voxels: ambient occlusion and one bounce */

/* What the passes march through (the screen: a G-buffer, and for one bounce the light its
   surfaces send) and where they gather: count points with normals, into out (AO: 1 float a
   point; one bounce: 3). */
typedef struct voxgi__screen_job {
    const voxgi_camera *cam;
    double eye[3], forward[3], right[3], up[3], tan_half;
    const float *pos, *nrm;       /* the screen's G-buffer */
    const float *radiance;        /* NULL: ambient occlusion; else per pixel the radiance its surface sends */
    voxgi_ao_method method;
    const voxgi__occupancy *O;    /* VOXELS */
    const voxgi_grid *grid;
    int hierarchical, rays, steps, point_sampling;
    double radius;
    uint64_t seed;
    const float *points, *normals;
    const uint32_t *pixel_of;     /* NULL, or per point the pixel whose random numbers it draws (else its own index) */
    float *out;
    size_t first_point;           /* the random numbers of point i are those of point first_point + i (pixel_of NULL) */
    const voxgi_volume *hidden_radiance; /* VOXELS with radiance: NULL, or the light of the voxels hidden hits meet */
    float *hidden_hits;           /* with hidden_radiance, per point and ray: the centre (grid units) of the voxel a
                                     hidden or off-screen hit met and the ray's direction, NAN in the first where
                                     the ray met none such */
} voxgi__screen_job;

/* The pixel whose centre ray passes nearest to world point s in front of the eye (returns 1), or
   0; *z: the point's distance along the view direction. */
static int voxgi__screen_pixel(const voxgi__screen_job *J, const double s[3], size_t *pix, double *z)
{
    const voxgi_camera *cam = J->cam;
    double d[3], x, y, sx, sy;
    int a;
    for (a = 0; a < 3; a++) d[a] = s[a] - J->eye[a];
    *z = d[0] * J->forward[0] + d[1] * J->forward[1] + d[2] * J->forward[2];
    if (!(*z > 0)) return 0;
    x = (d[0] * J->right[0] + d[1] * J->right[1] + d[2] * J->right[2]) / *z;
    y = (d[0] * J->up[0] + d[1] * J->up[1] + d[2] * J->up[2]) / *z;
    sx = (x / (J->tan_half * cam->width / cam->height) + 1) * 0.5 * cam->width;
    sy = (1 - y / J->tan_half) * 0.5 * cam->height;
    if (!(sx >= 0 && sx < cam->width && sy >= 0 && sy < cam->height)) return 0;
    *pix = (size_t)sy * (size_t)cam->width + (size_t)sx;
    return 1;
}

/* Whether pixel pix of a G-buffer's normals shows a surface (no surface: the normal 0). */
static int voxgi__has_surface(const float *nrm, size_t pix)
{
    return nrm[3 * pix] != 0 || nrm[3 * pix + 1] != 0 || nrm[3 * pix + 2] != 0;
}

/* 1 when point s lies behind the surface of the pixel it projects to (that pixel's plane met by
   the eye's ray through s, nearer the eye by more than radius / 1000) and that surface lies within
   radius of p; that pixel in *hit. */
static int voxgi__screen_behind(const voxgi__screen_job *J, const double p[3], const double s[3], size_t *hit)
{
    double R = J->radius, v[3], z, nv = 0, nq = 0, f, dq = 0;
    const float *q, *m;
    size_t at;
    int c;
    if (!voxgi__screen_pixel(J, s, &at, &z) || !voxgi__has_surface(J->nrm, at)) return 0;
    q = J->pos + 3 * at;
    m = J->nrm + 3 * at;
    for (c = 0; c < 3; c++) {
        v[c] = s[c] - J->eye[c];
        nv += m[c] * v[c];
        nq += m[c] * ((double)q[c] - J->eye[c]);
    }
    if (!(fabs(nv) > 1e-9 * sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]))) return 0; /* the plane edge-on */
    f = nq / nv;
    for (c = 0; c < 3; c++) dq += (J->eye[c] + f * v[c] - p[c]) * (J->eye[c] + f * v[c] - p[c]);
    if (!(f > 0 && f < 1 - 1e-3 * R / z && dq < R * R)) return 0;
    *hit = at;
    return 1;
}

/* The ray p + t dir, t in [0, radius], marched through the depth buffer: 1 at the first step
   behind the screen's surface (voxgi__screen_behind), its pixel in *hit. */
static int voxgi__screen_march(const voxgi__screen_job *J, const double p[3], const double dir[3], double jitter, size_t *hit)
{
    int j, c;
    for (j = 0; j < J->steps; j++) {
        double s[3], tt = (j + jitter) / J->steps * J->radius;
        for (c = 0; c < 3; c++) s[c] = p[c] + tt * dir[c];
        if (voxgi__screen_behind(J, p, s, hit)) return 1;
    }
    return 0;
}

static void voxgi__screen_last_voxel(void *user, const int64_t v[3]) { memcpy(user, v, 3 * sizeof(int64_t)); }

/* The ray from 1.5 voxels off p along its normal n to p + radius dir through the voxels: 1 when
   it meets one; *hit: the pixel showing the point where it enters that voxel, when that point
   lies within 2 voxels of that pixel's surface's plane, else (hidden or off screen) SIZE_MAX;
   v: the voxel met. */
static int voxgi__screen_voxels(const voxgi__screen_job *J, const double p[3], const double n[3], const double dir[3], uint64_t *steps, size_t *hit,
                                int64_t v[3])
{
    const voxgi_grid *g = J->grid;
    double o[3], d[3], vs = g->voxel_size, enter = 0, x[3], z, dq = 0;
    int a;
    for (a = 0; a < 3; a++) {
        o[a] = (p[a] + 1.5 * vs * n[a] - g->origin[a]) / vs;
        d[a] = (p[a] + J->radius * dir[a] - g->origin[a]) / vs - o[a];
    }
    *hit = SIZE_MAX;
    if (!voxgi__traverse(J->O, J->hierarchical, o, d, steps, voxgi__screen_last_voxel, v)) return 0;
    if (!J->radiance) return 1;
    for (a = 0; a < 3; a++) /* where the segment enters the voxel it met */
        if (d[a] != 0) enter = VOXGI__MAX(enter, VOXGI__MIN(((double)v[a] - o[a]) / d[a], ((double)v[a] + 1 - o[a]) / d[a]));
    for (a = 0; a < 3; a++) x[a] = g->origin[a] + (o[a] + enter * d[a]) * vs;
    if (!voxgi__screen_pixel(J, x, hit, &z) || !voxgi__has_surface(J->nrm, *hit)) { *hit = SIZE_MAX; return 1; }
    for (a = 0; a < 3; a++) dq += (double)J->nrm[3 * *hit + (size_t)a] * ((double)J->pos[3 * *hit + (size_t)a] - x[a]);
    if (!(fabs(dq) <= 2 * vs)) *hit = SIZE_MAX; /* another surface than the pixel's: hidden from the camera */
    return 1;
}

static void voxgi__screen_cpu(void *user, size_t first, size_t end)
{
    const voxgi__screen_job *J = (const voxgi__screen_job *)user;
    uint64_t steps = 0;
    size_t i;
    for (i = first; i < end; i++) {
        double p[3], n[3], t[3], b[3], rot[2], jitter, e[3] = {0, 0, 0};
        int k, a, blocked = 0;
        voxgi__rng g;
        for (a = 0; a < 3; a++) { p[a] = J->points[3 * i + (size_t)a]; n[a] = J->normals[3 * i + (size_t)a]; }
        for (k = 0; J->hidden_hits && k < J->rays; k++) J->hidden_hits[6 * (i * (size_t)J->rays + (size_t)k)] = NAN;
        if (n[0] != 0 || n[1] != 0 || n[2] != 0) {
            voxgi__rng_seed(&g, J->seed, J->pixel_of ? J->pixel_of[i] : J->first_point + i, 0);
            rot[0] = voxgi__rng_unit(&g);
            rot[1] = voxgi__rng_unit(&g);
            jitter = voxgi__rng_unit(&g);
            voxgi__basis(n, t, b);
            for (k = 0; k < J->rays; k++) { /* cosine-weighted: the Hammersley point on the disk, lifted */
                double u[2], r, phi, dir[3];
                size_t hit = SIZE_MAX;
                int64_t v[3] = {0, 0, 0};
                int met;
                voxgi_hammersley((uint32_t)k, (uint32_t)J->rays, rot, u);
                r = sqrt(u[0]);
                phi = 2 * VOXGI__PI * u[1];
                for (a = 0; a < 3; a++) dir[a] = r * cos(phi) * t[a] + r * sin(phi) * b[a] + sqrt(VOXGI__MAX(0.0, 1 - u[0])) * n[a];
                if (J->point_sampling) { /* one point along the ray, its distance Phi_3(k) shifted by the jitter */
                    double s3[3], f = voxgi_radical_inverse(3, (uint64_t)k) + jitter;
                    f -= floor(f);
                    for (a = 0; a < 3; a++) s3[a] = p[a] + f * J->radius * dir[a];
                    met = voxgi__screen_behind(J, p, s3, &hit);
                } else
                    met = J->method == VOXGI_AO_VOXELS ? voxgi__screen_voxels(J, p, n, dir, &steps, &hit, v) : voxgi__screen_march(J, p, dir, jitter, &hit);
                blocked += met;
                if (met && J->radiance && hit != SIZE_MAX)
                    for (a = 0; a < 3; a++) e[a] += J->radiance[3 * hit + (size_t)a];
                if (J->hidden_hits && met && hit == SIZE_MAX)
                    for (a = 0; a < 3; a++) {
                        J->hidden_hits[6 * (i * (size_t)J->rays + (size_t)k) + (size_t)a] = (float)v[a] + 0.5f;
                        J->hidden_hits[6 * (i * (size_t)J->rays + (size_t)k) + 3 + (size_t)a] = (float)dir[a];
                    }
            }
        }
        if (J->radiance)
            for (a = 0; a < 3; a++) J->out[3 * i + (size_t)a] = (float)(VOXGI__PI * e[a] / J->rays);
        else
            J->out[i] = (float)((double)blocked / J->rays);
    }
}

#ifndef VOXGI_NO_GL
/* Job J's rays at count points on GL (shaders/screen_rays.glsl, in float): the screen's G-buffer
   and radiance, and each point's rotation and jitter drawn here as the CPU draws them. Every
   position goes up relative to the eye (subtracted in double): in float a scene far from the
   origin would lose the differences the rays are made of (at 1e3 a coordinate rounds by 3e-5,
   as much as the march's self-occlusion guard). */
static voxgi_result voxgi__screen_gl(voxgi_context *ctx, const voxgi__screen_job *J, size_t count)
{
    voxgi__gl *gl = ctx->gl;
    size_t pixels = (size_t)J->cam->width * (size_t)J->cam->height, i, per = J->radiance ? 3 : 1;
    float *screen = NULL, *random = NULL, *points = NULL;
    unsigned int buf[8] = {0, 0, 0, 0, 0, 0, 0, 0}, p;
    int a;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_screen_rays);
    if (r != VOXGI_OK) return r;
    if (count > (size_t)UINT32_MAX / 6 / (size_t)J->rays || pixels > (size_t)UINT32_MAX / 9)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%lu points or %lu pixels in one GL pass", (unsigned long)count, (unsigned long)pixels);
    screen = (float *)voxgi__alloc_array(ctx, pixels, 36, 1);
    random = (float *)voxgi__alloc_array(ctx, count ? count : 1, 12, 0);
    points = (float *)voxgi__alloc_array(ctx, count ? count : 1, 12, 0);
    if (!screen || !random || !points) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the GL screen");
    for (i = 0; r == VOXGI_OK && i < count; i++)
        for (a = 0; a < 3; a++) points[3 * i + (size_t)a] = (float)((double)J->points[3 * i + (size_t)a] - J->eye[a]);
    for (i = 0; r == VOXGI_OK && i < pixels; i++)
        for (a = 0; a < 3; a++) {
            screen[9 * i + (size_t)a] = (float)((double)J->pos[3 * i + (size_t)a] - J->eye[a]);
            screen[9 * i + 3 + (size_t)a] = J->nrm[3 * i + (size_t)a];
            if (J->radiance) screen[9 * i + 6 + (size_t)a] = J->radiance[3 * i + (size_t)a];
        }
    for (i = 0; r == VOXGI_OK && i < count; i++) { /* voxgi__screen_cpu' draws */
        voxgi__rng g;
        voxgi__rng_seed(&g, J->seed, J->pixel_of ? J->pixel_of[i] : J->first_point + i, 0);
        for (a = 0; a < 3; a++) random[3 * i + (size_t)a] = (float)voxgi__rng_unit(&g);
    }
    if (r == VOXGI_OK) {
        p = gl->prog_screen_rays;
        buf[0] = voxgi__gl_buffer(ctx, count * 12, points);
        buf[1] = voxgi__gl_buffer(ctx, count * 12, J->normals);
        buf[2] = voxgi__gl_buffer(ctx, count * 4 * per, NULL);
        buf[3] = voxgi__gl_buffer(ctx, pixels * 36, screen);
        buf[4] = voxgi__gl_buffer(ctx, count * 12, random);
        if (J->hidden_hits) buf[5] = voxgi__gl_buffer(ctx, count * (size_t)J->rays * 24, NULL);
        if (J->O) voxgi__occ_upload(ctx, J->O, &buf[6], &buf[7]);
        for (i = 0; i < 8; i++) gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, (unsigned)i, buf[i] ? buf[i] : buf[0]);
        gl->UseProgram(p);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_levels, J->O ? J->O->levels : 0);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_hierarchical, J->hierarchical);
        if (J->grid) {
            gl->ProgramUniform3f(p, VOXGI__LOC_u_origin, (float)(J->grid->origin[0] - J->eye[0]), (float)(J->grid->origin[1] - J->eye[1]),
                                 (float)(J->grid->origin[2] - J->eye[2]));
            gl->ProgramUniform1f(p, VOXGI__LOC_u_voxel_size, (float)J->grid->voxel_size);
        }
        gl->ProgramUniform3f(p, VOXGI__LOC_u_eye, 0.0f, 0.0f, 0.0f); /* the frame's origin */
        gl->ProgramUniform3f(p, VOXGI__LOC_u_forward, (float)J->forward[0], (float)J->forward[1], (float)J->forward[2]);
        gl->ProgramUniform3f(p, VOXGI__LOC_u_right, (float)J->right[0], (float)J->right[1], (float)J->right[2]);
        gl->ProgramUniform3f(p, VOXGI__LOC_u_up, (float)J->up[0], (float)J->up[1], (float)J->up[2]);
        gl->ProgramUniform1f(p, VOXGI__LOC_u_tan, (float)J->tan_half);
        gl->ProgramUniform2i(p, VOXGI__LOC_u_size, J->cam->width, J->cam->height);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_rays, J->rays);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_steps, J->steps);
        gl->ProgramUniform1f(p, VOXGI__LOC_u_radius, (float)J->radius);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_gather, J->radiance != NULL);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_through_voxels, J->method == VOXGI_AO_VOXELS);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_point_sampling, J->point_sampling);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_hidden, J->hidden_hits != NULL);
        voxgi__gl_dispatch_points(gl, p, count);
        voxgi__gl_unbind(gl);
        r = voxgi__gl_read_buffer(ctx, buf[2], J->out, count * 4 * per);
        if (r == VOXGI_OK && J->hidden_hits) r = voxgi__gl_read_buffer(ctx, buf[5], J->hidden_hits, count * (size_t)J->rays * 24);
        for (i = 0; i < 8; i++) voxgi__gl_delete_buffer(ctx, buf[i]);
        if (r == VOXGI_OK) r = voxgi__gl_check(ctx, "the screen's rays");
    }
    voxgi__free(ctx, screen);
    voxgi__free(ctx, random);
    voxgi__free(ctx, points);
    return r;
}
#endif

/* Job J's rays at count points on the context's backend, as they are. */
static voxgi_result voxgi__screen_rays_on(voxgi_context *ctx, voxgi__screen_job *J, size_t count)
{
#ifndef VOXGI_NO_GL
    if (ctx->backend == VOXGI_BACKEND_GL) return voxgi__screen_gl(ctx, J, count);
#endif
    voxgi__parallel(ctx, count, 16, voxgi__screen_cpu, J);
    return VOXGI_OK;
}

/* Job J's rays at count points (J's points, normals, out) on the context's backend; with
   J->hidden_radiance, in parts of about a million rays, the light of the voxels the hidden
   hits met (voxgi_volume_sample at their centres: RADIANCE, or RADIANCE_BACK where the ray meets
   the side its RADIANCE_SIDE normal turns away) added after each part. */
static voxgi_result voxgi__screen_rays(voxgi_context *ctx, voxgi__screen_job *J, size_t count)
{
    size_t part = VOXGI__MAX((size_t)1, ((size_t)1 << 20) / (size_t)J->rays), first, i, n, k;
    float *hits, *pos, *lods, *L;
    uint32_t *owner;
    voxgi_volume_info vi;
    voxgi_result r = VOXGI_OK;
    if (!J->hidden_radiance) return voxgi__screen_rays_on(ctx, J, count);
    voxgi_volume_query(J->hidden_radiance, &vi);
    part = VOXGI__MIN(part, VOXGI__MAX(count, 1));
    hits = (float *)voxgi__alloc_array(ctx, part * (size_t)J->rays, 24, 0);
    pos = (float *)voxgi__alloc_array(ctx, part * (size_t)J->rays, 12, 0);
    lods = (float *)voxgi__alloc_array(ctx, part * (size_t)J->rays, 4, 1);
    L = (float *)voxgi__alloc_array(ctx, part * (size_t)J->rays, 48, 0); /* front, back, side: 4 each */
    owner = (uint32_t *)voxgi__alloc_array(ctx, part * (size_t)J->rays, 4, 0);
    if (!hits || !pos || !lods || !L || !owner) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the hidden hits of %lu points", (unsigned long)part);
    for (first = 0; r == VOXGI_OK && first < count; first += part) {
        voxgi__screen_job C = *J;
        size_t m = VOXGI__MIN(part, count - first);
        int a, sides = vi.attributes & VOXGI_ATTRIBUTE_RADIANCE_BACK ? 2 : 1;
        C.points += 3 * first;
        C.normals += 3 * first;
        C.out += 3 * first;
        if (C.pixel_of) C.pixel_of += first;
        C.first_point = J->first_point + first;
        C.hidden_hits = hits;
        if ((r = voxgi__screen_rays_on(ctx, &C, m)) != VOXGI_OK) break;
        for (i = n = 0; i < m * (size_t)J->rays; i++)
            if (!isnan(hits[6 * i])) {
                memcpy(pos + 3 * n, hits + 6 * i, 12);
                memcpy(hits + 6 * n + 3, hits + 6 * i + 3, 12); /* the direction, packed alongside (n <= i) */
                owner[n++] = (uint32_t)(i / (size_t)J->rays);
            }
        for (k = 0; n && r == VOXGI_OK && k < (size_t)(sides == 2 ? 3 : 1); k++)
            r = voxgi_volume_sample(ctx, J->hidden_radiance, k == 0 ? VOXGI_ATTRIBUTE_RADIANCE : k == 1 ? VOXGI_ATTRIBUTE_RADIANCE_BACK : VOXGI_ATTRIBUTE_RADIANCE_SIDE,
                                    VOXGI_DIR_POS_X, n, pos, lods, L + 4 * k * n);
        for (i = 0; r == VOXGI_OK && i < n; i++) {
            const float *d = hits + 6 * i + 3, *side = L + 8 * n + 4 * i;
            const float *from = sides == 2 && d[0] * side[0] + d[1] * side[1] + d[2] * side[2] > 0 ? L + 4 * n + 4 * i : L + 4 * i;
            for (a = 0; a < 3; a++) C.out[3 * owner[i] + (size_t)a] += (float)(VOXGI__PI / J->rays * from[a]);
        }
    }
    voxgi__free(ctx, hits);
    voxgi__free(ctx, pos);
    voxgi__free(ctx, lods);
    voxgi__free(ctx, L);
    voxgi__free(ctx, owner);
    return r;
}

/* A screen job from desc-like settings (validated here): the view, the G-buffer and the method. */
static voxgi_result voxgi__screen_setup(voxgi_context *ctx, voxgi__screen_job *J, const voxgi_camera *cam, const float *pos, const float *nrm,
                                        voxgi_ao_method method, voxgi_traversal traversal, int rays, int steps, float radius)
{
    voxgi_result r;
    memset(J, 0, sizeof *J);
    if ((r = voxgi__camera_frame(ctx, cam, J->eye, J->forward, J->right, J->up, &J->tan_half)) != VOXGI_OK) return r;
    J->cam = cam;
    J->pos = pos;
    J->nrm = nrm;
    J->method = method;
    J->hierarchical = traversal == VOXGI_TRAVERSAL_HIERARCHICAL;
    J->rays = rays ? rays : 16;
    J->steps = steps ? steps : 16;
    J->radius = radius;
    if (J->rays < 1 || J->rays > 65536 || J->steps < 1 || J->steps > 4096 || !(radius > 0 && isfinite(radius)) ||
        (method != VOXGI_AO_SCREEN && method != VOXGI_AO_VOXELS) || (traversal != VOXGI_TRAVERSAL_DDA && traversal != VOXGI_TRAVERSAL_HIERARCHICAL))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "rays %d (1..65536), steps %d (1..4096), radius %g (> 0), method %d, traversal %d", J->rays,
                           J->steps, (double)radius, (int)method, (int)traversal);
    return VOXGI_OK;
}

/* Every pixel of the screen as a point, through job J (its voxels' occupancy built here). */
static voxgi_result voxgi__screen_run(voxgi_context *ctx, voxgi__screen_job *J, const voxgi_voxels *voxels, uint64_t seed, float *out)
{
    voxgi__occupancy O;
    size_t pixels = (size_t)J->cam->width * (size_t)J->cam->height, i;
    voxgi_result r;
    for (i = 0; i < 3 * pixels; i++)
        if (!isfinite(J->pos[i]) || !isfinite(J->nrm[i]) || (J->radiance && !isfinite(J->radiance[i])))
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "pixel %lu is not finite", (unsigned long)(i / 3));
    if (J->method == VOXGI_AO_VOXELS) {
        if (!voxels) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "VOXELS needs the voxels");
        if ((r = voxgi__occ_build(ctx, voxels, J->hierarchical, &O)) != VOXGI_OK) return r;
        J->O = &O;
        J->grid = &voxels->info.grid;
    }
    J->seed = seed;
    J->points = J->pos;
    J->normals = J->nrm;
    J->out = out;
    r = voxgi__screen_rays(ctx, J, pixels);
    if (J->O) voxgi__occ_free(ctx, &O);
    J->O = NULL;
    return r;
}

VOXGI_API voxgi_result voxgi_ao(voxgi_context *ctx, const voxgi_ao_desc *desc, float *ao, size_t ao_bytes)
{
    voxgi__screen_job J;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!desc || !ao || !desc->positions || !desc->normals) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "desc, ao, positions or normals is NULL");
    if ((r = voxgi__screen_setup(ctx, &J, &desc->camera, desc->positions, desc->normals, desc->method, desc->traversal, desc->rays, desc->steps,
                                 desc->radius)) != VOXGI_OK)
        return r;
    if (desc->point_sampling && desc->method != VOXGI_AO_SCREEN) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "point sampling is for SCREEN");
    J.point_sampling = desc->point_sampling != 0;
    if (ao_bytes < (size_t)desc->camera.width * (size_t)desc->camera.height * 4)
        return voxgi__fail(ctx, VOXGI_ERR_BUFFER_TOO_SMALL, "ao holds %lu bytes, the image needs %lu", (unsigned long)ao_bytes,
                           (unsigned long)((size_t)desc->camera.width * (size_t)desc->camera.height * 4));
    return voxgi__screen_run(ctx, &J, desc->voxels, desc->seed, ao);
}

VOXGI_API voxgi_result voxgi_ssgi(voxgi_context *ctx, const voxgi_ssgi_desc *desc, float *irradiance, size_t irradiance_bytes)
{
    voxgi__screen_job J;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!desc || !irradiance || !desc->positions || !desc->normals || !desc->radiance)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "desc, irradiance, positions, normals or radiance is NULL");
    if ((r = voxgi__screen_setup(ctx, &J, &desc->camera, desc->positions, desc->normals, desc->method, desc->traversal, desc->rays, desc->steps,
                                 desc->radius)) != VOXGI_OK)
        return r;
    if (irradiance_bytes < (size_t)desc->camera.width * (size_t)desc->camera.height * 12)
        return voxgi__fail(ctx, VOXGI_ERR_BUFFER_TOO_SMALL, "irradiance holds %lu bytes, the image needs %lu", (unsigned long)irradiance_bytes,
                           (unsigned long)((size_t)desc->camera.width * (size_t)desc->camera.height * 12));
    J.radiance = desc->radiance;
    if (desc->hidden_radiance) {
        const voxgi_grid *g = desc->voxels ? &desc->voxels->info.grid : NULL;
        voxgi_volume_info vi;
        voxgi_volume_query(desc->hidden_radiance, &vi);
        if (desc->method != VOXGI_AO_VOXELS || !g || !(vi.attributes & VOXGI_ATTRIBUTE_RADIANCE) || vi.grid.voxel_size != g->voxel_size ||
            memcmp(vi.grid.origin, g->origin, sizeof g->origin) != 0 || memcmp(vi.grid.res, g->res, sizeof g->res) != 0)
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "hidden_radiance needs VOXELS and a RADIANCE volume on the voxels' grid");
        J.hidden_radiance = desc->hidden_radiance;
    }
    return voxgi__screen_run(ctx, &J, desc->voxels, desc->seed, irradiance);
}

/* ----- 11.3 edge-aware blur and upsampling */
typedef struct voxgi__filter_job {
    const float *pos, *nrm, *in;
    float *mid, *out;             /* mid: the row pass, w x ih, channels + 1 (the weight's sum) each */
    unsigned char *unsupported;
    int w, h, iw, ih, scale, window, channels;
    double eye[3], pixel_width, inv_two_sigma2; /* pixel_width: a pixel's width at distance 1 */
} voxgi__filter_job;

/* The weight of the sample at full pixel s for the pixel c, d pixels apart. */
static double voxgi__filter_weight(const voxgi__filter_job *F, size_t c, size_t s, int d)
{
    double dn = 0, dp = 0, dist2 = 0, t, dn2;
    int a;
    for (a = 0; a < 3; a++) {
        double e = (double)F->pos[3 * c + (size_t)a] - F->eye[a];
        dn += (double)F->nrm[3 * c + (size_t)a] * F->nrm[3 * s + (size_t)a];
        dp += ((double)F->pos[3 * s + (size_t)a] - F->pos[3 * c + (size_t)a]) * F->nrm[3 * c + (size_t)a];
        dist2 += e * e;
    }
    if (!(dn > 0)) return 0;
    dn2 = dn * dn;
    t = 2 * F->pixel_width * sqrt(dist2);
    return dn2 * dn2 * dn2 * dn2 * exp(-(double)(d * d) * F->inv_two_sigma2 - (t > 0 ? dp * dp / (t * t) : 0));
}

/* Rows [first, end) of the row pass (mid, row Y at the full row Y x scale). */
static void voxgi__filter_rows(void *user, size_t first, size_t end)
{
    voxgi__filter_job *F = (voxgi__filter_job *)user;
    size_t Y;
    for (Y = first; Y < end; Y++) {
        int x, X, k, fy = (int)Y * F->scale;
        for (x = 0; x < F->w; x++) {
            size_t c = (size_t)fy * (size_t)F->w + (size_t)x;
            float *m = F->mid + ((size_t)Y * (size_t)F->w + (size_t)x) * (size_t)(F->channels + 1);
            double sum = 0, v[4] = {0, 0, 0, 0};
            if (voxgi__has_surface(F->nrm, c))
                for (X = VOXGI__MAX(0, (x - F->window + F->scale - 1) / F->scale); X < F->iw && X * F->scale <= x + F->window; X++) {
                    size_t s = (size_t)fy * (size_t)F->w + (size_t)(X * F->scale);
                    double wt;
                    if (!voxgi__has_surface(F->nrm, s) || (wt = voxgi__filter_weight(F, c, s, X * F->scale - x)) <= 0) continue;
                    sum += wt;
                    for (k = 0; k < F->channels; k++) v[k] += wt * F->in[((size_t)Y * (size_t)F->iw + (size_t)X) * (size_t)F->channels + (size_t)k];
                }
            for (k = 0; k < F->channels; k++) m[k] = sum >= 1e-3 ? (float)(v[k] / sum) : 0;
            m[F->channels] = sum >= 1e-3 ? (float)sum : 0;
        }
    }
}

/* Rows [first, end) of the column pass (out). */
static void voxgi__filter_columns(void *user, size_t first, size_t end)
{
    voxgi__filter_job *F = (voxgi__filter_job *)user;
    size_t y;
    for (y = first; y < end; y++) {
        int x, Y, k;
        for (x = 0; x < F->w; x++) {
            size_t c = y * (size_t)F->w + (size_t)x;
            double sum = 0, v[4] = {0, 0, 0, 0};
            if (voxgi__has_surface(F->nrm, c))
                for (Y = VOXGI__MAX(0, ((int)y - F->window + F->scale - 1) / F->scale); Y < F->ih && Y * F->scale <= (int)y + F->window; Y++) {
                    size_t s = (size_t)(Y * F->scale) * (size_t)F->w + (size_t)x;
                    const float *m = F->mid + ((size_t)Y * (size_t)F->w + (size_t)x) * (size_t)(F->channels + 1);
                    double wt;
                    if (m[F->channels] <= 0 || (wt = voxgi__filter_weight(F, c, s, Y * F->scale - (int)y)) <= 0) continue;
                    sum += wt;
                    for (k = 0; k < F->channels; k++) v[k] += wt * m[k];
                }
            for (k = 0; k < F->channels; k++) F->out[c * (size_t)F->channels + (size_t)k] = sum >= 1e-3 ? (float)(v[k] / sum) : 0;
            if (F->unsupported) F->unsupported[c] = voxgi__has_surface(F->nrm, c) && sum < 1e-3;
        }
    }
}

/* The filter on the CPU: the row pass into F->mid, then the column pass. */
static void voxgi__filter_cpu(voxgi_context *ctx, voxgi__filter_job *F)
{
    voxgi__parallel(ctx, (size_t)F->ih, 1, voxgi__filter_rows, F);
    voxgi__parallel(ctx, (size_t)F->h, 1, voxgi__filter_columns, F);
}

#ifndef VOXGI_NO_GL
/* Both passes on GL (shaders/screen_filter.glsl, in float). */
static voxgi_result voxgi__filter_gl(voxgi_context *ctx, voxgi__filter_job *F)
{
    voxgi__gl *gl = ctx->gl;
    size_t pixels = (size_t)F->w * (size_t)F->h, mids = (size_t)F->w * (size_t)F->ih, i;
    unsigned int buf[5] = {0, 0, 0, 0, 0}, p;
    uint32_t *flags = NULL;
    float *screen = (float *)voxgi__alloc_array(ctx, pixels, 24, 0);
    int pass, a;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_screen_filter);
    if (r == VOXGI_OK && !screen) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the filter's G-buffer");
    if (r == VOXGI_OK && F->unsupported && !(flags = (uint32_t *)voxgi__alloc_array(ctx, pixels, 4, 0)))
        r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the filter's flags");
    if (r == VOXGI_OK) {
        for (i = 0; i < pixels; i++)
            for (a = 0; a < 3; a++) {
                screen[6 * i + (size_t)a] = F->pos[3 * i + (size_t)a];
                screen[6 * i + 3 + (size_t)a] = F->nrm[3 * i + (size_t)a];
            }
        p = gl->prog_screen_filter;
        buf[0] = voxgi__gl_buffer(ctx, pixels * 24, screen);
        buf[1] = voxgi__gl_buffer(ctx, (size_t)F->iw * (size_t)F->ih * (size_t)F->channels * 4, F->in);
        buf[2] = voxgi__gl_buffer(ctx, mids * (size_t)(F->channels + 1) * 4, NULL);
        buf[3] = voxgi__gl_buffer(ctx, pixels * (size_t)F->channels * 4, NULL);
        buf[4] = voxgi__gl_buffer(ctx, pixels * 4, NULL);
        for (i = 0; i < 5; i++) gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, (unsigned)i, buf[i]);
        gl->UseProgram(p);
        gl->ProgramUniform3f(p, VOXGI__LOC_u_eye, (float)F->eye[0], (float)F->eye[1], (float)F->eye[2]);
        gl->ProgramUniform2i(p, VOXGI__LOC_u_size, F->w, F->h);
        gl->ProgramUniform2i(p, VOXGI__LOC_u_src_dims, F->iw, F->ih);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_factor, F->scale);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_radius, F->window);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_channels, F->channels);
        gl->ProgramUniform1f(p, VOXGI__LOC_u_step, (float)F->pixel_width);
        gl->ProgramUniform1f(p, VOXGI__LOC_u_inv_s, (float)F->inv_two_sigma2);
        for (pass = 0; pass < 2; pass++) {
            gl->ProgramUniform1i(p, VOXGI__LOC_u_pass, pass);
            voxgi__gl_dispatch_points(gl, p, pass ? pixels : mids);
            gl->MemoryBarrier(VOXGI__GL_SHADER_STORAGE_BARRIER_BIT);
        }
        voxgi__gl_unbind(gl);
        r = voxgi__gl_read_buffer(ctx, buf[3], F->out, pixels * (size_t)F->channels * 4);
        if (r == VOXGI_OK && flags) r = voxgi__gl_read_buffer(ctx, buf[4], flags, pixels * 4);
        for (i = 0; flags && r == VOXGI_OK && i < pixels; i++) F->unsupported[i] = flags[i] != 0;
        for (i = 0; i < 5; i++) voxgi__gl_delete_buffer(ctx, buf[i]);
        if (r == VOXGI_OK) r = voxgi__gl_check(ctx, "the screen filter");
    }
    voxgi__free(ctx, screen);
    voxgi__free(ctx, flags);
    return r;
}
#endif

VOXGI_API voxgi_result voxgi_screen_filter(voxgi_context *ctx, const voxgi_screen_filter_desc *desc, const float *values, float *out, size_t out_bytes,
                                           unsigned char *unsupported)
{
    voxgi__filter_job F;
    double forward[3], right[3], up[3], tan_half;
    size_t pixels, i;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!desc || !values || !out || !desc->positions || !desc->normals) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "desc, values, out, positions or normals is NULL");
    memset(&F, 0, sizeof F);
    if ((r = voxgi__camera_frame(ctx, &desc->camera, F.eye, forward, right, up, &tan_half)) != VOXGI_OK) return r;
    if (desc->channels < 1 || desc->channels > 4 || desc->radius < 0 || desc->radius > 64 || (desc->half_resolution != 0 && desc->half_resolution != 1))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "channels %d (1..4), radius %d (0..64), half_resolution %d (0 or 1)", desc->channels, desc->radius,
                           desc->half_resolution);
    F.w = desc->camera.width;
    F.h = desc->camera.height;
    pixels = (size_t)F.w * (size_t)F.h;
    if (out_bytes < pixels * (size_t)desc->channels * 4)
        return voxgi__fail(ctx, VOXGI_ERR_BUFFER_TOO_SMALL, "out holds %lu bytes, the image needs %lu", (unsigned long)out_bytes,
                           (unsigned long)(pixels * (size_t)desc->channels * 4));
    for (i = 0; i < 3 * pixels; i++)
        if (!isfinite(desc->positions[i]) || !isfinite(desc->normals[i])) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "pixel %lu is not finite", (unsigned long)(i / 3));
    F.pos = desc->positions;
    F.nrm = desc->normals;
    F.in = values;
    F.out = out;
    F.unsupported = unsupported;
    F.channels = desc->channels;
    F.scale = desc->half_resolution ? 2 : 1;
    F.iw = (F.w + F.scale - 1) / F.scale;
    F.ih = (F.h + F.scale - 1) / F.scale;
    F.window = VOXGI__MAX(desc->radius, F.scale - 1);
    F.inv_two_sigma2 = 2.0 / VOXGI__MAX(F.window * F.window, 1);
    F.pixel_width = 2 * tan_half / F.h;
    if (!(F.mid = (float *)voxgi__alloc_array(ctx, (size_t)F.w * (size_t)F.ih, (size_t)(F.channels + 1) * 4, 0)))
        return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the filter's row pass");
#ifndef VOXGI_NO_GL
    if (ctx->backend == VOXGI_BACKEND_GL) r = voxgi__filter_gl(ctx, &F);
    else
#endif
        voxgi__filter_cpu(ctx, &F);
    voxgi__free(ctx, F.mid);
    return r;
}
#endif /* VOXGI_NO_SCREEN_SPACE */

/* ===================================================================== 12. line space */

#ifndef VOXGI_NO_LINE_SPACE
/* The tree's depth where the caller leaves it to the scene (0): 2 under 256 triangles, else 3. A
   few large triangles (a room, the Cornell box) fill most cells of every level, so a third level
   only adds steps (exact mode's image is the same, in about half the time); meshes of a thousand
   triangles and more want the finer leaves (docs/line-space.md). The line-space
   images' plan counts with it too. */
static int voxgi__plan_linespace_depth(uint64_t triangles)
{
    return triangles < 256 ? 2 : 3;
}

/* GL: the line space's arrays as storage buffers, bound at shaders/linespace.glsl's bindings: the
   nodes, the bits (in up to four parts, where GL's storage blocks are smaller than they: Mesa's
   128 MiB), the leaves, their triangle lists, the triangles. A walk takes these eight blocks and
   its input and output three: 11 of a compute shader's storage blocks. */
#define VOXGI__LS_GL_BUFFERS 8
#define VOXGI__LS_GL_BITS_PARTS 4
#define VOXGI__LS_GL_BLOCKS 11

struct voxgi_linespace {
    voxgi_linespace_info info;
    uint32_t *node;               /* 2 per node: its first child (UINT32_MAX: none; the N^3 children are consecutive, x fastest), then its
                                     line space (a node with children) or leaf (a filled node without) index, UINT32_MAX: empty */
    uint32_t *bits;               /* the line spaces, words_per_space each */
    uint32_t *leaf;               /* 2 per leaf: its first triangle reference, their count */
    uint32_t *tris;               /* the leaves' triangles, ascending in each */
    float *tv;                    /* 9 per triangle: its vertices relative to the centre */
    double centre[3];             /* the scene's bounds' centre (the root cube's; the ray core's too, so the triangle tests are its) */
    float half, scale;            /* the root cube's half edge, and n / its edge: the root's frame from the centre */
    float leaf_edge;              /* a leaf's edge in the root's frame (fast mode's exact zone at a segment's ends counts them) */
    size_t words_per_space;
    uint32_t pair_bit[6][6][3];   /* the ray entering by face fs and leaving by fe at patches ps, pe reads bit
                                     [fs][fe][0] + ps x [1] + pe x [2] of a line space (each unordered pair once) */
    unsigned int gl[VOXGI__LS_GL_BUFFERS]; /* made on a GL context: node, bits, leaf, tris, tv and the bits' further parts as storage
                                     buffers (VOXGI__LS_GL_BUFFERS) */
};

/* Triangles are listed in every leaf they come within this share of the root's edge of (2^-18):
   more than the float rounding of a ray's position in any node's frame, so a ray whose computed
   path slips past a leaf by rounding still finds the triangles it meets in the one beside it. */
#define VOXGI__LS_PAD 3.814697265625e-6

/* The index of the unordered pair of different faces (fs, fe), fs < fe, among the 15. */
static VOXGI__HOT_INLINE int voxgi__ls_face_pair(int fs, int fe)
{
    return fs * 5 - fs * (fs - 1) / 2 + (fe - fs - 1);
}

/* Patch (i, j) of face f (axis f / 2 at 0 or n by f % 2; i along the next axis, j the one after)
   of the node [0, n]^3 as a closed box. */
static void voxgi__ls_patch_box(int n, int f, int i, int j, double lo[3], double hi[3])
{
    int a = f >> 1;
    lo[a] = hi[a] = (f & 1) ? n : 0;
    lo[(a + 1) % 3] = i;
    hi[(a + 1) % 3] = i + 1;
    lo[(a + 2) % 3] = j;
    hi[(a + 2) % 3] = j + 1;
}

/* Whether the shaft between patches S and E (the convex hull of the two, the union over t in
   [0, 1] of the boxes (1 - t) S + t E) meets the closed box C: an interval of t left by the six
   linear bounds box(t) overlapping C puts on it. */
static int voxgi__ls_shaft_meets(const double slo[3], const double shi[3], const double elo[3], const double ehi[3], const double clo[3],
                                 const double chi[3])
{
    double t0 = 0, t1 = 1;
    int k;
    for (k = 0; k < 3; k++) {
        double d = elo[k] - slo[k], g = ehi[k] - shi[k];
        if (d > 0) t1 = VOXGI__MIN(t1, (chi[k] - slo[k]) / d); /* lo(t) <= chi */
        else if (d < 0) t0 = VOXGI__MAX(t0, (chi[k] - slo[k]) / d);
        else if (slo[k] > chi[k]) return 0;
        if (g > 0) t0 = VOXGI__MAX(t0, (clo[k] - shi[k]) / g); /* hi(t) >= clo */
        else if (g < 0) t1 = VOXGI__MIN(t1, (clo[k] - shi[k]) / g);
        else if (shi[k] < clo[k]) return 0;
    }
    return t0 <= t1 + 1e-12; /* touching counts: closed sets, and a rounded quotient never loses a point */
}

/* The bit of the shaft between patch ps of face fs and patch pe of face fe (fs != fe). */
static VOXGI__HOT_INLINE size_t voxgi__ls_bit(int n, int fs, int ps, int fe, int pe)
{
    size_t n2 = (size_t)n * (size_t)n;
    if (fs > fe) {
        int f = fs, p = ps;
        fs = fe; ps = pe; fe = f; pe = p;
    }
    return ((size_t)voxgi__ls_face_pair(fs, fe) * n2 + (size_t)ps) * n2 + (size_t)pe;
}

/* Whether the closed triangle v (9 doubles) meets the closed box [lo, hi] (separating axes: the
   box's 3, the triangle's normal, the 9 edge cross products; every comparison closed). */
static int voxgi__ls_tri_box(const double v[9], const double lo[3], const double hi[3])
{
    double c[3], h[3], p[9], e[9], nrm[3];
    int a, k, m;
    for (a = 0; a < 3; a++) {
        c[a] = 0.5 * (lo[a] + hi[a]);
        h[a] = 0.5 * (hi[a] - lo[a]);
        for (k = 0; k < 3; k++) p[3 * k + a] = v[3 * k + a] - c[a];
    }
    for (a = 0; a < 3; a++)
        if (VOXGI__MIN(p[a], VOXGI__MIN(p[3 + a], p[6 + a])) > h[a] || VOXGI__MAX(p[a], VOXGI__MAX(p[3 + a], p[6 + a])) < -h[a]) return 0;
    for (k = 0; k < 3; k++)
        for (a = 0; a < 3; a++) e[3 * k + a] = p[3 * ((k + 1) % 3) + a] - p[3 * k + a];
    nrm[0] = e[1] * e[5] - e[2] * e[4];
    nrm[1] = e[2] * e[3] - e[0] * e[5];
    nrm[2] = e[0] * e[4] - e[1] * e[3];
    for (m = -1; m < 9; m++) { /* m = -1: the normal; else edge m / 3 x box axis m % 3 */
        double ax[3], r, q0, q1, q2;
        if (m < 0) memcpy(ax, nrm, sizeof ax);
        else {
            const double *ed = e + 3 * (m / 3);
            int b = m % 3;
            ax[b] = 0;
            ax[(b + 1) % 3] = -ed[(b + 2) % 3];
            ax[(b + 2) % 3] = ed[(b + 1) % 3];
        }
        r = h[0] * fabs(ax[0]) + h[1] * fabs(ax[1]) + h[2] * fabs(ax[2]);
        q0 = p[0] * ax[0] + p[1] * ax[1] + p[2] * ax[2];
        q1 = p[3] * ax[0] + p[4] * ax[1] + p[5] * ax[2];
        q2 = p[6] * ax[0] + p[7] * ax[1] + p[8] * ax[2];
        if (VOXGI__MIN(q0, VOXGI__MIN(q1, q2)) > r || VOXGI__MAX(q0, VOXGI__MAX(q1, q2)) < -r) return 0;
    }
    return 1;
}

typedef struct voxgi__ls_build {
    voxgi_linespace *L;
    uint32_t *masks;              /* per child position (x fastest) the shafts it meets */
    const uint32_t *spaces;       /* per line space, its node */
} voxgi__ls_build;

/* Masks [first, end): every shaft of the node [0, n]^3 the child cell meets. */
static void voxgi__ls_masks(void *user, size_t first, size_t end)
{
    voxgi__ls_build *B = (voxgi__ls_build *)user;
    int n = B->L->info.n, fs, fe, ps, pe;
    double box[6 * 256][6]; /* every face's patches, lo then hi: n <= 16 */
    size_t c;
    for (fs = 0; fs < 6; fs++)
        for (ps = 0; ps < n * n; ps++) voxgi__ls_patch_box(n, fs, ps / n, ps % n, box[fs * n * n + ps], box[fs * n * n + ps] + 3);
    for (c = first; c < end; c++) {
        uint32_t *m = B->masks + c * B->L->words_per_space;
        double clo[3], chi[3];
        clo[0] = (double)(c % (size_t)n);
        clo[1] = (double)(c / (size_t)n % (size_t)n);
        clo[2] = (double)(c / ((size_t)n * (size_t)n));
        for (fs = 0; fs < 3; fs++) chi[fs] = clo[fs] + 1;
        for (fs = 0; fs < 6; fs++)
            for (fe = fs + 1; fe < 6; fe++)
                for (ps = 0; ps < n * n; ps++) {
                    const double *S = box[fs * n * n + ps];
                    size_t bit = voxgi__ls_bit(n, fs, ps, fe, 0);
                    for (pe = 0; pe < n * n; pe++, bit++) {
                        const double *E = box[fe * n * n + pe];
                        if (voxgi__ls_shaft_meets(S, S + 3, E, E + 3, clo, chi)) m[bit >> 5] |= 1u << (bit & 31);
                    }
                }
    }
}

/* Line spaces [first, end): the OR of the masks of each one's filled children. */
static void voxgi__ls_spaces(void *user, size_t first, size_t end)
{
    voxgi__ls_build *B = (voxgi__ls_build *)user;
    const voxgi_linespace *L = B->L;
    size_t s, c, w, children = (size_t)L->info.n * (size_t)L->info.n * (size_t)L->info.n;
    for (s = first; s < end; s++) {
        uint32_t *bits = L->bits + s * L->words_per_space, child0 = L->node[2 * (size_t)B->spaces[s]];
        for (c = 0; c < children; c++) {
            const uint32_t *ch = L->node + 2 * ((size_t)child0 + c);
            if (ch[0] == UINT32_MAX && ch[1] == UINT32_MAX) continue; /* empty */
            for (w = 0; w < L->words_per_space; w++) bits[w] |= B->masks[c * L->words_per_space + w];
        }
    }
}

VOXGI_API void voxgi_linespace_destroy(voxgi_context *ctx, voxgi_linespace *ls)
{
    if (!ctx || !ls) return;
#ifndef VOXGI_NO_GL
    {
        int k;
        for (k = 0; k < VOXGI__LS_GL_BUFFERS; k++) voxgi__gl_delete_buffer(ctx, ls->gl[k]);
    }
#endif
    voxgi__free(ctx, ls->node);
    voxgi__free(ctx, ls->bits);
    voxgi__free(ctx, ls->leaf);
    voxgi__free(ctx, ls->tris);
    voxgi__free(ctx, ls->tv);
    voxgi__free(ctx, ls);
}

VOXGI_API void voxgi_linespace_query(const voxgi_linespace *ls, voxgi_linespace_info *out)
{
    if (ls && out) *out = ls->info;
}

#ifndef VOXGI_NO_GL
static const unsigned int voxgi__ls_gl_binding[VOXGI__LS_GL_BUFFERS] = {0, 1, 2, 3, 4, 8, 9, 10};

/* The words of each part of the bits (all in one part where they fit a block). */
static uint64_t voxgi__ls_bits_part_words(const voxgi_context *ctx, const voxgi_linespace *L)
{
    uint64_t words = (uint64_t)L->words_per_space * L->info.line_spaces, most = (uint64_t)ctx->gl->max_ssbo_bytes / 4;
    return words <= most ? VOXGI__MAX(words, (uint64_t)1) : most;
}

/* The arrays in the order of ls->gl, their bytes; the first too large for GL (-1: none; 1: the
   bits, in more than four parts). */
static int voxgi__ls_arrays_gl(const voxgi_context *ctx, const voxgi_linespace *L, const void *data[VOXGI__LS_GL_BUFFERS], size_t bytes[VOXGI__LS_GL_BUFFERS])
{
    uint64_t words = (uint64_t)L->words_per_space * L->info.line_spaces, part = voxgi__ls_bits_part_words(ctx, L);
    int k;
    data[0] = L->node; bytes[0] = 8 * L->info.nodes;
    data[2] = L->leaf; bytes[2] = 8 * L->info.leaves;
    data[3] = L->tris; bytes[3] = 4 * L->info.triangle_refs;
    data[4] = L->tv; bytes[4] = 36 * L->info.triangles;
    for (k = 0; k < VOXGI__LS_GL_BITS_PARTS; k++) { /* part k: buffer 1, then 5, 6, 7 */
        uint64_t first = VOXGI__MIN(words, (uint64_t)k * part), n = VOXGI__MIN(words - first, part);
        data[k ? 4 + k : 1] = L->bits + first;
        bytes[k ? 4 + k : 1] = (size_t)(4 * n);
    }
    if (words > VOXGI__LS_GL_BITS_PARTS * part) return 1;
    for (k = 0; k < VOXGI__LS_GL_BUFFERS; k++)
        if ((int64_t)bytes[k] > ctx->gl->max_ssbo_bytes) return k;
    return -1;
}

/* The line space as storage buffers (in ls->gl's order), or none and why. */
static voxgi_result voxgi__ls_upload_gl(voxgi_context *ctx, const voxgi_linespace *L, unsigned int buf[VOXGI__LS_GL_BUFFERS])
{
    static const char *const names[5] = {"nodes", "bits", "leaves", "triangle lists", "triangles"};
    const void *data[VOXGI__LS_GL_BUFFERS];
    size_t bytes[VOXGI__LS_GL_BUFFERS];
    voxgi_result r;
    int k = voxgi__ls_arrays_gl(ctx, L, data, bytes);
    if (ctx->gl->max_compute_ssbo_blocks < VOXGI__LS_GL_BLOCKS)
        return voxgi__fail(ctx, VOXGI_ERR_UNSUPPORTED, "the line space's walk takes %d storage blocks; this GL gives compute shaders %d: use a CPU context",
                           VOXGI__LS_GL_BLOCKS, ctx->gl->max_compute_ssbo_blocks);
    if (k >= 0)
        return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "the line space's %s take %lu bytes, over %sGL_MAX_SHADER_STORAGE_BLOCK_SIZE %lld: use a CPU context",
                           names[k < 5 ? k : 1], k == 1 ? (unsigned long)(4 * L->words_per_space * L->info.line_spaces) : (unsigned long)bytes[k],
                           k == 1 ? "four times " : "", (long long)ctx->gl->max_ssbo_bytes);
    for (k = 0; k < VOXGI__LS_GL_BUFFERS; k++) buf[k] = voxgi__gl_buffer(ctx, bytes[k], bytes[k] ? data[k] : NULL);
    if ((r = voxgi__gl_check(ctx, "the line space's buffers")) != VOXGI_OK)
        for (k = 0; k < VOXGI__LS_GL_BUFFERS; k++) {
            voxgi__gl_delete_buffer(ctx, buf[k]);
            buf[k] = 0;
        }
    return r;
}

/* Binds the line space's buffers for a walk (shaders/linespace.glsl). */
static void voxgi__ls_bind_gl(voxgi__gl *gl, const unsigned int buf[VOXGI__LS_GL_BUFFERS])
{
    int k;
    for (k = 0; k < VOXGI__LS_GL_BUFFERS; k++) gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, voxgi__ls_gl_binding[k], buf[k]);
}
#endif

/* A growing array of `size`-byte items: room for item `index` (the capacity doubled, what it held kept). */
static int voxgi__ls_grow(voxgi_context *ctx, void **a, size_t index, size_t *cap, size_t size)
{
    size_t want;
    void *b;
    if (index < *cap) return 1;
    want = VOXGI__MAX(*cap * 2, (size_t)256);
    if (!(b = voxgi__alloc_array(ctx, want, size, 0))) return 0;
    if (*cap) memcpy(b, *a, *cap * size);
    voxgi__free(ctx, *a);
    *a = b;
    *cap = want;
    return 1;
}

/* Triangle t of the flattened scene, its three vertices in doubles. */
static void voxgi__ls_vertices(const voxgi__flat *f, uint32_t t, double v[9])
{
    int a;
    for (a = 0; a < 9; a++) v[a] = f->pos[3 * (size_t)f->tri[3 * (size_t)t + (size_t)(a / 3)] + (size_t)(a % 3)];
}

/* A node of the level being split: where it is, and its triangles (refs[first .. first + count)). */
typedef struct voxgi__ls_open {
    uint32_t node, first, count;
    double corner[3];
} voxgi__ls_open;

/* The children (x fastest) of the open node o, of edge `cell`, that the triangle v meets, each
   grown by pad on every side: their count, into out. The candidates: those its bounds reach, a
   cell either side. */
static size_t voxgi__ls_children_met(const voxgi__ls_open *o, int n, double cell, double pad, const double v[9], uint32_t *out)
{
    int rlo[3], rhi[3], x, y, z, a;
    size_t m = 0;
    for (a = 0; a < 3; a++) {
        double tl = VOXGI__MIN(v[a], VOXGI__MIN(v[3 + a], v[6 + a])), th = VOXGI__MAX(v[a], VOXGI__MAX(v[3 + a], v[6 + a]));
        rlo[a] = (int)VOXGI__MAX(0.0, floor((tl - o->corner[a]) / cell) - 1);
        rhi[a] = (int)VOXGI__MIN((double)(n - 1), floor((th - o->corner[a]) / cell) + 1);
    }
    for (z = rlo[2]; z <= rhi[2]; z++)
        for (y = rlo[1]; y <= rhi[1]; y++)
            for (x = rlo[0]; x <= rhi[0]; x++) {
                double blo[3], bhi[3];
                blo[0] = o->corner[0] + x * cell;
                blo[1] = o->corner[1] + y * cell;
                blo[2] = o->corner[2] + z * cell;
                for (a = 0; a < 3; a++) {
                    bhi[a] = blo[a] + cell + pad;
                    blo[a] -= pad;
                }
                if (voxgi__ls_tri_box(v, blo, bhi)) out[m++] = (uint32_t)(((size_t)z * (size_t)n + (size_t)y) * (size_t)n + (size_t)x);
            }
    return m;
}

VOXGI_API voxgi_result voxgi_linespace_create(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_linespace_desc *desc, voxgi_linespace **out)
{
    voxgi_linespace *L;
    voxgi__flat f;
    voxgi__ls_build B;
    voxgi__ls_open *open = NULL, *next = NULL;
    uint32_t *refs = NULL, *next_refs = NULL, *spaces = NULL, *cnt = NULL, *met = NULL;
    double t0 = voxgi__now_ms(), lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX}, ext = 0, cell;
    size_t nopen, nnext, nrefs, nnext_refs, cap_open = 0, cap_next = 0, cap_refs = 0, cap_next_refs = 0, cap_spaces = 0, nspaces = 0, cap_nodes = 0,
                                           nnodes = 0, cap_leaf = 0, nleaves = 0, ntris = 0, cap_tris = 0, i, budget, children, held;
    int n, depth, lev, a;
    voxgi_result r = VOXGI_OK;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!scene || !desc || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "scene, desc or out is NULL");
    *out = NULL;
    n = desc->n ? desc->n : 4;
    depth = desc->depth; /* 0: the scene's, once its triangles are counted (at most 16^3 leaves a side) */
    budget = desc->memory_budget ? desc->memory_budget : ctx->desc.memory_budget ? ctx->desc.memory_budget : SIZE_MAX;
    if (n < 2 || n > 16 || depth < 0 || depth > 8)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "n %d (2..16), depth %d (1..8, 0: from the scene)", n, depth);
    if (pow(n, depth) > 1048576.0) /* the rays' float frames resolve 2^-20 of the root */
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "n %d, depth %d: n^depth leaves per axis, at most 2^20", n, depth);
    children = (size_t)n * (size_t)n * (size_t)n;
    if ((r = voxgi__flatten(ctx, scene, 0, 0, &f)) != VOXGI_OK) return r;
    if (!depth) depth = voxgi__plan_linespace_depth(f.triangle_count);
    if (!(L = (voxgi_linespace *)voxgi__alloc_array(ctx, 1, sizeof *L, 1))) {
        voxgi__flat_free(ctx, &f);
        return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for a line space");
    }
    memset(&B, 0, sizeof B);
    L->info.n = n;
    L->info.depth = depth;
    L->words_per_space = (15 * children * (size_t)n + 31) / 32;
    for (i = 0; i < 3 * f.vertex_count; i++) {
        lo[i % 3] = VOXGI__MIN(lo[i % 3], (double)f.pos[i]);
        hi[i % 3] = VOXGI__MAX(hi[i % 3], (double)f.pos[i]);
    }
    for (a = 0; a < 3 && f.vertex_count; a++) ext = VOXGI__MAX(ext, hi[a] - lo[a]);
    L->info.size = ext > 0 ? ext * (1 + 1e-6) : 1; /* a hair larger: the scene inside, off the cube's faces */
    for (a = 0; a < 3; a++) {
        L->info.origin[a] = f.vertex_count ? 0.5 * (lo[a] + hi[a]) - 0.5 * L->info.size : 0;
        L->centre[a] = f.vertex_count ? 0.5 * (lo[a] + hi[a]) : 0;
    }
    L->half = (float)(0.5 * L->info.size);
    L->leaf_edge = (float)(1 / pow(n, depth - 1));
    L->scale = (float)(n / L->info.size);
    for (i = 0; i < 36; i++) {
        int fs = (int)i / 6, fe = (int)i % 6, n2 = n * n;
        L->pair_bit[fs][fe][0] = fs == fe ? 0 : (uint32_t)voxgi__ls_bit(n, fs, 0, fe, 0);
        L->pair_bit[fs][fe][1] = (uint32_t)(fs < fe ? n2 : 1);
        L->pair_bit[fs][fe][2] = (uint32_t)(fs < fe ? 1 : n2);
    }
    if (f.triangle_count >= UINT32_MAX) r = voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%lu triangles", (unsigned long)f.triangle_count);
    else if (36 * f.triangle_count > budget) r = voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%lu triangles need %lu bytes, over the budget of %lu", (unsigned long)f.triangle_count,
                                                           (unsigned long)(36 * f.triangle_count), (unsigned long)budget);
    else if (!(L->tv = (float *)voxgi__alloc_array(ctx, VOXGI__MAX(f.triangle_count, (size_t)1), 36, 0))) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the triangles");
    else if (children * L->words_per_space * 4 > budget)
        r = voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "the %lu child masks need %lu bytes, over the budget of %lu", (unsigned long)children,
                        (unsigned long)(children * L->words_per_space * 4), (unsigned long)budget);
    else
        for (i = 0; i < 9 * f.triangle_count; i++) /* relative to the centre, as the rays will be */
            L->tv[i] = (float)((double)f.pos[3 * (size_t)f.tri[i / 3] + i % 3] - L->centre[i % 3]);
    /* the root, holding every triangle with an area (one without can never be hit: leaving it out
       keeps fast mode from shadowing with it) */
    nrefs = f.triangle_count;
    cap_refs = VOXGI__MAX(nrefs, (size_t)1);
    if (r == VOXGI_OK && (!voxgi__ls_grow(ctx, (void **)&L->node, 0, &cap_nodes, 8) || !voxgi__ls_grow(ctx, (void **)&open, 0, &cap_open, sizeof *open) ||
                          !(refs = (uint32_t *)voxgi__alloc_array(ctx, cap_refs, 4, 0)) || !(cnt = (uint32_t *)voxgi__alloc_array(ctx, children + 1, 4, 0)) ||
                          !(met = (uint32_t *)voxgi__alloc_array(ctx, children, 4, 0))))
        r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the tree");
    if (r == VOXGI_OK) {
        L->node[0] = L->node[1] = UINT32_MAX;
        nnodes = 1;
        open[0].node = 0;
        open[0].first = 0;
        open[0].count = (uint32_t)nrefs;
        memcpy(open[0].corner, L->info.origin, sizeof open[0].corner);
        for (i = nrefs = 0; i < f.triangle_count; i++) {
            double g[3];
            voxgi__tri_unit_normal(&f, i, g);
            if (g[0] != 0 || g[1] != 0 || g[2] != 0) refs[nrefs++] = (uint32_t)i;
        }
        open[0].count = (uint32_t)nrefs;
    }
    nopen = nrefs ? 1 : 0;
    cell = L->info.size;
    for (lev = 1; r == VOXGI_OK && lev <= depth && nopen; lev++) { /* the children of every open node, in order */
        size_t k;
        cell /= n;
        nnext = nnext_refs = 0;
        for (k = 0; r == VOXGI_OK && k < nopen; k++) {
            const voxgi__ls_open *o = &open[k];
            size_t c, t, child0 = nnodes;
            double v[9];
            if (nnodes + children >= UINT32_MAX) { r = voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "more than 2^32 nodes"); break; }
            while (cap_nodes < nnodes + children)
                if (!voxgi__ls_grow(ctx, (void **)&L->node, cap_nodes, &cap_nodes, 8)) { r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the tree"); break; }
            if (r != VOXGI_OK) break;
            L->node[2 * o->node] = (uint32_t)child0;
            for (c = 0; c < 2 * children; c++) L->node[2 * child0 + c] = UINT32_MAX;
            nnodes += children;
            memset(cnt, 0, (children + 1) * 4);
            for (t = o->first; t < (size_t)o->first + o->count; t++) { /* each child's count */
                size_t m, j;
                voxgi__ls_vertices(&f, refs[t], v);
                m = voxgi__ls_children_met(o, n, cell, VOXGI__LS_PAD * L->info.size, v, met);
                for (j = 0; j < m; j++) cnt[met[j] + 1]++;
            }
            for (c = 0; c < children; c++) { /* a filled child opens on the next level, or is a leaf */
                uint32_t m = cnt[c + 1];
                cnt[c + 1] = cnt[c] + m; /* the lists' starts, in the level's array */
                if (!m) continue;
                if (lev < depth) {
                    if (!voxgi__ls_grow(ctx, (void **)&next, nnext, &cap_next, sizeof *next)) break;
                    next[nnext].node = (uint32_t)(child0 + c);
                    next[nnext].first = (uint32_t)(nnext_refs + cnt[c]);
                    next[nnext].count = m;
                    next[nnext].corner[0] = o->corner[0] + (double)(c % (size_t)n) * cell;
                    next[nnext].corner[1] = o->corner[1] + (double)(c / (size_t)n % (size_t)n) * cell;
                    next[nnext].corner[2] = o->corner[2] + (double)(c / ((size_t)n * (size_t)n)) * cell;
                    nnext++;
                } else {
                    if (!voxgi__ls_grow(ctx, (void **)&L->leaf, 2 * nleaves + 1, &cap_leaf, 4)) break;
                    L->node[2 * (child0 + c) + 1] = (uint32_t)nleaves;
                    L->leaf[2 * nleaves] = (uint32_t)(nnext_refs + cnt[c]);
                    L->leaf[2 * nleaves + 1] = m;
                    nleaves++;
                }
            }
            while (r == VOXGI_OK && c == children && cap_next_refs < nnext_refs + cnt[children])
                if (!voxgi__ls_grow(ctx, (void **)&next_refs, cap_next_refs, &cap_next_refs, 4)) break;
            if (c < children || cap_next_refs < nnext_refs + cnt[children]) { r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the tree"); break; }
            for (t = o->first; t < (size_t)o->first + o->count; t++) { /* the lists, each ascending */
                size_t m, j;
                voxgi__ls_vertices(&f, refs[t], v);
                m = voxgi__ls_children_met(o, n, cell, VOXGI__LS_PAD * L->info.size, v, met);
                for (j = 0; j < m; j++) next_refs[nnext_refs + cnt[met[j]]++] = refs[t];
            }
            nnext_refs += cnt[children];
            if (r == VOXGI_OK) { /* a node with children has a line space */
                if (!voxgi__ls_grow(ctx, (void **)&spaces, nspaces, &cap_spaces, 4)) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the tree");
                else {
                    L->node[2 * o->node + 1] = (uint32_t)nspaces;
                    spaces[nspaces++] = o->node;
                }
            }
            held = 8 * nnodes + L->words_per_space * 4 * nspaces + 4 * nnext_refs + 8 * nleaves + 36 * f.triangle_count;
            if (r == VOXGI_OK && held + children * L->words_per_space * 4 > budget)
                r = voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "the line space needs more than %lu bytes, over the budget of %lu", (unsigned long)held,
                                (unsigned long)budget);
        }
        if (r == VOXGI_OK && lev == depth) { /* the leaves' lists are the last level's */
            L->tris = next_refs;
            ntris = nnext_refs;
            cap_tris = cap_next_refs;
            next_refs = NULL;
            cap_next_refs = 0;
        } else { /* the next level's lists become the open ones */
            voxgi__ls_open *so = open;
            uint32_t *sr = refs;
            size_t sc = cap_open, src = cap_refs;
            open = next; cap_open = cap_next; next = so; cap_next = sc;
            refs = next_refs; cap_refs = cap_next_refs; next_refs = sr; cap_next_refs = src;
            nopen = nnext;
        }
    }
    if (r == VOXGI_OK && nspaces) { /* the child masks, then each line space: the OR of its filled children's */
        B.L = L;
        B.spaces = spaces;
        B.masks = (uint32_t *)voxgi__alloc_array(ctx, children * L->words_per_space, 4, 1);
        L->bits = (uint32_t *)voxgi__alloc_array(ctx, nspaces * L->words_per_space, 4, 1);
        if (!B.masks || !L->bits) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu line spaces", (unsigned long)nspaces);
        else {
            voxgi__parallel(ctx, children, 1, voxgi__ls_masks, &B);
            voxgi__parallel(ctx, nspaces, 1, voxgi__ls_spaces, &B);
        }
        voxgi__free(ctx, B.masks);
    }
    L->info.nodes = nnodes;
    L->info.line_spaces = nspaces;
    L->info.leaves = nleaves;
    L->info.triangle_refs = ntris;
    L->info.triangles = f.triangle_count;
    L->info.bytes = 8 * nnodes + L->words_per_space * 4 * nspaces + 4 * ntris + 8 * nleaves + 36 * f.triangle_count;
    L->info.allocated = sizeof *L + 8 * cap_nodes + L->words_per_space * 4 * nspaces + 4 * cap_tris + 4 * cap_leaf + 36 * VOXGI__MAX(f.triangle_count, (size_t)1);
#ifndef VOXGI_NO_GL
    if (r == VOXGI_OK && ctx->backend == VOXGI_BACKEND_GL) { /* kept for the GL rays (too large for GL: they fail, and say why) */
        const void *data[VOXGI__LS_GL_BUFFERS];
        size_t bytes[VOXGI__LS_GL_BUFFERS];
        if (voxgi__ls_arrays_gl(ctx, L, data, bytes) < 0 && ctx->gl->max_compute_ssbo_blocks >= VOXGI__LS_GL_BLOCKS) r = voxgi__ls_upload_gl(ctx, L, L->gl);
    }
#endif
    L->info.ms = voxgi__now_ms() - t0;
    voxgi__free(ctx, open);
    voxgi__free(ctx, next);
    voxgi__free(ctx, refs);
    voxgi__free(ctx, next_refs);
    voxgi__free(ctx, spaces);
    voxgi__free(ctx, cnt);
    voxgi__free(ctx, met);
    voxgi__flat_free(ctx, &f);
    if (r != VOXGI_OK) voxgi_linespace_destroy(ctx, L);
    else *out = L;
    return r;
}

/* ----- 12.2 shadow rays through the line space
   A ray lives in the frame of the node it crosses: the node is [0, n]^3 and its children unit
   cubes, so a child's frame is n (o - cell) with its direction n d, and t is the same in all.
   Everything is float, in an order GLSL repeats (shaders/linespace.glsl: no fused multiply-adds,
   each quotient the correctly rounded one), so the GL rays are the CPU's bit for bit.
   A node the segment crosses face to face asks its line space (the patches where it enters and
   leaves): clear, skip it; set at the last line-space level, fast mode calls the ray blocked,
   exact mode goes on to the leaves' triangles. A node holding an end of the segment (the shading
   point's, the light's) has no such line, so its children are walked, and at the leaves the
   triangles decide in both modes; fast mode also walks down wherever the segment lies within 3
   leaves' edges of an end (the surface a ray leaves fills the cells beside its start, and a
   shaft from a patch just above them touches them: it would shadow points near a node's side). No surface occludes itself, and fast
   mode is only ever too dark. */

/* A shadow ray: in the root's frame for the tree, and relative to the centre, sheared (Woop et
   al.), for the triangles; its segment t in (t0, t1). */
typedef struct voxgi__ls_ray {
    float o[3], d[3];             /* the root's frame */
    float ro[3], rd[3];           /* world units, relative to the centre */
    float t0, t1;
    float tn0, tn1;               /* fast mode reads bits as hits only between these: 3 leaves' edges from the ends */
    int kx, ky, kz;
    float sx, sy, sz;
} voxgi__ls_ray;

/* Fast mode walks down to the triangles within this many leaves' edges of a segment's ends. */
#define VOXGI__LS_EXACT_ENDS 3

/* What the rays cost: nodes entered, line-space bits read, triangles tested. */
typedef struct voxgi__ls_counts {
    uint64_t rays, nodes, bits, triangles;
} voxgi__ls_counts;

/* The ray from o along d (world units, float) for t in (t0, t1), fast mode's exact zone `near`
   (the root's frame) at each end; 0 for a zero direction. */
static int voxgi__ls_ray_set_centred(const voxgi_linespace *L, const float ro[3], const float d[3], float t0, float t1, float near, voxgi__ls_ray *r)
{
    int a, kz = 0, k[3];
    float sh[3];
    for (a = 0; a < 3; a++) {
        r->ro[a] = ro[a];
        r->rd[a] = d[a];
        r->o[a] = (r->ro[a] + L->half) * L->scale;
        r->d[a] = d[a] * L->scale;
        if (fabsf(d[a]) > fabsf(d[kz])) kz = a;
    }
    r->t0 = t0;
    r->t1 = t1;
    if (d[kz] == 0) return 0;
    r->tn0 = t0 + near / fabsf(r->d[kz]); /* the largest component: at least `near` of travel */
    r->tn1 = t1 - near / fabsf(r->d[kz]);
    voxgi__shear(d, k, sh);
    r->kx = k[0]; r->ky = k[1]; r->kz = k[2];
    r->sx = sh[0]; r->sy = sh[1]; r->sz = sh[2];
    return 1;
}

/* The same for origin o in the scene's frame. */
static int voxgi__ls_ray_set(const voxgi_linespace *L, const float o[3], const float d[3], float t0, float t1, float near, voxgi__ls_ray *r)
{
    float ro[3];
    int a;
    for (a = 0; a < 3; a++) ro[a] = (float)((double)o[a] - L->centre[a]);
    return voxgi__ls_ray_set_centred(L, ro, d, t0, t1, near, r);
}

/* Whether the ray meets triangle v (9 floats, relative to the centre) at t in (t0, t1): the
   watertight test of the ray core (sheared edge functions in float, those within rounding of 0
   again in double), so rays through shared edges and vertices never slip through. */
static VOXGI__HOT_INLINE int voxgi__ls_tri_hit(const float *v, const voxgi__ls_ray *r)
{
    int kx = r->kx, ky = r->ky, kz = r->kz;
    float az = v[kz] - r->ro[kz], bz = v[3 + kz] - r->ro[kz], cz = v[6 + kz] - r->ro[kz];
    float ax = (v[kx] - r->ro[kx]) - r->sx * az, ay = (v[ky] - r->ro[ky]) - r->sy * az;
    float bx = (v[3 + kx] - r->ro[kx]) - r->sx * bz, by = (v[3 + ky] - r->ro[ky]) - r->sy * bz;
    float cx = (v[6 + kx] - r->ro[kx]) - r->sx * cz, cy = (v[6 + ky] - r->ro[ky]) - r->sy * cz;
    float p0 = cx * by, q0 = cy * bx, p1 = ax * cy, q1 = ay * cx, p2 = bx * ay, q2 = by * ax;
    float u = p0 - q0, w = p1 - q1, x = p2 - q2, det, t;
    if (fabsf(u) <= VOXGI__EDGE_NEAR_ZERO * (fabsf(p0) + fabsf(q0)) || fabsf(w) <= VOXGI__EDGE_NEAR_ZERO * (fabsf(p1) + fabsf(q1)) ||
        fabsf(x) <= VOXGI__EDGE_NEAR_ZERO * (fabsf(p2) + fabsf(q2))) {
        double U = (double)cx * by - (double)cy * bx, W = (double)ax * cy - (double)ay * cx, X = (double)bx * ay - (double)by * ax, D, T;
        if ((U < 0 || W < 0 || X < 0) && (U > 0 || W > 0 || X > 0)) return 0;
        D = U + W + X;
        if (D == 0) return 0;
        T = (U * az + W * bz + X * cz) * (double)r->sz / D;
        return T > r->t0 && T < r->t1;
    }
    if ((u < 0 || w < 0 || x < 0) && (u > 0 || w > 0 || x > 0)) return 0;
    det = u + w + x;
    if (det == 0) return 0;
    t = (u * az + w * bz + x * cz) * r->sz / det;
    return t > r->t0 && t < r->t1;
}

/* The last triangles a ray tested (and missed): a triangle over several leaves is tested once. */
typedef struct voxgi__ls_mailbox {
    uint32_t id[8];
    unsigned next;
} voxgi__ls_mailbox;

/* Whether the ray meets a triangle of leaf `leaf` (mb: what it missed already). */
static VOXGI__HOT_INLINE int voxgi__ls_leaf_hit(const voxgi_linespace *L, uint32_t leaf, const voxgi__ls_ray *r, voxgi__ls_mailbox *mb, voxgi__ls_counts *cnt)
{
    const uint32_t *t = L->tris + L->leaf[2 * (size_t)leaf], *end = t + L->leaf[2 * (size_t)leaf + 1];
    for (; t < end; t++) {
        int k, seen = 0;
        for (k = 0; k < 8; k++) seen |= mb->id[k] == *t;
        if (seen) continue;
        cnt->triangles++;
        if (voxgi__ls_tri_hit(L->tv + 9 * (size_t)*t, r)) return 1;
        mb->id[mb->next++ & 7] = *t;
    }
    return 0;
}

/* The axes after a (u = [a], w = [a + 1]): a face's patch (i, j) runs i along u, j along w. */
static const int voxgi__ls_axis_after[5] = {1, 2, 0, 1, 2};

/* Where the ray (o, d in the node's frame) is at t, as a child's (or a face's patch's) index along
   `axis`: clamped to [0, n - 1], as shaders/linespace.glsl's cell_of. */
static VOXGI__HOT_INLINE int voxgi__ls_cell_at(int n, const float o[3], const float d[3], float t, int axis)
{
    int i = (int)(o[axis] + t * d[axis]); /* in [0, n] up to rounding (t lies within the node): no overflow */
    return i < 0 ? 0 : (i > n - 1 ? n - 1 : i);
}

/* The faces a ray going along d enters (in) and leaves (out) a box by, per axis: the face of axis a
   at 0 is 2 a, at n 2 a + 1. */
static VOXGI__HOT_INLINE void voxgi__ls_faces(const float d[3], int in[3], int out[3])
{
    int a;
    for (a = 0; a < 3; a++) {
        in[a] = 2 * a + (d[a] < 0);
        out[a] = 2 * a + (d[a] > 0);
    }
}

/* The bit of line space `space` for the ray (o, d in the node's frame) entering at ta by a face
   of axis ea and leaving at tb by one of axis xa (in, out: its faces, voxgi__ls_faces). */
static VOXGI__HOT_INLINE int voxgi__ls_crossing_bit(const voxgi_linespace *L, uint32_t space, const float o[3], const float d[3], const int in[3], const int out[3],
                                                    float ta, float tb, int ea, int xa, voxgi__ls_counts *cnt)
{
    const int n = L->info.n;
    const uint32_t *pair = L->pair_bit[in[ea]][out[xa]];
    uint32_t ps = (uint32_t)(voxgi__ls_cell_at(n, o, d, ta, voxgi__ls_axis_after[ea]) * n + voxgi__ls_cell_at(n, o, d, ta, voxgi__ls_axis_after[ea + 1]));
    uint32_t pe = (uint32_t)(voxgi__ls_cell_at(n, o, d, tb, voxgi__ls_axis_after[xa]) * n + voxgi__ls_cell_at(n, o, d, tb, voxgi__ls_axis_after[xa + 1]));
    uint32_t bit = pair[0] + ps * pair[1] + pe * pair[2];
    cnt->bits++;
    return (int)((L->bits[(size_t)space * L->words_per_space + (bit >> 5)] >> (bit & 31)) & 1);
}

/* Where the ray (o, d, in a frame; inv = 1 / d) is inside the box [lo, hi]^3 of that frame,
   closed: 0 if nowhere, else its t range and the axes of the faces it enters (ea) and leaves (xa)
   by; an axis the ray runs along (d 0) is never one of them. */
static VOXGI__HOT_INLINE int voxgi__ls_slab_inv(const float o[3], const float d[3], const float inv[3], const float lo[3], const float hi[3], float *ta, float *tb,
                                                int *ea, int *xa)
{
    float t_in = -INFINITY, t_out = INFINITY;
    int a, e = -1, x = -1;
    for (a = 0; a < 3; a++) {
        float tn, tf;
        if (d[a] == 0) {
            if (o[a] < lo[a] || o[a] > hi[a]) return 0;
            continue;
        }
        tn = ((d[a] > 0 ? lo[a] : hi[a]) - o[a]) * inv[a];
        tf = ((d[a] > 0 ? hi[a] : lo[a]) - o[a]) * inv[a];
        if (tn > t_in) { t_in = tn; e = a; }
        if (tf < t_out) { t_out = tf; x = a; }
    }
    *ta = t_in;
    *tb = t_out;
    *ea = e;
    *xa = x;
    return t_in <= t_out;
}

static VOXGI__HOT_INLINE int voxgi__ls_slab(const float o[3], const float d[3], const float lo[3], const float hi[3], float *ta, float *tb, int *ea, int *xa)
{
    const float inv[3] = {1.0f / d[0], 1.0f / d[1], 1.0f / d[2]};
    return voxgi__ls_slab_inv(o, d, inv, lo, hi, ta, tb, ea, xa);
}

/* A split node the DDA walks: the ray in its frame (its direction and 1 / direction are its
   level's), the child it is in, where that child was entered (t and the axis of the face, -1 where
   the segment starts in it), the node's exit. */
typedef struct voxgi__ls_level {
    uint32_t first;               /* the node's first child */
    int child;                    /* the current one among them, (z n + y) n + x */
    float o[3], next[3];          /* next: t where the ray leaves the current child along each axis */
    int cell[3];
    float t, t_out;
    int entry_axis, exit_axis;    /* exit_axis -1: the segment ends in the node */
} voxgi__ls_level;

/* Level s walks the node whose children start at `first` (its frame o, d, inv = 1 / d; up[a]: d[a]
   > 0) from ta (entered by a face of axis ea, or -1) to tb (left by axis xa, or -1). */
static VOXGI__HOT_INLINE void voxgi__ls_level_start(voxgi__ls_level *s, int n, const int up[3], uint32_t first, const float o[3], const float d[3], const float inv[3],
                                  float ta, float tb, int ea, int xa)
{
    int a;
    s->first = first;
    s->t = ta;
    s->t_out = tb;
    s->entry_axis = ea;
    s->exit_axis = xa;
    for (a = 0; a < 3; a++) {
        float p = o[a] + ta * d[a];
        s->o[a] = o[a];
        s->cell[a] = p < 1 ? 0 : (p >= (float)(n - 1) ? n - 1 : (int)p);
        s->next[a] = d[a] == 0 ? INFINITY : ((float)(s->cell[a] + up[a]) - o[a]) * inv[a]; /* inv: +-inf for 0, never used */
    }
    s->child = (s->cell[2] * n + s->cell[1]) * n + s->cell[0];
}

/* Level s's ray steps across the next plane of axis a (t: what it returns) into the next child:
   s->t is that t, or infinity where the node ends there. */
static VOXGI__HOT_INLINE float voxgi__ls_advance(voxgi__ls_level *s, int a, int n, const int up[3], const int step[3], const int child_step[3], const float inv[3])
{
    float t = s->next[a];
    s->cell[a] += step[a];
    s->child += child_step[a];
    s->next[a] = ((float)(s->cell[a] + up[a]) - s->o[a]) * inv[a];
    s->entry_axis = a;
    s->t = (unsigned)s->cell[a] >= (unsigned)n ? INFINITY : t;
    return t;
}

/* Whether the ray meets a triangle (exact) or, in fast mode, a set bit of the last line-space
   level: the per-ray walk, each node's children in the order the ray meets them (3D DDA). */
static int voxgi__ls_trace(const voxgi_linespace *L, const voxgi__ls_ray *r, int fast, voxgi__ls_counts *cnt)
{
    voxgi__ls_level st[8], cur;   /* the levels above the one walked, and that one */
    voxgi__ls_mailbox mb;
    float lv_d[8][3], lv_inv[8][3]; /* every node of a level has the same direction in its frame */
    int levels = 1, a, up[3], step[3], child_step[3], face_in[3], face_out[3];
    const int n = L->info.n, depth = L->info.depth;
    const float lo[3] = {0, 0, 0}, hi[3] = {(float)n, (float)n, (float)n};
    float ta, tb;
    int ea, xa, top = 0, blocked = 0;
    for (a = 0; a < 3; a++) lv_inv[0][a] = 1.0f / r->d[a];
    if (L->node[0] == UINT32_MAX || !voxgi__ls_slab_inv(r->o, r->d, lv_inv[0], lo, hi, &ta, &tb, &ea, &xa)) return 0; /* an empty scene, or outside */
    if (ta <= r->t0) { ta = r->t0; ea = -1; }
    if (tb >= r->t1) { tb = r->t1; xa = -1; }
    if (ta > tb) return 0;
    cnt->nodes++;
    voxgi__ls_faces(r->d, face_in, face_out); /* every level's: the signs are */
    if (ea >= 0 && xa >= 0) { /* through the root */
        if (!voxgi__ls_crossing_bit(L, L->node[1], r->o, r->d, face_in, face_out, ta, tb, ea, xa, cnt)) return 0;
        if (fast && depth == 1 && ta >= r->tn0 && tb <= r->tn1) return 1;
    }
    memset(&mb, 0xFF, sizeof mb.id);
    mb.next = 0;
    for (a = 0; a < 3; a++) { /* the signs are every level's */
        lv_d[0][a] = r->d[a];
        up[a] = r->d[a] > 0;
        step[a] = up[a] ? 1 : -1;
        child_step[a] = step[a] * (a == 0 ? 1 : (a == 1 ? n : n * n));
    }
    voxgi__ls_level_start(&cur, n, up, L->node[0], r->o, lv_d[0], lv_inv[0], ta, tb, ea, xa);
    for (;;) {
        uint32_t child, first, other;
        float ca = cur.t, cb, co[3];
        int c[3];
        if (!(ca <= cur.t_out)) { /* this node is done */
            if (--top < 0) break;
            cur = st[top];
            continue;
        }
        c[0] = cur.cell[0]; c[1] = cur.cell[1]; c[2] = cur.cell[2];
        child = cur.first + (uint32_t)cur.child;
        ea = cur.entry_axis;
        /* on to the next child, across the nearest of the three planes (each axis spelt out, so the
           level stays in registers) */
        if (cur.next[1] < cur.next[0]) xa = cur.next[2] < cur.next[1] ? 2 : 1;
        else xa = cur.next[2] < cur.next[0] ? 2 : 0;
        if (xa == 0) cb = voxgi__ls_advance(&cur, 0, n, up, step, child_step, lv_inv[top]);
        else if (xa == 1) cb = voxgi__ls_advance(&cur, 1, n, up, step, child_step, lv_inv[top]);
        else cb = voxgi__ls_advance(&cur, 2, n, up, step, child_step, lv_inv[top]);
        if (cb >= cur.t_out) { cb = cur.t_out; xa = cur.exit_axis; cur.t = INFINITY; }
        first = L->node[2 * (size_t)child];
        other = L->node[2 * (size_t)child + 1];
        if (first == UINT32_MAX) { /* a leaf or empty */
            if (other != UINT32_MAX && voxgi__ls_leaf_hit(L, other, r, &mb, cnt)) { blocked = 1; break; }
            continue;
        }
        cnt->nodes++;
        for (a = 0; a < 3; a++) co[a] = (cur.o[a] - (float)c[a]) * (float)n;
        if (levels == top + 1) { /* the first node of this level: its direction */
            for (a = 0; a < 3; a++) {
                lv_d[levels][a] = lv_d[top][a] * (float)n;
                lv_inv[levels][a] = 1.0f / lv_d[levels][a];
            }
            levels++;
        }
        if (ea >= 0 && xa >= 0) { /* crossed face to face: its line space */
            if (!voxgi__ls_crossing_bit(L, other, co, lv_d[top + 1], face_in, face_out, ca, cb, ea, xa, cnt)) continue;
            if (fast && top + 2 == depth && ca >= r->tn0 && cb <= r->tn1) { blocked = 1; break; }
        }
        st[top++] = cur;
        voxgi__ls_level_start(&cur, n, up, first, co, lv_d[top], lv_inv[top], ca, cb, ea, xa);
    }
    return blocked;
}

/* ----- packets: the rays from one point to the samples of a light walk each node together,
   slice by slice along the axis they mostly go (Wald et al.'s coherent grid traversal, after
   Klee): per slice the rectangle of children the packet's frustum can reach, each filled one
   tested against the rays still open (their arrays side by side, for the compiler's SIMD). The
   answers are the per-ray walk's: the same frames, slabs and bits; only the order differs. */

#define VOXGI__LS_PACKET 64

typedef struct voxgi__ls_packet {
    const voxgi_linespace *L;
    const voxgi__ls_ray *ray;     /* count rays from one origin */
    int count, fast, k;           /* k: the slices' axis, along which every ray goes the same way */
    float rlo[3], rhi[3];         /* the range of d[a] / d[k] over the rays (every frame's) */
    float d[9][3][VOXGI__LS_PACKET]; /* per level the rays' directions in its frame (split nodes' levels 0..7, and their children's) */
    float inv[8][3][VOXGI__LS_PACKET]; /* 1 / d of the split nodes' levels */
    uint64_t blocked;
    voxgi__ls_mailbox mb[VOXGI__LS_PACKET];
    voxgi__ls_counts *cnt;
} voxgi__ls_packet;

/* Per ray, where it is inside a node: t range and the axes it enters and leaves by (-1: an end). */
typedef struct voxgi__ls_span {
    float ta[VOXGI__LS_PACKET], tb[VOXGI__LS_PACKET];
    signed char ea[VOXGI__LS_PACKET], xa[VOXGI__LS_PACKET];
} voxgi__ls_span;

/* The children [lo, hi] along axis a that rays from o (in the frame) can reach while their k
   coordinate lies in [xlo, xhi] (o's own included). */
static void voxgi__ls_footprint(const voxgi__ls_packet *P, const float o[3], int a, float xlo, float xhi, int n, int *lo, int *hi)
{
    float p0 = xlo * P->rlo[a], p1 = xlo * P->rhi[a], p2 = xhi * P->rlo[a], p3 = xhi * P->rhi[a];
    float mn = VOXGI__MIN(VOXGI__MIN(p0, p1), VOXGI__MIN(p2, p3)), mx = VOXGI__MAX(VOXGI__MAX(p0, p1), VOXGI__MAX(p2, p3));
    float slack = 1e-3f * (1 + fabsf(mn) + fabsf(mx)); /* the ratios' rounding from frame to frame */
    float l = o[a] + mn - slack, h = o[a] + mx + slack;
    *lo = l < 0 ? 0 : (l >= (float)n ? n : (int)l);
    *hi = h < 0 ? -1 : (h >= (float)(n - 1) ? n - 1 : (int)h);
}

static void voxgi__ls_packet_node(voxgi__ls_packet *P, uint32_t node, int level, const float o[3], uint64_t active, const voxgi__ls_span *sp)
{
    const voxgi_linespace *L = P->L;
    const int n = L->info.n, k = P->k, u = (k + 1) % 3, w = (k + 2) % 3, dir = P->d[level][k][voxgi__ctz64(active)] > 0 ? 1 : -1;
    voxgi__ls_span sub;
    float reach_lo = INFINITY, reach_hi = -INFINITY;
    int s, s_end, i;
    uint64_t m;
    if (level > 7) return; /* never: depth <= 8 (the bound for the compiler) */
    for (m = active; m; m &= m - 1) { /* the slices the rays reach */
        int r = voxgi__ctz64(m);
        float x0 = o[k] + sp->ta[r] * P->d[level][k][r], x1 = o[k] + sp->tb[r] * P->d[level][k][r];
        reach_lo = VOXGI__MIN(reach_lo, VOXGI__MIN(x0, x1));
        reach_hi = VOXGI__MAX(reach_hi, VOXGI__MAX(x0, x1));
    }
    s = (int)VOXGI__MAX(0.0f, VOXGI__MIN((float)(n - 1), floorf(dir > 0 ? reach_lo : reach_hi)));
    s_end = (int)VOXGI__MAX(0.0f, VOXGI__MIN((float)(n - 1), floorf(dir > 0 ? reach_hi : reach_lo)));
    for (;; s += dir) {
        float xlo = (float)s - o[k], xhi = (float)(s + 1) - o[k];
        int ulo, uhi, wlo, whi, cu, cw;
        if (dir > 0) xlo = VOXGI__MAX(xlo, 0.0f);
        else xhi = VOXGI__MIN(xhi, 0.0f);
        voxgi__ls_footprint(P, o, u, xlo, xhi, n, &ulo, &uhi);
        voxgi__ls_footprint(P, o, w, xlo, xhi, n, &wlo, &whi);
        for (cw = wlo; cw <= whi; cw++)
            for (cu = ulo; cu <= uhi; cu++) {
                int c[3];
                uint32_t child, first, other;
                uint64_t into = 0;
                float lo[3], hi[3], co[3];
                c[k] = s; c[u] = cu; c[w] = cw;
                child = L->node[2 * node] + (uint32_t)((c[2] * n + c[1]) * n + c[0]);
                first = L->node[2 * (size_t)child];
                other = L->node[2 * (size_t)child + 1];
                if (first == UINT32_MAX && other == UINT32_MAX) continue; /* empty */
                for (i = 0; i < 3; i++) { lo[i] = (float)c[i]; hi[i] = (float)(c[i] + 1); }
                for (i = 0; i < 3; i++) co[i] = (o[i] - (float)c[i]) * (float)n;
                if (first != UINT32_MAX) P->cnt->nodes++;
                for (m = active & ~P->blocked; m; m &= m - 1) {
                    int r = voxgi__ctz64(m), ea, xa, a;
                    float ta, tb, d[3], inv[3], cd[3];
                    for (a = 0; a < 3; a++) {
                        d[a] = P->d[level][a][r];
                        inv[a] = P->inv[level][a][r];
                    }
                    if (!voxgi__ls_slab_inv(o, d, inv, lo, hi, &ta, &tb, &ea, &xa)) continue;
                    if (ta <= sp->ta[r]) { ta = sp->ta[r]; ea = sp->ea[r]; }
                    if (tb >= sp->tb[r]) { tb = sp->tb[r]; xa = sp->xa[r]; }
                    if (ta > tb) continue;
                    if (first == UINT32_MAX) { /* a leaf */
                        if (voxgi__ls_leaf_hit(L, other, &P->ray[r], &P->mb[r], P->cnt)) P->blocked |= (uint64_t)1 << r;
                        continue;
                    }
                    if (ea >= 0 && xa >= 0) {
                        int in[3], out[3];
                        for (a = 0; a < 3; a++) cd[a] = P->d[level + 1][a][r];
                        voxgi__ls_faces(cd, in, out);
                        if (!voxgi__ls_crossing_bit(L, other, co, cd, in, out, ta, tb, ea, xa, P->cnt)) continue;
                        if (P->fast && level + 2 == L->info.depth && ta >= P->ray[r].tn0 && tb <= P->ray[r].tn1) { P->blocked |= (uint64_t)1 << r; continue; }
                    }
                    sub.ta[r] = ta;
                    sub.tb[r] = tb;
                    sub.ea[r] = (signed char)ea;
                    sub.xa[r] = (signed char)xa;
                    into |= (uint64_t)1 << r;
                }
                if (into) voxgi__ls_packet_node(P, child, level + 1, co, into, &sub);
                if (!(active & ~P->blocked)) return;
            }
        if (s == s_end) break;
    }
}

/* Which of the count rays (one origin, count <= 64) are blocked, as bits. Rays not going the
   packet's way along its axis walk alone. */
static uint64_t voxgi__ls_trace_packet(const voxgi_linespace *L, const voxgi__ls_ray *ray, int count, int fast, voxgi__ls_counts *cnt)
{
    voxgi__ls_packet *P, Pbuf;
    voxgi__ls_span sp;
    const int n = L->info.n;
    const float lo[3] = {0, 0, 0}, hi[3] = {(float)n, (float)n, (float)n};
    float sum[3] = {0, 0, 0};
    uint64_t in = 0;
    int r, a, lev;
    P = &Pbuf;
    P->L = L;
    P->ray = ray;
    P->count = count;
    P->fast = fast;
    P->blocked = 0;
    P->cnt = cnt;
    memset(P->mb, 0xFF, sizeof P->mb);
    for (r = 0; r < count; r++)
        for (a = 0; a < 3; a++) sum[a] += ray[r].d[a];
    P->k = fabsf(sum[1]) > fabsf(sum[0]) ? 1 : 0;
    if (fabsf(sum[2]) > fabsf(sum[P->k])) P->k = 2;
    for (a = 0; a < 3; a++) { P->rlo[a] = INFINITY; P->rhi[a] = -INFINITY; }
    if (L->node[0] == UINT32_MAX) return 0;
    for (r = 0; r < count; r++) {
        float ta, tb;
        int ea, xa;
        if (!voxgi__ls_slab(ray[r].o, ray[r].d, lo, hi, &ta, &tb, &ea, &xa)) continue;
        if (ta <= ray[r].t0) { ta = ray[r].t0; ea = -1; }
        if (tb >= ray[r].t1) { tb = ray[r].t1; xa = -1; }
        if (ta > tb) continue;
        if (!(ray[r].d[P->k] != 0 && (ray[r].d[P->k] > 0) == (sum[P->k] > 0))) { /* against the packet's way: alone */
            if (voxgi__ls_trace(L, &ray[r], fast, cnt)) P->blocked |= (uint64_t)1 << r;
            continue;
        }
        cnt->nodes++;
        if (ea >= 0 && xa >= 0) {
            int in[3], out[3];
            voxgi__ls_faces(ray[r].d, in, out);
            if (!voxgi__ls_crossing_bit(L, L->node[1], ray[r].o, ray[r].d, in, out, ta, tb, ea, xa, cnt)) continue;
            if (fast && L->info.depth == 1 && ta >= ray[r].tn0 && tb <= ray[r].tn1) { P->blocked |= (uint64_t)1 << r; continue; }
        }
        sp.ta[r] = ta;
        sp.tb[r] = tb;
        sp.ea[r] = (signed char)ea;
        sp.xa[r] = (signed char)xa;
        for (a = 0; a < 3; a++) {
            float q = ray[r].d[a] / ray[r].d[P->k];
            P->rlo[a] = VOXGI__MIN(P->rlo[a], q);
            P->rhi[a] = VOXGI__MAX(P->rhi[a], q);
        }
        for (a = 0; a < 3; a++) {
            P->d[0][a][r] = ray[r].d[a];
            for (lev = 1; lev < L->info.depth; lev++) P->d[lev][a][r] = P->d[lev - 1][a][r] * (float)n;
            for (lev = 0; lev < L->info.depth; lev++) P->inv[lev][a][r] = 1.0f / P->d[lev][a][r];
        }
        in |= (uint64_t)1 << r;
    }
    if (in) voxgi__ls_packet_node(P, 0, 0, ray[voxgi__ctz64(in)].o, in, &sp);
    return P->blocked;
}

typedef struct voxgi__ls_job {
    const voxgi_linespace *L;
    const voxgi_ray *rays;
    unsigned char *occluded;
    const voxgi_linespace_light_desc *light;
    const float *points, *normals;
    float *visible, *weighted;
    float corner[3], eu[3], ev[3], hair;
    float near;                   /* fast mode's exact zone at each end, the root's frame */
    int fast, nu, nv;
    size_t chunk;
    voxgi__ls_counts *counts;     /* one per chunk */
} voxgi__ls_job;

static void voxgi__ls_rays_cpu(void *user, size_t first, size_t end)
{
    voxgi__ls_job *J = (voxgi__ls_job *)user;
    voxgi__ls_counts *cnt = &J->counts[first / J->chunk];
    size_t i;
    for (i = first; i < end; i++) {
        const voxgi_ray *q = &J->rays[i];
        voxgi__ls_ray r;
        J->occluded[i] = 0;
        if (!(q->tmax > q->tmin) || !voxgi__ls_ray_set(J->L, q->origin, q->direction, q->tmin, q->tmax, J->near, &r)) continue;
        J->occluded[i] = (unsigned char)voxgi__ls_trace(J->L, &r, J->fast, cnt);
    }
}

#ifndef VOXGI_NO_GL
/* The rays' line-space uniforms of program p (the walk's: shaders/linespace.glsl). */
static void voxgi__ls_walk_uniforms_gl(const voxgi_context *ctx, unsigned int p, const voxgi_linespace *L, int fast, float near)
{
    voxgi__gl *gl = ctx->gl;
    gl->ProgramUniform1ui(p, VOXGI__LOC_u_bits_part, (unsigned)voxgi__ls_bits_part_words(ctx, L));
    gl->ProgramUniform1i(p, VOXGI__LOC_u_n, L->info.n);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_depth, L->info.depth);
    gl->ProgramUniform1ui(p, VOXGI__LOC_u_words, (unsigned)L->words_per_space);
    gl->ProgramUniform3d(p, VOXGI__LOC_u_centre, L->centre[0], L->centre[1], L->centre[2]);
    gl->ProgramUniform1f(p, VOXGI__LOC_u_half, L->half);
    gl->ProgramUniform1f(p, VOXGI__LOC_u_scale, L->scale);
    gl->ProgramUniform1i(p, VOXGI__LOC_u_fast, fast);
    gl->ProgramUniform1f(p, VOXGI__LOC_u_near_ends, near);
}

/* voxgi__ls_rays_cpu on GL (shaders/linespace_rays.glsl), in slices of VOXGI__LS_GL_RAYS rays,
   each finished before the next. */
#define VOXGI__LS_GL_RAYS 16384
typedef char voxgi__ray_is_eight_floats[sizeof(voxgi_ray) == 32 ? 1 : -1]; /* the shader reads it so */
static voxgi_result voxgi__ls_rays_gl(voxgi_context *ctx, const voxgi__ls_job *J, size_t count)
{
    voxgi__gl *gl = ctx->gl;
    const voxgi_linespace *L = J->L;
    unsigned int own[VOXGI__LS_GL_BUFFERS] = {0, 0, 0, 0, 0, 0, 0, 0}, io[2] = {0, 0}, p;
    const unsigned int *lsb = L->gl[0] ? L->gl : own;
    size_t slice = VOXGI__MIN(count, (size_t)VOXGI__LS_GL_RAYS), first, i;
    uint32_t *flags;
    int k;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_linespace_rays);
    if (r != VOXGI_OK) return r;
    if (!L->gl[0] && (r = voxgi__ls_upload_gl(ctx, L, own)) != VOXGI_OK) return r; /* made on a CPU context: for this call */
    if (!(flags = (uint32_t *)voxgi__alloc_array(ctx, slice, 4, 0))) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu rays", (unsigned long)slice);
    if (r == VOXGI_OK) {
        p = gl->prog_linespace_rays;
        io[0] = voxgi__gl_buffer(ctx, slice * sizeof(voxgi_ray), NULL);
        io[1] = voxgi__gl_buffer(ctx, slice * 4, NULL);
        voxgi__ls_bind_gl(gl, lsb);
        for (k = 0; k < 2; k++) gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, (unsigned)(5 + k), io[k]);
        gl->UseProgram(p);
        voxgi__ls_walk_uniforms_gl(ctx, p, L, J->fast, J->near);
    }
    for (first = 0; r == VOXGI_OK && first < count; first += slice) {
        size_t m = VOXGI__MIN(slice, count - first);
        gl->NamedBufferSubData(io[0], 0, (ptrdiff_t)(m * sizeof(voxgi_ray)), J->rays + first); /* 8 floats a ray, as the shader reads them */
        gl->ProgramUniform1ui(p, VOXGI__LOC_u_count, (unsigned)m);
        voxgi__gl_dispatch_items(gl, (uint64_t)m);
        if ((r = voxgi__gl_read_buffer(ctx, io[1], flags, m * 4)) != VOXGI_OK) break;
        for (i = 0; i < m; i++) J->occluded[first + i] = (unsigned char)(flags[i] != 0);
    }
    voxgi__gl_unbind(gl);
    for (k = 0; k < VOXGI__LS_GL_BUFFERS; k++) voxgi__gl_delete_buffer(ctx, own[k]);
    for (k = 0; k < 2; k++) voxgi__gl_delete_buffer(ctx, io[k]);
    voxgi__free(ctx, flags);
    if (r == VOXGI_OK) r = voxgi__gl_check(ctx, "the line space's rays");
    return r;
}
#endif

VOXGI_API voxgi_result voxgi_linespace_occluded(voxgi_context *ctx, const voxgi_linespace *ls, voxgi_linespace_mode mode, size_t count, const voxgi_ray *rays,
                                                unsigned char *occluded)
{
    voxgi__ls_job J;
    voxgi_result r = VOXGI_OK;
    size_t i;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!ls || (count && (!rays || !occluded))) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "line space, rays or occluded is NULL");
    if (mode != VOXGI_LINESPACE_EXACT && mode != VOXGI_LINESPACE_FAST) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "mode %d", (int)mode);
    for (i = 0; i < count; i++)
        if (!voxgi__ray_finite(&rays[i])) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "ray %lu is not finite", (unsigned long)i);
    memset(&J, 0, sizeof J);
    J.L = ls;
    J.rays = rays;
    J.occluded = occluded;
    J.fast = mode == VOXGI_LINESPACE_FAST;
    J.near = (float)VOXGI__LS_EXACT_ENDS * ls->leaf_edge;
    J.chunk = 256;
    if (!(J.counts = (voxgi__ls_counts *)voxgi__alloc_array(ctx, count / J.chunk + 1, sizeof *J.counts, 1)))
        return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu rays", (unsigned long)count);
#ifndef VOXGI_NO_GL
    if (ctx->backend == VOXGI_BACKEND_GL && count) r = voxgi__ls_rays_gl(ctx, &J, count);
    else
#endif
        voxgi__parallel(ctx, count, J.chunk, voxgi__ls_rays_cpu, &J);
    voxgi__free(ctx, J.counts);
    return r;
}

/* A hash of 32 bits (the PCG output permutation), the same in GLSL. */
static uint32_t voxgi__ls_hash(uint32_t x)
{
    x = x * 747796405u + 2891336453u;
    x = ((x >> ((x >> 28) + 4u)) ^ x) * 277803737u;
    return (x >> 22) ^ x;
}

/* Sample k (cell (k % nu, k / nu) of the light's nu x nv grid, jittered) for point `point`:
   where on the light, as s and t along its edges. */
static void voxgi__ls_light_st(uint32_t seed, uint32_t point, int k, int nu, int nv, int triangle, float *s, float *t)
{
    uint32_t h1 = voxgi__ls_hash(seed ^ voxgi__ls_hash(point ^ voxgi__ls_hash((uint32_t)k))), h2 = voxgi__ls_hash(h1);
    *s = ((float)(k % nu) + (float)(h1 >> 8) * (1.0f / 16777216.0f)) / (float)nu;
    *t = ((float)(k / nu) + (float)(h2 >> 8) * (1.0f / 16777216.0f)) / (float)nv;
    if (triangle && *s + *t > 1) { *s = 1 - *s; *t = 1 - *t; }
}

/* How far a point's rays start off its surface: the line space's hair, or where the point's own
   float rounding is larger (far from the origin: p at 1e3 rounds by 3e-5), 2^-20 of its largest
   coordinate: more than that rounding and the origin's, twice over, so the ray never starts
   behind its surface. Powers of two and a maximum: the same float on GL (shaders/linespace_light.glsl). */
static float voxgi__ls_lift(float hair, const float p[3])
{
    float m = fmaxf(fabsf(p[0]), fmaxf(fabsf(p[1]), fabsf(p[2])));
    return fmaxf(hair, m * 9.5367431640625e-7f);
}

/* The segment from point p (unit normal nrm: the side its rays leave) to light point (s, t),
   in the frame of the line space's centre (where the light's corner, J->corner, is kept: far from
   the origin the light's points keep their place to the tree's triangles): origin voxgi__ls_lift
   off the surface, ending short of the light by 2^-16 of the way (its own triangles never block
   it), and the sample's weight cos_p cos_l / r^2. 0 where the cosine at p is not positive (the
   surface itself is in the way: no ray goes). */
static int voxgi__ls_light_ray(const voxgi_linespace *L, const voxgi__ls_job *J, const float p[3], const float nrm[3], float s, float t, voxgi__ls_ray *r,
                               double *weight)
{
    float o[3], d[3], cos_p, lift = voxgi__ls_lift(J->hair, p);
    double cos_l, len2, fn[3];
    int a;
    for (a = 0; a < 3; a++) {
        float q = (J->corner[a] + s * J->eu[a]) + t * J->ev[a];
        o[a] = (float)((double)p[a] - L->centre[a]) + lift * nrm[a];
        d[a] = q - o[a];
    }
    cos_p = (nrm[0] * d[0] + nrm[1] * d[1]) + nrm[2] * d[2];
    *weight = 0;
    if (!(cos_p > 0) || !voxgi__ls_ray_set_centred(L, o, d, 0.0f, 1.0f - 1.52587890625e-5f, J->near, r)) return 0;
    for (a = 0; a < 3; a++) fn[a] = (double)J->eu[(a + 1) % 3] * J->ev[(a + 2) % 3] - (double)J->eu[(a + 2) % 3] * J->ev[(a + 1) % 3];
    len2 = (double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2];
    cos_l = -(fn[0] * d[0] + fn[1] * d[1] + fn[2] * d[2]) / sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]);
    if (cos_l > 0) *weight = cos_p * cos_l / (len2 * len2);
    return 1;
}

static void voxgi__ls_light_cpu(void *user, size_t first, size_t end)
{
    voxgi__ls_job *J = (voxgi__ls_job *)user;
    voxgi__ls_counts *cnt = &J->counts[first / J->chunk];
    voxgi__ls_ray ray[VOXGI__LS_PACKET];
    double wt[VOXGI__LS_PACKET];
    const int S = J->nu * J->nv;
    size_t i;
    for (i = first; i < end; i++) {
        const float *p = J->points + 3 * i, *nrm = J->normals + 3 * i;
        double seen = 0, wsum = 0, wseen = 0;
        int k0, k;
        for (k0 = 0; k0 < S; k0 += VOXGI__LS_PACKET) {
            int m = 0;
            uint64_t blocked = 0;
            for (k = k0; k < S && k < k0 + VOXGI__LS_PACKET; k++) {
                float s, t;
                voxgi__ls_light_st(J->light->seed, (uint32_t)i, k, J->nu, J->nv, J->light->triangle, &s, &t);
                if (!voxgi__ls_light_ray(J->L, J, p, nrm, s, t, &ray[m], &wt[m])) continue;
                wsum += wt[m];
                m++;
            }
            cnt->rays += (uint64_t)m;
            if (J->light->packets && m > 1) blocked = voxgi__ls_trace_packet(J->L, ray, m, J->fast, cnt);
            else
                for (k = 0; k < m; k++) blocked |= (uint64_t)voxgi__ls_trace(J->L, &ray[k], J->fast, cnt) << k;
            for (k = 0; k < m; k++)
                if (!(blocked >> k & 1)) { seen += 1; wseen += wt[k]; }
        }
        if (J->visible) J->visible[i] = (float)(seen / S);
        if (J->weighted) J->weighted[i] = wsum > 0 ? (float)(wseen / wsum) : 0.0f;
    }
}

#ifndef VOXGI_NO_GL
/* voxgi__ls_light_cpu on GL (shaders/linespace_light.glsl): each ray walks alone (packets are the
   CPU's; the answers are the same), in slices of points and passes of at most
   VOXGI__LS_GL_SAMPLES samples per point (llvmpipe ends an invocation's loops after 65535
   iterations in all; a ray takes hundreds), each pass finished before the next, so no one
   submission runs long. The points' sums come back, and visible and weighted are made from them
   as the CPU makes them; nl: the light's unit normal. */
#define VOXGI__LS_GL_SAMPLES 16
#define VOXGI__LS_GL_POINTS 4096
static voxgi_result voxgi__ls_light_gl(voxgi_context *ctx, const voxgi__ls_job *J, size_t count, const float nl[3], uint64_t *rays)
{
    voxgi__gl *gl = ctx->gl;
    const voxgi_linespace *L = J->L;
    unsigned int own[VOXGI__LS_GL_BUFFERS] = {0, 0, 0, 0, 0, 0, 0, 0}, io[3] = {0, 0, 0}, p;
    const unsigned int *lsb = L->gl[0] ? L->gl : own;
    const int S = J->nu * J->nv;
    size_t slice = VOXGI__MIN(count, (size_t)VOXGI__LS_GL_POINTS), first, i;
    uint32_t *sums;
    int k;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_linespace);
    if (r != VOXGI_OK) return r;
    if (count > (size_t)UINT32_MAX) return voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%lu points in one GL call", (unsigned long)count);
    if (!L->gl[0] && (r = voxgi__ls_upload_gl(ctx, L, own)) != VOXGI_OK) return r; /* made on a CPU context: for this call */
    if (!(sums = (uint32_t *)voxgi__alloc_array(ctx, slice, 16, 0))) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu points", (unsigned long)slice);
    if (r == VOXGI_OK) {
        p = gl->prog_linespace;
        io[0] = voxgi__gl_buffer(ctx, slice * 12, NULL);
        io[1] = voxgi__gl_buffer(ctx, slice * 12, NULL);
        io[2] = voxgi__gl_buffer(ctx, slice * 16, NULL);
        voxgi__ls_bind_gl(gl, lsb);
        for (k = 0; k < 3; k++) gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, (unsigned)(5 + k), io[k]);
        gl->UseProgram(p);
        voxgi__ls_walk_uniforms_gl(ctx, p, L, J->fast, J->near);
        gl->ProgramUniform1f(p, VOXGI__LOC_u_hair, J->hair);
        gl->ProgramUniform3f(p, VOXGI__LOC_u_corner, J->corner[0], J->corner[1], J->corner[2]);
        gl->ProgramUniform3f(p, VOXGI__LOC_u_edge_u, J->eu[0], J->eu[1], J->eu[2]);
        gl->ProgramUniform3f(p, VOXGI__LOC_u_edge_v, J->ev[0], J->ev[1], J->ev[2]);
        gl->ProgramUniform3f(p, VOXGI__LOC_u_light_normal, nl[0], nl[1], nl[2]);
        gl->ProgramUniform1i(p, VOXGI__LOC_u_triangle, J->light->triangle != 0);
        gl->ProgramUniform1ui(p, VOXGI__LOC_u_seed, J->light->seed);
        gl->ProgramUniform2i(p, VOXGI__LOC_u_cells, J->nu, J->nv);
    }
    for (first = 0; r == VOXGI_OK && first < count; first += slice) {
        size_t m = VOXGI__MIN(slice, count - first);
        gl->NamedBufferSubData(io[0], 0, (ptrdiff_t)(m * 12), J->points + 3 * first);
        gl->NamedBufferSubData(io[1], 0, (ptrdiff_t)(m * 12), J->normals + 3 * first);
        gl->ProgramUniform1ui(p, VOXGI__LOC_u_first, (unsigned)first);
        gl->ProgramUniform1ui(p, VOXGI__LOC_u_count, (unsigned)m);
        for (k = 0; k < S; k += VOXGI__LS_GL_SAMPLES) {
            gl->ProgramUniform2i(p, VOXGI__LOC_u_samples, k, VOXGI__MIN(k + VOXGI__LS_GL_SAMPLES, S));
            voxgi__gl_dispatch_items(gl, (uint64_t)m);
            gl->Finish();
        }
        if ((r = voxgi__gl_read_buffer(ctx, io[2], sums, m * 16)) != VOXGI_OK) break;
        for (i = 0; i < m; i++) { /* seen, rays, the weights' sum, the seen weights' sum */
            float w[2];
            memcpy(w, sums + 4 * i + 2, sizeof w);
            *rays += sums[4 * i + 1];
            if (J->visible) J->visible[first + i] = (float)((double)sums[4 * i] / S);
            if (J->weighted) J->weighted[first + i] = w[0] > 0 ? (float)((double)w[1] / w[0]) : 0.0f;
        }
    }
    voxgi__gl_unbind(gl);
    for (k = 0; k < VOXGI__LS_GL_BUFFERS; k++) voxgi__gl_delete_buffer(ctx, own[k]);
    for (k = 0; k < 3; k++) voxgi__gl_delete_buffer(ctx, io[k]);
    voxgi__free(ctx, sums);
    if (r == VOXGI_OK) r = voxgi__gl_check(ctx, "the line space's shadow rays");
    return r;
}
#endif

VOXGI_API voxgi_result voxgi_linespace_light(voxgi_context *ctx, const voxgi_linespace *ls, const voxgi_linespace_light_desc *desc, size_t count,
                                             const float *points, const float *normals, float *visible, float *weighted, voxgi_linespace_stats *stats)
{
    voxgi__ls_job J;
    double t0 = voxgi__now_ms(), cross[3], area;
    size_t i, chunks;
    int a, S;
    voxgi_result r = VOXGI_OK;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (stats) memset(stats, 0, sizeof *stats);
    if (!ls || !desc || (count && (!points || !normals))) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "line space, desc, points or normals is NULL");
    if (desc->mode != VOXGI_LINESPACE_EXACT && desc->mode != VOXGI_LINESPACE_FAST) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "mode %d", (int)desc->mode);
    S = desc->samples ? desc->samples : 16;
    if (S < 1 || S > 4096) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "samples %d (1..4096)", S);
    if (desc->exact_ends < 0 || desc->exact_ends > 1 << 20) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "exact_ends %d (0..2^20)", desc->exact_ends);
    for (a = 0; a < 3; a++)
        if (!isfinite(desc->corner[a]) || !isfinite(desc->edge_u[a]) || !isfinite(desc->edge_v[a]))
            return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the light is not finite");
    for (a = 0; a < 3; a++) cross[a] = desc->edge_u[(a + 1) % 3] * desc->edge_v[(a + 2) % 3] - desc->edge_u[(a + 2) % 3] * desc->edge_v[(a + 1) % 3];
    area = sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
    if (!(area > 0)) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "the light's edges are parallel: it has no area");
    for (i = 0; i < 3 * count; i++)
        if (!isfinite(points[i]) || !isfinite(normals[i])) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "point %lu is not finite", (unsigned long)(i / 3));
    memset(&J, 0, sizeof J);
    J.L = ls;
    J.light = desc;
    J.points = points;
    J.normals = normals;
    J.visible = visible;
    J.weighted = weighted;
    J.fast = desc->mode == VOXGI_LINESPACE_FAST;
    J.near = (float)(desc->exact_ends ? desc->exact_ends : VOXGI__LS_EXACT_ENDS) * ls->leaf_edge;
    J.nu = (int)ceil(sqrt((double)S) - 1e-9);
    J.nv = (S + J.nu - 1) / J.nu;
    J.hair = (float)(ls->info.size * VOXGI__LS_PAD);
    for (a = 0; a < 3; a++) {
        J.corner[a] = (float)(desc->corner[a] - ls->centre[a]); /* voxgi__ls_light_ray's frame */
        J.eu[a] = (float)desc->edge_u[a];
        J.ev[a] = (float)desc->edge_v[a];
    }
    J.chunk = 64;
    chunks = count / J.chunk + 1;
    if (!(J.counts = (voxgi__ls_counts *)voxgi__alloc_array(ctx, chunks, sizeof *J.counts, 1)))
        return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu points", (unsigned long)count);
#ifndef VOXGI_NO_GL
    if (ctx->backend == VOXGI_BACKEND_GL && count) {
        float nl[3];
        for (a = 0; a < 3; a++) nl[a] = (float)(cross[a] / area);
        r = voxgi__ls_light_gl(ctx, &J, count, nl, &J.counts[0].rays);
    } else
#endif
        voxgi__parallel(ctx, count, J.chunk, voxgi__ls_light_cpu, &J);
    if (r == VOXGI_OK && stats) {
        for (i = 0; i < chunks; i++) {
            stats->rays += J.counts[i].rays;
            stats->nodes += J.counts[i].nodes;
            stats->bits += J.counts[i].bits;
            stats->triangle_tests += J.counts[i].triangles;
        }
        stats->samples = J.nu * J.nv;
        stats->ms = voxgi__now_ms() - t0;
    }
    voxgi__free(ctx, J.counts);
    return r;
}

/* ----- 12.3 area lights: rect lights, and emissive triangles as parallelograms */

/* An area light for the images: a rect light, or emissive triangles (two sharing an edge as a
   parallelogram when they make one, with the same emission), with its radiance. */
typedef struct voxgi__ls_area {
    voxgi_linespace_light_desc d;
    double radiance[3];
    uint32_t own[2];              /* its emissive triangles (UINT32_MAX: none): no light on themselves */
} voxgi__ls_area;

#define VOXGI__LS_AREA_LIGHTS 64

/* The scene's area lights into A (room for VOXGI__LS_AREA_LIGHTS): their count, -1 for more,
   -2 without memory. */
static int voxgi__ls_area_lights(voxgi_context *ctx, const voxgi_scene *scene, const voxgi__flat *f, voxgi__ls_area *A)
{
    size_t i, t, u;
    int count = 0, a, k;
    unsigned char *paired = (unsigned char *)voxgi__alloc_array(ctx, VOXGI__MAX(f->triangle_count, (size_t)1), 1, 1);
    if (!paired) return -2;
    for (i = 0; i < scene->light_count; i++) {
        const voxgi_light *L = &scene->lights[i];
        if (L->type != VOXGI_LIGHT_RECT) continue;
        if (count == VOXGI__LS_AREA_LIGHTS) { count = -1; break; }
        memset(&A[count], 0, sizeof A[count]);
        for (a = 0; a < 3; a++) {
            A[count].d.corner[a] = L->position[a];
            A[count].d.edge_u[a] = L->edge_u[a];
            A[count].d.edge_v[a] = L->edge_v[a];
            A[count].radiance[a] = L->intensity[a];
        }
        A[count].own[0] = A[count].own[1] = UINT32_MAX;
        count++;
    }
    for (t = 0; count >= 0 && t < f->triangle_count; t++) {
        const voxgi_material *m = voxgi__tri_material(f, t);
        const float *v[3];
        int partner_k = -1, shared = 0;
        size_t partner = 0;
        double g[3];
        if (!(m->emission[0] > 0 || m->emission[1] > 0 || m->emission[2] > 0) || paired[t]) continue;
        voxgi__tri_unit_normal(f, t, g);
        if (g[0] == 0 && g[1] == 0 && g[2] == 0) continue; /* no area: no light */
        if (count == VOXGI__LS_AREA_LIGHTS) { count = -1; break; }
        for (k = 0; k < 3; k++) v[k] = f->pos + 3 * (size_t)f->tri[3 * t + (size_t)k];
        for (u = t + 1; u < f->triangle_count && partner_k < 0; u++) { /* a partner: the same emission, an edge in common, a parallelogram */
            const voxgi_material *mu = voxgi__tri_material(f, u);
            const float *w[3];
            int in[3], out_k = -1, j, c;
            if (paired[u] || memcmp(mu->emission, m->emission, sizeof m->emission) != 0 || mu->albedo[0] != m->albedo[0] ||
                mu->albedo[1] != m->albedo[1] || mu->albedo[2] != m->albedo[2])
                continue;
            for (j = 0; j < 3; j++) w[j] = f->pos + 3 * (size_t)f->tri[3 * u + (size_t)j];
            for (shared = 0, k = 0; k < 3; k++) {
                in[k] = 0;
                for (j = 0; j < 3; j++) in[k] |= memcmp(v[k], w[j], 12) == 0;
                shared += in[k];
            }
            if (shared != 2) continue;
            for (j = 0; j < 3; j++) {
                int hit = 0;
                for (k = 0; k < 3; k++) hit |= memcmp(w[j], v[k], 12) == 0;
                if (!hit) out_k = j;
            }
            if (out_k < 0) continue; /* a degenerate partner: every corner one of t's */
            for (k = 0; k < 3 && in[k]; k++) {}
            for (c = 0; c < 3; c++) { /* v[k] + w[out] = the two shared vertices' sum */
                double s = 0, e = fabs((double)v[k][c]) + fabs((double)w[out_k][c]);
                for (j = 0; j < 3; j++) if (in[j]) { s += v[j][c]; e += fabs((double)v[j][c]); }
                if (fabs((double)v[k][c] + w[out_k][c] - s) > 1e-6 * e) break;
            }
            if (c == 3) { partner_k = k; partner = u; }
        }
        memset(&A[count], 0, sizeof A[count]);
        A[count].own[0] = (uint32_t)t;
        A[count].own[1] = UINT32_MAX;
        if (partner_k >= 0) { /* corner: t's vertex off the shared edge; edges to the shared ones, turned to face as t does */
            const float *s1 = v[(partner_k + 1) % 3], *s2 = v[(partner_k + 2) % 3];
            for (a = 0; a < 3; a++) {
                A[count].d.corner[a] = v[partner_k][a];
                A[count].d.edge_u[a] = (double)s1[a] - v[partner_k][a];
                A[count].d.edge_v[a] = (double)s2[a] - v[partner_k][a];
            }
            paired[partner] = 1;
            A[count].own[1] = (uint32_t)partner;
        } else {
            A[count].d.triangle = 1;
            for (a = 0; a < 3; a++) {
                A[count].d.corner[a] = v[0][a];
                A[count].d.edge_u[a] = (double)v[1][a] - v[0][a];
                A[count].d.edge_v[a] = (double)v[2][a] - v[0][a];
            }
        }
        for (a = 0; a < 3; a++) A[count].radiance[a] = m->emission[a];
        count++;
    }
    voxgi__free(ctx, paired);
    return count;
}

#endif /* VOXGI_NO_LINE_SPACE */

/* ===================================================================== 13. reference renderer */
#ifndef VOXGI_NO_REFERENCE

/* What a reference image asks for (voxgi_render_desc resolved for REFERENCE). */
typedef struct voxgi__ref_desc {
    voxgi_camera camera;
    int samples;                  /* per pixel */
    int bounces;                  /* indirect bounces: 0 = direct light only, 1 = one bounce, ...;
                                     -1 = unlimited (Russian roulette ends paths without bias) */
    uint64_t seed;
    int hide_emitters;            /* 1: leave out the emission the camera sees directly (to compare lighting alone) */
    float ao_radius;              /* > 0: ambient occlusion instead of light: per sample a camera ray and one
                                     cosine-distributed ray from its surface, occluded when it meets any
                                     surface within ao_radius; the pixel is the occluded share (grey), 0
                                     where the camera sees nothing (voxgi_ao's exact definition) */
    int screen_light_only;        /* 1 (with bounces 1): the bounce takes the light a surface reflects only where the
                                     camera sees that surface (inside the image, nothing in front): the most that
                                     one bounce from the screen (voxgi_ssgi) can find */
} voxgi__ref_desc;

typedef struct voxgi__ref {
    voxgi_context *ctx;
    const voxgi__tracer *tr;
    voxgi__lights lights;
    const voxgi__ref_desc *desc;
    double eye[3], right[3], up[3], forward[3], tan_half;
    double *sum;                  /* 3 per pixel */
    int first_sample, pass_samples;
    size_t rays;                  /* summed over the workers */
} voxgi__ref;

/* Whether the camera sees point p on primitive prim's side `front` (inside the image, nothing in
   front of it): one ray from the eye. */
static int voxgi__camera_sees(const voxgi__ref *R, const double p[3], uint32_t prim, int front, uint64_t *rays)
{
    const voxgi_camera *cam = &R->desc->camera;
    double d[3], z = 0, x = 0, y = 0;
    voxgi__hit h;
    int a;
    for (a = 0; a < 3; a++) {
        d[a] = p[a] - R->eye[a];
        z += d[a] * R->forward[a];
        x += d[a] * R->right[a];
        y += d[a] * R->up[a];
    }
    if (!(z > 0) || fabs(x / z) > R->tan_half * cam->width / cam->height || fabs(y / z) > R->tan_half) return 0;
    ++*rays;
    return voxgi__trace(R->tr, R->eye, d, DBL_MAX, UINT32_MAX, 0, &h) && h.prim == prim && h.front == front;
}

/* One path's radiance through the camera ray (o, d). */
static void voxgi__path(voxgi__ref *R, double o[3], double d[3], voxgi__rng *g, uint64_t *rays, double out[3])
{
    const voxgi__tracer *tr = R->tr;
    double T[3] = {1, 1, 1}, pdf_bsdf = 0; /* the density (per solid angle) of the bounce that led here */
    uint32_t skip = UINT32_MAX;
    int depth, a, bounces = R->desc->bounces;
    out[0] = out[1] = out[2] = 0;
    for (depth = 0;; depth++) {
        voxgi__hit h;
        double ns[3], e[3], t[3], b[3], r1, phi, lx, ly, lz;
        const voxgi_material *m;
        const double *n;
        ++*rays;
        if (!voxgi__trace(tr, o, d, DBL_MAX, skip, 0, &h)) break;
        m = voxgi__prim_material(tr, h.prim);
        n = tr->n + 3 * (size_t)h.prim;
        for (a = 0; a < 3; a++) ns[a] = h.front ? n[a] : -n[a];
        if (h.front && R->lights.emitter_pdf[h.prim] > 0) { /* seen by the camera, or found by a bounce (weighted against the direct light) */
            double mis = depth == 0 && R->desc->hide_emitters ? 0 : 1;
            if (depth > 0) {
                double pdf_light = R->lights.emitter_pdf[h.prim] * h.t * h.t / -(d[0] * n[0] + d[1] * n[1] + d[2] * n[2]);
                mis = pdf_bsdf * pdf_bsdf / (pdf_bsdf * pdf_bsdf + pdf_light * pdf_light);
            }
            for (a = 0; a < 3; a++) out[a] += T[a] * mis * m->emission[a];
        }
        if (bounces >= 0 && depth > bounces) break; /* this vertex only closed the last bounce's emission */
        voxgi__direct(&R->lights, h.p, ns, h.prim, g, 1, NULL, rays, e, NULL);
        if (depth == 1 && R->desc->screen_light_only && !voxgi__camera_sees(R, h.p, h.prim, h.front, rays)) e[0] = e[1] = e[2] = 0;
        for (a = 0; a < 3; a++) out[a] += T[a] * m->albedo[a] / VOXGI__PI * e[a];
        for (a = 0; a < 3; a++) T[a] *= m->albedo[a]; /* cosine sampling: albedo/pi x cos / pdf = albedo */
        if (bounces < 0 && depth >= 2) { /* Russian roulette */
            double q = VOXGI__MAX(T[0], VOXGI__MAX(T[1], T[2]));
            if (q < 1) {
                if (voxgi__rng_unit(g) >= q) break;
                for (a = 0; a < 3; a++) T[a] /= q;
            }
        }
        if (T[0] == 0 && T[1] == 0 && T[2] == 0) break;
        voxgi__basis(ns, t, b);
        r1 = voxgi__rng_unit(g);
        phi = 2 * VOXGI__PI * voxgi__rng_unit(g);
        lx = sqrt(r1) * cos(phi);
        ly = sqrt(r1) * sin(phi);
        lz = sqrt(1 - r1);
        for (a = 0; a < 3; a++) d[a] = lx * t[a] + ly * b[a] + lz * ns[a];
        voxgi__leave(tr, h.p, ns, o);
        pdf_bsdf = lz / VOXGI__PI;
        skip = h.prim;
    }
}

/* The AO mode's sample through the camera ray (o, d): 1 (in all three channels) when a
   cosine-distributed ray from the surface meets any surface within ao_radius. */
static void voxgi__occlusion(voxgi__ref *R, const double o[3], const double d[3], voxgi__rng *g, uint64_t *rays, double out[3])
{
    voxgi__hit h, any;
    double ns[3], t[3], b[3], dir[3], from[3], r1 = voxgi__rng_unit(g), phi = 2 * VOXGI__PI * voxgi__rng_unit(g);
    int a;
    out[0] = out[1] = out[2] = 0;
    ++*rays;
    if (!voxgi__trace(R->tr, o, d, DBL_MAX, UINT32_MAX, 0, &h)) return;
    for (a = 0; a < 3; a++) ns[a] = h.front ? R->tr->n[3 * (size_t)h.prim + (size_t)a] : -R->tr->n[3 * (size_t)h.prim + (size_t)a];
    voxgi__basis(ns, t, b);
    for (a = 0; a < 3; a++) dir[a] = sqrt(r1) * cos(phi) * t[a] + sqrt(r1) * sin(phi) * b[a] + sqrt(1 - r1) * ns[a];
    voxgi__leave(R->tr, h.p, ns, from);
    ++*rays;
    if (voxgi__trace(R->tr, from, dir, (double)R->desc->ao_radius, h.prim, 1, &any)) out[0] = out[1] = out[2] = 1;
}

static void voxgi__ref_rows(void *user, size_t first, size_t end)
{
    voxgi__ref *R = (voxgi__ref *)user;
    const voxgi_camera *cam = &R->desc->camera;
    uint64_t rays = 0;
    size_t y;
    for (y = first; y < end; y++) {
        int x, s;
        for (x = 0; x < cam->width; x++) {
            size_t pix = y * (size_t)cam->width + (size_t)x;
            double *acc = R->sum + 3 * pix;
            for (s = R->first_sample; s < R->first_sample + R->pass_samples; s++) {
                voxgi__rng g;
                double sx, sy, o[3], d[3], L[3];
                int a;
                voxgi__rng_seed(&g, R->desc->seed, pix, (uint64_t)s);
                sx = x + voxgi__rng_unit(&g);
                sy = (double)y + voxgi__rng_unit(&g);
                voxgi__camera_ray(cam, R->forward, R->right, R->up, R->tan_half, sx, sy, d);
                for (a = 0; a < 3; a++) o[a] = R->eye[a];
                if (R->desc->ao_radius > 0) voxgi__occlusion(R, o, d, &g, &rays, L);
                else voxgi__path(R, o, d, &g, &rays, L);
                for (a = 0; a < 3; a++) acc[a] += L[a];
            }
        }
    }
    VOXGI__ATOMIC_ADD_SIZE(&R->rays, (size_t)rays);
}

/* The image of the resolved desc into rgb through the tracer tr of the scene (its lights built
   here), progressively: 1/16 of the samples per pass, each pass reported to the progress
   callback, which may cancel; *rays: the rays cast. */
static voxgi_result voxgi__reference_trace(voxgi_context *ctx, const voxgi__tracer *tr, const voxgi_scene *scene, const voxgi__ref_desc *desc, float *rgb,
                                           uint64_t *rays)
{
    voxgi__ref R;
    const voxgi_camera *cam = &desc->camera;
    size_t pixels = (size_t)cam->width * (size_t)cam->height, i;
    int samples = desc->samples;
    voxgi_result r;
    memset(&R, 0, sizeof R);
    if ((r = voxgi__camera_frame(ctx, cam, R.eye, R.forward, R.right, R.up, &R.tan_half)) != VOXGI_OK) return r;
    R.ctx = ctx;
    R.tr = tr;
    R.desc = desc;
    R.sum = (double *)voxgi__alloc_array(ctx, pixels, 3 * sizeof(double), 1);
    if (!R.sum) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for a %d x %d render", cam->width, cam->height);
    r = voxgi__lights_build(ctx, scene, tr, &R.lights);
    for (R.first_sample = 0; r == VOXGI_OK && R.first_sample < samples; R.first_sample += R.pass_samples) { /* progressive passes */
        R.pass_samples = VOXGI__MIN(VOXGI__MAX(1, samples / 16), samples - R.first_sample);
        voxgi__parallel(ctx, (size_t)cam->height, 1, voxgi__ref_rows, &R);
        if (voxgi__progress(ctx, (double)(R.first_sample + R.pass_samples) / samples, "reference render"))
            r = voxgi__fail(ctx, VOXGI_ERR_CANCELLED, "reference render cancelled by the progress callback after %d samples per pixel",
                            R.first_sample + R.pass_samples);
    }
    for (i = 0; r == VOXGI_OK && i < 3 * pixels; i++) rgb[i] = (float)(R.sum[i] / samples);
    *rays += R.rays;
    voxgi__free(ctx, R.sum);
    voxgi__lights_free(ctx, &R.lights);
    return r;
}
#endif /* VOXGI_NO_REFERENCE */

/* ===================================================================== 14. planner and images */

/* ----- the planner: what a scene holds, and the items each method's row plans from it */

static const char *const voxgi__render_method_names[VOXGI_RENDER_METHOD_COUNT] = {"reference", "vct",  "tsm",    "rsm",      "sh",
                                                                                   "ssao",      "vao", "ssgi", "hybrid", "linespace"};
static const char *const voxgi__plan_item_names[VOXGI_PLAN_ITEM_COUNT] = {
    "albedo", "normal", "emission", "opacity", "lights", "voxels", "radiance volume", "radiance octree", "shadow maps", "transmittance layers",
    "reflective shadow maps", "SH volume", "line space", "voxelization", "light injection", "bounces", "cones", "gathers", "screen bounce",
    "occlusion", "soft shadows", "path tracing", "direct light", "seen emission"};

static double voxgi__plan_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void voxgi__plan_add(voxgi_plan_info *P, voxgi_plan_item_id id, int kept, const char *why, uint64_t bytes, int estimated)
{
    voxgi_plan_item *it;
    VOXGI_ASSERT(P->item_count < VOXGI_PLAN_MAX_ITEMS);
    it = &P->items[P->item_count++];
    it->id = id;
    it->name = voxgi__plan_item_names[id];
    it->kind = id < VOXGI_PLAN_VOXELS ? VOXGI_PLAN_CHANNEL : id < VOXGI_PLAN_VOXELIZATION ? VOXGI_PLAN_STRUCTURE : VOXGI_PLAN_PASS;
    it->kept = kept;
    it->why = why;
    it->bytes = kept ? bytes : 0;
    it->estimated = estimated;
    P->bytes += it->bytes;
}

/* Whether a triangle (its front face toward the eye) may lie in the camera's view: not when all
   three corners are behind the eye or beyond one side of the frustum (conservative). */
static int voxgi__plan_in_view(const double v[9], const double eye[3], const double fw[3], const double rt[3], const double up[3], double tan_y,
                               double tan_x)
{
    int k, out[5] = {0, 0, 0, 0, 0};
    for (k = 0; k < 3; k++) {
        double p[3], x, y, z;
        int a;
        for (a = 0; a < 3; a++) p[a] = v[3 * k + a] - eye[a];
        x = voxgi__plan_dot(p, rt);
        y = voxgi__plan_dot(p, up);
        z = voxgi__plan_dot(p, fw);
        out[0] += z <= 0;
        out[1] += x > z * tan_x;
        out[2] += -x > z * tan_x;
        out[3] += y > z * tan_y;
        out[4] += -y > z * tan_y;
    }
    for (k = 0; k < 5; k++)
        if (out[k] == 3) return 0;
    return 1;
}

/* The view of a scene whose camera is left zero: the bounds' centre from in front (-Z) and a
   little above, at 3.2 times the largest half extent, 40 degrees. */
static void voxgi__plan_fit_camera(const double lo[3], const double hi[3], voxgi_camera *cam)
{
    double c[3], r = 0;
    int a;
    for (a = 0; a < 3; a++) {
        c[a] = 0.5 * (lo[a] + hi[a]);
        r = VOXGI__MAX(r, 0.5 * (hi[a] - lo[a]));
    }
    cam->eye[0] = c[0];
    cam->eye[1] = c[1] + 0.6 * r;
    cam->eye[2] = c[2] - 3.2 * r;
    memcpy(cam->target, c, sizeof c);
    if (!(cam->fovy_degrees > 0)) cam->fovy_degrees = 40;
}

/* What the scene holds: triangles by material, lights by type, its surface; *crossing: the sum of
   area x (|nx| + |ny| + |nz|), the number of cells of edge 1 a surface crosses; *extent: the
   bounds' longest side; *absorptions: the distinct 1 - transparency of translucent triangles (a
   transmittance map's layers). A camera left zero (eye = target) is fitted to the bounds first;
   then whether it sees an emitter. */
static voxgi_result voxgi__plan_scene(voxgi_context *ctx, const voxgi_scene *scene, voxgi_camera *cam, voxgi_plan_info *P, double *crossing,
                                      double *extent, int *absorptions)
{
    float sigma[VOXGI__TSM_MAX_MATERIALS];
    double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
    voxgi__flat f;
#ifndef VOXGI_NO_LINE_SPACE
    voxgi__ls_area *A;
#endif
    double eye[3], fw[3], rt[3], up[3], tan_y = 0, tan_x = 0;
    size_t t, i;
    int pass;
    voxgi_result r;
    *crossing = 0;
    *absorptions = 0;
    if ((r = voxgi__flatten(ctx, scene, 0, 1, &f)) != VOXGI_OK) return r;
    P->triangles = f.triangle_count;
    for (pass = 0; pass < 2 && r == VOXGI_OK; pass++) { /* the scene, then what the camera sees of its emitters */
        if (pass) { /* the view, fitted to the bounds if left zero */
            if (!memcmp(cam->eye, cam->target, sizeof cam->eye) && f.triangle_count) voxgi__plan_fit_camera(lo, hi, cam);
            if ((r = voxgi__camera_frame(ctx, cam, eye, fw, rt, up, &tan_y)) != VOXGI_OK) break;
            tan_x = tan_y * cam->width / cam->height;
        }
        for (t = 0; t < f.triangle_count; t++) {
            const voxgi_material *m = voxgi__tri_material(&f, t);
            double v[9], e1[3], e2[3], n[3], area2, to[3];
            int a, emits = m->emission[0] > 0 || m->emission[1] > 0 || m->emission[2] > 0;
            if (pass && (!emits || P->emitters_in_view)) continue;
            for (a = 0; a < 9; a++) v[a] = f.pos[3 * (size_t)f.tri[3 * t + (size_t)(a / 3)] + (size_t)(a % 3)];
            for (a = 0; a < 3; a++) { e1[a] = v[3 + a] - v[a]; e2[a] = v[6 + a] - v[a]; }
            n[0] = e1[1] * e2[2] - e1[2] * e2[1];
            n[1] = e1[2] * e2[0] - e1[0] * e2[2];
            n[2] = e1[0] * e2[1] - e1[1] * e2[0];
            area2 = sqrt(voxgi__plan_dot(n, n));
            if (pass) {
                for (a = 0; a < 3; a++) to[a] = eye[a] - v[a];
                P->emitters_in_view = area2 > 0 && voxgi__plan_dot(n, to) > 0 && voxgi__plan_in_view(v, eye, fw, rt, up, tan_y, tan_x);
                continue;
            }
            for (a = 0; a < 9; a++) {
                lo[a % 3] = VOXGI__MIN(lo[a % 3], v[a]);
                hi[a % 3] = VOXGI__MAX(hi[a % 3], v[a]);
            }
            P->surface_area += 0.5 * area2;
            P->reflective_triangles += m->albedo[0] > 0 || m->albedo[1] > 0 || m->albedo[2] > 0;
            P->translucent_triangles += m->transparency > 0;
            if (m->transparency > 0 && m->transparency < 1 && *absorptions < VOXGI__TSM_MAX_MATERIALS) {
                for (a = 0; a < *absorptions && sigma[a] != 1 - m->transparency; a++) continue;
                if (a == *absorptions) sigma[(*absorptions)++] = 1 - m->transparency;
            }
            P->emissive_triangles += emits && area2 > 0;
            *crossing += 0.5 * (fabs(n[0]) + fabs(n[1]) + fabs(n[2])); /* a plane of area A crosses about A (|nx| + |ny| + |nz|) unit cells */
        }
    }
    *extent = 0;
    for (i = 0; i < 3 && f.triangle_count; i++) *extent = VOXGI__MAX(*extent, hi[i] - lo[i]);
    for (i = 0; i < scene->light_count; i++) {
        voxgi_light_type ty = scene->lights[i].type;
        P->point_lights += ty == VOXGI_LIGHT_POINT;
        P->spot_lights += ty == VOXGI_LIGHT_SPOT;
        P->directional_lights += ty == VOXGI_LIGHT_DIRECTIONAL;
        P->rect_lights += ty == VOXGI_LIGHT_RECT;
    }
#ifndef VOXGI_NO_LINE_SPACE
    A = r == VOXGI_OK ? (voxgi__ls_area *)voxgi__alloc_array(ctx, VOXGI__LS_AREA_LIGHTS, sizeof *A, 0) : NULL;
    if (r == VOXGI_OK && (!A || (P->area_lights = voxgi__ls_area_lights(ctx, scene, &f, A)) == -2)) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the planner");
    voxgi__free(ctx, A);
#else
    P->area_lights = P->rect_lights + (int)VOXGI__MIN(P->emissive_triangles, (uint64_t)64); /* without the line space's pairing */
#endif
    voxgi__flat_free(ctx, &f);
    return r;
}

VOXGI_API const voxgi_plan_item *voxgi_plan_find(const voxgi_plan_info *plan, voxgi_plan_item_id id)
{
    int i;
    for (i = 0; plan && i < plan->item_count; i++)
        if (plan->items[i].id == id) return &plan->items[i];
    return NULL;
}

/* What a method's plan reads: the settings asked for and resolved, the scene's counts in P, and
   what the scene has (each true with VOXGI_PLAN_EVERYTHING). A method's plan adds its items to P
   and resolves the defaults that depend on the scene. */
typedef struct voxgi__plan_job {
    voxgi_context *ctx;
    const voxgi_render_desc *asked;
    voxgi_render_desc *d;         /* the settings, resolved */
    voxgi_plan_info *P;
    unsigned flags;
    int all, lit, reflective, seen, gi, absorptions;
    const char *no_gi;            /* why there is no indirect light, when gi is 0 */
    double crossing, extent;      /* the scene's surface crossing a unit square, and its longest side */
    uint64_t budget;              /* the plan's memory budget (0: none) */
} voxgi__plan_job;

/* snprintf's rules over a running buffer. */
static void voxgi__describe(char *buf, size_t size, int *len, const char *fmt, ...)
{
    va_list ap;
    int n;
    va_start(ap, fmt);
    n = vsnprintf(*len >= 0 && (size_t)*len < size ? buf + *len : NULL, *len >= 0 && (size_t)*len < size ? size - (size_t)*len : 0, fmt, ap);
    va_end(ap);
    if (n > 0) *len += n;
}


/* ----- the G-buffer of voxgi's own images */
typedef struct voxgi__gbuffer_job {
    const voxgi__tracer *tr;
    const voxgi_camera *cam;
    double eye[3], forward[3], right[3], up[3], tan_half;
    float *pos, *nrm;
    uint32_t *tri;                /* UINT32_MAX: none */
} voxgi__gbuffer_job;

static void voxgi__gbuffer_cpu(void *user, size_t first, size_t end)
{
    voxgi__gbuffer_job *J = (voxgi__gbuffer_job *)user;
    size_t y;
    for (y = first; y < end; y++) {
        int x, a;
        for (x = 0; x < J->cam->width; x++) {
            size_t pix = y * (size_t)J->cam->width + (size_t)x;
            voxgi__hit h;
            double d[3];
            voxgi__camera_ray(J->cam, J->forward, J->right, J->up, J->tan_half, x + 0.5, (double)y + 0.5, d);
            J->tri[pix] = UINT32_MAX;
            for (a = 0; a < 3; a++) J->pos[3 * pix + (size_t)a] = J->nrm[3 * pix + (size_t)a] = 0;
            if (!voxgi__trace(J->tr, J->eye, d, DBL_MAX, UINT32_MAX, 0, &h)) continue;
            J->tri[pix] = h.prim;
            for (a = 0; a < 3; a++) {
                double n = J->tr->n[3 * (size_t)h.prim + (size_t)a];
                J->pos[3 * pix + (size_t)a] = (float)h.p[a];
                J->nrm[3 * pix + (size_t)a] = (float)(h.front ? n : -n);
            }
        }
    }
}

#ifndef VOXGI_NO_GL
/* The same rasterized (shaders/gbuffer.glsl): corners relative to the eye, a 32-bit float depth
   test, rows flipped to come from the top. */
static voxgi_result voxgi__gbuffer_gl(voxgi_context *ctx, voxgi__gbuffer_job *J)
{
    voxgi__gl *gl = ctx->gl;
    const voxgi__tracer *tr = J->tr;
    size_t nt = tr->flat.triangle_count, i, pixels = (size_t)J->cam->width * (size_t)J->cam->height;
    int w = J->cam->width, h = J->cam->height, a, depth_func = 0, depth_mask = 0, y;
    unsigned int tex[4] = {0, 0, 0, 0}, bufs[2], fbo = 0, vao = 0, p;
    const unsigned int draw[3] = {VOXGI__GL_COLOR_ATTACHMENT0, VOXGI__GL_COLOR_ATTACHMENT0 + 1, VOXGI__GL_COLOR_ATTACHMENT0 + 2};
    const float zeros[4] = {0, 0, 0, 0}, one = 1;
    const unsigned int none = UINT32_MAX;
    double far_d = 0;
    float *buf;
    voxgi__gl_raster_state state;
    voxgi_result r = voxgi__gl_get_program(ctx, VOXGI__GL_PROGRAM_gbuffer);
    if (r != VOXGI_OK) return r;
    if (!(buf = (float *)voxgi__alloc_array(ctx, VOXGI__MAX(pixels, 3 * nt) + 1, 16, 0)))
        return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for a %d x %d G-buffer", w, h);
    for (i = 0; i < 9 * nt; i++) {
        buf[4 * (i / 3) + i % 3] = (float)(tr->v[i] - J->eye[i % 3]);
        far_d = VOXGI__MAX(far_d, fabs(tr->v[i] - J->eye[i % 3]));
    }
    bufs[0] = voxgi__gl_buffer(ctx, 3 * nt * 16, buf);
    for (i = 0; i < 3 * nt; i++) buf[4 * (i / 3) + i % 3] = (float)tr->n[i];
    bufs[1] = voxgi__gl_buffer(ctx, nt * 16, buf);
    gl->CreateTextures(VOXGI__GL_TEXTURE_2D, 4, tex);
    gl->TextureStorage2D(tex[0], 1, VOXGI__GL_RGBA32F, w, h);
    gl->TextureStorage2D(tex[1], 1, VOXGI__GL_RGBA32F, w, h);
    gl->TextureStorage2D(tex[2], 1, VOXGI__GL_R32UI, w, h);
    gl->TextureStorage2D(tex[3], 1, VOXGI__GL_DEPTH_COMPONENT32F, w, h);
    gl->ClearTexImage(tex[0], 0, VOXGI__GL_RGBA, VOXGI__GL_FLOAT, zeros);
    gl->ClearTexImage(tex[1], 0, VOXGI__GL_RGBA, VOXGI__GL_FLOAT, zeros);
    gl->ClearTexImage(tex[2], 0, VOXGI__GL_RED_INTEGER, VOXGI__GL_UNSIGNED_INT, &none);
    gl->ClearTexImage(tex[3], 0, VOXGI__GL_DEPTH_COMPONENT, VOXGI__GL_FLOAT, &one);
    gl->CreateFramebuffers(1, &fbo);
    for (a = 0; a < 3; a++) gl->NamedFramebufferTexture(fbo, VOXGI__GL_COLOR_ATTACHMENT0 + (unsigned)a, tex[a], 0);
    gl->NamedFramebufferTexture(fbo, VOXGI__GL_DEPTH_ATTACHMENT, tex[3], 0);
    gl->NamedFramebufferDrawBuffers(fbo, 3, draw);
    if (gl->CheckNamedFramebufferStatus(fbo, VOXGI__GL_FRAMEBUFFER) != VOXGI__GL_FRAMEBUFFER_COMPLETE)
        r = voxgi__fail(ctx, VOXGI_ERR_GL, "the G-buffer framebuffer is incomplete");
    if (r == VOXGI_OK) {
        p = gl->prog_gbuffer;
        voxgi__gl_raster_begin(gl, &state);
        gl->GetIntegerv(VOXGI__GL_DEPTH_FUNC, &depth_func);
        gl->GetIntegerv(VOXGI__GL_DEPTH_WRITEMASK, &depth_mask);
        gl->Enable(VOXGI__GL_DEPTH_TEST);
        gl->DepthFunc(VOXGI__GL_LESS);
        gl->DepthMask(1);
        gl->CreateVertexArrays(1, &vao);
        gl->BindFramebuffer(VOXGI__GL_FRAMEBUFFER, fbo);
        gl->BindVertexArray(vao);
        gl->Viewport(0, 0, w, h);
        gl->UseProgram(p);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 0, bufs[0]);
        gl->BindBufferBase(VOXGI__GL_SHADER_STORAGE_BUFFER, 1, bufs[1]);
        gl->ProgramUniform3f(p, VOXGI__LOC_u_right, (float)J->right[0], (float)J->right[1], (float)J->right[2]);
        gl->ProgramUniform3f(p, VOXGI__LOC_u_up, (float)J->up[0], (float)J->up[1], (float)J->up[2]);
        gl->ProgramUniform3f(p, VOXGI__LOC_u_forward, (float)J->forward[0], (float)J->forward[1], (float)J->forward[2]);
        gl->ProgramUniform2f(p, VOXGI__LOC_u_tan, (float)(J->tan_half * w / h), (float)J->tan_half);
        gl->ProgramUniform1f(p, VOXGI__LOC_u_near, (float)(1e-4 * VOXGI__MAX(far_d, 1e-30)));
        gl->ProgramUniform1f(p, VOXGI__LOC_u_far, (float)(2 * VOXGI__MAX(far_d, 1e-30)));
        gl->DrawArrays(VOXGI__GL_TRIANGLES, 0, (int)(3 * nt));
        gl->BindFramebuffer(VOXGI__GL_FRAMEBUFFER, 0);
        gl->BindVertexArray(0);
        gl->DeleteVertexArrays(1, &vao);
        gl->DepthFunc((unsigned)depth_func);
        gl->DepthMask((unsigned char)depth_mask);
        gl->Disable(VOXGI__GL_DEPTH_TEST);
        voxgi__gl_raster_end(gl, &state);
        gl->MemoryBarrier(VOXGI__GL_TEXTURE_UPDATE_BARRIER_BIT);
        gl->GetTextureSubImage(tex[0], 0, 0, 0, 0, w, h, 1, VOXGI__GL_RGBA, VOXGI__GL_FLOAT, (int)(pixels * 16), buf);
        for (y = 0; y < h; y++) /* GL's rows come from the bottom */
            for (i = 0; i < (size_t)w; i++)
                for (a = 0; a < 3; a++) J->pos[3 * ((size_t)y * w + i) + (size_t)a] = (float)(buf[4 * ((size_t)(h - 1 - y) * w + i) + (size_t)a] + J->eye[a]);
        gl->GetTextureSubImage(tex[1], 0, 0, 0, 0, w, h, 1, VOXGI__GL_RGBA, VOXGI__GL_FLOAT, (int)(pixels * 16), buf);
        for (y = 0; y < h; y++)
            for (i = 0; i < (size_t)w; i++)
                for (a = 0; a < 3; a++) J->nrm[3 * ((size_t)y * w + i) + (size_t)a] = buf[4 * ((size_t)(h - 1 - y) * w + i) + (size_t)a];
        gl->GetTextureSubImage(tex[2], 0, 0, 0, 0, w, h, 1, VOXGI__GL_RED_INTEGER, VOXGI__GL_UNSIGNED_INT, (int)(pixels * 4), buf);
        for (y = 0; y < h; y++)
            for (i = 0; i < (size_t)w; i++) {
                size_t k = (size_t)y * w + i;
                memcpy(&J->tri[k], (const uint32_t *)buf + (size_t)(h - 1 - y) * w + i, 4);
                if (J->tri[k] == UINT32_MAX) for (a = 0; a < 3; a++) J->pos[3 * k + (size_t)a] = 0;
            }
        r = voxgi__gl_check(ctx, "the G-buffer");
    }
    gl->DeleteFramebuffers(1, &fbo);
    gl->DeleteTextures(4, tex);
    voxgi__gl_delete_buffer(ctx, bufs[0]);
    voxgi__gl_delete_buffer(ctx, bufs[1]);
    voxgi__gl_unbind(gl);
    voxgi__free(ctx, buf);
    return r;
}
#endif

/* The G-buffer on the context's backend. */
static voxgi_result voxgi__gbuffer(voxgi_context *ctx, const voxgi__tracer *tr, const voxgi_camera *cam, float *pos, float *nrm, uint32_t *tri)
{
    voxgi__gbuffer_job J;
    voxgi_result r;
    memset(&J, 0, sizeof J);
    if ((r = voxgi__camera_frame(ctx, cam, J.eye, J.forward, J.right, J.up, &J.tan_half)) != VOXGI_OK) return r;
    J.tr = tr;
    J.cam = cam;
    J.pos = pos;
    J.nrm = nrm;
    J.tri = tri;
#ifndef VOXGI_NO_GL
    if (ctx->backend == VOXGI_BACKEND_GL) return voxgi__gbuffer_gl(ctx, &J);
#endif
    voxgi__parallel(ctx, (size_t)cam->height, 1, voxgi__gbuffer_cpu, &J);
    return VOXGI_OK;
}

VOXGI_API voxgi_result voxgi_gbuffer_render(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_camera *camera, float *positions, float *normals,
                                            uint32_t *triangles)
{
    voxgi__tracer tr;
    float *pos = NULL, *nrm = NULL;
    uint32_t *tri = NULL;
    size_t pixels;
    voxgi_result r;
    double e[3], f[3], rt[3], u[3], t;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!camera) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "camera is NULL");
    if ((r = voxgi__camera_frame(ctx, camera, e, f, rt, u, &t)) != VOXGI_OK) return r;
    if ((r = voxgi__validate(ctx, scene, NULL, NULL)) != VOXGI_OK) return r;
    if ((r = voxgi__tracer_build(ctx, scene, &tr)) != VOXGI_OK) return r;
    pixels = (size_t)camera->width * (size_t)camera->height;
    pos = (float *)voxgi__alloc_array(ctx, pixels, 12, 0);
    nrm = (float *)voxgi__alloc_array(ctx, pixels, 12, 0);
    tri = (uint32_t *)voxgi__alloc_array(ctx, pixels, 4, 0);
    if (!pos || !nrm || !tri) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for a %lu-pixel G-buffer", (unsigned long)pixels);
    if (r == VOXGI_OK) r = voxgi__gbuffer(ctx, &tr, camera, pos, nrm, tri);
    if (r == VOXGI_OK) {
        if (positions) memcpy(positions, pos, pixels * 12);
        if (normals) memcpy(normals, nrm, pixels * 12);
        if (triangles) memcpy(triangles, tri, pixels * 4);
    }
    voxgi__free(ctx, pos);
    voxgi__free(ctx, nrm);
    voxgi__free(ctx, tri);
    voxgi__tracer_free(ctx, &tr);
    return r;
}

/* ----- one image, any method: the rows of voxgi_render's table

   A row makes its method's image in two steps over one voxgi__image: build, what the method
   takes from the scene (its ray scene and lights, the voxels, the radiance, maps, a line space),
   then gather, what the camera's pixels take from that (the G-buffer, the method's gathers, the
   direct light). What both made is freed by voxgi__image_free, also after an error. Every row
   reads the resolved desc and follows its plan: an item the plan leaves out is not made. */
typedef struct voxgi__image {
    voxgi_context *ctx;
    const voxgi_scene *scene;
    const voxgi_render_desc *d;   /* every default resolved */
    const voxgi_plan_info *plan;
    voxgi_render_info *info;
    float *rgb;
    int gi;                       /* the plan keeps the method's indirect light */
    size_t pixels;
    voxgi__tracer tr;
    voxgi__lights Ls;             /* the lights the rays sample (TSM: those without a map) */
    int have_tr, have_ls;
    float *pos, *nrm, *irr;       /* the G-buffer (the pixel centres' surfaces) and the indirect irradiance there, 3 per pixel */
    uint32_t *prim;               /* the G-buffer's triangles (UINT32_MAX: none) */
    unsigned char *want;          /* the pixels that gather */
    voxgi_grid grid;              /* the method's grid (its voxel size: the interpolation's plane distance) */
    const voxgi_voxels *vox;      /* its voxels, made (vox_owned) or kept (desc.voxels) */
    voxgi_voxels *vox_owned;
    voxgi__occupancy O;           /* their occupancy, for visibility */
    int have_occ;
    voxgi_volume *volume;         /* VCT: the radiance; HYBRID: the hidden light */
    voxgi_svo *octree;            /* VCT: the radiance in an octree */
    voxgi_tsm **tsm;              /* TSM: per scene light its map, or NULL */
    voxgi_light *map_less;        /* TSM: the lights without a map, */
    voxgi_scene map_less_scene;   /* and the scene with those alone (I->Ls points into it) */
    voxgi_rsm **rsm;              /* RSM: the maps made */
    size_t rsm_count;
    voxgi_sh *sh;
    float *reflected;             /* SSGI, HYBRID: the direct light the pixels' surfaces reflect */
    void *areas;                  /* LINESPACE: the area lights (voxgi__ls_area) */
    int lights;
    voxgi_linespace *ls_built;
} voxgi__image;

#if defined(VOXGI__DIRECT_LIGHT) || !defined(VOXGI_NO_LINE_SPACE) /* some method makes images */
/* A stage of the image done: its name and the time since t0. */
static void voxgi__image_stage(voxgi__image *I, const char *name, double t0)
{
    voxgi_render_info *f = I->info;
    VOXGI_ASSERT(f->stage_count < VOXGI_RENDER_MAX_STAGES);
    f->stages[f->stage_count].name = name;
    f->stages[f->stage_count++].ms = voxgi__now_ms() - t0;
}

static int voxgi__image_kept(const voxgi__image *I, voxgi_plan_item_id id)
{
    const voxgi_plan_item *it = voxgi_plan_find(I->plan, id);
    return it && it->kept;
}

/* The ray scene (the caller's kept one, or built) and, with `lights`, the scene's lights. */
static voxgi_result voxgi__image_rays(voxgi__image *I, int lights)
{
    voxgi_result r;
    if ((r = voxgi__tracer_build_with(I->ctx, I->scene, I->d->rays, &I->tr)) != VOXGI_OK) return r;
    I->have_tr = 1;
#ifdef VOXGI__DIRECT_LIGHT
    if (lights && (r = voxgi__lights_build(I->ctx, I->scene, &I->tr, &I->Ls)) == VOXGI_OK) I->have_ls = 1;
#else
    (void)lights;
#endif
    return r;
}

/* The G-buffer of the view (k x k points per pixel: k times the size) and the arrays the gathers fill. */
static voxgi_result voxgi__image_gbuffer(voxgi__image *I, int k)
{
    voxgi_camera cam = I->d->camera;
    size_t n;
    cam.width *= k;
    cam.height *= k;
    n = (size_t)cam.width * (size_t)cam.height;
    I->pos = (float *)voxgi__alloc_array(I->ctx, n, 12, 0);
    I->nrm = (float *)voxgi__alloc_array(I->ctx, n, 12, 0);
    I->irr = (float *)voxgi__alloc_array(I->ctx, n, 12, 1);
    I->prim = (uint32_t *)voxgi__alloc_array(I->ctx, n, 4, 0);
    I->want = (unsigned char *)voxgi__alloc_array(I->ctx, n, 1, 1);
    if (!I->pos || !I->nrm || !I->irr || !I->prim || !I->want) return voxgi__fail(I->ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for a %d x %d G-buffer", cam.width, cam.height);
    return voxgi__gbuffer(I->ctx, &I->tr, &cam, I->pos, I->nrm, I->prim);
}

/* The method's grid (d->resolution voxels along the longest side, `padding` voxels around) and,
   with `voxels`, its conservative voxels holding `attributes` and their occupancy (with OR mipmaps:
   `hierarchical`): the stage "voxels". */
static voxgi_result voxgi__image_voxels(voxgi__image *I, int padding, int voxels, int hierarchical, unsigned attributes)
{
    voxgi_voxelize_desc vd;
    voxgi_fit_desc fit;
    double t0 = voxgi__now_ms();
    voxgi_result r;
    memset(&vd, 0, sizeof vd);
    memset(&fit, 0, sizeof fit);
    fit.res = I->d->resolution;
    fit.padding = padding;
    if ((r = voxgi_fit_grid(I->ctx, I->scene, &fit, &I->grid)) != VOXGI_OK || !voxels) return r;
    vd.grid = I->grid;
    vd.attributes = attributes;
    if ((r = voxgi_voxelize(I->ctx, I->scene, &vd, &I->vox_owned)) == VOXGI_OK && (r = voxgi__occ_build(I->ctx, I->vox_owned, hierarchical, &I->O)) == VOXGI_OK)
        I->have_occ = 1;
    I->vox = I->vox_owned;
    voxgi__image_stage(I, "voxels", t0);
    I->info->bytes += (I->vox ? I->vox->info.bytes : 0) + (I->have_occ ? voxgi__occ_bytes(&I->O) : 0);
    return r;
}

#endif

static void voxgi__image_free(voxgi__image *I)
{
    voxgi_context *ctx = I->ctx;
    size_t i;
    if (I->have_occ) voxgi__occ_free(ctx, &I->O);
    if (I->vox_owned) voxgi_voxels_destroy(ctx, I->vox_owned);
    voxgi_volume_destroy(ctx, I->volume);
#ifndef VOXGI_NO_OCTREE
    voxgi_svo_destroy(ctx, I->octree);
#endif
#ifndef VOXGI_NO_LIGHT_SPACE
    for (i = 0; I->tsm && i < I->scene->light_count; i++) voxgi_tsm_destroy(ctx, I->tsm[i]);
    for (i = 0; i < I->rsm_count; i++) voxgi_rsm_destroy(ctx, I->rsm[i]);
    voxgi_sh_destroy(ctx, I->sh);
#endif
#ifndef VOXGI_NO_LINE_SPACE
    voxgi_linespace_destroy(ctx, I->ls_built);
#endif
    (void)i;
    voxgi__free(ctx, I->tsm);
    voxgi__free(ctx, I->map_less);
    voxgi__free(ctx, I->rsm);
    voxgi__free(ctx, I->reflected);
    voxgi__free(ctx, I->areas);
    voxgi__free(ctx, I->pos);
    voxgi__free(ctx, I->nrm);
    voxgi__free(ctx, I->irr);
    voxgi__free(ctx, I->prim);
    voxgi__free(ctx, I->want);
#ifdef VOXGI__DIRECT_LIGHT
    if (I->have_ls) voxgi__lights_free(ctx, &I->Ls);
#endif
    if (I->have_tr) voxgi__tracer_free(ctx, &I->tr);
}

/* ----- the reference: path tracing (part 13) */
#ifndef VOXGI_NO_REFERENCE
static voxgi_result voxgi__reference_defaults(voxgi_context *ctx, const voxgi_render_desc *in, voxgi_render_desc *d)
{
    d->reference = in->reference;
    if (!(d->reference.ao_radius >= 0 && isfinite(d->reference.ao_radius)) || (d->reference.screen_light_only && d->bounces != 1))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "reference: ao_radius %g, screen_light_only %d (with one bounce only)", (double)d->reference.ao_radius,
                           d->reference.screen_light_only);
    return VOXGI_OK;
}

static void voxgi__reference_plan(voxgi__plan_job *J)
{
    int ao = J->d->reference.ao_radius > 0;
    voxgi__plan_add(J->P, VOXGI_PLAN_PATH_TRACING, ao || J->lit, ao ? "ambient occlusion within the radius" : J->lit ? "the lights' and emitters' light along paths" : "no light and no emitter",
                    0, 0);
}

static void voxgi__reference_describe(const voxgi_render_desc *u, char *buf, size_t size, int *len)
{
    if (u->reference.ao_radius > 0) voxgi__describe(buf, size, len, ", ambient occlusion within %.4g", (double)u->reference.ao_radius);
    else if (u->reference.screen_light_only) voxgi__describe(buf, size, len, ", screen light only");
}

static voxgi_result voxgi__reference_image_build(voxgi__image *I)
{
    double t0 = voxgi__now_ms();
    voxgi_result r = voxgi__image_rays(I, 0);
    voxgi__image_stage(I, "bvh", t0);
    if (r == VOXGI_OK) {
        I->info->triangles = I->tr.flat.triangle_count;
        I->info->bvh_nodes = I->tr.rs->node_count;
    }
    return r;
}

static voxgi_result voxgi__reference_image_gather(voxgi__image *I)
{
    voxgi__ref_desc rd;
    double t0 = voxgi__now_ms();
    voxgi_result r;
    memset(&rd, 0, sizeof rd);
    rd.camera = I->d->camera;
    rd.samples = I->d->samples;
    rd.bounces = I->d->bounces;
    rd.seed = I->d->seed;
    rd.hide_emitters = I->d->hide_emitters;
    rd.ao_radius = I->d->reference.ao_radius;
    rd.screen_light_only = I->d->reference.screen_light_only;
    r = voxgi__reference_trace(I->ctx, &I->tr, I->scene, &rd, I->rgb, &I->info->rays);
    voxgi__image_stage(I, "render", t0);
    return r;
}
#endif

#if (!defined(VOXGI_NO_CONE_TRACING) && !defined(VOXGI_NO_LIGHT_INJECTION)) || !defined(VOXGI_NO_LIGHT_SPACE) /* their gather strides */
/* Anchors and the pixels between (cone tracing's and the reflective shadow maps' gathers at a
   stride s > 1): the anchors are every s-th pixel across and down and the last row and column
   (want[i] = 1 where such a pixel has a surface). */
static void voxgi__anchors(int w, int h, int stride, const uint32_t *prim, unsigned char *want)
{
    size_t i, pixels = (size_t)w * (size_t)h;
    for (i = 0; i < pixels; i++) {
        int x = (int)(i % (size_t)w), y = (int)(i / (size_t)w);
        want[i] = prim[i] != UINT32_MAX && (stride == 1 || ((x % stride == 0 || x == w - 1) && (y % stride == 0 || y == h - 1)));
    }
}

/* Every other pixel with a surface: the bilinear mean of the irradiance of the anchors around it
   (want: 1 at the anchors, on return 1 where a pixel needs its own gather) that share its
   surface (normals within 26 degrees, within `plane` of its plane), renormalized over them. With
   `strict` (Buchacher 2014's rule), only where at least three of the four share it (all of them
   on an anchor's row or column); else wherever one with weight does. */
static void voxgi__between_anchors(int w, int h, int stride, const float *pos, const float *nrm, const uint32_t *prim, double plane, int strict, float *irr,
                                   unsigned char *want)
{
    size_t i, pixels = (size_t)w * (size_t)h;
    for (i = 0; i < pixels; i++) {
        int x = (int)(i % (size_t)w), y = (int)(i / (size_t)w), x0 = x / stride * stride, y0 = y / stride * stride, k, a, weighted = 0, shared = 0;
        int xs[2], ys[2];
        double sum = 0, e[3] = {0, 0, 0};
        if (want[i] || prim[i] == UINT32_MAX) { want[i] = 0; continue; }
        xs[0] = x0; xs[1] = VOXGI__MIN(x0 + stride, w - 1);
        ys[0] = y0; ys[1] = VOXGI__MIN(y0 + stride, h - 1);
        for (k = 0; k < 4; k++) {
            size_t c = (size_t)ys[k >> 1] * (size_t)w + (size_t)xs[k & 1];
            double wx = xs[1] > xs[0] ? (double)(x - xs[0]) / (xs[1] - xs[0]) : 0, wy = ys[1] > ys[0] ? (double)(y - ys[0]) / (ys[1] - ys[0]) : 0;
            double wt = ((k & 1) ? wx : 1 - wx) * ((k >> 1) ? wy : 1 - wy), dn = 0, dp = 0;
            if (wt <= 0) continue;
            weighted++;
            if (prim[c] == UINT32_MAX) continue;
            for (a = 0; a < 3; a++) {
                dn += (double)nrm[3 * c + (size_t)a] * nrm[3 * i + (size_t)a];
                dp += ((double)pos[3 * c + (size_t)a] - pos[3 * i + (size_t)a]) * nrm[3 * i + (size_t)a];
            }
            if (dn < 0.9 || fabs(dp) > plane) continue; /* another surface: not its light */
            shared++;
            sum += wt;
            for (a = 0; a < 3; a++) e[a] += wt * irr[3 * c + (size_t)a];
        }
        if (sum > 1e-3 && (!strict || shared >= VOXGI__MIN(3, weighted))) for (a = 0; a < 3; a++) irr[3 * i + (size_t)a] = (float)(e[a] / sum);
        else want[i] = 1; /* too few anchors share its surface: its own gather */
    }
}
#endif

/* ----- cone-traced images */
#if !defined(VOXGI_NO_CONE_TRACING) && !defined(VOXGI_NO_LIGHT_INJECTION)
/* The cone tracer's Pareto front on the Cornell box (256 x 256 against a 1024-spp reference,
   anisotropic mips, step 0.5; docs/planner.md): the cheapest settings reaching each error. The
   middle one is the default. */
static const struct { double error; int resolution, cones, stride; } voxgi__plan_vct_front[] = {
    {0.0805, 64, 32, 6}, {0.0776, 96, 24, 6}, {0.0755, 96, 32, 6}};
#define VOXGI__PLAN_VCT_DEFAULT 1

/* The front's cheapest setting reaching a relative RMSE (0: the default; the closest where none does). */
static size_t voxgi__plan_vct_pick(double error)
{
    size_t f, n = sizeof voxgi__plan_vct_front / sizeof voxgi__plan_vct_front[0];
    if (!(error > 0)) return VOXGI__PLAN_VCT_DEFAULT;
    for (f = 0; f + 1 < n && voxgi__plan_vct_front[f].error > error; f++) continue;
    return f;
}

/* An octree of two-sided radiance per set voxel (measured: 8.0 MB for the Cornell box's 56,562
   voxels at 96^3, nodes and values). */
#define VOXGI__PLAN_OCTREE_BYTES_PER_VOXEL 148

/* The front's middle, or the cheapest point of it reaching the error asked for. */
static voxgi_result voxgi__vct_defaults(voxgi_context *ctx, const voxgi_render_desc *in, voxgi_render_desc *d)
{
    size_t f = voxgi__plan_vct_pick(d->error);
    voxgi_render_vct *v = &d->vct;
    *v = in->vct;
    if ((d->bounces > 1 || d->bounces < 0) && !v->bounce_block) v->bounce_block = 4; /* voxgi__inject_defaults' */
    if ((d->bounces > 1 || d->bounces < 0) && !v->bounce_cones.cones) v->bounce_cones.cones = 4;
    if ((unsigned)v->radiance > VOXGI_VCT_OCTREE || (unsigned)v->octree_format > VOXGI_SVO_FLOAT16 || v->cone_stride < 0 || v->cone_stride > 64 ||
        v->inject_samples < 0 || v->bounce_block < 0 || v->cones.cones < 0)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "vct: radiance %d, octree_format %d, cone_stride %d (0..64), inject_samples %d, bounce_block %d, cones %d",
                           (int)v->radiance, (int)v->octree_format, v->cone_stride, v->inject_samples, v->bounce_block, v->cones.cones);
#ifdef VOXGI_NO_OCTREE
    if (v->radiance == VOXGI_VCT_OCTREE) return voxgi__fail(ctx, VOXGI_ERR_UNSUPPORTED, "vct: an octree of the radiance, but the octree is left out (VOXGI_NO_OCTREE)");
#endif
    if (!d->resolution) d->resolution = voxgi__plan_vct_front[f].resolution;
    if (!v->cones.cones) v->cones.cones = voxgi__plan_vct_front[f].cones;
    if (!v->cone_stride) v->cone_stride = voxgi__plan_vct_front[f].stride;
    if (!v->inject_samples) v->inject_samples = ctx->backend == VOXGI_BACKEND_GL && !v->shadow_rays ? 16 : 4;
    return VOXGI_OK;
}

/* The voxels and what they hold, the radiance's store (the octree where the dense volume is over
   the budget and the octree within it), the bounces among the voxels, the cones. */
static void voxgi__vct_plan(voxgi__plan_job *J)
{
    voxgi_render_desc *d = J->d;
    voxgi_plan_info *P = J->P;
    const char *no_gi = J->no_gi;
    int gi = J->gi, all = J->all, bounces = gi && (all || d->bounces > 1 || d->bounces == -1), octree;
    uint64_t grid_bytes = voxgi_grid_voxel_count(&P->grid) / 8 + 4, dense, octree_bytes;
    voxgi_volume vol;
    if (d->error > 0) {
        P->expected_error = voxgi__plan_vct_front[voxgi__plan_vct_pick(d->error)].error;
        P->error_reachable = P->expected_error <= d->error;
    }
    memset(&vol, 0, sizeof vol);
    vol.info.filter = d->vct.radiance == VOXGI_VCT_ISOTROPIC || d->vct.radiance == VOXGI_VCT_OCTREE ? VOXGI_MIPS_ISOTROPIC : VOXGI_MIPS_ANISOTROPIC;
    vol.info.attributes = VOXGI_ATTRIBUTE_RADIANCE | (d->vct.one_sided ? 0u : VOXGI_ATTRIBUTE_RADIANCE_BACK | VOXGI_ATTRIBUTE_RADIANCE_SIDE);
    voxgi__volume_levels(&vol, &P->grid, 0);
    dense = voxgi__volume_bytes(&vol, J->ctx->backend == VOXGI_BACKEND_GL) + (d->vct.one_sided ? 0u : (uint64_t)vol.voxels * 4u);
    octree_bytes = P->voxels * VOXGI__PLAN_OCTREE_BYTES_PER_VOXEL;
#ifndef VOXGI_NO_OCTREE
    if (d->vct.radiance == VOXGI_VCT_RADIANCE_DEFAULT)
        d->vct.radiance = J->budget && dense > J->budget && octree_bytes <= J->budget ? VOXGI_VCT_OCTREE : VOXGI_VCT_ANISOTROPIC;
#else
    if (d->vct.radiance == VOXGI_VCT_RADIANCE_DEFAULT) d->vct.radiance = VOXGI_VCT_ANISOTROPIC;
#endif
    octree = d->vct.radiance == VOXGI_VCT_OCTREE;
    if (!octree) d->vct.octree_format = VOXGI_SVO_FLOAT32, d->vct.octree_bricks = 0;
    if (d->bounces >= 0 && d->bounces <= 1) memset(&d->vct.bounce_cones, 0, sizeof d->vct.bounce_cones), d->vct.bounce_block = 0;
    voxgi__plan_add(P, VOXGI_PLAN_ALBEDO, gi, gi ? "what the voxels reflect" : no_gi, P->voxels * 28, 1);
    voxgi__plan_add(P, VOXGI_PLAN_NORMAL, gi, gi ? "the voxels' light and mips face it" : no_gi, P->voxels * 24 + grid_bytes, 1);
    voxgi__plan_add(P, VOXGI_PLAN_EMISSION, all, all ? "everything asked for" : P->emissive_triangles ? "emitters light the voxels as area lights and the pixels directly" : "no emissive material",
                    P->voxels * 28, 1);
    voxgi__plan_add(P, VOXGI_PLAN_OPACITY, all, all ? "everything asked for" : P->translucent_triangles ? "the cone tracer's voxels are opaque" : "no translucent material", P->voxels * 12, 1);
    voxgi__plan_add(P, VOXGI_PLAN_VOXELS, gi, gi ? "conservative, the scene's surface" : no_gi, grid_bytes, 0);
    voxgi__plan_add(P, VOXGI_PLAN_VOXELIZATION, gi && !d->voxels,
                    !gi ? no_gi : d->voxels ? "the voxels kept (desc.voxels): the light only is re-injected" : (J->flags & VOXGI_PLAN_DYNAMIC) ? "the geometry moves: every frame"
                    : "a static scene: once (a change of lights re-injects only)", 0, 0);
    voxgi__plan_add(P, VOXGI_PLAN_LIGHT_INJECTION, gi, gi ? "the direct light into the voxels" : no_gi, 0, 0);
    voxgi__plan_add(P, VOXGI_PLAN_BOUNCES, bounces, bounces ? "light among the voxels before the cones" : !gi ? no_gi : "one bounce: the cones at the pixels", 0, 0);
    voxgi__plan_add(P, VOXGI_PLAN_RADIANCE_VOLUME, gi && !octree, !gi ? no_gi : !octree ? "within the budget" : J->asked->vct.radiance == VOXGI_VCT_OCTREE ? "the octree asked for"
                    : "over the memory budget: the octree", dense, 0);
    voxgi__plan_add(P, VOXGI_PLAN_RADIANCE_OCTREE, gi && octree, !gi ? no_gi : !octree ? "the dense volume fits the budget (and its anisotropic mips are better)"
                    : J->asked->vct.radiance == VOXGI_VCT_OCTREE ? "asked for" : "the dense volume is over the memory budget", octree_bytes, 1);
    voxgi__plan_add(P, VOXGI_PLAN_CONES, gi, gi ? "the indirect light at the pixels" : no_gi, 0, 0);
    voxgi__plan_add(P, VOXGI_PLAN_DIRECT_LIGHT, J->lit, J->lit ? "shadow rays to the lights and emitters" : "no light and no emitter", 0, 0);
}

static void voxgi__vct_describe(const voxgi_render_desc *u, char *buf, size_t size, int *len)
{
    static const char *const radiance[] = {"default", "anisotropic volume", "isotropic volume", "octree"}, *const formats[] = {"float32", "float16"};
    const voxgi_render_vct *v = &u->vct;
    voxgi__describe(buf, size, len, ", radiance %s, cones %d, cone stride %d, inject samples %d", radiance[(unsigned)v->radiance % 4u], v->cones.cones, v->cone_stride,
                    v->inject_samples);
    if (v->radiance == VOXGI_VCT_OCTREE) voxgi__describe(buf, size, len, " (%s%s)", formats[(unsigned)v->octree_format % 2u], v->octree_bricks ? ", bricks" : "");
    if (u->bounces > 1 || u->bounces == -1) voxgi__describe(buf, size, len, ", bounce cones %d, bounce block %d", v->bounce_cones.cones, v->bounce_block);
    if (v->one_sided) voxgi__describe(buf, size, len, ", one-sided");
    if (v->sampled_direct) voxgi__describe(buf, size, len, ", sampled direct light");
}

typedef struct voxgi__vct_job {
    const voxgi_render_desc *d;
    int gi;                       /* the cones' indirect light */
    const voxgi__tracer *tr;
    const voxgi__lights *lights;
    double eye[3], forward[3], right[3], up[3], tan_half;
    float *pos, *nrm, *irr;       /* per pixel: the centre ray's surface and the cones' irradiance there */
    uint32_t *prim;               /* per pixel: that surface's triangle (UINT32_MAX: none) */
    float *rgb;
    size_t rays;
    int analytic;                 /* the rect lights and emitters analytically, shadowed by the rays' visible share */
    double voxel_size;            /* world units: how far off its plane a neighbour's surface may lie and still be it */
} voxgi__vct_job;

/* The cones' irradiance for a ray through pixel (x, y) at sub-pixel (sx, sy) that met surface (p, n):
   the nearest of the 3 x 3 pixels whose centre's surface is that one (normal within 26 degrees, on
   its plane within a voxel), so that a pixel across an edge takes each side's light in proportion;
   the pixel's own where none is. */
static const float *voxgi__vct_ray_irradiance(const voxgi__vct_job *J, int x, int y, double sx, double sy, const double p[3], const double n[3])
{
    const voxgi_camera *cam = &J->d->camera;
    const float *best = J->irr + 3 * ((size_t)y * (size_t)cam->width + (size_t)x);
    double best_d = DBL_MAX;
    int dx, dy, a;
    for (dy = -1; dy <= 1; dy++)
        for (dx = -1; dx <= 1; dx++) {
            int xx = x + dx, yy = y + dy;
            size_t c;
            double dn = 0, dp = 0, d2;
            if (xx < 0 || yy < 0 || xx >= cam->width || yy >= cam->height) continue;
            c = (size_t)yy * (size_t)cam->width + (size_t)xx;
            if (J->prim[c] == UINT32_MAX) continue;
            for (a = 0; a < 3; a++) {
                dn += (double)J->nrm[3 * c + (size_t)a] * n[a];
                dp += ((double)J->pos[3 * c + (size_t)a] - p[a]) * n[a];
            }
            if (dn < 0.9 || fabs(dp) > J->voxel_size) continue;
            d2 = (xx + 0.5 - sx) * (xx + 0.5 - sx) + (yy + 0.5 - sy) * (yy + 0.5 - sy);
            if (d2 < best_d) { best_d = d2; best = J->irr + 3 * c; }
        }
    return best;
}

static void voxgi__vct_shade(void *user, size_t first, size_t end)
{
    voxgi__vct_job *J = (voxgi__vct_job *)user;
    const voxgi_camera *cam = &J->d->camera;
    int samples = J->d->samples;
    uint64_t rays = 0;
    size_t y;
    for (y = first; y < end; y++) {
        int x, s, a;
        for (x = 0; x < cam->width; x++) {
            size_t pix = y * (size_t)cam->width + (size_t)x;
            double L[3] = {0, 0, 0}, shadowed[3] = {0, 0, 0}, unshadowed[3] = {0, 0, 0}, exact[3] = {0, 0, 0}; /* area lights, albedo / pi x E */
            double indirect[3] = {0, 0, 0}; /* albedo / pi x the cones' irradiance, per ray */
            double rot[4], centre[3] = {0, 0, 0}; /* the exact unshadowed light at the pixel centre's surface */
            int used = 0, uniform = 1, lit = -1; /* uniform: every ray so far met the centre's triangle, with all or none of the lights */
            voxgi__rng g;
            voxgi__rng_seed(&g, J->d->seed, pix, 0);
            for (a = 0; a < 4; a++) rot[a] = voxgi__rng_unit(&g);
            if (J->analytic && J->prim[pix] != UINT32_MAX) {
                double p[3], n[3];
                for (a = 0; a < 3; a++) { p[a] = J->pos[3 * pix + (size_t)a]; n[a] = J->nrm[3 * pix + (size_t)a]; }
                voxgi__area_irradiance(J->lights, p, n, J->prim[pix], centre);
            }
            for (s = 0; s < samples; s++) { /* emission and direct light over the pixel's square */
                voxgi__hit h;
                double d[3], ns[3], e[3], u[4], area[8] = {0, 0, 0, 0, 0, 0, 0, 0}, ea[3];
                const voxgi_material *m;
                if (J->analytic && uniform && s >= 4 && s == samples / 2) break; /* the first half agree: one surface, lit alike; the exact light needs no more */
                voxgi__kronecker(4, s, rot, u); /* stratified over the pixel's square x the light, shifted per pixel */
                voxgi__camera_ray(cam, J->forward, J->right, J->up, J->tan_half, x + u[0], (double)y + u[1], d);
                ++rays;
                ++used;
                if (!voxgi__trace(J->tr, J->eye, d, DBL_MAX, UINT32_MAX, 0, &h)) { uniform = 0; continue; }
                m = voxgi__prim_material(J->tr, h.prim);
                for (a = 0; a < 3; a++) ns[a] = h.front ? J->tr->n[3 * (size_t)h.prim + (size_t)a] : -J->tr->n[3 * (size_t)h.prim + (size_t)a];
                voxgi__leave(J->tr, h.p, ns, h.p); /* off the surface: a light in its plane shines on it or not by no rounding */
                voxgi__direct(J->lights, h.p, ns, h.prim, &g, 0, u + 2, &rays, e, J->analytic ? area : NULL);
                if (J->analytic && h.prim == J->prim[pix]) memcpy(ea, centre, sizeof ea); /* the same surface: smooth across a pixel */
                else if (J->analytic) voxgi__area_irradiance(J->lights, h.p, ns, h.prim, ea);
                if (h.prim != J->prim[pix] || (area[7] > 0 && area[7] < area[6]) || (lit >= 0 && lit != (area[7] == 0))) uniform = 0;
                lit = area[7] == 0;
                if (J->gi) {
                    const float *irr = h.prim == J->prim[pix] ? J->irr + 3 * pix : voxgi__vct_ray_irradiance(J, x, (int)y, x + u[0], (double)y + u[1], h.p, ns);
                    for (a = 0; a < 3; a++) indirect[a] += m->albedo[a] / VOXGI__PI * irr[a];
                }
                for (a = 0; a < 3; a++) {
                    double k = m->albedo[a] / VOXGI__PI;
                    L[a] += (h.front && !J->d->hide_emitters ? m->emission[a] : 0) + k * (e[a] - area[a]);
                    shadowed[a] += k * area[a];
                    unshadowed[a] += k * area[3 + a];
                    if (J->analytic) exact[a] += k * ea[a];
                }
            }
            for (a = 0; a < 3; a++)
                L[a] = (L[a] + indirect[a] + (J->analytic && unshadowed[a] > 0 ? exact[a] * (shadowed[a] / unshadowed[a]) : shadowed[a])) / VOXGI__MAX(used, 1);
            for (a = 0; a < 3; a++) J->rgb[3 * pix + (size_t)a] = (float)L[a];
        }
    }
    VOXGI__ATOMIC_ADD_SIZE(&J->rays, (size_t)rays);
}

/* The cones' irradiance at the pixels flagged in want, into J->irr (a packed copy is traced);
   *traced: how many. */
static voxgi_result voxgi__vct_trace_pixels(voxgi_context *ctx, const voxgi_radiance_source *source, const voxgi_cone_desc *cd,
                                            const voxgi__vct_job *J, size_t pixels, const unsigned char *want, size_t *traced)
{
    size_t i, n = 0;
    float *pos, *nrm, *irr;
    voxgi_cone_desc seen = *cd; /* the pixels' surfaces are seen from the eye */
    voxgi_result r = VOXGI_OK;
    seen.seen_from_eye = 1;
    memcpy(seen.eye, J->eye, sizeof seen.eye);
    for (i = 0; i < pixels; i++) n += want[i];
    *traced = n;
    if (!n) return VOXGI_OK;
    pos = (float *)voxgi__alloc_array(ctx, n, 12, 0);
    nrm = (float *)voxgi__alloc_array(ctx, n, 12, 0);
    irr = (float *)voxgi__alloc_array(ctx, n, 12, 0);
    if (!pos || !nrm || !irr) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu cone points", (unsigned long)n);
    for (i = 0, n = 0; r == VOXGI_OK && i < pixels; i++)
        if (want[i]) { memcpy(pos + 3 * n, J->pos + 3 * i, 12); memcpy(nrm + 3 * n, J->nrm + 3 * i, 12); n++; }
    if (r == VOXGI_OK) r = voxgi_cone_trace(ctx, source, &seen, n, pos, nrm, irr, NULL);
    for (i = 0, n = 0; r == VOXGI_OK && i < pixels; i++)
        if (want[i]) { memcpy(J->irr + 3 * i, irr + 3 * n, 12); n++; }
    voxgi__free(ctx, pos);
    voxgi__free(ctx, nrm);
    voxgi__free(ctx, irr);
    return r;
}

/* The cone tracer's voxels of the scene (resolved desc): its grid, fitted with a voxel of
   padding, albedo and normal. */
static voxgi_result voxgi__vct_voxelize(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_render_desc *d, voxgi_voxels **vox)
{
    voxgi_fit_desc fit;
    voxgi_voxelize_desc xd;
    voxgi_result r;
    memset(&fit, 0, sizeof fit);
    memset(&xd, 0, sizeof xd);
    fit.res = d->resolution;
    fit.padding = 1;
    xd.attributes = VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL;
    r = voxgi_fit_grid(ctx, scene, &fit, &xd.grid);
    if (r == VOXGI_OK) r = voxgi_voxelize(ctx, scene, &xd, vox);
    return r;
}

/* Whether d->voxels are what voxgi__vct_voxelize would make of the scene now. */
static voxgi_result voxgi__vct_check_voxels(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_render_desc *d)
{
    const voxgi_voxels_info *vi = &d->voxels->info;
    voxgi_fit_desc fit;
    voxgi_grid g;
    voxgi_result r;
    uint64_t triangles = 0;
    size_t m;
    memset(&fit, 0, sizeof fit);
    fit.res = d->resolution;
    fit.padding = 1;
    if ((r = voxgi_fit_grid(ctx, scene, &fit, &g)) != VOXGI_OK) return r;
    for (m = 0; m < scene->mesh_count; m++) triangles += voxgi__mesh_triangles(&scene->meshes[m]);
    if (vi->backend != ctx->backend || vi->method != VOXGI_METHOD_CONSERVATIVE || (vi->attributes & (VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL)) !=
        (VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "desc.voxels: not from voxgi_render_voxelize on this context");
    if (memcmp(g.origin, vi->grid.origin, sizeof g.origin) != 0 || g.voxel_size != vi->grid.voxel_size || memcmp(g.res, vi->grid.res, sizeof g.res) != 0 ||
        triangles != vi->triangle_count)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "desc.voxels: made for other geometry or another resolution (%d x %d x %d voxels of %g, %lu triangles; "
                           "this image's grid is %d x %d x %d of %g, %lu triangles)", vi->grid.res[0], vi->grid.res[1], vi->grid.res[2], vi->grid.voxel_size,
                           (unsigned long)vi->triangle_count, g.res[0], g.res[1], g.res[2], g.voxel_size, (unsigned long)triangles);
    return VOXGI_OK;
}

/* The cones' irradiance at every pixel's surface (J->irr), or with a cone stride s > 1 at the
   anchors (voxgi__anchors), the pixels between interpolated (voxgi__between_anchors, not strict)
   or tracing their own where no anchor shares their surface. */
static voxgi_result voxgi__vct_cones(voxgi_context *ctx, const voxgi_render_desc *d, voxgi__vct_job *J, const voxgi_radiance_source *source,
                                     double voxel_size, size_t *traced)
{
    int w = d->camera.width, h = d->camera.height, stride = d->vct.cone_stride;
    size_t pixels = (size_t)w * (size_t)h, n = 0, more = 0;
    unsigned char *want = (unsigned char *)voxgi__alloc_array(ctx, pixels, 1, 1);
    voxgi_result r = VOXGI_OK;
    if (!want) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory");
    voxgi__anchors(w, h, stride, J->prim, want);
    r = voxgi__vct_trace_pixels(ctx, source, &d->vct.cones, J, pixels, want, &n);
    if (r == VOXGI_OK && stride > 1) {
        voxgi__between_anchors(w, h, stride, J->pos, J->nrm, J->prim, voxel_size, 0, J->irr, want);
        r = voxgi__vct_trace_pixels(ctx, source, &d->vct.cones, J, pixels, want, &more);
    }
    *traced = n + more;
    voxgi__free(ctx, want);
    return r;
}

/* The radiance the cones gather: the scene's voxels (made, or the caller's kept ones), the
   direct light injected (emission left out: the pixels take it from the direct light) and
   bounced, in a volume, moved into an octree where the desc says so. */
static voxgi_result voxgi__vct_image_build(voxgi__image *I)
{
    voxgi_context *ctx = I->ctx;
    const voxgi_render_desc *d = I->d;
    voxgi_inject_desc id;
    double t0;
    voxgi_result r;
    I->gi = voxgi__image_kept(I, VOXGI_PLAN_CONES);
    if (d->voxels && (r = voxgi__vct_check_voxels(ctx, I->scene, d)) != VOXGI_OK) return r;
    if ((r = voxgi__image_rays(I, 1)) != VOXGI_OK || !I->gi) return r;
    if (voxgi__cancelled(ctx, 0.0, "cone-traced image", "vct: voxelization")) return VOXGI_ERR_CANCELLED;
    t0 = voxgi__now_ms();
    if (d->voxels) I->vox = d->voxels;
    else if ((r = voxgi__vct_voxelize(ctx, I->scene, d, &I->vox_owned)) == VOXGI_OK) I->vox = I->vox_owned;
    voxgi__image_stage(I, "voxelize", t0);
    if (r == VOXGI_OK && voxgi__cancelled(ctx, 0.1, "cone-traced image", "vct: light injection")) r = VOXGI_ERR_CANCELLED;
    if (r != VOXGI_OK) return r;
    memset(&id, 0, sizeof id);
    id.volume.filter = d->vct.radiance == VOXGI_VCT_ANISOTROPIC ? VOXGI_MIPS_ANISOTROPIC : VOXGI_MIPS_ISOTROPIC;
    id.samples = d->vct.inject_samples;
    id.seed = d->seed;
    id.shadow_rays = d->vct.shadow_rays;
    id.bounces = d->bounces;
    id.gather = d->vct.bounce_cones;
    id.gather_block = d->vct.bounce_block;
    id.one_sided = d->vct.one_sided;
    I->info->voxels = I->vox->info.voxel_count;
    t0 = voxgi__now_ms();
    r = voxgi__inject_light(ctx, I->scene, I->vox, &id, &I->tr, &I->Ls, &I->volume); /* the image's tracer: one BVH build */
    voxgi__image_stage(I, "inject", t0);
    if (I->volume) {
        voxgi_volume_info vi;
        voxgi_volume_query(I->volume, &vi);
        I->info->bytes = vi.bytes;
    }
#ifndef VOXGI_NO_OCTREE
    if (r == VOXGI_OK && d->vct.radiance == VOXGI_VCT_OCTREE) { /* the radiance moves into an octree; the volume goes */
        voxgi_svo_desc sd;
        voxgi_svo_info si;
        memset(&sd, 0, sizeof sd);
        sd.attributes = VOXGI_ATTRIBUTE_RADIANCE;
        sd.radiance = I->volume;
        sd.format = d->vct.octree_format;
        sd.bricks = d->vct.octree_bricks;
        t0 = voxgi__now_ms();
        r = voxgi_svo_create(ctx, I->vox, &sd, &I->octree);
        voxgi__image_stage(I, "octree", t0);
        voxgi_volume_destroy(ctx, I->volume);
        I->volume = NULL;
        if (r == VOXGI_OK) { voxgi_svo_query(I->octree, &si); I->info->bytes = si.bytes; }
    }
#endif
    return r;
}

/* The G-buffer, the cones at its pixels, then per pixel emission + albedo / pi x (the direct light
   through exact shadow rays, `samples` rays stratified over the pixel and the light, + the cones'
   irradiance at the surface each ray met: the one gathered at the nearest of the 3 x 3 pixels whose
   centre lies on it, so that a pixel across an edge mixes its sides' indirect light as it mixes
   their direct light). */
static voxgi_result voxgi__vct_image_gather(voxgi__image *I)
{
    voxgi_context *ctx = I->ctx;
    voxgi__vct_job J;
    voxgi_radiance_source source;
    double t0;
    voxgi_result r;
    memset(&J, 0, sizeof J);
    if ((r = voxgi__camera_frame(ctx, &I->d->camera, J.eye, J.forward, J.right, J.up, &J.tan_half)) != VOXGI_OK) return r;
    if ((r = voxgi__image_gbuffer(I, 1)) != VOXGI_OK) return r;
    J.d = I->d;
    J.gi = I->gi;
    J.tr = &I->tr;
    J.lights = &I->Ls;
    J.rgb = I->rgb;
    J.analytic = !I->d->vct.sampled_direct && I->Ls.emitter_count <= VOXGI__ANALYTIC_EMITTERS;
    J.pos = I->pos;
    J.nrm = I->nrm;
    J.irr = I->irr;
    J.prim = I->prim;
    if (I->gi) {
        if (voxgi__cancelled(ctx, 0.4, "cone-traced image", "vct: cones")) return VOXGI_ERR_CANCELLED;
        memset(&source, 0, sizeof source);
        source.volume = I->volume;
        source.octree = I->octree;
        J.voxel_size = I->vox->info.grid.voxel_size;
        t0 = voxgi__now_ms();
        r = voxgi__vct_cones(ctx, I->d, &J, &source, J.voxel_size, &I->info->gathered);
        voxgi__image_stage(I, "cones", t0);
        if (r != VOXGI_OK) return r;
    }
    if (voxgi__cancelled(ctx, 0.8, "cone-traced image", "vct: direct light")) return VOXGI_ERR_CANCELLED;
    t0 = voxgi__now_ms();
    voxgi__parallel(ctx, (size_t)I->d->camera.height, 1, voxgi__vct_shade, &J);
    voxgi__image_stage(I, "direct", t0);
    return voxgi__cancelled(ctx, 1.0, "cone-traced image", "vct: done") ? VOXGI_ERR_CANCELLED : VOXGI_OK;
}

#endif

/* ----- images of the direct light (with transmittance shadow maps, and under one-bounce ones) */
#if !defined(VOXGI_NO_LIGHT_SPACE) || !defined(VOXGI_NO_SCREEN_SPACE)
typedef struct voxgi__direct_image_job {
    const voxgi_camera *cam;
    int samples, hide_emitters;   /* camera rays per pixel (stratified, shifted per pixel by the seed) */
    uint64_t seed;
    const voxgi__tracer *tr;
    const voxgi__lights *others;  /* the lights through exact shadow rays, and the emitters */
#ifndef VOXGI_NO_LIGHT_SPACE
    voxgi_tsm **maps;             /* per scene light: its transmittance shadow map, or NULL (maps NULL: none) */
#endif
    const voxgi_scene *scene;
    double eye[3], forward[3], right[3], up[3], tan_half;
    float *rgb;
    float *reflected;             /* or NULL: the direct light the pixels' surfaces reflect, without their emission */
} voxgi__direct_image_job;

static void voxgi__direct_image_rows(void *user, size_t first, size_t end)
{
    const voxgi__direct_image_job *J = (const voxgi__direct_image_job *)user;
    const voxgi_camera *cam = J->cam;
    int samples = J->samples;
    size_t y;
#ifndef VOXGI_NO_LIGHT_SPACE
    size_t li;
#endif
    for (y = first; y < end; y++) {
        int x;
        for (x = 0; x < cam->width; x++) {
            size_t pix = y * (size_t)cam->width + (size_t)x;
            double sum[3] = {0, 0, 0}, emitted[3] = {0, 0, 0}, rot[2];
            uint64_t rays = 0;
            voxgi__rng g;
            int s, a;
            voxgi__rng_seed(&g, J->seed, pix, 0);
            rot[0] = voxgi__rng_unit(&g);
            rot[1] = voxgi__rng_unit(&g);
            for (s = 0; s < samples; s++) {
                voxgi__hit h;
                const voxgi_material *m;
                double d[3], ns[3], e[3], u[2];
                voxgi__kronecker(2, s, rot, u);
                voxgi__camera_ray(cam, J->forward, J->right, J->up, J->tan_half, x + u[0], (double)y + u[1], d);
                if (!voxgi__trace(J->tr, J->eye, d, DBL_MAX, UINT32_MAX, 0, &h)) continue;
                m = voxgi__prim_material(J->tr, h.prim);
                for (a = 0; a < 3; a++) ns[a] = h.front ? J->tr->n[3 * (size_t)h.prim + (size_t)a] : -J->tr->n[3 * (size_t)h.prim + (size_t)a];
                if (h.front && !J->hide_emitters) for (a = 0; a < 3; a++) emitted[a] += m->emission[a];
#ifndef VOXGI_NO_LIGHT_SPACE
                for (li = 0; J->maps && li < J->scene->light_count; li++) { /* the maps' lights */
                    const voxgi_tsm *T = J->maps[li];
                    const voxgi_light *L = &J->scene->lights[li];
                    double c, to[3], dist = 0;
                    if (!T) continue;
                    if (L->type == VOXGI_LIGHT_SPOT) { /* toward the light, its cone, the inverse square */
                        for (a = 0; a < 3; a++) { to[a] = L->position[a] - h.p[a]; dist += to[a] * to[a]; }
                        dist = sqrt(dist);
                        if (!(dist > 0)) continue;
                        for (a = 0; a < 3; a++) to[a] /= dist;
                        c = (ns[0] * to[0] + ns[1] * to[1] + ns[2] * to[2]) * voxgi__spot_share(L, to) / (dist * dist);
                    } else
                        c = -(ns[0] * T->view.w[0] + ns[1] * T->view.w[1] + ns[2] * T->view.w[2]);
                    if (c <= 0) continue;
                    c *= voxgi__tsm_point(T, h.p, ns);
                    for (a = 0; a < 3; a++) sum[a] += m->albedo[a] / VOXGI__PI * L->intensity[a] * c;
                }
#endif
                voxgi__leave(J->tr, h.p, ns, h.p); /* off the surface for the shadow rays */
                voxgi__direct(J->others, h.p, ns, h.prim, &g, 0, NULL, &rays, e, NULL);
                for (a = 0; a < 3; a++) sum[a] += m->albedo[a] / VOXGI__PI * e[a];
            }
            for (a = 0; a < 3; a++) {
                J->rgb[3 * pix + (size_t)a] = (float)((sum[a] + emitted[a]) / samples);
                if (J->reflected) J->reflected[3 * pix + (size_t)a] = (float)(sum[a] / samples);
            }
        }
    }
}

/* Job J's direct light into rgb (J's view and maps set by the caller; samples 0 = 4): its time. */
static double voxgi__direct_image(voxgi_context *ctx, voxgi__direct_image_job *J, const voxgi_camera *cam, int samples, int hide_emitters, uint64_t seed,
                                  const voxgi__tracer *tr, const voxgi__lights *others, const voxgi_scene *scene, float *rgb)
{
    double t0 = voxgi__now_ms();
    J->cam = cam;
    J->samples = samples ? samples : 4;
    J->hide_emitters = hide_emitters;
    J->seed = seed;
    J->tr = tr;
    J->others = others;
    J->scene = scene;
    J->rgb = rgb;
    voxgi__parallel(ctx, (size_t)cam->height, 1, voxgi__direct_image_rows, J);
    return voxgi__now_ms() - t0;
}

/* The bounce's light, albedo / pi x irradiance, added into rgb. */
static void voxgi__image_add_bounce(const voxgi__image *I)
{
    size_t p;
    for (p = 0; p < I->pixels; p++) {
        const voxgi_material *m;
        int a;
        if (I->prim[p] == UINT32_MAX) continue;
        m = voxgi__prim_material(&I->tr, I->prim[p]);
        for (a = 0; a < 3; a++) I->rgb[3 * p + (size_t)a] += (float)(m->albedo[a] / VOXGI__PI * I->irr[3 * p + (size_t)a]);
    }
}

/* The direct light through exact shadow rays to the image's lights (and with maps, theirs) into
   rgb, the light the surfaces reflect into reflected (if not NULL): the stage "direct". */
static void voxgi__image_direct(voxgi__image *I, voxgi_tsm **maps, float *reflected, const char *stage)
{
    voxgi__direct_image_job J;
    double t0 = voxgi__now_ms();
    memset(&J, 0, sizeof J);
    voxgi__camera_frame(I->ctx, &I->d->camera, J.eye, J.forward, J.right, J.up, &J.tan_half); /* checked by the planner */
#ifndef VOXGI_NO_LIGHT_SPACE
    J.maps = maps;
#else
    (void)maps;
#endif
    J.reflected = reflected;
    voxgi__direct_image(I->ctx, &J, &I->d->camera, I->d->samples, I->d->hide_emitters, I->d->seed, &I->tr, &I->Ls, I->scene, I->rgb);
    voxgi__image_stage(I, stage, t0);
}
#endif

#ifndef VOXGI_NO_LIGHT_SPACE
/* ----- images of the direct light with transmittance shadow maps: every directional and spot
   light through its own map, the other lights and emitters through exact shadow rays */
static voxgi_result voxgi__tsm_defaults(voxgi_context *ctx, const voxgi_render_desc *in, voxgi_render_desc *d)
{
    (void)ctx;
    d->tsm = in->tsm;
    return VOXGI_OK;
}

static void voxgi__tsm_plan(voxgi__plan_job *J)
{
    voxgi_plan_info *P = J->P;
    int maps = P->directional_lights + P->spot_lights, layers = maps ? J->absorptions : 0, size = J->d->tsm.maps.size ? J->d->tsm.maps.size : 512;
    uint64_t texels = (uint64_t)size * (uint64_t)size; /* 64 slices: 2 words a texel per absorption */
    voxgi__plan_add(P, VOXGI_PLAN_SHADOW_MAPS, maps > 0, maps ? "the directional and spot lights' opaque depth" : "no directional or spot light", (uint64_t)maps * texels * 4u, 0);
    voxgi__plan_add(P, VOXGI_PLAN_TRANSMITTANCE_LAYERS, J->all || layers > 0,
                    layers ? "light through translucent surfaces, a slicemap per absorption" : J->all ? "everything asked for" /* kept without a map or an absorption */
                    : !maps ? "no directional or spot light" : "no translucent material",
                    (uint64_t)maps * (uint64_t)layers * texels * 2u * 4u, 0);
    voxgi__plan_add(P, VOXGI_PLAN_DIRECT_LIGHT, J->lit, J->lit ? "shadow rays to the other lights and emitters" : "no light and no emitter", 0, 0);
}

static void voxgi__tsm_describe(const voxgi_render_desc *u, char *buf, size_t size, int *len)
{
    voxgi__describe(buf, size, len, ", map size %d, slices %d", u->tsm.maps.size ? u->tsm.maps.size : 512, u->tsm.maps.slices ? u->tsm.maps.slices : 64);
    if (u->tsm.maps.sigma > 0) voxgi__describe(buf, size, len, ", sigma %.4g", (double)u->tsm.maps.sigma);
}

static voxgi_result voxgi__tsm_image_build(voxgi__image *I)
{
    voxgi_context *ctx = I->ctx;
    const voxgi_scene *scene = I->scene;
    size_t li, n = 0, lc = scene->light_count ? scene->light_count : 1;
    double t0;
    voxgi_result r;
    if ((r = voxgi__image_rays(I, 0)) != VOXGI_OK) return r;
    I->tsm = (voxgi_tsm **)voxgi__alloc_array(ctx, lc, sizeof *I->tsm, 1);
    I->map_less = (voxgi_light *)voxgi__alloc_array(ctx, lc, sizeof *I->map_less, 0);
    if (!I->tsm || !I->map_less) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory");
    t0 = voxgi__now_ms();
    for (li = 0; r == VOXGI_OK && li < scene->light_count; li++) {
        voxgi_tsm_desc td = I->d->tsm.maps;
        if (scene->lights[li].type != VOXGI_LIGHT_DIRECTIONAL && scene->lights[li].type != VOXGI_LIGHT_SPOT) { I->map_less[n++] = scene->lights[li]; continue; }
        td.light = li;
        if ((r = voxgi_tsm_create(ctx, scene, &td, &I->tsm[li])) == VOXGI_OK) {
            I->info->maps++;
            I->info->bytes += I->tsm[li]->info.bytes;
        }
    }
    voxgi__image_stage(I, "maps", t0);
    I->map_less_scene = *scene;
    I->map_less_scene.lights = n ? I->map_less : NULL;
    I->map_less_scene.light_count = n;
    if (r == VOXGI_OK && (r = voxgi__lights_build(ctx, &I->map_less_scene, &I->tr, &I->Ls)) == VOXGI_OK) I->have_ls = 1;
    return r;
}

static voxgi_result voxgi__tsm_image_gather(voxgi__image *I)
{
    voxgi__image_direct(I, I->tsm, NULL, "shade");
    return VOXGI_OK;
}

/* ----- one-bounce images: the reflective shadow maps' and the SH volume's

   What both share: the direct light as the transmittance maps' image (exact shadow rays), the
   G-buffer, a grid of `resolution` voxels along the scene's longest side (its voxel size the
   interpolation's plane distance) and, unless visibility is none, the occupancy of its
   conservative voxels; the method's gather at the anchors of the gather stride and where
   interpolation fails; the bounce albedo / pi x irradiance added to the direct light. */
/* A one-bounce gather at the pixels marked in want: gather(user, count, points, normals, out)
   sets out (3 per point), added into irr (3 per pixel); their number added into *gathered. */
typedef voxgi_result (*voxgi__gather_fn)(voxgi_context *ctx, void *user, size_t count, const float *points, const float *normals, float *out);
static voxgi_result voxgi__gather_pixels(voxgi_context *ctx, size_t pixels, const float *pos, const float *nrm, const unsigned char *want, float *irr,
                                         size_t *gathered, voxgi__gather_fn gather, void *user)
{
    size_t count = 0, i, k;
    float *p, *q, *e;
    voxgi_result r = VOXGI_OK;
    for (i = 0; i < pixels; i++) count += want[i] != 0;
    *gathered += count;
    if (!count) return VOXGI_OK;
    p = (float *)voxgi__alloc_array(ctx, count, 12, 0);
    q = (float *)voxgi__alloc_array(ctx, count, 12, 0);
    e = (float *)voxgi__alloc_array(ctx, count, 12, 0);
    if (p && q && e) {
        for (i = k = 0; i < pixels; i++)
            if (want[i]) {
                memcpy(p + 3 * k, pos + 3 * i, 12);
                memcpy(q + 3 * k, nrm + 3 * i, 12);
                k++;
            }
        r = gather(ctx, user, count, p, q, e);
        for (i = k = 0; r == VOXGI_OK && i < pixels; i++)
            if (want[i]) {
                int a;
                for (a = 0; a < 3; a++) irr[3 * i + (size_t)a] += e[3 * k + (size_t)a];
                k++;
            }
    }
    voxgi__free(ctx, p);
    voxgi__free(ctx, q);
    voxgi__free(ctx, e);
    return p && q && e ? r : voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for %lu gathers", (unsigned long)count);
}

/* The direct light, the G-buffer, the gathers at the anchors, then at the pixels between that
   cannot be interpolated; the bounce added into rgb. */
static voxgi_result voxgi__image_bounce(voxgi__image *I, int stride, voxgi__gather_fn gather, void *user)
{
    const voxgi_camera *cam = &I->d->camera;
    double t0;
    voxgi_result r;
    voxgi__image_direct(I, NULL, NULL, "direct");
    if ((r = voxgi__image_gbuffer(I, 1)) != VOXGI_OK || !I->gi) return r;
    t0 = voxgi__now_ms();
    voxgi__anchors(cam->width, cam->height, stride, I->prim, I->want);
    r = voxgi__gather_pixels(I->ctx, I->pixels, I->pos, I->nrm, I->want, I->irr, &I->info->gathered, gather, user);
    if (r == VOXGI_OK && stride > 1) {
        voxgi__between_anchors(cam->width, cam->height, stride, I->pos, I->nrm, I->prim, I->grid.voxel_size, 1, I->irr, I->want);
        r = voxgi__gather_pixels(I->ctx, I->pixels, I->pos, I->nrm, I->want, I->irr, &I->info->gathered, gather, user);
    }
    if (r == VOXGI_OK) voxgi__image_add_bounce(I);
    voxgi__image_stage(I, "gather", t0);
    return r;
}

/* An image's bounce at its pixels through a gather at points (a voxgi__point_gather). */
static voxgi_result voxgi__image_point_gather(voxgi_context *ctx, void *user, size_t count, const float *points, const float *normals, float *out)
{
    voxgi__point_gather *G = (voxgi__point_gather *)user;
    G->points = points;
    G->normals = normals;
    G->irradiance = out;
    return voxgi__point_gather_run(ctx, G, count);
}

/* RSM and SH alike: a grid of 64 for the visibility, every 4th pixel gathering. */
static voxgi_result voxgi__bounce_defaults(voxgi_context *ctx, const voxgi_render_desc *in, voxgi_render_desc *d)
{
    int sh = d->method == VOXGI_RENDER_SH, *stride = sh ? &d->sh.gather_stride : &d->rsm.gather_stride;
    voxgi_traversal vis;
    if (sh) d->sh = in->sh;
    else d->rsm = in->rsm;
    vis = sh ? d->sh.visibility : d->rsm.visibility;
    if ((unsigned)vis > VOXGI_TRAVERSAL_NONE || *stride < 0 || *stride > 64 || (sh && (d->resolution > 1024 || !(d->sh.opening >= 0 && d->sh.opening <= 4))))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "%s: visibility %d, gather_stride %d (0..64), resolution %d%s, opening %g (0..4)", sh ? "sh" : "rsm", (int)vis,
                           *stride, d->resolution, sh ? " (0..1024)" : "", (double)d->sh.opening);
    if (!d->resolution) d->resolution = 64;
    if (!*stride) *stride = 4;
    if (sh && !(d->sh.opening > 0)) d->sh.opening = 0.5f;
    if (sh && !d->sh.volume.seed) d->sh.volume.seed = d->seed; /* the patterns from the image's seed */
    if (!sh && !d->rsm.maps.seed) d->rsm.maps.seed = d->seed;
    return VOXGI_OK;
}

static void voxgi__bounce_plan(voxgi__plan_job *J)
{
    voxgi_plan_info *P = J->P;
    const char *no_gi = J->no_gi;
    int sh = J->d->method == VOXGI_RENDER_SH, gi = J->gi, areas = P->rect_lights + (P->emissive_triangles > 0);
    int vis = (sh ? J->d->sh.visibility : J->d->rsm.visibility) != VOXGI_TRAVERSAL_NONE;
    uint64_t gb = voxgi_grid_voxel_count(&P->grid) / 8 + 4;
    if (!sh)
        voxgi__plan_add(P, VOXGI_PLAN_REFLECTIVE_SHADOW_MAPS, gi, gi ? "the lit surfaces' points" : no_gi,
                        (uint64_t)(P->directional_lights + P->spot_lights) * (256u * 256u * 36u + 100u * 12u) + (uint64_t)areas * (4u * 256u * 256u * 36u + 200u * 12u), 0);
    else
        voxgi__plan_add(P, VOXGI_PLAN_SH_VOLUME, gi, gi ? "the direct light's spherical harmonics" : no_gi, voxgi_grid_voxel_count(&P->grid) * 64u * 8u / 7u, 1);
    voxgi__plan_add(P, VOXGI_PLAN_VOXELS, gi && vis, !gi ? no_gi : vis ? "the bounce's visibility" : "visibility none asked for", gb, 0);
    voxgi__plan_add(P, VOXGI_PLAN_GATHERS, gi, gi ? "one bounce at the pixels" : no_gi, 0, 0);
    voxgi__plan_add(P, VOXGI_PLAN_DIRECT_LIGHT, J->lit, J->lit ? "shadow rays to the lights and emitters" : "no light and no emitter", 0, 0);
}

static void voxgi__bounce_describe(const voxgi_render_desc *u, char *buf, size_t size, int *len)
{
    static const char *const visibility[] = {"hierarchical", "dda", "none"};
    if (u->method == VOXGI_RENDER_RSM)
        voxgi__describe(buf, size, len, ", visibility %s, gather stride %d, map size %d", visibility[(unsigned)u->rsm.visibility % 3u], u->rsm.gather_stride,
                        u->rsm.maps.size ? u->rsm.maps.size : 256);
    else
        voxgi__describe(buf, size, len, ", visibility %s, gather stride %d, opening %.4g", visibility[(unsigned)u->sh.visibility % 3u], u->sh.gather_stride,
                        (double)u->sh.opening);
}

static voxgi_result voxgi__rsm_image_build(voxgi__image *I)
{
    const voxgi_render_rsm *q = &I->d->rsm;
    size_t li;
    double t0;
    voxgi_result r;
    I->gi = voxgi__image_kept(I, VOXGI_PLAN_GATHERS);
    if ((r = voxgi__image_rays(I, 1)) != VOXGI_OK) return r;
    if ((r = voxgi__image_voxels(I, 0, voxgi__image_kept(I, VOXGI_PLAN_VOXELS), q->visibility == VOXGI_TRAVERSAL_HIERARCHICAL, 0)) != VOXGI_OK || !I->gi) return r;
    if (!(I->rsm = (voxgi_rsm **)voxgi__alloc_array(I->ctx, I->scene->light_count + 1, sizeof *I->rsm, 1))) return voxgi__fail(I->ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory");
    t0 = voxgi__now_ms();
    for (li = 0; r == VOXGI_OK && li <= I->scene->light_count; li++) { /* each light's map, then the emitters' */
        voxgi_rsm_desc rd = q->maps;
        voxgi_rsm_info ri;
        if (li == I->scene->light_count ? !I->Ls.emitter_count : I->scene->lights[li].type == VOXGI_LIGHT_POINT) continue;
        rd.light = li;
        rd.emitters = li == I->scene->light_count;
        if ((r = voxgi_rsm_create(I->ctx, I->scene, &rd, &I->rsm[I->rsm_count])) != VOXGI_OK) break;
        voxgi_rsm_query(I->rsm[I->rsm_count++], &ri);
        I->info->maps += ri.maps;
        I->info->bytes += ri.bytes;
    }
    voxgi__image_stage(I, "maps", t0);
    return r;
}

static voxgi_result voxgi__rsm_image_gather(voxgi__image *I)
{
    voxgi__rsm_gather_job G;
    voxgi__rsm_gather_init(&G);
    G.maps = I->rsm;
    G.n = I->rsm_count;
    G.grid = &I->grid;
    G.base.O = I->have_occ ? &I->O : NULL;
    G.base.hierarchical = I->d->rsm.visibility == VOXGI_TRAVERSAL_HIERARCHICAL;
    return voxgi__image_bounce(I, I->d->rsm.gather_stride, voxgi__image_point_gather, &G.base);
}

static voxgi_result voxgi__sh_image_build(voxgi__image *I)
{
    double t0;
    voxgi_result r;
    I->gi = voxgi__image_kept(I, VOXGI_PLAN_GATHERS);
    if ((r = voxgi__image_rays(I, 1)) != VOXGI_OK) return r;
    if ((r = voxgi__image_voxels(I, 0, voxgi__image_kept(I, VOXGI_PLAN_VOXELS), I->d->sh.visibility == VOXGI_TRAVERSAL_HIERARCHICAL, 0)) != VOXGI_OK || !I->gi)
        return r;
    t0 = voxgi__now_ms();
    r = voxgi_sh_create(I->ctx, I->scene, &I->grid, &I->d->sh.volume, &I->sh);
    voxgi__image_stage(I, "sh", t0);
    if (r == VOXGI_OK) {
        voxgi_sh_info si;
        voxgi_sh_query(I->sh, &si);
        I->info->bytes += si.bytes;
    }
    return r;
}

static voxgi_result voxgi__sh_image_gather(voxgi__image *I)
{
    voxgi__sh_gather_job G;
    voxgi__sh_gather_init(&G, I->sh, I->d->sh.opening);
    G.base.O = I->have_occ ? &I->O : NULL;
    G.base.hierarchical = I->d->sh.visibility == VOXGI_TRAVERSAL_HIERARCHICAL;
    return voxgi__image_bounce(I, I->d->sh.gather_stride, voxgi__image_point_gather, &G.base);
}
#endif /* VOXGI_NO_LIGHT_SPACE */

/* ----- images from the screen-space passes: ambient occlusion, one bounce from the screen */
#ifndef VOXGI_NO_SCREEN_SPACE
/* Job J's values (channels per pixel: 1 occlusion, 3 irradiance) into values at every pixel with
   a surface (its G-buffer J->pos, J->nrm), or with `half` at the pixels (2X, 2Y) only; then,
   with `half` or a blur, the edge-aware filter (voxgi_screen_filter) and the pixels it finds no
   sample for computed on their own (each pixel's random numbers its own, as voxgi_ao draws them:
   at a pixel computed, the values are voxgi_ao's). The number of points computed added into
   *gathered. */
static voxgi_result voxgi__screen_image(voxgi_context *ctx, voxgi__screen_job *J, int channels, int half, int blur, float *values, size_t *gathered)
{
    int w = J->cam->width, h = J->cam->height, iw = (w + 1) / 2, ih = (h + 1) / 2, round;
    size_t pixels = (size_t)w * (size_t)h, i, n, ch = (size_t)channels;
    unsigned char *want = (unsigned char *)voxgi__alloc_array(ctx, pixels, 1, 1);
    float *p = (float *)voxgi__alloc_array(ctx, pixels, 12, 0), *q = (float *)voxgi__alloc_array(ctx, pixels, 12, 0);
    float *e = (float *)voxgi__alloc_array(ctx, pixels, 4 * ch, 0), *raw = (float *)voxgi__alloc_array(ctx, pixels, 4 * ch, 1);
    uint32_t *ids = (uint32_t *)voxgi__alloc_array(ctx, pixels, 4, 0);
    voxgi_result r = pixels > UINT32_MAX ? voxgi__fail(ctx, VOXGI_ERR_TOO_LARGE, "%lu pixels", (unsigned long)pixels) : VOXGI_OK;
    if (!want || !p || !q || !e || !raw || !ids) r = voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for a %d x %d screen pass", w, h);
    for (i = 0; r == VOXGI_OK && i < pixels; i++)
        want[i] = voxgi__has_surface(J->nrm, i) && (!half || ((i % (size_t)w) % 2 == 0 && (i / (size_t)w) % 2 == 0));
    for (round = 0; r == VOXGI_OK && round < 2; round++) { /* the pixels wanted; then those the filter cannot fill */
        float *dst = round ? values : raw;
        for (i = n = 0; i < pixels; i++)
            if (want[i]) {
                memcpy(p + 3 * n, J->pos + 3 * i, 12);
                memcpy(q + 3 * n, J->nrm + 3 * i, 12);
                ids[n++] = (uint32_t)i;
            }
        *gathered += n;
        J->points = p;
        J->normals = q;
        J->pixel_of = ids;
        J->out = e;
        if (n && (r = voxgi__screen_rays(ctx, J, n)) != VOXGI_OK) break;
        for (i = n = 0; i < pixels; i++)
            if (want[i]) memcpy(dst + ch * i, e + ch * n++, 4 * ch);
        if (round) break;
        if (!half && !blur) {
            memcpy(values, raw, pixels * 4 * ch);
            break;
        } else {
            voxgi_screen_filter_desc fd;
            memset(&fd, 0, sizeof fd);
            fd.camera = *J->cam;
            fd.positions = J->pos;
            fd.normals = J->nrm;
            fd.channels = channels;
            fd.half_resolution = half;
            fd.radius = blur;
            if (half) /* raw's pixels (2X, 2Y) as the half-resolution image, in place: row by row, each row's pixels only move down */
                for (i = 0; i < (size_t)iw * (size_t)ih; i++) memmove(raw + ch * i, raw + ch * (2 * (i / (size_t)iw) * (size_t)w + 2 * (i % (size_t)iw)), 4 * ch);
            r = voxgi_screen_filter(ctx, &fd, raw, values, pixels * 4 * ch, want);
        }
    }
    voxgi__free(ctx, want);
    voxgi__free(ctx, p);
    voxgi__free(ctx, q);
    voxgi__free(ctx, e);
    voxgi__free(ctx, raw);
    voxgi__free(ctx, ids);
    J->pixel_of = NULL;
    return r;
}

/* SSAO and VAO: the ray scene, VAO's voxels. */
/* The screen passes' fronts (docs/screen-space.md): AO's edges blurred little at full resolution,
   the bounce more at half; Hybrid-GI's hidden light on. */
static voxgi_result voxgi__screen_defaults(voxgi_context *ctx, const voxgi_render_desc *in, voxgi_render_desc *d)
{
    int m = (int)d->method, gi = m == VOXGI_RENDER_SSGI || m == VOXGI_RENDER_HYBRID;
    voxgi_render_screen *sc = &d->screen;
    *sc = in->screen;
    if (sc->rays < 0 || sc->steps < 0 || !(sc->radius >= 0 && isfinite(sc->radius)) || (unsigned)sc->half_resolution > VOXGI_TOGGLE_OFF || sc->blur < -1 ||
        sc->blur > 64 || (unsigned)sc->hidden_light > VOXGI_TOGGLE_OFF || sc->inject_samples < 0 || (sc->point_sampling && m != VOXGI_RENDER_SSAO))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "%s: rays %d, steps %d, radius %g, half_resolution %d, blur %d (-1..64), hidden_light %d, inject_samples %d, "
                           "point_sampling %d (ssao only)", voxgi__render_method_names[m], sc->rays, sc->steps, (double)sc->radius, (int)sc->half_resolution, sc->blur,
                           (int)sc->hidden_light, sc->inject_samples, sc->point_sampling);
    if (!sc->rays) sc->rays = 16;
    if (!sc->steps) sc->steps = 16;
    if (!sc->half_resolution) sc->half_resolution = gi ? VOXGI_TOGGLE_ON : VOXGI_TOGGLE_OFF;
    if (!sc->blur) sc->blur = gi ? 8 : 2;
    if (m == VOXGI_RENDER_HYBRID && !sc->hidden_light) sc->hidden_light = VOXGI_TOGGLE_ON;
    if (m != VOXGI_RENDER_HYBRID) sc->hidden_light = VOXGI_TOGGLE_OFF;
#ifdef VOXGI_NO_LIGHT_INJECTION
    if (sc->hidden_light == VOXGI_TOGGLE_ON && in->screen.hidden_light == VOXGI_TOGGLE_ON)
        return voxgi__fail(ctx, VOXGI_ERR_UNSUPPORTED, "hybrid: hidden light needs light injection (VOXGI_NO_LIGHT_INJECTION)");
    sc->hidden_light = VOXGI_TOGGLE_OFF;
#endif
    if (sc->hidden_light == VOXGI_TOGGLE_ON && !sc->inject_samples) sc->inject_samples = ctx->backend == VOXGI_BACKEND_GL ? 16 : 4;
    if ((m == VOXGI_RENDER_VAO || m == VOXGI_RENDER_HYBRID) && !d->resolution) d->resolution = 128;
    return VOXGI_OK;
}

/* Occlusion's reach: a tenth of the scene. */
static void voxgi__ao_plan(voxgi__plan_job *J)
{
    voxgi_render_desc *d = J->d;
    if (!(d->screen.radius > 0)) d->screen.radius = (float)(0.1 * (J->extent > 0 ? J->extent : 1));
    voxgi__plan_add(J->P, VOXGI_PLAN_LIGHTS, J->all, J->all ? "everything asked for" : "occlusion sees geometry only", 0, 0);
    voxgi__plan_add(J->P, VOXGI_PLAN_VOXELS, d->resolution > 0, d->resolution > 0 ? "occlusion through the voxels" : "occlusion through the depth buffer",
                    voxgi_grid_voxel_count(&J->P->grid) / 8 + 4, 0);
    voxgi__plan_add(J->P, VOXGI_PLAN_OCCLUSION, 1, "the image", 0, 0);
}

/* The bounce's reach: across the scene. */
static void voxgi__ssgi_plan(voxgi__plan_job *J)
{
    voxgi_render_desc *d = J->d;
    int gi = J->gi;
    if (!(d->screen.radius > 0)) d->screen.radius = (float)(sqrt(3.0) * (J->extent > 0 ? J->extent : 1));
    voxgi__plan_add(J->P, VOXGI_PLAN_VOXELS, gi && d->resolution > 0, !gi ? J->no_gi : d->resolution > 0 ? "the bounce's visibility" : "visibility through the depth buffer",
                    voxgi_grid_voxel_count(&J->P->grid) / 8 + 4, 0);
    voxgi__plan_add(J->P, VOXGI_PLAN_SCREEN_BOUNCE, gi, gi ? "one bounce from the screen" : J->no_gi, 0, 0);
    voxgi__plan_add(J->P, VOXGI_PLAN_DIRECT_LIGHT, J->lit, J->lit ? "shadow rays to the lights and emitters" : "no light and no emitter", 0, 0);
}

static void voxgi__screen_describe(const voxgi_render_desc *u, char *buf, size_t size, int *len)
{
    static const char *const toggles[] = {"default", "on", "off"};
    const voxgi_render_screen *s = &u->screen;
    voxgi__describe(buf, size, len, ", rays %d, steps %d, radius %.4g, half resolution %s, blur %d", s->rays, s->steps, (double)s->radius,
                    toggles[(unsigned)s->half_resolution % 3u], VOXGI__MAX(s->blur, 0));
    if (u->method == VOXGI_RENDER_SSAO && s->point_sampling) voxgi__describe(buf, size, len, ", point sampling");
    if (u->method == VOXGI_RENDER_HYBRID) voxgi__describe(buf, size, len, ", hidden light %s", toggles[(unsigned)s->hidden_light % 3u]);
}

static voxgi_result voxgi__ao_image_build(voxgi__image *I)
{
    voxgi_result r = voxgi__image_rays(I, 0);
    if (r == VOXGI_OK && I->d->method == VOXGI_RENDER_VAO) r = voxgi__image_voxels(I, 0, 1, 1, 0);
    return r;
}

/* Ambient occlusion (grey: the occluded share in all three channels, 0 where nothing is) at the
   G-buffer's pixels, by voxgi_ao's rays at every pixel or at half resolution, blurred and
   upsampled by voxgi_screen_filter. */
static voxgi_result voxgi__ao_image_gather(voxgi__image *I)
{
    const voxgi_render_desc *d = I->d;
    const voxgi_render_screen *sc = &d->screen;
    voxgi__screen_job J;
    double t0 = voxgi__now_ms();
    size_t p;
    voxgi_result r = voxgi__image_gbuffer(I, 1);
    voxgi__image_stage(I, "gbuffer", t0);
    if (r != VOXGI_OK) return r;
    t0 = voxgi__now_ms();
    if ((r = voxgi__screen_setup(I->ctx, &J, &d->camera, I->pos, I->nrm, d->method == VOXGI_RENDER_VAO ? VOXGI_AO_VOXELS : VOXGI_AO_SCREEN,
                                 VOXGI_TRAVERSAL_HIERARCHICAL, sc->rays, sc->steps, sc->radius)) != VOXGI_OK)
        return r;
    J.point_sampling = sc->point_sampling != 0;
    J.O = I->have_occ ? &I->O : NULL;
    J.grid = I->vox ? &I->vox->info.grid : NULL;
    J.seed = d->seed;
    r = voxgi__screen_image(I->ctx, &J, 1, sc->half_resolution == VOXGI_TOGGLE_ON, VOXGI__MAX(sc->blur, 0), I->irr, &I->info->gathered);
    voxgi__image_stage(I, "ao", t0);
    for (p = 0; r == VOXGI_OK && p < I->pixels; p++) I->rgb[3 * p] = I->rgb[3 * p + 1] = I->rgb[3 * p + 2] = I->irr[p];
    return r;
}

/* SSGI and HYBRID: the ray scene and lights, HYBRID's voxels and, with the hidden light, the
   direct light injected into them (one level: only level 0 is read). */
static voxgi_result voxgi__ssgi_image_build(voxgi__image *I)
{
    int hidden = I->d->screen.hidden_light == VOXGI_TOGGLE_ON;
    voxgi_result r;
    I->gi = voxgi__image_kept(I, VOXGI_PLAN_SCREEN_BOUNCE);
    hidden = hidden && I->gi;
    if ((r = voxgi__image_rays(I, 1)) != VOXGI_OK) return r;
    if (I->d->method == VOXGI_RENDER_HYBRID &&
        (r = voxgi__image_voxels(I, 0, I->gi, 1, hidden ? VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL : 0u)) != VOXGI_OK)
        return r;
#ifndef VOXGI_NO_LIGHT_INJECTION
    if (hidden) {
        voxgi_inject_desc id;
        double t0 = voxgi__now_ms();
        memset(&id, 0, sizeof id);
        id.volume.levels = 1;
        id.samples = I->d->screen.inject_samples;
        id.seed = I->d->seed;
        r = voxgi__inject_light(I->ctx, I->scene, I->vox, &id, &I->tr, &I->Ls, &I->volume);
        voxgi__image_stage(I, "inject", t0);
        if (I->volume) {
            voxgi_volume_info vi;
            voxgi_volume_query(I->volume, &vi);
            I->info->bytes += vi.bytes;
        }
    }
#endif
    return r;
}

/* The direct light (the screen's radiance, the light its surfaces reflect), then one bounce
   from the screen (voxgi_ssgi) at every pixel or at half resolution, blurred and upsampled. */
static voxgi_result voxgi__ssgi_image_gather(voxgi__image *I)
{
    const voxgi_render_desc *d = I->d;
    const voxgi_render_screen *sc = &d->screen;
    voxgi__screen_job J;
    double t0;
    voxgi_result r;
    if (!(I->reflected = (float *)voxgi__alloc_array(I->ctx, I->pixels, 12, 0))) return voxgi__fail(I->ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for the screen's light");
    voxgi__image_direct(I, NULL, I->reflected, "direct");
    if ((r = voxgi__image_gbuffer(I, 1)) != VOXGI_OK || !I->gi) return r;
    t0 = voxgi__now_ms();
    if ((r = voxgi__screen_setup(I->ctx, &J, &d->camera, I->pos, I->nrm, d->method == VOXGI_RENDER_HYBRID ? VOXGI_AO_VOXELS : VOXGI_AO_SCREEN,
                                 VOXGI_TRAVERSAL_HIERARCHICAL, sc->rays, sc->steps, sc->radius)) != VOXGI_OK)
        return r;
    J.radiance = I->reflected;
    J.O = I->have_occ ? &I->O : NULL;
    J.grid = I->vox ? &I->grid : NULL;
    J.seed = d->seed;
    J.hidden_radiance = I->volume;
    r = voxgi__screen_image(I->ctx, &J, 3, sc->half_resolution == VOXGI_TOGGLE_ON, VOXGI__MAX(sc->blur, 0), I->irr, &I->info->gathered);
    if (r == VOXGI_OK) voxgi__image_add_bounce(I);
    voxgi__image_stage(I, "gather", t0);
    return r;
}
#endif /* VOXGI_NO_SCREEN_SPACE */

/* ----- images of the area lights' soft shadows through the line space */
#ifndef VOXGI_NO_LINE_SPACE
/* A line space's bytes (n, depth), by voxgi_linespace_create's formula with each level's split
   nodes estimated as the cells its surface crosses. */
static uint64_t voxgi__plan_linespace_bytes(uint64_t triangles, double crossing, double extent, int n, int depth)
{
    double cells = 1, split = 0, nodes = 1, leaves = 0, refs;
    int l;
    if (!triangles || !(extent > 0)) return 0;
    for (l = 0; l <= depth; l++) { /* level l: n^l cells a side */
        double edge = extent / cells, occupied = VOXGI__MIN(cells * cells * cells, VOXGI__MAX(1.0, ceil(crossing / (edge * edge))));
        if (l < depth) { split += occupied; nodes += occupied * n * n * n; }
        else leaves = occupied;
        cells *= n;
    }
    refs = VOXGI__MAX((double)triangles, leaves) * 1.5;
    return (uint64_t)(8 * nodes + (double)((15 * n * n * n * n + 31) / 32) * 4 * split + 4 * refs + 8 * leaves + 36 * (double)triangles);
}

/* voxgi report linespace's front (docs/line-space.md): 4 shadow rays on 2 x 2 points. */
static voxgi_result voxgi__ls_defaults(voxgi_context *ctx, const voxgi_render_desc *in, voxgi_render_desc *d)
{
    voxgi_render_linespace *L = &d->linespace;
    *L = in->linespace;
    if ((unsigned)L->mode > VOXGI_LINESPACE_FAST || L->samples < 0 || L->exact_ends < 0 || L->supersample < 0 || L->supersample > 16)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "linespace: mode %d, samples %d, exact_ends %d, supersample %d (0..16)", (int)L->mode, L->samples,
                           L->exact_ends, L->supersample);
    /* the tree's ranges as voxgi_linespace_create's, here already: the plan sizes the tree before it is made */
    if (L->tree.n < 0 || L->tree.n == 1 || L->tree.n > 16 || L->tree.depth < 0 || L->tree.depth > 8)
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "linespace: tree n %d (2..16, 0: 4), depth %d (1..8, 0: from the scene)", L->tree.n, L->tree.depth);
    if (!L->samples) L->samples = 4;
    if (!L->supersample) L->supersample = 2;
    if (!L->tree.n) L->tree.n = 4;
    if (!L->tree.memory_budget) L->tree.memory_budget = d->memory_budget; /* 0: the context's, as everywhere */
    if (L->mode == VOXGI_LINESPACE_FAST && !L->exact_ends) L->exact_ends = 3;
    return VOXGI_OK;
}

/* The tree's depth from the scene's triangles. */
static void voxgi__ls_plan(voxgi__plan_job *J)
{
    voxgi_plan_info *P = J->P;
    voxgi_render_linespace *L = &J->d->linespace;
    int keep = J->all || P->area_lights > 0;
    const char *none = P->area_lights < 0 ? "more than 64 area lights (the image refuses them)" : "no area light (rect light or emissive triangles)";
    if (!L->tree.depth && !L->ls) L->tree.depth = voxgi__plan_linespace_depth(P->triangles);
    voxgi__plan_add(P, VOXGI_PLAN_LINE_SPACE, keep && !L->ls, !keep ? none : L->ls ? "the line space kept (desc.linespace.ls)" : "soft shadows of the area lights",
                    voxgi__plan_linespace_bytes(P->triangles, J->crossing, J->extent, L->tree.n, L->tree.depth), 1);
    voxgi__plan_add(P, VOXGI_PLAN_SOFT_SHADOWS, keep, keep ? "the area lights' direct light" : none, 0, 0);
}

static void voxgi__ls_describe(const voxgi_render_desc *u, char *buf, size_t size, int *len)
{
    static const char *const modes[] = {"exact", "fast"};
    const voxgi_render_linespace *L = &u->linespace;
    voxgi__describe(buf, size, len, ", %s, n %d, depth %d, shadow samples %d, supersample %d%s", modes[(unsigned)L->mode % 2u], L->tree.n, L->tree.depth, L->samples,
                    L->supersample, L->packets ? ", packets" : "");
    if (L->mode == VOXGI_LINESPACE_FAST) voxgi__describe(buf, size, len, ", exact ends %d", L->exact_ends);
}

typedef struct voxgi__ls_shade {
    const voxgi__flat *f;
    const voxgi__ls_area *A;
    int lights, hide_emitters;
    const float *pos, *nrm, *weighted;  /* weighted: per light, per pixel */
    const uint32_t *tri;
    size_t pixels;
    float *rgb;
} voxgi__ls_shade;

/* Pixels [first, end): emission (unless hidden) + albedo / pi x the sum over the lights of their
   radiance x unshadowed irradiance (Lambert's polygon formula) x the rays' weighted visible share. */
static void voxgi__ls_shade_run(void *user, size_t first, size_t end)
{
    const voxgi__ls_shade *S = (const voxgi__ls_shade *)user;
    size_t i;
    for (i = first; i < end; i++) {
        uint32_t t = S->tri[i];
        const voxgi_material *m;
        double p[3], n[3], e[3] = {0, 0, 0}, g[3];
        int l, a;
        S->rgb[3 * i] = S->rgb[3 * i + 1] = S->rgb[3 * i + 2] = 0;
        if (t == UINT32_MAX) continue;
        m = voxgi__tri_material(S->f, t);
        for (a = 0; a < 3; a++) { p[a] = S->pos[3 * i + (size_t)a]; n[a] = S->nrm[3 * i + (size_t)a]; }
        for (l = 0; l < S->lights; l++) {
            const voxgi__ls_area *A = &S->A[l];
            double q[4][3], fn[3], irr;
            float share = S->weighted[(size_t)l * S->pixels + i];
            if (!(share > 0) || A->own[0] == t || A->own[1] == t) continue;
            for (a = 0; a < 3; a++) {
                q[0][a] = A->d.corner[a];
                q[1][a] = A->d.corner[a] + A->d.edge_u[a];
                q[2][a] = A->d.corner[a] + (A->d.triangle ? A->d.edge_v[a] : A->d.edge_u[a] + A->d.edge_v[a]);
                q[3][a] = A->d.corner[a] + A->d.edge_v[a];
                fn[a] = A->d.edge_u[(a + 1) % 3] * A->d.edge_v[(a + 2) % 3] - A->d.edge_u[(a + 2) % 3] * A->d.edge_v[(a + 1) % 3];
            }
            irr = voxgi__polygon_irradiance((const double(*)[3])q, A->d.triangle ? 3 : 4, fn, p, n) * share;
            for (a = 0; a < 3; a++) e[a] += A->radiance[a] * irr;
        }
        voxgi__tri_unit_normal(S->f, t, g);
        for (a = 0; a < 3; a++)
            S->rgb[3 * i + (size_t)a] = (float)(m->albedo[a] / VOXGI__PI * e[a] + (!S->hide_emitters && g[0] * n[0] + g[1] * n[1] + g[2] * n[2] > 0 ? m->emission[a] : 0));
    }
}

/* The area lights (each rect light; emissive triangles, two sharing an edge as one
   parallelogram; at most 64) and the line space, kept or built. */
static voxgi_result voxgi__ls_image_build(voxgi__image *I)
{
    double t0;
    voxgi_result r;
    if ((r = voxgi__image_rays(I, 0)) != VOXGI_OK) return r;
    if (!(I->areas = voxgi__alloc_array(I->ctx, VOXGI__LS_AREA_LIGHTS, sizeof(voxgi__ls_area), 0))) return voxgi__fail(I->ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory");
    I->lights = voxgi__ls_area_lights(I->ctx, I->scene, &I->tr.flat, (voxgi__ls_area *)I->areas);
    if (I->lights == -2) return voxgi__fail(I->ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory");
    if (I->lights < 0) return voxgi__fail(I->ctx, VOXGI_ERR_UNSUPPORTED, "more than %d area lights (rect lights, emissive triangles paired into parallelograms)", VOXGI__LS_AREA_LIGHTS);
    t0 = voxgi__now_ms();
    if (voxgi__image_kept(I, VOXGI_PLAN_LINE_SPACE)) r = voxgi_linespace_create(I->ctx, I->scene, &I->d->linespace.tree, &I->ls_built);
    voxgi__image_stage(I, "build", t0);
    return r;
}

/* Per pixel the surface the ray through its centre meets first (or the mean of k x k points over
   its square), then per area light its unshadowed irradiance exactly (Lambert's polygon formula)
   times the share voxgi_linespace_light's weighted output gives: emission (front faces, unless
   hidden) + albedo / pi x irradiance. An emitter never lights itself. */
static voxgi_result voxgi__ls_image_gather(voxgi__image *I)
{
    const voxgi_render_desc *d = I->d;
    const voxgi_render_linespace *Ld = &d->linespace;
    const voxgi_linespace *ls = Ld->ls ? Ld->ls : I->ls_built;
    voxgi__ls_area *A = (voxgi__ls_area *)I->areas;
    voxgi_linespace_stats *st = &I->info->shadow_rays;
    voxgi__ls_shade S;
    int k = Ld->supersample, l, w = d->camera.width;
    size_t points = I->pixels * (size_t)k * (size_t)k, i;
    float *weighted, *seen, *fine, *fine_seen;
    double t0 = voxgi__now_ms();
    voxgi_result r;
    if ((r = voxgi__image_gbuffer(I, k)) != VOXGI_OK) return r;
    voxgi__image_stage(I, "gbuffer", t0);
    weighted = (float *)voxgi__alloc_array(I->ctx, points * (size_t)VOXGI__MAX(I->lights, 1), 4, 0);
    seen = (float *)voxgi__alloc_array(I->ctx, points, 4, 0);
    fine = k > 1 ? (float *)voxgi__alloc_array(I->ctx, points, 12, 0) : I->rgb;
    fine_seen = (float *)voxgi__alloc_array(I->ctx, points, 4, 1);
    if (!weighted || !seen || !fine || !fine_seen) r = voxgi__fail(I->ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for a %lu-point image", (unsigned long)points);
    t0 = voxgi__now_ms();
    for (l = 0; r == VOXGI_OK && l < I->lights; l++) {
        voxgi_linespace_stats ls_st;
        A[l].d.mode = Ld->mode;
        A[l].d.samples = Ld->samples;
        A[l].d.packets = Ld->packets;
        A[l].d.seed = (uint32_t)d->seed + (uint32_t)l * 0x9E3779B9u;
        A[l].d.exact_ends = Ld->exact_ends;
        if ((r = voxgi_linespace_light(I->ctx, ls, &A[l].d, points, I->pos, I->nrm, seen, weighted + (size_t)l * points, &ls_st)) != VOXGI_OK) break;
        for (i = 0; i < points; i++) fine_seen[i] += seen[i] / (float)I->lights;
        st->rays += ls_st.rays;
        st->nodes += ls_st.nodes;
        st->bits += ls_st.bits;
        st->triangle_tests += ls_st.triangle_tests;
        st->samples = ls_st.samples;
    }
    st->ms = voxgi__now_ms() - t0;
    voxgi__image_stage(I, "shadows", t0);
    if (r == VOXGI_OK) {
        S.f = &I->tr.flat;
        S.A = A;
        S.lights = I->lights;
        S.hide_emitters = d->hide_emitters;
        S.pos = I->pos;
        S.nrm = I->nrm;
        S.tri = I->prim;
        S.weighted = weighted;
        S.pixels = points;
        S.rgb = fine;
        voxgi__parallel(I->ctx, points, 256, voxgi__ls_shade_run, &S);
        for (i = 0; i < I->pixels; i++) { /* each pixel the mean of its k x k points */
            size_t x = i % (size_t)w, y = i / (size_t)w, sx, sy;
            double sum[4] = {0, 0, 0, 0};
            for (sy = 0; sy < (size_t)k; sy++)
                for (sx = 0; sx < (size_t)k; sx++) {
                    size_t q = (y * (size_t)k + sy) * (size_t)w * (size_t)k + x * (size_t)k + sx;
                    for (l = 0; l < 3; l++) sum[l] += fine[3 * q + (size_t)l];
                    sum[3] += fine_seen[q];
                }
            if (k > 1) for (l = 0; l < 3; l++) I->rgb[3 * i + (size_t)l] = (float)(sum[l] / (k * k));
            if (Ld->visible) Ld->visible[i] = (float)(sum[3] / (k * k));
        }
        if (ls) voxgi_linespace_query(ls, &I->info->tree);
        I->info->lights = I->lights;
    }
    voxgi__free(I->ctx, weighted);
    voxgi__free(I->ctx, seen);
    voxgi__free(I->ctx, fine_seen);
    if (fine != I->rgb) voxgi__free(I->ctx, fine);
    return r;
}
#endif /* VOXGI_NO_LINE_SPACE */

/* ----- the table and the one entry point */
typedef struct voxgi__render_row {
    voxgi_result (*defaults)(voxgi_context *ctx, const voxgi_render_desc *in, voxgi_render_desc *d); /* its part of the desc, checked and resolved */
    void (*plan)(voxgi__plan_job *J);        /* its items, and the defaults that depend on the scene */
    void (*describe)(const voxgi_render_desc *u, char *buf, size_t size, int *len); /* its part of the settings */
    voxgi_result (*build)(voxgi__image *I);  /* what the method takes from the scene */
    voxgi_result (*gather)(voxgi__image *I); /* what the pixels take from that: the image */
    int samples;                             /* desc.samples' default; 0: it takes none (the pixels' centres) */
    int bounce;                              /* the indirect bounces it makes: 0, 1, or -1: desc.bounces */
    int voxels;                              /* 1: it reads desc.resolution */
    const char *left_out;                    /* NULL, or the macro that left the method out of this build */
} voxgi__render_row;
#define VOXGI__LEFT_OUT(macro) {NULL, NULL, NULL, NULL, NULL, 0, 0, 0, macro}

static const voxgi__render_row voxgi__render_rows[VOXGI_RENDER_METHOD_COUNT] = {
#ifndef VOXGI_NO_REFERENCE
    {voxgi__reference_defaults, voxgi__reference_plan, voxgi__reference_describe, voxgi__reference_image_build, voxgi__reference_image_gather, 64, -1, 0, NULL},
#else
    VOXGI__LEFT_OUT("VOXGI_NO_REFERENCE"),
#endif
#if !defined(VOXGI_NO_CONE_TRACING) && !defined(VOXGI_NO_LIGHT_INJECTION)
    {voxgi__vct_defaults, voxgi__vct_plan, voxgi__vct_describe, voxgi__vct_image_build, voxgi__vct_image_gather, 24, -1, 1, NULL},
#else
    VOXGI__LEFT_OUT("VOXGI_NO_CONE_TRACING or VOXGI_NO_LIGHT_INJECTION"),
#endif
#ifndef VOXGI_NO_LIGHT_SPACE
    {voxgi__tsm_defaults, voxgi__tsm_plan, voxgi__tsm_describe, voxgi__tsm_image_build, voxgi__tsm_image_gather, 4, 0, 0, NULL},
    {voxgi__bounce_defaults, voxgi__bounce_plan, voxgi__bounce_describe, voxgi__rsm_image_build, voxgi__rsm_image_gather, 24, 1, 1, NULL},
    {voxgi__bounce_defaults, voxgi__bounce_plan, voxgi__bounce_describe, voxgi__sh_image_build, voxgi__sh_image_gather, 24, 1, 1, NULL},
#else
    VOXGI__LEFT_OUT("VOXGI_NO_LIGHT_SPACE"),
    VOXGI__LEFT_OUT("VOXGI_NO_LIGHT_SPACE"),
    VOXGI__LEFT_OUT("VOXGI_NO_LIGHT_SPACE"),
#endif
#ifndef VOXGI_NO_SCREEN_SPACE
    {voxgi__screen_defaults, voxgi__ao_plan, voxgi__screen_describe, voxgi__ao_image_build, voxgi__ao_image_gather, 0, 0, 0, NULL},
    {voxgi__screen_defaults, voxgi__ao_plan, voxgi__screen_describe, voxgi__ao_image_build, voxgi__ao_image_gather, 0, 0, 1, NULL},
    {voxgi__screen_defaults, voxgi__ssgi_plan, voxgi__screen_describe, voxgi__ssgi_image_build, voxgi__ssgi_image_gather, 24, 1, 0, NULL},
    {voxgi__screen_defaults, voxgi__ssgi_plan, voxgi__screen_describe, voxgi__ssgi_image_build, voxgi__ssgi_image_gather, 24, 1, 1, NULL},
#else
    VOXGI__LEFT_OUT("VOXGI_NO_SCREEN_SPACE"),
    VOXGI__LEFT_OUT("VOXGI_NO_SCREEN_SPACE"),
    VOXGI__LEFT_OUT("VOXGI_NO_SCREEN_SPACE"),
    VOXGI__LEFT_OUT("VOXGI_NO_SCREEN_SPACE"),
#endif
#ifndef VOXGI_NO_LINE_SPACE
    {voxgi__ls_defaults, voxgi__ls_plan, voxgi__ls_describe, voxgi__ls_image_build, voxgi__ls_image_gather, 0, 0, 0, NULL},
#else
    VOXGI__LEFT_OUT("VOXGI_NO_LINE_SPACE"),
#endif
};

/* The settings a desc asks for, checked, every zero that needs no look at the scene resolved (the
   scene's: the camera, the screen radius, the line space's depth, VCT's radiance store, are the
   methods' plans'). A method reads its own part of the desc only: the others stay zero, so that
   what is reported is what ran. */
static voxgi_result voxgi__render_defaults(voxgi_context *ctx, const voxgi_render_desc *in, voxgi_render_desc *d)
{
    const voxgi__render_row *row;
    int m = (int)in->method;
    if ((unsigned)m >= VOXGI_RENDER_METHOD_COUNT) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "desc.method %d: no such method", m);
    row = &voxgi__render_rows[m];
    if (!row->build) return voxgi__fail(ctx, VOXGI_ERR_UNSUPPORTED, "method %s: left out of this build (%s)", voxgi__render_method_names[m], row->left_out);
    *d = *in;
    if (d->samples < 0 || d->resolution < 0 || d->resolution > 4096 || d->bounces < -1 || d->bounces > 64 || !(d->error >= 0 && d->error < 1))
        return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "samples %d (>= 0), resolution %d (0..4096), bounces %d (-1..64), error %g ([0, 1))", d->samples,
                           d->resolution, d->bounces, d->error);
    if (d->error > 0 && m != VOXGI_RENDER_VCT) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "desc.error: only vct chooses its settings from an error");
    if (d->voxels && m != VOXGI_RENDER_VCT) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "desc.voxels: only vct re-injects kept voxels");
    memset(&d->vct, 0, sizeof d->vct);
    memset(&d->tsm, 0, sizeof d->tsm);
    memset(&d->rsm, 0, sizeof d->rsm);
    memset(&d->sh, 0, sizeof d->sh);
    memset(&d->screen, 0, sizeof d->screen);
    memset(&d->linespace, 0, sizeof d->linespace);
    memset(&d->reference, 0, sizeof d->reference);
    if (!d->camera.width && !d->camera.height) d->camera.width = d->camera.height = 256;
    if (d->camera.fovy_degrees == 0) d->camera.fovy_degrees = 40;
    if (!d->bounces) d->bounces = 1;
    if (d->direct_only) d->bounces = 0;
    if (row->bounce >= 0) d->bounces = d->direct_only ? 0 : row->bounce;
    if (!row->samples) d->samples = 0;
    else if (!d->samples) d->samples = row->samples;
    if (!row->voxels) d->resolution = 0;
    return row->defaults(ctx, in, d);
}

/* The plan of a desc (its defaults resolved into *used, the scene's among them) with flags
   (VOXGI_PLAN_DYNAMIC, _EVERYTHING). */
static voxgi_result voxgi__plan_render(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_render_desc *desc, unsigned flags, voxgi_render_desc *used,
                                       voxgi_plan_info *plan)
{
    voxgi_plan_info P;
    voxgi__plan_job J;
    voxgi_render_desc *d = used;
    int m, ao;
    voxgi_result r;
    if ((r = voxgi__render_defaults(ctx, desc, d)) != VOXGI_OK) return r;
    if ((r = voxgi__validate(ctx, scene, NULL, NULL)) != VOXGI_OK) return r;
    memset(&P, 0, sizeof P);
    memset(&J, 0, sizeof J);
    m = (int)d->method;
    ao = m == VOXGI_RENDER_SSAO || m == VOXGI_RENDER_VAO;
    if ((r = voxgi__plan_scene(ctx, scene, &d->camera, &P, &J.crossing, &J.extent, &J.absorptions)) != VOXGI_OK) return r;
    if (d->resolution) {
        voxgi_fit_desc fit;
        memset(&fit, 0, sizeof fit);
        fit.res = d->resolution;
        fit.padding = 1;
        if ((r = voxgi_fit_grid(ctx, scene, &fit, &P.grid)) != VOXGI_OK) return r;
        P.voxels = (uint64_t)VOXGI__MIN((double)voxgi_grid_voxel_count(&P.grid), ceil(J.crossing / (P.grid.voxel_size * P.grid.voxel_size)));
        P.occupancy = (double)P.voxels / (double)voxgi_grid_voxel_count(&P.grid);
    }
    P.error_reachable = 1;
    J.ctx = ctx;
    J.asked = desc;
    J.d = d;
    J.P = &P;
    J.flags = flags;
    J.all = (flags & VOXGI_PLAN_EVERYTHING) != 0;
    J.budget = d->memory_budget ? d->memory_budget : ctx->desc.memory_budget;
    J.lit = J.all || scene->light_count || P.emissive_triangles;
    J.reflective = J.all || P.reflective_triangles;
    J.seen = J.all || P.emitters_in_view;
    J.gi = J.lit && J.reflective && !d->direct_only;
    J.no_gi = d->direct_only ? "the direct light alone asked for" : !J.lit ? "no light and no emitter" : "no reflective surface (every albedo is 0)";
    voxgi__render_rows[m].plan(&J);
    voxgi__plan_add(&P, VOXGI_PLAN_SEEN_EMISSION, J.seen && P.emissive_triangles && !ao && !d->hide_emitters,
                    ao ? "occlusion sees geometry only" : !P.emissive_triangles ? "no emissive material"
                    : d->hide_emitters ? "hidden (desc.hide_emitters)" : J.seen ? "emitters in view" : "the camera sees no emitter", 0, 0);
    *plan = P;
    return VOXGI_OK;
}

VOXGI_API voxgi_result voxgi_plan(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_render_desc *desc, unsigned flags, voxgi_plan_info *plan)
{
    voxgi_render_desc used;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!scene || !desc || !plan) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "scene, desc or plan is NULL");
    return voxgi__plan_render(ctx, scene, desc, flags, &used, plan);
}

VOXGI_API voxgi_result voxgi_render_resolve(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_render_desc *desc, voxgi_render_desc *used)
{
    voxgi_plan_info plan;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!scene || !desc || !used) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "scene, desc or used is NULL");
    return voxgi__plan_render(ctx, scene, desc, 0, used, &plan);
}

VOXGI_API int voxgi_render_describe(const voxgi_render_desc *u, char *buf, size_t size)
{
    const voxgi__render_row *row;
    int len = 0, m;
    if (buf && size) buf[0] = 0;
    if (!u || (unsigned)u->method >= VOXGI_RENDER_METHOD_COUNT) return 0;
    m = (int)u->method;
    row = &voxgi__render_rows[m];
    voxgi__describe(buf, size, &len, "%s: %d x %d, fovy %.4g, samples %d, seed %llu", voxgi__render_method_names[m], u->camera.width, u->camera.height,
                    u->camera.fovy_degrees, u->samples, (unsigned long long)u->seed);
    if (row->bounce < 0) voxgi__describe(buf, size, &len, ", bounces %d", u->bounces);
    if (u->resolution) voxgi__describe(buf, size, &len, ", resolution %d", u->resolution);
    if (u->hide_emitters) voxgi__describe(buf, size, &len, ", emitters hidden");
    if (u->error > 0) voxgi__describe(buf, size, &len, ", error %.4g", u->error);
    if (row->describe) row->describe(u, buf, size, &len);
    return len;
}

VOXGI_API voxgi_result voxgi_render_voxelize(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_render_desc *desc, voxgi_voxels **out)
{
    voxgi_render_desc d;
    voxgi_result r;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!desc || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "desc or out is NULL");
    *out = NULL;
    if (desc->method != VOXGI_RENDER_VCT) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "desc.method: only vct keeps voxels");
    if ((r = voxgi__render_defaults(ctx, desc, &d)) != VOXGI_OK) return r; /* refuses vct where it is left out */
    if ((r = voxgi__validate(ctx, scene, NULL, NULL)) != VOXGI_OK) return r;
#if !defined(VOXGI_NO_CONE_TRACING) && !defined(VOXGI_NO_LIGHT_INJECTION)
    return voxgi__vct_voxelize(ctx, scene, &d, out);
#else
    return VOXGI_ERR_UNSUPPORTED;
#endif
}

VOXGI_API voxgi_result voxgi_render(voxgi_context *ctx, const voxgi_scene *scene, const voxgi_render_desc *desc, float *rgb, size_t rgb_bytes,
                                    voxgi_render_info *info)
{
    voxgi_render_info inf;
    voxgi__image I;
    const voxgi__render_row *row;
    double t0 = voxgi__now_ms();
    voxgi_result r;
    int i;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (info) memset(info, 0, sizeof *info);
    if (!scene || !desc || !rgb) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "scene, desc or rgb is NULL");
    memset(&inf, 0, sizeof inf);
    if ((r = voxgi__plan_render(ctx, scene, desc, 0, &inf.used, &inf.plan)) != VOXGI_OK) return r;
    row = &voxgi__render_rows[inf.used.method];
    memset(&I, 0, sizeof I);
    I.pixels = (size_t)inf.used.camera.width * (size_t)inf.used.camera.height;
    if (rgb_bytes < I.pixels * 12)
        return voxgi__fail(ctx, VOXGI_ERR_BUFFER_TOO_SMALL, "rgb holds %lu bytes, the %d x %d image needs %lu", (unsigned long)rgb_bytes, inf.used.camera.width,
                           inf.used.camera.height, (unsigned long)(I.pixels * 12));
    for (i = 0; i < inf.plan.item_count; i++)
        if (!inf.plan.items[i].kept) voxgi__log(ctx, VOXGI_LOG_DEBUG, "plan: %s: left out - %s", inf.plan.items[i].name, inf.plan.items[i].why);
    if (!scene->light_count && !inf.plan.emissive_triangles && inf.used.method != VOXGI_RENDER_SSAO && inf.used.method != VOXGI_RENDER_VAO &&
        !(inf.used.method == VOXGI_RENDER_REFERENCE && desc->reference.ao_radius > 0))
        voxgi__log(ctx, VOXGI_LOG_WARNING, "no light and no emitter in the scene: the image is black (add a voxgi_light or a material with emission)");
    I.ctx = ctx;
    I.scene = scene;
    I.d = &inf.used;
    I.plan = &inf.plan;
    I.info = &inf;
    I.rgb = rgb;
    r = row->build(&I);
    if (r == VOXGI_OK) { /* every method reports (and can be cancelled) between its structures and its image */
        char stage[48];
        snprintf(stage, sizeof stage, "%s: built", voxgi__render_method_names[inf.used.method]);
        if (voxgi__progress(ctx, 1.0, stage)) r = voxgi__fail(ctx, VOXGI_ERR_CANCELLED, "the image cancelled by the progress callback (%s)", stage);
    }
    if (r == VOXGI_OK) r = row->gather(&I);
    voxgi__image_free(&I);
    inf.ms = voxgi__now_ms() - t0;
    if (info) *info = inf;
    return r;
}

VOXGI_API double voxgi_render_stage_ms(const voxgi_render_info *info, const char *name)
{
    int i;
    for (i = 0; i < info->stage_count; i++)
        if (!strcmp(info->stages[i].name, name)) return info->stages[i].ms;
    return 0;
}

VOXGI_API const char *voxgi_render_method_name(voxgi_render_method method)
{
    return (unsigned)method < VOXGI_RENDER_METHOD_COUNT ? voxgi__render_method_names[method] : NULL;
}

VOXGI_API int voxgi_render_method_find(const char *name)
{
    int m;
    for (m = 0; name && m < VOXGI_RENDER_METHOD_COUNT; m++)
        if (!strcmp(name, voxgi__render_method_names[m])) return m;
    return -1;
}

/* ===================================================================== 15. built-in scenes and files */

#define VOXGI__BUILTIN_VERTICES 6144
#define VOXGI__BUILTIN_TRIANGLES 6144
typedef struct voxgi__builtin {
    float pos[3 * VOXGI__BUILTIN_VERTICES];
    uint32_t idx[3 * VOXGI__BUILTIN_TRIANGLES], mat[VOXGI__BUILTIN_TRIANGLES];
    voxgi_material materials[8];
    voxgi_light lights[2];
    voxgi_mesh mesh;
    size_t nv, nt;
} voxgi__builtin;

/* A quad p0 p1 p2 p3 (in order around it) whose front faces `toward` (away = 1: faces away from it). */
static void voxgi__builtin_quad(voxgi__builtin *b, const double q[4][3], uint32_t mat, const double toward[3], int away)
{
    double e1[3], e2[3], n[3], d = 0;
    uint32_t v = (uint32_t)b->nv;
    int a, k, flip;
    for (a = 0; a < 3; a++) { e1[a] = q[1][a] - q[0][a]; e2[a] = q[2][a] - q[0][a]; }
    for (a = 0; a < 3; a++) n[a] = e1[(a + 1) % 3] * e2[(a + 2) % 3] - e1[(a + 2) % 3] * e2[(a + 1) % 3];
    for (a = 0; a < 3; a++) d += n[a] * (toward[a] - 0.25 * (q[0][a] + q[1][a] + q[2][a] + q[3][a]));
    flip = (d < 0) != (away != 0);
    for (k = 0; k < 4; k++)
        for (a = 0; a < 3; a++) b->pos[3 * b->nv + 3 * (size_t)k + (size_t)a] = (float)q[k][a];
    b->nv += 4;
    b->idx[3 * b->nt] = v; b->idx[3 * b->nt + 1] = v + (flip ? 2u : 1u); b->idx[3 * b->nt + 2] = v + (flip ? 1u : 2u);
    b->mat[b->nt++] = mat;
    b->idx[3 * b->nt] = v; b->idx[3 * b->nt + 1] = v + (flip ? 3u : 2u); b->idx[3 * b->nt + 2] = v + (flip ? 2u : 3u);
    b->mat[b->nt++] = mat;
}

/* An axis-aligned box's six faces, facing out (inward = 1: in). */
static void voxgi__builtin_box(voxgi__builtin *b, const double lo[3], const double hi[3], uint32_t mat, int inward)
{
    double c[3], q[4][3];
    int axis, side, k, a;
    for (a = 0; a < 3; a++) c[a] = 0.5 * (lo[a] + hi[a]);
    for (axis = 0; axis < 3; axis++)
        for (side = 0; side < 2; side++) {
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            for (k = 0; k < 4; k++) {
                q[k][axis] = side ? hi[axis] : lo[axis];
                q[k][u] = (k == 1 || k == 2) ? hi[u] : lo[u];
                q[k][v] = (k >= 2) ? hi[v] : lo[v];
            }
            voxgi__builtin_quad(b, (const double(*)[3])q, mat, c, !inward);
        }
}

/* A UV sphere (front faces out, or in). */
static void voxgi__builtin_sphere(voxgi__builtin *b, const double c[3], double r, int slices, int stacks, uint32_t mat, int inward)
{
    uint32_t first = (uint32_t)b->nv;
    int i, j;
    for (j = 0; j <= stacks; j++)
        for (i = 0; i <= slices; i++) {
            double th = VOXGI__PI * j / stacks, ph = 2 * VOXGI__PI * i / slices;
            b->pos[3 * b->nv] = (float)(c[0] + r * sin(th) * cos(ph));
            b->pos[3 * b->nv + 1] = (float)(c[1] + r * cos(th));
            b->pos[3 * b->nv + 2] = (float)(c[2] + r * sin(th) * sin(ph));
            b->nv++;
        }
    for (j = 0; j < stacks; j++)
        for (i = 0; i < slices; i++) { /* counter-clockwise from outside: (a, c, b), (b, c, d) */
            uint32_t a0 = first + (uint32_t)(j * (slices + 1) + i), b0 = a0 + 1, c0 = a0 + (uint32_t)slices + 1, d0 = c0 + 1;
            uint32_t t[6];
            int k;
            t[0] = a0; t[1] = inward ? c0 : b0; t[2] = inward ? b0 : c0;
            t[3] = b0; t[4] = inward ? c0 : d0; t[5] = inward ? d0 : c0;
            for (k = 0; k < 2; k++) {
                memcpy(b->idx + 3 * b->nt, t + 3 * k, 3 * sizeof(uint32_t));
                b->mat[b->nt++] = mat;
            }
        }
}

static void voxgi__material_set(voxgi_material *m, float r, float g, float bl, float er, float eg, float eb)
{
    m->albedo[0] = r; m->albedo[1] = g; m->albedo[2] = bl;
    m->emission[0] = er; m->emission[1] = eg; m->emission[2] = eb;
    m->transparency = 0;
}

static void voxgi__view(voxgi_camera *c, double ex, double ey, double ez, double tx, double ty, double tz, double fovy)
{
    c->eye[0] = ex; c->eye[1] = ey; c->eye[2] = ez;
    c->target[0] = tx; c->target[1] = ty; c->target[2] = tz;
    c->fovy_degrees = fovy;
    c->width = c->height = 256;
}

static const char *const voxgi__builtin_names[6] = {"cornell-box", "rsm-walls", "leak-box", "furnace", "leak-room", "foliage"};

VOXGI_API const char *voxgi_builtin_scene_names(void)
{
    return "cornell-box rsm-walls leak-box furnace leak-room foliage";
}

VOXGI_API voxgi_result voxgi_builtin_scene_create(voxgi_context *ctx, const char *name, voxgi_builtin_scene *out)
{
    voxgi__builtin *b;
    int which;
    if (!ctx) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!name || !out) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "name or out is NULL");
    memset(out, 0, sizeof *out);
    for (which = 0; which < 6 && strcmp(name, voxgi__builtin_names[which]) != 0; which++) {}
    if (which == 6) return voxgi__fail(ctx, VOXGI_ERR_INVALID_ARGUMENT, "no built-in scene \"%s\" (there are: %s)", name, voxgi_builtin_scene_names());
    if (!(b = (voxgi__builtin *)voxgi__alloc_array(ctx, 1, sizeof *b, 1))) return voxgi__fail(ctx, VOXGI_ERR_OUT_OF_MEMORY, "no memory for a scene");
    if (which == 0) { /* the Cornell box, millimetres / 1000 */
        static const double walls[5][4][3] = {
            {{552.8, 0, 0}, {0, 0, 0}, {0, 0, 559.2}, {549.6, 0, 559.2}},               /* floor */
            {{556, 548.8, 0}, {556, 548.8, 559.2}, {0, 548.8, 559.2}, {0, 548.8, 0}},   /* ceiling */
            {{549.6, 0, 559.2}, {0, 0, 559.2}, {0, 548.8, 559.2}, {556, 548.8, 559.2}}, /* back */
            {{0, 0, 559.2}, {0, 0, 0}, {0, 548.8, 0}, {0, 548.8, 559.2}},               /* right: green */
            {{552.8, 0, 0}, {549.6, 0, 559.2}, {556, 548.8, 559.2}, {556, 548.8, 0}}};  /* left: red */
        static const double light[4][3] = {{343, 548.7, 227}, {343, 548.7, 332}, {213, 548.7, 332}, {213, 548.7, 227}};
        static const double blocks[2][5][4][3] = {
            {{{130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}},
             {{290, 0, 114}, {290, 165, 114}, {240, 165, 272}, {240, 0, 272}},
             {{130, 0, 65}, {130, 165, 65}, {290, 165, 114}, {290, 0, 114}},
             {{82, 0, 225}, {82, 165, 225}, {130, 165, 65}, {130, 0, 65}},
             {{240, 0, 272}, {240, 165, 272}, {82, 165, 225}, {82, 0, 225}}},
            {{{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}},
             {{423, 0, 247}, {423, 330, 247}, {472, 330, 406}, {472, 0, 406}},
             {{472, 0, 406}, {472, 330, 406}, {314, 330, 456}, {314, 0, 456}},
             {{314, 0, 456}, {314, 330, 456}, {265, 330, 296}, {265, 0, 296}},
             {{265, 0, 296}, {265, 330, 296}, {423, 330, 247}, {423, 0, 247}}}};
        static const double centres[2][3] = {{186, 82.5, 168.5}, {368.5, 165, 351.5}};
        double room[3] = {278, 274.4, 279.6}, q[4][3], c[3];
        int w, k, a, blk;
        voxgi__material_set(&b->materials[0], 0.725f, 0.71f, 0.68f, 0, 0, 0);
        voxgi__material_set(&b->materials[1], 0.63f, 0.065f, 0.05f, 0, 0, 0);
        voxgi__material_set(&b->materials[2], 0.14f, 0.45f, 0.091f, 0, 0, 0);
        voxgi__material_set(&b->materials[3], 0.78f, 0.78f, 0.78f, 17, 12, 4);
        for (a = 0; a < 3; a++) room[a] /= 1000;
        for (w = 0; w < 5; w++) {
            for (k = 0; k < 4; k++) for (a = 0; a < 3; a++) q[k][a] = walls[w][k][a] / 1000;
            voxgi__builtin_quad(b, (const double(*)[3])q, w == 3 ? 2u : (w == 4 ? 1u : 0u), room, 0);
        }
        for (k = 0; k < 4; k++) for (a = 0; a < 3; a++) q[k][a] = light[k][a] / 1000;
        c[0] = 0.278; c[1] = 0; c[2] = 0.2795; /* faces down */
        voxgi__builtin_quad(b, (const double(*)[3])q, 3, c, 0);
        for (blk = 0; blk < 2; blk++)
            for (w = 0; w < 5; w++) {
                for (k = 0; k < 4; k++) for (a = 0; a < 3; a++) q[k][a] = blocks[blk][w][k][a] / 1000;
                for (a = 0; a < 3; a++) c[a] = centres[blk][a] / 1000;
                voxgi__builtin_quad(b, (const double(*)[3])q, 0, c, 1);
            }
        out->scene.material_count = 4;
        voxgi__view(&out->camera, 0.278, 0.273, -0.8, 0.278, 0.273, 0, 39.3077);
    } else if (which == 1) { /* two spheres, red and blue walls, a divider */
        static const double floor_q[4][3] = {{-2.5, 0, -2}, {2.5, 0, -2}, {2.5, 0, 1.5}, {-2.5, 0, 1.5}};
        static const double red[4][3] = {{-2.5, 0, 1}, {0, 0, 1}, {0, 2, 1}, {-2.5, 2, 1}}, blue[4][3] = {{0, 0, 1}, {2.5, 0, 1}, {2.5, 2, 1}, {0, 2, 1}};
        double up[3] = {0, 1, 0}, front[3] = {0, 1, -1}, lo[3] = {-0.05, 0, -1}, hi[3] = {0.05, 1.5, 1}, s0[3] = {-1.1, 0.5, 0}, s1[3] = {1.1, 0.5, 0};
        voxgi__material_set(&b->materials[0], 0.5f, 0.5f, 0.5f, 0, 0, 0);
        voxgi__material_set(&b->materials[1], 0.8f, 0.1f, 0.1f, 0, 0, 0);
        voxgi__material_set(&b->materials[2], 0.1f, 0.1f, 0.8f, 0, 0, 0);
        voxgi__material_set(&b->materials[3], 0.9f, 0.9f, 0.9f, 0, 0, 0);
        voxgi__builtin_quad(b, floor_q, 0, up, 0);
        voxgi__builtin_quad(b, red, 1, front, 0);
        voxgi__builtin_quad(b, blue, 2, front, 0);
        voxgi__builtin_box(b, lo, hi, 0, 0);
        voxgi__builtin_sphere(b, s0, 0.5, 48, 24, 3, 0);
        voxgi__builtin_sphere(b, s1, 0.5, 48, 24, 3, 0);
        b->lights[0].type = VOXGI_LIGHT_DIRECTIONAL;
        b->lights[0].direction[0] = 0.35f; b->lights[0].direction[1] = -0.8f; b->lights[0].direction[2] = 0.5f;
        b->lights[0].intensity[0] = b->lights[0].intensity[1] = b->lights[0].intensity[2] = 3;
        out->scene.material_count = 4;
        out->scene.light_count = 1;
        voxgi__view(&out->camera, 0, 2.2, -4.5, 0, 0.5, 0.3, 45);
    } else if (which == 2) { /* a closed box, lights and a lit ground outside */
        double lo[3] = {-0.5, 0, -0.5}, hi[3] = {0.5, 1, 0.5}, up[3] = {0, 1, 0};
        static const double ground[4][3] = {{-2, -0.01, -2}, {2, -0.01, -2}, {2, -0.01, 2}, {-2, -0.01, 2}};
        voxgi__material_set(&b->materials[0], 0.8f, 0.8f, 0.8f, 0, 0, 0);
        voxgi__builtin_box(b, lo, hi, 0, 1);
        voxgi__builtin_quad(b, ground, 0, up, 0);
        b->lights[0].type = VOXGI_LIGHT_DIRECTIONAL;
        b->lights[0].direction[0] = -0.3f; b->lights[0].direction[1] = -1; b->lights[0].direction[2] = 0.4f;
        b->lights[0].intensity[0] = b->lights[0].intensity[1] = b->lights[0].intensity[2] = 10;
        b->lights[1].type = VOXGI_LIGHT_POINT;
        b->lights[1].position[0] = 1.5f; b->lights[1].position[1] = 0.5f; b->lights[1].position[2] = -1;
        b->lights[1].intensity[0] = b->lights[1].intensity[1] = b->lights[1].intensity[2] = 50;
        out->scene.material_count = 1;
        out->scene.light_count = 2;
        voxgi__view(&out->camera, 0.3, 0.5, -0.4, -0.1, 0.35, 0.5, 90);
    } else if (which == 4) { /* a closed box in a closed room, lit by a lamp under the ceiling */
        double room_lo[3] = {-1, 0, -1}, room_hi[3] = {1, 2, 1}, box_lo[3] = {-0.3, 0, -0.3}, box_hi[3] = {0.3, 0.5, 0.3}, below[3] = {0, 0, 0};
        static const double lamp[4][3] = {{-0.2, 1.95, -0.2}, {0.2, 1.95, -0.2}, {0.2, 1.95, 0.2}, {-0.2, 1.95, 0.2}};
        voxgi__material_set(&b->materials[0], 0.5f, 0.5f, 0.5f, 0, 0, 0);
        voxgi__material_set(&b->materials[1], 0.5f, 0.5f, 0.5f, 10, 10, 10);
        voxgi__builtin_box(b, room_lo, room_hi, 0, 1);
        voxgi__builtin_box(b, box_lo, box_hi, 0, 0);
        voxgi__builtin_quad(b, lamp, 1, below, 0);
        out->scene.material_count = 2;
        voxgi__view(&out->camera, 0.15, 0.3, -0.2, -0.1, 0.15, 0.25, 90);
    } else if (which == 5) { /* a tree: trunk, translucent leaves, ground, sun */
        static const double ground[4][3] = {{-3, 0, -3}, {3, 0, -3}, {3, 0, 3}, {-3, 0, 3}};
        double up[3] = {0, 1, 0}, lo[3] = {-0.08, 0, -0.08}, hi[3] = {0.08, 1.3, 0.08};
        voxgi__rng g;
        int leaf, k, a;
        voxgi__material_set(&b->materials[0], 0.5f, 0.5f, 0.5f, 0, 0, 0);
        voxgi__material_set(&b->materials[1], 0.35f, 0.22f, 0.12f, 0, 0, 0);
        voxgi__material_set(&b->materials[2], 0.2f, 0.55f, 0.15f, 0, 0, 0);
        b->materials[2].transparency = 0.7f;
        voxgi__builtin_quad(b, ground, 0, up, 0);
        voxgi__builtin_box(b, lo, hi, 1, 0);
        voxgi__rng_seed(&g, 2014, 0, 0);
        for (leaf = 0; leaf < 1200; leaf++) { /* in an ellipsoid about (0, 1.6, 0), each facing its own way */
            double c[3], n[3], t[3], s[3], q[4][3], toward[3], len;
            do {
                for (a = 0; a < 3; a++) c[a] = 2 * voxgi__rng_unit(&g) - 1;
            } while (c[0] * c[0] + c[1] * c[1] + c[2] * c[2] > 1);
            c[0] *= 0.9; c[1] = 1.6 + 0.55 * c[1]; c[2] *= 0.9;
            do {
                for (a = 0; a < 3; a++) n[a] = 2 * voxgi__rng_unit(&g) - 1;
                len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            } while (len > 1 || len < 0.1);
            for (a = 0; a < 3; a++) n[a] /= len;
            voxgi__basis(n, t, s);
            for (k = 0; k < 4; k++)
                for (a = 0; a < 3; a++) q[k][a] = c[a] + 0.06 * ((k == 1 || k == 2 ? 1 : -1) * t[a] + (k >= 2 ? 1 : -1) * s[a]);
            for (a = 0; a < 3; a++) toward[a] = c[a] + n[a];
            voxgi__builtin_quad(b, (const double(*)[3])q, 2, toward, 0);
        }
        b->lights[0].type = VOXGI_LIGHT_DIRECTIONAL;
        b->lights[0].direction[0] = 0.4f; b->lights[0].direction[1] = -1; b->lights[0].direction[2] = 0.25f;
        b->lights[0].intensity[0] = b->lights[0].intensity[1] = b->lights[0].intensity[2] = 3;
        out->scene.material_count = 3;
        out->scene.light_count = 1;
        voxgi__view(&out->camera, -2.2, 2.3, -3.6, 0.3, 0.7, 0.2, 45);
    } else { /* the furnace */
        double c[3] = {0, 0, 0};
        voxgi__material_set(&b->materials[0], 0.5f, 0.5f, 0.5f, 1, 1, 1);
        voxgi__builtin_sphere(b, c, 1, 48, 24, 0, 1);
        out->scene.material_count = 1;
        voxgi__view(&out->camera, 0, 0, 0, 0.3, 0.2, 1, 90);
    }
    b->mesh.positions = b->pos;
    b->mesh.vertex_count = b->nv;
    b->mesh.indices = b->idx;
    b->mesh.index_count = 3 * b->nt;
    b->mesh.material_ids = b->mat;
    out->scene.meshes = &b->mesh;
    out->scene.mesh_count = 1;
    out->scene.materials = b->materials;
    out->scene.lights = out->scene.light_count ? b->lights : NULL;
    out->name = voxgi__builtin_names[which];
    out->storage = b;
    return VOXGI_OK;
}

VOXGI_API void voxgi_builtin_scene_destroy(voxgi_context *ctx, voxgi_builtin_scene *scene)
{
    if (!ctx || !scene) return;
    voxgi__free(ctx, scene->storage);
    memset(scene, 0, sizeof *scene);
}

/* ----- binvox files */
VOXGI_API voxgi_result voxgi_binvox_write(FILE *f, const voxgi_grid *g, const uint32_t *bits)
{
    int x, y, z, dmax;
    int value = -1, run = 0;
    if (!f || !g || !bits || voxgi_grid_voxel_count(g) == 0) return VOXGI_ERR_INVALID_ARGUMENT;
    dmax = VOXGI__MAX(g->res[0], VOXGI__MAX(g->res[1], g->res[2]));
    /* %.17g round-trips every double */
    fprintf(f, "#binvox 1\ndim %d %d %d\ntranslate %.17g %.17g %.17g\nscale %.17g\ndata\n", g->res[0], g->res[2], g->res[1],
            g->origin[0], g->origin[1], g->origin[2], g->voxel_size * dmax);
    for (x = 0; x < g->res[0]; x++)
        for (z = 0; z < g->res[2]; z++)
            for (y = 0; y < g->res[1]; y++) {
                uint64_t idx = (uint64_t)x + (uint64_t)g->res[0] * ((uint64_t)y + (uint64_t)g->res[1] * (uint64_t)z);
                int b = voxgi_bit_get(bits, idx);
                if (b == value && run < 255) { run++; continue; }
                if (run) { fputc(value, f); fputc(run, f); }
                value = b;
                run = 1;
            }
    fputc(value, f);
    fputc(run, f);
    return ferror(f) ? VOXGI_ERR_IO : VOXGI_OK;
}

VOXGI_API voxgi_result voxgi_binvox_read(FILE *f, voxgi_grid *g, uint32_t *bits, size_t bits_bytes, size_t *needed)
{
    char line[256];
    int dims[3] = {0, 0, 0}, have_dim = 0, have_data = 0, dmax;
    double tr[3] = {0, 0, 0}, scale = 1;
    uint64_t total, at = 0, x = 0, y = 0, z = 0;
    if (!f || !g) return VOXGI_ERR_INVALID_ARGUMENT;
    if (!fgets(line, sizeof line, f) || strncmp(line, "#binvox", 7) != 0) return VOXGI_ERR_FORMAT;
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, "dim", 3) == 0) have_dim = sscanf(line + 3, "%d %d %d", &dims[0], &dims[1], &dims[2]) == 3;
        else if (strncmp(line, "translate", 9) == 0) { if (sscanf(line + 9, "%lf %lf %lf", &tr[0], &tr[1], &tr[2]) != 3) return VOXGI_ERR_FORMAT; }
        else if (strncmp(line, "scale", 5) == 0) { if (sscanf(line + 5, "%lf", &scale) != 1) return VOXGI_ERR_FORMAT; }
        else if (strncmp(line, "data", 4) == 0) { have_data = 1; break; }
        else return VOXGI_ERR_FORMAT;
    }
    if (!have_dim || !have_data || dims[0] < 1 || dims[1] < 1 || dims[2] < 1 || dims[0] > VOXGI_MAX_RES ||
        dims[1] > VOXGI_MAX_RES || dims[2] > VOXGI_MAX_RES || !(scale > 0) || !isfinite(scale))
        return VOXGI_ERR_FORMAT;
    /* binvox's dim line is depth (x), height (z), width (y) */
    g->res[0] = dims[0];
    g->res[2] = dims[1];
    g->res[1] = dims[2];
    g->origin[0] = tr[0];
    g->origin[1] = tr[1];
    g->origin[2] = tr[2];
    dmax = VOXGI__MAX(dims[0], VOXGI__MAX(dims[1], dims[2]));
    g->voxel_size = scale / dmax;
    /* a grid voxgi takes (voxgi_validate_grid's ranges), or the file is refused */
    if (!(fabs(tr[0]) <= 1e30 && fabs(tr[1]) <= 1e30 && fabs(tr[2]) <= 1e30 && g->voxel_size >= 1e-30 && g->voxel_size <= 1e30))
        return VOXGI_ERR_FORMAT;
    total = voxgi_grid_voxel_count(g);
    if ((total + 31) / 32 * 4 > (uint64_t)((size_t)-1 / 2)) return VOXGI_ERR_TOO_LARGE;
    if (needed) *needed = (size_t)((total + 31) / 32 * 4);
    if (!bits) return VOXGI_OK;
    if (bits_bytes < (size_t)((total + 31) / 32 * 4)) return VOXGI_ERR_BUFFER_TOO_SMALL;
    memset(bits, 0, (size_t)((total + 31) / 32 * 4));
    while (at < total) {
        int value = fgetc(f), count = fgetc(f);
        if (value == EOF || count == EOF || value > 1 || count == 0 || at + (uint64_t)count > total) return VOXGI_ERR_FORMAT;
        while (count--) {
            if (value) {
                uint64_t idx = x + (uint64_t)g->res[0] * (y + (uint64_t)g->res[1] * z);
                bits[idx >> 5] |= 1u << (idx & 31u);
            }
            at++;
            /* y runs fastest, then z, then x */
            if (++y == (uint64_t)g->res[1]) { y = 0; if (++z == (uint64_t)g->res[2]) { z = 0; x++; } }
        }
    }
    return VOXGI_OK;
}


#endif /* VOXGI__IMPLEMENTED */
#endif /* VOXGI_IMPLEMENTATION */

/*
MIT License

Copyright (c) 2026 the voxgi authors

Permission is hereby granted, free of charge, to any person obtaining a copy of this software and
associated documentation files (the "Software"), to deal in the Software without restriction,
including without limitation the rights to use, copy, modify, merge, publish, distribute,
sublicense, and/or sell copies of the Software, and to permit persons to whom the Software is
furnished to do so, subject to the following conditions:

The above copyright notice and this permission notice shall be included in all copies or
substantial portions of the Software.

THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR IMPLIED, INCLUDING BUT
NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY, FITNESS FOR A PARTICULAR PURPOSE AND
NONINFRINGEMENT. IN NO EVENT SHALL THE AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM,
DAMAGES OR OTHER LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM, OUT
OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE SOFTWARE.
*/
