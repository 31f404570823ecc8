// Conservative voxelization by rasterization (Crassin & Green's geometry-shader voxelizer),
// after scene.glsl, triangle.glsl and conservative.glsl. The geometry stage projects each
// triangle along its dominant axis (largest |normal| component, the lowest axis on ties) into a
// u_view x u_view viewport whose pixels are the voxel columns, and grows it for conservative
// rasterization: every edge pushed out by half a pixel's extent along its normal plus 1/64 pixel
// (more than the float rounding of the corners), or, where the corners of a sliver would fly
// far, the bounding box grown the same way. Each fragment then runs the exact column tests of
// the compute voxelizer for its column, clipped to the triangle's exact voxel range (the
// bounding-box clip), so the set is the exact conservative one and each (triangle, voxel) pair
// is visited once: the attribute pass adds every pair exactly once.
layout(location = VOXGI_LOC_u_view) uniform int u_view;

#ifdef VOXGI_VERTEX
void main() { gl_Position = vec4(0.0); } // the geometry stage reads the vertices itself
#endif

#ifdef VOXGI_GEOMETRY
layout(triangles) in;
layout(triangle_strip, max_vertices = 4) out;
flat out uint g_tri;
flat out int g_axis;

void put(dvec2 p, uint t, int c)
{
    g_tri = t;
    g_axis = c;
    gl_Position = vec4(vec2(p * (2.0LF / double(u_view)) - 1.0LF), 0.0, 1.0);
    EmitVertex();
}

void main()
{
    uint t = uint(gl_PrimitiveIDIn);
    dvec3 q[3];
    for (int k = 0; k < 3; k++) q[k] = vp[tri_index[3u * t + uint(k)]].q.xyz;
    dvec3 nrm = cross(q[1] - q[0], q[2] - q[0]);
    int c = 0;
    for (int k = 1; k < 3; k++)
        if (abs(nrm[k]) > abs(nrm[c])) c = k;
    int a = (c + 1) % 3, b = (c + 2) % 3;
    dvec2 p[3];
    for (int k = 0; k < 3; k++) p[k] = dvec2(q[k][a], q[k][b]);
    if (nrm[c] < 0.0LF) { dvec2 s = p[1]; p[1] = p[2]; p[2] = s; } // counter-clockwise
    const double margin = 1.0LF / 64.0LF;
    dvec2 lo = min(p[0], min(p[1], p[2])), hi = max(p[0], max(p[1], p[2]));
    dvec2 grown[3];
    bool ok = nrm[c] != 0.0LF;
    for (int k = 0; k < 3 && ok; k++) { // corner k: the pushed edges k-1 and k meet
        dvec2 d0 = p[k] - p[(k + 2) % 3], d1 = p[(k + 1) % 3] - p[k];
        dvec2 m0 = dvec2(d0.y, -d0.x), m1 = dvec2(d1.y, -d1.x); // outward normals
        double h0 = dot(m0, p[k]) + 0.5LF * (abs(m0.x) + abs(m0.y)) + margin * length(m0);
        double h1 = dot(m1, p[k]) + 0.5LF * (abs(m1.x) + abs(m1.y)) + margin * length(m1);
        double det = m0.x * m1.y - m0.y * m1.x;
        grown[k] = dvec2(h0 * m1.y - h1 * m0.y, m0.x * h1 - m1.x * h0) / det;
        ok = det > 1e-12LF * length(m0) * length(m1) && length(grown[k] - p[k]) < 16.0LF;
    }
    if (ok) {
        for (int k = 0; k < 3; k++) put(grown[k], t, c);
    } else { // the bounding box, grown
        lo -= 0.5LF + margin;
        hi += 0.5LF + margin;
        put(lo, t, c);
        put(dvec2(hi.x, lo.y), t, c);
        put(dvec2(lo.x, hi.y), t, c);
        put(hi, t, c);
    }
    EndPrimitive();
}
#endif

#ifdef VOXGI_FRAGMENT
flat in uint g_tri;
flat in int g_axis;

void main()
{
    uint t = g_tri;
    if (u_attr != 0 && (tri_flags[t >> 5] & (1u << (t & 31u))) != 0u) return; // the CPU does all of it
    if (!setup(t)) return;
    if (any(equal(sig, ivec3(UNKNOWN))) || all(equal(sig, ivec3(0)))) { flag_triangle(); return; }
    forms();
    int c = g_axis, a = (c + 1) % 3, b = (c + 2) % 3;
    int ra = int(gl_FragCoord.x) - lo[a], rb = int(gl_FragCoord.y) - lo[b];
    if (ra < 0 || rb < 0 || ra >= ext[a] || rb >= ext[b]) return; // the bounding-box clip
    do_columns(c, -1, rb, ra, ra);
}
#endif
