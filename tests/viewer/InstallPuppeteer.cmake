# The browser test's setup (ctest fixture, tests/CMakeLists.txt): checks that Debian's chromium, node and npm are
# there and installs npm puppeteer-core (a DevTools-protocol client, no browser of its own) into PREFIX once.
# cmake -DNODE=... -DNPM=... -DCHROMIUM=... -DPREFIX=... -DVERSION=... -P InstallPuppeteer.cmake
foreach(tool NODE NPM CHROMIUM)
    if(NOT ${tool} OR ${tool} MATCHES "NOTFOUND$")
        string(TOLOWER ${tool} package)
        message(FATAL_ERROR "the browser test needs ${package} (Debian: apt-get install chromium nodejs npm, or run "
            "scripts/setup.sh), then re-run cmake")
    endif()
endforeach()
set(installed ${PREFIX}/node_modules/puppeteer-core/package.json)
if(EXISTS ${installed})
    file(READ ${installed} text)
    string(REGEX MATCH "\"version\": *\"([^\"]+)\"" matched "${text}")
    if(CMAKE_MATCH_1 STREQUAL VERSION)
        message(STATUS "puppeteer-core ${VERSION} already in ${PREFIX}")
        return()
    endif()
endif()
# puppeteer-core downloads nothing itself; the variable keeps any puppeteer package the resolver pulls in from
# fetching a browser: the test drives the system's chromium only
set(ENV{PUPPETEER_SKIP_DOWNLOAD} 1)
file(MAKE_DIRECTORY ${PREFIX})
execute_process(COMMAND ${NPM} install --prefix ${PREFIX} --no-audit --no-fund --no-save --loglevel=error
                        puppeteer-core@${VERSION}
    RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT EXISTS ${installed})
    message(FATAL_ERROR "npm install puppeteer-core@${VERSION} into ${PREFIX} failed (exit ${rc}): the npm registry "
        "must be reachable once, or copy a node_modules/puppeteer-core there")
endif()
