// The byte framing of obj_fuzz, shared by the target and its seed writer: OBJ text, then optionally
// kMtlSeparator and MTL text.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace nut::fuzz {

inline constexpr std::string_view kMtlSeparator = "\n--mtl--\n";

struct ObjInput {
  std::string_view obj, mtl;
  bool hasMtl = false;
};

inline ObjInput splitObjInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const std::size_t at = bytes.find(kMtlSeparator);
  if (at == std::string_view::npos) return {bytes, {}, false};
  return {bytes.substr(0, at), bytes.substr(at + kMtlSeparator.size()), true};
}

inline std::string joinObjInput(const std::string& obj, const std::string& mtl) {
  return obj + std::string(kMtlSeparator) + mtl;
}

}  // namespace nut::fuzz
