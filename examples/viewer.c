/* examples/viewer.c - a window onto voxgi's images (GLFW, OpenGL 4.5 core): a built-in scene or a
   mesh file (voxgi_io.h), orbited with the mouse, lit by a light the mouse moves, rendered by voxel
   cone tracing on the window's own GL context (voxgi_render on GL) or by the direct light or the
   path-traced reference, shown as a texture on the window; or the voxels themselves, drawn as
   cubes (one instanced draw of their outer faces, coloured by the voxels' albedo).
       viewer [SCENE|MESH] [options]      (viewer --help lists them and the keys)
   Headless (tests, Xvfb): --frames N --screenshot out.ppm|out.png draws N frames, saves the last
   one's pixels as the window shows them (glReadPixels) and exits. Exit 77: no window or no GL 4.5
   core context here. The scene is re-rendered only when the view, the light, the method or the
   window's size changes; its voxels are made once (voxgi_render_voxelize) and only the light is
   injected again. --voxels-npy PREFIX saves the voxels shown (PREFIX.npy, PREFIX.albedo.npy) and
   prints their grid, so a test can draw them its own way. Links the implementation object
   (build/voxgi_impl.o) and GLFW. */
#include "../voxgi.h"
#include "../voxgi_io.h"       /* the mesh loaders */
#include "../tools/image_io.h" /* the voxgi tool's PNG writer (vxt_write_png8) */
#define GLFW_INCLUDE_GLCOREARB
#include <GLFW/glfw3.h>

/* The GL functions this program calls, through GLFW's loader (voxgi takes the same). */
#define GL_FUNCTIONS(X) X(PFNGLCREATESHADERPROC, glCreateShader) X(PFNGLSHADERSOURCEPROC, glShaderSource) \
    X(PFNGLCOMPILESHADERPROC, glCompileShader) X(PFNGLCREATEPROGRAMPROC, glCreateProgram) X(PFNGLATTACHSHADERPROC, glAttachShader) \
    X(PFNGLLINKPROGRAMPROC, glLinkProgram) X(PFNGLGETPROGRAMIVPROC, glGetProgramiv) X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog) \
    X(PFNGLUSEPROGRAMPROC, glUseProgram) X(PFNGLPROGRAMUNIFORM1FPROC, glProgramUniform1f) X(PFNGLCREATETEXTURESPROC, glCreateTextures) \
    X(PFNGLTEXTURESTORAGE2DPROC, glTextureStorage2D) X(PFNGLTEXTURESUBIMAGE2DPROC, glTextureSubImage2D) X(PFNGLDELETETEXTURESPROC, glDeleteTextures) \
    X(PFNGLBINDTEXTUREUNITPROC, glBindTextureUnit) X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer) X(PFNGLVIEWPORTPROC, glViewport) \
    X(PFNGLDISABLEPROC, glDisable) X(PFNGLCREATEVERTEXARRAYSPROC, glCreateVertexArrays) X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray) \
    X(PFNGLDRAWARRAYSPROC, glDrawArrays) X(PFNGLREADBUFFERPROC, glReadBuffer) X(PFNGLPIXELSTOREIPROC, glPixelStorei) \
    X(PFNGLREADPIXELSPROC, glReadPixels) X(PFNGLCLEARCOLORPROC, glClearColor) X(PFNGLCLEARPROC, glClear) X(PFNGLGETSTRINGPROC, glGetString) \
    X(PFNGLCREATEBUFFERSPROC, glCreateBuffers) X(PFNGLNAMEDBUFFERDATAPROC, glNamedBufferData) X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers) \
    X(PFNGLBINDBUFFERBASEPROC, glBindBufferBase) X(PFNGLDRAWARRAYSINSTANCEDPROC, glDrawArraysInstanced) X(PFNGLENABLEPROC, glEnable) \
    X(PFNGLPROGRAMUNIFORMMATRIX4FVPROC, glProgramUniformMatrix4fv) X(PFNGLPROGRAMUNIFORM3FPROC, glProgramUniform3f)
#define GL_DECLARE(type, name) static type name;
#define GL_LOAD(type, name) name = (type)glfwGetProcAddress(#name);
GL_FUNCTIONS(GL_DECLARE)

/* The image shown: the render's linear radiance (rows from the top) through the same sRGB transfer
   the tool's PNGs take (tools/image_io.h), so a screenshot matches `voxgi render -o x.png`. */
static const char *vs = "#version 450 core\n"
    "void main() { vec2 p = vec2(gl_VertexID == 1 ? 3 : -1, gl_VertexID == 2 ? 3 : -1); gl_Position = vec4(p, 0, 1); }\n";
