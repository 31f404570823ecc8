// Draws the scene into one layer of the distance maps (after light_maps.glsl): vertex and
// fragment stages over the triangles' corners (3 vec4 per triangle, relative to the grid origin).
// embedded unless VOXGI_NO_LIGHT_INJECTION
layout(std430, binding = 0) readonly buffer Corners { vec4 corner[]; };
layout(std430, binding = 1) readonly buffer Casters { Caster casters[]; };
layout(location = VOXGI_LOC_u_caster) uniform int u_caster;
layout(location = VOXGI_LOC_u_face) uniform int u_face;      // cube face, or -1 for a directional light's one layer
layout(location = VOXGI_LOC_u_near) uniform float u_near;

#ifdef VOXGI_VERTEX
out vec3 v_p;
void main()
{
    Caster c = casters[u_caster];
    vec3 p = corner[gl_VertexID].xyz, f, r, u;
    v_p = p;
    if (u_face < 0) { // orthographic over the scene's bounding sphere
        voxgi_basis(c.dir.xyz, r, u);
        vec3 q = p - c.pos.xyz;
        gl_Position = vec4(dot(q, r) / c.dir.w, dot(q, u) / c.dir.w, 0.0, 1.0);
    } else { // a 90-degree perspective face; clipped only at the near plane (w >= near)
        cube_face(u_face, f, r, u);
        vec3 q = p - c.pos.xyz;
        float w = dot(q, f);
        gl_Position = vec4(dot(q, r), dot(q, u), w - 2.0 * u_near, w);
    }
}
#endif

#ifdef VOXGI_FRAGMENT
in vec3 v_p;
layout(binding = 0, r32ui) uniform coherent uimage2DArray u_maps;
void main()
{
    Caster c = casters[u_caster];
    float d = u_face < 0 ? dot(v_p - c.pos.xyz, c.dir.xyz) : length(v_p - c.pos.xyz);
    imageAtomicMin(u_maps, ivec3(ivec2(gl_FragCoord.xy), int(c.power.w) + max(u_face, 0)), floatBitsToUint(max(d, 0.0)));
}
#endif
