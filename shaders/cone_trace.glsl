// Cone tracing over a RADIANCE volume (voxgi.h, part "light injection and cone tracing"): the
// march of voxgi__cone_march step for step, with the textures' own filtering (the radiance is
// stored premultiplied, so linear filtering is right), or over an octree's RADIANCE where
// cone_svo.glsl defines VOXGI_CONE_SVO (after svo.glsl). Its passes: cone_trace_buffers.glsl
// (points and single cones in storage buffers) and cone_trace_images.glsl (a G-buffer).
// embedded unless VOXGI_NO_CONE_TRACING

// the regions of its empty space (voxgi__volume_regions): a volume's labels level after level,
// or an octree's per node slot then per leaf slot (voxgi__svo_regions); then 6 bounds per label
// from u_regions on (0: no enclosed region); level 0 is u_res voxels
layout(std430, binding = 5) readonly buffer Regions { uint regions[]; };
layout(location = VOXGI_LOC_u_regions) uniform uint u_regions;
layout(location = VOXGI_LOC_u_res) uniform ivec3 u_res;
#ifndef VOXGI_CONE_SVO
// isotropic: u_rad0; anisotropic: one texture per direction of travel, +x -x +y -y +z -z
layout(binding = 0) uniform sampler3D u_rad0;
layout(binding = 1) uniform sampler3D u_rad1;
layout(binding = 2) uniform sampler3D u_rad2;
layout(binding = 3) uniform sampler3D u_rad3;
layout(binding = 4) uniform sampler3D u_rad4;
layout(binding = 5) uniform sampler3D u_rad5;
// two-sided volumes: the back's the same way (units 9-14), the side (unit 15)
layout(binding = 9) uniform sampler3D u_back0;
layout(binding = 10) uniform sampler3D u_back1;
layout(binding = 11) uniform sampler3D u_back2;
layout(binding = 12) uniform sampler3D u_back3;
layout(binding = 13) uniform sampler3D u_back4;
layout(binding = 14) uniform sampler3D u_back5;
layout(binding = 15) uniform sampler3D u_side;
#endif
layout(location = VOXGI_LOC_u_size) uniform vec3 u_size;      // the textures' base size
layout(location = VOXGI_LOC_u_levels) uniform int u_levels;     // mip levels (an octree: depth + 1)
layout(location = VOXGI_LOC_u_anisotropic) uniform int u_anisotropic;
layout(location = VOXGI_LOC_u_two_sided) uniform int u_two_sided;
layout(location = VOXGI_LOC_u_back_coverage) uniform float u_back_coverage;
layout(location = VOXGI_LOC_u_cones) uniform int u_cones;
layout(location = VOXGI_LOC_u_half_tan) uniform float u_half_tan;
layout(location = VOXGI_LOC_u_step) uniform float u_step;
layout(location = VOXGI_LOC_u_offset) uniform float u_offset;
layout(location = VOXGI_LOC_u_max_distance) uniform float u_max_distance;
layout(location = VOXGI_LOC_u_seen_from_eye) uniform int u_seen_from_eye; // the points are seen from u_eye (grid units)
layout(location = VOXGI_LOC_u_eye) uniform vec3 u_eye;

#ifndef VOXGI_CONE_SVO
// Level k of the front (or the back) at texture coordinates uv along d: voxgi__cone_level.
vec4 cone_level(bool back, vec3 d, vec3 uv, float k)
{
    if (u_anisotropic == 0) return back ? textureLod(u_back0, uv, k) : textureLod(u_rad0, uv, k);
    vec3 w = d * d;
    if (back)
        return w.x * (d.x < 0.0 ? textureLod(u_back1, uv, k) : textureLod(u_back0, uv, k)) +
               w.y * (d.y < 0.0 ? textureLod(u_back3, uv, k) : textureLod(u_back2, uv, k)) +
               w.z * (d.z < 0.0 ? textureLod(u_back5, uv, k) : textureLod(u_back4, uv, k));
    return w.x * (d.x < 0.0 ? textureLod(u_rad1, uv, k) : textureLod(u_rad0, uv, k)) +
           w.y * (d.y < 0.0 ? textureLod(u_rad3, uv, k) : textureLod(u_rad2, uv, k)) +
           w.z * (d.z < 0.0 ? textureLod(u_rad5, uv, k) : textureLod(u_rad4, uv, k));
}
#endif

