// Raster slicemap (Eisemann & Decoret 2006; Buchacher 2014 method A), after triangle.glsl:
// vertex and fragment stages. Pixels are voxel columns along u_axis; the depth of each
// fragment is not the rasterizer's but the triangle's plane at the pixel centre, in double, in
// the same order as voxgi__slicemap_depth, so only the rasterizer's coverage differs from the
// CPU twin. Logic-op variant: each fragment writes its slice's bit into one of up to eight
// RGBA32UI targets (128 slices each, from u_first_slice), ORed by GL_COLOR_LOGIC_OP. Atomic
// variant: imageAtomicOr into an R32UI array, 32 slices per layer.
uniform int u_axis;
uniform int u_first_slice;
uniform int u_atomic;

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
layout(binding = 0, r32ui) uniform coherent uimage2DArray u_slices;
layout(location = 0) out uvec4 o0;
layout(location = 1) out uvec4 o1;
layout(location = 2) out uvec4 o2;
layout(location = 3) out uvec4 o3;
layout(location = 4) out uvec4 o4;
layout(location = 5) out uvec4 o5;
layout(location = 6) out uvec4 o6;
layout(location = 7) out uvec4 o7;

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
    uvec4 none = uvec4(0u);
    o0 = none; o1 = none; o2 = none; o3 = none; o4 = none; o5 = none; o6 = none; o7 = none;
    if (!(k >= 0.0LF && k < double(u_res[A]))) return;
    int slice = int(k);
    if (u_atomic != 0) {
        imageAtomicOr(u_slices, ivec3(ivec2(gl_FragCoord.xy), slice >> 5), 1u << uint(slice & 31));
        return;
    }
    int local = slice - u_first_slice;
    if (local < 0 || local >= 1024) return;
    uvec4 bit = uvec4(0u);
    bit[(local >> 5) & 3] = 1u << uint(local & 31);
    switch (local >> 7) {
    case 0: o0 = bit; break;
    case 1: o1 = bit; break;
    case 2: o2 = bit; break;
    case 3: o3 = bit; break;
    case 4: o4 = bit; break;
    case 5: o5 = bit; break;
    case 6: o6 = bit; break;
    default: o7 = bit; break;
    }
}
#endif
