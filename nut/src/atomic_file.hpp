// Files written whole or not at all (internal to the core and its PNG library): the bytes go to a
// temporary sibling of the destination, which is renamed over it once complete, so that a failure
// never leaves a half-written file. Errors name the destination and say why.
#pragma once

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <nut/error.hpp>

namespace nut::files {

// Streams `write`'s output into a new temporary sibling of `path` and returns its name, for
// moveIntoPlace(). When the file cannot be created (its folder missing, not a folder, or what the
// system says) or `write` or the flush fails, nothing is left behind.
Result<std::filesystem::path> writeTemporary(const std::filesystem::path& path,
                                             const std::function<bool(std::ofstream&)>& write);

// Renames `temporary` over `path`; on failure removes it.
Status moveIntoPlace(const std::filesystem::path& temporary, const std::filesystem::path& path);

// writeTemporary and moveIntoPlace of one whole buffer.
Status writeWhole(const std::filesystem::path& path, const std::string& bytes);

}  // namespace nut::files
