/* tests/test_exact.c - part 5: voxelization's exact tests against GMP (apart: it links -lgmp).

   Conservative and thin voxelization against their definitions on ARBITRARY float vertices and
   double grids, decided exactly in GMP rationals (mpq_t, a test-only dependency).

   tests/test_voxelize.c's integer oracle takes only coordinates on a 2^-20 lattice, where the
   library's double arithmetic is exact anyway, so it cannot tell a sound double filter from one
   that trusts its rounded results. Here the grid is any double (voxel sizes 0.1, 0.3, 1/3, ...,
   origins up to 1e6 away) and the triangles are built to sit exactly on the ties the filter must
   not decide alone: planes through voxel edges and corners, edges through voxel corners, faces,
   edges and vertices on grid planes, and a few float ulps off them. Every voxel of each
   triangle's exact range is decided by the oracle and compared with the library's bit; outside
   that range the library must set nothing.

   VOXGI_EXACT_FUZZ=n runs n times as many triangles (new ones after the default ones). */
#include "../voxgi.h"
#include "fixtures.h"
#include <gmp.h>

/* ---------------------------------------------------------------- the oracle
   Voxel (i,j,k) is the closed box [o + (i,j,k)s, o + (i+1,j+1,k+1)s] with o and s the grid's
   doubles taken as exact rationals, and the triangle is the closed convex hull of its three
   float vertices, also exact. CONSERVATIVE: the box meets the triangle. Two compact convex sets
   are disjoint exactly when some axis separates their projections, and for a box and a triangle
   the 13 axes below suffice: the box's 3 face normals, the triangle's normal, and each edge
   crossed with each box axis (the facet normals of their Minkowski difference). A degenerate
   triangle is the segment or point it is: its normal and zero edges give the zero vector, which
   separates nothing and is left out, and what remains are the facet normals of the box plus the
   segment (the 3 face normals and the segment direction crossed with each box axis), or the
   box's 3 face normals for a point; so the same test is exact for them too.

   THIN (Schwarz & Seidel's 6-separating set, as the header defines it): a conservative voxel
   whose inscribed octahedron meets the triangle's plane, |n.(c - v0)| <= h max|n_a| (c the
   centre, h = s/2; skipped when n = 0), and whose inscribed diamond (the square's 2D octahedron)
   passes each projection's edge tests: along an axis where the normal's component has sign
   sig != 0, sig (m.(c - v_k)) + h max(|m_x|, |m_y|) >= 0 for each edge k with inward normal
   m = (-e_y, e_x); where it is 0 the projection is a segment (or a point, then no test) and the
   diamond must meet its line, |m.(c - v_k)| <= h max(|m_x|, |m_y|) for any edge k of non-zero
   projected length (they all lie on that line, so which one does not matter).

   Nothing here shares code or arithmetic with the library. */
#define OX_AXES 13

typedef struct ox {
    mpq_t o[3], s, h;                  /* the grid: origin, voxel size, half of it */
    mpq_t v[3][3], e[3][3], n[3];      /* vertices, edges v_k -> v_k+1, normal e0 x (v2 - v0) */
    int axes, normal;                  /* axes in use; the normal is not zero */
    mpq_t sax[OX_AXES][3];             /* s * axis */
    mpq_t lo[OX_AXES], hi[OX_AXES];    /* box (i,j,k) meets the triangle on the axis iff lo <= sax.(i,j,k) <= hi */
    long rlo[3], rhi[3];               /* exact range of voxel indices the bounding boxes share, clamped to [-2, res + 1] */
    mpq_t w, t0, t1, t2, c[3];         /* scratch */
} ox;

static void ox_init(ox *x)
{
    int a, k;
    for (a = 0; a < 3; a++) {
        mpq_init(x->o[a]); mpq_init(x->n[a]); mpq_init(x->c[a]);
        for (k = 0; k < 3; k++) { mpq_init(x->v[k][a]); mpq_init(x->e[k][a]); }
    }
    for (k = 0; k < OX_AXES; k++) {
        mpq_init(x->lo[k]); mpq_init(x->hi[k]);
        for (a = 0; a < 3; a++) mpq_init(x->sax[k][a]);
    }
    mpq_init(x->s); mpq_init(x->h); mpq_init(x->w); mpq_init(x->t0); mpq_init(x->t1); mpq_init(x->t2);
}

static void ox_clear(ox *x)
{
    int a, k;
    for (a = 0; a < 3; a++) {
        mpq_clear(x->o[a]); mpq_clear(x->n[a]); mpq_clear(x->c[a]);
        for (k = 0; k < 3; k++) { mpq_clear(x->v[k][a]); mpq_clear(x->e[k][a]); }
    }
    for (k = 0; k < OX_AXES; k++) {
        mpq_clear(x->lo[k]); mpq_clear(x->hi[k]);
        for (a = 0; a < 3; a++) mpq_clear(x->sax[k][a]);
    }
    mpq_clear(x->s); mpq_clear(x->h); mpq_clear(x->w); mpq_clear(x->t0); mpq_clear(x->t1); mpq_clear(x->t2);
}

