// The game executable's command line: bad input exits non-zero with a message that helps.
#include <doctest/doctest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace {

struct Result {
    int exitCode = -1;
    std::string output;
};

Result runProgram(const std::string& exe, const std::string& args, const std::string& env) {
    const std::string command = env + " " + exe + " " + args + " 2>&1";
    Result r;
    FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::array<char, 512> buffer{};
    while (fgets(buffer.data(), int(buffer.size()), pipe))
        r.output += buffer.data();
    const int status = pclose(pipe);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

Result runGame(const std::string& args, const std::string& env = "") {
    return runProgram(LPV_GAME_EXE, args, env);
}

} // namespace

TEST_CASE("cli: an unknown backend name lists the valid ones and exits non-zero") {
    const Result r = runGame("--headless --backend d3d9");
    CHECK(r.exitCode != 0);
    CHECK(r.output.find("'render.backend' = 'd3d9': expected one of: auto, gl, vulkan, null") !=
          std::string::npos);
}

TEST_CASE("cli: vulkan without a driver fails clearly when fallback is not allowed") {
    const Result r =
        runGame("--headless --backend vulkan --no-fallback", "VK_DRIVER_FILES=/nonexistent/icd.json");
    CHECK(r.exitCode == 3);
    CHECK(r.output.find("vulkan") != std::string::npos);
    CHECK(r.output.find("fallback not allowed") != std::string::npos);
}

TEST_CASE("cli: vulkan without a driver falls back to gl and renders") {
    const Result r = runGame("--headless --backend vulkan --width 64 --height 64",
                             "VK_DRIVER_FILES=/nonexistent/icd.json");
    CHECK_MESSAGE(r.exitCode == 0, r.output);
    CHECK(r.output.find("falling back to 'gl'") != std::string::npos);
    CHECK(r.output.find("running on backend 'gl'") != std::string::npos);
}

TEST_CASE("cli: a config file with an unknown key names the file and line, and nothing runs") {
    const std::string path = "/tmp/lpv_cli_bad.toml";
    FILE* f = std::fopen(path.c_str(), "w");
    REQUIRE(f != nullptr);
    std::fputs("[render]\nbackend = \"gl\"\nbakcend = \"vulkan\"\n", f);
    std::fclose(f);
    const Result r = runGame("--headless --config " + path);
    CHECK(r.exitCode == 2);
    CHECK(r.output.find(path + ":3: unknown setting 'render.bakcend' (did you mean 'render.backend'?)") !=
          std::string::npos);
    CHECK(r.output.find("running on backend") == std::string::npos);
}

TEST_CASE("cli: --help-config lists the settings") {
    const Result r = runGame("--help-config");
    CHECK(r.exitCode == 0);
    CHECK(r.output.find("render.backend (enum, default auto, allowed auto, gl, vulkan, null)") !=
          std::string::npos);
}

namespace {
std::string fileBytes(const std::string& path) {
    std::string out;
    if (FILE* f = std::fopen(path.c_str(), "rb")) {
        std::array<char, 4096> buffer{};
        size_t n = 0;
        while ((n = std::fread(buffer.data(), 1, buffer.size(), f)) > 0)
            out.append(buffer.data(), n);
        std::fclose(f);
    }
    return out;
}
} // namespace

TEST_CASE("cli: gi.debug_view=indirect given at startup shows the indirect view") {
    // It used to follow only a change made while running (a key or the console): set in a file or
    // on the command line it was silently ignored.
    const std::string common = "--headless --backend gl --width 96 --height 64 --set gi.enabled=true ";
    const Result gi = runGame(common + "--set gi.debug_view=indirect --screenshot /tmp/lpv_cli_gi_view.png");
    const Result render =
        runGame(common + "--set render.debug_view=indirect --screenshot /tmp/lpv_cli_render_view.png");
    const Result final = runGame(common + "--screenshot /tmp/lpv_cli_final_view.png");
    REQUIRE_MESSAGE(gi.exitCode == 0, gi.output);
    REQUIRE_MESSAGE(render.exitCode == 0, render.output);
    REQUIRE_MESSAGE(final.exitCode == 0, final.output);
    const std::string a = fileBytes("/tmp/lpv_cli_gi_view.png"),
                      b = fileBytes("/tmp/lpv_cli_render_view.png"),
                      c = fileBytes("/tmp/lpv_cli_final_view.png");
    REQUIRE(!a.empty());
    CHECK(a == b);
    CHECK(a != c);
}

// What `./lpv.sh run` loads: the shipped sample config is valid and turns the GI on (its passes are
// in the profile report), here on the null device.
TEST_CASE("cli: the sample game's config is valid and turns GI on") {
    const Result r = runGame("--headless --backend null --frames 1 --config " LPV_SAMPLE_CONFIG
                             " --profile-out /tmp/lpv_cli_sample_profile");
    INFO(r.output);
    REQUIRE(r.exitCode == 0);
    FILE* f = std::fopen("/tmp/lpv_cli_sample_profile/summary.md", "r");
    REQUIRE(f != nullptr);
    std::string summary;
    std::array<char, 512> buffer{};
    while (std::fgets(buffer.data(), int(buffer.size()), f))
        summary += buffer.data();
    std::fclose(f);
    // The cascades propagate together (gi.cascades_together), after each cascade's injection.
    CHECK(summary.find("gi/propagate") != std::string::npos);
    CHECK(summary.find("gi/cascade0/inject") != std::string::npos);
}

