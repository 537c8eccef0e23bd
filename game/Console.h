// A console on standard input: each line `name=value` is checked and staged, and takes effect at
// the next frame. Lines are read on a thread so the frame loop never waits for input.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace lpv::game {

class Console {
public:
    Console();
    ~Console();
    // Lines typed since the last call.
    std::vector<std::string> takeLines();

private:
    // Shared with the reader thread, which may outlive the Console while blocked in getline.
    struct Lines {
        std::mutex mutex;
        std::vector<std::string> pending;
    };
    std::shared_ptr<Lines> lines_;
};

} // namespace lpv::game
