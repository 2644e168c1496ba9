// Fuzz target hni_fuzz: arbitrary bytes as an HNI image must never crash validate/decode, and what
// validate accepts must decode, measure and re-encode to a valid image.
// Input framing (see frame.hpp): u16 width, then RGBA8 pixels; the height is what the bytes fill.
#include <cstdint>
#include <cstdlib>

#include <nut/hni.hpp>

#include "frame.hpp"
#include "targets.hpp"

int nut::fuzz::hniInput(const std::uint8_t* data, std::size_t size) {
  const nut::Image image = nut::fuzz::unframe(data, size);
  if (!nut::validate(image).ok()) return 0;
  auto decoded = nut::decode(image);
  if (!decoded.ok()) std::abort();  // validate accepted what decode refuses
  (void)nut::computeStats(image);
  auto again = nut::compile(*decoded);
  // A valid image may still break a compile limit (e.g. records beyond the search width), but what
  // compile produces must validate.
  if (again.ok() && !nut::validate(*again).ok()) std::abort();
  return 0;
}
