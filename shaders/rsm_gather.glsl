// The reflective shadow maps' gather at a point (voxgi__rsm_point's GL twin, in float; run by
// point_gather.glsl): every map's pattern of texels through equation 5, each sample through the
// voxels (voxel_traverse.glsl) when u_levels > 0.
// embedded unless VOXGI_NO_LIGHT_SPACE
layout(std430, binding = 3) readonly buffer Texels { float texels[]; };    // 9 per texel: position, normal, flux
// 24 per map: u 0-2, v 3-5, w 6-8, lo 9-11, texel 12, eye 13-15, tan_half 16, kind 17 (0
// orthographic, 1 perspective, 2 hemisphere), size 18, radius 19, first sample 20, samples 21,
// first texel 22, near_z 23
layout(std430, binding = 4) readonly buffer Maps { float maps[]; };
layout(std430, binding = 5) readonly buffer Pattern { float pattern[]; }; // 3 per sample: offset, weight
layout(location = VOXGI_LOC_u_maps) uniform int u_maps;

const float PI = 3.14159265358979;

vec3 mvec(int m, int at) { return vec3(maps[24 * m + at], maps[24 * m + at + 1], maps[24 * m + at + 2]); }

// voxgi__disk_to_square: a direction's point of the concentric map's square (the rim at or below the horizon)
vec2 disk_to_square(vec3 p)
{
    float len = p.z > 0.0 ? length(p) : length(p.xy);
    if (!(len > 0.0)) return vec2(0.0);
    float x = p.x / len, y = p.y / len, r = min(1.0, sqrt(x * x + y * y)), phi = atan(y, x);
    if (phi < -PI / 4.0) phi += 2.0 * PI;
    if (phi < PI / 4.0) return vec2(r, phi * 4.0 / PI * r);
    if (phi < 3.0 * PI / 4.0) return vec2(-(phi - PI / 2.0) * 4.0 / PI * r, r);
    if (phi < 5.0 * PI / 4.0) return vec2(-r, -(phi - PI) * 4.0 / PI * r);
    return vec2((phi - 3.0 * PI / 2.0) * 4.0 / PI * r, -r);
}

// voxgi__view_point: x in map m's texels
vec2 view_point(int m, vec3 x)
{
    vec3 u = mvec(m, 0), v = mvec(m, 3), w = mvec(m, 6), eye = mvec(m, 13);
    float kind = maps[24 * m + 17], size = maps[24 * m + 18];
    if (kind == 2.0) {
        vec3 r = x - eye;
        vec2 sq = disk_to_square(vec3(dot(r, u), dot(r, v), dot(r, w)));
        return 0.5 * size * (1.0 + sq);
    }
    if (kind == 1.0) {
        vec3 r = x - eye;
        float z = max(dot(r, w), maps[24 * m + 23]), t = maps[24 * m + 16];
        return 0.5 * size * (1.0 + vec2(dot(r, u), dot(r, v)) / (z * t));
    }
    return (vec2(dot(x, u), dot(x, v)) - mvec(m, 9).xy) / maps[24 * m + 12];
}

vec3 gather(vec3 x, vec3 n)
{
    vec3 e = vec3(0.0);
    for (int m = 0; m < u_maps; m++) {
        float kind = maps[24 * m + 17], size = maps[24 * m + 18], radius = maps[24 * m + 19];
        int first = int(maps[24 * m + 20]), samples = int(maps[24 * m + 21]), isize = int(size);
        uint base = uint(maps[24 * m + 22]);
        float disc = PI * radius * radius;
        float spread = kind == 2.0 ? PI / (size * size) : (kind == 1.0 ? 4.0 * maps[24 * m + 16] * maps[24 * m + 16] / (size * size) : 0.0);
        vec3 eye = mvec(m, 13);
        vec2 st = view_point(m, x);
        for (int k = 0; k < samples; k++) {
            float s = st.x + pattern[3 * (first + k)], t = st.y + pattern[3 * (first + k) + 1];
            if (!(s >= 0.0 && s < size && t >= 0.0 && t < size)) continue;
            uint tx = base + uint(t) * uint(isize) + uint(s);
            vec3 phi = vec3(texels[9u * tx + 6u], texels[9u * tx + 7u], texels[9u * tx + 8u]);
            if (phi == vec3(0.0)) continue;
            vec3 xp = vec3(texels[9u * tx], texels[9u * tx + 1u], texels[9u * tx + 2u]);
            vec3 np = vec3(texels[9u * tx + 3u], texels[9u * tx + 4u], texels[9u * tx + 5u]);
            vec3 d = x - xp;
            float dist2 = dot(d, d), cp = dot(np, d), cx = -dot(n, d);
            if (cp <= 0.0 || cx <= 0.0) continue;
            if (spread > 0.0) {
                vec3 r = xp - eye;
                dist2 = max(dist2, dot(r, r) * spread);
            } else
                dist2 = max(dist2, maps[24 * m + 12] * maps[24 * m + 12]);
            if (u_levels > 0) { // each end 1.5 voxels off its own surface
                vec3 o = (x + 1.5 * u_voxel_size * n - u_origin) / u_voxel_size;
                vec3 to = (xp + 1.5 * u_voxel_size * np - u_origin) / u_voxel_size;
                if (occluded(o, to - o)) continue;
            }
            float f = disc * pattern[3 * (first + k) + 2] * cp * cx / (PI * dist2 * dist2);
            e += f * phi;
        }
    }
    return e;
}
