// Loading settings from TOML (toml++). Tables give the dotted names: [gi] grid_size = 32 is
// gi.grid_size. Every key must be a declared setting, every table a prefix of some (even an empty
// one); every value must have the declared type.
#include "engine/config/Config.h"
#include "engine/config/ShownText.h"

#include "platforms/Platform.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

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
        if (!decl.keyword.empty() && node.is_string() && *node.value<std::string>() == decl.keyword) {
            v = *node.value<std::string>();
            break;
        }
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
                          "'" + decl.name + "' = " + shownText(decl.format(v)) + ": expected " + expected);
    return v;
}

// A setting's name has at most this many more dotted parts than the deepest declared one before a
// key is refused as nested too deep: a little deeper is a typo ("gi.grid.size" for gi.grid_size), worth
// the nearest name, and the limit keeps the walk below and toml++'s own recursion shallow.
constexpr size_t kDepthSlack = 2;
// Arrays nested deeper than this in a value are refused before toml++ reads them (it recurses on
// each); no setting's value has more than one.
constexpr size_t kMaxArrayNesting = 64;

size_t partsOf(std::string_view name) {
    return size_t(std::count(name.begin(), name.end(), '.')) + 1;
}

struct DepthLimit {
    size_t settings = 1; // the most parts of a declared setting's name
    std::string example; // such a setting's name
    size_t keys() const { return settings + kDepthSlack; }
};

DepthLimit depthLimit() {
    DepthLimit limit;
    if (const SettingDecl* deepest = SettingRegistry::global().deepest()) {
        limit.settings = partsOf(deepest->name);
        limit.example = deepest->name;
    }
    return limit;
}

ConfigError nestedTooDeep(const std::string& source, int line, std::string_view name, size_t depth,
                          const DepthLimit& limit) {
    return ConfigError(source, line,
                       "key '" + shownText(name) + "' is nested " + std::to_string(depth) +
                           " levels deep; settings are at most " + std::to_string(limit.settings) +
                           " levels" + (limit.example.empty() ? "" : " ('" + limit.example + "')"));
}

// toml++ recurses on nested inline tables and arrays, and a table frees its children recursively:
// a key of 100,000 dotted parts, or as many nested arrays, overflows the stack inside it. This
// linear scan runs first and refuses a key nested deeper than DepthLimit::keys() (dotted parts, table
// headers and inline tables together) and arrays nested deeper than kMaxArrayNesting, naming the line.
// It reads just enough TOML for that: strings, comments, keys, and the brackets outside strings.
void refuseDeepNesting(std::string_view text, const std::string& source, const DepthLimit& limit) {
    struct Container {
        char kind;        // '{' an inline table, '[' an array
        size_t depth;     // the nesting of the keys inside it
        std::string name; // the dotted name it is the value of
    };
    std::vector<Container> open;
    size_t arrays = 0;     // '[' among `open`
    size_t tableDepth = 0; // the last [table] header's parts
    std::string tableName; // and its text
    bool inKey = true, header = false, keyHasText = false;
    size_t parts = 1, keyStart = 0; // the key being read
    int line = 1, keyLine = 1;
    size_t valueDepth = 0; // the key whose value is being read
    std::string valueName;

    const auto startKey = [&](size_t at) {
        inKey = true;
        header = keyHasText = false;
        parts = 1;
        keyStart = at;
        keyLine = line;
    };
    const auto keyText = [&](size_t end) {
        std::string_view k = text.substr(keyStart, end - keyStart);
        while (!k.empty() && (k.front() == ' ' || k.front() == '\t' || k.front() == '['))
            k.remove_prefix(1);
        while (!k.empty() && (k.back() == ' ' || k.back() == '\t'))
            k.remove_suffix(1);
        return k;
    };
    // The key ends at `end` ('=' or a header's ']'): refused when too deep, else its value follows.
    const auto endKey = [&](size_t end) {
        const size_t base = header ? 0 : open.empty() ? tableDepth : open.back().depth;
        const std::string& baseName = header ? std::string() : open.empty() ? tableName : open.back().name;
        const std::string name = (baseName.empty() ? "" : baseName + ".") + std::string(keyText(end));
        if (base + parts > limit.keys()) throw nestedTooDeep(source, keyLine, name, base + parts, limit);
        if (header) {
            tableDepth = parts;
            tableName = name;
        }
        inKey = false;
        valueDepth = base + parts;
        valueName = name;
    };

    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '\n') {
            ++line;
            if (open.empty()) startKey(i + 1);
            continue;
        }
        if (c == '#') { // a comment, to the end of the line
            const size_t end = text.find('\n', i);
            i = (end == std::string_view::npos ? text.size() : end) - 1;
            continue;
        }
        if (c == '"' || c == '\'') {
            // A string: multi-line when the quote is tripled; only basic ("") strings have escapes.
            keyHasText = true;
            const bool multiline = text.substr(i, 3) == std::string(3, c);
            size_t k = i + (multiline ? 3 : 1);
            for (; k < text.size(); ++k) {
                if (text[k] == '\n') {
                    if (!multiline) break; // unterminated: toml++ says so
                    ++line;
                } else if (c == '"' && text[k] == '\\') {
                    if (k + 1 < text.size() && text[k + 1] == '\n') ++line;
                    ++k;
                } else if (text[k] == c && (!multiline || text.substr(k, 3) == std::string(3, c))) {
                    if (multiline) k += 2;
                    break;
                }
            }
            i = std::min(k, text.size()) - (k < text.size() && text[k] == '\n' ? 1 : 0);
            if (k >= text.size()) break;
            continue;
        }
        if (inKey) {
            if (c == '[' && !keyHasText && open.empty() && !header) {
                header = true;
                if (i + 1 < text.size() && text[i + 1] == '[') ++i;
                keyStart = i + 1;
            } else if (c == '.') {
                ++parts;
            } else if (c == '=' && !header) {
                endKey(i);
            } else if (c == ']' && header) {
                endKey(i);
                if (i + 1 < text.size() && text[i + 1] == ']') ++i;
            } else if (c == '}' && !keyHasText && !open.empty() && open.back().kind == '{') {
                open.pop_back(); // an empty inline table, or a comma before its end
                inKey = false;
            } else if (c != ' ' && c != '\t' && c != '\r') {
                keyHasText = true;
            }
            continue;
        }
        if (c == '{') {
            open.push_back({'{', valueDepth, valueName});
            startKey(i + 1);
        } else if (c == '[') {
            if (++arrays > kMaxArrayNesting)
                throw ConfigError(
                    source, line,
                    "the value of '" + shownText(valueName) + "' has arrays nested more than " +
                        std::to_string(kMaxArrayNesting) +
                        " levels deep; a setting's value is one value or one array ([x, y, z])");
            // An array's elements are one level below its key (an inline table in one, more).
            open.push_back({'[', valueDepth + 1, valueName});
            valueDepth += 1;
        } else if ((c == ']' || c == '}') && !open.empty() && open.back().kind == (c == ']' ? '[' : '{')) {
            if (c == ']') --arrays;
            valueDepth = open.back().depth - (c == ']' ? 1 : 0);
            valueName = open.back().name;
            open.pop_back();
        } else if (c == ',' && !open.empty() && open.back().kind == '{') {
            startKey(i + 1);
        }
    }
}

