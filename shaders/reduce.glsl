// OR-reduction of a bit grid by a factor of 1 or 2 per axis (occupancy mipmaps, and the
// column OR-mipmap with factor {2,2,1}): one invocation per destination line along x.
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 0) readonly buffer Src { uint src[]; };
layout(std430, binding = 1) buffer Dst { uint dst[]; };
layout(location = VOXGI_LOC_u_src_res) uniform ivec3 u_src_res;
layout(location = VOXGI_LOC_u_dst_res) uniform ivec3 u_dst_res;
layout(location = VOXGI_LOC_u_factor) uniform ivec3 u_factor;

void main()
{
    uint line = gl_GlobalInvocationID.x;
    if (line >= uint(u_dst_res.y) * uint(u_dst_res.z)) return;
    int y = int(line % uint(u_dst_res.y)), z = int(line / uint(u_dst_res.y));
    for (int x = 0; x < u_dst_res.x; x++) {
        bool hit = false;
        for (int dz = 0; dz < u_factor.z && !hit; dz++)
            for (int dy = 0; dy < u_factor.y && !hit; dy++)
                for (int dx = 0; dx < u_factor.x && !hit; dx++) {
                    ivec3 s = ivec3(x, y, z) * u_factor + ivec3(dx, dy, dz);
                    if (any(greaterThanEqual(s, u_src_res))) continue;
                    uint i = uint(s.x) + uint(u_src_res.x) * (uint(s.y) + uint(u_src_res.y) * uint(s.z));
                    hit = ((src[i >> 5] >> (i & 31u)) & 1u) != 0u;
                }
        if (hit) {
            uint d = uint(x) + uint(u_dst_res.x) * (uint(y) + uint(u_dst_res.y) * uint(z));
            atomicOr(dst[d >> 5], 1u << (d & 31u));
        }
    }
}