// The share of a sample's back sides seen from o: voxgi__back_share (VOXGI__SIDE_RAMP 4096).
float back_share(vec4 side, vec3 o)
{
    float len = length(side.xyz);
    if (!(len > 0.0)) return 0.0;
    return clamp(0.5 - 4096.0 * (dot(side.xyz, o) - side.w) / len, 0.0, 1.0);
}

const uint REGION_OPEN = 1u, REGION_MIXED = 0xFFFFFFFFu, REGION_BORDER = 0x80000000u, REGION_UNSEEN = 0x20000000u;

// Where level k's labels start, and its size.
uint region_level(int k, out ivec3 dk)
{
    uint first = 0u;
    dk = u_res;
    for (int j = 0; j < k; j++) {
        first += uint(dk.x) * uint(dk.y) * uint(dk.z);
        dk = (dk + 1) / 2;
    }
    return first;
}

// Whether region b lies inside region a: voxgi__region_inside.
bool region_inside(uint a, uint b)
{
    if (a == REGION_OPEN) return true;
    if (b == REGION_OPEN || a == REGION_MIXED || b == REGION_MIXED) return false;
    uint pa = u_regions + 6u * a, pb = u_regions + 6u * b;
    return regions[pb] >= regions[pa] && regions[pb + 1u] >= regions[pa + 1u] && regions[pb + 2u] >= regions[pa + 2u] &&
           regions[pb + 3u] <= regions[pa + 3u] && regions[pb + 4u] <= regions[pa + 4u] && regions[pb + 5u] <= regions[pa + 5u];
}

// The label of level k's voxel v, 0 beyond the grid: voxgi__region_label.
uint region_label(int k, ivec3 v)
{
    ivec3 dk;
    uint first = region_level(k, dk);
    if (any(lessThan(v, ivec3(0))) || any(greaterThanEqual(v, dk))) return 0u;
#ifdef VOXGI_CONE_SVO // voxgi__svo_region
    int level = u_svo_depth - k;
    uint node = 0u;
    for (int m = 1; m <= level; m++) {
        uint ptr = svo_child[node];
        if (ptr == 0u) break; // in the empty cube of node
        ivec3 b = (v >> (level - m)) & 1;
        node = (m == u_svo_depth ? u_svo_nodes : 1u) + 8u * (ptr - 1u) + uint(b.x | (b.y << 1) | (b.z << 2));
    }
    return regions[node]; // a voxel's label, a node's, or that of the empty cube holding v
#else
    return regions[first + uint(v.x) + uint(dk.x) * (uint(v.y) + uint(dk.y) * uint(v.z))];
#endif
}

// The label of level 0's voxel v, 0 beyond the grid.
uint region_of(ivec3 v)
{
    return region_label(0, v);
}

// Level 0's side (RADIANCE_SIDE) at voxel v inside the grid: voxgi__side_at.
vec4 side_at(ivec3 v)
{
#ifdef VOXGI_CONE_SVO
    uint slot;
    bool leaf;
    return voxgi_svo_descend(u_svo_depth, v, slot, leaf) ? voxgi_svo_load_of(VOXGI_SVO_SIDE, leaf, slot) : vec4(0.0);
#else
    return texelFetch(u_side, v, 0);
#endif
}

// The region of level k's voxel holding p: voxgi__region_at.
uint region_at(int k, vec3 p)
{
    ivec3 dk;
    region_level(k, dk);
    vec3 c = p / float(1 << k);
    if (!(all(greaterThanEqual(c, vec3(0.0))) && all(lessThan(c, vec3(dk))))) return 0u;
    return region_label(k, ivec3(c));
}

