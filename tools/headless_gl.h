/* tools/headless_gl.h - a real, windowless OpenGL 4.5 core-profile context for voxgi's
 * tests, tools and examples.
 *
 * Two back ends, both loaded with dlopen at run time so that a program including this
 * header links with -ldl alone (nothing at all on glibc 2.34 or later):
 *   egl     EGL with the EGL_MESA_platform_surfaceless platform (libEGL.so.1): the GPU's
 *           driver when there is one, llvmpipe otherwise.
 *   osmesa  Mesa's off-screen library (libOSMesa.so.8), always the CPU.
 * No EGL, GL or OSMesa header is needed: the few types and enums used are declared here.
 * tools/deps.sh installs the Debian packages both back ends need.
 *
 *     char err[512];
 *     vxt_gl *gl = vxt_gl_create(VXT_GL_AUTO, err, sizeof err);
 *     if (!gl) { fprintf(stderr, "%s\n", err); return 1; }
 *     ... resolve GL functions with vxt_gl_get_proc("glDispatchCompute", gl) ...
 *     vxt_gl_destroy(gl);
 *
 * The context is current on the thread that created it. Mesa shares one surfaceless EGL
 * display per process and destroying a context terminates it, so keep one vxt_gl alive
 * at a time. Every function is static inline, so a program may use any subset of them
 * without unused-function warnings. */
#ifndef VXT_HEADLESS_GL_H
#define VXT_HEADLESS_GL_H

#include <dlfcn.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef enum vxt_gl_kind { VXT_GL_AUTO = 0, VXT_GL_EGL, VXT_GL_OSMESA } vxt_gl_kind;
typedef struct vxt_gl vxt_gl;
typedef void (*vxt_gl_proc)(void);

/* EGL: only what a surfaceless context needs. */
typedef void *vxt_gl__egl_ptr; /* EGLDisplay, EGLConfig, EGLContext, EGLSurface */
typedef int vxt_gl__egl_int;   /* EGLint is 32 bits on every platform dlopen exists on */
typedef unsigned vxt_gl__egl_bool;
typedef vxt_gl_proc (*vxt_gl__egl_get_proc_address_fn)(const char *name);
typedef const char *(*vxt_gl__egl_query_string_fn)(vxt_gl__egl_ptr dpy, vxt_gl__egl_int name);
typedef vxt_gl__egl_ptr (*vxt_gl__egl_get_platform_display_ext_fn)(unsigned platform, void *native,
                                                                   const vxt_gl__egl_int *attribs);
typedef vxt_gl__egl_int (*vxt_gl__egl_get_error_fn)(void);
typedef vxt_gl__egl_bool (*vxt_gl__egl_initialize_fn)(vxt_gl__egl_ptr dpy, vxt_gl__egl_int *major,
                                                      vxt_gl__egl_int *minor);
typedef vxt_gl__egl_bool (*vxt_gl__egl_terminate_fn)(vxt_gl__egl_ptr dpy);
typedef vxt_gl__egl_bool (*vxt_gl__egl_bind_api_fn)(unsigned api);
typedef vxt_gl__egl_bool (*vxt_gl__egl_choose_config_fn)(vxt_gl__egl_ptr dpy, const vxt_gl__egl_int *attribs,
                                                         vxt_gl__egl_ptr *configs, vxt_gl__egl_int size,
                                                         vxt_gl__egl_int *count);
typedef vxt_gl__egl_ptr (*vxt_gl__egl_create_context_fn)(vxt_gl__egl_ptr dpy, vxt_gl__egl_ptr config,
                                                         vxt_gl__egl_ptr share,
                                                         const vxt_gl__egl_int *attribs);
typedef vxt_gl__egl_bool (*vxt_gl__egl_destroy_context_fn)(vxt_gl__egl_ptr dpy, vxt_gl__egl_ptr ctx);
typedef vxt_gl__egl_bool (*vxt_gl__egl_make_current_fn)(vxt_gl__egl_ptr dpy, vxt_gl__egl_ptr draw,
                                                        vxt_gl__egl_ptr read, vxt_gl__egl_ptr ctx);
