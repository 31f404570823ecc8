// Cone tracing over a RADIANCE volume (voxgi.h, part "light injection and cone tracing"): the
// march of voxgi__cone_march step for step, with the textures' own filtering (the radiance is
// stored premultiplied, so linear filtering is right), or over an octree's RADIANCE where
// cone_svo.glsl defines VOXGI_CONE_SVO (after svo.glsl). Its passes: cone_trace_buffers.glsl
// (points and single cones in storage buffers) and cone_trace_images.glsl (a G-buffer).
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

// The share of a sample's back sides seen from o: voxgi__back_share (VOXGI__SIDE_RAMP 4096).
float back_share(vec4 side, vec3 o)
{
    float len = length(side.xyz);
    if (!(len > 0.0)) return 0.0;
    return clamp(0.5 - 4096.0 * (dot(side.xyz, o) - side.w) / len, 0.0, 1.0);
}
#endif

// The sample at p and lod along d, seen from the cone's origin o: voxgi__cone_sample.
vec4 cone_sample(vec3 d, vec3 p, float lod, vec3 o)
{
    float m = float(u_levels - 1);
    vec4 s;
#ifdef VOXGI_CONE_SVO
    s = voxgi_sample_svo(p, clamp(lod, 0.0, m));
#else
    if (u_two_sided != 0) { // each level on its own: the front and the back mixed by the back share
        float l = clamp(lod, 0.0, m), k0 = floor(l), t = l - k0;
        vec3 uv = p / u_size;
        vec4 v[2];
        for (int lev = 0; lev < (t > 0.0 ? 2 : 1); lev++) {
            float k = k0 + float(lev), back = back_share(textureLod(u_side, uv, k), o);
            vec4 f = back < 1.0 ? cone_level(false, d, uv, k) : vec4(0.0);
            if (back > 0.0) f = (1.0 - back) * f + back * u_back_coverage * cone_level(true, d, uv, k);
            v[lev] = f;
        }
        s = t > 0.0 ? v[0] + t * (v[1] - v[0]) : v[0];
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

// One cone from o (on a surface of unit normal n) along unit d, at cosine lz with n: marched from
// u_offset voxels along n, narrowing tan_k, up to max_d; (radiance, opacity). voxgi__cone_march.
vec4 march(vec3 o, vec3 n, vec3 d, float lz, float tan_k, float max_d)
{
    float t = u_offset, A = 0.0;
    vec3 C = vec3(0.0), start = o + u_offset * n; // where a sample's side is seen from
    while (t < max_d && A < 0.99) {
        float diam = max(1.0, 2.0 * t * tan_k), h = u_offset + (t - u_offset) * lz;
        vec3 p = o + u_offset * n + (t - u_offset) * d;
        float lod = min(min(log2(diam), log2(h / 1.5) - 1.0), float(u_levels - 1));
        vec4 s = cone_sample(d, p, lod, start);
        float ap = 1.0 - pow(1.0 - min(1.0, s.a * (u_anisotropic != 0 ? 2.0 : exp2(max(lod, 0.0)))), u_step);
        C += (1.0 - A) * ap * s.rgb;
        A += (1.0 - A) * ap;
        t += u_step * diam;
    }
    return vec4(C, A);
}

// The diffuse gather at o (grid units) on unit normal n: (irradiance, occlusion).
vec4 gather(vec3 o, vec3 n)
{
    vec3 t3, b3;
    voxgi_basis(n, t3, b3);
    vec3 e = vec3(0.0);
    float occ = 0.0;
    for (int k = 0; k < u_cones; k++) {
        float r = sqrt((float(k) + 0.5) / float(u_cones)), phi = 2.399963229728653 * float(k);
        vec3 l = vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - r * r)));
        vec4 c = march(o, n, l.x * t3 + l.y * b3 + l.z * n, l.z, min(u_half_tan, l.z / 3.0), u_max_distance);
        e += 3.14159265358979323846 / float(u_cones) * c.rgb;
        occ += c.a / float(u_cones);
    }
    return vec4(e, occ);
}
