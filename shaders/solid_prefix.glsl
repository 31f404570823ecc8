// Solid voxelization, parity pass: one invocation per line along the axis walks the toggles and
// sets every voxel with odd parity so far (atomicOr: neighbouring lines share words).
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 0) readonly buffer Toggles { uint toggles[]; };
layout(std430, binding = 1) buffer Solid { uint solid[]; };
layout(location = VOXGI_LOC_u_res) uniform ivec3 u_res;
layout(location = VOXGI_LOC_u_axis) uniform int u_axis;

void main()
{
    int A = u_axis, a = (A + 1) % 3, b = (A + 2) % 3;
    uint line = gl_GlobalInvocationID.x;
    if (line >= uint(u_res[a]) * uint(u_res[b])) return;
    ivec3 v;
    v[a] = int(line % uint(u_res[a]));
    v[b] = int(line / uint(u_res[a]));
    uint parity = 0u;
    for (int k = 0; k < u_res[A]; k++) {
        v[A] = k;
        uint idx = uint(v.x) + uint(u_res.x) * (uint(v.y) + uint(u_res.y) * uint(v.z));
        parity ^= (toggles[idx >> 5] >> (idx & 31u)) & 1u;
        if (parity != 0u) atomicOr(solid[idx >> 5], 1u << (idx & 31u));
    }
}
