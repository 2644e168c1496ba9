// The PNG encoder: chunks written here, filters chosen by trial compression, deflate by zlib or
// Zopfli (see png_encode.hpp).
#include <nut/png_encode.hpp>

#include <zlib.h>
#include <zopfli/deflate.h>
#include <zopfli/zopfli.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <thread>
#include <vector>

namespace nut {

namespace {

constexpr int kBytesPerPixel = 4;
constexpr int kFilterCount = 5;  // None, Sub, Up, Average, Paeth

using Bytes = std::vector<std::uint8_t>;

std::uint8_t paeth(int left, int up, int upLeft) {
  const int p = left + up - upLeft;
  const int pa = std::abs(p - left), pb = std::abs(p - up), pc = std::abs(p - upLeft);
  if (pa <= pb && pa <= pc) return static_cast<std::uint8_t>(left);
  return static_cast<std::uint8_t>(pb <= pc ? up : upLeft);
}

// Filters one scanline (`row`, with `above` the previous raw row or zeros) into `out`.
void filterRow(int filter, const std::uint8_t* row, const std::uint8_t* above, std::size_t length, std::uint8_t* out) {
  for (std::size_t i = 0; i < length; ++i) {
    const int left = i >= kBytesPerPixel ? row[i - kBytesPerPixel] : 0;
    const int upLeft = i >= kBytesPerPixel ? above[i - kBytesPerPixel] : 0;
    const int up = above[i];
    int predicted = 0;
    switch (filter) {
      case 1: predicted = left; break;
      case 2: predicted = up; break;
      case 3: predicted = (left + up) / 2; break;
      case 4: predicted = paeth(left, up, upLeft); break;
      default: break;
    }
    out[i] = static_cast<std::uint8_t>(row[i] - predicted);
  }
}

// libpng's heuristic: bytes read as signed, least sum of magnitudes.
double sumOfMagnitudes(const std::uint8_t* bytes, std::size_t length) {
  long sum = 0;
  for (std::size_t i = 0; i < length; ++i) sum += bytes[i] < 128 ? bytes[i] : 256 - bytes[i];
  return static_cast<double>(sum);
}

// Shannon entropy of the row's bytes times its length: fewer distinct, more repeated bytes win.
double entropyBits(const std::uint8_t* bytes, std::size_t length) {
  std::array<int, 256> counts{};
  for (std::size_t i = 0; i < length; ++i) ++counts[bytes[i]];
  double bits = 0;
  for (int c : counts)
    if (c > 0) bits -= c * std::log2(static_cast<double>(c) / static_cast<double>(length));
  return bits;
}

enum class Strategy { Fixed, LeastSum, LeastEntropy, Incremental };

// Bytes zlib needs for `row` after the window of `history` (up to 32 KB) already sent.
std::size_t incrementalCost(const std::uint8_t* history, std::size_t historySize, const std::uint8_t* row,
                            std::size_t length) {
  z_stream z{};
  deflateInit(&z, 6);
  const std::size_t window = std::min<std::size_t>(historySize, 32768);
  deflateSetDictionary(&z, history + historySize - window, static_cast<uInt>(window));
  std::vector<std::uint8_t> out(deflateBound(&z, static_cast<uLong>(length)) + 16);
  z.next_in = const_cast<Bytef*>(row);
  z.avail_in = static_cast<uInt>(length);
  z.next_out = out.data();
  z.avail_out = static_cast<uInt>(out.size());
  deflate(&z, Z_FINISH);
  const std::size_t size = z.total_out;
  deflateEnd(&z);
  return size;
}

// The filtered image stream: per row a filter byte, then the filtered bytes.
Bytes filterImage(const Image& image, Strategy strategy, int fixedFilter) {
  const std::size_t length = static_cast<std::size_t>(image.width) * kBytesPerPixel;
  const Bytes zeros(length, 0);
  Bytes stream((length + 1) * static_cast<std::size_t>(image.height));
  std::array<Bytes, kFilterCount> candidates;
  for (Bytes& c : candidates) c.resize(length);
  for (int y = 0; y < image.height; ++y) {
    const std::uint8_t* row = image.pixels.data() + static_cast<std::size_t>(y) * length;
    const std::uint8_t* above = y > 0 ? row - length : zeros.data();
    std::uint8_t* out = stream.data() + static_cast<std::size_t>(y) * (length + 1);
    int chosen = fixedFilter;
    if (strategy == Strategy::Fixed) {
      filterRow(chosen, row, above, length, out + 1);
    } else {
      double best = INFINITY;
      for (int f = 0; f < kFilterCount; ++f) {
        filterRow(f, row, above, length, candidates[static_cast<std::size_t>(f)].data());
        const std::uint8_t* c = candidates[static_cast<std::size_t>(f)].data();
        const double cost = strategy == Strategy::LeastSum       ? sumOfMagnitudes(c, length)
                            : strategy == Strategy::LeastEntropy ? entropyBits(c, length)
                                                                 : static_cast<double>(incrementalCost(stream.data(), static_cast<std::size_t>(y) * (length + 1), c, length));
        if (cost < best) best = cost, chosen = f;
      }
      std::memcpy(out + 1, candidates[static_cast<std::size_t>(chosen)].data(), length);
    }
    out[0] = static_cast<std::uint8_t>(chosen);
  }
  return stream;
}

Bytes zlibCompress(const Bytes& data, int level) {
  uLongf size = compressBound(static_cast<uLong>(data.size()));
  Bytes out(size);
  if (compress2(out.data(), &size, data.data(), static_cast<uLong>(data.size()), level) != Z_OK)
    throw std::runtime_error("zlib could not compress the PNG stream");  // only on out-of-memory
  out.resize(size);
  return out;
}

// Appends `bits` bits of `stream` (deflate's order: least significant bit first) to `out`, which
// holds `outBits` bits. Unused high bits of both last bytes are zero.
void appendBits(Bytes& out, std::size_t& outBits, const std::uint8_t* stream, std::size_t bits) {
  const unsigned shift = outBits % 8;
  out.resize((outBits + bits + 7) / 8, 0);
  for (std::size_t i = 0; i < (bits + 7) / 8; ++i) {
    const std::size_t at = outBits / 8 + i;
    out[at] = static_cast<std::uint8_t>(out[at] | stream[i] << shift);
    if (shift != 0 && at + 1 < out.size()) out[at + 1] = static_cast<std::uint8_t>(out[at + 1] | stream[i] >> (8 - shift));
  }
  outBits += bits;
}

// Zopfli, in one part per core: part i compresses its slice of the stream with everything before
// it as the back window, so the parts' deflate blocks join into the stream one pass would make
// (block boundaries aside) in a fraction of the time. Wrapped as zlib (header, Adler-32).
Bytes zopfliCompress(const Bytes& data) {
  ZopfliOptions options;
  ZopfliInitOptions(&options);
  // One pass: on HNI pixel streams (long runs and repeats) it is 15 % smaller than zlib's best,
  // and 5 passes gain 1 % more in 2.5 times the time.
  options.numiterations = 1;
  // Block splitting searches every split point of a stream of under 1,024 matches and literals,
  // which on a short HNI stream costs 0.05-0.3 s and pays nothing: on the 42 of Zurich's 49
  // converted buildings whose streams are under 16 KiB, one block each came out 26 B smaller in
  // all, in 0.35 s instead of 2.4 s. Longer streams gain from it (the sample building's 32 KB,
  // 80 B).
  constexpr std::size_t kMinSplitBytes = 16 * 1024;
  options.blocksplitting = data.size() >= kMinSplitBytes ? 1 : 0;
  constexpr std::size_t kMinPart = 64 * 1024;
  const std::size_t parts = std::clamp<std::size_t>(data.size() / kMinPart, 1, std::max(1u, std::thread::hardware_concurrency()));
  struct Part {
    unsigned char* bytes = nullptr;
    std::size_t size = 0;
    unsigned char bitPointer = 0;
  };
  std::vector<Part> out(parts);
  std::vector<std::thread> workers;
  for (std::size_t i = 0; i < parts; ++i)
    workers.emplace_back([&, i] {
      ZopfliDeflatePart(&options, 2, i + 1 == parts, data.data(), data.size() * i / parts, data.size() * (i + 1) / parts,
                        &out[i].bitPointer, &out[i].bytes, &out[i].size);
    });
  for (std::thread& t : workers) t.join();
  Bytes result{0x78, 0xda};  // zlib: deflate, 32 KB window, maximum compression
  std::size_t resultBits = 8 * result.size();
  for (Part& part : out) {
    // The bit pointer is how many bits of the last byte are used, 0 when it is full.
    const std::size_t bits = part.size * 8 - (part.bitPointer == 0 ? 0 : 8 - part.bitPointer);
    appendBits(result, resultBits, part.bytes, bits);
    std::free(part.bytes);
  }
  const auto adler = adler32(adler32(0L, Z_NULL, 0), data.data(), static_cast<uInt>(data.size()));
  for (int shift = 24; shift >= 0; shift -= 8) result.push_back(static_cast<std::uint8_t>(adler >> shift));
  return result;
}

// The smallest zlib stream of the image over the filter strategies the effort allows.
Bytes compressImage(const Image& image, PngEffort effort) {
  if (effort == PngEffort::Quick) return zlibCompress(filterImage(image, Strategy::LeastSum, 0), 6);
  Bytes bestStream, best;
  const auto consider = [&](Bytes stream) {
    Bytes compressed = zlibCompress(stream, 9);
    if (best.empty() || compressed.size() < best.size()) best = std::move(compressed), bestStream = std::move(stream);
  };
  // On HNIs one of these three wins among the cheap strategies (Sub on data that repeats along
  // rows, a per-row choice elsewhere); the other fixed filters and the incremental choice are
  // only worth their time for the file that is kept.
  consider(filterImage(image, Strategy::Fixed, 1));
  consider(filterImage(image, Strategy::LeastSum, 0));
  consider(filterImage(image, Strategy::LeastEntropy, 0));
  if (effort == PngEffort::Smallest) {
    for (int f : {0, 2, 3, 4}) consider(filterImage(image, Strategy::Fixed, f));
    // Zopfli runs at about 150-250 KB per second and core on HNI streams: an atlas page of 64 MB
    // would take minutes, so beyond this it keeps zlib's best (a few percent larger).
    constexpr std::size_t kMaxExhaustiveBytes = std::size_t{4} << 20;
    if (bestStream.size() <= kMaxExhaustiveBytes) {
      consider(filterImage(image, Strategy::Incremental, 0));
      Bytes zopfli = zopfliCompress(bestStream);
      if (zopfli.size() < best.size()) best = std::move(zopfli);
    }
  }
  return best;
}

void appendU32(std::string& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>(value >> shift));
}

void appendChunk(std::string& out, const char type[4], const std::uint8_t* data, std::size_t size) {
  appendU32(out, static_cast<std::uint32_t>(size));
  const std::size_t start = out.size();
  out.append(type, 4);
  out.append(reinterpret_cast<const char*>(data), size);
  const auto crc = crc32(0L, reinterpret_cast<const Bytef*>(out.data() + start), static_cast<uInt>(size + 4));
  appendU32(out, static_cast<std::uint32_t>(crc));
}

void appendText(std::string& out, const std::string& keyword, const std::string& value) {
  std::string data = keyword;
  data.push_back('\0');
  data += value;
  appendChunk(out, "tEXt", reinterpret_cast<const std::uint8_t*>(data.data()), data.size());
}

// The shortest decimal form of each coordinate that reads back as the same double.
std::string formatOrigin(const glm::dvec3& o) {
  std::string text;
  for (int a = 0; a < 3; ++a) {
    char buffer[32];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, o[a]).ptr;
    if (a > 0) text += ' ';
    text.append(buffer, end);
  }
  return text;
}

}  // namespace

std::string encodePng(const Image& image, const HniText* text, PngEffort effort) {
  std::string out = "\x89PNG\r\n\x1a\n";
  std::uint8_t header[13] = {};
  for (int i = 0; i < 4; ++i) {
    header[i] = static_cast<std::uint8_t>(static_cast<std::uint32_t>(image.width) >> (24 - 8 * i));
    header[4 + i] = static_cast<std::uint8_t>(static_cast<std::uint32_t>(image.height) >> (24 - 8 * i));
  }
  header[8] = 8;  // bits per channel
  header[9] = 6;  // colour type: RGBA
  appendChunk(out, "IHDR", header, sizeof header);
  if (text) {
    if (!text->name.empty()) appendText(out, "nut:name", text->name);
    if (!text->generator.empty()) appendText(out, "nut:generator", text->generator);
    if (!text->units.empty()) appendText(out, "nut:units", text->units);
    appendText(out, "nut:origin", formatOrigin(text->originM));
  }
  const Bytes compressed = compressImage(image, effort);
  appendChunk(out, "IDAT", compressed.data(), compressed.size());
  appendChunk(out, "IEND", nullptr, 0);
  return out;
}

}  // namespace nut
