// The edge-aware blur and upsampling (voxgi__filter_cpu's GL twin, in
// float): u_pass 0, one invocation per element of the row pass (full column, input row); u_pass 1,
// one per full-resolution pixel, down the row pass's columns.
// embedded unless VOXGI_NO_SCREEN_SPACE
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 0) readonly buffer Screen { float screen[]; };  // per pixel: position 3, normal 3
layout(std430, binding = 1) readonly buffer Values { float values[]; };  // u_channels per input pixel
layout(std430, binding = 2) buffer Mid { float mid[]; };                 // u_channels + 1 (the weights' sum) per element
layout(std430, binding = 3) writeonly buffer Out { float result[]; };    // u_channels per pixel
layout(std430, binding = 4) writeonly buffer Flags { uint unsupported[]; };
layout(location = VOXGI_LOC_u_count) uniform uint u_count;
layout(location = VOXGI_LOC_u_first) uniform uint u_first;
layout(location = VOXGI_LOC_u_eye) uniform vec3 u_eye;
layout(location = VOXGI_LOC_u_size) uniform ivec2 u_size;       // full resolution
layout(location = VOXGI_LOC_u_src_dims) uniform ivec2 u_src;    // the input's
layout(location = VOXGI_LOC_u_factor) uniform int u_scale;
layout(location = VOXGI_LOC_u_radius) uniform int u_window;
layout(location = VOXGI_LOC_u_channels) uniform int u_channels;
layout(location = VOXGI_LOC_u_step) uniform float u_pixel_width;
layout(location = VOXGI_LOC_u_inv_s) uniform float u_inv_two_sigma2;
layout(location = VOXGI_LOC_u_pass) uniform int u_pass;

vec3 position(uint pix) { return vec3(screen[6u * pix], screen[6u * pix + 1u], screen[6u * pix + 2u]); }
vec3 normal(uint pix) { return vec3(screen[6u * pix + 3u], screen[6u * pix + 4u], screen[6u * pix + 5u]); }
bool has_surface(uint pix) { return normal(pix) != vec3(0.0); }

// voxgi__filter_weight
float weight(uint c, uint s, int d)
{
    vec3 n = normal(c), p = position(c);
    float dn = dot(n, normal(s)), dp = dot(position(s) - p, n);
    if (!(dn > 0.0)) return 0.0;
    float dn2 = dn * dn, t = 2.0 * u_pixel_width * length(p - u_eye);
    return dn2 * dn2 * dn2 * dn2 * exp(-float(d * d) * u_inv_two_sigma2 - (t > 0.0 ? dp * dp / (t * t) : 0.0));
}

void main()
{
    uint i = gl_GlobalInvocationID.x + u_first;
    if (gl_GlobalInvocationID.x >= u_count) return;
    int w = u_size.x, x = int(i % uint(w)), row = int(i / uint(w));
    uint ch = uint(u_channels);
    float sum = 0.0;
    vec4 v = vec4(0.0);
    if (u_pass == 0) {
        uint c = uint(row * u_scale * w + x);
        if (has_surface(c))
            for (int X = max(0, (x - u_window + u_scale - 1) / u_scale); X < u_src.x && X * u_scale <= x + u_window; X++) {
                uint s = uint(row * u_scale * w + X * u_scale);
                if (!has_surface(s)) continue;
                float wt = weight(c, s, X * u_scale - x);
                if (wt <= 0.0) continue;
                sum += wt;
                for (uint k = 0u; k < ch; k++) v[k] += wt * values[uint(row * u_src.x + X) * ch + k];
            }
        for (uint k = 0u; k < ch; k++) mid[i * (ch + 1u) + k] = sum >= 1e-3 ? v[k] / sum : 0.0;
        mid[i * (ch + 1u) + ch] = sum >= 1e-3 ? sum : 0.0;
        return;
    }
    bool surface = has_surface(i);
    if (surface)
        for (int Y = max(0, (row - u_window + u_scale - 1) / u_scale); Y < u_src.y && Y * u_scale <= row + u_window; Y++) {
            uint m = uint(Y * w + x) * (ch + 1u);
            if (mid[m + ch] <= 0.0) continue;
            float wt = weight(i, uint(Y * u_scale * w + x), Y * u_scale - row);
            if (wt <= 0.0) continue;
            sum += wt;
            for (uint k = 0u; k < ch; k++) v[k] += wt * mid[m + k];
        }
    for (uint k = 0u; k < ch; k++) result[i * ch + k] = sum >= 1e-3 ? v[k] / sum : 0.0;
    unsupported[i] = surface && sum < 1e-3 ? 1u : 0u;
}
