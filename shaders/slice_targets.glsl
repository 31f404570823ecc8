// The raster slicemap's targets (after scene.glsl), shared by every pass that draws into them.
// Logic-op variant: a fragment writes its slice's bit into one of up to eight RGBA32UI targets
// (128 slices each, from u_first_slice), ORed by GL_COLOR_LOGIC_OP. Atomic variant:
// imageAtomicOr into an R32UI array, 32 slices per layer.
layout(location = VOXGI_LOC_u_first_slice) uniform int u_first_slice;
layout(location = VOXGI_LOC_u_atomic) uniform int u_atomic;
layout(location = VOXGI_LOC_u_view) uniform ivec2 u_view; // the viewport: powers of two, at least the slicemap's size

#ifdef VOXGI_FRAGMENT
layout(binding = 0, r32ui) uniform coherent uimage2DArray u_slices;
layout(location = 0) out uvec4 o0;
layout(location = 1) out uvec4 o1;
layout(location = 2) out uvec4 o2;
layout(location = 3) out uvec4 o3;
layout(location = 4) out uvec4 o4;
layout(location = 5) out uvec4 o5;
layout(location = 6) out uvec4 o6;
layout(location = 7) out uvec4 o7;

// Sets this pixel's bit of `slice`; a negative slice writes nothing.
void write_slice(int slice)
{
    uvec4 none = uvec4(0u);
    o0 = none; o1 = none; o2 = none; o3 = none; o4 = none; o5 = none; o6 = none; o7 = none;
    if (slice < 0) return;
    if (u_atomic != 0) {
        imageAtomicOr(u_slices, ivec3(ivec2(gl_FragCoord.xy), slice >> 5), 1u << uint(slice & 31));
        return;
    }
    int local = slice - u_first_slice;
    if (local < 0 || local >= 1024) return;
    uvec4 bit = uvec4(0u);
    bit[(local >> 5) & 3] = 1u << uint(local & 31);
    switch (local >> 7) {
    case 0: o0 = bit; break;
    case 1: o1 = bit; break;
    case 2: o2 = bit; break;
    case 3: o3 = bit; break;
    case 4: o4 = bit; break;
    case 5: o5 = bit; break;
    case 6: o6 = bit; break;
    default: o7 = bit; break;
    }
}
#endif