/* r = p . q (r must not alias either; uses t2) */
static void ox_dot(ox *x, mpq_t r, mpq_t const p[3], mpq_t const q[3])
{
    int a;
    mpq_set_ui(r, 0, 1);
    for (a = 0; a < 3; a++) {
        mpq_mul(x->t2, p[a], q[a]);
        mpq_add(r, r, x->t2);
    }
}

/* Adds axis A unless it is zero: the triangle's interval [tmin, tmax] on it, and the box's,
   [A.o + sA.(i,j,k) + s neg, A.o + sA.(i,j,k) + s pos] with neg/pos the sums of A's negative and
   positive components, become lo <= sA.(i,j,k) <= hi. */
static void ox_axis(ox *x, mpq_t const A[3])
{
    mpq_t tmin, tmax, p, ao, pos, neg;
    int a, k, q = x->axes;
    if (!mpq_sgn(A[0]) && !mpq_sgn(A[1]) && !mpq_sgn(A[2])) return;
    mpq_init(tmin); mpq_init(tmax); mpq_init(p); mpq_init(ao); mpq_init(pos); mpq_init(neg);
    for (k = 0; k < 3; k++) {
        ox_dot(x, p, A, (mpq_t const *)x->v[k]);
        if (k == 0 || mpq_cmp(p, tmin) < 0) mpq_set(tmin, p);
        if (k == 0 || mpq_cmp(p, tmax) > 0) mpq_set(tmax, p);
    }
    ox_dot(x, ao, A, (mpq_t const *)x->o);
    for (a = 0; a < 3; a++) {
        if (mpq_sgn(A[a]) > 0) mpq_add(pos, pos, A[a]);
        else mpq_add(neg, neg, A[a]);
        mpq_mul(x->sax[q][a], x->s, A[a]);
    }
    mpq_mul(pos, pos, x->s);
    mpq_mul(neg, neg, x->s);
    mpq_sub(x->lo[q], tmin, ao);
    mpq_sub(x->lo[q], x->lo[q], pos);
    mpq_sub(x->hi[q], tmax, ao);
    mpq_sub(x->hi[q], x->hi[q], neg);
    x->axes++;
    mpq_clear(tmin); mpq_clear(tmax); mpq_clear(p); mpq_clear(ao); mpq_clear(pos); mpq_clear(neg);
}

/* floor (ceil when up) of the rational q, clamped to [lo, hi] */
static long ox_round(const mpq_t q, int up, long lo, long hi)
{
    mpz_t z;
    long r;
    mpz_init(z);
    if (up) mpz_cdiv_q(z, mpq_numref(q), mpq_denref(q));
    else mpz_fdiv_q(z, mpq_numref(q), mpq_denref(q));
    r = mpz_cmp_si(z, lo) < 0 ? lo : (mpz_cmp_si(z, hi) > 0 ? hi : mpz_get_si(z));
    mpz_clear(z);
    return r;
}

/* The triangle v (9 floats) on grid g. */
static void ox_set(ox *x, const voxgi_grid *g, const float *v)
{
    mpq_t A[3];
    int a, k, u;
    for (a = 0; a < 3; a++) mpq_set_d(x->o[a], g->origin[a]); /* exact: every finite double is a rational */
    mpq_set_d(x->s, g->voxel_size);
    mpq_div_2exp(x->h, x->s, 1);
    for (k = 0; k < 3; k++)
        for (a = 0; a < 3; a++) mpq_set_d(x->v[k][a], (double)v[3 * k + a]);
    for (k = 0; k < 3; k++)
        for (a = 0; a < 3; a++) mpq_sub(x->e[k][a], x->v[(k + 1) % 3][a], x->v[k][a]);
    for (a = 0; a < 3; a++) { /* n = e0 x (v2 - v0) = e2 x e0 */
        mpq_mul(x->t0, x->e[2][(a + 1) % 3], x->e[0][(a + 2) % 3]);
        mpq_mul(x->t1, x->e[2][(a + 2) % 3], x->e[0][(a + 1) % 3]);
        mpq_sub(x->n[a], x->t0, x->t1);
    }
    x->normal = mpq_sgn(x->n[0]) || mpq_sgn(x->n[1]) || mpq_sgn(x->n[2]);
    for (a = 0; a < 3; a++) mpq_init(A[a]);
    x->axes = 0; /* (the order only matters for speed: the voxels asked about are in the box axes' range) */
    ox_axis(x, (mpq_t const *)x->n);
    for (k = 0; k < 3; k++)
        for (u = 0; u < 3; u++) { /* e_k x unit_u */
            mpq_set_ui(A[u], 0, 1);
            mpq_set(A[(u + 1) % 3], x->e[k][(u + 2) % 3]);
            mpq_neg(A[(u + 2) % 3], x->e[k][(u + 1) % 3]);
            ox_axis(x, (mpq_t const *)A);
        }
    for (u = 0; u < 3; u++) { /* the box's face normals */
        for (a = 0; a < 3; a++) mpq_set_ui(A[a], a == u, 1);
        ox_axis(x, (mpq_t const *)A);
    }
    for (a = 0; a < 3; a++) mpq_clear(A[a]);
    /* the exact index range: o + i s <= max and o + (i+1) s >= min */
    for (a = 0; a < 3; a++) {
        mpq_srcptr lo = x->v[0][a], hi = x->v[0][a];
        for (k = 1; k < 3; k++) {
            if (mpq_cmp(x->v[k][a], lo) < 0) lo = x->v[k][a];
            if (mpq_cmp(x->v[k][a], hi) > 0) hi = x->v[k][a];
        }
        mpq_sub(x->t0, lo, x->o[a]);
        mpq_div(x->t0, x->t0, x->s);
        x->rlo[a] = ox_round(x->t0, 1, -1, g->res[a] + 2) - 1;
        mpq_sub(x->t0, hi, x->o[a]);
        mpq_div(x->t0, x->t0, x->s);
        x->rhi[a] = ox_round(x->t0, 0, -2, g->res[a] + 1);
    }
}

