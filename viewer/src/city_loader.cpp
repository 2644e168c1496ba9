// The loader threads of the streaming viewer (viewer/city_loader.hpp).
#include <viewer/city_loader.hpp>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <nut/hni.hpp>
#include <nut/png_io.hpp>
#include <scene/glb.hpp>
#include <scene/mesh_file.hpp>
#include <scene/obj.hpp>

namespace nut::viewer {

Fetch localFiles() {
  return [](const std::string& path) -> Result<std::vector<std::uint8_t>> {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) return Error{path + ": no such file"};
    std::ifstream in(path, std::ios::binary);
    if (!in) return Error{path + ": cannot open (" + std::strerror(errno) + ")"};
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
  };
}

CityLoader::CityLoader(Fetch fetch, int threads) : fetch_(std::move(fetch)) {
  for (int t = 0; t < std::max(1, threads); ++t) threads_.emplace_back([this] { work(); });
}

CityLoader::~CityLoader() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
    queue_.clear();
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void CityLoader::request(LoadRequest request) {
  {
    const std::lock_guard lock(mutex_);
    queue_.push_back(std::move(request));
    ++outstanding_;
  }
  wake_.notify_one();
}

std::vector<LoadedHni> CityLoader::takeFinished() {
  const std::lock_guard lock(mutex_);
  std::vector<LoadedHni> out = std::move(finished_);
  finished_.clear();
  outstanding_ -= out.size();
  return out;
}

std::size_t CityLoader::outstanding() const {
  const std::lock_guard lock(mutex_);
  return outstanding_;
}

// A complementary mesh through the same fetch as the HNIs: a GLB, or an OBJ and the MTL files it
// names beside it (a missing MTL is the reader's warning, not an error).
Result<TriangleMesh> CityLoader::readComplement(const std::string& location, std::size_t& bytes) const {
  auto file = fetch_(location);
  if (!file) return file.error();
  bytes += file->size();
  if (scene::isGlbPath(location)) {
    std::vector<std::string> warnings;
    return scene::readGlbBytes(*file, location, warnings);
  }
  const scene::MtlReader mtl = [&](const std::string& path) -> Result<std::string> {
    auto text = fetch_(path);
    if (!text) return text.error();
    bytes += text->size();
    return std::string(text->begin(), text->end());
  };
  scene::ObjReadOptions options;
  options.oneMesh = true;
  auto contents = scene::readObjText(std::string(file->begin(), file->end()), location, mtl, options);
  if (!contents) return contents.error();
  return std::move(contents->objects.front());
}

void CityLoader::work() {
  while (true) {
    LoadRequest job;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      job = std::move(queue_.front());
      queue_.pop_front();
    }
    LoadedHni loaded;
    loaded.building = job.building;
    loaded.complementLevel = job.complementLevel;
    loaded.status = Ok{};
    if (!job.hni.empty()) {
      auto bytes = fetch_(job.hni);
      if (!bytes) {
        loaded.status = bytes.error();
      } else {
        loaded.bytes = bytes->size();
        auto png = readPngBytes(job.hni, std::move(*bytes));
        if (!png)
          loaded.status = png.error();
        else if (Status s = validate(png->image); !s)
          loaded.status = Error{job.hni + ": not a valid HNI: " + s.error().message};
        else
          loaded.image = std::move(png->image);
      }
    }
    if (loaded.status && !job.complement.empty()) {
      auto mesh = readComplement(job.complement, loaded.bytes);
      if (mesh)
        loaded.complement = std::move(*mesh);
      else
        loaded.status = mesh.error();
    }
    const std::lock_guard lock(mutex_);
    finished_.push_back(std::move(loaded));
  }
}

}  // namespace nut::viewer
