// Texture atlas via compute (Buchacher's method D), after scene.glsl and atlas.glsl: one
// invocation per atlas point sets its voxel in the bit grid.
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 4) buffer Bits { uint bits[]; };

void main()
{
    uint item = atlas_item();
    ivec3 v;
    if (item >= point_count || !atlas_point_voxel(points[item], v)) return;
    uint idx = uint(v.x) + uint(u_res.x) * (uint(v.y) + uint(u_res.y) * uint(v.z));
    atomicOr(bits[idx >> 5], 1u << (idx & 31u));
}