static const char *fs = "#version 450 core\n layout(binding = 0) uniform sampler2D image; layout(location = 0) uniform float exposure;\n"
    "out vec4 colour;\n"
    "void main() { ivec2 n = textureSize(image, 0), p = ivec2(gl_FragCoord.xy); vec3 c = vec3(0);\n"
    "  if (p.x < n.x && p.y < n.y) c = clamp(exposure * texelFetch(image, ivec2(p.x, n.y - 1 - p.y), 0).rgb, 0.0, 1.0);\n"
    "  colour = vec4(mix(12.92 * c, 1.055 * pow(c, vec3(1 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308))), 1); }\n";

/* The voxels as cubes: one instance per voxel with an outer face, 36 vertices (6 faces x 2 triangles),
   a face between two set voxels collapsed to a point. Each face's colour is the voxel's albedo
   times a fixed shade per face direction (+x -x +y -y +z -z: the top brightest, the bottom darkest),
   through the same transfer as the image (and tests/viewer_voxels.py's ray cast). */
static const char *cube_vs = "#version 450 core\n"
    "struct voxel { ivec4 at_faces; vec4 albedo; };\n"
    "layout(std430, binding = 0) readonly buffer voxels { voxel v[]; };\n"
    "layout(location = 0) uniform mat4 view_projection;\n"
    "layout(location = 1) uniform vec3 origin;\n"
    "layout(location = 2) uniform float voxel_size;\n"
    "out vec3 colour;\n"
    "const float shade[6] = float[](0.8, 0.8, 1.0, 0.5, 0.65, 0.65);\n"
    "const int corner[6] = int[](0, 1, 2, 0, 2, 3);\n"
    "void main() {\n"
    "  voxel x = v[gl_InstanceID]; int face = gl_VertexID / 6, axis = face / 2, c = corner[gl_VertexID % 6];\n"
    "  int u = (axis + 1) % 3, w = (axis + 2) % 3;\n"
    "  vec3 p = vec3(0); p[axis] = (face & 1) == 0 ? 1.0 : 0.0;\n"
    "  p[u] = (c == 1 || c == 2) ? 1.0 : 0.0; p[w] = c >= 2 ? 1.0 : 0.0;\n"
    "  colour = x.albedo.rgb * shade[face];\n"
    "  gl_Position = ((x.at_faces.w >> face) & 1) != 0 ? view_projection * vec4(origin + voxel_size * (vec3(x.at_faces.xyz) + p), 1) : vec4(0, 0, 2, 1);\n"
    "}\n";
static const char *cube_fs = "#version 450 core\n layout(location = 3) uniform float exposure;\n in vec3 colour; out vec4 frag;\n"
    "void main() { vec3 c = clamp(exposure * colour, 0.0, 1.0);\n"
    "  frag = vec4(mix(12.92 * c, 1.055 * pow(c, vec3(1 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308))), 1); }\n";

/* The methods a key steps through: cone tracing (on GL), the direct light alone, the reference, the voxels. */
typedef struct method { const char *name; voxgi_render_method method; int direct_only, voxels; } method;
static const method methods[] = {{"vct", VOXGI_RENDER_VCT, 0, 0}, {"direct", VOXGI_RENDER_VCT, 1, 0}, {"reference", VOXGI_RENDER_REFERENCE, 0, 0},
                                 {"voxels", VOXGI_RENDER_VCT, 0, 1}};
enum { METHODS = sizeof methods / sizeof methods[0] };

static const char *keys = "keys: left drag orbit, scroll zoom, right drag (or shift + left drag) move the light, "
                          "M next method (1 vct, 2 direct, 3 reference, 4 voxels), +/- exposure, R reset, P screenshot viewer.png, Q quit";

/* What the callbacks change. */
typedef struct viewer {
    voxgi_camera camera, home;    /* the view, and the one R returns to */
    voxgi_light *lights;          /* the scene's lights and room for a sun */
    voxgi_light home_light;
    size_t light_count, home_count;
    int moving;                   /* the light the mouse moves, or -1 (none yet: the first light drag adds a sun) */
    double radius;                /* the scene's bounding sphere, for the light's steps */
    int method, dirty, dragging, save;
    double x, y;                  /* the cursor where the drag last was */
    float exposure;
} viewer;

