// The scene as every pass reads it: vertices prepared by the CPU (voxgi__gl_vprep) and
// triangles as three vertex indices each.
struct VPrep {
    dvec4 q;   // xyz: (v - o) / s;  w: fraction bits of an exact q, or -1
    ivec4 lo;  // exact voxel range of the coordinate; w: bit a set when q[a] is exact
    ivec4 hi;
    vec4 w;    // the float vertex
    vec4 pad;
};
layout(std430, binding = VOXGI_BINDING_VERTICES) readonly buffer Verts { VPrep vp[]; };
layout(std430, binding = VOXGI_BINDING_TRIANGLES) readonly buffer Tris { uint tri_index[]; };
layout(location = VOXGI_LOC_u_res) uniform ivec3 u_res;
