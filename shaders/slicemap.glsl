// Raster slicemap (Eisemann & Decoret 2006; Buchacher 2014 method A), after scene.glsl and
// slice_targets.glsl: vertex and fragment stages. Pixels are voxel columns along u_axis. The
// corners go to the rasterizer already on its 1/256 subpixel grid, in a power-of-two viewport
// u_view (window = clip coordinates exactly), so its own snapping changes nothing; the depth of
// each fragment is not the rasterizer's but the unrounded triangle's plane at the pixel centre,
// in double, in the same order as voxgi__slicemap_depth. So the voxels equal the CPU twin's.
layout(location = VOXGI_LOC_u_axis) uniform int u_axis;

#ifdef VOXGI_VERTEX
flat out int v_tri;
double snap(double x) { return floor(x * 256.0LF + 0.5LF) / 256.0LF; }
void main()
{
    int A = u_axis, a = (A + 1) % 3, b = (A + 2) % 3;
    dvec3 q = vp[tri_index[gl_VertexID]].q.xyz;
    // window x, y = the voxel coordinates along a and b; z is unused (never clipped)
    gl_Position = vec4(float(snap(q[a]) * (2.0LF / double(u_view.x)) - 1.0LF), float(snap(q[b]) * (2.0LF / double(u_view.y)) - 1.0LF), 0.0, 1.0);
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