enum {
    VXT_GL__EGL_SUCCESS = 0x3000,
    VXT_GL__EGL_SURFACE_TYPE = 0x3033,
    VXT_GL__EGL_NONE = 0x3038,
    VXT_GL__EGL_RENDERABLE_TYPE = 0x3040,
    VXT_GL__EGL_EXTENSIONS = 0x3055,
    VXT_GL__EGL_CONTEXT_MAJOR_VERSION = 0x3098,
    VXT_GL__EGL_OPENGL_API = 0x30A2,
    VXT_GL__EGL_CONTEXT_MINOR_VERSION = 0x30FB,
    VXT_GL__EGL_CONTEXT_OPENGL_PROFILE_MASK = 0x30FD,
    VXT_GL__EGL_PLATFORM_SURFACELESS_MESA = 0x31DD,
    VXT_GL__EGL_OPENGL_BIT = 0x0008,
    VXT_GL__EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT = 0x0001
};

/* OSMesa */
typedef void *vxt_gl__osmesa_context;
typedef vxt_gl__osmesa_context (*vxt_gl__osmesa_create_context_attribs_fn)(const int *attribs,
                                                                          vxt_gl__osmesa_context share);
typedef unsigned char (*vxt_gl__osmesa_make_current_fn)(vxt_gl__osmesa_context ctx, void *buffer,
                                                        unsigned type, int width, int height);
typedef void (*vxt_gl__osmesa_destroy_context_fn)(vxt_gl__osmesa_context ctx);
typedef vxt_gl_proc (*vxt_gl__osmesa_get_proc_address_fn)(const char *name);
enum {
    VXT_GL__OSMESA_FORMAT = 0x22,
    VXT_GL__OSMESA_PROFILE = 0x33,
    VXT_GL__OSMESA_CORE_PROFILE = 0x34,
    VXT_GL__OSMESA_CONTEXT_MAJOR_VERSION = 0x36,
    VXT_GL__OSMESA_CONTEXT_MINOR_VERSION = 0x37,
    VXT_GL__OSMESA_RGBA = 0x1908, /* GL_RGBA */
    VXT_GL__GL_UNSIGNED_BYTE = 0x1401
};

enum { VXT_GL__GL_RENDERER = 0x1F01, VXT_GL__GL_VERSION = 0x1F02 };
typedef const unsigned char *(*vxt_gl__get_string_fn)(unsigned name);

struct vxt_gl {
    vxt_gl_kind kind;
    void *lib;
    char renderer[256];
    /* egl */
    vxt_gl__egl_ptr display, context;
    vxt_gl__egl_get_proc_address_fn egl_get_proc_address;
    vxt_gl__egl_make_current_fn egl_make_current;
    vxt_gl__egl_destroy_context_fn egl_destroy_context;
    vxt_gl__egl_terminate_fn egl_terminate;
    /* osmesa */
    vxt_gl__osmesa_context osmesa;
    unsigned char pixel[4]; /* OSMesa will not make a context current without a colour buffer */
    vxt_gl__osmesa_make_current_fn osmesa_make_current;
    vxt_gl__osmesa_destroy_context_fn osmesa_destroy_context;
    vxt_gl__osmesa_get_proc_address_fn osmesa_get_proc_address;
};

static inline void vxt_gl__fail(char *err, size_t err_size, const char *fmt, ...)
{
    va_list ap;
    if (!err || !err_size) return;
    va_start(ap, fmt);
    vsnprintf(err, err_size, fmt, ap);
    va_end(ap);
}

/* Stores dlsym's result into the function pointer at fn_out. ISO C has no conversion from
 * void * to a function pointer; POSIX guarantees both have the same representation. */
static inline int vxt_gl__sym(void *lib, const char *name, void *fn_out)
{
    void *p = dlsym(lib, name);
    memcpy(fn_out, &p, sizeof p);
    return p != NULL;
}

