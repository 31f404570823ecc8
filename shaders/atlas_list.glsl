// Texture atlas, after scene.glsl and atlas.glsl: the covered texels, counted (u_pass 0) or
// listed as points (u_pass 1); one invocation per texel.
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(binding = 0) uniform usampler2D u_atlas;
layout(location = VOXGI_LOC_u_size) uniform int u_size;
layout(location = VOXGI_LOC_u_pass) uniform int u_pass;

void main()
{
    uint item = atlas_item(), size = uint(u_size);
    if (item >= size * size) return;
    uvec2 texel = uvec2(item % size, item / size);
    uint t = texelFetch(u_atlas, ivec2(texel), 0).r;
    if (t == 0u) return;
    uint slot = atomicAdd(point_count, 1u);
    if (u_pass == 1) points[slot] = uvec2(texel.x | (texel.y << 16), t - 1u);
}