/* Does voxel idx's closed box meet the closed triangle? *touch: only on its boundary (some
   axis's intervals share just an end point). */
static int ox_meets(ox *x, const int idx[3], int *touch)
{
    int q, a;
    *touch = 0;
    for (q = 0; q < x->axes; q++) {
        int l, h;
        mpq_set_ui(x->w, 0, 1);
        for (a = 0; a < 3; a++) {
            if (!idx[a] || !mpq_sgn(x->sax[q][a])) continue;
            mpq_set_si(x->t0, idx[a], 1);
            mpq_mul(x->t0, x->t0, x->sax[q][a]);
            mpq_add(x->w, x->w, x->t0);
        }
        l = mpq_cmp(x->w, x->lo[q]);
        h = mpq_cmp(x->w, x->hi[q]);
        if (l < 0 || h > 0) return 0;
        if (l == 0 || h == 0) *touch = 1;
    }
    return 1;
}

/* |m . (c - p)| in the plane of axes (a, b) against h max(|m_a|, |m_b|) (m_c = 0) or over all
   three axes (c < 0): *g = m . (c - p) and *r the support; uses w, t0, t1. */
static void ox_form(ox *x, mpq_t const m[3], mpq_t const p[3], int c, mpq_t g, mpq_t r)
{
    int a;
    mpq_set_ui(g, 0, 1);
    mpq_set_ui(r, 0, 1);
    for (a = 0; a < 3; a++) {
        if (a == c) continue;
        mpq_sub(x->t0, x->c[a], p[a]);
        mpq_mul(x->t0, x->t0, m[a]);
        mpq_add(g, g, x->t0);
        mpq_abs(x->t1, m[a]);
        if (mpq_cmp(x->t1, r) > 0) mpq_set(r, x->t1);
    }
    mpq_mul(r, r, x->h);
}

/* The thin test of a voxel that meets the triangle. */
static int ox_thin(ox *x, const int idx[3])
{
    mpq_t g, r, m[3];
    int a, c, k, ok = 1;
    mpq_init(g); mpq_init(r);
    for (a = 0; a < 3; a++) {
        mpq_init(m[a]);
        mpq_set_si(x->c[a], 2 * idx[a] + 1, 2); /* the centre o + (idx + 1/2) s */
        mpq_mul(x->c[a], x->c[a], x->s);
        mpq_add(x->c[a], x->c[a], x->o[a]);
    }
    if (x->normal) {
        ox_form(x, (mpq_t const *)x->n, (mpq_t const *)x->v[0], -1, g, r);
        mpq_abs(g, g);
        if (mpq_cmp(g, r) > 0) ok = 0;
    }
    for (c = 0; ok && c < 3; c++) {
        int pa = (c + 1) % 3, pb = (c + 2) % 3, sig = mpq_sgn(x->n[c]);
        for (k = 0; ok && k < 3; k++) {
            if (sig == 0 && !mpq_sgn(x->e[k][pa]) && !mpq_sgn(x->e[k][pb])) continue; /* a point in this projection */
            mpq_set_ui(m[c], 0, 1);
            mpq_neg(m[pa], x->e[k][pb]);
            mpq_set(m[pb], x->e[k][pa]);
            ox_form(x, (mpq_t const *)m, (mpq_t const *)x->v[k], c, g, r);
            if (sig != 0) { /* sig g + r >= 0 */
                if (sig < 0) mpq_neg(g, g);
                mpq_add(g, g, r);
                if (mpq_sgn(g) < 0) ok = 0;
            } else { /* a segment-shaped projection: its line, on both sides; one edge is enough */
                mpq_abs(g, g);
                if (mpq_cmp(g, r) > 0) ok = 0;
                break;
            }
        }
    }
    for (a = 0; a < 3; a++) mpq_clear(m[a]);
    mpq_clear(g); mpq_clear(r);
    return ok;
}

/* ---------------------------------------------------------------- the cases
   A group is one grid and up to EX_TRIS triangles of one family. */
#define EX_TRIS 12
enum { FAM_PLANE, FAM_LINE, FAM_GRID, FAM_NEAR, FAM_COUNT };
static const char *const fam_name[FAM_COUNT] = {"plane through voxel edges", "edge through voxel corners",
                                                "on exact grid planes", "near grid planes"};

typedef struct ex_group {
    int family, n, ntri;
    voxgi_grid g;
    float v[EX_TRIS][9];
} ex_group;

static int rng_int(fx_rng *r, int n) { return (int)(fx_rng_u64(r) % (uint64_t)n); }

