// Text for the profiler overlay as solid rectangles: stb_easy_font's segment font, whose glyphs are
// a few axis-aligned bars each, so the overlay draws its labels with the same rectangles as its
// bars, with no font texture. Pixels, y down; a glyph is 6 pixels wide and at most 9 high.
#pragma once

#include <glm/vec4.hpp>

#include <cstdint>
#include <span>
#include <string_view>

namespace lpv::engine {

// One solid rectangle of the overlay: x, y, width, height in pixels (row 0 at the top), and RGBA.
struct OverlayRect {
    glm::vec4 rect;
    glm::vec4 color;
};

// Glyph height (the descenders of g, j, p, q, y included): a row shorter than this gets no text.
inline constexpr float kOverlayTextHeight = 9.0f;

// Writes the rectangles of `text` in `color`, its top-left corner at (x, y), into `out` from index
// `count` on, as many as `out` holds (what does not fit is left out); returns the new count.
// Printable ASCII only (anything else is drawn as '?'). Allocates nothing.
uint32_t overlayTextRects(std::string_view text, float x, float y, glm::vec4 color,
                          std::span<OverlayRect> out, uint32_t count);

// The width in pixels `text` takes (its advances; printable ASCII as above).
float overlayTextWidth(std::string_view text);

} // namespace lpv::engine
