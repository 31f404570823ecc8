// Output format of cone_trace_images.glsl: RGBA16F.
#define VOXGI_OUT_FORMAT rgba16f
