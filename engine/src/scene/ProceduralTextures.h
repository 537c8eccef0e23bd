// Textures made in code for the built-in atrium: stone, plaster, floor tiles, brick, wood and woven
// banner fabric. Every texture tiles seamlessly (the noise is periodic over the image) and is
// deterministic: the same arguments give the same pixels on every run and machine.
#pragma once

#include "engine/scene/Scene.h"

#include <glm/vec3.hpp>

#include <cstdint>

namespace lpv::engine::textures {

// Pale limestone with soft mottling; for columns, arches and cornices. One image covers 2 m.
TextureImage stoneAlbedo(uint32_t size);
// Off-white lime plaster with faint stains; tinted by the material's base color.
TextureImage plasterAlbedo(uint32_t size);

// Polished marble tiles, cream and red-brown in a checkerboard, 2 x 2 tiles per image, thin grout.
TextureImage floorTilesAlbedo(uint32_t size);
// Tangent-space normals (linear) of the same tiles: sunken grout and bevelled tile edges.
TextureImage floorTilesNormal(uint32_t size);

// Running-bond brick, 4 bricks across and 16 courses per image, each brick a slightly different red.
TextureImage brickAlbedo(uint32_t size);
// Tangent-space normals (linear) of the same bricks: recessed mortar and a rough brick face.
TextureImage brickNormal(uint32_t size);

// Horizontal planks with grain, for crates.
TextureImage woodAlbedo(uint32_t size);

// A banner of plain-woven `fabric` with a `trim` border and one of four emblems (`emblem` % 4);
// the whole banner maps to the image (uv 0..1), row 0 at the top.
TextureImage bannerFabric(glm::vec3 fabric, glm::vec3 trim, uint32_t emblem, uint32_t width, uint32_t height);

} // namespace lpv::engine::textures
