// Standard-input console reader.
#include "Console.h"

#include <iostream>
#include <thread>

namespace lpv::game {

Console::Console() : lines_(std::make_shared<Lines>()) {
    // The reader blocks in getline until input or end of file; detached so it never keeps the
    // game alive, and it owns a reference to the line buffer so it never outlives it.
    std::thread([lines = lines_] {
        std::string line;
        while (std::getline(std::cin, line)) {
            std::lock_guard lock(lines->mutex);
            lines->pending.push_back(line);
        }
    }).detach();
}

Console::~Console() = default;

std::vector<std::string> Console::takeLines() {
    std::lock_guard lock(lines_->mutex);
    std::vector<std::string> out;
    out.swap(lines_->pending);
    return out;
}

} // namespace lpv::game
