// PNG reading through libpng and writing through our encoder (png_encode.hpp), bit-exact for
// RGBA8, with the HNI text chunks; PFM and text files with the same atomic-write rule.
//
// libpng rather than an image library such as OpenImageIO: a PNG is the only image we read, and
// loading OpenImageIO's plugins' 260 shared libraries took 0.25 s at the start of every process.
#include <nut/png_io.hpp>

#include <png.h>
#include <zlib.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>

#include <nut/format.hpp>

#include "atomic_file.hpp"

namespace nut {

namespace {

constexpr const char* kName = "nut:name";
constexpr const char* kGenerator = "nut:generator";
constexpr const char* kUnits = "nut:units";
constexpr const char* kOrigin = "nut:origin";

std::uint32_t readBigEndian32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) << 24 | static_cast<std::uint32_t>(p[1]) << 16 |
         static_cast<std::uint32_t>(p[2]) << 8 | p[3];
}

// The size an IHDR chunk's data declares, refused over the kind's bound (png_io.hpp).
Status checkDeclaredSize(const std::string& path, const std::uint8_t* ihdr, PngKind kind) {
  const std::uint32_t width = readBigEndian32(ihdr), height = readBigEndian32(ihdr + 4);
  const bool hni = kind == PngKind::Hni;
  const auto most = static_cast<std::uint32_t>(hni ? format::kMaxImageSize : kMaxRenderSize);
  if (width <= most && height <= most) return Ok{};
  return Error{path + ": the PNG declares " + std::to_string(width) + "x" + std::to_string(height) + " pixels; " +
               (hni ? "an HNI" : "a render") + " has at most " + std::to_string(most) + "x" + std::to_string(most)};
}

// Walks the PNG chunk structure (signature, lengths, CRCs, IHDR first with a size within the
// kind's bound, IEND last) so that a truncated, corrupted or oversized file gets one precise error
// instead of a decoder's complaint midway, or an allocation the size of what the file declares.
Status checkPngStructure(const std::string& path, const std::vector<std::uint8_t>& bytes, PngKind kind) {
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
    if (first && length >= 8)  // a shorter IHDR is libpng's error to report
      if (Status s = checkDeclaredSize(path, &bytes[at + 8], kind); !s) return s;
    first = false;
    at += 12 + length;
    if (type == "IEND") return Ok{};
  }
}

// A decode in progress. It lives on the heap: libpng reports errors by longjmp back to
// decodePng, after which automatic variables changed since the setjmp would be indeterminate.
struct PngDecode {
  const std::vector<std::uint8_t>* bytes = nullptr;
  std::size_t at = 0;  // next byte libpng reads
  std::string error;
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  std::vector<png_bytep> rows;
  std::vector<std::pair<std::string, std::string>> text;  // keyword, value; later chunks win
};

void onPngError(png_structp png, png_const_charp message) {
  static_cast<PngDecode*>(png_get_error_ptr(png))->error = message;
  png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {}  // warnings (unknown chunks, sRGB profiles) are not errors here

void readFromMemory(png_structp png, png_bytep out, png_size_t length) {
  auto* decode = static_cast<PngDecode*>(png_get_io_ptr(png));
  if (length > decode->bytes->size() - decode->at) png_error(png, "read past the end of the file");
  std::memcpy(out, decode->bytes->data() + decode->at, length);
  decode->at += length;
}

void collectText(png_structp png, png_infop info, PngDecode& decode) {
  png_textp text = nullptr;
  const int count = png_get_text(png, info, &text, nullptr);
  for (int i = 0; i < count; ++i) decode.text.emplace_back(text[i].key, text[i].text ? text[i].text : "");
}

// Everything that may longjmp; no automatic object here has a destructor to skip.
void decodeInto(png_structp png, png_infop info, png_infop end, PngDecode& decode) {
  png_set_read_fn(png, &decode, readFromMemory);
  png_read_info(png, info);
  if (png_get_bit_depth(png, info) > 8) png_error(png, "not an 8-bit PNG (16 bits per channel)");
  decode.width = static_cast<int>(png_get_image_width(png, info));
  decode.height = static_cast<int>(png_get_image_height(png, info));  // bounded by checkDeclaredSize
  // Widen whatever the file holds to RGBA8 as stored: palette and grey to RGB, transparency
  // chunks to alpha, missing alpha = 255. No gamma or colour conversion is asked for.
  const png_byte colour = png_get_color_type(png, info);
  if (colour == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colour == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  if (colour == PNG_COLOR_TYPE_GRAY || colour == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
  png_set_filler(png, 0xff, PNG_FILLER_AFTER);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const std::size_t stride = static_cast<std::size_t>(decode.width) * 4;
  if (png_get_rowbytes(png, info) != stride) png_error(png, "unsupported PNG layout");
  decode.rgba.resize(stride * static_cast<std::size_t>(decode.height));
  decode.rows.resize(static_cast<std::size_t>(decode.height));
  for (std::size_t y = 0; y < decode.rows.size(); ++y) decode.rows[y] = decode.rgba.data() + y * stride;
  png_read_image(png, decode.rows.data());
  png_read_end(png, end);
  collectText(png, info, decode);
  collectText(png, end, decode);
}

// Decodes a file whose chunk structure checkPngStructure accepted; errors name the file.
Status decodePng(const std::string& path, const std::vector<std::uint8_t>& bytes, PngDecode& decode) {
  decode.bytes = &bytes;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &decode, onPngError, onPngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  png_infop end = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info || !end) {
    png_destroy_read_struct(&png, &info, &end);
    return Error{path + ": out of memory to decode the PNG"};
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, &end);
    return Error{path + ": " + decode.error};
  }
  decodeInto(png, info, end, decode);
  png_destroy_read_struct(&png, &info, &end);
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
  return files::writeWhole(path, bytes);
}

Status writeTextFile(const std::string& path, const std::string& text) { return files::writeWhole(path, text); }

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
  return files::writeWhole(path, encodePng(image, nullptr, effort));
}

Status writeHni(const std::string& path, const Image& image, const HniText& text, PngEffort effort) {
  if (image.width <= 0 || image.height <= 0) return Error{path + ": cannot write an empty image"};
  return files::writeWhole(path, encodePng(image, &text, effort));
}

Result<PngFile> readPng(const std::string& path, PngKind kind) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return Error{path + ": no such file"};
  std::vector<std::uint8_t> bytes;
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) return Error{path + ": cannot open (" + std::strerror(errno) + ")"};
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  return readPngBytes(path, std::move(bytes), kind);
}

Result<PngFile> readPngBytes(const std::string& path, std::vector<std::uint8_t> bytes, PngKind kind) {
  if (Status s = checkPngStructure(path, bytes, kind); !s) return s.error();
  const auto decode = std::make_unique<PngDecode>();
  if (Status s = decodePng(path, bytes, *decode); !s) return s.error();
  PngFile file;
  file.image.width = decode->width;
  file.image.height = decode->height;
  file.image.pixels = std::move(decode->rgba);
  file.text.units = "m";
  std::string origin = "0 0 0";
  for (const auto& [key, value] : decode->text) {
    if (key == kName) file.text.name = value;
    if (key == kGenerator) file.text.generator = value;
    if (key == kUnits) file.text.units = value;
    if (key == kOrigin) origin = value;
  }
  std::istringstream originStream(origin);
  originStream >> file.text.originM.x >> file.text.originM.y >> file.text.originM.z;
  if (!originStream) return Error{path + ": malformed nut:origin text chunk"};
  file.fileBytes = bytes.size();
  return file;
}

}  // namespace nut
