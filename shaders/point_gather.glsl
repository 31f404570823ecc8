// What the one-bounce gathers at points share (voxgi__point_gather's GL side, before
// rsm_gather.glsl or sh_gather.glsl): one invocation per point, its position and normal in, the
// irradiance the method's gather() finds there out.
// embedded unless VOXGI_NO_LIGHT_SPACE
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 0) readonly buffer Points { float points[]; };    // 3 per point
layout(std430, binding = 1) readonly buffer Normals { float normals[]; };  // 3 per point
layout(std430, binding = 2) writeonly buffer Irradiance { float irradiance[]; }; // 3 per point
layout(location = VOXGI_LOC_u_count) uniform uint u_count;
layout(location = VOXGI_LOC_u_first) uniform uint u_first;
layout(location = VOXGI_LOC_u_origin) uniform vec3 u_origin;      // the voxels' grid
layout(location = VOXGI_LOC_u_voxel_size) uniform float u_voxel_size;

vec3 gather(vec3 x, vec3 n);

void main()
{
    uint at = gl_GlobalInvocationID.x + u_first;
    if (gl_GlobalInvocationID.x >= u_count) return;
    vec3 e = gather(vec3(points[3u * at], points[3u * at + 1u], points[3u * at + 2u]), vec3(normals[3u * at], normals[3u * at + 1u], normals[3u * at + 2u]));
    irradiance[3u * at] = e.x;
    irradiance[3u * at + 1u] = e.y;
    irradiance[3u * at + 2u] = e.z;
}
