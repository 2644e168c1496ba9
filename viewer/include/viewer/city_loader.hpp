// viewer/city_loader.hpp — the streaming viewer's loader threads: each building's PNG is fetched,
// decoded and validated off the render thread, in the order the renderer asks for them, and handed
// back whole, with the building's complementary mesh when it has one. A failure (missing,
// unreadable, corrupt, invalid) comes back as the error.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nut/error.hpp>
#include <nut/image.hpp>
#include <nut/triangle_mesh.hpp>

namespace nut::viewer {

// Bytes of a location (a path, or a URL for an HTTP fetch). Called from the loader threads.
using Fetch = std::function<Result<std::vector<std::uint8_t>>(const std::string& location)>;

// Reads local files.
Fetch localFiles();

struct LoadedHni {
  std::size_t building = 0;
  Result<Image> image = Error{"not loaded"};  // validated; the building's error when a file failed
  std::optional<TriangleMesh> complement;     // when the building has one
  std::size_t bytes = 0;                      // fetched
};

class CityLoader {
 public:
  CityLoader(Fetch fetch, int threads);
  ~CityLoader();  // drops what is queued and joins the threads
  CityLoader(const CityLoader&) = delete;
  CityLoader& operator=(const CityLoader&) = delete;

  // Queues a building's PNG, and its complementary mesh (a GLB, or an OBJ with its MTL files) when
  // `complement` is not empty; requests are served in the order made.
  void request(std::size_t building, std::string location, std::string complement = {});
  // What has finished since the last call.
  std::vector<LoadedHni> takeFinished();
  // Requested and not yet taken.
  std::size_t outstanding() const;

 private:
  void work();
  Result<TriangleMesh> readComplement(const std::string& location, std::size_t& bytes) const;

  Fetch fetch_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  struct Job {
    std::size_t building;
    std::string location, complement;
  };
  std::deque<Job> queue_;
  std::vector<LoadedHni> finished_;
  std::size_t outstanding_ = 0;
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace nut::viewer
