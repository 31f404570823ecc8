// Solid voxelization by flooding: u_op 0 seeds "outside" with the empty voxels on the grid's
// boundary; u_op 1 sweeps every line along u_axis forward and backward, spreading outside
// through empty voxels (the CPU twin's sweeps), and counts what changed; u_op 2 writes the
// solid: every voxel the outside never reached.
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 0) readonly buffer Surface { uint surface[]; };
layout(std430, binding = 1) buffer Outside { uint outside[]; };
layout(std430, binding = 2) buffer Changed { uint changed; };
layout(std430, binding = 3) buffer Solid { uint solid[]; };
layout(location = VOXGI_LOC_u_res) uniform ivec3 u_res;
layout(location = VOXGI_LOC_u_axis) uniform int u_axis;
layout(location = VOXGI_LOC_u_op) uniform int u_op;
layout(location = VOXGI_LOC_u_words) uniform uint u_words;

uint voxel_index(ivec3 v) { return uint(v.x) + uint(u_res.x) * (uint(v.y) + uint(u_res.y) * uint(v.z)); }
bool bit(uint idx) { return ((surface[idx >> 5] >> (idx & 31u)) & 1u) != 0u; }
bool out_bit(uint idx) { return ((outside[idx >> 5] >> (idx & 31u)) & 1u) != 0u; }

void main()
{
    uint id = gl_GlobalInvocationID.x;
    if (u_op == 2) {
        if (id >= u_words) return;
        uint total = uint(u_res.x) * uint(u_res.y) * uint(u_res.z), keep = 0xffffffffu;
        if (id == u_words - 1u && (total & 31u) != 0u) keep = (1u << (total & 31u)) - 1u;
        solid[id] = ~outside[id] & keep;
        return;
    }
    int A = u_axis, a = (A + 1) % 3, b = (A + 2) % 3;
    if (id >= uint(u_res[a]) * uint(u_res[b])) return;
    ivec3 v;
    v[a] = int(id % uint(u_res[a]));
    v[b] = int(id / uint(u_res[a]));
    bool edge_line = v[a] == 0 || v[b] == 0 || v[a] == u_res[a] - 1 || v[b] == u_res[b] - 1;
    if (u_op == 0) {
        for (int k = 0; k < u_res[A]; k++) {
            v[A] = k;
            uint idx = voxel_index(v);
            if ((edge_line || k == 0 || k == u_res[A] - 1) && !bit(idx)) atomicOr(outside[idx >> 5], 1u << (idx & 31u));
        }
        return;
    }
    uint grew = 0u;
    for (int d = 0; d < 2; d++) {
        bool reach = false;
        for (int t = 0; t < u_res[A]; t++) {
            v[A] = d == 0 ? t : u_res[A] - 1 - t;
            uint idx = voxel_index(v);
            if (bit(idx)) reach = false;
            else if (out_bit(idx)) reach = true;
            else if (reach) { atomicOr(outside[idx >> 5], 1u << (idx & 31u)); grew++; }
        }
    }
    if (grew != 0u) atomicAdd(changed, grew);
}
