// Raster slicemap: slicemap columns (u_per_layer slices per array layer: 128 in RGBA32UI, 32 in
// R32UI) into the linear bit grid, one invocation per column.
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(binding = 0) uniform usampler2DArray u_slices;
layout(std430, binding = 0) buffer Bits { uint bits[]; };
layout(location = VOXGI_LOC_u_res) uniform ivec3 u_res;
layout(location = VOXGI_LOC_u_axis) uniform int u_axis;
layout(location = VOXGI_LOC_u_per_layer) uniform int u_per_layer;

void main()
{
    int A = u_axis, a = (A + 1) % 3, b = (A + 2) % 3;
    uint column = gl_GlobalInvocationID.x;
    if (column >= uint(u_res[a]) * uint(u_res[b])) return;
    ivec3 v;
    v[a] = int(column % uint(u_res[a]));
    v[b] = int(column / uint(u_res[a]));
    for (int base = 0; base < u_res[A]; base += 32) {
        uint word = texelFetch(u_slices, ivec3(v[a], v[b], base / u_per_layer), 0)[(base % u_per_layer) >> 5];
        for (; word != 0u; word &= word - 1u) {
            v[A] = base + findLSB(word);
            if (v[A] >= u_res[A]) break;
            uint idx = uint(v.x) + uint(u_res.x) * (uint(v.y) + uint(u_res.y) * uint(v.z));
            atomicOr(bits[idx >> 5], 1u << (idx & 31u));
        }
    }
}
