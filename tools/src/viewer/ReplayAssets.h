#ifndef MICHI_TOOLS_SRC_VIEWER_REPLAY_ASSETS_
#define MICHI_TOOLS_SRC_VIEWER_REPLAY_ASSETS_

// Private to michi_tools: the files a replay page inlines, compiled in by cmake/michiEmbed.cmake (tools/CMakeLists.txt
// names them): Debian's three.js and OrbitControls (libjs-three) and the page's template and script (viewer/page/).

#include <cstddef>

namespace michi
{
    namespace tools
    {
        namespace replay_assets
        {
            extern const char THREE_JS[];
            extern const std::size_t THREE_JS_SIZE;
            extern const char ORBIT_CONTROLS_JS[];
            extern const std::size_t ORBIT_CONTROLS_JS_SIZE;
            extern const char PAGE_HTML[];
            extern const std::size_t PAGE_HTML_SIZE;
            extern const char PAGE_JS[];
            extern const std::size_t PAGE_JS_SIZE;
        }  // namespace replay_assets
    }      // namespace tools
}  // namespace michi

#endif