// Whether the segment from a to b meets voxel v's box: voxgi__segment_meets.
bool segment_meets(vec3 a, vec3 b, ivec3 v)
{
    float t0 = 0.0, t1 = 1.0;
    for (int ax = 0; ax < 3; ax++) {
        float d = b[ax] - a[ax], lo = float(v[ax]) - a[ax], hi = float(v[ax]) + 1.0 - a[ax];
        if (d == 0.0) {
            if (lo > 0.0 || hi < 0.0) return false;
            continue;
        }
        float ta = lo / d, tb = hi / d;
        t0 = max(t0, min(ta, tb));
        t1 = min(t1, max(ta, tb));
        if (t0 > t1) return false;
    }
    return true;
}

// Voxel o + (0.5 + s) n of level 0 in v; false beyond the grid: voxgi__along_voxel.
bool along_voxel(vec3 o, vec3 n, int s, out ivec3 v)
{
    vec3 q = o + (0.5 + float(s)) * n;
    v = ivec3(q);
    return all(greaterThanEqual(q, vec3(0.0))) && all(lessThan(q, vec3(u_res)));
}

// Where the eye sees o, the region of the first empty voxel on the way to it: voxgi__home_toward_eye.
uint home_toward_eye(vec3 o)
{
    vec3 d = u_eye - o;
    float len = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    for (int s = 0; s < 4 && 0.5 + float(s) < len; s++) {
        vec3 q = o + (0.5 + float(s)) / len * d;
        if (any(lessThan(q, vec3(0.0))) || any(greaterThanEqual(q, vec3(u_res)))) return REGION_OPEN;
        uint r = region_at(0, q);
        if (r != 0u && (r & REGION_BORDER) == 0u) return r;
    }
    return 0u;
}

// The enclosed region the cones from o on unit normal n start in: voxgi__home_region.
uint home_region(vec3 o, vec3 n)
{
    uint seen = u_seen_from_eye != 0 ? home_toward_eye(o) : 0u;
    if (seen != 0u) return seen == REGION_OPEN ? 0u : seen;
    vec3 start = o + 0.25 * n;
    for (int s = 0; s < 4; s++) { // voxgi__home_along: a point the eye sees takes no region across a wall
        ivec3 v;
        uint r = along_voxel(o, n, s, v) ? region_of(v) : 0u;
        if (r == 0u || (r & REGION_BORDER) != 0u) continue;
        bool crossed = false;
        for (int k = 0; u_seen_from_eye != 0 && k < s && !crossed; k++) {
            ivec3 w;
            if (!along_voxel(o, n, k, w)) continue;
            vec4 pl = side_at(w);
            vec3 vc = vec3(v) + 0.5;
            float at_start = pl.x * start.x + pl.y * start.y + pl.z * start.z - pl.w, at_v = pl.x * vc.x + pl.y * vc.y + pl.z * vc.z - pl.w;
            crossed = (at_start > 0.0 && at_v < 0.0) || (at_start < 0.0 && at_v > 0.0);
        }
        if (crossed) break;
        return r == REGION_OPEN ? 0u : r;
    }
    vec3 q = o + 0.25 * n;
    ivec3 c = ivec3(floor(q));
    uint best = 0u;
    float best_d2 = 1e30;
    for (int strict = 1; strict >= 0 && best == 0u; strict--) // all the planes around q; where that leaves none, those the segment passes
    for (int ez = c.z - 2; ez <= c.z + 2; ez++)
        for (int ey = c.y - 2; ey <= c.y + 2; ey++)
            for (int ex = c.x - 2; ex <= c.x + 2; ex++) {
                ivec3 e = ivec3(ex, ey, ez);
                if (any(lessThan(e, ivec3(0))) || any(greaterThanEqual(e, u_res))) continue;
                uint r = region_of(e);
                if (r == 0u || (r & REGION_BORDER) != 0u) continue;
                vec3 ec = vec3(e) + 0.5;
                float d2 = (ec.x - q.x) * (ec.x - q.x) + (ec.y - q.y) * (ec.y - q.y) + (ec.z - q.z) * (ec.z - q.z);
                if (!(d2 < best_d2)) continue;
                bool ok = true;
                for (int vz = c.z - 1; ok && vz <= c.z + 1; vz++)
                    for (int vy = c.y - 1; ok && vy <= c.y + 1; vy++)
                        for (int vx = c.x - 1; ok && vx <= c.x + 1; vx++) {
                            ivec3 v = ivec3(vx, vy, vz);
                            if (any(lessThan(v, ivec3(0))) || any(greaterThanEqual(v, u_res)) || (strict == 0 && !segment_meets(q, ec, v))) continue;
                            vec4 pl = side_at(v);
                            float at_q = pl.x * q.x + pl.y * q.y + pl.z * q.z - pl.w, at_e = pl.x * ec.x + pl.y * ec.y + pl.z * ec.z - pl.w;
                            ok = !((at_q > 0.0 && at_e < 0.0) || (at_q < 0.0 && at_e > 0.0));
                        }
                if (ok) { best = r; best_d2 = d2; }
            }
    return best == REGION_OPEN ? 0u : best;
}

