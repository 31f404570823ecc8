// Volume Buffer (Gaitatzes, Mavridis & Papaioannou 2011), after scene.glsl: one layered draw per
// sweep axis u_axis. The geometry stage keeps the triangles whose dominant axis (largest
// |normal| component of (q1-q0)x(q2-q0), the lowest axis on ties) is u_axis, rounds their
// corners to the 1/256 subpixel grid of the (u_axis+1, u_axis+2) plane, and sends them to the
// layers (slices along u_axis) they span:
//   M2 (u_slicing 2): the whole triangle to every layer of its depth range; the fragment stage
//      keeps the fragment in the layer floor(depth) of the plane at the pixel centre, in double,
//      as voxgi__vb_pixel does, so the voxels equal the CPU twin's;
//   M1 (u_slicing 1): the triangle cut at the layer boundaries into convex pieces, each drawn
//      into its own layer; a pixel centre near a cut (within the subpixel rounding of the cut
//      points) may land in the neighbouring layer.
// One invocation draws a triangle that spans at most one invocation's output budget of layers;
// a longer one is listed and drawn again by the big pass (volume_buffer_big.glsl), whose 32
// invocations share its layers; layers beyond that are lost and counted (the paper's
// max_vertices holes). Fragments write the triangle's values into up to three float targets
// whose blending (ADD or MAX per target and channel) the host sets.
#ifndef VB_INVOCATIONS
#define VB_INVOCATIONS 1
#endif
layout(std430, binding = 2) readonly buffer Values { float values[]; }; // 10 per triangle
layout(std430, binding = 3) buffer Lost { uint lost; uint big_count; uint big_list[]; };
layout(location = VOXGI_LOC_u_big) uniform int u_big;       // 1: this draw goes over big_list
layout(location = VOXGI_LOC_u_axis) uniform int u_axis;
layout(location = VOXGI_LOC_u_view) uniform ivec2 u_view;    // viewport, powers of two: window = clip exactly
layout(location = VOXGI_LOC_u_slicing) uniform int u_slicing;
layout(location = VOXGI_LOC_u_with_values) uniform int u_with_values; // 0: target 0 is R32F and counts fragments in red

#ifdef VOXGI_VERTEX
void main() { gl_Position = vec4(0.0); } // the geometry stage reads the vertices itself
#endif

#ifdef VOXGI_GEOMETRY
#define SLABS_M2 56 // 3 vertices each
#define SLABS_M1 33 // up to 5 vertices each
layout(triangles, invocations = VB_INVOCATIONS) in;
layout(triangle_strip, max_vertices = 168) out;
flat out uint g_tri;

double snap(double x) { return floor(x * 256.0LF + 0.5LF) / 256.0LF; }

void put(dvec3 p, int a, int b, uint t, int layer)
{
    g_tri = t;
    gl_Layer = layer;
    gl_Position = vec4(float(snap(p[a]) * (2.0LF / double(u_view.x)) - 1.0LF), float(snap(p[b]) * (2.0LF / double(u_view.y)) - 1.0LF), 0.0, 1.0);
    EmitVertex();
}

