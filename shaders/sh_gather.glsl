// The SH volume's gather at a point (voxgi__sh_point's GL twin, in float; run by
// point_gather.glsl): the Barnes-Hut walk of the levels from the coarsest, each cell seen whole through the voxels
// (voxel_traverse.glsl) when u_levels > 0, up to half a voxel before the cell.
// embedded unless VOXGI_NO_LIGHT_SPACE
layout(std430, binding = 3) readonly buffer Cells { float cells[]; };      // 16 per cell, level after level
layout(std430, binding = 4) readonly buffer CellLevels { uint cell_level[]; }; // per level: cells per axis, first cell
layout(location = VOXGI_LOC_u_cell_levels) uniform int u_cell_levels;
layout(location = VOXGI_LOC_u_opening) uniform float u_opening;

const float Y0 = 0.28209479177387814, Y1 = 0.48860251190291992;

vec3 gather(vec3 x, vec3 n)
{
    vec3 e = vec3(0.0);
    float vs = u_voxel_size;
    ivec4 stack[8 * 24];
    int top = 0;
    stack[top++] = ivec4(u_cell_levels - 1, 0, 0, 0);
    while (top > 0) {
        ivec4 s = stack[--top];
        int l = s.x;
        ivec3 c = s.yzw;
        uint rx = cell_level[4 * l], ry = cell_level[4 * l + 1];
        uint ci = 16u * (cell_level[4 * l + 3] + uint(c.x) + rx * (uint(c.y) + ry * uint(c.z)));
        float wsum = cells[ci + 15u];
        if (!(wsum > 0.0)) continue;
        vec3 p = vec3(cells[ci + 12u], cells[ci + 13u], cells[ci + 14u]) / wsum, d = p - x;
        float dist2 = dot(d, d), dist = sqrt(dist2), size = vs * float(1 << l);
        if (l > 0 && !(size <= u_opening * dist)) { // too near to be one point: its children
            for (int k = 0; k < 8; k++) {
                ivec3 q = 2 * c + ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
                if (q.x >= int(cell_level[4 * (l - 1)]) || q.y >= int(cell_level[4 * (l - 1) + 1]) || q.z >= int(cell_level[4 * (l - 1) + 2])) continue;
                stack[top++] = ivec4(l - 1, q);
            }
            continue;
        }
        if (!(dist > vs)) continue; // the point's own surface
        vec3 w = -d / dist;
        float cr = dot(n, d) / dist;
        if (cr <= 0.0) continue;
        if (u_levels > 0) { // from x 1.5 voxels off its surface toward the centroid, up to half a voxel before the cell
            vec3 o = (x + 1.5 * vs * n - u_origin) / vs, dd = (p - u_origin) / vs - o;
            float enter = 0.0, len = length(dd);
            for (int a = 0; a < 3; a++) {
                if (dd[a] == 0.0) continue;
                float lo = float(c[a] * (1 << l)), hi = lo + float(1 << l);
                float t0 = (lo - o[a]) / dd[a], t1 = (hi - o[a]) / dd[a];
                enter = max(enter, min(t0, t1));
            }
            enter -= 0.5 / len;
            if (enter > 0.0 && occluded(o, dd * enter)) continue;
        }
        for (int a = 0; a < 3; a++) {
            uint k = ci + 4u * uint(a);
            float I = cells[k] * Y0 + Y1 * (cells[k + 1u] * w.y + cells[k + 2u] * w.z + cells[k + 3u] * w.x);
            if (I > 0.0) e[a] += I * cr / dist2;
        }
    }
    return e;
}
