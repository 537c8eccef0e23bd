// LPV Engine sample game (foundation stage): opens the device the user asked for, renders a lit,
// spinning cube for N frames headless or in a window, and writes the last frame as a PNG. The
// engine's renderer, scenes and GI plug in here as they arrive.
#include "GameShaders.h"

#include "engine/DeviceSettings.h"
#include "engine/ImageFile.h"
#include "engine/config/Config.h"
#include "engine/config/SettingsHelp.h"
#include "platforms/Clock.h"
#include "platforms/Log.h"
#include "platforms/Window.h"
#include "rhi/Device.h"
#include "rhi/Error.h"

#include <CLI/CLI.hpp>

#define GLM_FORCE_DEPTH_ZERO_TO_ONE
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>
#include <memory>
#include <optional>
#include <vector>

using namespace lpv;

namespace {

struct Options {
    std::vector<std::string> configFiles;
    // (source, key=value): --set and the shorthand flags, in order.
    std::vector<std::pair<std::string, std::string>> overrides;
    bool headless = false;
    int frames = -1;  // -1: 1 headless, until closed in a window
    std::string screenshot;
};

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
};

struct FrameUniforms {
    glm::mat4 viewProjection;
    glm::mat4 model;
    glm::vec4 lightDirection;
};

std::vector<Vertex> cubeVertices() {
    std::vector<Vertex> v;
    const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::vec3& n : normals) {
        const glm::vec3 u = std::abs(n.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        const glm::vec3 w = glm::cross(n, u);
        const glm::vec3 corners[4] = {n - u - w, n + u - w, n + u + w, n - u + w};
        for (int i : {0, 1, 2, 0, 2, 3}) v.push_back({corners[i] * 0.5f, n});
    }
    return v;
}

