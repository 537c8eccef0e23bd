// Devices for tests: the list of backends a test body runs against, and a device wrapper that
// turns every validation-layer / GL debug message into a test failure.
#pragma once

#include "rhi/Device.h"

#include <memory>
#include <string>
#include <vector>

namespace lpv::test {

struct BackendUnderTest {
    std::string name; // "vulkan", "gl-egl", "gl-osmesa"
    rhi::BackendKind kind;
    rhi::GlHeadless glHeadless = rhi::GlHeadless::EglSurfaceless;
};

// Every GPU backend, or those named by --backends=a,b on the test command line.
const std::vector<BackendUnderTest>& selectedBackends();
// The null backend (simulated timestamps, 2 frames in flight): front-end tests without a GPU.
std::unique_ptr<rhi::Device> nullDevice();
void selectBackends(const std::string& commaSeparated);
const BackendUnderTest& backendByName(const std::string& name);

class TestDevice {
public:
    // `base`: further device settings; its backend, fallback and validation fields are replaced.
    explicit TestDevice(const BackendUnderTest& backend, rhi::DeviceConfig base = {});
    ~TestDevice();
    rhi::Device& operator*() { return *device_; }
    rhi::Device* operator->() { return device_.get(); }
    // Checks (as a doctest CHECK) that no debug message arrived so far, and clears them.
    void expectSilent();

private:
    std::shared_ptr<std::vector<std::string>> messages_;
    std::unique_ptr<rhi::Device> device_;
};

} // namespace lpv::test
