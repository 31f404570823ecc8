// Sampling an attribute volume (voxgi.h, part "attribute volumes and mipmaps"): the function the
// lighting passes use, and a compute pass that applies it to a list of points (voxgi_volume_sample
// on GL). p in grid units of level 0, lod in levels; the texture's base size is u_size (the
// grid rounded up so GL's mip chain holds every level; the padding is empty), filtering
// LINEAR_MIPMAP_LINEAR with an empty border: trilinear between voxel centres, linear between
// levels, as voxgi__sample_level on the CPU.
vec4 voxgi_sample_volume(sampler3D volume, vec3 p, float lod, vec3 size, float max_lod)
{
    return textureLod(volume, p / size, clamp(lod, 0.0, max_lod));
}

#ifdef VOXGI_COMPUTE
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(binding = 0) uniform sampler3D u_volume;
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };  // xyz, lod
layout(std430, binding = 1) writeonly buffer Samples { vec4 samples[]; };
uniform uint u_count;
uniform vec3 u_size;
uniform float u_max_lod;

void main()
{
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    if (i >= u_count) return;
    samples[i] = voxgi_sample_volume(u_volume, points[i].xyz, points[i].w, u_size, u_max_lod);
}
#endif
