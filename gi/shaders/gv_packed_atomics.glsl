// Blending done with integer atomics on r32ui texels (gv_camera_marks.comp). The camera's marks:
// what a point drawn into an RGBA8 target with max blending stored, packed in the same 4 bytes; a
// compare-and-swap loop retries until no other invocation wrote the texel between its read and its
// swap, and a mark the texel already holds swaps nothing. The image is `coherent`: the first read
// can be stale, the swap cannot. (A function cannot take an image, so the shader names its own in
// the macro.)
#ifndef LPV_GV_PACKED_ATOMICS_GLSL
#define LPV_GV_PACKED_ATOMICS_GLSL

// Per byte, the larger of a's and b's (four unorm8 fields).
uint maxPerByte(uint a, uint b) {
    uvec4 m = max((uvec4(a) >> uvec4(0, 8, 16, 24)) & 0xffu, (uvec4(b) >> uvec4(0, 8, 16, 24)) & 0xffu);
    return m.x | (m.y << 8) | (m.z << 16) | (m.w << 24);
}

// image[coord] = per byte max(image[coord], packUnorm4x8(value)).
#define GV_ATOMIC_MAX_UNORM4X8(image, coord, value)                                                      \
    {                                                                                                   \
        uint packed_ = packUnorm4x8(value);                                                             \
        uint old_ = imageLoad(image, coord).r;                                                          \
        for (;;) {                                                                                      \
            uint want_ = maxPerByte(old_, packed_);                                                     \
            if (want_ == old_) break;                                                                   \
            uint seen_ = imageAtomicCompSwap(image, coord, old_, want_);                                \
            if (seen_ == old_) break;                                                                   \
            old_ = seen_;                                                                               \
        }                                                                                               \
    }

#endif