static void normalize3(double v[3]) { double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); if (l > 0) v[0] /= l, v[1] /= l, v[2] /= l; }
/* The camera's right and up (a voxgi_camera is +Y up). */
static void camera_frame(const voxgi_camera *c, double right[3], double up[3])
{
    double f[3] = {c->target[0] - c->eye[0], c->target[1] - c->eye[1], c->target[2] - c->eye[2]};
    normalize3(f);
    right[0] = -f[2], right[1] = 0, right[2] = f[0];
    normalize3(right);
    up[0] = right[1] * f[2] - right[2] * f[1], up[1] = right[2] * f[0] - right[0] * f[2], up[2] = right[0] * f[1] - right[1] * f[0];
}

/* A sun from the camera's upper left, irradiance pi (as `voxgi render` adds to an unlit scene). */
static voxgi_light default_sun(const voxgi_camera *c)
{
    voxgi_light sun = {.type = VOXGI_LIGHT_DIRECTIONAL, .intensity = {3.14159265f, 3.14159265f, 3.14159265f}};
    double f[3] = {c->target[0] - c->eye[0], c->target[1] - c->eye[1], c->target[2] - c->eye[2]}, r[3], u[3];
    int k;
    normalize3(f);
    camera_frame(c, r, u);
    for (k = 0; k < 3; k++) f[k] += r[k] - u[k]; /* the light travels forward, to the right and down */
    normalize3(f);
    for (k = 0; k < 3; k++) sun.direction[k] = (float)f[k];
    return sun;
}

/* Turns v about the world's Y by yaw and up or down by pitch (its elevation kept within 80 degrees). */
static void orbit(double v[3], double yaw, double pitch)
{
    double r = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]), az = atan2(v[0], v[2]), el = asin(v[1] / r);
    az += yaw;
    el = fmax(-1.4, fmin(1.4, el + pitch));
    v[0] = r * cos(el) * sin(az), v[1] = r * sin(el), v[2] = r * cos(el) * cos(az);
}

static void on_drag(GLFWwindow *w, double x, double y)
{
    viewer *v = (viewer *)glfwGetWindowUserPointer(w);
    double dx = x - v->x, dy = y - v->y, right[3], up[3], d[3];
    int k, light = v->dragging == 2;
    v->x = x, v->y = y;
    if (!v->dragging || (dx == 0 && dy == 0)) return;
    if (light && v->moving < 0) { /* the scene's light is its emitters only: the drag adds a sun to move */
        v->lights[v->light_count] = default_sun(&v->camera);
        v->moving = (int)v->light_count++;
        printf("viewer: added a sun from the camera's upper left; the right drag moves it\n");
    }
    if (light) {
        voxgi_light *l = &v->lights[v->moving];
        if (l->type == VOXGI_LIGHT_DIRECTIONAL) {
            for (k = 0; k < 3; k++) d[k] = l->direction[k];
            orbit(d, 0.01 * dx, 0.01 * dy);
            for (k = 0; k < 3; k++) l->direction[k] = (float)d[k];
        } else { /* point, spot and rect lights slide in the view's plane */
            camera_frame(&v->camera, right, up);
            for (k = 0; k < 3; k++) l->position[k] += (float)(v->radius * 0.004 * (dx * right[k] - dy * up[k]));
        }
    } else {
        for (k = 0; k < 3; k++) d[k] = v->camera.eye[k] - v->camera.target[k];
        orbit(d, -0.01 * dx, 0.01 * dy);
        for (k = 0; k < 3; k++) v->camera.eye[k] = v->camera.target[k] + d[k];
    }
    v->dirty = 1;
}

static void on_button(GLFWwindow *w, int button, int action, int mods)
{
    viewer *v = (viewer *)glfwGetWindowUserPointer(w);
    glfwGetCursorPos(w, &v->x, &v->y);
    if (action == GLFW_RELEASE) v->dragging = 0;
    else if (button == GLFW_MOUSE_BUTTON_RIGHT || (button == GLFW_MOUSE_BUTTON_LEFT && (mods & GLFW_MOD_SHIFT))) v->dragging = 2;
    else if (button == GLFW_MOUSE_BUTTON_LEFT) v->dragging = 1;
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    viewer *v = (viewer *)glfwGetWindowUserPointer(w);
    int k;
    (void)dx;
    for (k = 0; k < 3; k++) v->camera.eye[k] = v->camera.target[k] + (v->camera.eye[k] - v->camera.target[k]) * pow(0.9, dy);
    v->dirty = 1;
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    viewer *v = (viewer *)glfwGetWindowUserPointer(w);
    (void)scancode, (void)mods;
    if (action != GLFW_PRESS) return;
    switch (key) {
    case GLFW_KEY_M: v->method = (v->method + 1) % METHODS, v->dirty = 1; break;
    case GLFW_KEY_1: case GLFW_KEY_2: case GLFW_KEY_3: case GLFW_KEY_4: v->method = key - GLFW_KEY_1, v->dirty = 1; break;
    case GLFW_KEY_EQUAL: case GLFW_KEY_KP_ADD: v->exposure *= 1.25f; break;
    case GLFW_KEY_MINUS: case GLFW_KEY_KP_SUBTRACT: v->exposure /= 1.25f; break;
    case GLFW_KEY_R:
        v->camera = v->home, v->light_count = v->home_count, v->exposure = 1, v->dirty = 1;
        if (v->home_count) v->lights[0] = v->home_light;
        if (v->moving >= (int)v->home_count) v->moving = -1;
        break;
    case GLFW_KEY_P: v->save = 1; break;
    case GLFW_KEY_Q: case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(w, 1); break;
    default: break;
    }
}