// ./lpv.sh run passes its own --screenshot and --profile-out before the caller's: the last wins.
TEST_CASE("cli: --screenshot and --profile-out given twice take the last") {
    std::remove("/tmp/lpv_cli_first.png");
    std::remove("/tmp/lpv_cli_last.png");
    const Result r = runGame("--headless --backend null --frames 1 --screenshot /tmp/lpv_cli_first.png "
                             "--screenshot /tmp/lpv_cli_last.png --profile-out /tmp/lpv_cli_first_profile "
                             "--profile-out /tmp/lpv_cli_last_profile");
    INFO(r.output);
    REQUIRE(r.exitCode == 0);
    const auto exists = [](const char* path) {
        FILE* f = std::fopen(path, "r");
        if (f) std::fclose(f);
        return f != nullptr;
    };
    CHECK(exists("/tmp/lpv_cli_last.png"));
    CHECK(!exists("/tmp/lpv_cli_first.png"));
    CHECK(exists("/tmp/lpv_cli_last_profile/summary.md"));
    CHECK(!exists("/tmp/lpv_cli_first_profile/summary.md"));
}

namespace {
// The smallest run: no GPU, a tiny frame, one frame.
const std::string kTinyRun = "--headless --backend null --width 160 --height 90 --frames 1 ";

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// `link` becomes a symbolic link to /dev/full: opening it works, writing fails with ENOSPC.
void linkToFullDevice(const std::string& link) {
    std::filesystem::create_directories(std::filesystem::path(link).parent_path());
    std::filesystem::remove(link);
    REQUIRE(symlink("/dev/full", link.c_str()) == 0);
}
} // namespace

TEST_CASE("cli: a screenshot that cannot be written is an error naming the path and the reason") {
    // stbi_write_png and SaveEXR ignore fclose errors: a full disk used to pass for success.
    for (const std::string path :
         {"/tmp/lpv_cli_full/a.png", "/tmp/lpv_cli_full/a.pfm", "/tmp/lpv_cli_full/a.exr"}) {
        linkToFullDevice(path);
        const Result r = runGame(kTinyRun + "--screenshot " + path);
        INFO(r.output);
        CHECK(r.exitCode == 1);
        CHECK(contains(r.output, "cannot write " + path + ": No space left on device"));
        CHECK(!contains(r.output, "game: wrote"));
    }
}

TEST_CASE("cli: a screenshot type other than .png, .exr or .pfm is refused before anything runs") {
    // Such paths used to be written as PNG whatever they were called.
    const Result jpg = runGame(kTinyRun + "--screenshot /tmp/lpv_cli_shot.jpg");
    CHECK(jpg.exitCode == 2);
    CHECK(contains(jpg.output, "--screenshot /tmp/lpv_cli_shot.jpg: unsupported image type '.jpg' (expected "
                               ".png, .exr or .pfm)"));
    CHECK(!contains(jpg.output, "running on backend"));
    const Result bare = runGame(kTinyRun + "--screenshot /tmp/lpv_cli_shot");
    CHECK(bare.exitCode == 2);
    CHECK(
        contains(bare.output, "--screenshot /tmp/lpv_cli_shot: no image type (expected .png, .exr or .pfm)"));
    // The type is read in any case.
    std::filesystem::remove("/tmp/lpv_cli_shot.PNG");
    const Result upper = runGame(kTinyRun + "--screenshot /tmp/lpv_cli_shot.PNG");
    CHECK_MESSAGE(upper.exitCode == 0, upper.output);
    CHECK(std::filesystem::exists("/tmp/lpv_cli_shot.PNG"));
}

TEST_CASE("cli: an output path that cannot be written fails before the run, with the reason") {
    // It used to fail after every frame was rendered, and cost the other outputs.
    std::filesystem::remove_all("/tmp/lpv_cli_p1");
    const Result shot = runGame(kTinyRun + "--screenshot /proc/lpv_cli.png --profile-out /tmp/lpv_cli_p1");
    INFO(shot.output);
    CHECK(shot.exitCode == 2);
    CHECK(contains(shot.output, "error: --screenshot: cannot write /proc/lpv_cli.png: "));
    CHECK(!contains(shot.output, "running on backend"));

    FILE* f = std::fopen("/tmp/lpv_cli_not_a_folder", "w");
    REQUIRE(f != nullptr);
    std::fclose(f);
    const Result profile = runGame(kTinyRun + "--profile-out /tmp/lpv_cli_not_a_folder/profile");
    INFO(profile.output);
    CHECK(profile.exitCode == 2);
    CHECK(contains(profile.output,
                   "error: --profile-out: cannot create directory /tmp/lpv_cli_not_a_folder/profile: "));
    CHECK(!contains(profile.output, "running on backend"));
}

