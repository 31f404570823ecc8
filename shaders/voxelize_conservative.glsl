// Exact conservative voxelization, the GL twin of voxgi.h's CPU voxelizer (same tests, same
// error bounds). One invocation per triangle (pass 0); triangles with many columns are listed
// and split over rows and column chunks by pass 1, so one huge triangle is spread over
// thousands of invocations. Every sign the double filter cannot certify is handed to the CPU:
// single voxels as (triangle, voxel) pairs, whole triangles through a flag bit.
layout(local_size_x = VOXGI_LOCAL_SIZE) in;

struct VPrep {
    dvec4 q;   // xyz: (v - o) / s;  w: fraction bits of an exact q, or -1
    ivec4 lo;  // exact voxel range of the coordinate; w: bit a set when q[a] is exact
    ivec4 hi;
    vec4 w;    // the float vertex
    vec4 pad;
};
layout(std430, binding = 0) readonly buffer Verts { VPrep vp[]; };
layout(std430, binding = 1) readonly buffer Tris { uint tri_index[]; };
layout(std430, binding = 2) buffer Bits { uint bits[]; };
// dispatch (x, y, z) for pass 1, then counters
layout(std430, binding = 3) buffer Control { uint big_dispatch; uint split_y; uint split_z; uint big_count; uint pair_count; uint flagged_count; };
layout(std430, binding = 4) buffer Pairs { uvec4 pairs[]; };
layout(std430, binding = 5) buffer Flags { uint tri_flags[]; };
layout(std430, binding = 6) buffer Big { uint big_list[]; };

uniform ivec3 u_res;
uniform uint u_tri_count;
uniform uint u_tri_offset;
uniform double u_inv_s;
uniform uint u_pair_capacity;
uniform int u_pass;
uniform int u_thin;        // 1: the thin (6-separating) tests too

const double U = 1.1102230246251565404e-16LF; // 2^-53
const int UNKNOWN = 2;
double gamma_(double k) { return k * U / (1.0LF - k * U); }

struct Lin { dvec3 k; dvec3 dk; dvec2 v0; double vc; double err; ivec3 off0; ivec3 off1; int orient; int vertex; };

uint T;
ivec3 lo, hi, ext;
bvec3 one_slice;
dvec3 r[3], dr[3], e[3], de[3];
dvec3 n, dn;
ivec3 sig;
bool exact;
Lin plane;
Lin proj[9];
ivec3 proj_count;

bool setup(uint t)
{
    T = t;
    uint vi[3];
    for (int k = 0; k < 3; k++) vi[k] = tri_index[3u * t + uint(k)];
    ivec3 ulo = min(vp[vi[0]].lo.xyz, min(vp[vi[1]].lo.xyz, vp[vi[2]].lo.xyz));
    ivec3 uhi = max(vp[vi[0]].hi.xyz, max(vp[vi[1]].hi.xyz, vp[vi[2]].hi.xyz));
    lo = max(ulo, ivec3(0));
    hi = min(uhi, u_res - 1);
    if (any(greaterThan(lo, hi))) return false;
    one_slice = equal(ulo, uhi);
    ext = hi - lo + 1;
    double m = 0.0LF;
    bool lattice = true;
    int fb = 0;
    for (int k = 0; k < 3; k++) {
        dvec3 q = vp[vi[k]].q.xyz;
        int frac = int(vp[vi[k]].q.w), exact_axes = vp[vi[k]].lo.w;
        r[k] = q - dvec3(lo);
        dr[k] = 2.01LF * U * abs(q) + U * abs(r[k]);
        for (int a = 0; a < 3; a++)
            if (((exact_axes >> a) & 1) != 0) dr[k][a] = 0.0LF;
        m = max(m, max(max(abs(r[k].x), abs(r[k].y)), max(abs(r[k].z), double(max(ext.x, max(ext.y, ext.z))))));
        lattice = lattice && frac >= 0;
        fb = max(fb, frac);
    }
    exact = false;
    if (lattice) {
        int nbits = 0;
        while (nbits < 20 && double(1 << nbits) < 2.0LF * m + 1.0LF) nbits++;
        exact = nbits + fb <= 16;
    }
    for (int k = 0; k < 3; k++) {
        int j = (k + 1) % 3;
        if (exact) {
            e[k] = r[j] - r[k];
            de[k] = dvec3(0.0LF);
        } else {
            e[k] = (dvec3(vp[vi[j]].w.xyz) - dvec3(vp[vi[k]].w.xyz)) * u_inv_s;
            de[k] = 3.01LF * U * abs(e[k]);
        }
    }
    for (int c = 0; c < 3; c++) {
        int a = (c + 1) % 3, b = (c + 2) % 3;
        double e0a = e[0][a], e0b = e[0][b], fa = -e[2][a], fb2 = -e[2][b];
        double p1 = e0a * fb2, p2 = e0b * fa;
        n[c] = p1 - p2;
        dn[c] = exact ? 0.0LF
                      : (abs(e0a) * de[2][b] + abs(fb2) * de[0][a] + de[0][a] * de[2][b] +
                         abs(e0b) * de[2][a] + abs(fa) * de[0][b] + de[0][b] * de[2][a] +
                         gamma_(2.0LF) * (abs(p1) + abs(p2))) * 1.001LF;
        if (n[c] > dn[c]) sig[c] = 1;
        else if (n[c] < -dn[c]) sig[c] = -1;
        else sig[c] = dn[c] == 0.0LF ? 0 : UNKNOWN;
    }
    return true;
}

