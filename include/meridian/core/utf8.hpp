#pragma once
/// \file utf8.hpp
/// UTF-8 validation for text read from files (names, descriptions, remarks),
/// so that text which ends up in JSON or HTML is known to be valid there.
/// The rules are those of RFC 3629 §4 (Unicode 15, Table 3-7 "Well-Formed
/// UTF-8 Byte Sequences"): no overlong forms, no surrogates (U+D800–DFFF),
/// nothing above U+10FFFF.

#include <cstddef>
#include <optional>
#include <string_view>

namespace meridian {

/// Byte offset of the first byte that does not begin a well-formed UTF-8
/// sequence in `text` (a stray continuation byte, a lead byte such as 0xC0,
/// 0xC1, 0xF5–0xFF, or a sequence that is truncated, overlong, a surrogate
/// or above U+10FFFF); nullopt when all of `text` is well-formed UTF-8.
inline std::optional<std::size_t> first_invalid_utf8(std::string_view text) noexcept {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  std::size_t i = 0;
  while (i < text.size()) {
    const unsigned char b = byte(i);
    if (b < 0x80) {
      ++i;
      continue;
    }
    std::size_t len = 0;
    unsigned char lo = 0x80, hi = 0xBF;  // allowed range of the second byte
    if (b >= 0xC2 && b <= 0xDF) len = 2;
    else if (b == 0xE0) len = 3, lo = 0xA0;
    else if (b == 0xED) len = 3, hi = 0x9F;  // no surrogates
    else if (b >= 0xE1 && b <= 0xEF) len = 3;
    else if (b == 0xF0) len = 4, lo = 0x90;
    else if (b == 0xF4) len = 4, hi = 0x8F;  // ≤ U+10FFFF
    else if (b >= 0xF1 && b <= 0xF3) len = 4;
    else return i;
    if (i + len > text.size() || byte(i + 1) < lo || byte(i + 1) > hi) return i;
    for (std::size_t k = 2; k < len; ++k)
      if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return i;
    i += len;
  }
  return std::nullopt;
}

}  // namespace meridian