TEST_CASE("cli: outputs that fail at the end cost nothing else, and each failure is reported") {
    const std::string shot = "/tmp/lpv_cli_full/b.png", profile = "/tmp/lpv_cli_profile_full";
    std::filesystem::remove_all(profile);
    linkToFullDevice(shot);
    linkToFullDevice(profile + "/trace.json");
    const Result r = runGame(kTinyRun + "--screenshot " + shot + " --profile-out " + profile);
    INFO(r.output);
    CHECK(r.exitCode == 1);
    CHECK(contains(r.output, "error: cannot write " + shot + ": No space left on device"));
    CHECK(contains(r.output, "error: cannot write " + profile + "/trace.json: No space left on device"));
    CHECK(contains(r.output, "Frame profile: platform")); // the summary, printed all the same
    CHECK(std::filesystem::file_size(profile + "/summary.md") > 0);
    CHECK(std::filesystem::file_size(profile + "/summary.csv") > 0);
    CHECK(std::filesystem::file_size(profile + "/frames.svg") > 0);
}

TEST_CASE("cli: a bad command line exits 2 with CLI11's message, and a misspelt option gets a hint") {
    // CLI11's own exit codes (109, 104, 114) used to leak out instead of the documented 2.
    const Result misspelt = runGame(kTinyRun + "--widht 100");
    INFO(misspelt.output);
    CHECK(misspelt.exitCode == 2);
    CHECK(contains(misspelt.output, "--widht"));
    CHECK(contains(misspelt.output, "error: unknown option '--widht' (did you mean '--width'?)"));
    const Result assigned = runGame(kTinyRun + "--scren-shot=/tmp/x.png");
    CHECK(assigned.exitCode == 2);
    CHECK(contains(assigned.output, "error: unknown option '--scren-shot' (did you mean '--screenshot'?)"));
    const Result notANumber = runGame("--headless --backend null --frames lots");
    CHECK(notANumber.exitCode == 2);
    CHECK(contains(notANumber.output, "lots"));
    const Result noValue = runGame("--headless --backend null --scene");
    CHECK(noValue.exitCode == 2);
    CHECK(contains(noValue.output, "--scene"));
    const Result help = runGame("--help");
    CHECK(help.exitCode == 0);
    CHECK(contains(help.output, "--screenshot"));
    // An unknown option alone is named once (CLI11's message said it again).
    const Result unknown = runGame("--bogus");
    INFO(unknown.output);
    CHECK(unknown.exitCode == 2);
    CHECK(unknown.output.find("--bogus") != std::string::npos);
    CHECK(unknown.output.find("--bogus") == unknown.output.rfind("--bogus"));
    // An empty output path would write nothing, silently.
    for (const char* flag : {"--screenshot", "--profile-out"}) {
        const Result empty = runGame(kTinyRun + flag + " ''");
        INFO(empty.output);
        CHECK(empty.exitCode == 2);
        CHECK(contains(empty.output, std::string(flag) + ": expected a path, got an empty one"));
    }
}

// CLI11 gives an option written `--name=` the next argument as its value: `--profile-out=
// --frames=1` wrote the profile into a folder named "--frames=1", and `lpv_rhi_bench --backends=
// --runs=1` called --runs=1 a backend.
TEST_CASE("cli: an option with nothing after '=' is refused, not given the next argument") {
    const Result game =
        runGame("--headless --backend null --width 160 --height 90 --profile-out= --frames=1");
    INFO(game.output);
    CHECK(game.exitCode == 2);
    CHECK(contains(game.output, "error: --profile-out=: expected a value after '='"));
    CHECK(!contains(game.output, "running on backend"));
    const Result bench = runProgram(LPV_BENCH_EXE, "--backends= --parts=console", "");
    INFO(bench.output);
    CHECK(bench.exitCode == 2);
    CHECK(contains(bench.output, "error: --backends=: expected a value after '='"));
    const Result twice = runProgram(LPV_BENCH_EXE, "--backends=vulkan,vulkan --parts=console", "");
    CHECK(twice.exitCode == 2);
    CHECK(contains(twice.output, "--backends: vulkan is named twice"));
    // After `--` nothing is an option (and the game takes no arguments there, which CLI11 refuses).
    const Result ended = runGame(kTinyRun + "-- --x=");
    INFO(ended.output);
    CHECK(ended.exitCode == 2);
    CHECK(contains(ended.output, "error: unexpected argument '--x='"));
    CHECK(!contains(ended.output, "expected a value after '='"));
    const Result stray = runGame(kTinyRun + "stray");
    CHECK(stray.exitCode == 2);
    CHECK(contains(stray.output, "error: unexpected argument 'stray'"));
}

TEST_CASE("cli: --frames takes a positive number") {
    // 0 and negative counts used to fall back to the default: in a window, forever.
    for (const char* frames : {"0", "-1"}) {
        const Result r = runGame(std::string("--headless --backend null --frames ") + frames);
        INFO(r.output);
        CHECK(r.exitCode == 2);
        CHECK(contains(r.output,
                       std::string("error: --frames: expected a positive number of frames, got ") + frames));
        CHECK(!contains(r.output, "running on backend"));
    }
}

