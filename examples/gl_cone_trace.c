/* examples/gl_cone_trace.c - voxel cone tracing in the caller's own OpenGL 4.5 frame, the path an
   engine takes: its own context (here EGL without a window), its own G-buffer drawn by its own
   shaders (world positions and normals in two textures), then voxgi on that same context: the
   scene voxelized and lit on GL, and the indirect light gathered by cones at the G-buffer's pixels
   into the caller's texture (voxgi_cone_trace_gl). Prints the mean irradiance; writes it as a PNG
   when given a path. Exit 77: no GL 4.5 context can be made here.
       gl_cone_trace [out.png]
   Links the implementation object (build/voxgi_impl.o) and libEGL. */
#include "../voxgi.h"
#include "../tools/image_io.h" /* the voxgi tool's PNG writer (vxt_write_png) */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

/* The GL functions this program calls, through the same loader voxgi takes. */
#define GL_FUNCTIONS(X) X(PFNGLCREATESHADERPROC, glCreateShader) X(PFNGLSHADERSOURCEPROC, glShaderSource) \
    X(PFNGLCOMPILESHADERPROC, glCompileShader) X(PFNGLCREATEPROGRAMPROC, glCreateProgram) X(PFNGLATTACHSHADERPROC, glAttachShader) \
    X(PFNGLLINKPROGRAMPROC, glLinkProgram) X(PFNGLGETPROGRAMIVPROC, glGetProgramiv) X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog) \
    X(PFNGLUSEPROGRAMPROC, glUseProgram) X(PFNGLPROGRAMUNIFORM3FVPROC, glProgramUniform3fv) X(PFNGLCREATETEXTURESPROC, glCreateTextures) \
    X(PFNGLTEXTURESTORAGE2DPROC, glTextureStorage2D) X(PFNGLCREATEFRAMEBUFFERSPROC, glCreateFramebuffers) \
    X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, glNamedFramebufferTexture) X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, glNamedFramebufferDrawBuffers) \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, glClearNamedFramebufferfv) X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer) X(PFNGLVIEWPORTPROC, glViewport) \
    X(PFNGLENABLEPROC, glEnable) X(PFNGLCREATEVERTEXARRAYSPROC, glCreateVertexArrays) X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray) \
    X(PFNGLDRAWARRAYSPROC, glDrawArrays) X(PFNGLGETTEXTUREIMAGEPROC, glGetTextureImage)
#define GL_DECLARE(type, name) static type name;
#define GL_LOAD(type, name) name = (type)eglGetProcAddress(#name);
GL_FUNCTIONS(GL_DECLARE)

enum { W = 64, H = 64, VERTICES = 18 };
/* The scene: a corner of a room, three unit quads of two triangles each, facing in. */
static const float xyz[3 * VERTICES] = {0, 0, 0, 0, 0, 1, 1, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0,  /* the floor, y = 0 (white) */
                                        0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0,  /* the back wall, z = 0 (red) */
                                        0, 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1}; /* the left wall, x = 0 (green) */
static const uint32_t material_ids[VERTICES / 3] = {0, 0, 1, 1, 2, 2};
static const voxgi_material materials[3] = {{.albedo = {0.8f, 0.8f, 0.8f}}, {.albedo = {0.8f, 0.1f, 0.1f}}, {.albedo = {0.1f, 0.8f, 0.1f}}};
/* The G-buffer's shaders: a camera at eye looking at the corner (40 degrees), flat normals turned to the eye. */
static const char *vs = "#version 450 core\n layout(location = 0) uniform vec3 P[18]; out vec3 wp; flat out vec3 wn;\n"
    "const vec3 eye = vec3(1.8, 1.3, 2.2), f = normalize(vec3(0.4, 0.3, 0.4) - eye), r = normalize(cross(f, vec3(0, 1, 0))), u = cross(r, f);\n"
    "void main() { int t = gl_VertexID / 3 * 3; vec3 d;\n"
    "  wp = P[gl_VertexID]; d = wp - eye; wn = normalize(cross(P[t + 1] - P[t], P[t + 2] - P[t])); wn = faceforward(wn, d, wn);\n"
    "  gl_Position = vec4(dot(d, r) / 0.364, dot(d, u) / 0.364, (10.1 * dot(d, f) - 2.0) / 9.9, dot(d, f)); }\n"; /* tan 20 deg; near 0.1, far 10 */
