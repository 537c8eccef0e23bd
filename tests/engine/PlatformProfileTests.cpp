// Platform profiles: the built-in ones load with the published numbers; bad files are refused
// with file and line.
#include "engine/PlatformSettings.h"
#include "platforms/PlatformProfile.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <stdexcept>

using namespace lpv;

namespace {
std::string errorOf(auto&& f) {
    try {
        f();
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "(no error)";
}
} // namespace

TEST_CASE("platform profiles: x360, ps3 and pc load with their budgets") {
    CHECK(platforms::builtinProfileNames() == std::vector<std::string>{"x360", "ps3", "pc"});
    const auto x360 = platforms::loadPlatformProfile("x360");
    CHECK(x360.name == "x360");
    CHECK(x360.frameBudgetMs == doctest::Approx(33.333));
    CHECK(x360.giBudgetMs == doctest::Approx(3.3)); // CryEngine 3: 10% of a 30 fps frame
    CHECK(x360.gpuMemoryBytes == 512ull << 20);
    CHECK(x360.throughput.aluGflops == doctest::Approx(240.0));
    CHECK(x360.allowsShFormat("rgba8"));
    CHECK_FALSE(x360.allowsShFormat("rgba16f"));
    CHECK(x360.maxVolumeSize == 64);
    const auto ps3 = platforms::loadPlatformProfile("ps3");
    CHECK(ps3.gpuMemoryBytes == 256ull << 20);
    CHECK(ps3.throughput.memoryGBs == doctest::Approx(20.8));
    const auto pc = platforms::loadPlatformProfile("pc");
    CHECK(pc.allowsShFormat("rgba32f"));
    CHECK(pc.frameBudgetMs < x360.frameBudgetMs);
}

TEST_CASE("platform profiles: bad files name the file, the line and the problem") {
    const std::string good(R"(name = "t"
description = "d"
[frame]
target_ms = 33.3
[gi]
budget_ms = 3.3
time = "predicted"
memory_budget_bytes = 1024
sh_formats = ["rgba8"]
max_volume_size = 64
[memory]
gpu_bytes = 1
[throughput]
alu_gflops = 1
texel_rate_g = 1
fill_rate_gpix = 1
memory_gbs = 1
edram_gbs = 0
triangle_rate_m = 1
texture_blocks_alu = false
)");
    CHECK(platforms::parsePlatformProfile(good, "t.toml").giMemoryBudgetBytes == 1024);
    std::string unknown = good + "[extra]\nrops = 8\n";
    CHECK(errorOf([&] { platforms::parsePlatformProfile(unknown, "t.toml"); }) ==
          "t.toml:22: unknown platform profile key 'extra.rops'");
    std::string wrong = good;
    wrong.replace(wrong.find("budget_ms = 3.3"), 15, "budget_ms = \"x\"");
    CHECK(errorOf([&] { platforms::parsePlatformProfile(wrong, "t.toml"); }) ==
          "t.toml:6: 'gi.budget_ms': expected a positive number");
    // A zero budget would put every frame over it, each pass at 0% of it.
    std::string zero = good;
    zero.replace(zero.find("target_ms = "), 12, "target_ms = 0 #");
    CHECK(errorOf([&] {
              platforms::parsePlatformProfile(zero, "t.toml");
          }).ends_with("'frame.target_ms': expected a positive number"));
    std::string missing = good;
    missing.erase(missing.find("edram_gbs = 0\n"), 14);
    CHECK(errorOf([&] { platforms::parsePlatformProfile(missing, "t.toml"); }) ==
          "t.toml: missing platform profile key 'throughput.edram_gbs'");
    CHECK(errorOf([&] { platforms::loadPlatformProfile("wii"); }) ==
          "platform profile 'wii' is neither a built-in profile (x360, ps3, pc) nor a file: No such file or "
          "directory");
    // Empty tables name no keys, but an unknown one is still refused; so is a table for a key.
    CHECK_THROWS_WITH_AS(platforms::parsePlatformProfile(good + "\n[extra]\n", "t.toml"),
                         "t.toml:22: unknown platform profile table 'extra'", std::runtime_error);
    std::string tableForKey = good;
    tableForKey.replace(tableForKey.find("description = \"d\""), 17, "description = {}");
    CHECK(errorOf([&] { platforms::parsePlatformProfile(tableForKey, "t.toml"); }) ==
          "t.toml:2: 'description': expected a string");
    // The name is what the log and the report show the profile by.
    std::string unnamed = good;
    unnamed.replace(0, 10, "name = \"\"");
    CHECK(errorOf([&] { platforms::parsePlatformProfile(unnamed, "t.toml"); }) ==
          "t.toml:1: 'name': expected a non-empty string");
    // What the GI time budget holds: the time predicted from [throughput], or the measured time.
    CHECK(platforms::parsePlatformProfile(good, "t.toml").giTimePredicted);
    std::string measured = good;
    measured.replace(measured.find("\"predicted\""), 11, "\"measured\"");
    CHECK_FALSE(platforms::parsePlatformProfile(measured, "t.toml").giTimePredicted);
    std::string guessed = good;
    guessed.replace(guessed.find("\"predicted\""), 11, "\"guessed\"");
    CHECK(errorOf([&] { platforms::parsePlatformProfile(guessed, "t.toml"); }) ==
          "t.toml:7: 'gi.time': expected \"predicted\" (from the [throughput] figures) or \"measured\" (on "
          "this "
          "device)");
    CHECK(platforms::loadPlatformProfile("x360").giTimePredicted);
    CHECK(platforms::loadPlatformProfile("ps3").giTimePredicted);
    CHECK_FALSE(platforms::loadPlatformProfile("pc").giTimePredicted);
}

TEST_CASE("platform profiles: a path that cannot be read says so, with the OS's reason") {
    const std::string dir = "/tmp/lpv_profiletest_dir";
    std::filesystem::create_directories(dir);
    CHECK_THROWS_WITH_AS(platforms::loadPlatformProfile(dir),
                         (dir + ": cannot read the platform profile file: Is a directory").c_str(),
                         std::runtime_error);
    engine::Config config;
    config.applyOverride("platform.profile=" + dir, "--platform");
    CHECK_THROWS_WITH_AS(
        engine::activePlatformProfile(config),
        ("--platform: platform.profile: " + dir + ": cannot read the platform profile file: Is a directory")
            .c_str(),
        engine::ConfigError);
    std::filesystem::remove(dir);
}

TEST_CASE("platform profiles: platform.profile selects one, and a bad one is a config error") {
    engine::Config config;
    CHECK(engine::activePlatformProfile(config).name == "pc");
    config.applyOverride("platform.profile=ps3");
    CHECK(engine::activePlatformProfile(config).name == "ps3");
    config.applyOverride("platform.profile=dreamcast");
    CHECK_THROWS_AS(engine::activePlatformProfile(config), engine::ConfigError);
}
