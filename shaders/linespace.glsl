// The line space's walk (voxgi.h part 12, voxgi__ls_trace's GL twin), shared by the shadow rays
// of an area light (linespace_light.glsl) and of given rays (linespace_rays.glsl): each ray walked
// alone by the DDA. Every step is the CPU's float arithmetic in the CPU's order, so a ray's answer
// is the CPU's bit for bit: `precise` keeps each a * b + c two roundings (no fused
// multiply-add), and each quotient is the double quotient rounded to float (GLSL's float division
// may be 2.5 ulp off; a correctly rounded double quotient rounded again to float is the correctly
// rounded float quotient, as 53 >= 2 x 24 + 2 bits).
// embedded unless VOXGI_NO_LINE_SPACE
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 0) readonly buffer Nodes { uint node[]; };       // 2 per node: first child, line space or leaf
layout(std430, binding = 1) readonly buffer Bits0 { uint bits0[]; };      // the line spaces, u_words each, in parts of
layout(std430, binding = 8) readonly buffer Bits1 { uint bits1[]; };      // u_bits_part words (GL's storage blocks may be
layout(std430, binding = 9) readonly buffer Bits2 { uint bits2[]; };      // smaller than they)
layout(std430, binding = 10) readonly buffer Bits3 { uint bits3[]; };
layout(std430, binding = 2) readonly buffer Leaves { uint leaf[]; };      // 2 per leaf: first triangle reference, count
layout(std430, binding = 3) readonly buffer Refs { uint tris[]; };        // the leaves' triangles
layout(std430, binding = 4) readonly buffer Triangles { float tv[]; };    // 9 per triangle, relative to the centre
layout(location = VOXGI_LOC_u_count) uniform uint u_count;     // points (rays) in this slice
layout(location = VOXGI_LOC_u_n) uniform int u_n;              // children per axis
layout(location = VOXGI_LOC_u_depth) uniform int u_depth;
layout(location = VOXGI_LOC_u_words) uniform uint u_words;     // per line space
layout(location = VOXGI_LOC_u_bits_part) uniform uint u_bits_part; // words per part of the bits
layout(location = VOXGI_LOC_u_centre) uniform dvec3 u_centre;
layout(location = VOXGI_LOC_u_half) uniform float u_half;      // the root's half edge
layout(location = VOXGI_LOC_u_scale) uniform float u_scale;    // n / the root's edge
layout(location = VOXGI_LOC_u_fast) uniform int u_fast;
layout(location = VOXGI_LOC_u_near_ends) uniform float u_near_ends; // fast mode's exact zone at each end, the root's frame

const uint NONE = 0xFFFFFFFFu;
#define INF uintBitsToFloat(0x7F800000u)
const float EDGE_NEAR_ZERO = 4.76837158203125e-7; // VOXGI__EDGE_NEAR_ZERO, 2^-21

// a / b correctly rounded, as C's float division
float quot(float a, float b)
{
    return float(double(a) / double(b));
}

// The child (or patch) along an axis at coordinate p of a node's frame: [0, n - 1], clamped.
int cell_of(float p)
{
    return p < 1.0 ? 0 : (p >= float(u_n - 1) ? u_n - 1 : int(p));
}

// ---- the ray (voxgi__ls_ray): the root's frame for the tree, sheared for the triangles
precise vec3 r_o, r_d, r_ro;
float r_t0, r_t1;
precise float r_tn0, r_tn1; // fast mode reads bits as hits only between these
int r_kx, r_ky, r_kz;
precise float r_sx, r_sy, r_sz;

// voxgi__ls_ray_set_centred: the origin in the frame of the centre; false for a zero direction
bool ray_set_centred(vec3 ro, vec3 d, float t0, float t1)
{
    int kz = 0;
    for (int a = 0; a < 3; a++) {
        r_ro[a] = ro[a];
        r_o[a] = (r_ro[a] + u_half) * u_scale;
        r_d[a] = d[a] * u_scale;
        if (abs(d[a]) > abs(d[kz])) kz = a;
    }
    r_t0 = t0;
    r_t1 = t1;
    if (d[kz] == 0.0) return false;
    r_tn0 = t0 + quot(u_near_ends, abs(r_d[kz]));
    r_tn1 = t1 - quot(u_near_ends, abs(r_d[kz]));
    r_kz = kz;
    r_kx = (kz + 1) % 3;
    r_ky = (r_kx + 1) % 3;
    if (d[kz] < 0.0) { int k = r_kx; r_kx = r_ky; r_ky = k; } // keep the winding
    r_sx = quot(d[r_kx], d[kz]);
    r_sy = quot(d[r_ky], d[kz]);
    r_sz = quot(1.0, d[kz]);
    return true;
}

