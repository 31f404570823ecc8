// Light injection on GL (after light_maps.glsl): the irradiance at each voxel's lookup point
// (its centre moved off its surface, relative to the grid origin) on its unit normal, from every
// caster, each seen through its distance map: lit where the nearest surface in the point's own
// texel is not nearer than the point, less u_bias and half a texel's width for slopes (a filter
// over neighbouring texels would see past the foot of a wall that shadows a point beside it).
// voxgi__inject_range is the CPU's twin with exact shadow rays.
// embedded unless VOXGI_NO_LIGHT_INJECTION
layout(local_size_x = VOXGI_LOCAL_SIZE) in;
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };   // 2 per voxel: lookup point, unit normal (w = 0: none)
layout(std430, binding = 1) readonly buffer Casters { Caster casters[]; };
layout(std430, binding = 2) writeonly buffer Irradiance { vec4 irradiance[]; };
layout(binding = 0, r32ui) uniform readonly uimage2DArray u_maps;
layout(location = VOXGI_LOC_u_count) uniform uint u_count;
layout(location = VOXGI_LOC_u_casters) uniform int u_casters;
layout(location = VOXGI_LOC_u_size) uniform int u_size;      // texels per map side
layout(location = VOXGI_LOC_u_bias) uniform float u_bias;

float visible(int layer, vec2 uv, float d, float texel)
{
    vec2 t = (uv * 0.5 + 0.5) * float(u_size);
    ivec2 c = clamp(ivec2(floor(t)), ivec2(0), ivec2(u_size - 1));
    float m = uintBitsToFloat(imageLoad(u_maps, ivec3(c, layer)).r);
    return d <= m + u_bias + 0.5 * texel ? 1.0 : 0.0;
}

void main()
{
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    if (i >= u_count) return;
    vec3 p = points[2u * i].xyz, n = points[2u * i + 1u].xyz;
    vec3 e = vec3(0.0);
    if (points[2u * i + 1u].w != 0.0)
        for (int k = 0; k < u_casters; k++) {
            Caster c = casters[k];
            int type = int(c.pos.w), first = int(c.power.w);
            if (type == 0) { // directional
                vec3 l = -c.dir.xyz, r, u;
                float cs = dot(l, n);
                if (cs <= 0.0) continue;
                voxgi_basis(c.dir.xyz, r, u);
                vec3 q = p - c.pos.xyz;
                e += c.power.rgb * cs * visible(first, vec2(dot(q, r), dot(q, u)) / c.dir.w, dot(q, c.dir.xyz), 2.0 * c.dir.w / float(u_size));
                continue;
            }
            vec3 q = p - c.pos.xyz; // light -> point
            float dist = length(q);
            if (dist <= 0.0) continue;
            vec3 l = -q / dist;
            float cs = dot(l, n), w = 1.0;
            if (cs <= 0.0) continue;
            if (type == 2) { // spot: smoothstep from the outer to the inner cone
                float ca = dot(-l, c.dir.xyz), ci = c.param.x, co = c.param.y;
                float x = ci > co ? clamp((ca - co) / (ci - co), 0.0, 1.0) : (ca >= ci ? 1.0 : 0.0);
                w = x * x * (3.0 - 2.0 * x);
            } else if (type == 3) w = max(0.0, dot(-l, c.dir.xyz)); // the sampled surface's cosine
            if (w <= 0.0) continue;
            vec3 aq = abs(q);
            int axis = aq.x >= aq.y && aq.x >= aq.z ? 0 : (aq.y >= aq.z ? 1 : 2), face = 2 * axis + (q[axis] < 0.0 ? 1 : 0);
            vec3 f, r, u;
            cube_face(face, f, r, u);
            float fw = dot(q, f);
            e += c.power.rgb * w * cs / (dist * dist) * visible(first + face, vec2(dot(q, r), dot(q, u)) / fw, dist, 2.0 * dist / float(u_size));
        }
    irradiance[i] = vec4(e, 0.0);
}
