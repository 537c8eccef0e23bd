#ifndef PATCH_FORM_FACTOR_GLSL
#define PATCH_FORM_FACTOR_GLSL
// A VPL near a receiver is the patch it clusters, not a point: the irradiance a uniformly
// emitting rectangle sends p, over its radiant exitance, is its form factor, which Lambert's
// contour integral gives exactly however near. A point's cos x cos / (pi r^2) misses the light
// next to a corner: at the foot of a wall over a lit floor the point's cosine at the floor is
// zero, while half of the wall's hemisphere is lit floor.

// The tangent of a patch's rectangle on the plane with normal m: the world axis least along m,
// made perpendicular (the bitangent is m x tangent). vpl_cluster.comp measures the rectangle in
// this frame, so it fits the texels the patch clusters.
vec3 patchTangent(vec3 m) {
    vec3 a = abs(m.x) <= abs(m.y) && abs(m.x) <= abs(m.z) ? vec3(1.0, 0.0, 0.0)
             : (abs(m.y) <= abs(m.z) ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, 1.0));
    return normalize(a - m * dot(a, m));
}

// A patch's half extents along its tangent and bitangent, packed in a VPL's position.w (two
// halves): positive and finite, so `position.w > 0` still tells a lit VPL.
float packPatchExtents(vec2 halfExtents) {
    return uintBitsToFloat(packHalf2x16(clamp(halfExtents, vec2(1e-3), vec2(6e4))));
}
vec2 patchExtents(float packed) {
    return unpackHalf2x16(floatBitsToUint(packed));
}

// Whether a receiver r^2 from the centre of a patch with half extents e is near enough to need
// the patch: farther than 10 half extents, a point's kernel is within 2% of its form factor
// (tests/gi/PatchFormFactorGpuTests.cpp). None (e.x 0, a point VPL) is never near.
bool nearPatch(float r2, vec2 e) {
    return e.x > 1e-3 && r2 < 100.0 * max(e.x * e.x, e.y * e.y);
}

// The form factor from p (normal n) to the rectangle centred at c with normal m and half extents
// e along patchTangent(m) and its bitangent, its part under p's horizon clipped away; 0 where p
// is behind the rectangle's plane.
float patchFormFactor(vec3 p, vec3 n, vec3 c, vec3 m, vec2 e) {
    vec3 d = c - p;
    if (dot(m, d) >= 0.0) return 0.0;
    vec3 tangent = patchTangent(m);
    vec3 t = e.x * tangent, b = e.y * cross(m, tangent);
    vec3 corners[4] = vec3[4](d + t + b, d - t + b, d - t - b, d + t - b);
    // Sutherland-Hodgman against the horizon: at most 5 vertices.
    vec3 q[5];
    int k = 0;
    for (int i = 0; i < 4; ++i) {
        vec3 a = corners[i], z = corners[(i + 1) & 3];
        float da = dot(a, n), dz = dot(z, n);
        if (da >= 0.0) q[k++] = a;
        if ((da >= 0.0) != (dz >= 0.0)) q[k++] = mix(a, z, da / (da - dz));
    }
    float sum = 0.0;
    for (int i = 0; i < k; ++i) {
        vec3 u = normalize(q[i]), w = normalize(q[i + 1 < k ? i + 1 : 0]);
        vec3 x = cross(u, w);
        float s = length(x);
        if (s > 1e-9) sum += atan(s, dot(u, w)) * dot(x, n) / s;
    }
    return abs(sum) * (0.5 / 3.14159265358979);
}
#endif
