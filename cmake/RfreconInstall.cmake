# `cmake --install`: the tool, every layer's static library and public headers, and the CMake package rfrecon
# (find_package(rfrecon) gives rfrecon::core ... rfrecon::pipeline and rfrecon::rfrecon, docs/api.md).
include(CMakePackageConfigHelpers)
get_property(rfrecon_layers GLOBAL PROPERTY RFRECON_LAYERS)
# Headers: each layer installs its own (cmake/RfreconLayer.cmake, kernels/CMakeLists.txt) under include/rfrecon/,
# and each target's INSTALL_INTERFACE include directories point there.
install(TARGETS ${rfrecon_layers} rfrecon_all EXPORT rfreconTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
set(rfrecon_package_dir ${CMAKE_INSTALL_LIBDIR}/cmake/rfrecon)
install(EXPORT rfreconTargets NAMESPACE rfrecon:: DESTINATION ${rfrecon_package_dir})
# The layers' exported names double as the package's components: find_package(rfrecon COMPONENTS depth sim).
list(TRANSFORM rfrecon_layers REPLACE "^rfrecon_" "" OUTPUT_VARIABLE RFRECON_PACKAGE_COMPONENTS)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/rfreconConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/rfreconConfig.cmake INSTALL_DESTINATION ${rfrecon_package_dir})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/rfreconConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/rfreconConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/rfreconConfigVersion.cmake
        DESTINATION ${rfrecon_package_dir})
