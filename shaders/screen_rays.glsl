// Rays through the screen or the voxels (voxgi__screen_cpu' GL twin, in float): ambient occlusion
// (u_gather 0: the occluded share) or one bounce from the screen's radiance (u_gather 1: pi / rays
// x the radiance met), at count points; the per-point rotation and jitter come from the CPU (the
// same random numbers), the rays from the Hammersley set.
// embedded unless VOXGI_NO_SCREEN_SPACE
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 0) readonly buffer Points { float points[]; };   // 3 per point
layout(std430, binding = 1) readonly buffer Normals { float normals[]; }; // 3 per point
layout(std430, binding = 2) writeonly buffer Out { float result[]; };     // 1 (occlusion) or 3 per point
layout(std430, binding = 3) readonly buffer Screen { float screen[]; };   // per pixel: position 3, normal 3, radiance 3
layout(std430, binding = 4) readonly buffer Random { float random[]; };   // 3 per point: rotation, jitter
layout(std430, binding = 5) writeonly buffer Hidden { float hidden[]; };  // u_hidden: 6 per point and ray, the voxel a hidden hit met, the ray
layout(location = VOXGI_LOC_u_count) uniform uint u_count;
layout(location = VOXGI_LOC_u_first) uniform uint u_first;
layout(location = VOXGI_LOC_u_origin) uniform vec3 u_origin;
layout(location = VOXGI_LOC_u_voxel_size) uniform float u_voxel_size;
layout(location = VOXGI_LOC_u_eye) uniform vec3 u_eye;
layout(location = VOXGI_LOC_u_forward) uniform vec3 u_forward;
layout(location = VOXGI_LOC_u_right) uniform vec3 u_right;
layout(location = VOXGI_LOC_u_up) uniform vec3 u_up;
layout(location = VOXGI_LOC_u_tan) uniform float u_tan_half;
layout(location = VOXGI_LOC_u_size) uniform ivec2 u_size;
layout(location = VOXGI_LOC_u_rays) uniform int u_rays;
layout(location = VOXGI_LOC_u_steps) uniform int u_steps;
layout(location = VOXGI_LOC_u_radius) uniform float u_radius;
layout(location = VOXGI_LOC_u_gather) uniform int u_gather;
layout(location = VOXGI_LOC_u_through_voxels) uniform int u_through_voxels;
layout(location = VOXGI_LOC_u_point_sampling) uniform int u_point_sampling;
layout(location = VOXGI_LOC_u_hidden) uniform int u_hidden;

const float PI = 3.14159265358979;

vec3 svec(uint pix, uint at) { return vec3(screen[9u * pix + at], screen[9u * pix + at + 1u], screen[9u * pix + at + 2u]); }
bool has_surface(uint pix) { return svec(pix, 3u) != vec3(0.0); }

// voxgi__screen_pixel: the pixel whose centre ray passes nearest to s, or false
bool screen_pixel(vec3 s, out uint pix, out float z)
{
    vec3 d = s - u_eye;
    pix = 0u;
    z = dot(d, u_forward);
    if (!(z > 0.0)) return false;
    float x = dot(d, u_right) / z, y = dot(d, u_up) / z;
    float sx = (x / (u_tan_half * float(u_size.x) / float(u_size.y)) + 1.0) * 0.5 * float(u_size.x);
    float sy = (1.0 - y / u_tan_half) * 0.5 * float(u_size.y);
    if (!(sx >= 0.0 && sx < float(u_size.x) && sy >= 0.0 && sy < float(u_size.y))) return false;
    pix = uint(sy) * uint(u_size.x) + uint(sx);
    return true;
}

// voxgi__screen_behind: s behind the surface of its pixel, that surface within the radius of p
bool behind(vec3 p, vec3 s, out uint hit)
{
    float z;
    uint at;
    hit = 0u;
    if (!screen_pixel(s, at, z) || !has_surface(at)) return false;
    vec3 q = svec(at, 0u), m = svec(at, 3u), v = s - u_eye;
    float nv = dot(m, v), nq = dot(m, q - u_eye);
    if (!(abs(nv) > 1e-9 * length(v))) return false;
    float f = nq / nv;
    vec3 e = u_eye + f * v - p;
    if (!(f > 0.0 && f < 1.0 - 1e-3 * u_radius / z && dot(e, e) < u_radius * u_radius)) return false;
    hit = at;
    return true;
}

