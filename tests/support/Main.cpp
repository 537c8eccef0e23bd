// doctest runner with one extra option: --backends=vulkan,gl-egl,gl-osmesa limits the GPU
// backends the suites run against (ctest registers one entry per backend).
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include "TestDevice.h"

#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    std::vector<char*> rest;
    for (int i = 0; i < argc; ++i) {
        constexpr const char* kOption = "--backends=";
        if (std::strncmp(argv[i], kOption, std::strlen(kOption)) == 0) {
            try {
                lpv::test::selectBackends(argv[i] + std::strlen(kOption));
            } catch (const std::exception& e) {
                std::cerr << e.what() << "\n";
                return 2;
            }
        } else {
            rest.push_back(argv[i]);
        }
    }
    doctest::Context context(int(rest.size()), rest.data());
    return context.run();
}
