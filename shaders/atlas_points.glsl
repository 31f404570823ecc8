// Texture atlas drawn as points (Buchacher's method B), after scene.glsl, atlas.glsl and
// slice_targets.glsl: each point goes to its voxel's column, at the exact pixel centre, and
// sets its slice along u_axis.
layout(location = VOXGI_LOC_u_axis) uniform int u_axis;

#ifdef VOXGI_VERTEX
flat out int v_slice;
void main()
{
    int A = u_axis, a = (A + 1) % 3, b = (A + 2) % 3;
    ivec3 v;
    gl_PointSize = 1.0;
    if (!atlas_point_voxel(points[gl_VertexID], v)) { // clipped away
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        v_slice = -1;
        return;
    }
    gl_Position = vec4((2.0 * float(v[a]) + 1.0) / float(u_view.x) - 1.0, (2.0 * float(v[b]) + 1.0) / float(u_view.y) - 1.0, 0.0, 1.0);
    v_slice = v[A];
}
#endif

#ifdef VOXGI_FRAGMENT
flat in int v_slice;
void main() { write_slice(v_slice); }
#endif
