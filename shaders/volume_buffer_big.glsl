// The Volume Buffer's big pass (before volume_buffer.glsl): 32 geometry-shader invocations per
// triangle, for the triangles that span more layers than one invocation may emit.
#define VB_INVOCATIONS 32