TEST_CASE("cli: --help-config takes 'markdown' or nothing") {
    // Any other word used to give the text list.
    const Result bogus = runGame("--help-config bogus");
    CHECK(bogus.exitCode == 2);
    CHECK(contains(bogus.output, "error: --help-config: expected 'markdown' or nothing, got 'bogus'"));
    CHECK(!contains(bogus.output, "render.backend"));
    const Result markdown = runGame("--help-config markdown");
    CHECK(markdown.exitCode == 0);
    CHECK(contains(markdown.output, "| `render.backend` |"));
}

TEST_CASE("cli: --no-fallback needs a named backend") {
    // With auto it used to fall back all the same, logging "falling back to 'gl'".
    const std::string expected =
        "error: --no-fallback: render.allow_fallback=false needs a named render.backend "
        "(vulkan, gl or null); auto tries vulkan, then gl";
    for (const char* backend : {"", "--backend auto "}) {
        const Result r = runGame(std::string("--headless --no-fallback ") + backend);
        INFO(r.output);
        CHECK(r.exitCode == 2);
        CHECK(contains(r.output, expected));
        CHECK(!contains(r.output, "falling back"));
        CHECK(!contains(r.output, "running on backend"));
    }
    const Result named = runGame(kTinyRun + "--no-fallback");
    CHECK_MESSAGE(named.exitCode == 0, named.output);
}

TEST_CASE("cli: without a reachable X display the game says why it runs headless") {
    // It used to run headless without a word. Nothing listens on display :4242.
    const Result r = runGame("--backend null --width 160 --height 90 --frames 1", "DISPLAY=:4242");
    INFO(r.output);
    CHECK(r.exitCode == 0);
    CHECK(contains(r.output, "[warning] game: no window (X11: Failed to open display :4242); falling back to "
                             "headless"));
    const Result strict =
        runGame("--backend null --width 160 --height 90 --frames 1 --no-fallback", "DISPLAY=:4242");
    INFO(strict.output);
    CHECK(strict.exitCode == 3);
    CHECK(contains(strict.output,
                   "error: no window (X11: Failed to open display :4242); falling back to headless "
                   "not allowed"));
    CHECK(!contains(strict.output, "running on backend"));
    // With no display named at all (a server, CI) headless is what was asked for: no warning, and
    // --no-fallback does not refuse it.
    const Result none = runGame("--backend null --width 160 --height 90 --frames 1 --no-fallback",
                                "env -u DISPLAY -u WAYLAND_DISPLAY");
    INFO(none.output);
    CHECK(none.exitCode == 0);
    CHECK(contains(none.output, "no display configured (DISPLAY is not set): headless"));
    CHECK(!contains(none.output, "[warning]"));
}

// A console change the GI refuses is undone, and the frames go on. The restored settings keep
// where they came from: gi.debug_slice's default (16) is clamped to a 16-cell volume, but restored as
// a new choice it was refused on every frame after, and the game stopped drawing.
TEST_CASE("cli: a refused console change is undone once and the frames go on") {
    // 200000 frames of the null device (about 2 s): the console's reader thread hands the lines over
    // long before the end, however busy the machine.
    const Result r =
        runGame("--headless --backend null --width 64 --height 48 --frames 200000 "
                "--set gi.enabled=true --set gi.grid_size=16 --profile-out /tmp/lpv_cli_refused",
                "printf 'gi.debug_slice=20\\n\\n# a comment\\nplatform.profile=x360  # later\\n' |");
    INFO(r.output);
    REQUIRE(r.exitCode == 0);
    size_t refusals = 0;
    for (size_t at = r.output.find("GI change refused"); at != std::string::npos;
         at = r.output.find("GI change refused", at + 1))
        ++refusals;
    CHECK(refusals == 1);
    CHECK(r.output.find("'gi.debug_slice' = 20: outside the volume") != std::string::npos);
    CHECK(r.output.find("game: gi.debug_slice = 16 (restored)") != std::string::npos);
    // The profiler and the GI took the profile at startup: a change waits for a restart, and says so.
    CHECK(r.output.find("game: platform.profile = x360 (takes effect after a restart)") != std::string::npos);
    CHECK(r.output.find("Frame profile: platform pc") != std::string::npos);
    // An empty line and a comment change nothing and say nothing; a comment after a setting is
    // left out of its value (it was read as "x360  # later").
    CHECK(r.output.find("expected key=value") == std::string::npos);
    // Every frame is drawn and checked, the refused change's too (with the settings restored).
    const size_t checked = r.output.find("frames checked ");
    REQUIRE(checked != std::string::npos);
    CHECK(std::stoi(r.output.substr(checked + 15)) == 200000);
}

