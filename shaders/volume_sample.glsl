// voxgi_volume_sample on GL (voxgi.h, part "attribute volumes and mipmaps"): sampling.glsl's
// voxgi_sample_volume applied to a list of points.
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(binding = 0) uniform sampler3D u_volume;
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };  // xyz, lod
layout(std430, binding = 1) writeonly buffer Samples { vec4 samples[]; };
layout(location = VOXGI_LOC_u_count) uniform uint u_count;
layout(location = VOXGI_LOC_u_size) uniform vec3 u_size;
layout(location = VOXGI_LOC_u_max_lod) uniform float u_max_lod;

void main()
{
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    if (i >= u_count) return;
    samples[i] = voxgi_sample_volume(u_volume, points[i].xyz, points[i].w, u_size, u_max_lod);
}
