# glint_embed_text(TARGET <lib> FILE <path> FUNCTION <qualified name>)
#
# Embeds a text file (a web page) into a library as `std::string_view FUNCTION()`, so an
# installed glint writes it anywhere. Rebuilt when the file changes.
function(glint_embed_text)
  cmake_parse_arguments(ARG "" "TARGET;FILE;FUNCTION" "" ${ARGN})
  get_filename_component(name "${ARG_FILE}" NAME_WE)
  set(out "${CMAKE_CURRENT_BINARY_DIR}/embedded_${name}.cpp")
  add_custom_command(
    OUTPUT "${out}"
    COMMAND ${CMAKE_COMMAND} -DIN=${ARG_FILE} -DOUT=${out} -DFUNCTION=${ARG_FUNCTION}
            -P "${PROJECT_SOURCE_DIR}/cmake/EmbedTextScript.cmake"
    DEPENDS "${ARG_FILE}" "${PROJECT_SOURCE_DIR}/cmake/EmbedTextScript.cmake"
    COMMENT "Embedding ${ARG_FILE}"
    VERBATIM)
  target_sources(${ARG_TARGET} PRIVATE "${out}")
endfunction()