/* The spacing of floats in the binade that holds m > 0. */
static double float_spacing(double m)
{
    int e;
    frexp(m, &e);
    return ldexp(1.0, e - 24);
}

static double snap(double x, double step) { return floor(x / step + 0.5) * step; }

/* x as a float, or 0 in *ok when it is none. */
static float to_float(double x, int *ok)
{
    float f = (float)x;
    if ((double)f != x) *ok = 0;
    return f;
}

/* f moved by k floats (k may be negative). */
static float ulps(float f, int k)
{
    for (; k > 0; k--) f = nextafterf(f, INFINITY);
    for (; k < 0; k++) f = nextafterf(f, -INFINITY);
    return f;
}

/* Non-dyadic voxel sizes mostly; far from the origin, none so small that the floats there are
   coarser than a voxel. */
static double pick_size(fx_rng *r, int far)
{
    static const double sizes[6] = {0.1, 0.3, 1.0 / 3.0, 0.7, 0.15, 1.1};
    int u = rng_int(r, 8);
    if (u < 6) return sizes[u];
    return far ? fx_rng_range(r, 0.1, 2.0) : fx_rng_range(r, 0.01, 2.0);
}

/* 0, a small float or one 1e4..1e6 away (either sign). */
static double pick_base(fx_rng *r)
{
    int u = rng_int(r, 4);
    double m;
    if (u == 0) return 0;
    if (u == 1) return (float)fx_rng_range(r, -3, 3);
    m = pow(10, fx_rng_range(r, 4, 6));
    return (float)(fx_rng_unit(r) < 0.5 ? -m : m);
}

static void pick_res(fx_rng *r, voxgi_grid *g)
{
    int a;
    for (a = 0; a < 3; a++) g->res[a] = 8 + rng_int(r, 5);
}

/* Tie families share this frame: o_a = X + c_a on a float lattice of spacing ul, so that
   o + w is a float for every w on it (near the grid), and the voxel corners o + s(i,j,k) with
   alpha.(i,j,k) = 0 lie exactly on the plane alpha.(p - o) = 0 however s rounds. */
typedef struct ex_frame { double X, c[3], ul, s; } ex_frame;

static void pick_frame(fx_rng *r, ex_group *G, ex_frame *f)
{
    int a;
    pick_res(r, &G->g);
    f->X = pick_base(r);
    f->s = pick_size(r, fabs(f->X) > 100);
    f->ul = float_spacing(fabs(f->X) + 4.0 * 16 * f->s + 1);
    f->X = snap(f->X, f->ul);
    for (a = 0; a < 3; a++) {
        f->c[a] = rng_int(r, 2) ? 0 : snap(fx_rng_range(r, -f->s, f->s), f->ul);
        G->g.origin[a] = f->X + f->c[a];
    }
    G->g.voxel_size = f->s;
}

/* A vertex o + w (w in world units, on the lattice); 0 in *ok when it is not a float. */
static void frame_vertex(const ex_frame *f, const double w[3], float *v, int *ok)
{
    int a;
    for (a = 0; a < 3; a++) v[a] = to_float(f->X + f->c[a] + w[a], ok);
}

/* Nudges one coordinate of one vertex a few floats, a quarter of the time. */
static void maybe_nudge(fx_rng *r, float *v)
{
    static const int steps[4] = {1, -1, 2, -3};
    if (rng_int(r, 4) == 0) {
        int i = rng_int(r, 9);
        v[i] = ulps(v[i], steps[rng_int(r, 4)]);
    }
}

/* Triangles in planes alpha.(p - o) = 0 (small integer alpha of mixed signs), which hold the
   voxel corners with alpha.(i,j,k) = 0: whole voxel edges when a component is zero. */
static int gen_plane_tri(fx_rng *r, const ex_group *G, const ex_frame *f, float *v)
{
    int al[3], z = rng_int(r, 3), x = (z + 1) % 3, y = (z + 2) % 3, k, a, tries, ok = 1, shape = rng_int(r, 10);
    double step, w[3][3], P[3], L = rng_int(r, 3) == 0 ? 0.7 : (rng_int(r, 2) ? 2.0 : 4.0);
    al[z] = -(1 + rng_int(r, 2));
    do { al[x] = rng_int(r, 3); al[y] = rng_int(r, 3); } while (al[x] == 0 && al[y] == 0);
    step = -al[z] * f->ul; /* free coordinates on this lattice keep the solved one on ul's */
    for (tries = 0; tries < 20; tries++) {
        P[x] = snap(fx_rng_range(r, 0.5, G->g.res[x] - 0.5) * f->s, step);
        P[y] = snap(fx_rng_range(r, 0.5, G->g.res[y] - 0.5) * f->s, step);
        P[z] = -(al[x] * P[x] + al[y] * P[y]) / al[z];
        if (P[z] >= 0 && P[z] <= G->g.res[z] * f->s) break;
    }
    for (k = 0; k < 3; k++) {
        w[k][x] = P[x] + snap(fx_rng_range(r, -L, L) * f->s, step);
        w[k][y] = P[y] + snap(fx_rng_range(r, -L, L) * f->s, step);
        if (shape == 0 && k == 2) { /* a needle: the third vertex a few lattice steps off the first edge's middle */
            w[2][x] = snap(0.5 * (w[0][x] + w[1][x]), step) + step * (rng_int(r, 5) - 2);
            w[2][y] = snap(0.5 * (w[0][y] + w[1][y]), step) + step * (rng_int(r, 5) - 2);
        }
        if (shape == 1 && k == 2) { w[2][x] = w[0][x]; w[2][y] = w[0][y]; } /* a segment */
        w[k][z] = -(al[x] * w[k][x] + al[y] * w[k][y]) / al[z];
    }
    for (k = 0; k < 3; k++) frame_vertex(f, w[k], v + 3 * k, &ok);
    if (shape == 2) for (a = 0; a < 3; a++) v[3 + a] = v[6 + a] = v[a]; /* a point */
    maybe_nudge(r, v);
    return ok;
}

