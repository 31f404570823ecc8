// Raster slicemap (Eisemann & Decoret 2006; Buchacher 2014 method A), after scene.glsl and
// slice_targets.glsl: vertex and fragment stages. Pixels are voxel columns along u_axis; the
// depth of each fragment is not the rasterizer's but the triangle's plane at the pixel centre,
// in double, in the same order as voxgi__slicemap_depth, so only the rasterizer's coverage
// differs from the CPU twin.
layout(location = VOXGI_LOC_u_axis) uniform int u_axis;

#ifdef VOXGI_VERTEX
flat out int v_tri;
void main()
{
    int A = u_axis, a = (A + 1) % 3, b = (A + 2) % 3;
    dvec3 q = vp[tri_index[gl_VertexID]].q.xyz;
    // window x, y = the voxel coordinates along a and b; z is unused (never clipped)
    gl_Position = vec4(float(2.0LF * q[a] / double(u_res[a]) - 1.0LF), float(2.0LF * q[b] / double(u_res[b]) - 1.0LF), 0.0, 1.0);
    v_tri = gl_VertexID / 3;
}
#endif

#ifdef VOXGI_FRAGMENT
flat in int v_tri;

void main()
{
    int A = u_axis, a = (A + 1) % 3, b = (A + 2) % 3;
    uint t = uint(v_tri);
    dvec3 q0 = vp[tri_index[3u * t]].q.xyz, q1 = vp[tri_index[3u * t + 1u]].q.xyz, q2 = vp[tri_index[3u * t + 2u]].q.xyz;
    double e1a = q1[a] - q0[a], e1b = q1[b] - q0[b], e1A = q1[A] - q0[A];
    double fa = q2[a] - q0[a], fb = q2[b] - q0[b], fA = q2[A] - q0[A];
    double na = e1b * fA - e1A * fb, nb = e1A * fa - e1a * fA, nA = e1a * fb - e1b * fa;
    double z = q0[A] - (na * (double(gl_FragCoord.x) - q0[a]) + nb * (double(gl_FragCoord.y) - q0[b])) / nA;
    double k = floor(z);
    write_slice(k >= 0.0LF && k < double(u_res[A]) ? int(k) : -1);
}
#endif