// Corner `corner` of level k's trilinear sample at p (voxgi__cone_corners): its voxel, and its
// weight (0 beyond the level's size dk). No arrays: llvmpipe keeps those in memory.
float region_corner(int k, vec3 p, ivec3 dk, int corner, out ivec3 v)
{
    vec3 c = p / float(1 << k) - 0.5, f = c - floor(c);
    ivec3 hi = ivec3(corner & 1, (corner >> 1) & 1, corner >> 2);
    v = ivec3(floor(c)) + hi;
    if (any(lessThan(v, ivec3(0))) || any(greaterThanEqual(v, dk))) return 0.0;
    return (hi.x != 0 ? f.x : 1.0 - f.x) * (hi.y != 0 ? f.y : 1.0 - f.y) * (hi.z != 0 ? f.z : 1.0 - f.z);
}

// Whether level k's trilinear sample at p reads no region but home's and those inside it: voxgi__region_clear.
bool region_clear(int k, vec3 p, uint home)
{
    ivec3 dk, v;
    region_level(k, dk);
    for (int corner = 0; corner < 8; corner++) {
        if (region_corner(k, p, dk, corner, v) == 0.0) continue;
        uint r = region_label(k, v);
        if (r != 0u && r != home && !region_inside(home, r)) return false;
    }
    return true;
}

// Whether level 0's voxel v is a surface's lit from a region neither home nor inside it.
bool region_left_out(ivec3 v, uint home)
{
    uint r = region_of(v);
    uint of = r & ~(REGION_BORDER | REGION_UNSEEN);
    return (r & REGION_BORDER) != 0u && ((r & REGION_UNSEEN) != 0u || (of != home && !region_inside(home, of)));
}

#ifdef VOXGI_CONE_SVO
// Level k of a two-sided octree at p, by hand from its slots (without, at level 0 from region
// home, the voxels region_left_out drops): the front and the back mixed by the back share seen
// from o, as voxgi__cone_sample.
vec4 svo_two_sided_level(int k, vec3 p, vec3 o, uint home)
{
    ivec3 dk, v;
    region_level(k, dk);
    vec4 side = vec4(0.0), front = vec4(0.0), behind = vec4(0.0);
    for (int corner = 0; corner < 8; corner++) {
        float w = region_corner(k, p, dk, corner, v);
        uint slot;
        bool leaf;
        if (w == 0.0 || (home != 0u && k == 0 && region_left_out(v, home)) || !voxgi_svo_descend(u_svo_depth - k, v, slot, leaf)) continue;
        side += w * voxgi_svo_load_of(VOXGI_SVO_SIDE, leaf, slot);
        front += w * voxgi_svo_load(leaf, slot);
        behind += w * voxgi_svo_load_of(VOXGI_SVO_BACK, leaf, slot);
    }
    float back = back_share(side, o);
    return (1.0 - back) * front + back * u_back_coverage * behind;
}
#else
// Level 0 at p without the surfaces' voxels lit from a region that is neither home nor inside it
// (voxgi__cone_sample): false where it leaves none out (the textures' own filter serves);
// else the side, the front and the back filtered by hand from the rest.
bool level0_without(vec3 p, uint home, out vec4 side, out vec4 front, out vec4 back)
{
    ivec3 v;
    bool any_out = false;
    side = front = back = vec4(0.0);
    for (int corner = 0; corner < 8; corner++)
        if (region_corner(0, p, u_res, corner, v) != 0.0 && region_left_out(v, home)) any_out = true;
    if (!any_out) return false;
    for (int corner = 0; corner < 8; corner++) {
        float w = region_corner(0, p, u_res, corner, v);
        if (w == 0.0 || region_left_out(v, home)) continue;
        side += w * texelFetch(u_side, v, 0);
        front += w * texelFetch(u_rad0, v, 0);
        back += w * texelFetch(u_back0, v, 0);
    }
    return true;
}