/* Triangles with an edge on the line o + t delta (delta >= 0, small integers), which passes
   through the voxel corners m delta, and in each projection through more of the square corners. */
static int gen_line_tri(fx_rng *r, const ex_group *G, const ex_frame *f, float *v)
{
    int d[3], k, a, ok = 1, shape = rng_int(r, 8);
    double w[3][3], t0, t1, big = 0;
    do {
        for (a = 0; a < 3; a++) d[a] = rng_int(r, 4);
    } while (!d[0] && !d[1] && !d[2]);
    for (a = 0; a < 3; a++) big = fmax(big, d[a]);
    t0 = snap(fx_rng_range(r, -1.0, 2.0) * f->s / big, f->ul);
    t1 = t0 + snap(fx_rng_range(r, 1.0, 6.0) * f->s / big, f->ul);
    for (a = 0; a < 3; a++) {
        w[0][a] = t0 * d[a];
        w[1][a] = t1 * d[a];
        w[2][a] = snap(fx_rng_range(r, -0.5, 5.0) * f->s, f->ul);
    }
    if (shape == 0) /* a segment on the line */
        for (a = 0; a < 3; a++) w[2][a] = snap(fx_rng_range(r, -1.0, 6.0) * f->s / big, f->ul) * d[a];
    if (shape == 1) /* a needle along it */
        for (a = 0; a < 3; a++) w[2][a] = snap(0.5 * (t0 + t1), f->ul) * d[a] + f->ul * (rng_int(r, 5) - 2);
    if (shape == 2) /* a point on a corner of the grid */
        for (k = 0; k < 3; k++)
            for (a = 0; a < 3; a++) w[k][a] = 0;
    for (k = 0; k < 3; k++) frame_vertex(f, w[k], v + 3 * k, &ok);
    (void)G;
    maybe_nudge(r, v);
    return ok;
}

/* One grid plane per axis placed exactly on a float P_a: o_a = P_a - K_a s, when that is a
   double (it is near the origin, where it is tiny; else o_a rounds and the plane is only near);
   faces, edges and vertices on them. */
static void gen_grid_group(fx_rng *r, ex_group *G)
{
    double X = rng_int(r, 3) ? 0 : (float)fx_rng_range(r, -3, 3), s = pick_size(r, 0), P[3];
    int a, k, i;
    mpq_t q, back;
    mpq_init(q); mpq_init(back);
    pick_res(r, &G->g);
    G->g.voxel_size = s;
    for (a = 0; a < 3; a++) {
        int K = 2 + rng_int(r, G->g.res[a] - 3);
        float target = (float)(X + K * s);
        double o;
        mpq_set_d(q, s);
        mpq_set_si(back, K, 1);
        mpq_mul(q, q, back);
        mpq_set_d(back, (double)target);
        mpq_sub(q, back, q); /* target - K s */
        o = mpq_get_d(q);
        G->g.origin[a] = o;
        P[a] = target;
    }
    mpq_clear(q); mpq_clear(back);
    for (i = 0; i < G->ntri; i++) {
        float *v = G->v[i];
        int pat = rng_int(r, 8), ax = rng_int(r, 3), bx = (ax + 1 + rng_int(r, 2)) % 3;
        double L = rng_int(r, 3) == 0 ? 0.7 : 2.5;
        for (k = 0; k < 3; k++)
            for (a = 0; a < 3; a++) v[3 * k + a] = (float)(P[a] + fx_rng_range(r, -L, L) * s);
        switch (pat) {
        case 0: case 1: /* a face in the plane of axis ax */
            for (k = 0; k < 3; k++) v[3 * k + ax] = (float)P[ax];
            if (pat == 1) v[bx] = v[3 + bx] = (float)P[bx]; /* and an edge on a voxel edge */
            break;
        case 2: /* an edge on the voxel edge line of axes ax, bx */
            v[ax] = v[3 + ax] = (float)P[ax];
            v[bx] = v[3 + bx] = (float)P[bx];
            break;
        case 3: /* a vertex on the voxel corner */
            for (a = 0; a < 3; a++) v[a] = (float)P[a];
            break;
        case 4: /* a vertex on the corner and the opposite edge in a plane through it */
            for (a = 0; a < 3; a++) v[a] = (float)P[a];
            v[3 + ax] = v[6 + ax] = (float)P[ax];
            break;
        case 5: /* a segment on the voxel edge line, or a point on the corner */
            for (a = 0; a < 3; a++) v[a] = v[3 + a] = (float)P[a];
            v[3 + ax] = (float)(P[ax] + fx_rng_range(r, -L, L) * s);
            if (rng_int(r, 3) == 0) v[3 + ax] = (float)P[ax];
            for (a = 0; a < 3; a++) v[6 + a] = v[3 * rng_int(r, 2) + a];
            break;
        case 6: /* a face almost in the plane: a float or two off */
            for (k = 0; k < 3; k++) v[3 * k + ax] = ulps((float)P[ax], rng_int(r, 5) - 2);
            break;
        default: /* two vertices in the plane */
            v[ax] = v[3 + ax] = (float)P[ax];
            break;
        }
        maybe_nudge(r, v);
    }
}

