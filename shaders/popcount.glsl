// Counts the set bits of a bit grid: each invocation sums a strided share of the words.
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 0) readonly buffer Bits { uint bits[]; };
layout(std430, binding = 1) buffer Count { uint count; };
layout(location = VOXGI_LOC_u_words) uniform uint u_words;

void main()
{
    uint c = 0u;
    uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    for (uint i = gl_GlobalInvocationID.x; i < u_words; i += stride) c += uint(bitCount(bits[i]));
    if (c != 0u) atomicAdd(count, c);
}