/* The cubes' instances (as cube_vs reads them): every set voxel with a face on an empty voxel or the
   grid's edge, that face mask and its albedo (0.8 grey where the voxels hold none). Returns the
   instances into *buffer and their count, or -1 (voxgi's message printed). */
typedef struct cube { int32_t at_faces[4]; float albedo[4]; } cube;
static long cube_instances(voxgi_context *ctx, const voxgi_voxels *vox, GLuint *buffer)
{
    voxgi_voxels_info in;
    uint32_t *bits = NULL;
    float *albedo = NULL;
    cube *cubes = NULL;
    size_t bytes = 0, set = 0, n = 0;
    long count = -1;
    int64_t c[3], res[3];
    int a, f;
    voxgi_voxels_query(vox, &in);
    for (a = 0; a < 3; a++) res[a] = in.grid.res[a];
    if (voxgi_voxels_read(ctx, vox, NULL, 0, &bytes) != VOXGI_OK || !(bits = (uint32_t *)malloc(bytes)) ||
        voxgi_voxels_read(ctx, vox, bits, bytes, NULL) != VOXGI_OK)
        goto done;
    if ((in.attributes & VOXGI_ATTRIBUTE_ALBEDO) &&
        (!(albedo = (float *)malloc(in.voxel_count * 12 + 12)) ||
         voxgi_voxels_read_attribute(ctx, vox, VOXGI_ATTRIBUTE_ALBEDO, albedo, in.voxel_count * 12 + 12, NULL) != VOXGI_OK))
        goto done;
    if (!(cubes = (cube *)malloc((in.voxel_count + 1) * sizeof *cubes))) goto done;
    for (c[2] = 0; c[2] < res[2]; c[2]++)
        for (c[1] = 0; c[1] < res[1]; c[1]++)
            for (c[0] = 0; c[0] < res[0]; c[0]++) {
                int faces = 0;
                if (!voxgi_bit_get(bits, (uint64_t)(c[0] + res[0] * (c[1] + res[1] * c[2])))) continue;
                for (f = 0; f < 6; f++) { /* +x -x +y -y +z -z: the neighbour across the face */
                    int64_t q[3] = {c[0], c[1], c[2]};
                    q[f / 2] += f & 1 ? -1 : 1;
                    if (q[f / 2] < 0 || q[f / 2] >= res[f / 2] || !voxgi_bit_get(bits, (uint64_t)(q[0] + res[0] * (q[1] + res[1] * q[2])))) faces |= 1 << f;
                }
                if (faces) {
                    cube *x = &cubes[n++];
                    for (a = 0; a < 3; a++) {
                        x->at_faces[a] = (int32_t)c[a];
                        x->albedo[a] = albedo ? albedo[3 * set + (size_t)a] : 0.8f;
                    }
                    x->at_faces[3] = faces, x->albedo[3] = 1;
                }
                set++;
            }
    glCreateBuffers(1, buffer);
    glNamedBufferData(*buffer, (GLsizeiptr)((n ? n : 1) * sizeof *cubes), cubes, GL_STATIC_DRAW);
    count = (long)n;
done:
    if (count < 0) fprintf(stderr, "viewer: the voxels: %s\n", voxgi_last_error(ctx));
    free(bits);
    free(albedo);
    free(cubes);
    return count;
}

/* The camera's view and projection (gluLookAt up +Y, gluPerspective) in column-major order, so that a
   pixel's centre sees along voxgi's ray through it; near and far bound the box [lo, hi]. */