static const char *fs = "#version 450 core\n in vec3 wp; flat in vec3 wn; layout(location = 0) out vec4 pos; layout(location = 1) out vec4 nrm;\n"
    "void main() { pos = vec4(wp, 1); nrm = vec4(wn, 0); }\n";

int main(int argc, char **argv)
{
    static const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    static const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                             EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    static const GLenum draw_buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    static const float zero[4] = {0, 0, 0, 0}, one = 1;
    static float irr[4 * W * H], nrm[4 * W * H], rgb[3 * W * H];
    EGLDisplay dpy = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    EGLConfig config = NULL; /* EGL_NO_CONFIG_KHR where no config is needed or found */
    EGLContext egl = EGL_NO_CONTEXT;
    EGLint count = 0;
    voxgi_mesh mesh = {.positions = xyz, .vertex_count = VERTICES, .material_ids = material_ids}; /* no indices: 3 vertices a triangle */
    voxgi_light sun = {.type = VOXGI_LIGHT_DIRECTIONAL, .direction = {-0.4f, -0.8f, -0.45f}, .intensity = {3, 3, 3}}; /* irradiance 3 */
    voxgi_scene scene = {.meshes = &mesh, .mesh_count = 1, .materials = materials, .material_count = 3, .lights = &sun, .light_count = 1};
    voxgi_desc desc = {0};
    voxgi_fit_desc fit = {.res = 32, .padding = 1}; /* 32 voxels along the longest side, an empty one at each end */
    voxgi_voxelize_desc vd = {.attributes = VOXGI_ATTRIBUTE_ALBEDO | VOXGI_ATTRIBUTE_NORMAL}; /* what light injection needs */
    voxgi_inject_desc id = {0}; /* zero fields: the defaults (the direct light, no bounce among the voxels) */
    voxgi_cone_desc cd = {0};   /* 16 cones, each a sixteenth of the cosine-weighted hemisphere */
    voxgi_radiance_source source = {0};
    voxgi_gl_gbuffer gb = {0};
    voxgi_context *ctx = NULL; voxgi_voxels *vox = NULL; voxgi_volume *vol = NULL;
    GLuint tex[4], fbo, vao, prog, shader;
    GLint linked = 0;
    char log[1024]; /* the shaders' link log */
    double sum[3] = {0, 0, 0};
    int i, a, surface = 0, finite = 1, ok;

    /* 1. The application's GL 4.5 core context: EGL on Mesa's surfaceless platform, no window. */
    if (dpy != EGL_NO_DISPLAY && eglInitialize(dpy, NULL, NULL) && eglBindAPI(EGL_OPENGL_API)) {
        eglChooseConfig(dpy, config_attribs, &config, 1, &count);
        egl = eglCreateContext(dpy, config, EGL_NO_CONTEXT, context_attribs);
    }
    if (egl == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, egl)) {
        printf("gl_cone_trace: skipped: no OpenGL 4.5 core context through EGL (error 0x%x)\n", (unsigned)eglGetError());
        return 77;
    }
    GL_FUNCTIONS(GL_LOAD)

    /* 2. Its G-buffer: positions and normals (RGBA32F) with a depth texture, and the texture voxgi writes. */
    glCreateTextures(GL_TEXTURE_2D, 4, tex);
    for (i = 0; i < 4; i++) glTextureStorage2D(tex[i], 1, i == 2 ? GL_DEPTH_COMPONENT32F : GL_RGBA32F, W, H);
    glCreateFramebuffers(1, &fbo);
    for (i = 0; i < 3; i++) glNamedFramebufferTexture(fbo, i == 2 ? GL_DEPTH_ATTACHMENT : GL_COLOR_ATTACHMENT0 + i, tex[i], 0);
    glNamedFramebufferDrawBuffers(fbo, 2, draw_buffers);
    prog = glCreateProgram();
    for (i = 0; i < 2; i++) {
        shader = glCreateShader(i ? GL_FRAGMENT_SHADER : GL_VERTEX_SHADER);
        glShaderSource(shader, 1, i ? &fs : &vs, NULL);
        glCompileShader(shader);
        glAttachShader(prog, shader);
    }
    glLinkProgram(prog);
    glGetProgramiv(prog, GL_LINK_STATUS, &linked);
    if (!linked) {
        glGetProgramInfoLog(prog, sizeof log, NULL, log);
        fprintf(stderr, "the G-buffer's shaders: %s\n", log);
        return 1;
    }
    glProgramUniform3fv(prog, 0, VERTICES, xyz);
    glCreateVertexArrays(1, &vao);
    for (i = 0; i < 2; i++) glClearNamedFramebufferfv(fbo, GL_COLOR, i, zero); /* normal (0, 0, 0): no surface there */
    glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &one);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, W, H);
    glEnable(GL_DEPTH_TEST);
    glUseProgram(prog);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, VERTICES);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);

    /* 3. voxgi on the same context: voxelize (albedo and normal), inject the sun's light, trace cones at the G-buffer. */
    desc.backend = VOXGI_BACKEND_GL; /* GL even on a software rasteriser (AUTO would take the CPU there) */
    desc.gl_get_proc_address = (voxgi_gl_loader)eglGetProcAddress;
    gb.position_texture = tex[0], gb.normal_texture = tex[1], gb.irradiance_texture = tex[3], gb.width = W, gb.height = H;
    ok = voxgi_create(&desc, &ctx) == VOXGI_OK && voxgi_fit_grid(ctx, &scene, &fit, &vd.grid) == VOXGI_OK &&
         voxgi_voxelize(ctx, &scene, &vd, &vox) == VOXGI_OK && voxgi_inject_light(ctx, &scene, vox, &id, &vol) == VOXGI_OK;
    source.volume = vol; /* the cones gather from the radiance volume's mips (or from an octree of it: source.octree) */
    ok = ok && voxgi_cone_trace_gl(ctx, &source, &cd, &gb) == VOXGI_OK;
    if (!ok) fprintf(stderr, "voxgi: %s\n", ctx ? voxgi_last_error(ctx) : "no context");

    /* 4. Read the irradiance back (rgb; occlusion in alpha) where the G-buffer has a surface. */
    if (ok) {
        glGetTextureImage(tex[3], 0, GL_RGBA, GL_FLOAT, sizeof irr, irr);
        glGetTextureImage(tex[1], 0, GL_RGBA, GL_FLOAT, sizeof nrm, nrm);
        for (i = 0; i < W * H; i++) {
            for (a = 0; a < 4; a++) finite &= isfinite(irr[4 * i + a]) != 0;
            if (nrm[4 * i] == 0 && nrm[4 * i + 1] == 0 && nrm[4 * i + 2] == 0) continue;
            surface++;
            for (a = 0; a < 3; a++) sum[a] += irr[4 * i + a];
        }
        printf("%d of %d x %d pixels see a surface; mean irradiance %.4f %.4f %.4f, %s\n", surface, W, H, sum[0] / (surface ? surface : 1),
               sum[1] / (surface ? surface : 1), sum[2] / (surface ? surface : 1), finite ? "all finite" : "NOT FINITE");
        for (i = 0; i < W * H; i++) /* rows from the top for the PNG; GL's start at the bottom */
            for (a = 0; a < 3; a++) rgb[3 * i + a] = irr[4 * ((H - 1 - i / W) * W + i % W) + a];
        if (argc > 1 && vxt_write_png(argv[1], rgb, W, H, 1.0f) != 0) ok = 0, fprintf(stderr, "cannot write %s\n", argv[1]);
    }
    voxgi_volume_destroy(ctx, vol);
    voxgi_voxels_destroy(ctx, vox);
    voxgi_destroy(ctx);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, egl);
    eglTerminate(dpy);
    return ok && finite ? 0 : 1;
}
