/* tests/test_fuzz_inputs.c - every input the fuzzers have a file of, run through its harness in the
 * normal test build: the seeds (fuzz/corpus/NAME/) and every finding (fuzz/regressions/NAME/, the
 * input that showed a bug, kept so the bug stays fixed). The harnesses of fuzz/ are compiled in
 * here with the test's compiler (under ASan and UBSan in build/asan/), each through its
 * LLVMFuzzerTestOneInput renamed; their checks (FUZZ_CHECK) report as this harness's checks,
 * naming the input, instead of aborting. Runs from the repository's root (tests/run.sh). */
#ifndef _XOPEN_SOURCE
#define _XOPEN_SOURCE 700 /* mkdtemp, fmemopen, opendir */
#endif
#include "harness.h"

#include <dirent.h>

static char current_input[512]; /* the input being run: the harnesses' checks and a sanitizer's report name it */
#define FUZZ_CHECK(cond) TH_CHECK(cond, "%s: %s", current_input, #cond)

#define LLVMFuzzerTestOneInput fuzz_obj_input
#include "../fuzz/fuzz_obj.c"
#undef LLVMFuzzerTestOneInput
#define LLVMFuzzerTestOneInput fuzz_mtl_input
#include "../fuzz/fuzz_mtl.c"
#undef LLVMFuzzerTestOneInput
#define LLVMFuzzerTestOneInput fuzz_off_input
#include "../fuzz/fuzz_off.c"
#undef LLVMFuzzerTestOneInput
#define LLVMFuzzerTestOneInput fuzz_stl_input
#include "../fuzz/fuzz_stl.c"
#undef LLVMFuzzerTestOneInput
#define LLVMFuzzerTestOneInput fuzz_ply_input
#include "../fuzz/fuzz_ply.c"
#undef LLVMFuzzerTestOneInput
#define LLVMFuzzerTestOneInput fuzz_gltf_input
#include "../fuzz/fuzz_gltf.c"
#undef LLVMFuzzerTestOneInput
#define LLVMFuzzerTestOneInput fuzz_glb_input
#include "../fuzz/fuzz_glb.c"
#undef LLVMFuzzerTestOneInput
#define LLVMFuzzerTestOneInput fuzz_binvox_input
#include "../fuzz/fuzz_binvox.c"
#undef LLVMFuzzerTestOneInput
#define LLVMFuzzerTestOneInput fuzz_pfm_input
#include "../fuzz/fuzz_pfm.c"
#undef LLVMFuzzerTestOneInput
#define LLVMFuzzerTestOneInput fuzz_svo_input
#include "../fuzz/fuzz_svo.c"
#undef LLVMFuzzerTestOneInput
#define LLVMFuzzerTestOneInput fuzz_api_input
#include "../fuzz/fuzz_api.c"
#undef LLVMFuzzerTestOneInput

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/common_interface_defs.h>
static void name_the_input(void) { fprintf(stderr, "while running the fuzz input %s\n", current_input); }
/* As `make fuzz` runs the harnesses (-rss_limit_mb=2048, which limits one allocation too): an input
   that makes a reader ask for more than 2 GiB at once is a finding, not a slow success. */
const char *__asan_default_options(void);
const char *__asan_default_options(void) { return "max_allocation_size_mb=2048"; }
#endif

typedef int (*harness_fn)(const uint8_t *data, size_t size);

static int by_name(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* Runs every file of folder through fn, in name order; returns how many. */
static int run_dir(const char *folder, harness_fn fn)
{
    DIR *d = opendir(folder);
    struct dirent *e;
    char *names[512];
    int n = 0, i;
    if (!d) return 0; /* a harness without findings has no regressions folder */
    while ((e = readdir(d)) && n < 512)
        if (e->d_name[0] != '.') names[n++] = strdup(e->d_name);
    closedir(d);
    qsort(names, (size_t)n, sizeof names[0], by_name);
    for (i = 0; i < n; i++) {
        FILE *f;
        long size;
        unsigned char *data = NULL;
        snprintf(current_input, sizeof current_input, "%s/%s", folder, names[i]);
        f = fopen(current_input, "rb");
        TH_CHECK(f != NULL, "cannot open %s", current_input);
        if (f && fseek(f, 0, SEEK_END) == 0 && (size = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0 &&
            (data = (unsigned char *)malloc((size_t)size + 1)) != NULL && fread(data, 1, (size_t)size, f) == (size_t)size)
            fn(data, (size_t)size); /* libFuzzer hands over a buffer of exactly the input's bytes, as here */
        else
            TH_CHECK(0, "cannot read %s", current_input);
        if (f) fclose(f);
        free(data);
        free(names[i]);
    }
    return n;
}

/* A harness's seeds, which must exist, and its regressions. */
static void run_harness(const char *name, harness_fn fn)
{
    char folder[256];
    snprintf(folder, sizeof folder, "fuzz/corpus/%s", name);
    TH_CHECK(run_dir(folder, fn) > 0, "no seeds in %s (run from the repository's root)", folder);
    snprintf(folder, sizeof folder, "fuzz/regressions/%s", name);
    run_dir(folder, fn);
}

static void test_fuzz_inputs_obj(void) { run_harness("obj", fuzz_obj_input); }
static void test_fuzz_inputs_mtl(void) { run_harness("mtl", fuzz_mtl_input); }
static void test_fuzz_inputs_off(void) { run_harness("off", fuzz_off_input); }
static void test_fuzz_inputs_stl(void) { run_harness("stl", fuzz_stl_input); }
static void test_fuzz_inputs_ply(void) { run_harness("ply", fuzz_ply_input); }
static void test_fuzz_inputs_gltf(void) { run_harness("gltf", fuzz_gltf_input); }
static void test_fuzz_inputs_glb(void) { run_harness("glb", fuzz_glb_input); }
static void test_fuzz_inputs_binvox(void) { run_harness("binvox", fuzz_binvox_input); }
static void test_fuzz_inputs_pfm(void) { run_harness("pfm", fuzz_pfm_input); }
static void test_fuzz_inputs_svo(void) { run_harness("svo", fuzz_svo_input); }
static void test_fuzz_inputs_api(void) { run_harness("api", fuzz_api_input); }

int main(void)
{
#if defined(__SANITIZE_ADDRESS__)
    __sanitizer_set_death_callback(name_the_input);
#endif
    TH_RUN(test_fuzz_inputs_obj);
    TH_RUN(test_fuzz_inputs_mtl);
    TH_RUN(test_fuzz_inputs_off);
    TH_RUN(test_fuzz_inputs_stl);
    TH_RUN(test_fuzz_inputs_ply);
    TH_RUN(test_fuzz_inputs_gltf);
    TH_RUN(test_fuzz_inputs_glb);
    TH_RUN(test_fuzz_inputs_binvox);
    TH_RUN(test_fuzz_inputs_pfm);
    TH_RUN(test_fuzz_inputs_svo);
    TH_RUN(test_fuzz_inputs_api);
    voxgi_destroy(fuzz_context());
    return th_finish();
}
