// One mip level of an attribute volume from the level below (voxgi.h, part "attribute volumes
// and mipmaps"): per parent voxel, its 2x2x2 children (beyond the grid: empty). u_dir < 0:
// isotropic (mean alpha, alpha-weighted value); else anisotropic along u_dir (+x -x +y -y +z -z):
// the four child pairs along the axis composited front to back, averaged, un-premultiplied.
// The same float formulas as voxgi__mip_voxel. u_single: the volume holds alpha alone (R32F);
// u_premultiplied: the values are stored multiplied by alpha (RADIANCE).
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = 0) uniform sampler3D u_src;
layout(binding = 0, rgba32f) uniform writeonly image3D u_dst;
layout(binding = 1, r32f) uniform writeonly image3D u_dst_single;
layout(location = VOXGI_LOC_u_src_dims) uniform ivec3 u_src_dims;
layout(location = VOXGI_LOC_u_dst_dims) uniform ivec3 u_dst_dims;
layout(location = VOXGI_LOC_u_src_level) uniform int u_src_level;
layout(location = VOXGI_LOC_u_dir) uniform int u_dir;
layout(location = VOXGI_LOC_u_single) uniform int u_single;
layout(location = VOXGI_LOC_u_premultiplied) uniform int u_premultiplied;

void main()
{
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(p, u_dst_dims))) return;
    vec4 c[8];
    for (int k = 0; k < 8; k++) {
        ivec3 v = 2 * p + ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
        c[k] = vec4(0.0);
        if (all(lessThan(v, u_src_dims))) {
            vec4 t = texelFetch(u_src, v, u_src_level);
            c[k] = u_single != 0 ? vec4(0.0, 0.0, 0.0, t.r) : t;
        }
    }
    float asum = 0.0;
    vec3 vsum = vec3(0.0);
    float pairs = 8.0;
    if (u_dir < 0) {
        for (int k = 0; k < 8; k++) {
            asum += c[k].a;
            vsum += u_premultiplied != 0 ? c[k].rgb : c[k].rgb * c[k].a;
        }
    } else {
        int bit = 1 << (u_dir / 2);
        pairs = 0.0;
        for (int k = 0; k < 8; k++) {
            if ((k & bit) != 0) continue;
            vec4 nr = (u_dir & 1) != 0 ? c[k | bit] : c[k], fr = (u_dir & 1) != 0 ? c[k] : c[k | bit];
            asum += nr.a + (1.0 - nr.a) * fr.a;
            vsum += u_premultiplied != 0 ? nr.rgb + (1.0 - nr.a) * fr.rgb : nr.rgb * nr.a + (1.0 - nr.a) * fr.rgb * fr.a;
            pairs += 1.0;
        }
    }
    if (u_single != 0) { imageStore(u_dst_single, p, vec4(asum / pairs)); return; }
    imageStore(u_dst, p, vec4(u_premultiplied != 0 ? vsum / pairs : (asum > 0.0 ? vsum / asum : vec3(0.0)), asum / pairs));
}
