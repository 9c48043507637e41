# `make doc` (or `cmake --build . --target doc`): the API reference from the top-level Doxyfile into
# <build>/doc/html. Made only when Doxygen is found, never part of the default build.
find_package(Doxygen QUIET)
if(DOXYGEN_FOUND)
    # The Doxyfile's paths are relative to the source root; only the output directory changes per build.
    file(WRITE "${PROJECT_BINARY_DIR}/Doxyfile.doc"
        "@INCLUDE = \"${PROJECT_SOURCE_DIR}/Doxyfile\"\nOUTPUT_DIRECTORY = \"${PROJECT_BINARY_DIR}/doc\"\n")
    add_custom_target(doc
        COMMAND Doxygen::doxygen "${PROJECT_BINARY_DIR}/Doxyfile.doc"
        WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}"
        COMMENT "Doxygen: ${PROJECT_BINARY_DIR}/doc/html/index.html"
        VERBATIM)
endif()
