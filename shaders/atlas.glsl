// Texture atlas (voxgi.h, part "voxelization: texture atlas"), after scene.glsl: the charts,
// the point list, and the voxel of a point, in the arithmetic and order of voxgi__atlas_point.
layout(std430, binding = 2) readonly buffer Charts { vec2 chart[]; };  // 3 corners per triangle, texels
layout(std430, binding = 3) buffer Points { uint point_count; uint points_pad; uvec2 points[]; }; // (x | y << 16, triangle)

bool atlas_point_voxel(uvec2 p, out ivec3 v)
{
    uint t = p.y;
    dvec2 c0 = dvec2(chart[3u * t]), c1 = dvec2(chart[3u * t + 1u]), c2 = dvec2(chart[3u * t + 2u]);
    dvec3 q0 = vp[tri_index[3u * t]].q.xyz, q1 = vp[tri_index[3u * t + 1u]].q.xyz, q2 = vp[tri_index[3u * t + 2u]].q.xyz;
    // exact: the corners lie on the 1/256 lattice below 2^14
    double px = double(p.x & 0xffffu) + 0.5LF - c0.x, py = double(p.x >> 16) + 0.5LF - c0.y;
    double e1x = c1.x - c0.x, e1y = c1.y - c0.y, e2x = c2.x - c0.x, e2y = c2.y - c0.y;
    double den = e1x * e2y - e1y * e2x, n1 = px * e2y - py * e2x, n2 = e1x * py - e1y * px;
    v = ivec3(0);
    for (int a = 0; a < 3; a++) {
        precise double s = n1 * (q1[a] - q0[a]) + n2 * (q2[a] - q0[a]);
        precise double pa = q0[a] + s / den;
        double k = floor(pa);
        if (!(k >= 0.0LF && k < double(u_res[a]))) return false;
        v[a] = int(k);
    }
    return true;
}

#ifdef VOXGI_COMPUTE
// Invocations are laid out in rows of work groups (atlas sizes exceed one dispatch row).
uint atlas_item() { return gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * uint(VOXGI_LOCAL_SIZE); }
#endif
