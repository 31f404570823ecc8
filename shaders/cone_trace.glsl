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
#endif
layout(location = VOXGI_LOC_u_size) uniform vec3 u_size;      // the textures' base size
layout(location = VOXGI_LOC_u_levels) uniform int u_levels;     // mip levels (an octree: depth + 1)
layout(location = VOXGI_LOC_u_anisotropic) uniform int u_anisotropic;
layout(location = VOXGI_LOC_u_cones) uniform int u_cones;
layout(location = VOXGI_LOC_u_half_tan) uniform float u_half_tan;
layout(location = VOXGI_LOC_u_step) uniform float u_step;
layout(location = VOXGI_LOC_u_offset) uniform float u_offset;
layout(location = VOXGI_LOC_u_max_distance) uniform float u_max_distance;

vec4 cone_sample(vec3 d, vec3 p, float lod)
{
    float m = float(u_levels - 1);
    vec4 s;
#ifdef VOXGI_CONE_SVO
    s = voxgi_sample_svo(p, clamp(lod, 0.0, m));
#else
    if (u_anisotropic == 0) s = voxgi_sample_volume(u_rad0, p, lod, u_size, m);
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
    vec3 C = vec3(0.0);
    while (t < max_d && A < 0.99) {
        float diam = max(1.0, 2.0 * t * tan_k), h = u_offset + (t - u_offset) * lz;
        vec3 p = o + u_offset * n + (t - u_offset) * d;
        float lod = min(min(log2(diam), log2(h / 1.5) - 1.0), float(u_levels - 1));
        vec4 s = cone_sample(d, p, lod);
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
