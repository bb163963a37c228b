#pragma once
/// \file unicode.hpp
/// Unicode normalisation of names read from files, so that the same point
/// booked with other code points is recognised as the same: a full-width
/// "Ⅱ３" (U+FF13) and "Ⅱ3", an ideographic space, a ligature. The form is
/// NFKC (Unicode Standard Annex #15, "Unicode Normalization Forms"):
/// compatibility decomposition, then canonical composition. It folds
/// compatibility characters to their plain forms — "Ⅱ" (U+2161 ROMAN NUMERAL
/// TWO) becomes "II", "３" becomes "3" — and keeps case, so "ii3" is another
/// name. Computed by utf8proc (Unicode 15 tables in Debian 12's 2.8.0).

#include <string>
#include <string_view>

namespace meridian {

/// `text` in NFKC. Throws InputError when `text` is not well-formed UTF-8
/// (utf8.hpp's rules; readers validate text before it gets here).
std::string nfkc(std::string_view text);

/// Whether two names are the same after NFKC (nfkc(a) == nfkc(b)).
bool same_name_nfkc(std::string_view a, std::string_view b);

}  // namespace meridian
