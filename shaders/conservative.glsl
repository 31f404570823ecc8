// Exact conservative (and thin) voxel tests of one triangle's columns, after scene.glsl and
// triangle.glsl: the GL twin of voxgi.h's CPU voxelizer (same tests, same error bounds), shared
// by the compute voxelizer (voxelize_conservative.glsl) and the geometry-shader one
// (voxelize_geometry.glsl). Every sign the double filter cannot certify is handed to the CPU:
// single voxels as (triangle, voxel) pairs, whole triangles through a flag bit.

layout(std430, binding = VOXGI_BINDING_BITS) buffer Bits { uint bits[]; };
layout(location = VOXGI_LOC_u_thin) uniform int u_thin;        // 1: the thin (6-separating) tests too

// The attribute pass (u_attr 1): the bits are final; a voxel the tests set receives its
// triangle's fixed-point values, added to 64-bit sums (low word, then the carry into the high
// word: the total is exact whatever the order) after a count, at the voxel's rank.
layout(std430, binding = VOXGI_BINDING_RANK) readonly buffer Rank { uint rank[]; };
layout(std430, binding = VOXGI_BINDING_RECORDS) readonly buffer Rec { uint rec[]; };
layout(std430, binding = VOXGI_BINDING_SUMS) buffer Sums { uint sums[]; };
layout(location = VOXGI_LOC_u_attr) uniform int u_attr;
layout(location = VOXGI_LOC_u_channels) uniform int u_channels;
layout(location = VOXGI_LOC_u_max_channels) uniform uint u_max_channels; // bit c: channel c keeps the maximum (in the low word), else the sum

void add_attributes(uint idx)
{
    uint slot = rank[idx >> 5] + uint(bitCount(bits[idx >> 5] & ((1u << (idx & 31u)) - 1u)));
    uint base = slot * uint(1 + 2 * u_channels);
    atomicAdd(sums[base], 1u);
    for (int c = 0; c < u_channels; c++) {
        uint v = rec[T * uint(u_channels) + uint(c)], at = base + 1u + 2u * uint(c);
        if ((u_max_channels & (1u << uint(c))) != 0u) { atomicMax(sums[at], v); continue; }
        uint old = atomicAdd(sums[at], v);
        if (old + v < old) atomicAdd(sums[at + 1u], 1u);
    }
}

// One side of a thin test for this voxel alone (see voxgi__sign_thin_tight).
int sign_thin_tight(Lin L, int side, ivec3 rel)
{
    int known = 0;
    for (int j = 0; j < 3; j++) {
        double v = 0.0LF, bound = 0.0LF, gm = 0.0LF, sj = L.k[j] > 0.0LF ? 1.0LF : -1.0LF;
        for (int a = 0; a < 3; a++) {
            double off = a == j ? 0.5LF + (side == 1 ? 0.5LF : -0.5LF) * sj : 0.5LF;
            double ta = (double(rel[a]) + off) - r[L.vertex][a];
            double dt = dr[L.vertex][a] + U * abs(ta);
            v += L.k[a] * ta;
            bound += abs(L.k[a]) * dt + L.dk[a] * abs(ta) + L.dk[a] * dt;
            gm += abs(L.k[a] * ta);
        }
        if (abs(L.k[j]) <= L.dk[j]) bound += L.dk[j];
        bound += gamma_(3.0LF) * gm * 1.01LF;
        int s = sign_within(v, bound == 0.0LF ? 0.0LF : bound * 1.001LF);
        if (s == 0) return 0;
        if (s == 1) { if (side == 1) return 1; known++; }
        if (s == -1) { if (side == 0) return -1; known++; }
    }
    return known == 3 ? (side == 1 ? -1 : 1) : UNKNOWN;
}

// The form against the voxel's inscribed octahedron or diamond (see voxgi__test_lin_thin).
int test_lin_thin(Lin L, ivec3 rel)
{
    int result = 1;
    double vc = L.vc + L.k.x * double(rel.x) + L.k.y * double(rel.y) + L.k.z * double(rel.z);
    double T = 0.5LF * max(abs(L.k.x), max(abs(L.k.y), abs(L.k.z)));
    double dT = 0.5LF * max(L.dk.x, max(L.dk.y, L.dk.z));
    for (int side = L.orient != 0 ? 1 : 0; side < 2; side++) {
        double w = side == 1 ? vc + T : vc - T;
        int s = sign_within(w, L.err == 0.0LF && dT == 0.0LF ? 0.0LF : (L.err + dT + U * abs(w)) * 1.001LF);
        if (s == UNKNOWN) s = sign_thin_tight(L, side, rel);
        if (s == UNKNOWN) result = UNKNOWN;
        else if (side == 0 ? s > 0 : s < 0) return 0;
    }
    return result;
}

