// The G-buffer voxgi rasterizes for its own images on GL (voxgi.h, part "light injection and
// cone tracing": voxgi_gbuffer_render): per pixel the nearest surface's position (relative to
// the eye), its normal facing the camera and its triangle. Vertex and fragment stages over the
// triangles' corners (3 vec4 per triangle, relative to the eye); the depth test on the distance
// along the view direction.
layout(std430, binding = 0) readonly buffer Corners { vec4 corner[]; };
layout(std430, binding = 1) readonly buffer Normals { vec4 tri_normal[]; };
layout(location = VOXGI_LOC_u_right) uniform vec3 u_right; // the camera's frame
layout(location = VOXGI_LOC_u_up) uniform vec3 u_up;
layout(location = VOXGI_LOC_u_forward) uniform vec3 u_forward;
layout(location = VOXGI_LOC_u_tan) uniform vec2 u_tan;                    // tan of the half field of view, across and up
layout(location = VOXGI_LOC_u_near) uniform float u_near;
layout(location = VOXGI_LOC_u_far) uniform float u_far;

#ifdef VOXGI_VERTEX
out vec3 v_p;
flat out int v_tri;
void main()
{
    vec3 q = corner[gl_VertexID].xyz;
    float w = dot(q, u_forward);
    v_p = q;
    v_tri = gl_VertexID / 3;
    gl_Position = vec4(dot(q, u_right) / u_tan.x, dot(q, u_up) / u_tan.y, (u_far + u_near) / (u_far - u_near) * w - 2.0 * u_far * u_near / (u_far - u_near), w);
}
#endif

#ifdef VOXGI_FRAGMENT
in vec3 v_p;
flat in int v_tri;
layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out uint o_triangle;
void main()
{
    vec3 n = tri_normal[v_tri].xyz;
    o_position = vec4(v_p, 1.0);
    o_normal = vec4(dot(n, v_p) < 0.0 ? n : -n, 0.0);
    o_triangle = uint(v_tri);
    // linear depth: the projective one cannot tell apart surfaces 1e-4 of the distance apart (a
    // lamp just below a ceiling), so that the drawing order would decide
    gl_FragDepth = dot(v_p, u_forward) / u_far;
}
#endif