/* Whether the space-separated extension list has exactly this name. */
static inline int vxt_gl__has_ext(const char *list, const char *name)
{
    size_t n = strlen(name);
    const char *p;
    for (p = list; (p = strstr(p, name)) != NULL; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return 1;
    return 0;
}

static inline void *vxt_gl__open(const char *const *names, const char *who, const char *package,
                                 char *err, size_t err_size)
{
    char first_error[256] = "";
    int i;
    for (i = 0; names[i]; i++) {
        /* NODELETE: Mesa (and the LLVM inside it) does not survive being unloaded and loaded
         * again, so the library stays mapped after the last dlclose. */
        void *lib = dlopen(names[i], RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
        if (lib) return lib;
        if (!first_error[0]) snprintf(first_error, sizeof first_error, "%s", dlerror());
    }
    vxt_gl__fail(err, err_size, "%s: cannot load %s (install %s): %s", who, names[0], package, first_error);
    return NULL;
}

static inline vxt_gl_proc vxt_gl_get_proc(const char *name, void *user)
{
    const vxt_gl *gl = (const vxt_gl *)user;
    return gl->kind == VXT_GL_EGL ? gl->egl_get_proc_address(name) : gl->osmesa_get_proc_address(name);
}

/* Reads GL_RENDERER and checks GL_VERSION is at least 4.5 on the now-current context. */
static inline int vxt_gl__check_current(vxt_gl *gl, const char *who, char *err, size_t err_size)
{
    vxt_gl__get_string_fn get_string = (vxt_gl__get_string_fn)vxt_gl_get_proc("glGetString", gl);
    const char *version = get_string ? (const char *)get_string(VXT_GL__GL_VERSION) : NULL;
    const char *renderer = get_string ? (const char *)get_string(VXT_GL__GL_RENDERER) : NULL;
    int major = 0, minor = 0;
    if (!version || sscanf(version, "%d.%d", &major, &minor) != 2) {
        vxt_gl__fail(err, err_size, "%s: the context has no readable GL_VERSION", who);
        return 0;
    }
    if (major < 4 || (major == 4 && minor < 5)) {
        vxt_gl__fail(err, err_size, "%s: got OpenGL %s, need 4.5", who, version);
        return 0;
    }
    snprintf(gl->renderer, sizeof gl->renderer, "%s", renderer ? renderer : "?");
    return 1;
}

/* Keeps every shared library mapped now (the GL driver and what it loaded: LLVM, the DRI
 * driver, the EGL vendor) loaded for the rest of the process. Mesa unloads its driver when the
 * last context goes, and a leak checker that runs at exit can then neither name a driver's
 * frames nor match a suppression by library: the driver's own lost bytes would be reported as
 * ours. Pinning changes nothing else: NOLOAD opens only what is already mapped. Linux only (it
 * reads /proc/self/maps); elsewhere it does nothing. */
static inline void vxt_gl__pin_loaded_libraries(void)
{
    char line[4096], last[4096] = "";
    FILE *maps = fopen("/proc/self/maps", "r");
    if (!maps) return;
    while (fgets(line, sizeof line, maps)) {
        char *path = strchr(line, '/'), *end;
        void *lib;
        if (!path || !strstr(path, ".so")) continue;
        end = path + strcspn(path, "\n");
        *end = '\0';
        if (strcmp(path, last) == 0) continue; /* a library spans several consecutive mappings */
        snprintf(last, sizeof last, "%s", path);
        lib = dlopen(path, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
        if (lib) dlclose(lib); /* the reference NOLOAD took; NODELETE stays */
    }
    fclose(maps);
}

static inline void vxt_gl_destroy(vxt_gl *gl)
{
    if (!gl) return;
    vxt_gl__pin_loaded_libraries();
    if (gl->context) {
        gl->egl_make_current(gl->display, NULL, NULL, NULL);
        gl->egl_destroy_context(gl->display, gl->context);
    }
    if (gl->display) gl->egl_terminate(gl->display);
    if (gl->osmesa) {
        gl->osmesa_make_current(NULL, NULL, 0, 0, 0);
        gl->osmesa_destroy_context(gl->osmesa);
    }
    if (gl->lib) dlclose(gl->lib);
    free(gl);
}

static inline vxt_gl *vxt_gl__create_egl(char *err, size_t err_size)
{
    static const char *const names[] = {"libEGL.so.1", "libEGL.so", NULL};
    static const vxt_gl__egl_int config_attribs[] = {
        VXT_GL__EGL_RENDERABLE_TYPE, VXT_GL__EGL_OPENGL_BIT,
        VXT_GL__EGL_SURFACE_TYPE, 0, /* surfaceless configs may have no surface type at all */
        VXT_GL__EGL_NONE};
    static const vxt_gl__egl_int context_attribs[] = {
        VXT_GL__EGL_CONTEXT_MAJOR_VERSION, 4,
        VXT_GL__EGL_CONTEXT_MINOR_VERSION, 5,
        VXT_GL__EGL_CONTEXT_OPENGL_PROFILE_MASK, VXT_GL__EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
        VXT_GL__EGL_NONE};
    vxt_gl__egl_query_string_fn query_string;
    vxt_gl__egl_get_platform_display_ext_fn get_platform_display;
    vxt_gl__egl_get_error_fn get_error;
    vxt_gl__egl_initialize_fn initialize;
    vxt_gl__egl_bind_api_fn bind_api;
    vxt_gl__egl_choose_config_fn choose_config;
    vxt_gl__egl_create_context_fn create_context;
    vxt_gl__egl_ptr config = NULL;
    vxt_gl__egl_int major = 0, minor = 0, count = 0;
    const char *client_exts, *display_exts;
    vxt_gl *gl = (vxt_gl *)calloc(1, sizeof *gl);

    if (!gl) { vxt_gl__fail(err, err_size, "EGL: out of memory"); return NULL; }
    gl->kind = VXT_GL_EGL;
    gl->lib = vxt_gl__open(names, "EGL", "libegl1", err, err_size);
    if (!gl->lib) goto fail;
    if (!vxt_gl__sym(gl->lib, "eglGetProcAddress", &gl->egl_get_proc_address)
        || !vxt_gl__sym(gl->lib, "eglQueryString", &query_string)
        || !vxt_gl__sym(gl->lib, "eglGetError", &get_error)
        || !vxt_gl__sym(gl->lib, "eglInitialize", &initialize)
        || !vxt_gl__sym(gl->lib, "eglTerminate", &gl->egl_terminate)
        || !vxt_gl__sym(gl->lib, "eglBindAPI", &bind_api)
        || !vxt_gl__sym(gl->lib, "eglChooseConfig", &choose_config)
        || !vxt_gl__sym(gl->lib, "eglCreateContext", &create_context)
        || !vxt_gl__sym(gl->lib, "eglDestroyContext", &gl->egl_destroy_context)
        || !vxt_gl__sym(gl->lib, "eglMakeCurrent", &gl->egl_make_current)) {
        vxt_gl__fail(err, err_size, "EGL: libEGL.so.1 lacks an EGL 1.4 entry point: %s", dlerror());
        goto fail;
    }

    /* Surfaceless needs no window system, no X server and no DRM device. */
    client_exts = query_string(NULL, VXT_GL__EGL_EXTENSIONS);
    if (!client_exts || !vxt_gl__has_ext(client_exts, "EGL_MESA_platform_surfaceless")) {
        vxt_gl__fail(err, err_size, "EGL: no EGL_MESA_platform_surfaceless (install libegl-mesa0); "
                     "client extensions: %s", client_exts && *client_exts ? client_exts : "(none)");
        goto fail;
    }
    /* eglGetPlatformDisplayEXT takes EGLint attributes where EGL 1.5's eglGetPlatformDisplay
     * takes EGLAttrib; with no attributes the two are interchangeable. */
    get_platform_display = (vxt_gl__egl_get_platform_display_ext_fn)
        gl->egl_get_proc_address("eglGetPlatformDisplayEXT");
    if (!get_platform_display)
        get_platform_display = (vxt_gl__egl_get_platform_display_ext_fn)
            gl->egl_get_proc_address("eglGetPlatformDisplay");
    if (!get_platform_display) {
        vxt_gl__fail(err, err_size, "EGL: neither eglGetPlatformDisplayEXT nor eglGetPlatformDisplay exists");
        goto fail;
    }
    gl->display = get_platform_display(VXT_GL__EGL_PLATFORM_SURFACELESS_MESA, NULL, NULL);
    if (!gl->display || !initialize(gl->display, &major, &minor)) {
        vxt_gl__fail(err, err_size, "EGL: cannot initialise the surfaceless display (error 0x%x; "
                     "install libgl1-mesa-dri for llvmpipe)", (unsigned)get_error());
        gl->display = NULL;
        goto fail;
    }
    if (!bind_api(VXT_GL__EGL_OPENGL_API)) {
        vxt_gl__fail(err, err_size, "EGL %d.%d: desktop OpenGL API unavailable (error 0x%x)",
                     major, minor, (unsigned)get_error());
        goto fail;
    }
    display_exts = query_string(gl->display, VXT_GL__EGL_EXTENSIONS);
    if (!display_exts || !vxt_gl__has_ext(display_exts, "EGL_KHR_no_config_context")) {
        if (!choose_config(gl->display, config_attribs, &config, 1, &count) || count < 1) {
            vxt_gl__fail(err, err_size, "EGL %d.%d: no config renders with desktop OpenGL (error 0x%x)",
                         major, minor, (unsigned)get_error());
            goto fail;
        }
    }
    gl->context = create_context(gl->display, config, NULL, context_attribs);
    if (!gl->context) {
        vxt_gl__fail(err, err_size, "EGL %d.%d: cannot create an OpenGL 4.5 core context (error 0x%x)",
                     major, minor, (unsigned)get_error());
        goto fail;
    }
    if (!gl->egl_make_current(gl->display, NULL, NULL, gl->context)) {
        vxt_gl__fail(err, err_size, "EGL %d.%d: cannot make a context current without a surface "
                     "(error 0x%x)", major, minor, (unsigned)get_error());
        goto fail;
    }
    if (!vxt_gl__check_current(gl, "EGL", err, err_size)) goto fail;
    return gl;
fail:
    vxt_gl_destroy(gl);
    return NULL;
}

static inline vxt_gl *vxt_gl__create_osmesa(char *err, size_t err_size)
{
    static const char *const names[] = {"libOSMesa.so.8", "libOSMesa.so", NULL};
    static const int attribs[] = {
        VXT_GL__OSMESA_FORMAT, VXT_GL__OSMESA_RGBA,
        VXT_GL__OSMESA_CONTEXT_MAJOR_VERSION, 4,
        VXT_GL__OSMESA_CONTEXT_MINOR_VERSION, 5,
        VXT_GL__OSMESA_PROFILE, VXT_GL__OSMESA_CORE_PROFILE,
        0};
    vxt_gl__osmesa_create_context_attribs_fn create_context;
    vxt_gl *gl = (vxt_gl *)calloc(1, sizeof *gl);

    if (!gl) { vxt_gl__fail(err, err_size, "OSMesa: out of memory"); return NULL; }
    gl->kind = VXT_GL_OSMESA;
    gl->lib = vxt_gl__open(names, "OSMesa", "libosmesa6", err, err_size);
    if (!gl->lib) goto fail;
    if (!vxt_gl__sym(gl->lib, "OSMesaCreateContextAttribs", &create_context)
        || !vxt_gl__sym(gl->lib, "OSMesaMakeCurrent", &gl->osmesa_make_current)
        || !vxt_gl__sym(gl->lib, "OSMesaDestroyContext", &gl->osmesa_destroy_context)
        || !vxt_gl__sym(gl->lib, "OSMesaGetProcAddress", &gl->osmesa_get_proc_address)) {
        vxt_gl__fail(err, err_size, "OSMesa: library too old, it lacks %s", dlerror());
        goto fail;
    }
    gl->osmesa = create_context(attribs, NULL);
    if (!gl->osmesa) {
        vxt_gl__fail(err, err_size, "OSMesa: cannot create an OpenGL 4.5 core context "
                     "(a classic-driver OSMesa stops at 3.x; the gallium one is needed)");
        goto fail;
    }
    if (!gl->osmesa_make_current(gl->osmesa, gl->pixel, VXT_GL__GL_UNSIGNED_BYTE, 1, 1)) {
        vxt_gl__fail(err, err_size, "OSMesa: OSMesaMakeCurrent failed");
        goto fail;
    }
    if (!vxt_gl__check_current(gl, "OSMesa", err, err_size)) goto fail;
    return gl;
fail:
    vxt_gl_destroy(gl);
    return NULL;
}

static inline vxt_gl *vxt_gl_create(vxt_gl_kind kind, char *err, size_t err_size)
{
    char egl_err[512];
    vxt_gl *gl;
    if (kind == VXT_GL_EGL) return vxt_gl__create_egl(err, err_size);
    if (kind == VXT_GL_OSMESA) return vxt_gl__create_osmesa(err, err_size);
    gl = vxt_gl__create_egl(egl_err, sizeof egl_err);
    if (gl) return gl;
    gl = vxt_gl__create_osmesa(err, err_size);
    if (!gl && err && err_size) {
        char osmesa_err[512];
        snprintf(osmesa_err, sizeof osmesa_err, "%s", err);
        vxt_gl__fail(err, err_size, "no headless OpenGL 4.5: %s; %s", egl_err, osmesa_err);
    }
    return gl;
}

static inline const char *vxt_gl_kind_name(const vxt_gl *gl)
{
    return gl->kind == VXT_GL_EGL ? "egl" : "osmesa";
}

static inline const char *vxt_gl_renderer(const vxt_gl *gl)
{
    return gl->renderer;
}

static inline int vxt_gl_kind_parse(const char *s, vxt_gl_kind *out)
{
    static const char *const names[] = {"auto", "egl", "osmesa"};
    int i;
    for (i = 0; i < 3; i++) {
        if (s && strcmp(s, names[i]) == 0) {
            *out = (vxt_gl_kind)i;
            return 0;
        }
    }
    return -1;
}

#endif