void main()
{
    uint t = u_big != 0 ? big_list[gl_PrimitiveIDIn] : uint(gl_PrimitiveIDIn);
    dvec3 q[3];
    for (int k = 0; k < 3; k++) q[k] = vp[tri_index[3u * t + uint(k)]].q.xyz;
    dvec3 e = q[1] - q[0], f = q[2] - q[0];
    precise dvec3 n = dvec3(e.y * f.z - f.y * e.z, e.z * f.x - f.z * e.x, e.x * f.y - f.x * e.y);
    int c = 0;
    for (int k = 1; k < 3; k++)
        if (abs(n[k]) > abs(n[c])) c = k;
    if (c != u_axis || n[c] == 0.0LF) return;
    int a = (c + 1) % 3, b = (c + 2) % 3;
    double zlo = min(q[0][c], min(q[1][c], q[2][c])), zhi = max(q[0][c], max(q[1][c], q[2][c]));
    // rounding the corners moves a covered centre by at most 1/512 pixel: its depth by 1/256 slice
    int first = max(int(floor(zlo - 1.0LF / 128.0LF)), 0), last = min(int(floor(zhi + 1.0LF / 128.0LF)), u_res[c] - 1);
    int per = u_slicing == 1 ? SLABS_M1 : SLABS_M2;
    if (u_big == 0 && last - first + 1 > per) { big_list[atomicAdd(big_count, 1u)] = t; return; }
    if (gl_InvocationID == 0 && last - first + 1 > per * VB_INVOCATIONS) atomicAdd(lost, uint(last - first + 1 - per * VB_INVOCATIONS));
    int s0 = first + gl_InvocationID * per, s1 = min(last, s0 + per - 1);
    for (int s = s0; s <= s1; s++) {
        if (u_slicing != 1) {
            for (int k = 0; k < 3; k++) put(q[k], a, b, t, s);
            EndPrimitive();
            continue;
        }
        // M1: the triangle clipped to s <= z <= s + 1 (Sutherland-Hodgman, two planes)
        dvec3 poly[5], next[5];
        int count = 3;
        for (int k = 0; k < 3; k++) poly[k] = q[k];
        for (int side = 0; side < 2 && count > 0; side++) {
            double plane = double(s + side);
            int m = 0;
            for (int k = 0; k < count; k++) {
                dvec3 p0 = poly[k], p1 = poly[(k + 1) % count];
                double d0 = side == 0 ? p0[c] - plane : plane - p0[c], d1 = side == 0 ? p1[c] - plane : plane - p1[c];
                // half-open slabs [s, s + 1): a face on a boundary belongs to the slab above it
                bool in0 = side == 0 ? d0 >= 0.0LF : d0 > 0.0LF, in1 = side == 0 ? d1 >= 0.0LF : d1 > 0.0LF;
                if (in0 && m < 5) next[m++] = p0;
                if (in0 != in1 && m < 5) next[m++] = p0 + (p1 - p0) * (d0 / (d0 - d1));
            }
            count = m;
            for (int k = 0; k < count; k++) poly[k] = next[k];
        }
        if (count < 3) continue;
        // a convex polygon as a strip: 0, 1, n-1, 2, n-2, ...
        put(poly[0], a, b, t, s);
        int lo = 1, hi = count - 1;
        for (int k = 1; k < count; k++) {
            if ((k & 1) == 1) put(poly[lo++], a, b, t, s);
            else put(poly[hi--], a, b, t, s);
        }
        EndPrimitive();
    }
}
#endif

#ifdef VOXGI_FRAGMENT
flat in uint g_tri;
layout(location = 0) out vec4 o0; // albedo, 1 (the fragment count)
layout(location = 1) out vec4 o1; // normal, opacity
layout(location = 2) out vec4 o2; // emission

void main()
{
    uint t = g_tri;
    if (u_slicing != 1) {
        int A = u_axis, a = (A + 1) % 3, b = (A + 2) % 3;
        dvec3 q0 = vp[tri_index[3u * t]].q.xyz, q1 = vp[tri_index[3u * t + 1u]].q.xyz, q2 = vp[tri_index[3u * t + 2u]].q.xyz;
        double e1a = q1[a] - q0[a], e1b = q1[b] - q0[b], e1A = q1[A] - q0[A];
        double fa = q2[a] - q0[a], fb = q2[b] - q0[b], fA = q2[A] - q0[A];
        double na = e1b * fA - e1A * fb, nb = e1A * fa - e1a * fA, nA = e1a * fb - e1b * fa;
        double z = q0[A] - (na * (double(gl_FragCoord.x) - q0[a]) + nb * (double(gl_FragCoord.y) - q0[b])) / nA;
        if (floor(z) != double(gl_Layer)) discard;
    }
    uint v = 10u * t;
    o0 = u_with_values != 0 ? vec4(values[v], values[v + 1u], values[v + 2u], 1.0) : vec4(1.0, 0.0, 0.0, 0.0);
    o1 = vec4(values[v + 3u], values[v + 4u], values[v + 5u], values[v + 9u]);
    o2 = vec4(values[v + 6u], values[v + 7u], values[v + 8u], 0.0);
}
#endif
