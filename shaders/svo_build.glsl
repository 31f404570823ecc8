// Building the sparse voxel octree on the GPU (voxgi.h, part "sparse voxel octree"), after
// Crassin & Green: level by level the voxel fragments flag the nodes they fall in, the flagged
// nodes get their child tiles (allocate) and the new tiles are cleared (initialise); the
// allocate and initialise passes are sized on the GPU (indirect dispatch). Then the fragments
// write the leaf values and each level's nodes, bottom up, the isotropic mip of their tile.
// Every node with a tile is in the node list (slot, coordinates at its level), level by level.
// embedded unless VOXGI_NO_OCTREE
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 3) readonly buffer Fragments { uvec2 fragments[]; };  // x | y << 16, z
layout(std430, binding = 4) buffer NodeList { uvec4 node_list[]; };           // slot, x, y, z
layout(std430, binding = 5) buffer Counters { uint counters[]; };
layout(std430, binding = 6) buffer Neighbours { uint svo_neighbour[]; };
layout(std430, binding = 7) readonly buffer FragmentValues { vec4 fragment_values[]; };
layout(location = VOXGI_LOC_u_pass) uniform int u_pass;
layout(location = VOXGI_LOC_u_premultiplied) uniform int u_premultiplied; // mip: the values are stored premultiplied by alpha (RADIANCE): their plain mean
layout(location = VOXGI_LOC_u_level) uniform int u_level;   // the level being built (flag, allocate), mipped or linked
layout(location = VOXGI_LOC_u_count) uniform uint u_count;  // items of a directly sized pass
layout(location = VOXGI_LOC_u_first) uniform uint u_first;  // its first node list entry

#define VOXGI_PASS_FLAG 0
#define VOXGI_PASS_ARGS 1
#define VOXGI_PASS_ALLOCATE 2
#define VOXGI_PASS_INIT 3
#define VOXGI_PASS_LEAVES 4
#define VOXGI_PASS_MIP 5
#define VOXGI_PASS_NEIGHBOURS 6
#define VOXGI_PASS_BRICKS 7
// counters: [0] inner tiles, [1] leaf tiles, [2] nodes flagged at this level, [3] node list
// entries, [4..6] allocate dispatch, [8..10] initialise dispatch, [12] the parents' first
// entry, [13] the first entry of the next level's parents, [14] the first new inner tile,
// [15] the flagged nodes being allocated
#define VOXGI_FLAG 0xFFFFFFFFu

ivec3 voxgi_fragment(uint i)
{
    uvec2 f = fragments[i];
    return ivec3(int(f.x & 0xFFFFu), int(f.x >> 16), int(f.y));
}

void voxgi_svo_store(bool leaf, uint slot, vec4 c)
{
    uint base = leaf ? u_svo_leaf_first : 0u;
    if (u_svo_format == 0) {
        if (u_svo_single != 0) {
            svo_words[base + slot] = floatBitsToUint(c.a);
            return;
        }
        uvec4 u = floatBitsToUint(c);
        for (uint k = 0u; k < 4u; k++) svo_words[base + 4u * slot + k] = u[k];
        return;
    }
    if (u_svo_single != 0) { // two slots share a word: or into the cleared word
        atomicOr(svo_words[base + (slot >> 1)], voxgi_half_from_float(c.a) << (16u * (slot & 1u)));
        return;
    }
    svo_words[base + 2u * slot] = voxgi_half_from_float(c.r) | (voxgi_half_from_float(c.g) << 16);
    svo_words[base + 2u * slot + 1u] = voxgi_half_from_float(c.b) | (voxgi_half_from_float(c.a) << 16);
}

