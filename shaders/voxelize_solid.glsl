// Solid voxelization, toggle pass (after triangle.glsl): the GL twin of voxgi__solid_triangle.
// In every column whose centre a triangle owns, the first voxel whose centre lies at or above
// the triangle is toggled (atomicXor, so order does not matter); solid_prefix.glsl turns the
// toggles into parity. A column whose ownership or height the filter cannot certify goes to
// the CPU as a (triangle, column) pair; a triangle whose orientation it cannot certify is
// flagged before any of its toggles are written.
layout(local_size_x = VOXGI_LOCAL_SIZE) in;

layout(std430, binding = VOXGI_BINDING_BITS) buffer Toggles { uint toggles[]; };

// Sign of form L at the centre of voxel rel, with the per-voxel bound (see voxgi__form_sign).
int centre_sign(Lin L, ivec3 rel)
{
    double v = 0.0LF, bound = 0.0LF, gm = 0.0LF;
    for (int a = 0; a < 3; a++) {
        double ta = (double(rel[a]) + 0.5LF) - r[L.vertex][a];
        double dt = dr[L.vertex][a] + U * abs(ta);
        v += L.k[a] * ta;
        bound += abs(L.k[a]) * dt + L.dk[a] * abs(ta) + L.dk[a] * dt;
        gm += abs(L.k[a] * ta);
    }
    bound += gamma_(3.0LF) * gm * 1.01LF;
    return sign_within(v, bound == 0.0LF ? 0.0LF : bound * 1.001LF);
}

// 1 when the triangle's projection along A owns the column centre, 0 when not, else UNKNOWN.
int owns_centre(int A, ivec3 rel)
{
    int a = (A + 1) % 3, b = (A + 2) % 3, result = 1;
    for (int i = 0; i < proj_count[A]; i++) { // oriented: form i is edge i
        Lin L = proj[3 * A + i];
        int s = centre_sign(L, rel);
        if (s == UNKNOWN) result = UNKNOWN;
        else if (s < 0) return 0;
        else if (s == 0) {
            double da = double(L.orient) * e[i][a], db = double(L.orient) * e[i][b];
            if (!(db < 0.0LF || (db == 0.0LF && da > 0.0LF))) return 0;
        }
    }
    return result;
}

void hand_over_column(ivec3 rel)
{
    uint at = atomicAdd(pair_count, 1u);
    if (at < u_pair_capacity) pairs[at] = uvec4(T, uvec3(lo + rel));
}

void solid_column(int A, ivec3 rel)
{
    int a = (A + 1) % 3, b = (A + 2) % 3, kmax = u_res[A] - 1 - lo[A];
    rel[A] = 0;
    int own = owns_centre(A, rel);
    if (own == 0) return;
    if (own == UNKNOWN) { hand_over_column(rel); return; }
    double zc = ceil(r[0][A] - (n[a] * (double(rel[a]) + 0.5LF - r[0][a]) + n[b] * (double(rel[b]) + 0.5LF - r[0][b])) / n[A] - 0.5LF);
    int k = !(zc >= double(-lo[A])) ? -lo[A] : (zc > double(kmax + 1) ? kmax + 1 : int(zc));
    for (;;) {
        if (k <= -lo[A]) break;
        rel[A] = k - 1;
        int s = centre_sign(plane, rel);
        if (s == UNKNOWN) { rel[A] = 0; hand_over_column(rel); return; }
        if (sig[A] * s < 0) break;
        k--;
    }
    for (;;) {
        if (k > kmax) break;
        rel[A] = k;
        int s = centre_sign(plane, rel);
        if (s == UNKNOWN) { rel[A] = 0; hand_over_column(rel); return; }
        if (sig[A] * s >= 0) break;
        k++;
    }
    if (k <= kmax) {
        ivec3 v = lo + rel;
        v[A] = lo[A] + k;
        uint idx = uint(v.x) + uint(u_res.x) * (uint(v.y) + uint(u_res.y) * uint(v.z));
        atomicXor(toggles[idx >> 5], 1u << (idx & 31u));
    }
}

// Triangle setup for the solid axis; false when the triangle owns no centre or was flagged.
bool prepare_solid(uint t)
{
    if (!setup(t)) return false;
    int A = u_solid_axis;
    if (sig[A] == 0) return false;
    if (sig[A] == UNKNOWN) { flag_triangle(); return false; }
    forms();
    return true;
}

void main()
{
    int A = u_solid_axis, a = (A + 1) % 3, b = (A + 2) % 3;
    if (u_pass == 0) {
        uint t = u_tri_offset + gl_GlobalInvocationID.x;
        if (t >= u_tri_count || !prepare_solid(t)) return;
        if (listed_as_big(t, a, b)) return;
        for (int rb = 0; rb < ext[b]; rb++) {
            ivec2 span = row_span(A, rb);
            for (int ra = span.x; ra <= span.y; ra++) {
                ivec3 rel = ivec3(0);
                rel[a] = ra;
                rel[b] = rb;
                solid_column(A, rel);
            }
        }
    } else {
        uint lanes = gl_NumWorkGroups.y * gl_WorkGroupSize.x;
        uint lane = gl_WorkGroupID.y * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
        for (uint bi = gl_WorkGroupID.x; bi < big_count; bi += gl_NumWorkGroups.x) {
            if (!lane_has_work(big_list[bi], lane)) continue;
            setup(big_list[bi]);
            forms();
            int chunks = (ext[a] + CHUNK - 1) / CHUNK;
            uint items = uint(ext[b] * chunks);
            for (uint item = lane; item < items; item += lanes) {
                int rb = int(item) / chunks, ch = int(item) % chunks;
                ivec2 span = row_span(A, rb);
                for (int ra = max(span.x, ch * CHUNK); ra <= min(span.y, ch * CHUNK + CHUNK - 1); ra++) {
                    ivec3 rel = ivec3(0);
                    rel[a] = ra;
                    rel[b] = rb;
                    solid_column(A, rel);
                }
            }
        }
    }
}
