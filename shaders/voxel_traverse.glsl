// Voxel visibility (voxgi__traverse's GL twin, in float): whether the segment o + t d, t in
// [0, 1] (voxel units), meets an occupied voxel, by 3D-DDA or, from the coarsest level, by the
// hierarchy of the OR mipmaps. Level l has occ_level[4 l .. 4 l + 2] cells per axis and its bits
// from word occ_level[4 l + 3] of occ_bits. What the grid does not hold does not block.
// embedded unless VOXGI_NO_LIGHT_SPACE and VOXGI_NO_SCREEN_SPACE
layout(std430, binding = 6) readonly buffer OccBits { uint occ_bits[]; };
layout(std430, binding = 7) readonly buffer OccLevels { uint occ_level[]; };
layout(location = VOXGI_LOC_u_levels) uniform int u_levels; // 0: no visibility
layout(location = VOXGI_LOC_u_hierarchical) uniform int u_hierarchical;

bool occ_get(int l, ivec3 c)
{
    uint rx = occ_level[4 * l], ry = occ_level[4 * l + 1];
    uint at = uint(c.x) + rx * (uint(c.y) + ry * uint(c.z));
    return ((occ_bits[occ_level[4 * l + 3] + (at >> 5u)] >> (at & 31u)) & 1u) != 0u;
}

ivec3 occ_res(int l) { return ivec3(occ_level[4 * l], occ_level[4 * l + 1], occ_level[4 * l + 2]); }

// The voxel holding the point at t, each axis clamped into [lo, hi].
ivec3 voxel_at(vec3 o, vec3 d, float t, ivec3 lo, ivec3 hi)
{
    vec3 x = clamp(floor(o + t * d), vec3(lo), vec3(hi));
    return ivec3(x);
}

// Whether the segment meets an occupied voxel, and which (hit)
bool occluded_at(vec3 o, vec3 d, out ivec3 hit)
{
    hit = ivec3(0);
    ivec3 res = occ_res(0), lo = ivec3(0), hi = res - 1, v;
    float t0 = 0.0, t1 = 1.0;
    int l = u_hierarchical != 0 ? u_levels - 1 : 0;
    for (int a = 0; a < 3; a++) { // the segment cut to the grid's box
        if (d[a] == 0.0) {
            if (!(o[a] >= 0.0 && o[a] <= float(res[a]))) return false;
            continue;
        }
        float ta = (0.0 - o[a]) / d[a], tb = (float(res[a]) - o[a]) / d[a];
        t0 = max(t0, min(ta, tb));
        t1 = min(t1, max(ta, tb));
    }
    if (!(t0 <= t1)) return false;
    v = voxel_at(o, d, t0, lo, hi);
    for (;;) {
        int size = 1 << l, axis = 0;
        ivec3 cell = v >> l;
        if (occ_get(l, cell)) {
            if (l == 0) { hit = v; return true; }
            l--;
            continue;
        }
        float t = 3.0e38;
        for (int a = 0; a < 3; a++) { // where the cell is left, the lowest axis on ties
            if (d[a] == 0.0) continue;
            float ta = (float((cell[a] + (d[a] > 0.0 ? 1 : 0)) * size) - o[a]) / d[a];
            if (ta < t) { t = ta; axis = a; }
        }
        if (!(t <= t1)) return false;
        ivec3 clo = cell * size, chi = min(clo + size - 1, hi);
        v = voxel_at(o, d, t, clo, chi);
        v[axis] = d[axis] > 0.0 ? (cell[axis] + 1) * size : cell[axis] * size - 1;
        if (v[axis] < 0 || v[axis] > hi[axis]) return false;
        if (u_hierarchical != 0 && l < u_levels - 1) l++;
    }
}

bool occluded(vec3 o, vec3 d)
{
    ivec3 hit;
    return occluded_at(o, d, hit);
}
