// The back-end factories behind nut::viewer::createContext; each lives in its own file and is
// compiled only when its library was found (viewer/CMakeLists.txt).
#pragma once

#include <memory>

#include <viewer/context.hpp>

namespace nut::viewer {

Result<std::unique_ptr<Context>> createOSMesaContext(const ContextOptions& options);
Result<std::unique_ptr<Context>> createEglContext(const ContextOptions& options);
Result<std::unique_ptr<Context>> createGlfwContext(const ContextOptions& options);

}  // namespace nut::viewer
