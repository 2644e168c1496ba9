// The back-end factories behind nut::viewer::createContext; each lives in its own file (OSMesa's
// only in a build with NUT_GL_OSMESA, viewer/CMakeLists.txt).
#pragma once

#include <memory>

#include <viewer/context.hpp>

namespace nut::viewer {

Result<std::unique_ptr<Context>> createOSMesaContext(const ContextOptions& options);
Result<std::unique_ptr<Context>> createEglContext(const ContextOptions& options);
Result<std::unique_ptr<Context>> createGlfwContext(const ContextOptions& options);

}  // namespace nut::viewer
