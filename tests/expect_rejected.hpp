// Test helper: an HNI that validate() must refuse with a message containing `needle`, and that
// decode() refuses too.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include <nut/hni.hpp>

namespace nut::testing {

inline void expectRejected(const Image& image, const std::string& needle) {
  const Status s = validate(image);
  ASSERT_FALSE(s.ok()) << "accepted; expected: " << needle;
  EXPECT_NE(s.error().message.find(needle), std::string::npos) << s.error().message;
  EXPECT_FALSE(decode(image).ok());
}

}  // namespace nut::testing
