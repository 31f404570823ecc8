// Shared by the triangle passes (voxelize_conservative.glsl, voxelize_solid.glsl), after
// scene.glsl: the per-triangle setup, test forms and error bounds of voxgi.h's exact voxelizer,
// the same arithmetic in double.

// dispatch (x, y, z) for pass 1, then counters
layout(std430, binding = VOXGI_BINDING_CONTROL) buffer Control { uint big_dispatch; uint split_y; uint split_z; uint big_count; uint pair_count; uint flagged_count; };
layout(std430, binding = VOXGI_BINDING_PAIRS) buffer Pairs { uvec4 pairs[]; };
layout(std430, binding = VOXGI_BINDING_FLAGS) buffer Flags { uint tri_flags[]; };
layout(std430, binding = VOXGI_BINDING_BIG) buffer Big { uint big_list[]; };


layout(location = VOXGI_LOC_u_tri_count) uniform uint u_tri_count;
layout(location = VOXGI_LOC_u_tri_offset) uniform uint u_tri_offset;
layout(location = VOXGI_LOC_u_inv_s) uniform double u_inv_s;
layout(location = VOXGI_LOC_u_pair_capacity) uniform uint u_pair_capacity;
layout(location = VOXGI_LOC_u_pass) uniform int u_pass;
layout(location = VOXGI_LOC_u_solid_axis) uniform int u_solid_axis;  // solid parity: keep triangles below the grid on this axis, else -1

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
    if (u_solid_axis >= 0 && uhi[u_solid_axis] < 0) { ulo[u_solid_axis] = 0; uhi[u_solid_axis] = 0; }
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
    double v = 0.0LF, bound = 0.0LF, g = 0.0LF;
    ivec3 off = side == 0 ? L.off0 : L.off1;
    for (int a = 0; a < 3; a++) {
        double ta = double(rel[a] + off[a]) - r[L.vertex][a];
        double dt = dr[L.vertex][a] + U * abs(ta);
        v += L.k[a] * ta;
        bound += abs(L.k[a]) * dt + L.dk[a] * abs(ta) + L.dk[a] * dt;
        g += abs(L.k[a] * ta);
    }
    return sign_within(v, (bound + gamma_(3.0LF) * g * 1.01LF) * 1.001LF);
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

// Pass 0 lists a triangle of more than VOXGI_SMALL_COLUMNS columns (rows along b, columns
// along a) for pass 1, and sizes pass 1's indirect dispatch: one work group column per listed
// triangle, and enough work groups per triangle that no lane gets more than two chunks
// (VOXGI_SMALL_COLUMNS columns). Bounded work per invocation is not only speed: llvmpipe cuts
// off invocations that loop too long and their voxels would be lost without a trace.
const int CHUNK = 32;
bool listed_as_big(uint t, int a, int b)
{
    if (ext[a] * ext[b] <= VOXGI_SMALL_COLUMNS) return false;
    uint at = atomicAdd(big_count, 1u);
    big_list[at] = t;
    atomicMax(big_dispatch, min(at + 1u, 65535u));
    uint items = uint(ext[b] * ((ext[a] + CHUNK - 1) / CHUNK));
    atomicMax(split_y, min((items + uint(2 * VOXGI_LOCAL_SIZE) - 1u) / uint(2 * VOXGI_LOCAL_SIZE), 65535u));
    return true;
}

// Pass 1 splits a big triangle's rows into chunks of columns, one per lane. Lanes beyond an
// upper bound of its chunks (from the vertices' voxel ranges alone, whatever the column axis)
// skip the triangle without its setup.
bool lane_has_work(uint t, uint lane)
{
    uint v0 = tri_index[3u * t], v1 = tri_index[3u * t + 1u], v2 = tri_index[3u * t + 2u];
    ivec3 extent = min(max(vp[v0].hi.xyz, max(vp[v1].hi.xyz, vp[v2].hi.xyz)), u_res - 1) -
              max(min(vp[v0].lo.xyz, min(vp[v1].lo.xyz, vp[v2].lo.xyz)), ivec3(0)) + 1;
    int m = max(extent.x, max(extent.y, extent.z));
    return lane < uint(m * ((m + CHUNK - 1) / CHUNK));
}

