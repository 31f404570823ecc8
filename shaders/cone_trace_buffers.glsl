// voxgi_cone_trace and voxgi_trace_cones on GL (after cone_trace.glsl): points or cones from a
// storage buffer, results into another (bindings 3 and 4: an octree's buffers take 0 to 2 and 6).
// embedded unless VOXGI_NO_CONE_TRACING
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 3) readonly buffer Points { vec4 points[]; };   // 3 per point or cone, grid units
layout(std430, binding = 4) writeonly buffer Gathered { vec4 gathered[]; }; // irradiance and occlusion, or radiance and opacity

bool gather_point(uint i, out vec3 o, out vec3 n)
{
    o = points[3u * i].xyz;
    n = points[3u * i + 1u].xyz;
    return true;
}

void gather_result(uint i, vec4 irradiance_occlusion)
{
    gathered[i] = irradiance_occlusion;
}

// u_cones > 0: diffuse gathers at points (position, normal; gather_pass); u_cones == 0: single
// cones (origin and tan of the half-angle, direction and reach, normal and its cosine with the
// direction), as voxgi__cone_each_cpu, one invocation each.
void main()
{
    uint g = gl_GlobalInvocationID.x, i = u_first + g;
    if (u_cones != 0) {
        gather_pass(g);
        return;
    }
    if (g >= u_count) return;
    vec4 a = points[3u * i], b = points[3u * i + 1u], c = points[3u * i + 2u];
    gathered[i] = march(a.xyz, c.xyz, b.xyz, c.w, c.w > 0.0 && c.w < 1.0 ? min(a.w, c.w / 3.0) : a.w, b.w, home_of(a.xyz, c.xyz));
}
