// cone_trace.glsl over an octree's RADIANCE (voxgi_cone_trace_svo, voxgi_trace_cones_svo): its
// samples through svo.glsl's voxgi_sample_svo instead of the volume's textures.
// embedded unless VOXGI_NO_CONE_TRACING or VOXGI_NO_OCTREE
#define VOXGI_CONE_SVO
