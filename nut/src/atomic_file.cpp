// Files written whole or not at all: see atomic_file.hpp.
#include "atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <random>
#include <string>

namespace nut::files {

namespace {

std::filesystem::path temporarySibling(const std::filesystem::path& path) {
  std::random_device device;
  return path.parent_path() / (path.filename().string() + ".tmp" + std::to_string(device()));
}

// Why `path` could not be created; `error` is errno right after the failed open.
std::string cannotCreate(const std::filesystem::path& path, int error) {
  const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
  std::error_code ignored;
  std::string why = error != 0 ? std::strerror(error) : "the system gave no reason";
  if (!std::filesystem::exists(folder, ignored))
    why = "there is no folder " + folder.string();
  else if (!std::filesystem::is_directory(folder, ignored))
    why = folder.string() + " is not a folder";
  return path.string() + ": cannot create the file (" + why + ")";
}

}  // namespace

Result<std::filesystem::path> writeTemporary(const std::filesystem::path& path,
                                             const std::function<bool(std::ofstream&)>& write) {
  const std::filesystem::path temporary = temporarySibling(path);
  errno = 0;
  std::ofstream out(temporary, std::ios::binary);
  if (!out) return Error{cannotCreate(path, errno)};
  if (!write(out) || !out.flush()) {
    out.close();
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    return Error{path.string() + ": write failed"};
  }
  return temporary;
}

Status moveIntoPlace(const std::filesystem::path& temporary, const std::filesystem::path& path) {
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (!error) return Ok{};
  std::filesystem::remove(temporary, error);
  return Error{path.string() + ": cannot rename the written file into place"};
}

Status writeWhole(const std::filesystem::path& path, const std::string& bytes) {
  auto temporary = writeTemporary(path, [&](std::ofstream& out) {
    return static_cast<bool>(out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())));
  });
  if (!temporary) return temporary.error();
  return moveIntoPlace(*temporary, path);
}

}  // namespace nut::files
