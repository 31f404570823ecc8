// Distance maps for light injection on GL (voxgi.h, part "light injection and cone tracing"):
// what the map pass (light_map_draw.glsl) and the injection pass (inject.glsl) share. A map is
// one layer of a 2D array of r32ui texels holding the float bits of the distance from the light
// to the nearest surface (positive floats order as their bits, so imageAtomicMin keeps the
// nearest; no depth buffer is needed). A directional light has one orthographic layer over the
// scene's bounding sphere, distance measured along the light's travel from a plane behind the
// scene; every other caster (a point, spot, or a sampled point on an area light or emitter) has
// six 90-degree cube faces, +x -x +y -y +z -z, distance = Euclidean.
// embedded unless VOXGI_NO_LIGHT_INJECTION
struct Caster {
    vec4 pos;    // point: position; directional: the plane behind the scene (its point); w: type (0 directional, 1 point, 2 spot, 3 area sample)
    vec4 dir;    // directional: travel direction; spot: axis; area sample: the surface's normal; w: the map's half-width (directional)
    vec4 power;  // rgb: intensity (directional: irradiance); w: first layer
    vec4 param;  // spot: cos of the inner and outer angles
};

// Cube face k's forward, right and up.
void cube_face(int k, out vec3 f, out vec3 r, out vec3 u)
{
    f = vec3(0.0);
    f[k / 2] = (k & 1) != 0 ? -1.0 : 1.0;
    r = vec3(0.0);
    r[(k / 2 + 1) % 3] = 1.0;
    u = cross(f, r);
}
