// The values of every setting, layered in order: defaults, then TOML files, then command-line
// overrides (--set key=value). Anything wrong - unknown key, wrong type, out of range, malformed
// TOML - is a ConfigError naming the source (file and line, or the --set argument) and what was
// expected; nothing is ignored and nothing silently falls back to a default.
//
// Changes while running (game keys, console lines) are staged and applied by applyPending() at
// the start of the next frame, so a frame never sees half a change.
#pragma once

#include "engine/config/Setting.h"

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace lpv::engine {

class ConfigError : public std::runtime_error {
public:
    ConfigError(std::string source, int line, const std::string& message);
    const std::string& source() const { return source_; }
    int line() const { return line_; } // 0 when the source has no lines (a --set argument)

private:
    std::string source_;
    int line_;
};

class Config {
public:
    // Every registered setting at its default.
    Config();

    void loadFile(const std::string& path);
    void loadString(std::string_view toml, const std::string& sourceName);
    // "gi.grid_size=48". Applies immediately (startup).
    void applyOverride(std::string_view assignment, const std::string& sourceName = "--set");

    // Validates now (throws ConfigError), applies at the next applyPending().
    void stage(std::string_view assignment, const std::string& sourceName = "console");
    void stage(const SettingDecl& decl, SettingValue value, const std::string& sourceName);
    // Applies staged changes; returns the settings whose value changed. Called once per frame.
    std::vector<const SettingDecl*> applyPending();

    bool get(const BoolSetting& s) const { return std::get<bool>(value(s.decl())); }
    int64_t get(const IntSetting& s) const { return std::get<int64_t>(value(s.decl())); }
    double get(const FloatSetting& s) const { return std::get<double>(value(s.decl())); }
    // nullopt: "auto".
    std::optional<double> get(const AutoFloatSetting& s) const {
        const SettingValue& v = value(s.decl());
        return std::holds_alternative<double>(v) ? std::optional<double>(std::get<double>(v)) : std::nullopt;
    }
    const std::string& get(const StringSetting& s) const { return std::get<std::string>(value(s.decl())); }
    glm::vec3 get(const Vec3Setting& s) const { return std::get<glm::vec3>(value(s.decl())); }
    template <typename E> E get(const EnumSetting<E>& s) const {
        return s.fromName(std::get<std::string>(value(s.decl())));
    }

    const SettingValue& value(const SettingDecl& decl) const;
    // Where the current value came from: "default", "game.toml:12", "--set".
    const std::string& origin(const SettingDecl& decl) const;
    // Sets a value now (validated), for code and tests.
    void set(const SettingDecl& decl, SettingValue value, const std::string& origin);

    // Converts text (a --set value or a console line) to a value of the setting's type, or throws.
    static SettingValue parse(const SettingDecl& decl, std::string_view text, const std::string& source,
                              int line);
    // Empty when `value` is acceptable for `decl`, else what was expected.
    static std::string validate(const SettingDecl& decl, const SettingValue& value);

private:
    struct Slot {
        SettingValue value;
        std::string origin;
    };
    struct Pending {
        const SettingDecl* decl;
        SettingValue value;
        std::string origin;
    };
    Slot& slot(const SettingDecl& decl);
    const SettingDecl& lookup(std::string_view name, const std::string& source, int line) const;
    void assign(std::string_view assignment, const std::string& source, bool staged);

    std::vector<Slot> slots_;
    std::vector<Pending> pending_;
};

} // namespace lpv::engine
