// Texture atlas fill, after scene.glsl and atlas.glsl: every chart drawn into an R32UI atlas,
// which keeps triangle + 1 per covered texel centre (primitive order: the last chart drawn wins).
// The viewport is u_view texels, a power of two, so the corners reach the rasterizer unrounded.
layout(location = VOXGI_LOC_u_view) uniform int u_view;

#ifdef VOXGI_VERTEX
flat out uint v_tri;
void main()
{
    gl_Position = vec4(chart[gl_VertexID] * (2.0 / float(u_view)) - 1.0, 0.0, 1.0);
    v_tri = uint(gl_VertexID / 3);
}
#endif

#ifdef VOXGI_FRAGMENT
flat in uint v_tri;
layout(location = 0) out uint o_tri;
void main() { o_tri = v_tri + 1u; }
#endif
