// Setting declarations and the registry they join at static initialisation.
#include "engine/config/Setting.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace lpv::engine {

std::string_view settingTypeName(SettingType t) {
    switch (t) {
    case SettingType::Bool:
        return "bool";
    case SettingType::Int:
        return "int";
    case SettingType::Float:
        return "float";
    case SettingType::Enum:
        return "enum";
    case SettingType::String:
        return "string";
    case SettingType::Vec3:
        return "vec3";
    }
    return "?";
}

namespace {
std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}
} // namespace

std::string SettingDecl::expected() const {
    switch (type) {
    case SettingType::Bool:
        return "a bool (true or false)";
    case SettingType::Int:
        return min <= max ? "an integer in [" + number(min) + ", " + number(max) + "]" : "an integer";
    case SettingType::Float:
        return (min <= max ? "a number in [" + number(min) + ", " + number(max) + "]"
                           : std::string("a number")) +
               (keyword.empty() ? "" : " or " + keyword);
    case SettingType::Enum: {
        std::string s = "one of: ";
        for (size_t i = 0; i < choices.size(); ++i)
            s += (i ? ", " : "") + choices[i];
        return s;
    }
    case SettingType::String:
        return "a string";
    case SettingType::Vec3:
        return std::string("three numbers") +
               (min <= max ? " in [" + number(min) + ", " + number(max) + "]" : std::string()) +
               " ([x, y, z] in TOML, x,y,z on the command line)";
    }
    return "?";
}

std::string SettingDecl::format(const SettingValue& v) const {
    return std::visit(
        [](const auto& x) -> std::string {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, bool>)
                return x ? "true" : "false";
            else if constexpr (std::is_same_v<T, int64_t>)
                return std::to_string(x);
            else if constexpr (std::is_same_v<T, double>)
                return number(x);
            else if constexpr (std::is_same_v<T, std::string>)
                return x;
            else
                return number(x.x) + "," + number(x.y) + "," + number(x.z);
        },
        v);
}

SettingRegistry& SettingRegistry::global() {
    static SettingRegistry registry;
    return registry;
}

const SettingDecl& SettingRegistry::add(SettingDecl decl) {
    if (find(decl.name)) throw std::logic_error("setting '" + decl.name + "' is declared twice");
    decl.index = uint32_t(decls_.size());
    // Declarations live as long as the process; the registry owns them.
    decls_.push_back(new SettingDecl(std::move(decl)));
    return *decls_.back();
}

const SettingDecl* SettingRegistry::find(std::string_view name) const {
    for (const SettingDecl* d : decls_)
        if (d->name == name) return d;
    return nullptr;
}

namespace {
size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

// The candidate closest to `name`, or empty when none is close enough to be a likely typo.
std::string closest(std::string_view name, const std::vector<std::string_view>& candidates) {
    std::string best;
    size_t bestDistance = std::max<size_t>(3, name.size() / 3) + 1; // beyond this, no suggestion
    for (const std::string_view c : candidates) {
        // The lengths' difference is a lower bound on the distance: a 1 MB name costs nothing.
        const size_t lengthDifference =
            name.size() > c.size() ? name.size() - c.size() : c.size() - name.size();
        if (lengthDifference >= bestDistance) continue;
        const size_t dist = editDistance(name, c);
        if (dist < bestDistance) {
            bestDistance = dist;
            best = c;
        }
    }
    return best;
}
} // namespace

std::string SettingRegistry::nearest(std::string_view name) const {
    std::vector<std::string_view> names;
    for (const SettingDecl* d : decls_)
        names.emplace_back(d->name);
    return closest(name, names);
}

bool SettingRegistry::isTable(std::string_view name) const {
    for (const SettingDecl* d : decls_)
        if (d->name.size() > name.size() && d->name.starts_with(name) && d->name[name.size()] == '.')
            return true;
    return false;
}

