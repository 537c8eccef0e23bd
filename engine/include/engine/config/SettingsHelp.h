// Listings of every registered setting, for --help-config and for the README's settings table
// (which is generated from this, and a test checks it is current).
#pragma once

#include <string>

namespace lpv::engine {

class Config;

// One block per setting: name, type, default, range/choices, help, restart note.
std::string settingsHelpText();
// A Markdown table: | setting | type | default | allowed | applies | description |
std::string settingsMarkdownTable();

} // namespace lpv::engine