// The walk goes no deeper than refuseDeepNesting allows; the check here keeps it so whatever the
// text (a table toml++ builds from something the scan does not foresee).
// `depth`: the parts of `prefix`.
void walk(Config& config, const toml::table& table, const std::string& prefix, size_t depth,
          const std::string& source, const DepthLimit& limit) {

    const SettingRegistry& registry = SettingRegistry::global();
    for (const auto& [key, node] : table) {
        const std::string name =
            prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
        if (depth + 1 > limit.keys()) throw nestedTooDeep(source, lineOf(node), name, depth + 1, limit);
        const SettingDecl* decl = registry.find(name);
        const toml::table* sub = node.as_table();
        if (sub && !decl) {
            // A table with keys names its settings below; an empty one names none, so it must at
            // least be a table that holds settings, or a typo would pass unnoticed.
            if (sub->empty() && !registry.isTable(name)) {
                const std::string suggestion = registry.nearestTable(name);
                throw ConfigError(source, lineOf(node),
                                  "unknown table '" + shownText(name) + "'" +
                                      (suggestion.empty() ? std::string(" (--help-config lists the settings)")
                                                          : " (did you mean '" + suggestion + "'?)"));
            }
            walk(config, *sub, name, depth + 1, source, limit);
            continue;
        }
        if (!decl && registry.isTable(name))
            throw ConfigError(source, lineOf(node),
                              "'" + shownText(name) + "' is a table of settings, got " +
                                  std::string(typeNameOf(node)));
        if (!decl) {
            const std::string suggestion = registry.nearest(name);
            throw ConfigError(source, lineOf(node),
                              "unknown setting '" + shownText(name) + "'" +
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
    const DepthLimit limit = depthLimit();
    refuseDeepNesting(text, sourceName, limit);
    toml::table table;
    try {
        table = toml::parse(text, sourceName);
    } catch (const toml::parse_error& e) {
        const int badUtf8 =
            e.description().find("utf-8") != std::string_view::npos ? lineOfInvalidUtf8(text) : 0;
        throw ConfigError(sourceName, badUtf8 ? badUtf8 : int(e.source().begin.line),
                          "malformed TOML: " + std::string(e.description()));
    }
    walk(*this, table, "", 0, sourceName, limit);
}

void Config::loadFile(const std::string& path) {
    std::string text;
    if (const int error = platforms::Platform::tryReadFile(path, text))
        throw ConfigError(path, 0, "cannot read the config file: " + std::string(std::strerror(error)));
    loadString(text, path);
}

} // namespace lpv::engine