Lin lin_make(dvec3 k, dvec3 dk, int vk)
{
    Lin L;
    L.off0 = ivec3(lessThan(k, dvec3(0.0LF)));
    L.off1 = ivec3(greaterThan(k, dvec3(0.0LF)));
    L.v0.x = k.x * (double(L.off0.x) - r[vk].x) + k.y * (double(L.off0.y) - r[vk].y) + k.z * (double(L.off0.z) - r[vk].z);
    L.v0.y = k.x * (double(L.off1.x) - r[vk].x) + k.y * (double(L.off1.y) - r[vk].y) + k.z * (double(L.off1.z) - r[vk].z);
    L.vc = k.x * (0.5LF - r[vk].x) + k.y * (0.5LF - r[vk].y) + k.z * (0.5LF - r[vk].z);
    double s = 0.0LF, mag = 0.0LF;
    for (int a = 0; a < 3; a++) {
        double Tm = abs(r[vk][a]) + 1.0LF + double(ext[a]);
        s += abs(k[a]) * dr[vk][a] + Tm * dk[a] + dk[a] * dr[vk][a];
        mag += abs(k[a]) * Tm;
    }
    L.k = k;
    L.dk = dk;
    L.vertex = vk;
    L.err = exact ? 0.0LF : (s + gamma_(8.0LF) * mag * 1.01LF) * 1.001LF;
    L.orient = 0;
    return L;
}

void forms()
{
    plane = lin_make(n, dn, 0);
    for (int c = 0; c < 3; c++) {
        int a = (c + 1) % 3, b = (c + 2) % 3, best = -1, cnt = 0;
        double len = 0.0LF;
        for (int k = 0; k < 3; k++) {
            double l = abs(e[k][a]) + abs(e[k][b]);
            if (l > len) { len = l; best = k; }
        }
        for (int k = 0; k < 3; k++) {
            int o = sig[c];
            if (o == 0 && k != best) continue;
            double os = o != 0 ? double(o) : 1.0LF;
            dvec3 m = dvec3(0.0LF), dm = dvec3(0.0LF);
            m[a] = -e[k][b] * os;
            m[b] = e[k][a] * os;
            dm[a] = de[k][b];
            dm[b] = de[k][a];
            Lin L = lin_make(m, dm, k);
            L.orient = o;
            proj[3 * c + cnt] = L;
            cnt++;
        }
        proj_count[c] = cnt;
    }
}

int sign_within(double v, double err)
{
    if (v > err) return 1;
    if (v < -err) return -1;
    return err == 0.0LF ? 0 : UNKNOWN;
}

// A bound for this voxel alone (see voxgi__sign_tight): exact ties need no CPU help.
int sign_tight(Lin L, int side, ivec3 rel)
{
    double v = 0.0LF, e = 0.0LF, g = 0.0LF;
    ivec3 off = side == 0 ? L.off0 : L.off1;
    for (int a = 0; a < 3; a++) {
        double ta = double(rel[a] + off[a]) - r[L.vertex][a];
        double dt = dr[L.vertex][a] + U * abs(ta);
        v += L.k[a] * ta;
        e += abs(L.k[a]) * dt + L.dk[a] * abs(ta) + L.dk[a] * dt;
        g += abs(L.k[a] * ta);
    }
    return sign_within(v, (e + gamma_(3.0LF) * g * 1.01LF) * 1.001LF);
}

// 1 pass, 0 fail, UNKNOWN when the bound cannot tell
int test_lin(Lin L, ivec3 rel)
{
    int result = 1;
    dvec3 dr3 = dvec3(rel);
    for (int side = L.orient != 0 ? 1 : 0; side < 2; side++) {
        double v = (side == 0 ? L.v0.x : L.v0.y) + L.k.x * dr3.x + L.k.y * dr3.y + L.k.z * dr3.z;
        int s = sign_within(v, L.err);
        if (s == UNKNOWN) s = sign_tight(L, side, rel);
        if (s == UNKNOWN) result = UNKNOWN;
        else if (side == 0 ? s > 0 : s < 0) return 0;
    }
    return result;
}

int combine(int a, int b) { return (a == 0 || b == 0) ? 0 : max(a, b); }