/* The nearest float to a grid plane, or a few floats off it. */
static float near_plane(fx_rng *r, const voxgi_grid *g, int a, double u)
{
    return ulps((float)(g->origin[a] + floor(u) * g->voxel_size), rng_int(r, 5) - 2);
}

/* Random triangles (needles, slivers, faces almost parallel to voxel faces) whose coordinates are
   floats next to grid planes, on any origin, as a plain fuzz would make them. */
static void gen_near_group(fx_rng *r, ex_group *G)
{
    double X = pick_base(r), s = pick_size(r, fabs(X) > 100);
    int a, k, i;
    pick_res(r, &G->g);
    G->g.voxel_size = s;
    for (a = 0; a < 3; a++) G->g.origin[a] = X + fx_rng_range(r, -s, s);
    for (i = 0; i < G->ntri; i++) {
        float *v = G->v[i];
        int shape = rng_int(r, 4), flat = rng_int(r, 3);
        double L = rng_int(r, 2) ? 0.5 : 3.0, C[3];
        for (a = 0; a < 3; a++) C[a] = fx_rng_range(r, 1, G->g.res[a] - 1);
        for (k = 0; k < 3; k++)
            for (a = 0; a < 3; a++) {
                double u = C[a] + fx_rng_range(r, -L, L);
                v[3 * k + a] = rng_int(r, 2) ? near_plane(r, &G->g, a, u + 0.5) : (float)(G->g.origin[a] + u * s);
            }
        if (shape == 0) /* a needle */
            for (a = 0; a < 3; a++) v[6 + a] = ulps((float)(0.5 * ((double)v[a] + v[3 + a])), rng_int(r, 5) - 2);
        if (shape == 1) /* almost parallel to a voxel face */
            for (k = 0; k < 3; k++) v[3 * k + flat] = ulps(v[flat], rng_int(r, 3) - 1);
    }
}

/* Group n of a family (its own generator, seeded by family and n). */
static void make_group(int family, int n, ex_group *G)
{
    fx_rng r = fx_rng_seeded(0x5eed0000ull + 0x100000ull * (uint64_t)family + (uint64_t)n);
    int i, tries;
    memset(G, 0, sizeof *G);
    G->family = family;
    G->n = n;
    G->ntri = EX_TRIS;
    if (family == FAM_GRID) gen_grid_group(&r, G);
    else if (family == FAM_NEAR) gen_near_group(&r, G);
    else {
        ex_frame f;
        pick_frame(&r, G, &f);
        for (i = 0; i < G->ntri; i++)
            for (tries = 0; tries < 50; tries++)
                if (family == FAM_PLANE ? gen_plane_tri(&r, G, &f, G->v[i]) : gen_line_tri(&r, G, &f, G->v[i])) break;
    }
}

/* ---------------------------------------------------------------- library runs and comparison */
static uint32_t *lib_bits(voxgi_context *ctx, const voxgi_grid *g, const float *v, size_t ntri, voxgi_method method,
                          voxgi_voxels_info *info)
{
    static const uint32_t idx[3 * EX_TRIS] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17,
                                              18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31, 32, 33, 34, 35};
    voxgi_mesh mesh;
    voxgi_scene sc;
    voxgi_voxelize_desc vd;
    scene_of_triangles(&sc, &mesh, v, 3 * ntri, idx, ntri);
    memset(&vd, 0, sizeof vd);
    vd.grid = *g;
    vd.method = method;
    return voxelized_bits(ctx, &sc, &vd, info);
}

typedef struct ex_stats {
    uint64_t triangles, groups, far, oracle_voxels, set, touching, thin_set, lib_exact_tests;
    uint64_t differ[2], differ_tris[2]; /* conservative, thin: voxels and triangles (GL: groups) */
    uint64_t missed[2];                 /* of which the library missed (the rest it set wrongly) */
    int printed;                        /* triangles reported */
} ex_stats;
static int g_printed; /* triangles reported by the tests so far (a few in all) */

static void print_grid(const ex_group *G)
{
    printf("      grid origin (%a, %a, %a) = (%.17g, %.17g, %.17g), voxel size %a = %.17g, res %d x %d x %d\n", G->g.origin[0],
           G->g.origin[1], G->g.origin[2], G->g.origin[0], G->g.origin[1], G->g.origin[2], G->g.voxel_size, G->g.voxel_size,
           G->g.res[0], G->g.res[1], G->g.res[2]);
}