void main()
{
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    if (u_pass == VOXGI_PASS_ARGS) { // one invocation: the next passes' sizes
        if (i != 0u) return;
        uint start = counters[13], end = counters[3];
        counters[12] = start;
        counters[13] = end;
        counters[14] = counters[0];
        counters[15] = counters[2];
        counters[2] = 0u;
        uint allocate = (8u * (end - start) + uint(VOXGI_LOCAL_SIZE) - 1u) / uint(VOXGI_LOCAL_SIZE);
        uint init = u_level < u_svo_depth - 1 ? (8u * counters[15] + uint(VOXGI_LOCAL_SIZE) - 1u) / uint(VOXGI_LOCAL_SIZE) : 0u;
        counters[4] = min(allocate, 65535u); // rows of at most 65535 work groups
        counters[5] = (allocate + 65534u) / 65535u;
        counters[8] = min(init, 65535u);
        counters[9] = (init + 65534u) / 65535u;
        counters[6] = counters[10] = 1u;
        return;
    }
    if (u_pass == VOXGI_PASS_FLAG) { // per fragment: its node at u_level
        if (i >= u_count) return;
        uint slot;
        bool leaf;
        if (voxgi_svo_descend(u_level, voxgi_fragment(i) >> (u_svo_depth - u_level), slot, leaf) &&
            atomicCompSwap(svo_child[slot], 0u, VOXGI_FLAG) == 0u)
            atomicAdd(counters[2], 1u);
        return;
    }
    if (u_pass == VOXGI_PASS_ALLOCATE) { // per slot of the parents' tiles: a flagged node gets its tile
        uint start = counters[12];
        if (i >= 8u * (counters[13] - start)) return;
        uvec4 parent = node_list[start + i / 8u];
        uint digit = i & 7u, slot = 1u + 8u * (svo_child[parent.x] - 1u) + digit;
        if (svo_child[slot] != VOXGI_FLAG) return;
        svo_child[slot] = 1u + atomicAdd(counters[u_level < u_svo_depth - 1 ? 0 : 1], 1u);
        node_list[atomicAdd(counters[3], 1u)] = uvec4(slot, 2u * parent.yzw + uvec3(digit & 1u, (digit >> 1) & 1u, digit >> 2));
        return;
    }
    if (u_pass == VOXGI_PASS_INIT) { // per slot of the new inner tiles: no children yet
        if (i >= 8u * counters[15]) return;
        svo_child[1u + 8u * counters[14] + i] = 0u;
        return;
    }
    if (u_pass == VOXGI_PASS_LEAVES) { // per fragment: its value into its leaf slot
        if (i >= u_count) return;
        uint slot;
        bool leaf;
        if (voxgi_svo_descend(u_svo_depth, voxgi_fragment(i), slot, leaf)) voxgi_svo_store(true, slot, fragment_values[i]);
        return;
    }
    if (i >= u_count) return;
    if (u_pass == VOXGI_PASS_BRICKS) { // per texel of the bricks of u_level's nodes: the value one level down
        uvec4 owner = node_list[u_first + i / 64u];
        uint t = i & 63u, brick = (u_level < u_svo_depth - 1 ? 0u : u_svo_inner_tiles) + svo_child[owner.x] - 1u;
        ivec3 q = 2 * ivec3(owner.yzw) - 1 + ivec3(t & 3u, (t >> 2) & 3u, t >> 4);
        voxgi_svo_store(false, u_svo_nodes + 64u * brick + t, voxgi_svo_fetch(u_level + 1, q));
        return;
    }
    uvec4 node = node_list[u_first + i];
    if (u_pass == VOXGI_PASS_MIP) { // per node of u_level: the isotropic mip of its tile (voxgi__mip_combine)
        bool leaves = u_level == u_svo_depth - 1;
        uint tile = svo_child[node.x] - 1u;
        precise float asum = 0.0;
        precise vec3 vsum = vec3(0.0);
        for (uint k = 0u; k < 8u; k++) {
            vec4 c = voxgi_svo_load(leaves, (leaves ? 0u : 1u) + 8u * tile + k);
            asum += c.a;
            vsum += u_premultiplied != 0 ? c.rgb : c.rgb * c.a;
        }
        if (u_premultiplied != 0) voxgi_svo_store(false, node.x, vec4(vsum / 8.0, asum / 8.0));
        else voxgi_svo_store(false, node.x, vec4(asum > 0.0 ? vsum / asum : vec3(0.0), asum / 8.0));
        return;
    }
    if (u_pass == VOXGI_PASS_NEIGHBOURS) { // per node of u_level: the slots one step away, 0 = none
        for (int dir = 0; dir < 6; dir++) {
            ivec3 c = ivec3(node.yzw);
            c[dir / 2] += (dir & 1) != 0 ? -1 : 1;
            uint slot;
            bool leaf;
            svo_neighbour[6u * node.x + uint(dir)] = voxgi_svo_descend(u_level, c, slot, leaf) && svo_child[slot] != 0u ? slot : 0u;
        }
    }
}
