// The sparse voxel octree on the GPU (voxgi.h, part "sparse voxel octree"): its buffers, value
// formats, descent, point fetch and sampling, shared by the build passes (svo_build.glsl) and
// the lighting passes. The layout is the CPU octree's byte for byte: svo_child[slot] = 1 + the
// index of the slot's child tile (0: none); inner tile t holds slots 1 + 8t .. 8 + 8t, leaf tile t
// the leaf slots 8t .. 7 + 8t; values per slot RGBA32F / R32F (u_svo_format 0) or RGBA16F / R16F
// (1, two halves per word, the first in the low bits), (value, alpha), opacity alpha alone; an
// attribute's node values, then from word u_svo_leaf_first on its leaf values, in one buffer.
// Cone tracing (VOXGI_CONE_SVO) also reads a two-sided octree's back and side, laid out alike.
// embedded unless VOXGI_NO_OCTREE
layout(std430, binding = VOXGI_BINDING_SVO_CHILD) buffer SvoChild { uint svo_child[]; };
layout(std430, binding = VOXGI_BINDING_SVO_VALUES) buffer SvoValues { uint svo_words[]; };
#ifdef VOXGI_CONE_SVO
layout(std430, binding = VOXGI_BINDING_SVO_BACK_VALUES) readonly buffer SvoBackValues { uint svo_back_words[]; };
layout(std430, binding = VOXGI_BINDING_SVO_SIDE_VALUES) readonly buffer SvoSideValues { uint svo_side_words[]; };
#endif
layout(location = VOXGI_LOC_u_svo_leaf_first) uniform uint u_svo_leaf_first;
layout(location = VOXGI_LOC_u_svo_depth) uniform int u_svo_depth;   // leaves at level depth
layout(location = VOXGI_LOC_u_svo_format) uniform int u_svo_format;  // 0: float32, 1: float16
layout(location = VOXGI_LOC_u_svo_single) uniform int u_svo_single;  // 1: the attribute is opacity (alpha alone)
layout(location = VOXGI_LOC_u_svo_bricks) uniform int u_svo_bricks;  // 1: every inner node has a brick (4x4x4 values of its children's level)
layout(location = VOXGI_LOC_u_svo_nodes) uniform uint u_svo_nodes;  // node slots; brick b's texels follow them at u_svo_nodes + 64 b
layout(location = VOXGI_LOC_u_svo_inner_tiles) uniform uint u_svo_inner_tiles; // bricks of nodes with inner tiles come first, then those with leaf tiles

// float -> half, nearest, ties to even; integer steps as voxgi__half_from_float.
uint voxgi_half_from_float(float f)
{
    uint x = floatBitsToUint(f), sign = (x >> 16) & 0x8000u, ax = x & 0x7FFFFFFFu;
    if (ax >= 0x47800000u) return sign | 0x7C00u;
    if (ax < 0x38800000u) {
        float v = abs(f) * 16777216.0;
        uint h = uint(v);
        float frac = v - float(h);
        if (frac > 0.5 || (frac == 0.5 && (h & 1u) != 0u)) h += 1u;
        return sign | h;
    }
    ax += 0x0FFFu + ((ax >> 13) & 1u);
    return sign | min((ax >> 13) - (112u << 10), 0x7C00u);
}

float voxgi_float_from_half(uint h)
{
    return unpackHalf2x16(h & 0xFFFFu).x; // exact
}

#define VOXGI_SVO_BOUND 0 // the attribute bound (SvoValues)
#define VOXGI_SVO_BACK 1
#define VOXGI_SVO_SIDE 2

// Word i of the node (or leaf) values of the bound attribute, or of the back's or the side's.
uint voxgi_svo_word(int attr, bool leaf, uint i)
{
    uint at = (leaf ? u_svo_leaf_first : 0u) + i;
#ifdef VOXGI_CONE_SVO
    if (attr == VOXGI_SVO_BACK) return svo_back_words[at];
    if (attr == VOXGI_SVO_SIDE) return svo_side_words[at];
#endif
    return svo_words[at];
}

// A slot's value as (value, alpha), of attr.
vec4 voxgi_svo_load_of(int attr, bool leaf, uint slot)
{
    if (u_svo_format == 0) {
        if (u_svo_single != 0) return vec4(0.0, 0.0, 0.0, uintBitsToFloat(voxgi_svo_word(attr, leaf, slot)));
        return uintBitsToFloat(uvec4(voxgi_svo_word(attr, leaf, 4u * slot), voxgi_svo_word(attr, leaf, 4u * slot + 1u),
                                     voxgi_svo_word(attr, leaf, 4u * slot + 2u), voxgi_svo_word(attr, leaf, 4u * slot + 3u)));
    }
    if (u_svo_single != 0) return vec4(0.0, 0.0, 0.0, voxgi_float_from_half(voxgi_svo_word(attr, leaf, slot >> 1) >> (16u * (slot & 1u))));
    uint lo = voxgi_svo_word(attr, leaf, 2u * slot), hi = voxgi_svo_word(attr, leaf, 2u * slot + 1u);
    return vec4(voxgi_float_from_half(lo), voxgi_float_from_half(lo >> 16), voxgi_float_from_half(hi), voxgi_float_from_half(hi >> 16));
}