/* Triangle t of G, exactly (hexadecimal floats) and readably, and its grid. */
static void print_triangle(const ex_group *G, int t)
{
    const float *v = G->v[t];
    int k;
    printf("      triangle");
    for (k = 0; k < 3; k++) printf(" (%a, %a, %a)", (double)v[3 * k], (double)v[3 * k + 1], (double)v[3 * k + 2]);
    printf("\n        = (%.9g, %.9g, %.9g) (%.9g, %.9g, %.9g) (%.9g, %.9g, %.9g)\n", v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]);
    print_grid(G);
}

/* The oracle's bits for triangle t of G (conservative, and thin in *thin), counting into st. */
static void oracle_bits(ox *x, const ex_group *G, int t, uint32_t *cons, uint32_t *thin, ex_stats *st)
{
    int idx[3], a;
    ox_set(x, &G->g, G->v[t]);
    for (idx[2] = (int)x->rlo[2]; idx[2] <= x->rhi[2]; idx[2]++)
        for (idx[1] = (int)x->rlo[1]; idx[1] <= x->rhi[1]; idx[1]++)
            for (idx[0] = (int)x->rlo[0]; idx[0] <= x->rhi[0]; idx[0]++) {
                int touch, in = 1;
                uint64_t l;
                for (a = 0; a < 3; a++) in &= idx[a] >= 0 && idx[a] < G->g.res[a];
                if (!in) continue;
                st->oracle_voxels++;
                if (!ox_meets(x, idx, &touch)) continue;
                l = (uint64_t)idx[0] + (uint64_t)G->g.res[0] * ((uint64_t)idx[1] + (uint64_t)G->g.res[1] * (uint64_t)idx[2]);
                cons[l >> 5] |= 1u << (l & 31);
                st->set++;
                st->touching += (uint64_t)touch;
                if (ox_thin(x, idx)) {
                    thin[l >> 5] |= 1u << (l & 31);
                    st->thin_set++;
                }
            }
}

/* Voxels where the library's bits and the oracle's differ (*missed: those it left unset); the
   first few triangles reported. */
static uint64_t compare(const uint32_t *lib, const uint32_t *ref, const ex_group *G, int t, const char *what, uint64_t *missed,
                        ex_stats *st)
{
    uint64_t n = voxgi_grid_voxel_count(&G->g), l, diff = 0, shown = 0;
    const int *res = G->g.res;
    for (l = 0; l < n; l++)
        if (voxgi_bit_get(lib, l) != voxgi_bit_get(ref, l)) {
            diff++;
            *missed += (uint64_t)voxgi_bit_get(ref, l);
        }
    if (!diff || st->printed >= 6) return diff;
    if (t >= 0)
        printf("    %s, %s, group %d, triangle %d: %llu voxels differ:", what, fam_name[G->family], G->n, t, (unsigned long long)diff);
    else printf("    %s, %s, group %d (its %d triangles as one mesh): %llu voxels differ:", what, fam_name[G->family], G->n, G->ntri,
                (unsigned long long)diff);
    for (l = 0; l < n && shown < 4; l++)
        if (voxgi_bit_get(lib, l) != voxgi_bit_get(ref, l))
            printf("%s voxel (%d,%d,%d) library %d exact %d", shown++ ? ";" : "", (int)(l % (uint64_t)res[0]),
                   (int)(l / (uint64_t)res[0] % (uint64_t)res[1]), (int)(l / ((uint64_t)res[0] * (uint64_t)res[1])), voxgi_bit_get(lib, l),
                   voxgi_bit_get(ref, l));
    printf("%s\n", diff > shown ? "; ..." : "");
    if (t >= 0) print_triangle(G, t);
    else print_grid(G);
    st->printed++;
    return diff;
}

/* Every triangle of the group alone on cpu (when not NULL), conservative and thin, against the
   oracle; then the group as one mesh on gl (when not NULL) against the union. */
static void check_group(voxgi_context *cpu, voxgi_context *gl, ox *x, const ex_group *G, ex_stats *st)
{
    size_t words = (size_t)((voxgi_grid_voxel_count(&G->g) + 31) / 32), w;
    uint32_t *all = (uint32_t *)calloc(words, 4), *cons = (uint32_t *)malloc(words * 4), *thin = (uint32_t *)malloc(words * 4);
    int t, m;
    st->groups++;
    st->far += fabs(G->g.origin[0]) > 1000;
    for (t = 0; t < G->ntri; t++) {
        memset(cons, 0, words * 4);
        memset(thin, 0, words * 4);
        oracle_bits(x, G, t, cons, thin, st);
        for (w = 0; w < words; w++) all[w] |= cons[w];
        st->triangles++;
        for (m = 0; cpu && m < 2; m++) {
            voxgi_voxels_info info;
            uint32_t *lib = lib_bits(cpu, &G->g, G->v[t], 1, m ? VOXGI_METHOD_THIN : VOXGI_METHOD_CONSERVATIVE, &info);
            uint64_t d = lib ? compare(lib, m ? thin : cons, G, t, m ? "thin" : "conservative", &st->missed[m], st) : 1;
            st->differ[m] += d;
            st->differ_tris[m] += d != 0;
            if (lib) st->lib_exact_tests += info.exact_tests;
            free(lib);
        }
    }
    if (gl) {
        voxgi_voxels_info info;
        uint32_t *lib = lib_bits(gl, &G->g, &G->v[0][0], (size_t)G->ntri, VOXGI_METHOD_CONSERVATIVE, &info);
        uint64_t d = lib ? compare(lib, all, G, -1, "conservative on GL", &st->missed[0], st) : 1;
        st->differ[0] += d;
        st->differ_tris[0] += d != 0;
        if (lib) st->lib_exact_tests += info.exact_tests;
        free(lib);
    }
    free(all);
    free(cons);
    free(thin);
}