int test_thin(ivec3 rel)
{
    int result = combine(1, test_lin_thin(plane, rel)); // prepare() hands degenerate triangles over
    for (int c = 0; c < 3 && result != 0; c++)
        for (int i = 0; i < proj_count[c] && result != 0; i++) result = combine(result, test_lin_thin(proj[3 * c + i], rel));
    return result;
}

void emit(ivec3 rel, int status)
{
    if (u_thin != 0 && status != 0) status = combine(status, test_thin(rel));
    ivec3 v = lo + rel;
    if (status == 1) {
        uint idx = uint(v.x) + uint(u_res.x) * (uint(v.y) + uint(u_res.y) * uint(v.z));
        uint mask = 1u << (idx & 31u);
        if (u_attr != 0) add_attributes(idx);
        else if ((bits[idx >> 5] & mask) == 0u) atomicOr(bits[idx >> 5], mask);
    } else if (status == UNKNOWN) {
        uint at = atomicAdd(pair_count, 1u);
        if (at < u_pair_capacity) pairs[at] = uvec4(T, uvec3(v));
        else flag_triangle();
    }
}

// Voxels of columns [first, last] of one row, columns along axis c.
void do_columns(int c, int single, int rel_b, int first, int last)
{
    int a = (c + 1) % 3, b = (c + 2) % 3;
    for (int ra = first; ra <= last; ra++) {
        ivec3 rel = ivec3(0);
        rel[a] = ra;
        rel[b] = rel_b;
        int col = test_projection(c, rel);
        if (col == 0) continue;
        if (single >= 0) { emit(rel, col); continue; }
        ivec2 kr;
        double nc = n[c], dsum = dn.x + dn.y + dn.z;
        if (abs(nc) <= 4.0LF * dsum) kr = ivec2(0, ext[c] - 1);
        else {
            double ka = -n[a] / nc, kb = -n[b] / nc;
            double Da = abs(double(rel[a]) - r[0][a]) + 1.0LF, Db = abs(double(rel[b]) - r[0][b]) + 1.0LF;
            double z0 = r[0][c] + ka * (double(rel[a]) - r[0][a]) + kb * (double(rel[b]) - r[0][b]);
            double dka = (dn[a] + abs(ka) * dn[c]) / (abs(nc) - dn[c]);
            double dkb = (dn[b] + abs(kb) * dn[c]) / (abs(nc) - dn[c]);
            double m = 2.0LF * (dka * Da + dkb * Db) + 2.0LF * (dr[0][c] + abs(ka) * dr[0][a] + abs(kb) * dr[0][b]) +
                       1e-9LF * (1.0LF + abs(z0) + abs(ka) * Da + abs(kb) * Db);
            double zmin = z0 + min(ka, 0.0LF) + min(kb, 0.0LF), zmax = z0 + max(ka, 0.0LF) + max(kb, 0.0LF);
            kr = cell_range(zmin - m, zmax + m, ext[c] - 1);
        }
        for (int rc = kr.x; rc <= kr.y; rc++) {
            rel[c] = rc;
            int s = combine(col, test_lin(plane, rel));
            if (s != 0) s = combine(s, test_projection(a, rel));
            if (s != 0) s = combine(s, test_projection(b, rel));
            if (s != 0) emit(rel, s);
        }
    }
}

// Everything up to the choice of the column axis; returns it, or -1 when the triangle is done.
int prepare(uint t, out int single)
{
    single = -1;
    if (!setup(t)) return -1;
    int thin = 0;
    for (int a = 0; a < 3; a++)
        if (one_slice[a]) { thin++; single = a; }
    if (thin >= 2 && u_thin == 0) { // a column or a voxel: all of its range
        for (int k = lo.z; k <= hi.z; k++)
            for (int j = lo.y; j <= hi.y; j++)
                for (int i = lo.x; i <= hi.x; i++) emit(ivec3(i, j, k) - lo, 1);
        return -1;
    }
    if (any(equal(sig, ivec3(UNKNOWN))) || all(equal(sig, ivec3(0)))) { flag_triangle(); return -1; }
    forms();
    if (single >= 0) return single;
    int c = -1;
    for (int a = 0; a < 3; a++)
        if (sig[a] != 0 && (c < 0 || abs(n[a]) > abs(n[c]))) c = a;
    return c;
}

