// Backend selection and validation-checked devices for the GPU test suites.
#include "TestDevice.h"

#include <doctest/doctest.h>
#include <utility>

#include <sstream>
#include <stdexcept>

namespace lpv::test {
namespace {

std::vector<BackendUnderTest> allBackends() {
    return {{"vulkan", rhi::BackendKind::Vulkan},
            {"gl-egl", rhi::BackendKind::OpenGL, rhi::GlHeadless::EglSurfaceless},
            {"gl-osmesa", rhi::BackendKind::OpenGL, rhi::GlHeadless::OSMesa}};
}

std::vector<BackendUnderTest>& selection() {
    static std::vector<BackendUnderTest> s = allBackends();
    return s;
}

} // namespace

const std::vector<BackendUnderTest>& selectedBackends() {
    return selection();
}

const BackendUnderTest& backendByName(const std::string& name) {
    static const std::vector<BackendUnderTest> all = allBackends();
    for (const auto& b : all)
        if (b.name == name) return b;
    throw std::invalid_argument("unknown test backend '" + name + "' (vulkan, gl-egl, gl-osmesa)");
}

void selectBackends(const std::string& list) {
    std::vector<BackendUnderTest> chosen;
    std::stringstream in(list);
    std::string name;
    while (std::getline(in, name, ','))
        if (!name.empty()) chosen.push_back(backendByName(name));
    selection() = std::move(chosen);
}

TestDevice::TestDevice(const BackendUnderTest& backend, rhi::DeviceConfig base)
    : messages_(std::make_shared<std::vector<std::string>>()) {
    rhi::DeviceConfig config = std::move(base);
    config.backend = backend.kind;
    config.glHeadless = backend.glHeadless;
    config.allowFallback = false; // a test of one backend must never silently run on the other
    config.validation = true;
    config.onDebugMessage = [messages = messages_](const rhi::DebugMessage& m) {
        if (m.severity != rhi::DebugSeverity::Info) messages->push_back(m.text);
    };
    device_ = rhi::createDevice(config);
}

TestDevice::~TestDevice() {
    if (device_) device_->waitIdle();
    device_.reset();
    // Messages raised while tearing down count too.
    for (const auto& m : *messages_)
        FAIL_CHECK("debug message during teardown: " << m);
}

void TestDevice::expectSilent() {
    for (const auto& m : *messages_)
        FAIL_CHECK("validation / debug message: " << m);
    messages_->clear();
}

std::unique_ptr<rhi::Device> nullDevice() {
    rhi::DeviceConfig config;
    config.backend = rhi::BackendKind::Null;
    config.framesInFlight = 2;
    return rhi::createDevice(config);
}

} // namespace lpv::test
