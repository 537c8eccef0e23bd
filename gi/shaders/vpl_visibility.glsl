// Whether b sees a through the faces of a cascade's cells: a 3D DDA over the cells of the grid
// with corner origin.xyz, cell origin.w and n cells a side, stopped by the first blocked face. The
// includer defines `bool faceBlocked(ivec3 cell, int axis, vec2 span)`: whether the lower face
// along `axis` of `cell` (inside the grid) blocks a segment spanning [span.x, span.y] cells along
// that axis, the scene's surfaces crossing it (gi/SurfaceVoxels.h, surface_faces.glsl). A segment
// leaving the volume is open beyond it.
float faceVisibility(vec4 origin, int n, vec3 a, vec3 b) {
    vec3 ta = (a - origin.xyz) / origin.w, tb = (b - origin.xyz) / origin.w;
    ivec3 c = ivec3(floor(ta));
    vec3 d = tb - ta;
    ivec3 st = ivec3(sign(d));
    vec3 inv = 1.0 / max(abs(d), vec3(1e-6));
    vec3 lo = min(ta, tb), hi = max(ta, tb);
    vec3 tMax = vec3(d.x > 0.0 ? float(c.x + 1) - ta.x : ta.x - float(c.x),
                     d.y > 0.0 ? float(c.y + 1) - ta.y : ta.y - float(c.y),
                     d.z > 0.0 ? float(c.z + 1) - ta.z : ta.z - float(c.z)) * inv;
    for (int i = 0; i < 3 * n; ++i) {
        int axis = tMax.x < tMax.y ? (tMax.x < tMax.z ? 0 : 2) : (tMax.y < tMax.z ? 1 : 2);
        if (tMax[axis] > 1.0) break;
        ivec3 upper = c;
        if (st[axis] > 0) upper[axis] += 1;
        if (any(lessThan(upper, ivec3(0))) || any(greaterThanEqual(upper, ivec3(n)))) break;
        if (faceBlocked(upper, axis, vec2(lo[axis], hi[axis]))) return 0.0;
        c[axis] += st[axis];
        tMax[axis] += inv[axis];
    }
    return 1.0;
}

// How far in front of its surface a march between two surfaces starts, in cells: more than half.
// A surface marks the face nearest to it (surface_voxels.frag), at most half a cell away on either
// side; one lying on a cell's centre (a ceiling at 5.5 m in 0.2 m cells: levels put surfaces at
// round heights) ties between the face behind it and the one half a cell in front, where a march
// starting exactly half a cell out then began, blocked or not by the last bit of its position.
const float kSurfaceLift = 0.51;

// Whether the surface point b (normal nb) sees the surface point a (normal na), each lifted off
// its surface past its own face.
float surfaceVisibility(vec4 origin, int n, vec3 a, vec3 na, vec3 b, vec3 nb) {
    const float lift = kSurfaceLift * origin.w;
    return faceVisibility(origin, n, a + lift * na, b + lift * nb);
}
