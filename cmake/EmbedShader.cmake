# Writes one shader's SPIR-V words and SPIRV-Cross GLSL into a C++ source (run with cmake -P).
file(READ ${SPV} hex HEX)
string(LENGTH "${hex}" hex_len)
math(EXPR rem "${hex_len} % 8")
if(NOT rem EQUAL 0 OR hex_len EQUAL 0)
  message(FATAL_ERROR "${SPV}: not a SPIR-V module (size ${hex_len} hex digits)")
endif()
# SPIR-V is a stream of little-endian 32-bit words.
string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1u," words "${hex}")
string(REGEX REPLACE "(([^,]*,){8})" "\\1\n    " words "${words}")
file(READ ${GLSL} glsl)
# A vertex shader that writes gl_Layer needs GL_ARB_shader_viewport_layer_array in GLSL 4.50.
# SPIRV-Cross (Debian 12) requests it only for the SPIR-V extension's capability, not for the core
# ShaderLayer capability glslang emits for Vulkan 1.2+, so add it here.
if(STAGE STREQUAL "Vertex" AND glsl MATCHES "gl_Layer" AND NOT glsl MATCHES "GL_ARB_shader_viewport_layer_array")
  string(REGEX REPLACE "^#version 450\n" "#version 450\n#extension GL_ARB_shader_viewport_layer_array : require\n"
                       glsl "${glsl}")
endif()
set(delim "lpv_glsl")
file(WRITE ${OUT}
  "// Generated from ${NAME}; do not edit.\n"
  "#include \"rhi/Shader.h\"\n"
  "#include <cstdint>\n"
  "namespace {\n"
  "const uint32_t kSpirv[] = {\n    ${words}\n};\n"
  "const char kGlsl[] = R\"${delim}(${glsl})${delim}\";\n"
  "} // namespace\n"
  "namespace ${NAMESPACE} {\n"
  "extern const lpv::rhi::ShaderBinary ${SYMBOL};\n"
  "const lpv::rhi::ShaderBinary ${SYMBOL}{\"${NAME}\", lpv::rhi::ShaderStage::${STAGE}, kSpirv, "
  "{kGlsl, sizeof(kGlsl) - 1}};\n"
  "} // namespace ${NAMESPACE}\n")
