// voxgi_cone_trace and voxgi_trace_cones on GL (after cone_trace.glsl): points or cones from a
// storage buffer, results into another, one invocation each (bindings 3 and 4: an octree's
// buffers take 0 to 2).
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 3) readonly buffer Points { vec4 points[]; };   // 3 per point or cone, grid units
layout(std430, binding = 4) writeonly buffer Gathered { vec4 gathered[]; }; // irradiance and occlusion, or radiance and opacity
layout(location = VOXGI_LOC_u_first) uniform uint u_first;
layout(location = VOXGI_LOC_u_count) uniform uint u_count;

// u_cones > 0: diffuse gathers at points (position, normal); u_cones == 0: single cones
// (origin and tan of the half-angle, direction and reach, normal and its cosine with the
// direction), as voxgi__cone_each_range.
void main()
{
    uint i = u_first + gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    vec4 a = points[3u * i], b = points[3u * i + 1u], c = points[3u * i + 2u];
    if (u_cones == 0) // narrowed near the surface unless it leaves along its normal
        gathered[i] = march(a.xyz, c.xyz, b.xyz, c.w, c.w > 0.0 && c.w < 1.0 ? min(a.w, c.w / 3.0) : a.w, b.w, home_of(a.xyz, c.xyz));
    else gathered[i] = gather(a.xyz, b.xyz);
}