int run(const Options& opt) {
    engine::Config config;
    for (const std::string& file : opt.configFiles) config.loadFile(file);
    for (const auto& [source, assignment] : opt.overrides) config.applyOverride(assignment, source);
    const uint32_t width = engine::renderWidth(config), height = engine::renderHeight(config);

    std::unique_ptr<platforms::Window> window;
    if (!opt.headless && platforms::Window::displayAvailable())
        window = std::make_unique<platforms::Window>(platforms::WindowDesc{width, height, "LPV Engine"});

    rhi::DeviceConfig deviceConfig = engine::deviceConfigFrom(config);
    deviceConfig.window = window.get();
    const uint64_t t0 = platforms::nowNanoseconds();
    std::unique_ptr<rhi::Device> device = rhi::createDevice(deviceConfig);
    log::info("game: running on backend '" + std::string(rhi::backendName(device->backend())) + "' (" +
              device->caps().deviceName + ", " + std::to_string((platforms::nowNanoseconds() - t0) / 1000000) +
              " ms to create)" + (window ? ", windowed" : ", headless"));

    using namespace rhi;
    const std::vector<Vertex> vertices = cubeVertices();
    const BufferHandle vb = device->createBuffer(
        {vertices.size() * sizeof(Vertex), kBufferVertex, MemoryAccess::GpuOnly, "cube vertices", "game.mesh"},
        vertices.data());
    const TextureHandle color = device->createTexture(
        {TextureKind::Tex2D, Format::RGBA8Srgb, width, height, 1, 1,
         kTextureColorTarget | kTextureSampled | kTextureTransfer, "frame color", "game.frame"});
    const TextureHandle depth = device->createTexture({TextureKind::Tex2D, Format::D32F, width, height, 1,
                                                       1, kTextureDepthTarget, "frame depth", "game.frame"});
    GraphicsPipelineDesc pd;
    pd.vertex = &game::shaders::cube_vert;
    pd.fragment = &game::shaders::cube_frag;
    pd.vertexBuffers = {{sizeof(Vertex)}};
    pd.attributes = {{0, VertexFormat::Float3, offsetof(Vertex, position)},
                     {1, VertexFormat::Float3, offsetof(Vertex, normal)}};
    pd.depthTest = pd.depthWrite = true;
    pd.colorFormats = {Format::RGBA8Srgb};
    pd.depthFormat = Format::D32F;
    pd.debugName = "cube";
    const GraphicsPipelineHandle pipeline = device->createPipeline(pd);

    const int frames = opt.frames > 0 ? opt.frames : (window ? 0 : 1);
    glm::mat4 projection = glm::perspective(glm::radians(50.0f), float(width) / float(height), 0.1f, 50.0f);
    projection[1][1] *= -1.0f;  // image row 0 at the top on every backend
    const glm::mat4 view = glm::lookAt(glm::vec3(1.8f, 1.4f, 2.4f), glm::vec3(0.0f), glm::vec3(0, 1, 0));
    for (int frame = 0; frames == 0 || frame < frames; ++frame) {
        if (window) {
            window->pollEvents();
            if (window->shouldClose()) break;
        }
        FrameUniforms u;
        u.viewProjection = projection * view;
        u.model = glm::rotate(glm::mat4(1.0f), 0.6f + 0.02f * float(frame), glm::vec3(0, 1, 0));
        u.lightDirection = glm::vec4(glm::normalize(glm::vec3(-0.4f, -1.0f, -0.6f)), 0.0f);

        CommandList& cmd = device->beginFrame();
        RenderPassDesc pass;
        pass.colors[0] = {color, 0, 0, LoadOp::Clear, {0.05f, 0.07f, 0.1f, 1.0f}};
        pass.colorCount = 1;
        pass.depth = {depth, 0, LoadOp::Clear, 1.0f};
        pass.debugName = "cube";
        cmd.beginRenderPass(pass);
        cmd.bindPipeline(pipeline);
        cmd.bindVertexBuffer(0, vb);
        cmd.pushUniforms(0, &u, sizeof(u));
        cmd.draw(uint32_t(vertices.size()));
        cmd.endRenderPass();
        device->endFrame(window ? color : TextureHandle{});
    }
    device->waitIdle();

    if (!opt.screenshot.empty()) {
        std::vector<uint8_t> pixels(size_t(width) * height * 4);
        device->readTexture(color, 0, pixels.data(), pixels.size());
        engine::writePng(opt.screenshot, width, height, pixels);
        log::info("game: wrote " + opt.screenshot + " (backend '" + std::string(rhi::backendName(device->backend())) +
                  "')");
    }
    device->destroy(pipeline);
    device->destroy(depth);
    device->destroy(color);
    device->destroy(vb);
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"LPV Engine sample game"};
    Options opt;
    std::string helpConfig;
    const auto shorthand = [&](const char* flag, const char* key) {
        return [&opt, flag, key](const std::string& v) { opt.overrides.emplace_back(flag, std::string(key) + "=" + v); };
    };
    app.add_option("--config", opt.configFiles, "TOML config file(s), applied in order");
    app.add_option_function<std::vector<std::string>>(
        "--set",
        [&](const std::vector<std::string>& v) {
            for (const std::string& a : v) opt.overrides.emplace_back("--set", a);
        },
        "Override a setting: --set gi.enabled=true (after the config files)");
    app.add_option_function<std::string>("--backend", shorthand("--backend", "render.backend"),
                                         "Graphics backend: auto, gl, vulkan, null (= --set render.backend=...)");
    app.add_option_function<std::string>("--gl-platform", shorthand("--gl-platform", "render.gl_platform"),
                                         "Headless GL context: egl or osmesa");
    app.add_flag_callback("--no-fallback", [&] { opt.overrides.emplace_back("--no-fallback", "render.allow_fallback=false"); },
                          "Fail instead of falling back to the other backend");
    app.add_flag_callback("--validation", [&] { opt.overrides.emplace_back("--validation", "render.validation=true"); },
                          "Vulkan validation layer / GL debug output");
    app.add_option_function<std::string>("--width", shorthand("--width", "render.width"), "Frame width");
    app.add_option_function<std::string>("--height", shorthand("--height", "render.height"), "Frame height");
    app.add_flag("--headless", opt.headless, "Never open a window");
    app.add_option("--frames", opt.frames, "Frames to render (default: 1 headless, until closed in a window)");
    app.add_option("--screenshot", opt.screenshot, "Write the last frame to this PNG file");
    app.add_option("--help-config", helpConfig, "List every setting (text or markdown) and exit")
        ->expected(0, 1)
        ->default_str("text");
    CLI11_PARSE(app, argc, argv);
    if (app.count("--help-config")) {
        std::fputs((helpConfig == "markdown" ? engine::settingsMarkdownTable() : engine::settingsHelpText()).c_str(), stdout);
        return 0;
    }
    try {
        return run(opt);
    } catch (const engine::ConfigError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const rhi::BackendUnavailable& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 3;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
