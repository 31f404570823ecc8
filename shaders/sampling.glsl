// What every sampler of voxel data shares (voxgi.h, part "attribute volumes and mipmaps").

// The lod at which one voxel is as wide as a footprint of `diameter` voxels of level 0 (a cone's
// width where it samples): log2(diameter), 0 below one voxel; voxgi_lod_from_footprint in C.
float voxgi_lod_from_footprint(float diameter)
{
    return diameter > 1.0 ? log2(diameter) : 0.0;
}
