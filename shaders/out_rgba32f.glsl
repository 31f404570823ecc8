// Output format of cone_trace_images.glsl: RGBA32F.
#define VOXGI_OUT_FORMAT rgba32f