// gi.debug_view=indirect moves render.debug_view along; when the change it came with is refused,
// the restore puts render.debug_view back too (it stayed on the indirect view).
TEST_CASE("cli: a refused console change undoes the view gi.debug_view moved") {
    const Result r = runGame("--headless --backend null --width 64 --height 48 --frames 200000 "
                             "--set gi.enabled=true --set gi.grid_size=16",
                             "printf 'gi.debug_view=indirect\\ngi.debug_slice=20\\n' |");
    INFO(r.output);
    REQUIRE(r.exitCode == 0);
    REQUIRE(contains(r.output, "GI change refused"));
    // The console's thread hands lines over one by one: both usually arrive in the same frame, and
    // then both are undone; else the view change was accepted a frame earlier and stays.
    if (contains(r.output, "game: gi.debug_view = none (restored)"))
        CHECK(contains(r.output, "game: render.debug_view = final (restored)"));
    else
        CHECK(!contains(r.output, "render.debug_view = final (restored)"));
}

// The report's peak memory is what the configured run allocated: the renderer used to make the
// sun's shadow map and the indirect targets at their defaults (2048^2, full resolution) before the
// first frame remade them, and the peak counted both.
TEST_CASE("cli: the report's peak memory holds no render targets made at default sizes") {
    const Result r = runGame("--headless --backend null --width 320 --height 180 --config " LPV_SAMPLE_CONFIG
                             " --set render.shadow_map_size=256 --profile-out /tmp/lpv_cli_peak");
    INFO(r.output);
    REQUIRE(r.exitCode == 0);
    // The report's memory table: "| render.shadow | 0.250 MiB | 0.250 MiB | 1 |" (current, peak).
    const std::string summary = fileBytes("/tmp/lpv_cli_peak/summary.md");
    const auto memory = [&](const std::string& category) {
        const size_t at = summary.find("| " + category + " | ", summary.find("## Memory"));
        REQUIRE(at != std::string::npos);
        const std::string line = summary.substr(at + category.size() + 5);
        const size_t next = line.find(" | ");
        REQUIRE(next != std::string::npos);
        return std::pair{std::stod(line), std::stod(line.substr(next + 3))};
    };
    const auto [shadowNow, shadowPeak] = memory("render.shadow");
    CHECK(shadowNow == doctest::Approx(0.25)); // 256^2 x 4 bytes
    CHECK(shadowPeak == shadowNow);
    // The sample config's GI looks up a quarter of the pixels (gi.resolution=half).
    const auto [lightingNow, lightingPeak] = memory("render.lighting");
    CHECK(lightingPeak == lightingNow);
}

// RGBA8 clipping is read back frames after the frame that met it; a run of one frame (what
// `./lpv.sh run` renders) reads it at its end, so it warns as a long run does.
TEST_CASE("cli: a run of one frame whose RGBA8 volumes clip says so in the log and the report") {
    const Result r =
        runGame("--headless --backend gl --width 96 --height 64 --frames 1 --config " LPV_SAMPLE_CONFIG
                " --set gi.sh_format=rgba8 --set gi.rgba8_range=4 --profile-out /tmp/lpv_cli_clip1");
    INFO(r.output);
    REQUIRE(r.exitCode == 0);
    // Which cascade meets it depends on the cell size gi.cell_size = auto chose (the coarser ones
    // gather more light a cell).
    CHECK(r.output.find("gi: RGBA8 volumes clip: cascade ") != std::string::npos);
    const std::string summary = fileBytes("/tmp/lpv_cli_clip1/summary.md");
    CHECK(summary.find("## GI RGBA8 clipping") != std::string::npos);
    CHECK(summary.find("set gi.rgba8_range to") != std::string::npos);
}

// The README's first example, as a team would copy it: it warned on the default scene that its
// RGBA8 volumes clip (1.53x the default gi.rgba8_range).
TEST_CASE("cli: the README's game.toml runs on the default scene and its volumes do not clip") {
    const std::string readme = fileBytes(LPV_README);
    const size_t begin = readme.find("# game.toml\n"), end = readme.find("```", begin);
    REQUIRE(begin != std::string::npos);
    REQUIRE(end != std::string::npos);
    const std::string path = "/tmp/lpv_cli_readme_game.toml";
    std::ofstream(path) << readme.substr(begin, end - begin);
    for (const char* backend : {"vulkan", "gl"}) {
        CAPTURE(backend);
        const Result r =
            runGame(std::string("--headless --no-fallback --width 320 --height 240 --frames 3 --backend ") +
                    backend + " --config " + path);
        INFO(r.output);
        CHECK(r.exitCode == 0);
        CHECK(contains(r.output, "platform profile 'x360'"));
        CHECK(!contains(r.output, "RGBA8 volumes clip"));
        // lavapipe rounds 3D images up past the 3 MiB (the test below); GL allocates what it plans.
        if (std::string(backend) == "gl") CHECK(!contains(r.output, "[warning]"));
    }
}

