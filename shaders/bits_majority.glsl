// Solid voxelization by vote: a voxel is set when at least two of the three parity grids agree.
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 0) readonly buffer A { uint ga[]; };
layout(std430, binding = 1) readonly buffer B { uint gb[]; };
layout(std430, binding = 2) buffer C { uint gc[]; };
layout(location = VOXGI_LOC_u_words) uniform uint u_words;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i < u_words) gc[i] = (ga[i] & gb[i]) | (gb[i] & gc[i]) | (ga[i] & gc[i]);
}
