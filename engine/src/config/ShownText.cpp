// Long input text cut short for messages (see ShownText.h).
#include "engine/config/ShownText.h"

namespace lpv::engine {

std::string shownText(std::string_view text, size_t limit) {
    if (text.size() <= limit) return std::string(text);
    size_t cut = limit;
    // Back off to the start of a UTF-8 sequence: a message must stay valid text.
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80)
        --cut;
    return std::string(text.substr(0, cut)) + "... (" + std::to_string(text.size()) + " bytes)";
}

} // namespace lpv::engine