// The README's Xbox 360 example holds 2.98 MiB of the 3 MiB; a device may allocate more (lavapipe
// rounds 3D images up, CPU devices add the cascade classes). Whenever the report marks GI memory
// over budget, the log has said why.
TEST_CASE("cli: GI memory allocated beyond the budget the check passed is explained in a warning") {
    const Result r = runGame("--headless --backend vulkan --no-fallback --platform x360 --frames 1 "
                             "--set gi.enabled=true --set gi.cascades=1 --set gi.iterations=6 "
                             "--set gi.rsm_size=128 --set gi.vpl_count=1024 --set gi.sh_format=rgba8 "
                             "--profile-out /tmp/lpv_cli_gi_memory");
    INFO(r.output);
    REQUIRE(r.exitCode == 0);
    const bool over = r.output.find("of 3.000 MiB budget (OVER BUDGET)") != std::string::npos;
    const bool warned = r.output.find("gi: the device allocated") != std::string::npos;
    CHECK(over == warned);
    if (warned) CHECK(r.output.find("the budget check's count") != std::string::npos);
    // lavapipe allocates 3.14 MiB here: on this machine's CI the warning is exercised.
    WARN_MESSAGE(over, "this device allocates within the budget: the warning was not exercised");
}

// The console preset on this machine's Vulkan (lavapipe, which rounds 3D images up): it starts, its
// GI memory stays within the console's 3 MiB (the cascade classes a CPU device adds are the
// device's, not GI's), and the budget scheduler (the preset sets adapt) changes nothing.
TEST_CASE(
    "cli: the console preset runs as configured on the x360 profile: GI memory in budget, no budget step") {
    const Result r =
        runGame("--headless --backend vulkan --no-fallback --platform x360 --frames 8 --width 640 "
                "--height 360 --config " LPV_CONSOLE_PRESET " --set gi.cell_size=0.23 "
                "--profile-out /tmp/lpv_cli_console_preset");
    INFO(r.output);
    REQUIRE(r.exitCode == 0);
    CHECK(r.output.find("GI total: ") != std::string::npos);
    CHECK(r.output.find("(OVER BUDGET)\n") == std::string::npos);
    // Adapt's one note: the first frame, which makes every cascade, leaves its second bounce to
    // the next frame; no step.
    const std::string summary = fileBytes("/tmp/lpv_cli_console_preset/summary.md");
    const size_t changes = summary.find("## GI budget changes\n\n| frame | note |\n|---|---|\n");
    REQUIRE(changes != std::string::npos);
    const size_t first = summary.find("|---|---|\n", changes) + 10, second = summary.find('\n', first) + 1;
    CHECK(summary.substr(first, second - first).find("further bounces left to the next frame") !=
          std::string::npos);
    CHECK(summary.substr(second, 2) != "| ");
    CHECK(r.output.find("gi: the device allocated") == std::string::npos);
}

// --set and the shorthand flags are one list, applied in the order given: the flags used to be
// applied after every --set, whatever the order, and a flag given twice was a parse error.
TEST_CASE("cli: --set and the shorthand flags apply in the order given, the later winning") {
    // The screenshot's size, from its PNG header (IHDR: width and height, big-endian, at 16).
    const auto shotSize = [](const std::string& args) {
        const std::string shot = "/tmp/lpv_cli_order/shot.png";
        std::filesystem::remove(shot);
        const Result r = runGame("--headless --backend null --frames 1 --screenshot " + shot + " " + args);
        INFO(r.output);
        REQUIRE(r.exitCode == 0);
        unsigned char head[24] = {};
        FILE* f = std::fopen(shot.c_str(), "rb");
        REQUIRE(f != nullptr);
        REQUIRE(std::fread(head, 1, sizeof(head), f) == sizeof(head));
        std::fclose(f);
        const auto be = [&](int at) {
            return (uint32_t(head[at]) << 24) | (uint32_t(head[at + 1]) << 16) |
                   (uint32_t(head[at + 2]) << 8) | uint32_t(head[at + 3]);
        };
        return std::pair(be(16), be(20));
    };
    CHECK(shotSize("--width 140 --height 40 --set render.width=130") == std::pair(130u, 40u));
    CHECK(shotSize("--set render.width=130 --width 140 --height 40") == std::pair(140u, 40u));
    CHECK(shotSize("--width 140 --width 150 --height 40") == std::pair(150u, 40u));
    CHECK(shotSize("--set render.width=120 render.height=60 --height 50") == std::pair(120u, 50u));
    // --scene, --frames and --camera-path given twice take the last too (they were a parse error).
    const Result twice =
        runGame("--headless --backend null --width 64 --height 48 --scene atrium --scene cornell "
                "--frames 1 --frames 2 --camera-path flythrough --camera-path orbit --profile-out "
                "/tmp/lpv_cli_twice");
    INFO(twice.output);
    CHECK(twice.exitCode == 0);
    CHECK(contains(twice.output, "scene 'cornell'"));
    CHECK(contains(twice.output, "frames checked 2,"));
}

