// PNG reading through OpenImageIO and writing through our encoder (png_encode.hpp), bit-exact for
// RGBA8, with the HNI text chunks; PFM and text files with the same atomic-write rule.
#include <nut/png_io.hpp>

#include <OpenImageIO/imageio.h>
#include <zlib.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>

namespace nut {

namespace {

constexpr const char* kName = "nut:name";
constexpr const char* kGenerator = "nut:generator";
constexpr const char* kUnits = "nut:units";
constexpr const char* kOrigin = "nut:origin";

// A sibling of `path` that no other writer picks.
std::filesystem::path temporaryPath(const std::filesystem::path& path) {
  std::random_device device;
  return path.parent_path() / (path.filename().string() + ".tmp" + std::to_string(device()));
}

// OpenImageIO's error text may span lines (libpng adds its own); keep the first.
std::string firstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

std::uint32_t readBigEndian32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) << 24 | static_cast<std::uint32_t>(p[1]) << 16 |
         static_cast<std::uint32_t>(p[2]) << 8 | p[3];
}

// Walks the PNG chunk structure (signature, lengths, CRCs, IHDR first, IEND last) so that a
// truncated or corrupted file gets one precise error instead of a decoder's complaint midway.
Status checkPngStructure(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), {}};
  static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() < 8 || !std::equal(kSignature, kSignature + 8, bytes.begin()))
    return Error{path + ": not a PNG file (bad signature)"};
  std::size_t at = 8;
  bool first = true;
  while (true) {
    if (bytes.size() - at < 12)
      return Error{path + ": truncated PNG: chunk header at byte " + std::to_string(at) + " runs past the end"};
    const std::uint32_t length = readBigEndian32(&bytes[at]);
    const std::string type(bytes.begin() + static_cast<std::ptrdiff_t>(at) + 4, bytes.begin() + static_cast<std::ptrdiff_t>(at) + 8);
    if (length > bytes.size() - at - 12)
      return Error{path + ": truncated PNG: chunk " + type + " at byte " + std::to_string(at) + " needs " +
                   std::to_string(length) + " bytes, " + std::to_string(bytes.size() - at - 12) + " remain"};
    const auto crc = crc32(crc32(0L, Z_NULL, 0), &bytes[at + 4], length + 4);
    if (crc != readBigEndian32(&bytes[at + 8 + length]))
      return Error{path + ": corrupt PNG: CRC mismatch in chunk " + type + " at byte " + std::to_string(at)};
    if (first && type != "IHDR") return Error{path + ": corrupt PNG: first chunk is " + type + ", not IHDR"};
    first = false;
    at += 12 + length;
    if (type == "IEND") return Ok{};
  }
}

// Writes bytes to a temporary sibling and renames it over `path`.
Status writeAtomically(const std::string& path, const std::string& bytes) {
  const std::filesystem::path target(path);
  const std::filesystem::path temporary = temporaryPath(target);
  {
    std::ofstream out(temporary, std::ios::binary);
    if (!out) return Error{path + ": cannot create the file"};
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out.flush()) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      return Error{path + ": write failed"};
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, target, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    return Error{path + ": cannot rename the written file into place"};
  }
  return Ok{};
}

}  // namespace

Status writePfm(const std::string& path, int width, int height, const std::vector<float>& values) {
  if (width <= 0 || height <= 0 || values.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    return Error{path + ": PFM size does not match its values"};
  std::string bytes = "Pf\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
  const std::size_t header = bytes.size();
  bytes.resize(header + values.size() * sizeof(float));
  for (int y = 0; y < height; ++y)  // PFM stores the bottom row first
    std::memcpy(&bytes[header + static_cast<std::size_t>(y) * static_cast<std::size_t>(width) * sizeof(float)],
                &values[static_cast<std::size_t>(height - 1 - y) * static_cast<std::size_t>(width)],
                static_cast<std::size_t>(width) * sizeof(float));
  return writeAtomically(path, bytes);
}

Status writeTextFile(const std::string& path, const std::string& text) { return writeAtomically(path, text); }

Result<std::string> readTextFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return Error{path + ": is a directory, not a file"};
  std::ifstream file(path, std::ios::binary);
  if (!file) return Error{path + ": cannot open (" + std::strerror(errno) + ")"};
  std::string text;
  try {
    // libstdc++ reports some read errors by throwing even without an exception mask.
    text.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  } catch (const std::ios_base::failure& e) {
    return Error{path + ": read error (" + e.what() + ")"};
  }
  if (file.bad()) return Error{path + ": read error"};
  return text;
}

Status writePng(const std::string& path, const Image& image, PngEffort effort) {
  if (image.width <= 0 || image.height <= 0) return Error{path + ": cannot write an empty image"};
  return writeAtomically(path, encodePng(image, nullptr, effort));
}

Status writeHni(const std::string& path, const Image& image, const HniText& text, PngEffort effort) {
  if (image.width <= 0 || image.height <= 0) return Error{path + ": cannot write an empty image"};
  return writeAtomically(path, encodePng(image, &text, effort));
}

Result<PngFile> readPng(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return Error{path + ": no such file"};
  if (Status s = checkPngStructure(path); !s) return s.error();
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) return Error{path + ": not a readable image: " + firstLine(OIIO::geterror())};
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
    return Error{path + ": " + firstLine(in->geterror())};
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
