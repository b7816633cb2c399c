# glint_embed_shaders(TARGET <lib> ROOT <dir> FILES <relative paths...>)
#
# Embeds GLSL files into the binary so an installed glint runs anywhere. Generates
# one .cpp holding a sorted table {relative path, source}; the shader loader in
# src/gl looks paths up there. The generated file is rebuilt when any shader changes.
function(glint_embed_shaders)
  cmake_parse_arguments(ARG "" "TARGET;ROOT" "FILES" ${ARGN})
  set(out "${CMAKE_CURRENT_BINARY_DIR}/embedded_shaders.cpp")
  set(deps "")
  foreach(f IN LISTS ARG_FILES)
    list(APPEND deps "${ARG_ROOT}/${f}")
  endforeach()
  add_custom_command(
    OUTPUT "${out}"
    COMMAND ${CMAKE_COMMAND} -DROOT=${ARG_ROOT} "-DFILES=${ARG_FILES}" -DOUT=${out}
            -P "${PROJECT_SOURCE_DIR}/cmake/EmbedShadersScript.cmake"
    DEPENDS ${deps} "${PROJECT_SOURCE_DIR}/cmake/EmbedShadersScript.cmake"
    COMMENT "Embedding ${CMAKE_CURRENT_LIST_DIR} shaders"
    VERBATIM)
  target_sources(${ARG_TARGET} PRIVATE "${out}")
endfunction()