std::string SettingRegistry::nearestTable(std::string_view name) const {
    // Every dotted prefix of a setting's name: "gi.debug_slice" gives "gi".
    std::vector<std::string_view> tables;
    for (const SettingDecl* d : decls_)
        for (size_t dot = d->name.find('.'); dot != std::string::npos; dot = d->name.find('.', dot + 1))
            tables.emplace_back(std::string_view(d->name).substr(0, dot));
    return closest(name, tables);
}

std::string nearestName(std::string_view name, const std::vector<std::string>& candidates) {
    return closest(name, std::vector<std::string_view>(candidates.begin(), candidates.end()));
}

std::vector<const SettingDecl*> SettingRegistry::all() const {
    std::vector<const SettingDecl*> out(decls_.begin(), decls_.end());
    std::sort(out.begin(), out.end(), [](auto* a, auto* b) { return a->name < b->name; });
    return out;
}

const SettingDecl* SettingRegistry::deepest() const {
    const SettingDecl* best = nullptr;
    size_t bestParts = 0;
    for (const SettingDecl* d : all()) {
        const size_t parts = size_t(std::count(d->name.begin(), d->name.end(), '.')) + 1;
        if (parts > bestParts) {
            best = d;
            bestParts = parts;
        }
    }
    return best;
}

namespace {
const SettingDecl& declare(std::string_view name, SettingType type, SettingValue def, double min, double max,
                           std::string_view help, Apply apply, std::vector<std::string> choices = {}) {
    SettingDecl d;
    d.name = name;
    d.type = type;
    d.defaultValue = std::move(def);
    d.min = min;
    d.max = max;
    d.help = help;
    d.apply = apply;
    d.choices = std::move(choices);
    return SettingRegistry::global().add(std::move(d));
}
} // namespace

BoolSetting::BoolSetting(std::string_view name, bool def, std::string_view help, Apply apply)
    : decl_(&declare(name, SettingType::Bool, def, 1, 0, help, apply)) {}

IntSetting::IntSetting(std::string_view name, int64_t def, int64_t min, int64_t max, std::string_view help,
                       Apply apply)
    : decl_(&declare(name, SettingType::Int, def, double(min), double(max), help, apply)) {}

FloatSetting::FloatSetting(std::string_view name, double def, double min, double max, std::string_view help,
                           Apply apply)
    : decl_(&declare(name, SettingType::Float, def, min, max, help, apply)) {}

AutoFloatSetting::AutoFloatSetting(std::string_view name, std::optional<double> def, double min, double max,
                                   std::string_view help, Apply apply)
    : decl_([&]() -> const SettingDecl* {
          SettingDecl d;
          d.name = name;
          d.type = SettingType::Float;
          d.defaultValue = def ? SettingValue(*def) : SettingValue(std::string("auto"));
          d.min = min;
          d.max = max;
          d.help = help;
          d.apply = apply;
          d.keyword = "auto";
          return &SettingRegistry::global().add(std::move(d));
      }()) {}

StringSetting::StringSetting(std::string_view name, std::string_view def, std::string_view help, Apply apply)
    : decl_(&declare(name, SettingType::String, std::string(def), 1, 0, help, apply)) {}

Vec3Setting::Vec3Setting(std::string_view name, glm::vec3 def, std::string_view help, Apply apply)
    : decl_(&declare(name, SettingType::Vec3, def, 1, 0, help, apply)) {}

Vec3Setting::Vec3Setting(std::string_view name, glm::vec3 def, double min, double max, std::string_view help,
                         Apply apply)
    : decl_(&declare(name, SettingType::Vec3, def, min, max, help, apply)) {}

const SettingDecl& registerEnumSetting(std::string_view name, std::string_view def,
                                       std::vector<std::string> choices, std::string_view help, Apply apply) {
    return declare(name, SettingType::Enum, std::string(def), 1, 0, help, apply, std::move(choices));
}

} // namespace lpv::engine