// voxgi__ls_tri_hit: the watertight test, edge functions within rounding of 0 again in double
bool tri_hit(uint t)
{
    uint b = 9u * t;
    int kx = r_kx, ky = r_ky, kz = r_kz;
    precise float az = tv[b + uint(kz)] - r_ro[kz], bz = tv[b + 3u + uint(kz)] - r_ro[kz], cz = tv[b + 6u + uint(kz)] - r_ro[kz];
    precise float ax = (tv[b + uint(kx)] - r_ro[kx]) - r_sx * az, ay = (tv[b + uint(ky)] - r_ro[ky]) - r_sy * az;
    precise float bx = (tv[b + 3u + uint(kx)] - r_ro[kx]) - r_sx * bz, by = (tv[b + 3u + uint(ky)] - r_ro[ky]) - r_sy * bz;
    precise float cx = (tv[b + 6u + uint(kx)] - r_ro[kx]) - r_sx * cz, cy = (tv[b + 6u + uint(ky)] - r_ro[ky]) - r_sy * cz;
    precise float p0 = cx * by, q0 = cy * bx, p1 = ax * cy, q1 = ay * cx, p2 = bx * ay, q2 = by * ax;
    precise float u = p0 - q0, w = p1 - q1, x = p2 - q2;
    if (abs(u) <= EDGE_NEAR_ZERO * (abs(p0) + abs(q0)) || abs(w) <= EDGE_NEAR_ZERO * (abs(p1) + abs(q1)) ||
        abs(x) <= EDGE_NEAR_ZERO * (abs(p2) + abs(q2))) {
        precise double U = double(cx) * double(by) - double(cy) * double(bx), W = double(ax) * double(cy) - double(ay) * double(cx),
                       X = double(bx) * double(ay) - double(by) * double(ax);
        if ((U < 0.0LF || W < 0.0LF || X < 0.0LF) && (U > 0.0LF || W > 0.0LF || X > 0.0LF)) return false;
        precise double D = U + W + X;
        if (D == 0.0LF) return false;
        precise double T = (U * double(az) + W * double(bz) + X * double(cz)) * double(r_sz) / D;
        return T > double(r_t0) && T < double(r_t1);
    }
    if ((u < 0.0 || w < 0.0 || x < 0.0) && (u > 0.0 || w > 0.0 || x > 0.0)) return false;
    precise float det = u + w + x;
    if (det == 0.0) return false;
    precise float num = (u * az + w * bz + x * cz) * r_sz;
    float t_hit = quot(num, det);
    return t_hit > r_t0 && t_hit < r_t1;
}

// voxgi__ls_leaf_hit
bool leaf_hit(uint l)
{
    uint first = leaf[2u * l], end = first + leaf[2u * l + 1u];
    for (uint k = first; k < end; k++)
        if (tri_hit(tris[k])) return true;
    return false;
}

// voxgi__ls_patch_at: the patch of a face of `axis` where the ray (o, d in a node's frame) meets it at t
int patch_at(vec3 o, vec3 d, float t, int axis)
{
    int u = (axis + 1) % 3, w = (axis + 2) % 3;
    precise float pu = o[u] + t * d[u], pw = o[w] + t * d[w];
    return cell_of(pu) * u_n + cell_of(pw);
}

// voxgi__ls_crossing_bit: line space `space`'s bit of the ray entering at ta by a face of axis ea and leaving at tb by one of axis xa
bool crossing_bit(uint space, vec3 o, vec3 d, float ta, float tb, int ea, int xa)
{
    int n2 = u_n * u_n, fs = 2 * ea + (d[ea] < 0.0 ? 1 : 0), ps = patch_at(o, d, ta, ea), fe = 2 * xa + (d[xa] > 0.0 ? 1 : 0), pe = patch_at(o, d, tb, xa);
    if (fs > fe) {
        int f = fs, p = ps;
        fs = fe; ps = pe; fe = f; pe = p;
    }
    uint bit = uint(((fs * 5 - fs * (fs - 1) / 2 + (fe - fs - 1)) * n2 + ps) * n2 + pe);
    uint w = space * u_words + (bit >> 5u), part = w / u_bits_part, at = w - part * u_bits_part;
    uint word = part == 0u ? bits0[at] : part == 1u ? bits1[at] : part == 2u ? bits2[at] : bits3[at];
    return ((word >> (bit & 31u)) & 1u) != 0u;
}

// voxgi__ls_slab over the root [0, n]^3
bool root_slab(out float ta, out float tb, out int ea, out int xa)
{
    float lo = 0.0, hi = float(u_n);
    ta = -INF;
    tb = INF;
    ea = xa = -1;
    for (int a = 0; a < 3; a++) {
        if (r_d[a] == 0.0) {
            if (r_o[a] < lo || r_o[a] > hi) return false;
            continue;
        }
        float inv = quot(1.0, r_d[a]);
        precise float tn = ((r_d[a] > 0.0 ? lo : hi) - r_o[a]) * inv, tf = ((r_d[a] > 0.0 ? hi : lo) - r_o[a]) * inv;
        if (tn > ta) { ta = tn; ea = a; }
        if (tf < tb) { tb = tf; xa = a; }
    }
    return ta <= tb;
}

