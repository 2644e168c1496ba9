// viewer/city_loader.hpp — the streaming viewer's loader threads: each building's PNG is fetched,
// decoded and validated off the render thread, in the order the renderer asks for them, and handed
// back whole, with the level of the building's complementary mesh asked for, or that level alone.
// A failure (missing, unreadable, corrupt, invalid) comes back as the error.
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
  Status status = Error{"not loaded"};     // the building's error when a file failed
  std::optional<Image> image;              // validated; none when only a complement level was asked for
  std::optional<TriangleMesh> complement;  // the level asked for, when one was
  std::size_t complementLevel = 0;         // which: 0 the mesh itself, k its k-th coarser level
  std::size_t bytes = 0;                   // fetched
};

// What to fetch for a building: its PNG, a level of its complementary mesh (a GLB, or an OBJ with
// its MTL files), or both. An empty location is not fetched.
struct LoadRequest {
  std::size_t building = 0;
  std::string hni, complement;
  std::size_t complementLevel = 0;
};

class CityLoader {
 public:
  CityLoader(Fetch fetch, int threads);
  ~CityLoader();  // drops what is queued and joins the threads
  CityLoader(const CityLoader&) = delete;
  CityLoader& operator=(const CityLoader&) = delete;

  // Queues a request; requests are served in the order made.
  void request(LoadRequest request);
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
  std::deque<LoadRequest> queue_;
  std::vector<LoadedHni> finished_;
  std::size_t outstanding_ = 0;
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace nut::viewer
