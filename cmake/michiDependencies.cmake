# Every external dependency of michi, found once. Debian 12 packages: see scripts/setup.sh.
include(michiOmplTarget)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(fcl 0.6 REQUIRED)               # target: fcl
find_package(urdfdom REQUIRED)               # variables only in Debian's 3.0 config
find_package(assimp REQUIRED)                # target: assimp::assimp
find_package(yaml-cpp REQUIRED)              # target: yaml-cpp
find_package(Boost 1.71 REQUIRED COMPONENTS filesystem)
find_package(Threads REQUIRED)
find_package(PNG REQUIRED)                   # target: PNG::PNG (map images, validity/scene)

if(NOT TARGET michi_urdfdom)
    add_library(michi_urdfdom INTERFACE)
    target_include_directories(michi_urdfdom SYSTEM INTERFACE ${urdfdom_INCLUDE_DIRS})
    target_link_libraries(michi_urdfdom INTERFACE ${urdfdom_LIBRARIES})
    install(TARGETS michi_urdfdom EXPORT michiTargets)
endif()
