// An area light's shadow rays through the line space (voxgi__ls_light_cpu's GL twin; the walk is
// linespace.glsl's): per point the light's samples [u_samples.x, u_samples.y), their sums added to
// the point's. The weights alone are float, not the CPU's double: they may differ in the last bits.
// embedded unless VOXGI_NO_LINE_SPACE
layout(std430, binding = 5) readonly buffer Points { float points[]; };   // 3 per point of this slice
layout(std430, binding = 6) readonly buffer Normals { float normals[]; }; // 3 per point of this slice
struct Sum { uint seen, rays; float weight, weight_seen; };               // samples not blocked, rays traced, their weights
layout(std430, binding = 7) buffer Sums { Sum sums[]; };                  // 1 per point of this slice
layout(location = VOXGI_LOC_u_first) uniform uint u_first;     // the slice's first point in the call (the samples' hash)
layout(location = VOXGI_LOC_u_hair) uniform float u_hair;      // the rays' offset along the normal
layout(location = VOXGI_LOC_u_corner) uniform vec3 u_corner;       // the light's corner, relative to u_centre
layout(location = VOXGI_LOC_u_edge_u) uniform vec3 u_edge_u;
layout(location = VOXGI_LOC_u_edge_v) uniform vec3 u_edge_v;
layout(location = VOXGI_LOC_u_light_normal) uniform vec3 u_light_normal; // unit, the side the light shines to
layout(location = VOXGI_LOC_u_triangle) uniform int u_triangle;
layout(location = VOXGI_LOC_u_seed) uniform uint u_seed;
layout(location = VOXGI_LOC_u_cells) uniform ivec2 u_cells;     // nu x nv
layout(location = VOXGI_LOC_u_samples) uniform ivec2 u_samples; // this pass's samples [x, y)

// voxgi__ls_hash
uint hash(uint x)
{
    x = x * 747796405u + 2891336453u;
    x = ((x >> ((x >> 28u) + 4u)) ^ x) * 277803737u;
    return (x >> 22u) ^ x;
}

// voxgi__ls_light_st: sample k of the point, as s and t along the light's edges
void light_st(uint point, int k, out float s, out float t)
{
    uint h1 = hash(u_seed ^ hash(point ^ hash(uint(k)))), h2 = hash(h1);
    precise float ks = float(k % u_cells.x) + float(h1 >> 8u) * (1.0 / 16777216.0), kt = float(k / u_cells.x) + float(h2 >> 8u) * (1.0 / 16777216.0);
    s = quot(ks, float(u_cells.x));
    t = quot(kt, float(u_cells.y));
    if (u_triangle != 0 && s + t > 1.0) { s = 1.0 - s; t = 1.0 - t; }
}

void main()
{
    if (gl_GlobalInvocationID.x >= u_count) return;
    uint i = gl_GlobalInvocationID.x;
    vec3 p = vec3(points[3u * i], points[3u * i + 1u], points[3u * i + 2u]), nrm = vec3(normals[3u * i], normals[3u * i + 1u], normals[3u * i + 2u]);
    Sum sum = u_samples.x == 0 ? Sum(0u, 0u, 0.0, 0.0) : sums[i];
    precise vec3 o;
    float lift = max(u_hair, max(abs(p.x), max(abs(p.y), abs(p.z))) * 9.5367431640625e-7); // voxgi__ls_lift
    for (int a = 0; a < 3; a++) o[a] = float(double(p[a]) - u_centre[a]) + lift * nrm[a];
    for (int k = u_samples.x; k < u_samples.y; k++) { // voxgi__ls_light_ray, then the ray alone
        float s, t;
        light_st(u_first + i, k, s, t);
        precise vec3 d;
        for (int a = 0; a < 3; a++) {
            precise float q = (u_corner[a] + s * u_edge_u[a]) + t * u_edge_v[a];
            d[a] = q - o[a];
        }
        precise float cos_p = (nrm.x * d.x + nrm.y * d.y) + nrm.z * d.z;
        if (!(cos_p > 0.0) || !ray_set_centred(o, d, 0.0, 1.0 - 1.52587890625e-5)) continue;
        float len2 = dot(d, d), cos_l = -dot(u_light_normal, d), w = cos_l > 0.0 ? (cos_p / len2) * (cos_l / len2) : 0.0;
        sum.rays++;
        sum.weight += w;
        if (!trace(u_fast != 0)) {
            sum.seen++;
            sum.weight_seen += w;
        }
    }
    sums[i] = sum;
}
