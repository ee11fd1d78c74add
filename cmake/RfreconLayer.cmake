# rfrecon_add_layer(NAME [PUBLIC deps...] [PRIVATE deps...]): one static library per layer, built from the *.cc files
# of the calling directory, as target rfrecon_NAME (alias and exported name rfrecon::NAME). Headers are included from
# the repository root ("host/core/errors.h"), the same paths once installed under include/rfrecon/. Which layer may
# include which is docs/architecture.md's graph, checked by scripts/check_layers.py.
function(rfrecon_add_layer name)
  cmake_parse_arguments(ARG "" "" "PUBLIC;PRIVATE" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  file(GLOB headers CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.h)
  add_library(rfrecon_${name} STATIC ${sources})
  add_library(rfrecon::${name} ALIAS rfrecon_${name})
  set_target_properties(rfrecon_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(rfrecon_${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
                                                    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/rfrecon>)
  target_compile_options(rfrecon_${name} PRIVATE -Wall -Wextra -Wpedantic)
  target_link_libraries(rfrecon_${name} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE})
  file(RELATIVE_PATH dir ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
  install(FILES ${headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rfrecon/${dir})
  set_property(GLOBAL APPEND PROPERTY RFRECON_LAYERS rfrecon_${name})
endfunction()
