// PNG read/write through OpenImageIO, bit-exact for RGBA8, with the HNI text chunks.
#include <nut/png_io.hpp>

#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <filesystem>
#include <random>
#include <sstream>

namespace nut {

namespace {

constexpr const char* kName = "nut:name";
constexpr const char* kGenerator = "nut:generator";
constexpr const char* kUnits = "nut:units";
constexpr const char* kOrigin = "nut:origin";

std::string formatOrigin(const glm::dvec3& o) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "%.17g %.17g %.17g", o.x, o.y, o.z);
  return buffer;
}

// A sibling of `path` that no other writer picks.
std::filesystem::path temporaryPath(const std::filesystem::path& path) {
  std::random_device device;
  return path.parent_path() / (path.filename().string() + ".tmp" + std::to_string(device()));
}

}  // namespace

Status writePng(const std::string& path, const Image& image, const HniText& text) {
  if (image.width <= 0 || image.height <= 0) return Error{path + ": cannot write an empty image"};
  const std::filesystem::path target(path);
  const std::filesystem::path temporary = temporaryPath(target);
  auto out = OIIO::ImageOutput::create("png");
  if (!out) return Error{path + ": no PNG writer: " + OIIO::geterror()};
  OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);
  spec.attribute("png:compressionLevel", 9);
  if (!text.name.empty()) spec.attribute(kName, text.name);
  if (!text.generator.empty()) spec.attribute(kGenerator, text.generator);
  if (!text.units.empty()) spec.attribute(kUnits, text.units);
  spec.attribute(kOrigin, formatOrigin(text.originM));
  if (!out->open(temporary.string(), spec)) return Error{path + ": " + out->geterror()};
  const bool written = out->write_image(OIIO::TypeDesc::UINT8, image.pixels.data());
  const bool closed = out->close();
  if (!written || !closed) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    return Error{path + ": " + out->geterror()};
  }
  std::error_code error;
  std::filesystem::rename(temporary, target, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    return Error{path + ": cannot rename the written file into place"};
  }
  return Ok{};
}

Result<PngFile> readPng(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return Error{path + ": no such file"};
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) return Error{path + ": not a readable image: " + OIIO::geterror()};
  const OIIO::ImageSpec& spec = in->spec();
  if (std::string(in->format_name()) != "png") return Error{path + ": not a PNG file"};
  if (spec.format != OIIO::TypeDesc::UINT8) return Error{path + ": not an 8-bit PNG"};
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels < 1 || spec.nchannels > 4)
    return Error{path + ": unsupported PNG layout"};
  PngFile file;
  file.image = Image(spec.width, spec.height);
  // Read the channels the file has, then widen to RGBA (grey -> RGB, missing alpha = 255).
  std::vector<std::uint8_t> raw(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) *
                                static_cast<std::size_t>(spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, raw.data()))
    return Error{path + ": " + in->geterror()};
  const int n = spec.nchannels;
  for (std::size_t i = 0; i < raw.size() / static_cast<std::size_t>(n); ++i) {
    const std::uint8_t* s = raw.data() + i * static_cast<std::size_t>(n);
    std::uint8_t* d = file.image.pixels.data() + i * 4;
    const bool grey = n <= 2;
    d[0] = s[0];
    d[1] = grey ? s[0] : s[1];
    d[2] = grey ? s[0] : s[2];
    d[3] = n == 2 ? s[1] : (n == 4 ? s[3] : 255);
  }
  file.text.name = spec.get_string_attribute(kName);
  file.text.generator = spec.get_string_attribute(kGenerator);
  file.text.units = spec.get_string_attribute(kUnits, "m");
  std::istringstream origin(spec.get_string_attribute(kOrigin, "0 0 0"));
  origin >> file.text.originM.x >> file.text.originM.y >> file.text.originM.z;
  if (!origin) return Error{path + ": malformed nut:origin text chunk"};
  file.fileBytes = std::filesystem::file_size(path, error);
  return file;
}

}  // namespace nut
