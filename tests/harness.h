/* tests/harness.h - the one tiny test harness every test program shares.
 *
 * A test program defines test functions, runs them with TH_RUN, and ends main() with
 * `return th_finish();`. It prints one line per test ("PASS name", "FAIL name: why",
 * "SKIP name: why") and a machine-readable tally "RESULT <passed> <failed> <skipped>".
 * tests/run.sh adds up the tallies of every program and prints "N passed, N failed" last.
 * A skipped test is never counted as passed. */
#ifndef VOXGI_TEST_HARNESS_H
#define VOXGI_TEST_HARNESS_H
#include <stdio.h>
#include <stdarg.h>
#include <string.h>
#include <stdlib.h>

typedef struct th_state { int passed, failed, skipped, cur_failed, cur_skipped; const char *cur; } th_state;
static th_state th_;

/* Record a failed check of the running test, with a printf-style reason; the test goes on. */
static inline void th_fail_(const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    if (!th_.cur_failed) printf("FAIL %s\n", th_.cur ? th_.cur : "?");
    th_.cur_failed++;
    if (th_.cur_failed > 20) return; /* one broken test must not flood the log */
    printf("    %s:%d: ", file, line);
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    printf("\n");
}
/* Mark the running test as skipped (loudly), e.g. when no GL 4.5 context can be made. */
static inline void th_skip(const char *fmt, ...)
{
    va_list ap;
    th_.cur_skipped = 1;
    printf("SKIP %s: ", th_.cur ? th_.cur : "?");
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    printf("\n");
}

/* Whether a GL 4.5 context must exist (VOXGI_REQUIRE_GL=1, as in CI): then a test that finds
   none fails instead of skipping. Unset, empty or 0: it skips. Any other value is a typo that
   must not quietly turn the requirement off, so it counts as required. */
static inline int th_gl_required(void)
{
    const char *v = getenv("VOXGI_REQUIRE_GL");
    return v && *v && strcmp(v, "0") != 0;
}

#define TH_CHECK(cond, ...) do { if (!(cond)) th_fail_(__FILE__, __LINE__, __VA_ARGS__); } while (0)
/* TH_ONLY=substring runs only the tests whose name contains it, TH_EXCLUDE=substring all others. */
#define TH_RUN(fn) do {                                                       \
        if (getenv("TH_ONLY") && !strstr(#fn, getenv("TH_ONLY"))) break;      \
        if (getenv("TH_EXCLUDE") && strstr(#fn, getenv("TH_EXCLUDE"))) break; \
        th_.cur = #fn; th_.cur_failed = 0; th_.cur_skipped = 0;               \
        fn();                                                                 \
        if (th_.cur_failed) th_.failed++;                                     \
        else if (th_.cur_skipped) th_.skipped++;                              \
        else { th_.passed++; printf("PASS %s\n", #fn); }                      \
        fflush(stdout);                                                       \
    } while (0)

static inline int th_finish(void)
{
    printf("RESULT %d %d %d\n", th_.passed, th_.failed, th_.skipped);
    return th_.failed ? 1 : 0;
}
#endif
