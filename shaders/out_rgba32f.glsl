// Output format of cone_trace_images.glsl: RGBA32F.
// embedded unless VOXGI_NO_CONE_TRACING
#define VOXGI_OUT_FORMAT rgba32f
