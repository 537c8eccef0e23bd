// Both benchmarks' command lines parsed as the game parses its own: a bad one is bad input and
// exits 2 (CLI11's own codes are 100 and more), with the reason.
#pragma once

#include "engine/config/EmptyOptionValue.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <optional>

namespace lpv::bench {

// Empty when the benchmark should run; else the code to exit with (0 after --help).
inline std::optional<int> parseCommandLine(CLI::App& app, int argc, char** argv) {
    if (engine::refuseEmptyOptionValue(argc, argv)) return 2;
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) { // --help
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "error: %s\nRun with --help for more information.\n", e.what());
        return 2;
    }
    return std::nullopt;
}

} // namespace lpv::bench
