// A command-line option written with '=' and nothing after it (`--profile-out= --frames=2`).
// CLI11 takes such an option's value from the next argument, whatever it is, so the example would
// write the profile into a folder named "--frames=2". The game and the benchmarks refuse it first.
#pragma once

#include <optional>
#include <span>
#include <string>

namespace lpv::engine {

// The first argument of the form `--name=` (before a `--` that ends the options), if any.
std::optional<std::string> findEmptyOptionValue(std::span<char* const> args);

// The same check for a program's argv: prints the error (with the --help hint) to stderr and
// returns true when it finds one; the caller exits 2.
bool refuseEmptyOptionValue(int argc, char** argv);

} // namespace lpv::engine
