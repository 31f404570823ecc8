// Point lookups and samples of a GPU octree at a list of points (voxgi_svo_lookup and
// voxgi_svo_sample on GL), through the functions of svo.glsl the lighting passes use.
// embedded unless VOXGI_NO_OCTREE
#ifdef VOXGI_COMPUTE
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 3) readonly buffer Points { vec4 points[]; };  // lookups: uvec3 bits, level; samples: xyz, lod
layout(std430, binding = 4) writeonly buffer Samples { vec4 samples[]; };
layout(location = VOXGI_LOC_u_count) uniform uint u_count;
layout(location = VOXGI_LOC_u_lookup) uniform int u_lookup;  // 1: point lookups at level points[i].w; 2: the lod of footprint points[i].w; else samples

void main()
{
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    if (i >= u_count) return;
    vec4 q = points[i];
    if (u_lookup == 1) {
        int level = int(floatBitsToUint(q.w));
        samples[i] = voxgi_svo_fetch(level, ivec3(floatBitsToUint(q.xyz) >> uint(u_svo_depth - level)));
    } else if (u_lookup == 2) samples[i] = vec4(voxgi_lod_from_footprint(q.w));
    else samples[i] = voxgi_sample_svo(q.xyz, q.w);
}
#endif
