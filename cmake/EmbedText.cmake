# vt_embed_text(OUTPUT header NAME symbol FILES file...): a header defining
# `inline constexpr char symbol[]` with the files' text concatenated, regenerated when they change.
function(vt_embed_text)
  cmake_parse_arguments(EMBED "" "OUTPUT;NAME" "FILES" ${ARGN})
  string(REPLACE ";" "|" files "${EMBED_FILES}")  # one argument; the script splits it again
  add_custom_command(
    OUTPUT ${EMBED_OUTPUT}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${EMBED_OUTPUT} -DNAME=${EMBED_NAME} -DFILES=${files}
            -P ${PROJECT_SOURCE_DIR}/cmake/EmbedTextScript.cmake
    DEPENDS ${EMBED_FILES} ${PROJECT_SOURCE_DIR}/cmake/EmbedTextScript.cmake
    COMMENT "Embedding ${EMBED_NAME}"
    VERBATIM)
endfunction()
