# Every third-party dependency comes from a Debian package, found here and nowhere else.
find_package(Threads REQUIRED)  # glslang's config needs it first
find_package(PkgConfig REQUIRED)
find_package(Vulkan REQUIRED)
find_package(glfw3 3.3 REQUIRED)
find_package(glm REQUIRED)
find_package(doctest REQUIRED)
find_package(tomlplusplus REQUIRED)
find_package(CLI11 REQUIRED)
find_package(TinyGLTF REQUIRED)
find_package(tinyexr REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(meshoptimizer REQUIRED)
find_package(embree 3 REQUIRED)  # the path-traced reference (reference/)

pkg_check_modules(EGL REQUIRED IMPORTED_TARGET egl)
pkg_check_modules(OSMESA REQUIRED IMPORTED_TARGET osmesa)
pkg_check_modules(SPIRV_CROSS REQUIRED IMPORTED_TARGET spirv-cross-c-shared)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)

find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)
find_program(SPIRV_CROSS_EXE spirv-cross REQUIRED)

# GL types and enums only (GL/glcorearb.h); entry points are loaded at run time.
find_path(GLCOREARB_INCLUDE_DIR GL/glcorearb.h REQUIRED)