/* ---------------------------------------------------------------- tests */
static int fuzz_rounds(void)
{
    const char *e = getenv("VOXGI_EXACT_FUZZ");
    int n = e ? atoi(e) : 1;
    return n < 1 ? 1 : n;
}

/* Groups per family in the default run; in the reduced builds (FX_REDUCED) every REDUCED_SHARE-th
   of them; on GL every GL_SHARE-th (llvmpipe takes milliseconds a draw). */
#define GROUPS_PER_FAMILY 40
#define REDUCED_SHARE 5
#define GL_SHARE 4

static void report(const char *what, const ex_stats *st)
{
    printf("    %s: %llu triangles in %llu groups (%llu far from the origin), %llu oracle voxels, %llu set (%llu only touching), "
           "%llu thin; library exact tests %llu\n",
           what, (unsigned long long)st->triangles, (unsigned long long)st->groups, (unsigned long long)st->far,
           (unsigned long long)st->oracle_voxels, (unsigned long long)st->set, (unsigned long long)st->touching,
           (unsigned long long)st->thin_set, (unsigned long long)st->lib_exact_tests);
}

/* The family's groups on the CPU, triangle by triangle, or on GL, group by group. */
static void fuzz_family(int family, int on_gl)
{
    voxgi_context *ctx = make_ctx(on_gl ? VOXGI_BACKEND_GL : VOXGI_BACKEND_CPU, 1);
    ox x;
    ex_stats st;
    int n, groups = GROUPS_PER_FAMILY * fuzz_rounds(), step = (FX_REDUCED ? REDUCED_SHARE : 1) * (on_gl ? GL_SHARE : 1);
    char what[80];
    TH_CHECK(ctx != NULL, "no %s context", on_gl ? "GL" : "CPU");
    if (!ctx) return;
    memset(&st, 0, sizeof st);
    st.printed = g_printed;
    ox_init(&x);
    for (n = 0; n < groups; n += step) {
        ex_group G;
        make_group(family, n, &G);
        check_group(on_gl ? NULL : ctx, on_gl ? ctx : NULL, &x, &G, &st);
    }
    ox_clear(&x);
    voxgi_destroy(ctx);
    g_printed = st.printed;
    snprintf(what, sizeof what, "%s%s", fam_name[family], on_gl ? " (GL)" : "");
    report(what, &st);
    TH_CHECK(st.differ[0] == 0, "%s: %llu voxels of %llu %s differ from exact conservative voxelization (%llu missed, %llu extra)",
             what, (unsigned long long)st.differ[0], (unsigned long long)st.differ_tris[0], on_gl ? "groups" : "triangles",
             (unsigned long long)st.missed[0], (unsigned long long)(st.differ[0] - st.missed[0]));
    TH_CHECK(st.differ[1] == 0, "%s: %llu voxels of %llu triangles differ from exact thin voxelization (%llu missed, %llu extra)", what,
             (unsigned long long)st.differ[1], (unsigned long long)st.differ_tris[1], (unsigned long long)st.missed[1],
             (unsigned long long)(st.differ[1] - st.missed[1]));
    /* the oracle is neither trivially true nor false, and the tie families do reach ties */
    TH_CHECK(st.set > 0 && st.set < st.oracle_voxels && st.thin_set > 0 && st.thin_set < st.set,
             "%s: the oracle set %llu of %llu voxels (thin %llu)", what, (unsigned long long)st.set, (unsigned long long)st.oracle_voxels,
             (unsigned long long)st.thin_set);
    TH_CHECK(family == FAM_NEAR || st.touching > 0, "%s: no voxel only touches its triangle", what);
}

static void test_exact_plane_through_voxel_edges(void) { fuzz_family(FAM_PLANE, 0); }
static void test_exact_edge_through_voxel_corners(void) { fuzz_family(FAM_LINE, 0); }
static void test_exact_on_grid_planes(void) { fuzz_family(FAM_GRID, 0); }
static void test_exact_near_grid_planes(void) { fuzz_family(FAM_NEAR, 0); }

/* The GL backend, whole groups at once (it hands what its filter cannot decide to the CPU). */
static void test_exact_gl(void)
{
    int f;
    if (!have_gl()) return;
    for (f = 0; f < FAM_COUNT; f++) fuzz_family(f, 1);
}

int main(void)
{
    gl_open();
    TH_RUN(test_exact_plane_through_voxel_edges);
    TH_RUN(test_exact_edge_through_voxel_corners);
    TH_RUN(test_exact_on_grid_planes);
    TH_RUN(test_exact_near_grid_planes);
    TH_RUN(test_exact_gl);
    gl_close();
    return th_finish();
}