// Level k of a two-sided volume at texture coordinates uv along d: the front and the back mixed
// by the back share seen from o.
vec4 two_sided_level(vec3 d, vec3 uv, float k, vec3 o)
{
    float back = back_share(textureLod(u_side, uv, k), o);
    vec4 f = back < 1.0 ? cone_level(false, d, uv, k) : vec4(0.0);
    if (back > 0.0) f = (1.0 - back) * f + back * u_back_coverage * cone_level(true, d, uv, k);
    return f;
}
#endif

// The sample at p and lod along d, seen from the cone's origin o, from region home (0: none):
// voxgi__cone_sample.
vec4 cone_sample(vec3 d, vec3 p, float lod, vec3 o, uint home)
{
    float m = float(u_levels - 1);
    vec4 s;
#ifdef VOXGI_CONE_SVO
    if (u_two_sided != 0) {
        float l = clamp(lod, 0.0, m), k0 = floor(l), t = l - k0;
        vec4 v0 = svo_two_sided_level(int(k0), p, o, home);
        s = t > 0.0 ? v0 + t * (svo_two_sided_level(int(k0) + 1, p, o, home) - v0) : v0;
    } else s = voxgi_sample_svo(p, clamp(lod, 0.0, m));
#else
    if (u_two_sided != 0) { // each level on its own: the front and the back mixed by the back share
        float l = clamp(lod, 0.0, m), k0 = floor(l), t = l - k0;
        vec3 uv = p / u_size;
        vec4 v0, side, front, behind;
        if (home != 0u && k0 == 0.0 && level0_without(p, home, side, front, behind)) {
            float back = back_share(side, o);
            v0 = (1.0 - back) * front + back * u_back_coverage * behind;
        } else
            v0 = two_sided_level(d, uv, k0, o);
        s = t > 0.0 ? v0 + t * (two_sided_level(d, uv, k0 + 1.0, o) - v0) : v0;
    } else if (u_anisotropic == 0) s = voxgi_sample_volume(u_rad0, p, lod, u_size, m);
    else { // the axis volumes along the travel direction, weighted by its squared components
        vec3 w = d * d;
        s = w.x * (d.x < 0.0 ? voxgi_sample_volume(u_rad1, p, lod, u_size, m) : voxgi_sample_volume(u_rad0, p, lod, u_size, m)) +
            w.y * (d.y < 0.0 ? voxgi_sample_volume(u_rad3, p, lod, u_size, m) : voxgi_sample_volume(u_rad2, p, lod, u_size, m)) +
            w.z * (d.z < 0.0 ? voxgi_sample_volume(u_rad5, p, lod, u_size, m) : voxgi_sample_volume(u_rad4, p, lod, u_size, m));
    }
#endif
    return vec4(s.a > 0.0 ? s.rgb / s.a : vec3(0.0), s.a);
}

// The cones' region from o on unit normal n: home_region where the volume has regions, else 0.
uint home_of(vec3 o, vec3 n)
{
    return u_regions != 0u ? home_region(o, n) : 0u;
}