static void view_projection(const voxgi_camera *c, int w, int h, const double lo[3], const double hi[3], float m[16])
{
    double f[3] = {c->target[0] - c->eye[0], c->target[1] - c->eye[1], c->target[2] - c->eye[2]}, r[3], u[3], far = 0, near, t, p[16], v[16];
    int i, j, k;
    normalize3(f);
    camera_frame(c, r, u);
    for (k = 0; k < 3; k++) far += fmax((lo[k] - c->eye[k]) * (lo[k] - c->eye[k]), (hi[k] - c->eye[k]) * (hi[k] - c->eye[k]));
    far = 1.01 * sqrt(far);
    near = far * 1e-4;
    t = 1 / tan(c->fovy_degrees * 3.14159265358979 / 360);
    memset(p, 0, sizeof p);
    memset(v, 0, sizeof v);
    p[0] = t * h / w, p[5] = t, p[10] = -(far + near) / (far - near), p[11] = -1, p[14] = -2 * far * near / (far - near);
    for (k = 0; k < 3; k++) {
        v[4 * k] = r[k], v[4 * k + 1] = u[k], v[4 * k + 2] = -f[k];
        v[12] -= r[k] * c->eye[k], v[13] -= u[k] * c->eye[k], v[14] += f[k] * c->eye[k];
    }
    v[15] = 1;
    for (i = 0; i < 4; i++) /* column i of p * v */
        for (j = 0; j < 4; j++) {
            double s = 0;
            for (k = 0; k < 4; k++) s += p[4 * k + j] * v[4 * i + k];
            m[4 * i + j] = (float)s;
        }
}

/* A program from a vertex and a fragment shader's source; 0 (its log printed) when it does not link. */
static GLuint program(const char *vertex, const char *fragment)
{
    GLuint prog = glCreateProgram(), shader;
    GLint linked = 0;
    char log[1024];
    int i;
    for (i = 0; i < 2; i++) {
        shader = glCreateShader(i ? GL_FRAGMENT_SHADER : GL_VERTEX_SHADER);
        glShaderSource(shader, 1, i ? &fragment : &vertex, NULL);
        glCompileShader(shader);
        glAttachShader(prog, shader);
    }
    glLinkProgram(prog);
    glGetProgramiv(prog, GL_LINK_STATUS, &linked);
    if (linked) return prog;
    glGetProgramInfoLog(prog, sizeof log, NULL, log);
    fprintf(stderr, "viewer: a display shader: %s\n", log);
    return 0;
}

/* The window's pixels (the back buffer, as drawn) into a PPM or PNG, rows from the top; 0 on success. */
static int save_pixels(const char *path, int w, int h)
{
    unsigned char *px = (unsigned char *)malloc((size_t)w * (size_t)h * 3), *rows = (unsigned char *)malloc((size_t)w * (size_t)h * 3);
    size_t len = strlen(path), stride = (size_t)w * 3;
    int y, rc = -1;
    FILE *f;
    if (px && rows) {
        glReadBuffer(GL_BACK);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, px);
        for (y = 0; y < h; y++) memcpy(rows + (size_t)y * stride, px + (size_t)(h - 1 - y) * stride, stride); /* GL's rows start at the bottom */
        if (len > 4 && strcmp(path + len - 4, ".png") == 0) {
            rc = vxt_write_png8(path, rows, w, h);
        } else if ((f = fopen(path, "wb")) != NULL) {
            rc = fprintf(f, "P6\n%d %d\n255\n", w, h) > 0 && fwrite(rows, stride, (size_t)h, f) == (size_t)h ? 0 : -1;
            if (fclose(f) != 0) rc = -1;
        }
    }
    free(px);
    free(rows);
    return rc;
}

static int usage(FILE *to)
{
    fprintf(to, "usage: viewer [SCENE|MESH] [options]\n"
                "  SCENE: a built-in scene (%s; default cornell-box), MESH: .obj .off .stl .ply .gltf .glb\n"
                "  --method vct|direct|reference|voxels  the first method (default vct: cone tracing on GL)\n"
                "  --size W H                      the window's size in pixels (default 256 256)\n"
                "  --camera EX EY EZ TX TY TZ FOVY the first view (default: the scene's, or the mesh framed)\n"
                "  --spp N                         reference: paths per pixel (default 4)\n"
                "  --frames N                      draw N frames, then exit (headless runs, tests)\n"
                "  --screenshot OUT.ppm|OUT.png    with --frames: save the last frame's pixels\n"
                "  --voxels-npy PREFIX             save the voxels (PREFIX.npy occupancy, PREFIX.albedo.npy) and print their grid\n"
                "%s\n", voxgi_builtin_scene_names(), keys);
    return to == stdout ? 0 : 2;
}

