#include <gtest/gtest.h>

#include "meridian/core/error.hpp"
#include "meridian/core/unicode.hpp"

namespace {

using meridian::nfkc;
using meridian::same_name_nfkc;

TEST(Unicode, NfkcAsPythonsUnicodedataGivesIt) {
  // Expected values from Python 3.11's unicodedata.normalize("NFKC", s), an independent implementation.
  EXPECT_EQ(nfkc("\u2161\uFF13"), "II3");                 // Ⅱ３: Roman numeral two, full-width three
  EXPECT_EQ(nfkc("\u21613"), "II3");                      // Ⅱ3
  EXPECT_EQ(nfkc("\uFF2A\uFF34\uFF11\uFF15"), "JT15");    // ＪＴ１５
  EXPECT_EQ(nfkc("e\u0301"), "\xC3\xA9");                 // e + combining acute composes to é
  EXPECT_EQ(nfkc("\uFB01"), "fi");                        // the ligature ﬁ
  EXPECT_EQ(nfkc("\u2161\u30003"), "II 3");               // an ideographic space is a space
  EXPECT_EQ(nfkc("\u4E95\u4E0B\u5BFC\u7EBF\u70B9\u21614"), "\u4E95\u4E0B\u5BFC\u7EBF\u70B9II4");  // 井下导线点Ⅱ4
  EXPECT_EQ(nfkc("ii3"), "ii3");                          // case is kept
  EXPECT_EQ(nfkc(""), "");
}

TEST(Unicode, SameNameAfterNfkc) {
  EXPECT_TRUE(same_name_nfkc("\u21613", "\u2161\uFF13"));
  EXPECT_TRUE(same_name_nfkc("\u21613", "II3"));
  EXPECT_FALSE(same_name_nfkc("\u21613", "\u21614"));
  EXPECT_FALSE(same_name_nfkc("II3", "ii3"));
  EXPECT_THROW((void)nfkc("K\xF6ln"), meridian::InputError);  // Latin-1, not UTF-8
}

}  // namespace