// A slot's value of the bound attribute.
vec4 voxgi_svo_load(bool leaf, uint slot)
{
    return voxgi_svo_load_of(VOXGI_SVO_BOUND, leaf, slot);
}

// The slot of the node at `level` (0 = the root) holding v (in level-`level` coordinates);
// false where there is none. leaf: the slot is a leaf slot (level == depth).
bool voxgi_svo_descend(int level, ivec3 v, out uint slot, out bool leaf)
{
    slot = 0u;
    leaf = false;
    if (any(lessThan(v, ivec3(0))) || any(greaterThanEqual(v, ivec3(1 << level)))) return false;
    bool found = true;
    for (int m = 1; m <= level && found; m++) {
        uint ptr = svo_child[slot];
        found = ptr != 0u;
        if (found) {
            ivec3 b = (v >> (level - m)) & 1;
            leaf = m == u_svo_depth;
            slot = (leaf ? 0u : 1u) + 8u * (ptr - 1u) + uint(b.x | (b.y << 1) | (b.z << 2));
        }
    }
    return found;
}

// The stored value of the node at `level` holding v; zero where there is none.
vec4 voxgi_svo_fetch(int level, ivec3 v)
{
    uint slot;
    bool leaf;
    return voxgi_svo_descend(level, v, slot, leaf) ? voxgi_svo_load(leaf, slot) : vec4(0.0);
}

// Trilinear at mip level k from one descent and the brick of the node around p one level up;
// where an ancestor is missing and the sample's corners all lie in its box, empty; false where
// the lookups must do it (voxgi__svo_brick_trilinear on the CPU).
bool voxgi_svo_brick_trilinear(int k, vec3 p, out vec4 s)
{
    int lev = u_svo_depth - k - 1;
    s = vec4(0.0);
    if (u_svo_bricks == 0 || lev < 0) return false;
    vec3 c = p / float(1 << k) - 0.5, f = c - floor(c);
    ivec3 i0 = ivec3(floor(c)), pc = ivec3(floor(p / float(1 << (k + 1))));
    if (any(lessThan(pc, ivec3(0))) || any(greaterThanEqual(pc, ivec3(1 << lev)))) return false;
    uint node = 0u, ptr = 0u;
    for (int m = 0; m <= lev; m++) {
        ptr = svo_child[node];
        if (ptr == 0u) {
            int sh = lev + 1 - m;
            ivec3 lo = (pc >> (lev - m)) << sh, hi = ((pc >> (lev - m)) + 1) << sh;
            return all(greaterThanEqual(i0, lo)) && all(lessThan(i0 + 1, hi));
        }
        if (m < lev) {
            ivec3 b = (pc >> (lev - m - 1)) & 1;
            node = 1u + 8u * (ptr - 1u) + uint(b.x | (b.y << 1) | (b.z << 2));
        }
    }
    uint first = u_svo_nodes + 64u * ((lev < u_svo_depth - 1 ? 0u : u_svo_inner_tiles) + ptr - 1u);
    ivec3 t0 = i0 - (2 * pc - 1);
    for (int corner = 0; corner < 8; corner++) {
        ivec3 hi = ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1), t = t0 + hi;
        vec3 w3 = mix(1.0 - f, f, vec3(hi));
        float w = w3.x * w3.y * w3.z;
        if (w != 0.0) s += w * voxgi_svo_load(false, first + uint(t.x + 4 * t.y + 16 * t.z));
    }
    return true;
}

// Trilinear between the node centres of mip level k (octree level depth - k) at p (grid units of
// the voxels), as voxgi__trilinear on the CPU.
vec4 voxgi_svo_trilinear(int k, vec3 p)
{
    vec4 s;
    if (voxgi_svo_brick_trilinear(k, p, s)) return s;
    vec3 c = p / float(1 << k) - 0.5, f = c - floor(c);
    ivec3 i0 = ivec3(floor(c));
    for (int corner = 0; corner < 8; corner++) {
        ivec3 hi = ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        vec3 w3 = mix(1.0 - f, f, vec3(hi));
        float w = w3.x * w3.y * w3.z;
        if (w != 0.0) s += w * voxgi_svo_fetch(u_svo_depth - k, i0 + hi);
    }
    return s;
}

// The octree's sample at p (grid units) and lod (0 = the voxels, depth = the root; fractional:
// linear between levels), as voxgi_svo_sample on the CPU.
vec4 voxgi_sample_svo(vec3 p, float lod)
{
    float l = clamp(lod, 0.0, float(u_svo_depth)), t = l - floor(l);
    int k0 = int(floor(l));
    vec4 s0 = voxgi_svo_trilinear(k0, p);
    return t > 0.0 ? s0 + t * (voxgi_svo_trilinear(k0 + 1, p) - s0) : s0;
}
