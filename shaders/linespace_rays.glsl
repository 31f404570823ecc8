// Given rays through the line space (voxgi__ls_rays_cpu's GL twin; the walk is linespace.glsl's):
// per ray whether something lies on it at t in (tmin, tmax).
// embedded unless VOXGI_NO_LINE_SPACE
layout(std430, binding = 5) readonly buffer Rays { float rays[]; };      // 8 per ray of this slice: voxgi_ray
layout(std430, binding = 6) writeonly buffer Occluded { uint occluded[]; }; // 1 per ray of this slice

// voxgi__ls_ray_set: the origin in the scene's frame
bool ray_set(vec3 o, vec3 d, float t0, float t1)
{
    precise vec3 ro;
    for (int a = 0; a < 3; a++) ro[a] = float(double(o[a]) - u_centre[a]);
    return ray_set_centred(ro, d, t0, t1);
}

void main()
{
    if (gl_GlobalInvocationID.x >= u_count) return;
    uint i = gl_GlobalInvocationID.x, b = 8u * i;
    vec3 o = vec3(rays[b], rays[b + 1u], rays[b + 2u]), d = vec3(rays[b + 4u], rays[b + 5u], rays[b + 6u]);
    float t0 = rays[b + 3u], t1 = rays[b + 7u];
    occluded[i] = t1 > t0 && ray_set(o, d, t0, t1) && trace(u_fast != 0) ? 1u : 0u;
}