// The benchmark checks its output folder before it renders for minutes, and says when no part
// it runs writes there.
TEST_CASE("cli: lpv_bench refuses an --out it cannot write or nothing would use, and settings the GI refuses "
          "together, before it runs") {
    const auto bench = [](const std::string& args) { return runProgram(LPV_BENCH_EXE, args, ""); };
    const Result unwritable = bench("--parts=frames --backends=vulkan --out=/proc/lpv_bench_out");
    INFO(unwritable.output);
    CHECK(unwritable.exitCode == 2);
    CHECK(contains(unwritable.output, "error: --out: "));
    CHECK(!contains(unwritable.output, "## Frames")); // nothing ran
    const Result unused = bench("--parts=console --out=/tmp/lpv_bench_unused_out");
    INFO(unused.output);
    CHECK(unused.exitCode == 2);
    CHECK(contains(unused.output, "only the frames part writes files"));
    // Settings the GI refuses together fail before a device starts too, as they do in the game.
    const Result together =
        bench("--parts=frames --backends=vulkan --set gi.bounces=3 --set gi.occlusion=false");
    INFO(together.output);
    CHECK(together.exitCode == 2);
    CHECK(contains(together.output, "'gi.bounces' = 3: expected 1 while gi.occlusion is false"));
    CHECK(!contains(together.output, "## Frames"));
    // The frames part turns GI on and off itself; gi.debug_view=indirect is the game's shortcut.
    const Result off = bench("--parts=frames --backends=vulkan --set gi.enabled=false");
    CHECK(off.exitCode == 2);
    CHECK(contains(off.output, "leave gi.enabled out"));
    const Result view = bench("--parts=frames --backends=vulkan --set gi.debug_view=indirect");
    CHECK(view.exitCode == 2);
    CHECK(contains(view.output, "set render.debug_view=indirect"));
}

// A team times its own settings file in the frames part (--config, before --set): what is wrong in
// it names the file and line before a device starts, and the table's heading shows what was timed.
TEST_CASE("cli: lpv_bench --config times a settings file, and names its file and line when it is wrong") {
    const auto bench = [](const std::string& args) { return runProgram(LPV_BENCH_EXE, args, ""); };
    const std::filesystem::path dir = "/tmp/lpv_cli_bench_config";
    std::filesystem::create_directories(dir);
    const auto write = [&](const std::string& name, const std::string& text) {
        std::ofstream(dir / name) << text;
        return (dir / name).string();
    };
    const Result wrongType = bench("--parts=frames --backends=vulkan --config " +
                                   write("type.toml", "[gi]\ncascades = 2\ngrid_size = \"big\"\n"));
    INFO(wrongType.output);
    CHECK(wrongType.exitCode == 2);
    CHECK(contains(wrongType.output, "type.toml:3: 'gi.grid_size' has a string value"));
    CHECK(!contains(wrongType.output, "## Frames"));
    const Result off =
        bench("--parts=frames --backends=vulkan --config " + write("off.toml", "[gi]\n\nenabled = false\n"));
    INFO(off.output);
    CHECK(off.exitCode == 2);
    CHECK(contains(off.output, "off.toml:3: gi.enabled = false"));
    CHECK(contains(off.output, "leave gi.enabled out"));
    // --set comes after the file, as in the game.
    const Result timed = bench("--parts=frames --backends=vulkan --scenes=cornell --frames=1 --config " +
                               std::string(LPV_CONSOLE_PRESET) + " --set gi.iterations=6");
    INFO(timed.output);
    CHECK(timed.exitCode == 0);
    CHECK(contains(timed.output,
                   "GI 3 x 24^3, 6 iterations, 2 bounces, quarter resolution, rgba8, RSM 128^2, "
                   "coarse cascades every 2 frames"));
    CHECK(contains(timed.output, "gi.budget_policy = adapt (" + std::string(LPV_CONSOLE_PRESET) + ":"));
    CHECK(contains(timed.output, "of the frame (goal: at most 10%)"));
}

// Two screenshots that would hold less than asked, said in the log: the null backend's (black),
// and an HDR one of a GI debug view drawn over the tone-mapped frame.
TEST_CASE("cli: a screenshot that cannot show what was asked says so") {
    const Result black =
        runGame("--headless --backend null --width 64 --height 48 --screenshot /tmp/lpv_cli_shots/n.png");
    INFO(black.output);
    CHECK(black.exitCode == 0);
    CHECK(contains(black.output,
                   "[warning] game: the 'null' backend draws nothing: /tmp/lpv_cli_shots/n.png is black"));
    const Result hdr = runGame("--headless --backend null --width 64 --height 48 --set gi.enabled=true "
                               "--set gi.debug_view=vpls --screenshot /tmp/lpv_cli_shots/v.pfm");
    INFO(hdr.output);
    CHECK(hdr.exitCode == 0);
    CHECK(contains(hdr.output,
                   "gi.debug_view=vpls is drawn over the tone-mapped frame: /tmp/lpv_cli_shots/v.pfm"));
    const Result png = runGame("--headless --backend null --width 64 --height 48 --set gi.enabled=true "
                               "--set gi.debug_view=vpls --screenshot /tmp/lpv_cli_shots/v.png");
    INFO(png.output);
    CHECK(png.exitCode == 0);
    CHECK(contains(png.output, "game: wrote /tmp/lpv_cli_shots/v.png"));
    CHECK(!contains(png.output, "is drawn over the tone-mapped frame"));
    // With GI off nothing is drawn over the frame.
    const Result off = runGame("--headless --backend null --width 64 --height 48 --set gi.debug_view=vpls "
                               "--screenshot /tmp/lpv_cli_shots/off.pfm");
    INFO(off.output);
    CHECK(off.exitCode == 0);
    CHECK(!contains(off.output, "is drawn over the tone-mapped frame"));
}