// voxgi__screen_march
bool march(vec3 p, vec3 dir, float jitter, out uint hit)
{
    hit = 0u;
    for (int j = 0; j < u_steps; j++) {
        float tt = (float(j) + jitter) / float(u_steps) * u_radius;
        if (behind(p, p + tt * dir, hit)) return true;
    }
    return false;
}

// voxgi_radical_inverse(3, k)
float phi3(int k)
{
    float r = 0.0, f = 1.0 / 3.0;
    for (int i = k; i > 0; i /= 3) {
        r += float(i % 3) * f;
        f /= 3.0;
    }
    return r;
}

// voxgi__screen_voxels: met, and the pixel showing the entry point (0xFFFFFFFF: hidden or off screen);
// v: the voxel met
bool through_voxels(vec3 p, vec3 n, vec3 dir, out uint hit, out ivec3 v)
{
    float vs = u_voxel_size, enter = 0.0, z;
    vec3 o = (p + 1.5 * vs * n - u_origin) / vs, d = (p + u_radius * dir - u_origin) / vs - o;
    hit = 0xFFFFFFFFu;
    if (!occluded_at(o, d, v)) return false;
    if (u_gather == 0) return true;
    for (int a = 0; a < 3; a++)
        if (d[a] != 0.0) enter = max(enter, min((float(v[a]) - o[a]) / d[a], (float(v[a]) + 1.0 - o[a]) / d[a]));
    vec3 x = u_origin + (o + enter * d) * vs;
    uint at;
    if (!screen_pixel(x, at, z) || !has_surface(at)) return true;
    if (abs(dot(svec(at, 3u), svec(at, 0u) - x)) <= 2.0 * vs) hit = at;
    return true;
}

void main()
{
    uint i = gl_GlobalInvocationID.x + u_first;
    if (gl_GlobalInvocationID.x >= u_count) return;
    vec3 p = vec3(points[3u * i], points[3u * i + 1u], points[3u * i + 2u]);
    vec3 n = vec3(normals[3u * i], normals[3u * i + 1u], normals[3u * i + 2u]);
    vec3 e = vec3(0.0);
    int blocked = 0;
    for (int k = 0; u_hidden != 0 && k < u_rays; k++) hidden[6u * (i * uint(u_rays) + uint(k))] = uintBitsToFloat(0x7FC00000u);
    if (n != vec3(0.0)) {
        vec2 rot = vec2(random[3u * i], random[3u * i + 1u]);
        float jitter = random[3u * i + 2u];
        // voxgi__basis
        float sgn = n.z >= 0.0 ? 1.0 : -1.0, a0 = -1.0 / (sgn + n.z), c0 = n.x * n.y * a0;
        vec3 t = vec3(1.0 + sgn * n.x * n.x * a0, sgn * c0, -sgn * n.x), b = vec3(c0, sgn + n.y * n.y * a0, -n.y);
        for (int k = 0; k < u_rays; k++) {
            vec2 u = fract(vec2(float(k) / float(u_rays), float(bitfieldReverse(uint(k))) * 2.3283064365386963e-10) + rot);
            float r = sqrt(u.x), phi = 2.0 * PI * u.y;
            vec3 dir = r * cos(phi) * t + r * sin(phi) * b + sqrt(max(0.0, 1.0 - u.x)) * n;
            uint hit;
            ivec3 v = ivec3(0);
            bool met;
            if (u_point_sampling != 0) met = behind(p, p + fract(phi3(k) + jitter) * u_radius * dir, hit); // one point along the ray
            else met = u_through_voxels != 0 ? through_voxels(p, n, dir, hit, v) : march(p, dir, jitter, hit);
            if (met) blocked++;
            if (met && u_gather != 0 && hit != 0xFFFFFFFFu) e += svec(hit, 6u);
            if (met && u_hidden != 0 && hit == 0xFFFFFFFFu)
                for (int a = 0; a < 3; a++) {
                    hidden[6u * (i * uint(u_rays) + uint(k)) + uint(a)] = float(v[a]) + 0.5;
                    hidden[6u * (i * uint(u_rays) + uint(k)) + 3u + uint(a)] = dir[a];
                }
        }
    }
    if (u_gather != 0) {
        result[3u * i] = PI * e.x / float(u_rays);
        result[3u * i + 1u] = PI * e.y / float(u_rays);
        result[3u * i + 2u] = PI * e.z / float(u_rays);
    } else
        result[i] = float(blocked) / float(u_rays);
}
