// Text and Markdown listings of the setting registry.
#include "engine/config/SettingsHelp.h"

#include "engine/config/Setting.h"

#include <sstream>

namespace lpv::engine {
namespace {

std::string allowed(const SettingDecl& d) {
    switch (d.type) {
    case SettingType::Int:
    case SettingType::Float: {
        if (d.min > d.max) return d.keyword.empty() ? "any" : "any, " + d.keyword;
        std::ostringstream s;
        s << d.min << " .. " << d.max;
        if (!d.keyword.empty()) s << ", " << d.keyword;
        return s.str();
    }
    case SettingType::Enum: {
        std::string s;
        for (size_t i = 0; i < d.choices.size(); ++i)
            s += (i ? ", " : "") + d.choices[i];
        return s;
    }
    case SettingType::Bool:
        return "true, false";
    case SettingType::String:
        return "text";
    case SettingType::Vec3: {
        if (d.min > d.max) return "[x, y, z]";
        std::ostringstream s;
        s << "[x, y, z], each " << d.min << " .. " << d.max;
        return s.str();
    }
    }
    return "";
}

} // namespace

std::string settingsHelpText() {
    std::ostringstream out;
    out << "Settings (set in a TOML file given with --config, or with --set name=value):\n\n";
    for (const SettingDecl* d : SettingRegistry::global().all()) {
        out << "  " << d->name << " (" << settingTypeName(d->type) << ", default "
            << d->format(d->defaultValue) << ", allowed " << allowed(*d) << ")\n      " << d->help
            << (d->apply == Apply::Restart ? " [needs a restart]" : "") << "\n";
    }
    return out.str();
}

std::string settingsMarkdownTable() {
    std::ostringstream out;
    out << "| setting | type | default | allowed | applies | description |\n";
    out << "|---|---|---|---|---|---|\n";
    for (const SettingDecl* d : SettingRegistry::global().all()) {
        out << "| `" << d->name << "` | " << settingTypeName(d->type) << " | `" << d->format(d->defaultValue)
            << "` | " << allowed(*d) << " | " << (d->apply == Apply::Restart ? "restart" : "next frame")
            << " | " << d->help << " |\n";
    }
    return out.str();
}

} // namespace lpv::engine