// Ctrl+C (or a SIGTERM) ended the process where it stood: no profile and no screenshot. `timeout`
// signals the game and then its own process group, so the game gets the signal twice at once.
TEST_CASE("cli: SIGINT and SIGTERM end the run and its outputs are written") {
    for (const std::string signal : {"INT", "TERM"}) {
        CAPTURE(signal);
        const std::string dir = "/tmp/lpv_cli_signal_" + signal;
        std::filesystem::remove_all(dir);
        const Result r = runProgram("timeout --preserve-status -k 60 -s " + signal + " 3 " + LPV_GAME_EXE,
                                    "--headless --backend null --width 64 --height 48 --frames 1000000000 "
                                    "--profile-out " +
                                        dir + "/profile --screenshot " + dir + "/shot.png",
                                    "");
        INFO(r.output);
        CHECK(r.exitCode == 0);
        CHECK(contains(r.output, "game: SIG" + signal + " after "));
        CHECK(std::filesystem::file_size(dir + "/profile/summary.md") > 0);
        CHECK(std::filesystem::file_size(dir + "/profile/trace.json") > 0);
        CHECK(std::filesystem::file_size(dir + "/shot.png") > 0);
    }
}

// A second Ctrl+C, 0.3 s or more after the first, stops the process at once: the first waits for
// the frame in flight, and a frame can take long. Here it is the lights hall's 148 lights lit per
// pixel at 2560x1440 on OSMesa with llvmpipe held to 2 threads (LP_NUM_THREADS), as slow on any
// machine: with the second signal ignored, the game ended 4.3 s after it on this 2-core machine.
// The shell starts the game in the background, waits for its log to say it is ready to render,
// and half a second more for the first frame to be under way, then signals it twice 0.35 s apart;
// the game dies of the second signal (the shell's status 128 + 2) long before the frame ends, with
// no outputs written. A watchdog kills the game after 60 s whatever happens. Timed from the
// backend's line instead, the setup after it took more than 2 s with Mesa's shader cache cold (as
// after tests.shader_cache_reset) and both cores busy, and the first signal came before the first
// frame. The on-disk shader cache is off for this run: cold and with both cores busy, its writer
// thread was still in the kernel 1.5-2.6 s after the game's own threads had died of the second
// signal, and the shell's wait for the process measured that instead.
TEST_CASE("cli: a second SIGINT stops the game at once") {
    const std::string dir = "/tmp/lpv_cli_second_signal_" + std::to_string(getpid());
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string game =
        "MESA_SHADER_CACHE_DISABLE=true LP_NUM_THREADS=2 " + std::string(LPV_GAME_EXE) +
        " --headless --backend gl --gl-platform osmesa --scene lights --width 2560 --height 1440"
        " --set gi.enabled=true --set gi.analytic_lights=false --frames 1000"
        " --screenshot " +
        dir + "/shot.png";
    const std::string script = dir + "/signal-twice.sh";
    std::ofstream(script)
        << "log=" << dir << "/game.log\n"
        << game << " > $log 2>&1 &\n"
        << "pid=$!\n"
        << "(sleep 60; kill -KILL $pid 2>/dev/null) >/dev/null 2>&1 &\n"
        << "watchdog=$!\n"
        << "n=0\n"
        << "until grep -q 'ready to render' $log || [ $n -ge 600 ]; do sleep 0.05; n=$((n+1)); done\n"
        << "sleep 0.5; kill -INT $pid; sleep 0.35\n"
        << "start=$(date +%s%N); kill -INT $pid; wait $pid; status=$?; end=$(date +%s%N)\n"
        << "kill $watchdog 2>/dev/null\n"
        << "echo \"status $status after $(( (end - start) / 1000000 )) ms\"\n"
        << "cat $log\n";
    const Result r = runProgram("sh", script, "");
    INFO(r.output);
    CHECK(contains(r.output, "running on backend"));
    REQUIRE(contains(r.output, "status 130 after "));
    // At once: the frame it cut short takes seconds.
    const size_t at = r.output.find("status 130 after ") + std::string("status 130 after ").size();
    CHECK(std::stoi(r.output.substr(at)) < 1000);
    CHECK(!contains(r.output, "game: SIGINT after"));
    CHECK(!std::filesystem::exists(dir + "/shot.png"));
    std::filesystem::remove_all(dir);
}

// A key of 20,000 dotted parts overflowed the stack (SIGSEGV); it is bad input like any other.
TEST_CASE("cli: a config key nested 20,000 levels deep exits 2 naming the file and line") {
    const std::string path = "/tmp/lpv_cli_deep.toml";
    std::string key = "a";
    for (int i = 1; i < 20000; ++i)
        key += ".a";
    std::ofstream(path) << "# deep\n" << key << " = 1\n";
    const Result r = runGame("--headless --backend null --frames 1 --config " + path);
    CHECK(r.exitCode == 2);
    CHECK_MESSAGE(r.output.find(path + ":2: key 'a.a.a.a") != std::string::npos, r.output);
    CHECK(r.output.find("is nested 20000 levels deep; settings are at most ") != std::string::npos);
}