int main(int argc, char **argv)
{
    const char *what = "cornell-box", *shot = NULL, *voxels_npy = NULL;
    int size[2] = {256, 256}, frames = 0, spp = 4, have_camera = 0, i, k, ok = 1, frame, lit = 0, fw = 0, fh = 0, w = 0, h = 0, rc = 0;
    double cam[7];
    viewer v;
    voxgi_builtin_scene bs;
    voxgi_io_mesh m;
    voxgi_scene scene;
    voxgi_desc desc = {0};
    voxgi_context *ctx = NULL;
    voxgi_voxels *voxels = NULL;
    GLFWwindow *win;
    GLuint prog, cube_prog, vao, tex = 0, cube_buffer = 0;
    long cubes = -1;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    float *rgb = NULL;
    char err[512], line[1024];

    memset(&v, 0, sizeof v);
    memset(&bs, 0, sizeof bs);
    memset(&m, 0, sizeof m);
    v.exposure = 1;
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        int more = argc - 1 - i;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) return usage(stdout);
        if (strcmp(a, "--method") == 0 && more >= 1) {
            for (v.method = 0; v.method < METHODS && strcmp(methods[v.method].name, argv[i + 1]) != 0; v.method++) {}
            if (v.method == METHODS) return usage(stderr);
            i++;
        } else if (strcmp(a, "--size") == 0 && more >= 2) {
            size[0] = atoi(argv[++i]), size[1] = atoi(argv[++i]);
            if (size[0] < 1 || size[1] < 1 || size[0] > 16384 || size[1] > 16384) return usage(stderr);
        } else if (strcmp(a, "--camera") == 0 && more >= 7) {
            for (k = 0; k < 7; k++) cam[k] = atof(argv[++i]);
            have_camera = 1;
        } else if (strcmp(a, "--spp") == 0 && more >= 1) {
            if ((spp = atoi(argv[++i])) < 1) return usage(stderr);
        } else if (strcmp(a, "--frames") == 0 && more >= 1) {
            if ((frames = atoi(argv[++i])) < 1) return usage(stderr);
        } else if (strcmp(a, "--screenshot") == 0 && more >= 1) {
            shot = argv[++i];
        } else if (strcmp(a, "--voxels-npy") == 0 && more >= 1) {
            voxels_npy = argv[++i];
        } else if (a[0] != '-') {
            what = a;
        } else {
            return usage(stderr);
        }
    }
    if (shot && !frames) {
        fprintf(stderr, "viewer: --screenshot needs --frames N\n");
        return 2;
    }

    /* 1. The window and its GL 4.5 core context; voxgi on the same context. */
    if (!glfwInit()) {
        printf("viewer: skipped: no window system (GLFW cannot start; is DISPLAY set?)\n");
        return 77;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_RESIZABLE, frames ? GLFW_FALSE : GLFW_TRUE);
    if ((win = glfwCreateWindow(size[0], size[1], "voxgi viewer", NULL, NULL)) == NULL) {
        printf("viewer: skipped: no OpenGL 4.5 core context on this display\n");
        glfwTerminate();
        return 77;
    }
    glfwMakeContextCurrent(win);
    glfwSwapInterval(frames ? 0 : 1);
    GL_FUNCTIONS(GL_LOAD)
    printf("viewer: %s\n", (const char *)glGetString(GL_RENDERER));
    desc.backend = VOXGI_BACKEND_GL; /* GL even on a software rasteriser (AUTO would take the CPU there) */
    desc.gl_get_proc_address = (voxgi_gl_loader)glfwGetProcAddress;
    if (voxgi_create(&desc, &ctx) != VOXGI_OK) {
        fprintf(stderr, "viewer: voxgi on this GL context: %s\n", ctx ? voxgi_last_error(ctx) : "no context");
        rc = 1;
        goto done;
    }

    /* 2. The scene: built in, or a mesh file framed from a three-quarter view above its front. */
    if (strchr(what, '.') == NULL) {
        if (voxgi_builtin_scene_create(ctx, what, &bs) != VOXGI_OK) {
            fprintf(stderr, "viewer: %s\n", voxgi_last_error(ctx));
            rc = 2;
            goto done;
        }
        scene = bs.scene, v.camera = bs.camera;
    } else {
        if (voxgi_io_load_mesh(what, &m, err, sizeof err) != 0) {
            fprintf(stderr, "%s\n", err);
            rc = 1;
            goto done;
        }
        scene = voxgi_io_mesh_scene(&m);
        if (!scene.mesh_count) {
            fprintf(stderr, "viewer: %s has no triangles\n", what);
            rc = 1;
            goto done;
        }
        v.camera.width = size[0], v.camera.height = size[1];
    }
    /* The scene's box (positions as given: voxgi_scene.origin is zero here), to frame a mesh and bound the cubes' depth. */
    for (i = 0; i < (int)scene.mesh_count; i++) {
        const voxgi_mesh *mesh = &scene.meshes[i];
        size_t j;
        for (j = 0; mesh->positions && j < mesh->vertex_count; j++)
            for (k = 0; k < 3; k++) lo[k] = fmin(lo[k], mesh->positions[3 * j + (size_t)k]), hi[k] = fmax(hi[k], mesh->positions[3 * j + (size_t)k]);
    }
    if (m.vertex_count) voxgi_camera_frame_bounds(lo, hi, &v.camera);
    if (have_camera) {
        for (k = 0; k < 3; k++) v.camera.eye[k] = cam[k], v.camera.target[k] = cam[3 + k];
        v.camera.fovy_degrees = cam[6];
    }
    v.radius = 0;
    for (k = 0; k < 3; k++) v.radius += (v.camera.eye[k] - v.camera.target[k]) * (v.camera.eye[k] - v.camera.target[k]);
    v.radius = 0.5 * sqrt(v.radius); /* about the scene's size: a framed view stands a few radii off */
    /* The lights: the scene's (the mouse moves the first), or a sun where nothing lights the scene. */
    v.lights = (voxgi_light *)calloc(scene.light_count + 1, sizeof *v.lights);
    if (!v.lights) { rc = 1; goto done; }
    if (scene.light_count) memcpy(v.lights, scene.lights, scene.light_count * sizeof *v.lights);
    v.light_count = scene.light_count, v.moving = scene.light_count ? 0 : -1;
    for (i = 0; i < (int)scene.mesh_count && scene.materials && !lit; i++) {
        const voxgi_mesh *mesh = &scene.meshes[i];
        size_t t, n = mesh->indices ? mesh->index_count / 3 : mesh->vertex_count / 3;
        for (t = 0; t < n && !lit; t++) {
            uint32_t id = mesh->material_ids ? mesh->material_ids[t] : mesh->material;
            for (k = 0; k < 3 && id < scene.material_count; k++) lit |= scene.materials[id].emission[k] > 0;
        }
    }
    if (!v.light_count && !lit) {
        v.lights[0] = default_sun(&v.camera), v.light_count = 1, v.moving = 0;
        printf("viewer: no light or emitter in the scene: added a sun from the camera's upper left\n");
    }
    v.home = v.camera, v.home_count = v.light_count, v.home_light = v.lights[0];
    scene.lights = v.lights;

    /* 3. The programs that show the image and the cubes. */
    if (!(prog = program(vs, fs)) || !(cube_prog = program(cube_vs, cube_fs))) {
        rc = 1;
        goto done;
    }
    glCreateVertexArrays(1, &vao);
    glfwSetWindowUserPointer(win, &v);
    glfwSetCursorPosCallback(win, on_drag);
    glfwSetMouseButtonCallback(win, on_button);
    glfwSetScrollCallback(win, on_scroll);
    glfwSetKeyCallback(win, on_key);
    printf("%s\n", keys);

    /* 4. The frames: render when something changed, then show the image. */
    v.dirty = 1;
    for (frame = 0; ok && !glfwWindowShouldClose(win) && (!frames || frame < frames); frame++) {
        glfwGetFramebufferSize(win, &fw, &fh);
        if (fw < 1 || fh < 1) { glfwWaitEvents(); continue; } /* minimised */
        if (fw != w || fh != h) v.dirty = 1;
        if (v.dirty) {
            voxgi_render_desc d;
            voxgi_render_info info;
            const method *me = &methods[v.method];
            memset(&d, 0, sizeof d);
            d.method = me->method;
            d.direct_only = me->direct_only;
            d.camera = v.camera;
            d.camera.width = fw, d.camera.height = fh;
            if (me->method == VOXGI_RENDER_REFERENCE) d.samples = spp;
            scene.light_count = v.light_count;
            /* the geometry stands still: its voxels once, then only the light is injected again */
            if ((me->method == VOXGI_RENDER_VCT || voxels_npy) && !voxels) {
                voxgi_voxels_info in;
                if (voxgi_render_voxelize(ctx, &scene, &d, &voxels) != VOXGI_OK) {
                    fprintf(stderr, "viewer: voxgi: %s\n", voxgi_last_error(ctx));
                    rc = 1;
                    break;
                }
                voxgi_voxels_query(voxels, &in);
                printf("viewer: voxels %d x %d x %d, origin %.9g %.9g %.9g, voxel size %.9g, %llu set\n", in.grid.res[0], in.grid.res[1], in.grid.res[2],
                       in.grid.origin[0], in.grid.origin[1], in.grid.origin[2], in.grid.voxel_size, (unsigned long long)in.voxel_count);
                if (voxels_npy) {
                    snprintf(line, sizeof line, "%s.npy", voxels_npy);
                    if (voxgi_io_write_npy(ctx, voxels, line, err, sizeof err) == 0) {
                        snprintf(line, sizeof line, "%s.albedo.npy", voxels_npy);
                        if (voxgi_io_write_npy_attribute(ctx, voxels, VOXGI_ATTRIBUTE_ALBEDO, line, err, sizeof err) == 0) err[0] = 0;
                    }
                    if (err[0]) {
                        fprintf(stderr, "viewer: %s\n", err);
                        rc = 1;
                        break;
                    }
                }
            }
            if (me->method == VOXGI_RENDER_VCT) d.voxels = voxels;
            if (me->voxels) { /* the cubes: their instances once, drawn below every frame */
                if (cubes < 0 && (cubes = cube_instances(ctx, voxels, &cube_buffer)) < 0) {
                    rc = 1;
                    break;
                }
                snprintf(line, sizeof line, "voxgi viewer - voxels: %ld cubes - M method, left drag orbit, +/- exposure, P screenshot", cubes);
                glfwSetWindowTitle(win, line);
                v.dirty = 0;
                goto draw;
            }
            if (fw != w || fh != h) {
                free(rgb);
                glDeleteTextures(1, &tex);
                w = fw, h = fh;
                rgb = (float *)malloc((size_t)w * (size_t)h * 12);
                glCreateTextures(GL_TEXTURE_2D, 1, &tex);
                glTextureStorage2D(tex, 1, GL_RGB32F, w, h);
            }
            ok = rgb != NULL && voxgi_render(ctx, &scene, &d, rgb, (size_t)w * (size_t)h * 12, &info) == VOXGI_OK;
            if (!ok) {
                fprintf(stderr, "viewer: voxgi: %s\n", voxgi_last_error(ctx));
                rc = 1;
                break;
            }
            voxgi_render_describe(&info.used, line, sizeof line);
            printf("%s (%.0f ms)\n", line, info.ms);
            snprintf(line, sizeof line, "voxgi viewer - %s %.0f ms - M method, left drag orbit, right drag light, +/- exposure, P screenshot",
                     me->name, info.ms);
            glfwSetWindowTitle(win, line);
            glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
            glTextureSubImage2D(tex, 0, 0, 0, w, h, GL_RGB, GL_FLOAT, rgb);
            v.dirty = 0;
        }
    draw:
        /* voxgi leaves its own GL state bound: set all this pass needs */
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, fw, fh);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_CULL_FACE);
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glBindVertexArray(vao);
        if (methods[v.method].voxels) { /* the cubes, nearest in front */
            voxgi_voxels_info in;
            float vp[16];
            voxgi_voxels_query(voxels, &in);
            view_projection(&v.camera, fw, fh, lo, hi, vp);
            glEnable(GL_DEPTH_TEST);
            glUseProgram(cube_prog);
            glProgramUniformMatrix4fv(cube_prog, 0, 1, GL_FALSE, vp);
            glProgramUniform3f(cube_prog, 1, (float)in.grid.origin[0], (float)in.grid.origin[1], (float)in.grid.origin[2]);
            glProgramUniform1f(cube_prog, 2, (float)in.grid.voxel_size);
            glProgramUniform1f(cube_prog, 3, v.exposure);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, cube_buffer);
            glDrawArraysInstanced(GL_TRIANGLES, 0, 36, (GLsizei)cubes);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
        } else {
            glUseProgram(prog);
            glProgramUniform1f(prog, 0, v.exposure);
            glBindTextureUnit(0, tex);
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
        if ((shot && frame == frames - 1) || v.save) {
            const char *path = v.save ? "viewer.png" : shot;
            if (save_pixels(path, fw, fh) != 0) fprintf(stderr, "viewer: cannot write %s\n", path), rc = 1;
            else printf("viewer: wrote %s (%d x %d, frame %d)\n", path, fw, fh, frame + 1);
            v.save = 0;
        }
        glfwSwapBuffers(win);
        if (frames) glfwPollEvents();
        else glfwWaitEventsTimeout(0.1);
    }
done:
    if (cube_buffer) glDeleteBuffers(1, &cube_buffer);
    free(rgb);
    free(v.lights);
    voxgi_voxels_destroy(ctx, voxels);
    voxgi_builtin_scene_destroy(ctx, &bs);
    voxgi_io_mesh_free(&m);
    voxgi_destroy(ctx);
    glfwDestroyWindow(win);
    glfwTerminate();
    return rc;
}
