// Volume Buffer merge, after scene.glsl: the three sweeps' volumes (axis c stores voxel v at
// (v[c+1], v[c+2], v[c])) into the bit grid (u_pass 0: the fragment count is not zero), then
// (u_pass 1) each set voxel's values at its rank: sums for AVERAGE (divided by the count) and
// ADD, maxima for MAX (normals stored as n / 2 + 1/2 under MAX, decoded here).
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(binding = 0) uniform sampler3D u_t0[3]; // albedo, count
layout(binding = 3) uniform sampler3D u_t1[3]; // normal, opacity
layout(binding = 6) uniform sampler3D u_t2[3]; // emission
layout(std430, binding = 4) buffer Bits { uint bits[]; };
layout(std430, binding = 7) readonly buffer Rank { uint rank[]; };
layout(std430, binding = 8) writeonly buffer Out { float merged[]; };
layout(std430, binding = 9) writeonly buffer Counts { uint counts[]; };
layout(location = VOXGI_LOC_u_pass) uniform int u_pass;
layout(location = VOXGI_LOC_u_attributes) uniform uint u_attributes; // voxgi_attribute bits
layout(location = VOXGI_LOC_u_blend) uniform ivec4 u_blend;     // per attribute: 0 AVERAGE, 1 MAX, 2 ADD
layout(location = VOXGI_LOC_u_channels) uniform int u_channels;

void main()
{
    uint item = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * 65536u;
    if (item >= uint(u_res.x) * uint(u_res.y) * uint(u_res.z)) return;
    ivec3 v = ivec3(int(item % uint(u_res.x)), int(item / uint(u_res.x) % uint(u_res.y)), int(item / (uint(u_res.x) * uint(u_res.y))));
    vec4 t0[3], t1[3], t2[3];
    float count = 0.0;
    for (int c = 0; c < 3; c++) {
        ivec3 at = ivec3(v[(c + 1) % 3], v[(c + 2) % 3], v[c]);
        t0[c] = texelFetch(u_t0[c], at, 0);
        t1[c] = (u_attributes & 10u) != 0u ? texelFetch(u_t1[c], at, 0) : vec4(0.0);
        t2[c] = (u_attributes & 4u) != 0u ? texelFetch(u_t2[c], at, 0) : vec4(0.0);
        count += u_attributes != 0u ? t0[c].a : t0[c].r;
    }
    if (count == 0.0) return;
    if (u_pass == 0) {
        atomicOr(bits[item >> 5], 1u << (item & 31u));
        return;
    }
    uint slot = rank[item >> 5] + uint(bitCount(bits[item >> 5] & ((1u << (item & 31u)) - 1u)));
    counts[slot] = uint(count);
    int ch = 0;
    for (int attr = 0; attr < 4; attr++) {
        if ((u_attributes & (1u << uint(attr))) == 0u) continue;
        int width = attr == 3 ? 1 : 3;
        for (int k = 0; k < width; k++) {
            float s = 0.0, m = 0.0;
            for (int c = 0; c < 3; c++) {
                float x = attr == 0 ? t0[c][k] : (attr == 1 ? t1[c][k] : (attr == 2 ? t2[c][k] : t1[c].a));
                s += x;
                m = max(m, x);
            }
            float r = u_blend[attr] == 1 ? m : (u_blend[attr] == 2 ? s : s / count);
            if (attr == 1 && u_blend[attr] == 1) r = 2.0 * r - 1.0;
            merged[slot * uint(u_channels) + uint(ch++)] = r;
        }
    }
}
