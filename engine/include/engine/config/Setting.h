// Typed settings ("cvars"), each declared once, next to the code that uses it, with its default,
// range and one line of help:
//
//   const IntSetting kGridSize{"gi.grid_size", 32, 16, 64, "LPV cells per axis"};
//
// A declaration registers itself in the process-wide SettingRegistry at static initialisation, so
// --help-config, the README's settings table and the config loader all see the same list. Values
// live in a Config (engine/config/Config.h), not in the declaration.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace lpv::engine {

enum class SettingType { Bool, Int, Float, Enum, String, Vec3 };
std::string_view settingTypeName(SettingType t);

// Enum values are held by name.
using SettingValue = std::variant<bool, int64_t, double, std::string, glm::vec3>;

// When a change made while running takes effect.
enum class Apply { NextFrame, Restart };

struct SettingDecl {
    std::string name;
    SettingType type = SettingType::Int;
    SettingValue defaultValue;
    double min = 0.0, max = 0.0;      // Int, Float and Vec3 (each component); min > max: unbounded
    std::vector<std::string> choices; // Enum only
    std::string keyword;              // Float only: a word accepted instead of a number ("auto")
    std::string help;
    Apply apply = Apply::NextFrame;
    uint32_t index = 0; // registration order, the slot in a Config

    // "int in [16, 64]", "one of: rgba8, rgba16f", "vec3": what a value must be.
    std::string expected() const;
    std::string format(const SettingValue& v) const;
};

// The candidate closest to `name` (edit distance), or empty when none is close enough to be a
// likely misspelling: the "did you mean" of settings and of command-line options.
std::string nearestName(std::string_view name, const std::vector<std::string>& candidates);

class SettingRegistry {
public:
    static SettingRegistry& global();
    const SettingDecl& add(SettingDecl decl); // throws std::logic_error on a duplicate name
    const SettingDecl* find(std::string_view name) const;
    // The registered name closest to `name` (edit distance), or empty when nothing is close.
    std::string nearest(std::string_view name) const;
    // Whether `name` is a table of settings in TOML: some setting's name starts with "name.".
    bool isTable(std::string_view name) const;
    // The table name closest to `name`, as nearest() does for settings.
    std::string nearestTable(std::string_view name) const;
    // Sorted by name.
    std::vector<const SettingDecl*> all() const;
    // The setting whose name has the most dotted parts (the first by name among equals), or null.
    const SettingDecl* deepest() const;
    size_t size() const { return decls_.size(); }

private:
    std::vector<SettingDecl*> decls_;
};

class BoolSetting {
public:
    BoolSetting(std::string_view name, bool def, std::string_view help, Apply apply = Apply::NextFrame);
    const SettingDecl& decl() const { return *decl_; }

private:
    const SettingDecl* decl_;
};

class IntSetting {
public:
    IntSetting(std::string_view name, int64_t def, int64_t min, int64_t max, std::string_view help,
               Apply apply = Apply::NextFrame);
    const SettingDecl& decl() const { return *decl_; }

private:
    const SettingDecl* decl_;
};

class FloatSetting {
public:
    FloatSetting(std::string_view name, double def, double min, double max, std::string_view help,
                 Apply apply = Apply::NextFrame);
    const SettingDecl& decl() const { return *decl_; }

private:
    const SettingDecl* decl_;
};

// A number, or the word "auto" for a value the engine chooses itself (Config::get gives nullopt).
class AutoFloatSetting {
public:
    // `def`: nullopt for auto.
    AutoFloatSetting(std::string_view name, std::optional<double> def, double min, double max,
                     std::string_view help, Apply apply = Apply::NextFrame);
    const SettingDecl& decl() const { return *decl_; }

private:
    const SettingDecl* decl_;
};

class StringSetting {
public:
    StringSetting(std::string_view name, std::string_view def, std::string_view help,
                  Apply apply = Apply::NextFrame);
    const SettingDecl& decl() const { return *decl_; }

private:
    const SettingDecl* decl_;
};

class Vec3Setting {
public:
    Vec3Setting(std::string_view name, glm::vec3 def, std::string_view help, Apply apply = Apply::NextFrame);
    // Each component in [min, max] (a colour or an intensity cannot be negative).
    Vec3Setting(std::string_view name, glm::vec3 def, double min, double max, std::string_view help,
                Apply apply = Apply::NextFrame);
    const SettingDecl& decl() const { return *decl_; }

private:
    const SettingDecl* decl_;
};

const SettingDecl& registerEnumSetting(std::string_view name, std::string_view def,
                                       std::vector<std::string> choices, std::string_view help, Apply apply);

// An enum setting maps names to values of E; the names are what files and the command line use.
template <typename E> class EnumSetting {
public:
    EnumSetting(std::string_view name, E def, std::initializer_list<std::pair<E, const char*>> choices,
                std::string_view help, Apply apply = Apply::NextFrame)
        : values_(choices) {
        std::vector<std::string> names;
        std::string defName;
        for (const auto& [value, n] : choices) {
            names.emplace_back(n);
            if (value == def) defName = n;
        }
        decl_ = &registerEnumSetting(name, defName, std::move(names), help, apply);
    }
    const SettingDecl& decl() const { return *decl_; }
    E fromName(const std::string& n) const {
        for (const auto& [value, name] : values_)
            if (n == name) return value;
        return values_.front().first; // unreachable: Config only stores declared names
    }
    const char* nameOf(E e) const {
        for (const auto& [value, name] : values_)
            if (value == e) return name;
        return "?";
    }

private:
    std::vector<std::pair<E, const char*>> values_;
    const SettingDecl* decl_;
};

} // namespace lpv::engine
