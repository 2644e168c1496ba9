// The loader threads of the streaming viewer (viewer/city_loader.hpp).
#include <viewer/city_loader.hpp>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <nut/hni.hpp>
#include <nut/png_io.hpp>

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

void CityLoader::request(std::size_t building, std::string location) {
  {
    const std::lock_guard lock(mutex_);
    queue_.emplace_back(building, std::move(location));
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

void CityLoader::work() {
  while (true) {
    std::pair<std::size_t, std::string> job;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      job = std::move(queue_.front());
      queue_.pop_front();
    }
    LoadedHni loaded;
    loaded.building = job.first;
    auto bytes = fetch_(job.second);
    if (!bytes) {
      loaded.image = bytes.error();
    } else {
      loaded.bytes = bytes->size();
      auto png = readPngBytes(job.second, std::move(*bytes));
      if (!png)
        loaded.image = png.error();
      else if (Status s = validate(png->image); !s)
        loaded.image = Error{job.second + ": not a valid HNI: " + s.error().message};
      else
        loaded.image = std::move(png->image);
    }
    const std::lock_guard lock(mutex_);
    finished_.push_back(std::move(loaded));
  }
}

}  // namespace nut::viewer
