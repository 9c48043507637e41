# michi_add_component(NAME SOURCES ... DEPENDS ...): a library michi_<NAME> exported as michi::<NAME>, whose headers
# live in <NAME>/include/michi/<NAME>/ both in the tree and once installed.
function(michi_add_component name)
    cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPENDS;PRIVATE_DEPENDS" ${ARGN})
    set(target michi_${name})
    if(ARG_SOURCES)
        add_library(${target} SHARED ${ARG_SOURCES})
        target_include_directories(${target} PUBLIC
            $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
            $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
        target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_DEPENDS} PRIVATE ${ARG_PRIVATE_DEPENDS})
        target_compile_options(${target} PRIVATE -Wall -Wextra)
        set_target_properties(${target} PROPERTIES OUTPUT_NAME michi_${name} EXPORT_NAME ${name}
            VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}
            INSTALL_RPATH "$ORIGIN")
    else()
        add_library(${target} INTERFACE)
        target_include_directories(${target} INTERFACE
            $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
            $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
        target_link_libraries(${target} INTERFACE ${ARG_PUBLIC_DEPENDS})
        set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
    endif()
    add_library(michi::${name} ALIAS ${target})
    install(TARGETS ${target} EXPORT michiTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
    # a component may have no headers yet (git keeps no empty folders, so a clean checkout lacks include/)
    if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/include)
        install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    endif()
endfunction()
