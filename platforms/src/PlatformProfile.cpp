// Loading platform profiles from TOML, strictly: every key known, every key present.
#include "platforms/PlatformProfile.h"

#include "platforms/Platform.h"

#include "BuiltinProfiles.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <stdexcept>
#include <type_traits>

namespace lpv::platforms {

bool PlatformProfile::allowsShFormat(std::string_view format) const {
    return std::find(shFormats.begin(), shFormats.end(), format) != shFormats.end();
}

namespace {

struct Field {
    std::function<bool(const toml::node&, PlatformProfile&)> read; // false: wrong type or value
    const char* expected;
};

// Budgets and sizes: 0 would make every frame over budget or no volume fit, with no word why.
template <typename T> Field positive(T PlatformProfile::*member) {
    return {[member](const toml::node& n, PlatformProfile& p) {
                if (!n.is_number()) return false;
                const double v = *n.value<double>();
                // Within the field's type, and whole where it counts (a size, bytes).
                if (!(v > 0) || v > double(std::numeric_limits<T>::max())) return false;
                if (std::is_integral_v<T> && std::floor(v) != v) return false;
                p.*member = T(v);
                return true;
            },
            std::is_integral_v<T> ? "a positive integer" : "a positive number"};
}

Field throughput(double Throughput::*member) {
    return {[member](const toml::node& n, PlatformProfile& p) {
                if (!n.is_number() || *n.value<double>() < 0) return false;
                p.throughput.*member = *n.value<double>();
                return true;
            },
            "a non-negative number"};
}

Field text(std::string PlatformProfile::*member) {
    return {[member](const toml::node& n, PlatformProfile& p) {
                if (!n.is_string()) return false;
                p.*member = *n.value<std::string>();
                return true;
            },
            "a string"};
}

// A name the log and the report show the profile by: an empty one would show nothing.
Field nonEmptyText(std::string PlatformProfile::*member) {
    return {[member](const toml::node& n, PlatformProfile& p) {
                if (!n.is_string() || n.value<std::string>()->empty()) return false;
                p.*member = *n.value<std::string>();
                return true;
            },
            "a non-empty string"};
}

const std::map<std::string, Field>& fields() {
    static const std::map<std::string, Field> f = {
        {"name", nonEmptyText(&PlatformProfile::name)},
        {"description", text(&PlatformProfile::description)},
        {"frame.target_ms", positive(&PlatformProfile::frameBudgetMs)},
        {"gi.budget_ms", positive(&PlatformProfile::giBudgetMs)},
        {"gi.time",
         {[](const toml::node& n, PlatformProfile& p) {
              const auto v = n.value<std::string>();
              if (!n.is_string() || (*v != "predicted" && *v != "measured")) return false;
              p.giTimePredicted = *v == "predicted";
              return true;
          },
          "\"predicted\" (from the [throughput] figures) or \"measured\" (on this device)"}},
        {"gi.memory_budget_bytes", positive(&PlatformProfile::giMemoryBudgetBytes)},
        {"gi.max_volume_size", positive(&PlatformProfile::maxVolumeSize)},
        {"gi.sh_formats",
         {[](const toml::node& n, PlatformProfile& p) {
              const toml::array* a = n.as_array();
              if (!a || a->empty()) return false;
              for (const toml::node& e : *a) {
                  const auto s = e.value<std::string>();
                  if (!s || (*s != "rgba8" && *s != "rgba16f" && *s != "rgba32f")) return false;
                  p.shFormats.push_back(*s);
              }
              return true;
          },
          "a non-empty array of \"rgba8\", \"rgba16f\", \"rgba32f\""}},
        {"memory.gpu_bytes", positive(&PlatformProfile::gpuMemoryBytes)},
        {"throughput.alu_gflops", throughput(&Throughput::aluGflops)},
        {"throughput.texel_rate_g", throughput(&Throughput::texelRateG)},
        {"throughput.fill_rate_gpix", throughput(&Throughput::fillRateGpix)},
        {"throughput.memory_gbs", throughput(&Throughput::memoryGBs)},
        {"throughput.edram_gbs", throughput(&Throughput::edramGBs)},
        {"throughput.triangle_rate_m", throughput(&Throughput::triangleRateM)},
        {"throughput.texture_blocks_alu",
         {[](const toml::node& n, PlatformProfile& p) {
              if (!n.is_boolean()) return false;
              p.throughput.textureBlocksAlu = *n.value<bool>();
              return true;
          },
          "true or false"}},
    };
    return f;
}

// Whether some key lives under `name`: "throughput" for "throughput.alu_gflops".
bool isTable(const std::string& name) {
    for (const auto& [key, field] : fields())
        if (key.starts_with(name + ".")) return true;
    return false;
}

[[noreturn]] void fail(const std::string& source, const toml::node* n, const std::string& message) {
    const std::string where = n ? source + ":" + std::to_string(n->source().begin.line) : source;
    throw std::runtime_error(where + ": " + message);
}

void walk(const toml::table& t, const std::string& prefix, const std::string& source, PlatformProfile& p,
          std::vector<std::string>& seen) {
    for (const auto& [key, node] : t) {
        const std::string name =
            prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
        const auto it = fields().find(name);
        const toml::table* sub = node.as_table();
        if (sub && it == fields().end()) {
            // An empty table names no keys; it must still be one of the profile's tables.
            if (sub->empty() && !isTable(name))
                fail(source, &node, "unknown platform profile table '" + name + "'");
            walk(*sub, name, source, p, seen);
            continue;
        }
        if (it == fields().end()) fail(source, &node, "unknown platform profile key '" + name + "'");
        if (!it->second.read(node, p)) fail(source, &node, "'" + name + "': expected " + it->second.expected);
        seen.push_back(name);
    }
}

} // namespace

PlatformProfile parsePlatformProfile(std::string_view text, const std::string& sourceName) {
    toml::table table;
    try {
        table = toml::parse(text, sourceName);
    } catch (const toml::parse_error& e) {
        throw std::runtime_error(sourceName + ":" + std::to_string(e.source().begin.line) +
                                 ": malformed TOML: " + std::string(e.description()));
    }
    PlatformProfile p;
    p.source = sourceName;
    std::vector<std::string> seen;
    walk(table, "", sourceName, p, seen);
    for (const auto& [name, field] : fields())
        if (std::find(seen.begin(), seen.end(), name) == seen.end())
            fail(sourceName, nullptr, "missing platform profile key '" + name + "'");
    return p;
}

std::vector<std::string> builtinProfileNames() {
    std::vector<std::string> names;
    for (const auto& b : builtinProfiles())
        names.emplace_back(b.name);
    return names;
}

PlatformProfile loadPlatformProfile(std::string_view nameOrPath) {
    for (const auto& b : builtinProfiles())
        if (b.name == nameOrPath)
            return parsePlatformProfile(b.toml, "platforms/profiles/" + std::string(b.name) + ".toml");
    const std::string path(nameOrPath);
    std::string text;
    if (const int error = Platform::tryReadFile(path, text)) {
        if (error != ENOENT)
            throw std::runtime_error(path +
                                     ": cannot read the platform profile file: " + std::strerror(error));
        std::string names;
        for (const auto& n : builtinProfileNames())
            names += (names.empty() ? "" : ", ") + n;
        throw std::runtime_error("platform profile '" + path + "' is neither a built-in profile (" + names +
                                 ") nor a file: " + std::strerror(error));
    }
    return parsePlatformProfile(text, path);
}

} // namespace lpv::platforms