// One cone from o (on a surface of unit normal n) along unit d, at cosine lz with n: marched from
// u_offset voxels along n, narrowing tan_k, up to max_d; (radiance, opacity). voxgi__cone_march.
vec4 march(vec3 o, vec3 n, vec3 d, float lz, float tan_k, float max_d, uint home)
{
    float t = u_offset, A = 0.0;
    vec3 C = vec3(0.0), start = o + u_offset * n, last = vec3(0.0); // where a sample's side is seen from; the last colour seen
    while (t < max_d && A < 0.99) {
        float diam = max(1.0, 2.0 * t * tan_k), h = u_offset + (t - u_offset) * lz;
        vec3 p = o + u_offset * n + (t - u_offset) * d;
        float lod = min(min(log2(diam), log2(h / 1.5) - 1.0), float(u_levels - 1));
        if (home != 0u) { // out of an enclosed region: ended where it leaves it, no level reaching beyond it
            uint here = region_at(0, p);
            if (here != 0u && (here & REGION_BORDER) == 0u && here != home && !region_inside(home, here)) {
                C += (1.0 - A) * last; // the rest of the cone ends on the enclosure, as last seen
                A = 1.0;
                break;
            }
            int k = int(ceil(lod));
            while (k > 0 && !region_clear(k, p, home)) k--;
            if (float(k) < lod) { lod = float(k); diam = exp2(lod); }
        }
        vec4 s = cone_sample(d, p, lod, start, home);
        if (s.a > 0.0) last = s.rgb;
        float ap = 1.0 - pow(1.0 - min(1.0, s.a * (u_anisotropic != 0 ? 2.0 : exp2(max(lod, 0.0)))), u_step);
        C += (1.0 - A) * ap * s.rgb;
        A += (1.0 - A) * ap;
        t += u_step * min(diam, max(1.0, h)); // voxgi__cone_march: no leap over what lies just above
    }
    return vec4(C, A);
}

// The diffuse gathers of the points or pixels u_first .. u_first + u_count - 1, in three passes
// (u_pass): 0 each one's home region, 1 each of its cones on an invocation of its own, 2 their
// sums in cone order, (irradiance, occlusion). llvmpipe ends an invocation's loops after 65535
// iterations in all (LP_MAX_TGSI_LOOP_ITERATIONS), which a whole gather of 32 cones over an
// octree at 64^3 exceeds (its sums came out short); one cone stays well below.
// cone_trace_buffers.glsl and cone_trace_images.glsl say where a point comes from and where its
// gather goes.
layout(std430, binding = 7) buffer ConeScratch { uvec4 cone_scratch[]; }; // cone k of point j at k u_count + j, then u_count homes
layout(location = VOXGI_LOC_u_pass) uniform int u_pass;
layout(location = VOXGI_LOC_u_first) uniform uint u_first; // the slice's first point
layout(location = VOXGI_LOC_u_count) uniform uint u_count;
bool gather_point(uint i, out vec3 o, out vec3 n); // false: no surface there (its gather is 0)
void gather_result(uint i, vec4 irradiance_occlusion);

void gather_pass(uint g)
{
    uint cones = uint(u_cones), homes = u_count * cones;
    vec3 o, n;
    if (u_pass == 1) { // cone k of point j: 8 neighbouring points' cone 0, their cone 1, ... (alike in a SIMD vector, near in the caches)
        uint j = g / (8u * cones) * 8u + g % 8u, kk = g / 8u % cones;
        float k = float(kk);
        if (j >= u_count) return;
        if (!gather_point(u_first + j, o, n)) return;
        vec3 t3, b3;
        voxgi_basis(n, t3, b3);
        float r = sqrt((k + 0.5) / float(u_cones)), phi = 2.399963229728653 * k;
        vec3 l = vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - r * r)));
        cone_scratch[kk * u_count + j] = floatBitsToUint(march(o, n, l.x * t3 + l.y * b3 + l.z * n, l.z, min(u_half_tan, l.z / 3.0), u_max_distance, cone_scratch[homes + j].x));
        return;
    }
    if (g >= u_count) return;
    bool surface = gather_point(u_first + g, o, n);
    if (u_pass == 0) {
        cone_scratch[homes + g] = uvec4(surface ? home_of(o, n) : 0u);
        return;
    }
    vec3 e = vec3(0.0);
    float occ = 0.0;
    for (uint k = 0u; surface && k < cones; k++) {
        vec4 c = uintBitsToFloat(cone_scratch[k * u_count + g]);
        e += 3.14159265358979323846 / float(u_cones) * c.rgb;
        occ += c.a / float(u_cones);
    }
    gather_result(u_first + g, vec4(e, occ));
}
