# OMPL 1.5 ships no imported target (ompl::ompl arrives in 1.7): make one from the variables its config sets.
# Used both in michi's own build and by michiConfig.cmake for consumers.
if(NOT TARGET ompl::ompl)
    find_package(ompl REQUIRED)
    add_library(ompl::ompl INTERFACE IMPORTED)
    set_target_properties(ompl::ompl PROPERTIES
        INTERFACE_INCLUDE_DIRECTORIES "${OMPL_INCLUDE_DIRS}"
        INTERFACE_LINK_LIBRARIES "${OMPL_LIBRARIES}")
endif()
