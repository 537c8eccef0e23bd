// Where a point lies in a cascade, and which cascade answers for it: shared by the lookup, the
// glossy march (lpv_cascades.glsl) and the cascade classification (cascade_classify_body.glsl). No
// resources, so a stage may include it without declaring the volumes.
#ifndef CASCADE_REGION_GLSL
#define CASCADE_REGION_GLSL

// Where p lies in the volume whose cell 0's corner and cell size are `origin` (xyz, w), in uvw.
vec3 uvwInVolume(vec4 origin, int cells, vec3 p) { return (p - origin.xyz) * (1.0 / (origin.w * float(cells))); }

// How far inside a cascade's usable region p lies: 0 at its border, 1 at the inner edge of its
// blend band (`band`: the band's width as a fraction of the half-extent, CryEngine's
// e_GIBlendRatio), negative outside. The usable region stops a cell short of the volume, so the
// lookup's half-cell offsets and trilinear filtering stay inside. The finest cascade in which it is
// positive answers for p (lookup and glossy march alike), blended into the next coarser one where
// it is below 1.
float cascadeInsideness(vec4 origin, int cells, float band, vec3 p) {
    vec3 uvw = uvwInVolume(origin, cells, p);
    float margin = 1.0 / float(cells);
    vec3 d = min(uvw - margin, (1.0 - margin) - uvw); // distance to the nearer border, per axis
    float nearest = min(d.x, min(d.y, d.z));
    return nearest * (1.0 / max(band * (0.5 - margin), 1e-6));
}

// Whether a cascade holds the glossy march from surface point p with normal n: the march starts
// half a cell out along n, and the cascade holds it when that start is half a cell inside its
// border, so trilinear filtering stays inside. Testing the start rather than p keeps a floor that
// lies on a cascade's border (where a volume pushed inside the scene puts it) in that finer
// cascade; the lookup, which also looks half a cell behind the surface, needs a cell more, so the
// march's cascade is the lookup's or the next finer one.
bool glossyMarchHeld(vec4 origin, int cells, vec3 p, vec3 n) {
    vec3 uvw = uvwInVolume(origin, cells, p + 0.5 * origin.w * n);
    float margin = 0.5 / float(cells);
    return all(greaterThanEqual(uvw, vec3(margin))) && all(lessThanEqual(uvw, vec3(1.0 - margin)));
}

// How much glossy march a surface of this roughness gets (gi.glossy_max_roughness): all of it up to
// 0.1 below `maxRoughness`, fading to none at it, so no seam shows where materials cross it. A
// surface it gives nothing is not marched (the march's cost is per pixel): it keeps the lookup's
// reflection, the volume evaluated at its lobe's mean light direction (lpv_lookup.glsl). 0 for
// every surface when `maxRoughness` is 0 (glossy off).
float glossyFade(float roughness, float maxRoughness) { return clamp((maxRoughness - roughness) * 10.0, 0.0, 1.0); }

// Cascade classes (gi/CascadeClasses.h): on devices that run both sides of every branch, a
// classification pass stores each lookup texel's class as a stencil, and the lookup and the glossy
// march draw once per cascade with a stencil test on their field, so each texel runs only its own
// cascade's code. Bits 0-1: the lookup's cascade, bit 2: in its blend band, bit 3: looked up (the
// sky keeps the cleared 0); bits 4-5: the glossy march's cascade, bit 6: marched (not on the sky
// or surfaces glossyFade gives nothing). CascadeClasses.cpp tests the same fields.
int cascadeClassStencil(int lookupCascade, bool blend, bool marched, int marchCascade) {
    return 8 | lookupCascade | (blend ? 4 : 0) | (marched ? 64 | (marchCascade << 4) : 0);
}

#endif
