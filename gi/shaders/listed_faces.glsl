// The lists of reflecting faces (GatheredReflection): 16 lists, one per cell phase, and per cell a
// 32-bit slot word: its listed faces in bits 26-31 (-x -y -z +x +y +z), the slot of the first in
// its phase's list in bits 0-25 (0: none). Shared by the reflection that lists them
// (lpv_reflect_gathered_body.glsl) and the gathers that read them (vpl_gather.frag and the
// reflection from a list).
#ifndef LISTED_FACES_GLSL
#define LISTED_FACES_GLSL

// Cell c's phase: every 4 x 4 block of cells on a plane of the grid holds each of the 16 once.
int facePhase(ivec3 c) { return ((c.x + c.y) & 3) + 4 * ((c.y + c.z) & 3); }

uint listedFaceCount(uint slots) { return uint(bitCount(slots >> 26)); }
uint firstListedSlot(uint slots) { return slots & 0x3ffffffu; }
uint packListedSlots(uint mask, uint first) { return (mask << 26) | first; }

// Where cell c's first listed face is in the lists, each phase's `room` slots long.
uint listedAt(ivec3 c, uint slots, uint room) { return uint(facePhase(c)) * room + firstListedSlot(slots); }

// The cell a listed face belongs to (its centre plus half a cell along its normal, into the cell),
// in the grid whose corner is origin.xyz and cell origin.w.
ivec3 listedFaceCell(vec3 position, vec3 normal, vec4 origin) {
    return ivec3(floor((position + 0.5 * origin.w * normal - origin.xyz) / origin.w));
}

#endif
