# The installed package: public headers, the static libraries and a relocatable
# LpvEngineConfig.cmake, so that a game writes find_package(LpvEngine CONFIG REQUIRED) and links
# lpv::gi, lpv::engine, lpv::platforms and lpv::rhi, and lpv::gi_adapter, the GI read from the
# engine's config and renderer (examples/ is such a game; tests/package
# installs this build and builds it). In the tree the same names are aliases.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(LPV_PACKAGE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/LpvEngine)
set(LPV_PACKAGE_PRESET_DIR ${CMAKE_INSTALL_DATADIR}/LpvEngine/presets)

set(lpv_package_targets)
# name:folder, the folder holding the library's include/.
foreach(entry rhi:rhi platforms:platforms engine:engine gi:gi gi_adapter:gi/adapter)
  string(REPLACE ":" ";" entry ${entry})
  list(GET entry 0 name)
  list(GET entry 1 folder)
  set(target lpv_${name})
  add_library(lpv::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  # The tree's include folders (the public headers, and the generated shader declarations that only
  # the library's own sources include) hold in the build; installed, every public header is under
  # include/, and the header folders hold nothing but public headers.
  get_target_property(dirs ${target} INTERFACE_INCLUDE_DIRECTORIES)
  set(build_dirs)
  foreach(dir IN LISTS dirs)
    list(APPEND build_dirs "$<BUILD_INTERFACE:${dir}>")
  endforeach()
  set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES
                                             "${build_dirs};$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>")
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${folder}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  list(APPEND lpv_package_targets ${target})
endforeach()

install(TARGETS ${lpv_package_targets} EXPORT LpvEngineTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
# Static libraries carry their private dependencies into the export ($<LINK_ONLY:...>):
# LpvEngineConfig.cmake finds every one of them.
install(EXPORT LpvEngineTargets NAMESPACE lpv:: DESTINATION ${LPV_PACKAGE_CMAKE_DIR})
# The platform profiles are compiled into lpv_platforms; the GI's console preset is a file a game
# loads with its own config (LpvEngine_PRESET_DIR).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/gi/presets/ DESTINATION ${LPV_PACKAGE_PRESET_DIR} FILES_MATCHING
        PATTERN "*.toml")

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/LpvEngineConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/package/LpvEngineConfig.cmake
                              INSTALL_DESTINATION ${LPV_PACKAGE_CMAKE_DIR} PATH_VARS LPV_PACKAGE_PRESET_DIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/LpvEngineConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/package/LpvEngineConfig.cmake
              ${PROJECT_BINARY_DIR}/package/LpvEngineConfigVersion.cmake DESTINATION ${LPV_PACKAGE_CMAKE_DIR})
