// Transmittance shadow map lookups (voxgi__tsm_point's GL twin): one invocation per point, in
// double in the CPU's order of operations (precise: no fused multiply-adds), the layers'
// transmittance a product of (1 - sigma) as on the CPU, so the answers are the same bit for bit
// where the GL's doubles round as IEEE's do (llvmpipe).
// embedded unless VOXGI_NO_LIGHT_SPACE
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 0) readonly buffer Points { float points[]; };   // 3 per point
layout(std430, binding = 1) readonly buffer Normals { float normals[]; }; // 3 per point, when P[25] != 0
layout(std430, binding = 2) readonly buffer Columns { uint columns[]; };  // per material, per texel, P[23] words
layout(std430, binding = 3) readonly buffer Opaque { float opaque[]; };   // per texel
// P: u 0-2, v 3-5, w 6-8, lo 9-11, texel 12, slice 13, eye 14-16, tan_half 17, near 18, far 19,
// size 20, slices 21, perspective 22, words 23, materials 24, normals given 25, sigma 26-33
layout(std430, binding = 4) readonly buffer Params { double P[]; };
layout(std430, binding = 5) writeonly buffer Light { float light_out[]; };
layout(location = VOXGI_LOC_u_count) uniform uint u_count;

dvec3 pvec(int at) { return dvec3(P[at], P[at + 1], P[at + 2]); }

// voxgi__tsm_frame
dvec3 frame(dvec3 x)
{
    dvec3 u = pvec(0), v = pvec(3), w = pvec(6);
    precise dvec3 o;
    if (P[22] != 0.0LF) {
        dvec3 eye = pvec(14);
        precise dvec3 r = x - eye;
        precise double z = max(r.x * w.x + r.y * w.y + r.z * w.z, P[18]);
        precise double ru = r.x * u.x + r.y * u.y + r.z * u.z, rv = r.x * v.x + r.y * v.y + r.z * v.z;
        o.x = 0.5LF * P[20] * (1.0LF + ru / (z * P[17]));
        o.y = 0.5LF * P[20] * (1.0LF + rv / (z * P[17]));
        o.z = P[21] * (1.0LF / P[18] - 1.0LF / z) / (1.0LF / P[18] - 1.0LF / P[19]);
        return o;
    }
    precise double xu = x.x * u.x + x.y * u.y + x.z * u.z, xv = x.x * v.x + x.y * v.y + x.z * v.z, xw = x.x * w.x + x.y * w.y + x.z * w.z;
    o.x = (xu - P[9]) / P[12];
    o.y = (xv - P[10]) / P[12];
    o.z = (xw - P[11]) / P[13];
    return o;
}

void main()
{
    uint at = gl_GlobalInvocationID.x;
    if (at >= u_count) return;
    precise dvec3 x = dvec3(points[3u * at], points[3u * at + 1u], points[3u * at + 2u]);
    dvec3 n = P[25] != 0.0LF ? dvec3(normals[3u * at], normals[3u * at + 1u], normals[3u * at + 2u]) : dvec3(0.0LF);
    dvec3 w = pvec(6);
    precise double bias = 0.0LF;
    if (P[22] != 0.0LF) {
        dvec3 eye = pvec(14);
        precise dvec3 r = x - eye;
        precise double z = r.x * w.x + r.y * w.y + r.z * w.z;
        if (!(z > P[18])) { light_out[at] = 1.0; return; }
        if (P[25] != 0.0LF) {
            precise double texel = 2.0LF * z * P[17] / P[20], along = n.x * r.x + n.y * r.y + n.z * r.z;
            precise double step = (along > 0.0LF ? -1.0LF : 1.0LF) * 1.5LF * texel;
            x = x + step * n;
            bias = 0.5LF * texel * P[21] / (z * z * (1.0LF / P[18] - 1.0LF / P[19]));
        }
    } else if (P[25] != 0.0LF) {
        precise double facing = n.x * w.x + n.y * w.y + n.z * w.z;
        precise double step = (facing > 0.0LF ? -1.0LF : 1.0LF) * 1.5LF * P[12];
        x = x + step * n;
        bias = 0.5LF * P[12] / P[13];
    }
    precise dvec3 p = frame(x);
    if (!(p.x >= 0.0LF && p.x < P[20] && p.y >= 0.0LF && p.y < P[20])) { light_out[at] = 1.0; return; }
    int size = int(P[20]), slices = int(P[21]), words = int(P[23]), materials = int(P[24]);
    uint texel = uint(int(p.y)) * uint(size) + uint(int(p.x));
    if (double(opaque[texel]) < p.z - bias) { light_out[at] = 0.0; return; }
    int k = p.z <= 0.0LF ? 0 : (p.z >= double(slices) ? slices : int(p.z)); // the slices before the point's own
    precise double light = 1.0LF;
    uint texels = uint(size) * uint(size);
    for (int g = 0; g < materials; g++) {
        uint col = (uint(g) * texels + texel) * uint(words);
        int layers = 0;
        for (int wd = 0; wd < (k >> 5); wd++) layers += bitCount(columns[col + uint(wd)]);
        if ((k & 31) != 0) layers += bitCount(columns[col + uint(k >> 5)] & ((1u << uint(k & 31)) - 1u));
        precise double pass = 1.0LF - P[26 + g];
        for (int l = 0; l < layers; l++) light *= pass;
    }
    light_out[at] = float(light);
}
