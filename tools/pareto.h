/* tools/pareto.h - the Pareto front of measured configurations (time against error), the one
   rule every report marks its front by, and the fastest configuration reaching an error. Rows of
   any struct: the fields are named by their offsets. No dependencies: the tests include it too. */
#ifndef VXT_PARETO_H
#define VXT_PARETO_H
#include <math.h>
#include <stddef.h>
#include <string.h>

/* A row of report all, and the tests' rows. */
typedef struct pareto_point {
    double ms, error;
    int group;  /* fronts are per group */
    int front;  /* 1: on its group's front */
} pareto_point;

#define PARETO_NO_GROUP ((size_t)-1) /* every row in one group */

static inline double pareto_double_at(const void *rows, size_t i, size_t size, size_t at)
{
    double v;
    memcpy(&v, (const unsigned char *)rows + i * size + at, sizeof v);
    return v;
}

static inline int pareto_int_at(const void *rows, size_t i, size_t size, size_t at)
{
    int v = 0;
    if (at != PARETO_NO_GROUP) memcpy(&v, (const unsigned char *)rows + i * size + at, sizeof v);
    return v;
}

/* Marks the front of n rows of `size` bytes: the int at front_at is set to 1 when the row's time
   (the double at ms_at) and error (at error_at) are finite and no other such row of its group
   (the int at group_at) is at least as fast and at least as close and strictly better in one of
   the two, else to 0. Rows with the same time and error are all on the front or all off it. */
static inline void pareto_mark_rows(void *rows, size_t n, size_t size, size_t ms_at, size_t error_at, size_t group_at, size_t front_at)
{
    size_t i, j;
    for (i = 0; i < n; i++) {
        const double t = pareto_double_at(rows, i, size, ms_at), e = pareto_double_at(rows, i, size, error_at);
        const int g = pareto_int_at(rows, i, size, group_at);
        int front = isfinite(t) && isfinite(e);
        for (j = 0; j < n && front; j++) {
            const double tj = pareto_double_at(rows, j, size, ms_at), ej = pareto_double_at(rows, j, size, error_at);
            if (j != i && pareto_int_at(rows, j, size, group_at) == g && isfinite(tj) && isfinite(ej) && tj <= t && ej <= e && (tj < t || ej < e))
                front = 0;
        }
        memcpy((unsigned char *)rows + i * size + front_at, &front, sizeof front);
    }
}

/* PARETO_MARK(rows, n, type, ms, error, group, front): the fields by name (group: a field, or
   give PARETO_NO_GROUP through pareto_mark_rows). */
#define PARETO_MARK(rows, n, type, ms, error, group, front) \
    pareto_mark_rows((rows), (n), sizeof(type), offsetof(type, ms), offsetof(type, error), offsetof(type, group), offsetof(type, front))

static inline void pareto_mark(pareto_point *p, size_t n) { PARETO_MARK(p, n, pareto_point, ms, error, group, front); }

/* The fastest point of group g whose error is at most `target` (of equal times the closer, then
   the first); -1 when none reaches it. It is on the front (whatever beats it would be faster or,
   as fast, closer). */
static inline long pareto_fastest(const pareto_point *p, size_t n, int g, double target)
{
    long best = -1;
    size_t i;
    for (i = 0; i < n; i++) {
        if (p[i].group != g || !(p[i].error <= target) || !isfinite(p[i].ms)) continue;
        if (best < 0 || p[i].ms < p[best].ms || (p[i].ms == p[best].ms && p[i].error < p[best].error)) best = (long)i;
    }
    return best;
}
#endif
