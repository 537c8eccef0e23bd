// Config: layering (defaults < files in order < --set), every error class with file and line, and
// staged changes that apply at the next frame.
#include "engine/config/Config.h"
#include "engine/config/SettingsHelp.h"

#include <doctest/doctest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

using namespace lpv::engine;

namespace {

enum class Format { Rgba8, Rgba16f };

// Declared here as a subsystem would declare them.
const BoolSetting kEnabled{"cfgtest.enabled", false, "Turns the feature on"};
const IntSetting kGrid{"cfgtest.grid_size", 32, 16, 64, "Cells per axis"};
const FloatSetting kScale{"cfgtest.scale", 1.0, 0.0, 10.0, "A scale"};
const StringSetting kName{"cfgtest.name", "box", "A name"};
const Vec3Setting kDir{"cfgtest.sun_direction", {0.0f, -1.0f, 0.0f}, "Where the sun shines"};
const EnumSetting<Format> kFormat{"cfgtest.format",
                                  Format::Rgba16f,
                                  {{Format::Rgba8, "rgba8"}, {Format::Rgba16f, "rgba16f"}},
                                  "Storage format"};
const IntSetting kRestart{"cfgtest.window_count", 1, 1, 4, "Windows", Apply::Restart};
const Vec3Setting kTint{"cfgtest.tint", {1.0f, 1.0f, 1.0f}, 0.0, 10.0, "A colour, never negative"};

std::string errorOf(auto&& f) {
    try {
        f();
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "(no error)";
}

std::string writeTemp(const std::string& name, const std::string& text) {
    const std::string path = "/tmp/lpv_cfgtest_" + name;
    std::ofstream(path) << text;
    return path;
}

} // namespace

TEST_CASE("config: defaults") {
    Config c;
    CHECK(c.get(kEnabled) == false);
    CHECK(c.get(kGrid) == 32);
    CHECK(c.get(kFormat) == Format::Rgba16f);
    CHECK(c.get(kDir).y == -1.0f);
    CHECK(c.origin(kGrid.decl()) == "default");
}

TEST_CASE("config: files layer in order, then --set overrides them") {
    const std::string a =
        writeTemp("a.toml", "[cfgtest]\nenabled = true\ngrid_size = 48\nname = \"atrium\"\n");
    const std::string b =
        writeTemp("b.toml", "cfgtest.grid_size = 24\ncfgtest.sun_direction = [0.5, -1, 0.25]\n");
    Config c;
    c.loadFile(a);
    c.loadFile(b);
    CHECK(c.get(kEnabled) == true);
    CHECK(c.get(kGrid) == 24); // the later file wins
    CHECK(c.origin(kGrid.decl()) == b + ":1");
    CHECK(c.get(kName) == "atrium");
    CHECK(c.get(kDir).x == 0.5f);
    c.applyOverride("cfgtest.grid_size=64");
    c.applyOverride("cfgtest.format=rgba8");
    c.applyOverride("cfgtest.sun_direction=1,2,3");
    CHECK(c.get(kGrid) == 64);
    CHECK(c.origin(kGrid.decl()) == "--set");
    CHECK(c.get(kFormat) == Format::Rgba8);
    CHECK(c.get(kDir).z == 3.0f);
    CHECK(c.get(kScale) == 1.0); // untouched
}

TEST_CASE("config: an unknown key is an error naming the file, the line and the nearest key") {
    Config c;
    const std::string e =
        errorOf([&] { c.loadString("[cfgtest]\nenabled = true\ngrid_sise = 40\n", "game.toml"); });
    CHECK(e == "game.toml:3: unknown setting 'cfgtest.grid_sise' (did you mean 'cfgtest.grid_size'?)");
    const std::string far = errorOf([&] { c.loadString("zzzzzzzz.qqqqqq = 1\n", "game.toml"); });
    CHECK(far.find("game.toml:1: unknown setting 'zzzzzzzz.qqqqqq'") == 0);
    CHECK(far.find("did you mean") == std::string::npos);
    CHECK(errorOf([&] { c.applyOverride("cfgtest.enabeld=true"); }) ==
          "--set: unknown setting 'cfgtest.enabeld' (did you mean 'cfgtest.enabled'?)");
}

TEST_CASE("config: a wrong type names what was expected") {
    Config c;
    CHECK(errorOf([&] { c.loadString("\n[cfgtest]\ngrid_size = \"big\"\n", "t.toml"); }) ==
          "t.toml:3: 'cfgtest.grid_size' has a string value: expected an integer in [16, 64]");
    CHECK(errorOf([&] { c.loadString("cfgtest.enabled = 1\n", "t.toml"); }) ==
          "t.toml:1: 'cfgtest.enabled' has an integer value: expected a bool (true or false)");
    CHECK(errorOf([&] { c.loadString("cfgtest.sun_direction = [1, 2]\n", "t.toml"); }).find("t.toml:1:") ==
          0);
    CHECK(errorOf([&] { c.applyOverride("cfgtest.scale=fast"); }) ==
          "--set: 'cfgtest.scale' = 'fast': expected a number in [0, 10]");
    CHECK(errorOf([&] { c.applyOverride("cfgtest.grid_size"); }).find("expected key=value") !=
          std::string::npos);
}

TEST_CASE("config: out of range values and unknown enum names are errors") {
    Config c;
    CHECK(errorOf([&] { c.loadString("cfgtest.grid_size = 65\n", "t.toml"); }) ==
          "t.toml:1: 'cfgtest.grid_size' = 65: expected an integer in [16, 64]");
    CHECK(errorOf([&] { c.applyOverride("cfgtest.grid_size=8"); }) ==
          "--set: 'cfgtest.grid_size' = '8': expected an integer in [16, 64]");
    CHECK(errorOf([&] { c.loadString("cfgtest.format = \"bc7\"\n", "t.toml"); }) ==
          "t.toml:1: 'cfgtest.format' = bc7: expected one of: rgba8, rgba16f");
    CHECK(c.get(kGrid) == 32); // a refused value changes nothing
}

TEST_CASE("config: malformed TOML names the file and line") {
    Config c;
    const std::string e =
        errorOf([&] { c.loadString("[cfgtest]\nenabled = true\ngrid_size = = 3\n", "broken.toml"); });
    CHECK(e.find("broken.toml:3: malformed TOML") == 0);
    CHECK(errorOf([&] { c.loadFile("/nonexistent/game.toml"); }) ==
          "/nonexistent/game.toml: cannot read the config file: No such file or directory");
}

// toml++ put an invalid byte at the start of a line on the line before it.
TEST_CASE("config: invalid UTF-8 is reported on its own line") {
    Config c;
    for (const char* bad : {"\xff", "\xc0\xaf", "\xed\xa0\x80", "\xf4\x90\x80\x80", "\xe2\x82"}) {
        CAPTURE(std::string(bad));
        const std::string atStart = errorOf(
            [&] { c.loadString(std::string("[cfgtest]\nenabled = true\n") + bad + " = 3\n", "utf8.toml"); });
        CHECK(atStart.find("utf8.toml:3: malformed TOML") == 0);
        const std::string inComment = errorOf([&] {
            c.loadString(std::string("[cfgtest]\nenabled = true # ") + bad + "\ngrid_size = 20\n",
                         "utf8.toml");
        });
        CHECK(inComment.find("utf8.toml:2: malformed TOML") == 0);
    }
    // Valid multi-byte text is not an error where TOML allows it.
    CHECK_NOTHROW(
        c.loadString("[cfgtest]\nname = \"caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x99\x82\"\n", "utf8.toml"));
}

TEST_CASE(
    "config: a path that opens but cannot be read is an error with the OS's reason, not an empty file") {
    const std::string dir = "/tmp/lpv_cfgtest_dir.toml";
    std::filesystem::create_directories(dir);
    Config c;
    CHECK_THROWS_WITH_AS(c.loadFile(dir), (dir + ": cannot read the config file: Is a directory").c_str(),
                         ConfigError);
    CHECK_THROWS_WITH_AS(c.loadFile("/proc/self/mem"),
                         "/proc/self/mem: cannot read the config file: Input/output error", ConfigError);
    std::filesystem::remove(dir);
}

TEST_CASE("config: a table, an empty one included, where a value belongs is a wrong type") {
    Config c;
    CHECK_THROWS_WITH_AS(c.loadString("[cfgtest]\ngrid_size = {}\n", "t.toml"),
                         "t.toml:2: 'cfgtest.grid_size' has a table value: expected an integer in [16, 64]",
                         ConfigError);
    CHECK(errorOf([&] { c.loadString("[cfgtest]\ngrid_size = { x = 1 }\n", "t.toml"); }) ==
          "t.toml:2: 'cfgtest.grid_size' has a table value: expected an integer in [16, 64]");
    CHECK(errorOf([&] { c.loadString("\n[cfgtest.enabled]\n", "t.toml"); }) ==
          "t.toml:2: 'cfgtest.enabled' has a table value: expected a bool (true or false)");
    CHECK(errorOf([&] { c.loadString("[[cfgtest.name]]\n", "t.toml"); }) ==
          "t.toml:1: 'cfgtest.name' has an array value: expected a string");
    CHECK(c.get(kGrid) == 32);
}

TEST_CASE("config: an empty array where a value belongs is a wrong type") {
    Config c;
    CHECK_THROWS_WITH_AS(c.loadString("cfgtest.scale = []\n", "t.toml"),
                         "t.toml:1: 'cfgtest.scale' has an array value: expected a number in [0, 10]",
                         ConfigError);
    CHECK(errorOf([&] { c.loadString("cfgtest.sun_direction = []\n", "t.toml"); }) ==
          "t.toml:1: 'cfgtest.sun_direction' has an empty array value: expected three numbers ([x, y, z] in "
          "TOML, x,y,z on the command line)");
    CHECK(errorOf([&] {
              c.loadString("cfgtest.sun_direction = [1, 2]\n", "t.toml");
          }).find("t.toml:1: 'cfgtest.sun_direction' has a 2-element array value") == 0);
}

TEST_CASE("config: an unknown table is an error, even an empty one") {
    Config c;
    CHECK_THROWS_WITH_AS(c.loadString("[cfgtest]\nenabled = true\n\n[cfgtest.bogus]\n", "game.toml"),
                         "game.toml:4: unknown table 'cfgtest.bogus' (--help-config lists the settings)",
                         ConfigError);
    CHECK(errorOf([&] { c.loadString("[cfgtst]\n", "game.toml"); }) ==
          "game.toml:1: unknown table 'cfgtst' (did you mean 'cfgtest'?)");
    CHECK(errorOf([&] { c.loadString("cfgtest = {}\n", "game.toml"); }) == "(no error)"); // known, empty
    // A table of settings written as something else: an array of tables, a value.
    CHECK(errorOf([&] { c.loadString("[[cfgtest]]\ngrid_size = 40\n", "game.toml"); }) ==
          "game.toml:1: 'cfgtest' is a table of settings, got an array");
    CHECK(errorOf([&] { c.loadString("cfgtest = 3\n", "game.toml"); }) ==
          "game.toml:1: 'cfgtest' is a table of settings, got an integer");
}

TEST_CASE("config: a bounded vec3 refuses a component out of range from a file and from --set") {
    Config c;
    CHECK_THROWS_WITH_AS(
        c.loadString("\ncfgtest.tint = [0.5, -0.1, 1]\n", "t.toml"),
        "t.toml:2: 'cfgtest.tint' = 0.5,-0.1,1: expected three numbers in [0, 10] ([x, y, z] "
        "in TOML, x,y,z on the command line)",
        ConfigError);
    CHECK(errorOf([&] { c.applyOverride("cfgtest.tint=1,1,11"); }) ==
          "--set: 'cfgtest.tint' = '1,1,11': expected three numbers in [0, 10] ([x, y, z] in TOML, x,y,z on "
          "the command line)");
    c.applyOverride("cfgtest.tint=0,0,10");
    CHECK(c.get(kTint).z == 10.0f);
    CHECK(settingsHelpText().find("cfgtest.tint (vec3, default 1,1,1, allowed [x, y, z], each 0 .. 10)") !=
          std::string::npos);
}

TEST_CASE("config: changes while running apply at the next frame") {
    Config c;
    c.stage("cfgtest.grid_size=40", "console");
    c.stage(kEnabled.decl(), true, "key G");
    CHECK(c.get(kGrid) == 32); // this frame still sees the old value
    CHECK_THROWS_AS(c.stage("cfgtest.grid_size=100", "console"), ConfigError); // checked when staged
    const auto changed = c.applyPending();
    CHECK(changed.size() == 2);
    CHECK(c.get(kGrid) == 40);
    CHECK(c.get(kEnabled));
    CHECK(c.origin(kGrid.decl()) == "console");
    CHECK(c.applyPending().empty());
    c.stage("cfgtest.grid_size=40", "console"); // same value: not a change
    CHECK(c.applyPending().empty());
}

TEST_CASE("config: help lists every setting with type, default, range and help") {
    const std::string help = settingsHelpText();
    CHECK(help.find("cfgtest.grid_size (int, default 32, allowed 16 .. 64)") != std::string::npos);
    CHECK(help.find("Cells per axis") != std::string::npos);
    CHECK(help.find("cfgtest.window_count") != std::string::npos);
    CHECK(help.find("[needs a restart]") != std::string::npos);
    const std::string table = settingsMarkdownTable();
    CHECK(table.find(
              "| `cfgtest.format` | enum | `rgba16f` | rgba8, rgba16f | next frame | Storage format |") !=
          std::string::npos);
    CHECK(kRestart.decl().apply == Apply::Restart);
}

namespace {

// "a.b.c..." with `parts` parts: "k0.k1.k2...".
std::string dottedKey(int parts) {
    std::string key = "k0";
    for (int i = 1; i < parts; ++i)
        key += ".k" + std::to_string(i % 10);
    return key;
}

} // namespace

// A key of 20,000 dotted parts (a 60 KB file) overflowed the stack in the loader's recursion; toml++
// itself recurses on nested inline tables and arrays and in a table's destructor. Each form is refused
// before toml++ reads it, with the file, the line and the limit.
TEST_CASE("config: keys, table headers and inline tables nested thousands deep are refused, not a crash") {
    for (const int parts : {20000, 100000}) {
        INFO("parts: " << parts);
        const std::string key = dottedKey(parts);
        const std::string keyShown = key.substr(0, 80) + "... (" + std::to_string(key.size()) + " bytes)";
        const std::string deep =
            " is nested " + std::to_string(parts) + " levels deep; settings are at most ";
        Config c;
        const std::string dotted = errorOf([&] { c.loadString("\n" + key + " = 1\n", "deep.toml"); });
        CHECK(dotted.starts_with("deep.toml:2: key '" + keyShown + "'" + deep));
        const std::string header = errorOf([&] { c.loadString("[" + key + "]\nx = 1\n", "deep.toml"); });
        CHECK(header.starts_with("deep.toml:1: key '" + keyShown + "'" + deep));
        // "k = {k = {k = ... 1}}", a key `parts` levels deep.
        std::string inlineTables;
        for (int i = 0; i + 1 < parts; ++i)
            inlineTables += "k = {";
        inlineTables += "k = 1" + std::string(size_t(parts - 1), '}');
        const std::string nested = errorOf([&] { c.loadString("\n\n" + inlineTables + "\n", "deep.toml"); });
        // Refused at the first key deeper than any setting, before the rest is read.
        CHECK(nested.starts_with("deep.toml:3: key 'k.k.k"));
        CHECK(nested.find(" levels deep; settings are at most ") != std::string::npos);
        // Arrays nested as deep in a value.
        const std::string arrays =
            "cfgtest.tint = " + std::string(size_t(parts), '[') + std::string(size_t(parts), ']') + "\n";
        CHECK(errorOf([&] { c.loadString(arrays, "deep.toml"); }) ==
              "deep.toml:1: the value of 'cfgtest.tint' has arrays nested more than 64 levels deep; a "
              "setting's value is one value or one array ([x, y, z])");
        CHECK(c.origin(kTint.decl()) == "default");
    }
}

TEST_CASE("config: a key a few levels deeper than any setting names the depth; quoted dots are one part") {
    Config c;
    CHECK(
        errorOf([&] { c.loadString("[cfgtest.grid]\nsize.x.y.z.w = 1\n", "d.toml"); })
            .starts_with("d.toml:2: key 'cfgtest.grid.size.x.y.z.w' is nested 7 levels deep; settings are at "
                         "most "));
    // A little deeper than any setting is more likely a typo: the nearest name is worth more.
    CHECK(errorOf([&] { c.loadString("cfgtest.grid.size = 1\n", "d.toml"); }) ==
          "d.toml:1: unknown setting 'cfgtest.grid.size' (did you mean 'cfgtest.grid_size'?)");
    // A dot inside a quoted key and in a float value counts no level.
    c.loadString("[cfgtest]\n\"scale\" = 1.5 # a.b.c.d.e\nname = \"a.b.c.d.e.f\"\n", "q.toml");
    CHECK(c.get(kScale) == 1.5);
    CHECK(c.get(kName) == "a.b.c.d.e.f");
    CHECK(errorOf([&] { c.loadString("[cfgtest]\n\"sc.ale\" = 1.5\n", "q.toml"); }) ==
          "q.toml:2: unknown setting 'cfgtest.sc.ale' (did you mean 'cfgtest.scale'?)");
}

// A 1 MB value or key was echoed whole in the error: it is cut, and says how long it was.
TEST_CASE("config: a very long value or key is cut short in the error") {
    Config c;
    const std::string value(1 << 20, 'x');
    const std::string cut = std::string(80, 'x') + "... (1048576 bytes)";
    CHECK(errorOf([&] { c.loadString("cfgtest.format = \"" + value + "\"\n", "long.toml"); }) ==
          "long.toml:1: 'cfgtest.format' = " + cut + ": expected one of: rgba8, rgba16f");
    CHECK(errorOf([&] { c.applyOverride("cfgtest.format=" + value); }) ==
          "--set: 'cfgtest.format' = '" + cut + "': expected one of: rgba8, rgba16f");
    CHECK(errorOf([&] { c.loadString("cfgtest." + value + " = 1\n", "long.toml"); }) ==
          "long.toml:1: unknown setting 'cfgtest." + std::string(72, 'x') +
              "... (1048584 bytes)' "
              "(--help-config lists them all)");
    CHECK(errorOf([&] { c.applyOverride(value); }) == "--set: '" + cut + "': expected key=value");
}
