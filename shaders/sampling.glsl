// What every sampler of voxel data shares (voxgi.h, part "attribute volumes and mipmaps").

// An orthonormal frame (t, b) around unit n, as voxgi__basis (for cone sets and light maps).
void voxgi_basis(vec3 n, out vec3 t, out vec3 b)
{
    float sgn = n.z >= 0.0 ? 1.0 : -1.0, a = -1.0 / (sgn + n.z), c = n.x * n.y * a;
    t = vec3(1.0 + sgn * n.x * n.x * a, sgn * c, -sgn * n.x);
    b = vec3(c, sgn + n.y * n.y * a, -n.y);
}

// The lod at which one voxel is as wide as a footprint of `diameter` voxels of level 0 (a cone's
// width where it samples): log2(diameter), 0 below one voxel; voxgi_lod_from_footprint in C.
float voxgi_lod_from_footprint(float diameter)
{
    return diameter > 1.0 ? log2(diameter) : 0.0;
}

// Sampling an attribute volume: p in grid units of level 0, lod in levels; the texture's base
// size is `size` (the grid rounded up so GL's mip chain holds every level; the padding is
// empty), filtering LINEAR_MIPMAP_LINEAR with an empty border: trilinear between voxel centres,
// linear between levels, as voxgi__sample_level on the CPU.
vec4 voxgi_sample_volume(sampler3D volume, vec3 p, float lod, vec3 size, float max_lod)
{
    return textureLod(volume, p / size, clamp(lod, 0.0, max_lod));
}