// ---- the walk (voxgi__ls_level): the node being walked, and the nodes above it, suspended
uint w_node;
precise vec3 w_o, w_d, w_inv, w_next; // the ray in the node's frame; next: t where it leaves the current child along each axis
ivec3 w_cell;                          // the current child
float w_t, w_out;                      // where the current child was entered, and the node is left
int w_entry, w_exit;                   // the axes of those faces (-1: an end of the segment)
uint st_node[8];
vec3 st_o[8], st_d[8], st_inv[8], st_next[8];
ivec3 st_cell[8];
float st_t[8], st_out[8];
int st_entry[8], st_exit[8];

// voxgi__ls_level_start: walk node nd (the ray's frame o, d) from ta (entered by a face of axis ea) to tb (left by axis xa)
void level_start(uint nd, vec3 o, vec3 d, float ta, float tb, int ea, int xa)
{
    w_node = nd;
    w_t = ta;
    w_out = tb;
    w_entry = ea;
    w_exit = xa;
    w_o = o;
    w_d = d;
    for (int a = 0; a < 3; a++) {
        precise float p = o[a] + ta * d[a];
        int c = cell_of(p);
        w_cell[a] = c;
        w_inv[a] = d[a] == 0.0 ? INF : quot(1.0, d[a]); // never used along an axis the ray runs along: its next is inf
        w_next[a] = d[a] == 0.0 ? INF : (float(c + (d[a] > 0.0 ? 1 : 0)) - o[a]) * w_inv[a];
    }
}

void suspend(int s)
{
    st_node[s] = w_node; st_o[s] = w_o; st_d[s] = w_d; st_inv[s] = w_inv; st_next[s] = w_next;
    st_cell[s] = w_cell; st_t[s] = w_t; st_out[s] = w_out; st_entry[s] = w_entry; st_exit[s] = w_exit;
}

void resume(int s)
{
    w_node = st_node[s]; w_o = st_o[s]; w_d = st_d[s]; w_inv = st_inv[s]; w_next = st_next[s];
    w_cell = st_cell[s]; w_t = st_t[s]; w_out = st_out[s]; w_entry = st_entry[s]; w_exit = st_exit[s];
}

// voxgi__ls_trace: blocked by a triangle or, fast, by a set bit of the last line-space level
bool trace(bool fast)
{
    float ta, tb;
    int ea, xa, level = 0;
    if (node[0] == NONE || !root_slab(ta, tb, ea, xa)) return false; // an empty scene, or outside
    if (ta <= r_t0) { ta = r_t0; ea = -1; }
    if (tb >= r_t1) { tb = r_t1; xa = -1; }
    if (ta > tb) return false;
    if (ea >= 0 && xa >= 0) { // through the root
        if (!crossing_bit(node[1], r_o, r_d, ta, tb, ea, xa)) return false;
        if (fast && u_depth == 1 && ta >= r_tn0 && tb <= r_tn1) return true;
    }
    level_start(0u, r_o, r_d, ta, tb, ea, xa);
    for (;;) {
        float ca = w_t;
        if (!(ca <= w_out)) { // this node is done
            if (--level < 0) return false;
            resume(level);
            continue;
        }
        int m = w_next.y < w_next.x ? 1 : 0;
        float cb = m == 1 ? w_next.y : w_next.x;
        if (w_next.z < cb) { m = 2; cb = w_next.z; }
        if (cb >= w_out) { cb = w_out; xa = w_exit; }
        else xa = m;
        ea = w_entry;
        ivec3 c = w_cell;
        bool up = w_d[m] > 0.0;
        int cm = c[m] + (up ? 1 : -1); // on to the next child
        w_cell[m] = cm;
        w_next[m] = (float(cm + (up ? 1 : 0)) - w_o[m]) * w_inv[m];
        w_entry = m;
        w_t = (cb == w_out || cm < 0 || cm >= u_n) ? INF : cb;
        uint child = node[2u * w_node] + uint((c.z * u_n + c.y) * u_n + c.x);
        uint first = node[2u * child], other = node[2u * child + 1u];
        if (first == NONE) { // a leaf or empty
            if (other != NONE && leaf_hit(other)) return true;
            continue;
        }
        precise vec3 co = (w_o - vec3(c)) * float(u_n), cd = w_d * float(u_n);
        if (ea >= 0 && xa >= 0) { // crossed face to face: its line space
            if (!crossing_bit(other, co, cd, ca, cb, ea, xa)) continue;
            if (fast && level + 2 == u_depth && ca >= r_tn0 && cb <= r_tn1) return true;
        }
        suspend(level++);
        level_start(child, co, cd, ca, cb, ea, xa);
    }
    return false;
}
