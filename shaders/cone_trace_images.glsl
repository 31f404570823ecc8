// voxgi_cone_trace_gl (after cone_trace.glsl and out_*.glsl): the diffuse gather over the
// caller's G-buffer textures, pixel i = x + width y. Positions in world units (texel rgb),
// normals in rgb (a zero normal: no surface, written 0); out: irradiance and occlusion, or with
// an albedo texture the reflected radiance albedo / pi x irradiance.
// embedded unless VOXGI_NO_CONE_TRACING
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(binding = 6) uniform sampler2D u_positions;
layout(binding = 7) uniform sampler2D u_normals;
layout(binding = 8) uniform sampler2D u_albedo;
layout(binding = 0, VOXGI_OUT_FORMAT) uniform writeonly image2D u_out;
layout(location = VOXGI_LOC_u_image) uniform ivec2 u_image;
layout(location = VOXGI_LOC_u_origin) uniform vec3 u_origin;    // the grid's origin and voxel size: world -> grid units
layout(location = VOXGI_LOC_u_voxel_size) uniform float u_voxel_size;
layout(location = VOXGI_LOC_u_has_albedo) uniform int u_has_albedo;

ivec2 pixel(uint i)
{
    return ivec2(int(i % uint(u_image.x)), int(i / uint(u_image.x)));
}

bool gather_point(uint i, out vec3 o, out vec3 n)
{
    ivec2 px = pixel(i);
    n = texelFetch(u_normals, px, 0).rgb;
    o = (texelFetch(u_positions, px, 0).rgb - u_origin) / u_voxel_size;
    if (dot(n, n) == 0.0) return false;
    n = normalize(n);
    return true;
}

void gather_result(uint i, vec4 g)
{
    ivec2 px = pixel(i);
    if (u_has_albedo != 0) g.rgb *= texelFetch(u_albedo, px, 0).rgb / 3.14159265358979323846;
    imageStore(u_out, px, g);
}

void main()
{
    gather_pass(gl_GlobalInvocationID.x);
}
