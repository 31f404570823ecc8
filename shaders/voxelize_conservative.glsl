// Exact conservative (and thin) voxelization by compute, after scene.glsl, triangle.glsl and
// conservative.glsl. One invocation per triangle (pass 0); triangles with many columns are
// listed and split over rows and column chunks by pass 1, so one huge triangle is spread over
// thousands of invocations.
layout(local_size_x = VOXGI_LOCAL_SIZE) in;

void main()
{
    int single;
    if (u_pass == 0) {
        uint t = u_tri_offset + gl_GlobalInvocationID.x;
        if (t >= u_tri_count) return;
        if (u_attr != 0 && (tri_flags[t >> 5] & (1u << (t & 31u))) != 0u) return; // the CPU does all of it
        int c = prepare(t, single);
        if (c < 0) return;
        int a = (c + 1) % 3, b = (c + 2) % 3;
        if (listed_as_big(t, a, b)) return;
        for (int rb = 0; rb < ext[b]; rb++) {
            ivec2 span = sig[c] != 0 ? row_span(c, rb) : ivec2(0, ext[a] - 1);
            do_columns(c, single, rb, span.x, span.y);
        }
    } else {
        uint lanes = gl_NumWorkGroups.y * gl_WorkGroupSize.x;
        uint lane = gl_WorkGroupID.y * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
        for (uint bi = gl_WorkGroupID.x; bi < big_count; bi += gl_NumWorkGroups.x) {
            if (!lane_has_work(big_list[bi], lane)) continue;
            int c = prepare(big_list[bi], single);
            int a = (c + 1) % 3, b = (c + 2) % 3;
            int chunks = (ext[a] + CHUNK - 1) / CHUNK;
            uint items = uint(ext[b] * chunks);
            for (uint item = lane; item < items; item += lanes) {
                int rb = int(item) / chunks, ch = int(item) % chunks;
                ivec2 span = sig[c] != 0 ? row_span(c, rb) : ivec2(0, ext[a] - 1);
                do_columns(c, single, rb, max(span.x, ch * CHUNK), min(span.y, ch * CHUNK + CHUNK - 1));
            }
        }
    }
}
