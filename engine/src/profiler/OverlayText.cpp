// The overlay's text from stb_easy_font (Debian's libstb-dev), one character at a time so that a
// glyph's quads fit a small stack buffer whatever the string's length.
#include "engine/profiler/OverlayText.h"

// The header's functions are static; the overlay uses two of them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace lpv::engine {
namespace {

char printable(char c) {
    return c >= 32 && c < 127 ? c : '?';
}

} // namespace

uint32_t overlayTextRects(std::string_view text, float x, float y, glm::vec4 color,
                          std::span<OverlayRect> out, uint32_t count) {
    // stb_easy_font_print writes 4 vertices of 16 bytes (x, y, z, colour) per quad; the busiest
    // glyph (X) has 11 quads.
    char quads[16 * 64];
    for (const char c : text) {
        char one[2] = {printable(c), 0};
        const int n = stb_easy_font_print(x, y, one, nullptr, quads, int(sizeof(quads)));
        for (int q = 0; q < n && count < out.size(); ++q) {
            // Corners 0 (top left) and 2 (bottom right) of the quad.
            const float* v0 = reinterpret_cast<const float*>(quads + q * 64);
            const float* v2 = reinterpret_cast<const float*>(quads + q * 64 + 32);
            out[count++] = {glm::vec4(v0[0], v0[1], v2[0] - v0[0], v2[1] - v0[1]), color};
        }
        x += float(stb_easy_font_width(one));
    }
    return count;
}

float overlayTextWidth(std::string_view text) {
    float width = 0.0f;
    for (const char c : text) {
        char one[2] = {printable(c), 0};
        width += float(stb_easy_font_width(one));
    }
    return width;
}

} // namespace lpv::engine
