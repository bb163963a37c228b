// UTF-8 validation against the well-formed byte sequences of Unicode 15,
// Table 3-7 (the boundaries of every row, and one step past them).

#include <gtest/gtest.h>

#include <string>

#include "meridian/core/utf8.hpp"

namespace {

using meridian::first_invalid_utf8;

TEST(Utf8, AcceptsEveryRowOfTable3_7AtItsBoundaries) {
  for (const std::string s :
       {"", "plain ASCII \x7F", "\xC2\x80", "\xDF\xBF", "\xE0\xA0\x80", "\xE0\xBF\xBF",
        "\xE1\x80\x80", "\xEC\xBF\xBF", "\xED\x80\x80", "\xED\x9F\xBF", "\xEE\x80\x80",
        "\xEF\xBF\xBF", "\xF0\x90\x80\x80", "\xF0\xBF\xBF\xBF", "\xF1\x80\x80\x80",
        "\xF3\xBF\xBF\xBF", "\xF4\x80\x80\x80", "\xF4\x8F\xBF\xBF", "K\xC3\xB6ln \xE5\x8C\x97"})
    EXPECT_FALSE(first_invalid_utf8(s).has_value()) << s;
}

TEST(Utf8, RejectsIllFormedSequencesAtTheirFirstByte) {
  struct Case {
    std::string text;
    std::size_t at;
  };
  for (const Case& c : std::initializer_list<Case>{{"K\xF6ln", 1},       // Latin-1
                                                   {"\x80", 0},          // stray continuation byte
                                                   {"ab\xC0\xAF", 2},    // overlong '/'
                                                   {"\xC1\xBF", 0},      // overlong
                                                   {"\xE0\x9F\xBF", 0},  // overlong 3-byte
                                                   {"\xED\xA0\x80", 0},  // surrogate U+D800
                                                   {"\xF0\x8F\xBF\xBF", 0},  // overlong 4-byte
                                                   {"\xF4\x90\x80\x80", 0},  // above U+10FFFF
                                                   {"\xF5\x80\x80\x80", 0},  // lead byte never used
                                                   {"\xFF", 0},
                                                   {"ok\xE2\x82", 2},     // truncated
                                                   {"\xE2\x28\xA1", 0},   // bad second byte
                                                   {"\xE2\x82\x28", 0}})  // bad third byte
    EXPECT_EQ(first_invalid_utf8(c.text), c.at) << c.text;
}

}  // namespace
