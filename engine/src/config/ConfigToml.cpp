// Loading settings from TOML (toml++). Tables give the dotted names: [gi] grid_size = 32 is
// gi.grid_size. Every key must be a declared setting, every table a prefix of some (even an empty
// one); every value must have the declared type.
#include "engine/config/Config.h"

#include "platforms/Platform.h"

#include <toml++/toml.h>

#include <cstdint>
#include <cstring>

namespace lpv::engine {
namespace {

int lineOf(const toml::node& n) {
    return int(n.source().begin.line);
}

std::string_view typeNameOf(const toml::node& node) {
    switch (node.type()) {
    case toml::node_type::string:
        return "a string";
    case toml::node_type::integer:
        return "an integer";
    case toml::node_type::floating_point:
        return "a float";
    case toml::node_type::boolean:
        return "a bool";
    case toml::node_type::array:
        return "an array";
    case toml::node_type::table:
        return "a table";
    default:
        return "a date/time";
    }
}

SettingValue convert(const SettingDecl& decl, const toml::node& node, const std::string& source) {
    const auto wrongType = [&](std::string_view got) {
        return ConfigError(source, lineOf(node),
                           "'" + decl.name + "' has " + std::string(got) + " value: expected " +
                               decl.expected());
    };
    SettingValue v;
    switch (decl.type) {
    case SettingType::Bool:
        if (!node.is_boolean()) throw wrongType(typeNameOf(node));
        v = *node.value<bool>();
        break;
    case SettingType::Int:
        if (!node.is_integer()) throw wrongType(typeNameOf(node));
        v = *node.value<int64_t>();
        break;
    case SettingType::Float:
        if (!node.is_number()) throw wrongType(typeNameOf(node));
        v = *node.value<double>();
        break;
    case SettingType::Enum:
    case SettingType::String:
        if (!node.is_string()) throw wrongType(typeNameOf(node));
        v = *node.value<std::string>();
        break;
    case SettingType::Vec3: {
        const toml::array* a = node.as_array();
        if (!a || a->size() != 3)
            throw wrongType(!a           ? std::string(typeNameOf(node))
                            : a->empty() ? std::string("an empty array")
                                         : "a " + std::to_string(a->size()) + "-element array");
        glm::vec3 x;
        for (size_t i = 0; i < 3; ++i) {
            if (!(*a)[i].is_number()) throw wrongType("an array with a non-number");
            x[int(i)] = float(*(*a)[i].value<double>());
        }
        v = x;
        break;
    }
    }
    if (const std::string expected = Config::validate(decl, v); !expected.empty())
        throw ConfigError(source, lineOf(node),
                          "'" + decl.name + "' = " + decl.format(v) + ": expected " + expected);
    return v;
}

void walk(Config& config, const toml::table& table, const std::string& prefix, const std::string& source) {
    const SettingRegistry& registry = SettingRegistry::global();
    for (const auto& [key, node] : table) {
        const std::string name =
            prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
        const SettingDecl* decl = registry.find(name);
        const toml::table* sub = node.as_table();
        if (sub && !decl) {
            // A table with keys names its settings below; an empty one names none, so it must at
            // least be a table that holds settings, or a typo would pass unnoticed.
            if (sub->empty() && !registry.isTable(name)) {
                const std::string suggestion = registry.nearestTable(name);
                throw ConfigError(source, lineOf(node),
                                  "unknown table '" + name + "'" +
                                      (suggestion.empty() ? std::string(" (--help-config lists the settings)")
                                                          : " (did you mean '" + suggestion + "'?)"));
            }
            walk(config, *sub, name, source);
            continue;
        }
        if (!decl && registry.isTable(name))
            throw ConfigError(source, lineOf(node),
                              "'" + name + "' is a table of settings, got " + std::string(typeNameOf(node)));
        if (!decl) {
            const std::string suggestion = registry.nearest(name);
            throw ConfigError(source, lineOf(node),
                              "unknown setting '" + name + "'" +
                                  (suggestion.empty() ? std::string(" (--help-config lists them all)")
                                                      : " (did you mean '" + suggestion + "'?)"));
        }
        // A table where a setting's value belongs, empty or not, is a wrong type (convert says so).
        config.set(*decl, convert(*decl, node, source), source + ":" + std::to_string(lineOf(node)));
    }
}

// The line of the first byte that does not begin or continue a well-formed UTF-8 sequence (RFC
// 3629: no overlong forms, no surrogates, nothing past U+10FFFF), or 0 if the text is valid.
// toml++ reports an invalid byte at a line's start on the line before it.
int lineOfInvalidUtf8(std::string_view text) {
    int line = 1;
    for (size_t i = 0; i < text.size();) {
        const auto byte = [&](size_t k) { return k < text.size() ? uint8_t(text[k]) : uint8_t(0); };
        const uint8_t b = byte(i);
        if (b == '\n') ++line;
        if (b < 0x80) {
            ++i;
            continue;
        }
        // The sequence's length, and the range its second byte must fall in.
        size_t length = 0;
        uint8_t low = 0x80, high = 0xBF;
        if (b >= 0xC2 && b <= 0xDF)
            length = 2;
        else if (b >= 0xE0 && b <= 0xEF) {
            length = 3;
            if (b == 0xE0) low = 0xA0;
            if (b == 0xED) high = 0x9F;
        } else if (b >= 0xF0 && b <= 0xF4) {
            length = 4;
            if (b == 0xF0) low = 0x90;
            if (b == 0xF4) high = 0x8F;
        } else
            return line;
        if (byte(i + 1) < low || byte(i + 1) > high) return line;
        for (size_t k = 2; k < length; ++k)
            if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return line;
        i += length;
    }
    return 0;
}

} // namespace

void Config::loadString(std::string_view text, const std::string& sourceName) {
    toml::table table;
    try {
        table = toml::parse(text, sourceName);
    } catch (const toml::parse_error& e) {
        const int badUtf8 =
            e.description().find("utf-8") != std::string_view::npos ? lineOfInvalidUtf8(text) : 0;
        throw ConfigError(sourceName, badUtf8 ? badUtf8 : int(e.source().begin.line),
                          "malformed TOML: " + std::string(e.description()));
    }
    walk(*this, table, "", sourceName);
}

void Config::loadFile(const std::string& path) {
    std::string text;
    if (const int error = platforms::Platform::tryReadFile(path, text))
        throw ConfigError(path, 0, "cannot read the config file: " + std::string(std::strerror(error)));
    loadString(text, path);
}

} // namespace lpv::engine
