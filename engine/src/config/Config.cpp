// Setting values: validation, text parsing, layering and staged changes.
#include "engine/config/Config.h"
#include "engine/config/ShownText.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

namespace lpv::engine {

ConfigError::ConfigError(std::string source, int line, const std::string& message)
    : std::runtime_error(source + (line > 0 ? ":" + std::to_string(line) : "") + ": " + message),
      source_(std::move(source)), line_(line) {}

Config::Config() {
    for (const SettingDecl* d : SettingRegistry::global().all())
        slot(*d);
}

Config::Slot& Config::slot(const SettingDecl& decl) {
    // Settings registered after this Config was made (late static init) start at their default.
    if (decl.index >= slots_.size()) slots_.resize(decl.index + 1);
    Slot& s = slots_[decl.index];
    if (s.origin.empty()) {
        s.value = decl.defaultValue;
        s.origin = "default";
    }
    return s;
}

const SettingValue& Config::value(const SettingDecl& decl) const {
    return const_cast<Config*>(this)->slot(decl).value;
}

const std::string& Config::origin(const SettingDecl& decl) const {
    return const_cast<Config*>(this)->slot(decl).origin;
}

std::string Config::validate(const SettingDecl& decl, const SettingValue& v) {
    switch (decl.type) {
    case SettingType::Bool:
        if (!std::holds_alternative<bool>(v)) return decl.expected();
        break;
    case SettingType::Int:
        if (!std::holds_alternative<int64_t>(v)) return decl.expected();
        if (decl.min <= decl.max &&
            (double(std::get<int64_t>(v)) < decl.min || double(std::get<int64_t>(v)) > decl.max))
            return decl.expected();
        break;
    case SettingType::Float: {
        if (const std::string* word = std::get_if<std::string>(&v))
            return !decl.keyword.empty() && *word == decl.keyword ? std::string() : decl.expected();
        if (!std::holds_alternative<double>(v)) return decl.expected();
        const double x = std::get<double>(v);
        if (!std::isfinite(x) || (decl.min <= decl.max && (x < decl.min || x > decl.max)))
            return decl.expected();
        break;
    }
    case SettingType::Enum: {
        if (!std::holds_alternative<std::string>(v)) return decl.expected();
        bool found = false;
        for (const auto& c : decl.choices)
            found = found || c == std::get<std::string>(v);
        if (!found) return decl.expected();
        break;
    }
    case SettingType::String:
        if (!std::holds_alternative<std::string>(v)) return decl.expected();
        break;
    case SettingType::Vec3: {
        if (!std::holds_alternative<glm::vec3>(v)) return decl.expected();
        const glm::vec3 x = std::get<glm::vec3>(v);
        for (int i = 0; i < 3; ++i)
            if (!std::isfinite(x[i]) || (decl.min <= decl.max && (x[i] < decl.min || x[i] > decl.max)))
                return decl.expected();
        break;
    }
    }
    return {};
}

void Config::set(const SettingDecl& decl, SettingValue v, const std::string& origin) {
    if (const std::string expected = validate(decl, v); !expected.empty())
        throw ConfigError(origin, 0,
                          "'" + decl.name + "' = " + shownText(decl.format(v)) + ": expected " + expected);
    Slot& s = slot(decl);
    s.value = std::move(v);
    s.origin = origin;
}

namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
        s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
        s.remove_suffix(1);
    return s;
}

bool parseDouble(std::string_view text, double& out) {
    const std::string s(trim(text));
    if (s.empty()) return false;
    std::istringstream in(s);
    in.imbue(std::locale::classic());
    in >> out;
    return in && in.peek() == std::char_traits<char>::eof();
}

} // namespace

SettingValue Config::parse(const SettingDecl& decl, std::string_view raw, const std::string& source,
                           int line) {
    const std::string_view text = trim(raw);
    const auto fail = [&]() -> ConfigError {
        return ConfigError(source, line,
                           "'" + decl.name + "' = '" + shownText(text) + "': expected " + decl.expected());
    };
    SettingValue v;
    switch (decl.type) {
    case SettingType::Bool:
        if (text == "true" || text == "1" || text == "on")
            v = true;
        else if (text == "false" || text == "0" || text == "off")
            v = false;
        else
            throw fail();
        break;
    case SettingType::Int: {
        int64_t x = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
        if (ec != std::errc() || end != text.data() + text.size() || text.empty()) throw fail();
        v = x;
        break;
    }
    case SettingType::Float: {
        if (!decl.keyword.empty() && text == decl.keyword) {
            v = std::string(text);
            break;
        }
        double x = 0;
        if (!parseDouble(text, x)) throw fail();
        v = x;
        break;
    }
    case SettingType::Enum:
    case SettingType::String:
        v = std::string(text);
        break;
    case SettingType::Vec3: {
        glm::vec3 x;
        std::string_view rest = text;
        if (rest.size() >= 2 && rest.front() == '[' && rest.back() == ']')
            rest = rest.substr(1, rest.size() - 2);
        for (int i = 0; i < 3; ++i) {
            const size_t comma = rest.find(',');
            const std::string_view part = i < 2 ? rest.substr(0, comma) : rest;
            double c = 0;
            if ((i < 2 && comma == std::string_view::npos) || !parseDouble(part, c)) throw fail();
            x[i] = float(c);
            if (i < 2) rest = rest.substr(comma + 1);
        }
        v = x;
        break;
    }
    }
    if (!validate(decl, v).empty()) throw fail();
    return v;
}

const SettingDecl& Config::lookup(std::string_view name, const std::string& source, int line) const {
    if (const SettingDecl* d = SettingRegistry::global().find(name)) return *d;
    const std::string suggestion = SettingRegistry::global().nearest(name);
    throw ConfigError(source, line,
                      "unknown setting '" + shownText(name) + "'" +
                          (suggestion.empty() ? std::string(" (--help-config lists them all)")
                                              : " (did you mean '" + suggestion + "'?)"));
}

void Config::assign(std::string_view assignment, const std::string& source, bool staged) {
    const size_t eq = assignment.find('=');
    if (eq == std::string_view::npos)
        throw ConfigError(source, 0, "'" + shownText(assignment) + "': expected key=value");
    const std::string_view key = trim(assignment.substr(0, eq));
    const SettingDecl& decl = lookup(key, source, 0);
    SettingValue v = parse(decl, assignment.substr(eq + 1), source, 0);
    if (staged)
        pending_.push_back({&decl, std::move(v), source});
    else
        set(decl, std::move(v), source);
}

void Config::applyOverride(std::string_view assignment, const std::string& sourceName) {
    assign(assignment, sourceName, false);
}

void Config::stage(std::string_view assignment, const std::string& sourceName) {
    assign(assignment, sourceName, true);
}

void Config::stage(const SettingDecl& decl, SettingValue v, const std::string& sourceName) {
    if (const std::string expected = validate(decl, v); !expected.empty())
        throw ConfigError(sourceName, 0,
                          "'" + decl.name + "' = " + shownText(decl.format(v)) + ": expected " + expected);
    pending_.push_back({&decl, std::move(v), sourceName});
}

std::vector<const SettingDecl*> Config::applyPending() {
    std::vector<const SettingDecl*> changed;
    for (Pending& p : pending_) {
        Slot& s = slot(*p.decl);
        if (s.value == p.value) continue;
        s.value = std::move(p.value);
        s.origin = std::move(p.origin);
        if (std::find(changed.begin(), changed.end(), p.decl) == changed.end()) changed.push_back(p.decl);
    }
    pending_.clear();
    return changed;
}

} // namespace lpv::engine