// One side of a thin test for this voxel alone (see voxgi__sign_thin_tight).
int sign_thin_tight(Lin L, int side, ivec3 rel)
{
    int known = 0;
    for (int j = 0; j < 3; j++) {
        double v = 0.0LF, e = 0.0LF, gm = 0.0LF, sj = L.k[j] > 0.0LF ? 1.0LF : -1.0LF;
        for (int a = 0; a < 3; a++) {
            double off = a == j ? 0.5LF + (side == 1 ? 0.5LF : -0.5LF) * sj : 0.5LF;
            double ta = (double(rel[a]) + off) - r[L.vertex][a];
            double dt = dr[L.vertex][a] + U * abs(ta);
            v += L.k[a] * ta;
            e += abs(L.k[a]) * dt + L.dk[a] * abs(ta) + L.dk[a] * dt;
            gm += abs(L.k[a] * ta);
        }
        if (abs(L.k[j]) <= L.dk[j]) e += L.dk[j];
        e += gamma_(3.0LF) * gm * 1.01LF;
        int s = sign_within(v, e == 0.0LF ? 0.0LF : e * 1.001LF);
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

int test_projection(int c, ivec3 rel)
{
    int result = 1;
    for (int i = 0; i < proj_count[c]; i++) {
        result = combine(result, test_lin(proj[3 * c + i], rel));
        if (result == 0) return 0;
    }
    return result;
}

void flag_triangle()
{
    atomicOr(tri_flags[T >> 5], 1u << (T & 31u));
    atomicAdd(flagged_count, 1u);
}

void emit(ivec3 rel, int status)
{
    if (u_thin != 0 && status != 0) status = combine(status, test_thin(rel));
    ivec3 v = lo + rel;
    if (status == 1) {
        uint idx = uint(v.x) + uint(u_res.x) * (uint(v.y) + uint(u_res.y) * uint(v.z));
        uint mask = 1u << (idx & 31u);
        if ((bits[idx >> 5] & mask) == 0u) atomicOr(bits[idx >> 5], mask);
    } else if (status == UNKNOWN) {
        uint at = atomicAdd(pair_count, 1u);
        if (at < u_pair_capacity) pairs[at] = uvec4(T, uvec3(v));
        else flag_triangle();
    }
}

// Columns [first, last] of a row that can pass the oriented projection tests (a superset).
ivec2 row_span(int c, int rel_b)
{
    int a = (c + 1) % 3, b = (c + 2) % 3;
    double first = 0.0LF, last = double(ext[a] - 1);
    for (int i = 0; i < proj_count[c]; i++) {
        Lin L = proj[3 * c + i];
        if (L.orient == 0) break;
        double g = L.v0.y + L.k[b] * double(rel_b) + L.err, ka = L.k[a];
        if (ka > 0.0LF) first = max(first, floor(-g / ka) - 1.0LF);
        else if (ka < 0.0LF) last = min(last, ceil(-g / ka) + 1.0LF);
        else if (g < 0.0LF) last = -1.0LF;
    }
    return first > last ? ivec2(1, 0) : ivec2(int(first), int(last));
}

ivec2 cell_range(double zlo, double zhi, int maxi)
{
    double f = ceil(zlo) - 1.0LF, l = floor(zhi);
    return ivec2(f < 0.0LF ? 0 : (f > double(maxi) ? maxi + 1 : int(f)), l > double(maxi) ? maxi : (l < 0.0LF ? -1 : int(l)));
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

const int CHUNK = 32;

void main()
{
    int single;
    if (u_pass == 0) {
        uint t = u_tri_offset + gl_GlobalInvocationID.x;
        if (t >= u_tri_count) return;
        int c = prepare(t, single);
        if (c < 0) return;
        int a = (c + 1) % 3, b = (c + 2) % 3;
        if (ext[a] * ext[b] > VOXGI_SMALL_COLUMNS) {
            uint at = atomicAdd(big_count, 1u);
            big_list[at] = t;
            atomicMax(big_dispatch, min(at + 1u, 65535u));
            return;
        }
        for (int rb = 0; rb < ext[b]; rb++) {
            ivec2 span = sig[c] != 0 ? row_span(c, rb) : ivec2(0, ext[a] - 1);
            do_columns(c, single, rb, span.x, span.y);
        }
    } else {
        uint lanes = gl_NumWorkGroups.y * gl_WorkGroupSize.x;
        uint lane = gl_WorkGroupID.y * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
        for (uint bi = gl_WorkGroupID.x; bi < big_count; bi += gl_NumWorkGroups.x) {
            int c = prepare(big_list[bi], single);
            int a = (c + 1) % 3, b = (c + 2) % 3;
            int chunks = (ext[a] + CHUNK - 1) / CHUNK;
            uint items = uint(ext[b] * chunks);
            for (uint item = lane; item < items; item += lanes) {
                int rb = int(item) / chunks, ch = int(item) % chunks;
                ivec2 span = sig[c] != 0 ? row_span(c, rb) : ivec2(0, ext[a] - 1);
                do_columns(c, single, rb, max(span.x, ch * CHUNK), min(span.y, ch * CHUNK + CHUNK - 1));
            }
        }
    }
}
