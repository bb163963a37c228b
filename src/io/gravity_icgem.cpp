#include "meridian/io/gravity_icgem.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/utf8.hpp"
#include "gravity_text.hpp"

namespace meridian::io {
namespace {

using gravity::GravityModelData;
using gravity::SphericalHarmonicCoefficients;

// Gfc lines a complete model to degree n, order m needs (2 ≤ degree; degrees
// 0 and 1 may be omitted).
std::uint64_t required_lines(int n, int m) {
  if (n < 2) return 0;
  const std::uint64_t N = static_cast<std::uint64_t>(n), M = static_cast<std::uint64_t>(m);
  const std::uint64_t k = std::min(N, M);  // degrees 2..k have every order
  const std::uint64_t full = k >= 2 ? (k + 1) * (k + 2) / 2 - 3 : 0;
  return full + (N - std::max<std::uint64_t>(k, 1)) * (M + 1);
}

// One pass over the text of a .gfc file: the header lines up to end_of_head, then the gfc
// lines, then the completeness check. Errors name the file and the current line.
class IcgemParser {
 public:
  IcgemParser(std::string file, const std::string& text, const gravity::Truncation& truncation)
      : file_(std::move(file)), text_(text), truncation_(truncation) {
    model_.source_file = file_;
  }

  GravityModelData parse(const std::filesystem::path& path) {
    std::size_t pos = 0;
    while (pos < text_.size()) {
      const std::size_t eol = std::min(text_.find('\n', pos), text_.size());
      const std::string_view line(text_.data() + pos, eol - pos);
      pos = eol + 1;
      ++line_no_;
      if (line.size() > detail::kMaxTextLineBytes) throw detail::line_too_long(file_, line_no_);
      detail::split_fields(line, f_);
      if (f_.empty()) continue;
      if (in_header_) header_line();
      else gfc_line();
    }
    finish();
    if (model_.name.empty()) model_.name = path.stem().string();
    return std::move(model_);
  }

 private:
  ParseError fail(const std::string& msg, const std::string& field = {}) const {
    return ParseError(msg, {file_, line_no_, field});
  }

  // Header text that reaches outputs (JSON, HTML) must be UTF-8.
  std::string text_value(std::string_view v, const char* key) const {
    if (const auto bad = first_invalid_utf8(v))
      throw fail(fmt::format("{} is not UTF-8 text (byte 0x{:02X} at position {})", key,
                             static_cast<unsigned char>(v[*bad]), *bad + 1),
                 key);
    return std::string(v);
  }

  double positive_number(const char* what) const {
    if (f_.size() < 2) throw fail(fmt::format("{} has no value", what), what);
    const auto v = detail::parse_double(f_[1]);
    if (!v || !std::isfinite(*v) || *v <= 0)
      throw fail(fmt::format("{} must be a positive number, got \"{}\"", what, f_[1]), what);
    return *v;
  }

  // A key that means something here, given a second time: refused (which one would win is
  // not for the reader to guess).
  void once(const std::string& key) {
    static constexpr std::string_view kKeys[] = {"earth_gravity_constant", "radius", "max_degree", "modelname",
                                                 "tide_system", "product_type", "norm", "errors"};
    if (std::find(std::begin(kKeys), std::end(kKeys), key) == std::end(kKeys)) return;
    const auto [it, fresh] = key_lines_.emplace(key, line_no_);
    if (!fresh)
      throw fail(fmt::format("{} is given twice in the header, on lines {} and {}", key, it->second, line_no_), key);
  }

  void header_line() {
    const std::string key = detail::lower(f_[0]);
    once(key);
    if (key == "end_of_head") end_of_head();
    else if (key == "earth_gravity_constant") {
      gm_ = positive_number("earth_gravity_constant");
      detail::check_model_gm(*gm_, file_, line_no_, "earth_gravity_constant");
    } else if (key == "radius") {
      radius_ = positive_number("radius");
      detail::check_model_radius(*radius_, file_, line_no_, "radius");
    }
    else if (key == "max_degree") {
      const auto v = f_.size() >= 2 ? detail::parse_int(f_[1]) : std::nullopt;
      if (!v || *v < 0) throw fail("max_degree must be a non-negative integer", "max_degree");
      max_degree_ = *v;
    } else if (key == "modelname" && f_.size() >= 2) model_.name = text_value(f_[1], "modelname");
    else if (key == "tide_system" && f_.size() >= 2) model_.tide_system = text_value(f_[1], "tide_system");
    else if (key == "product_type" && f_.size() >= 2 && detail::lower(f_[1]) != "gravity_field")
      throw fail(fmt::format("product_type \"{}\" is not a gravity_field", f_[1]), "product_type");
    else if (key == "norm" && f_.size() >= 2 && detail::lower(f_[1]) != "fully_normalized")
      throw fail(fmt::format("normalisation \"{}\" is not supported (only fully_normalized)", f_[1]), "norm");
    else if (key == "norm" && f_.size() >= 2) model_.normalization = std::string(f_[1]);
  }

  // The header is complete: the kept degree and order, and the coefficient set allocated.
  void end_of_head() {
    in_header_ = false;
    if (!gm_) throw fail("header has no earth_gravity_constant", "earth_gravity_constant");
    if (!radius_) throw fail("header has no radius", "radius");
    if (!max_degree_) throw fail("header has no max_degree", "max_degree");
    N_ = truncation_.max_degree < 0 ? *max_degree_ : std::min(truncation_.max_degree, *max_degree_);
    const int mo = truncation_.max_order < 0 ? N_ : truncation_.max_order;
    M_ = std::min(mo, N_);
    // A header's degree is a claim about the file: check it against the
    // file's size before allocating (the shortest line "gfc 2 0 0 0" has
    // 11 characters and a line end), so memory stays proportional to it.
    const std::uint64_t lines = required_lines(N_, M_), bytes = lines > 0 ? 12 * lines - 1 : 0;
    if (bytes > text_.size())
      throw fail(fmt::format("max_degree {} cannot be right: a complete model to degree {} (order {}) has {} gfc "
                             "lines, at least {} bytes, and the file has {} bytes",
                             *max_degree_, N_, M_, lines, bytes, text_.size()),
                 "max_degree");
    model_.file_max_degree = *max_degree_;
    model_.coefficients = SphericalHarmonicCoefficients(N_, M_);
    seen_.assign(model_.coefficients.size(), 0);
  }

  void gfc_line() {
    const std::string key = detail::lower(f_[0]);
    if (key == "gfct" || key == "trnd" || key == "acos" || key == "asin" || key == "dot")
      throw fail(fmt::format("time-variable record \"{}\" is not supported (static gfc models only)", f_[0]), key);
    if (key != "gfc") throw fail(fmt::format("unknown record \"{}\" (expected gfc)", f_[0]));
    if (f_.size() < 5) throw fail(fmt::format("gfc line has {} fields, expected at least 5 (gfc n m C S)", f_.size()));
    const auto n = detail::parse_int(f_[1]), m = detail::parse_int(f_[2]);
    if (!n || !m) throw fail("degree and order must be integers", "n m");
    if (*m < 0 || *n < *m) throw fail(fmt::format("invalid (n, m) = ({}, {})", *n, *m), "n m");
    if (*n > model_.file_max_degree)
      throw fail(fmt::format("degree {} exceeds the header's max_degree {}", *n, model_.file_max_degree), "n");
    const auto c = detail::parse_double(f_[3]), s = detail::parse_double(f_[4]);
    if (!c || !std::isfinite(*c)) throw fail(fmt::format("C is not a number: \"{}\"", f_[3]), "C");
    if (!s || !std::isfinite(*s)) throw fail(fmt::format("S is not a number: \"{}\"", f_[4]), "S");
    // Fully normalised coefficients are at most 1 in absolute value (C̄00 = 1).
    if (std::abs(*c) > 1) throw fail(fmt::format("C = {:g} is not a fully normalised coefficient (|C| <= 1)", *c), "C");
    if (std::abs(*s) > 1) throw fail(fmt::format("S = {:g} is not a fully normalised coefficient (|S| <= 1)", *s), "S");
    for (std::size_t i = 5; i < f_.size(); ++i)
      if (!detail::parse_double(f_[i])) throw fail(fmt::format("field {} is not a number: \"{}\"", i + 1, f_[i]));
    if (*n > N_ || *m > M_) return;  // truncated away
    const std::size_t k = model_.coefficients.index(*n, *m);
    if (seen_[k] != 0)
      throw fail(fmt::format("duplicate coefficient (n, m) = ({}, {}), first given on line {}", *n, *m, seen_[k]), "n m");
    seen_[k] = line_no_;
    if (*m == 0 && *s != 0) throw fail(fmt::format("S for order 0 must be zero, got {}", *s), "S");
    model_.coefficients.set(*n, *m, *c, *s);
  }

  // After the last line: a header was ended and every kept coefficient of degree ≥ 2 given.
  void finish() {
    if (in_header_) throw ParseError("no end_of_head line: not an ICGEM file or truncated header", {file_, line_no_, ""});
    if (!seen_.empty() && seen_[0] == 0) model_.coefficients.set(0, 0, 1.0, 0.0);
    for (int n = 2; n <= N_; ++n)
      for (int m = 0; m <= std::min(n, M_); ++m)
        if (seen_[model_.coefficients.index(n, m)] == 0)
          throw ParseError(fmt::format("missing coefficient (n, m) = ({}, {}) (file truncated or incomplete?)", n, m),
                           {file_, line_no_, "gfc"});
    model_.gm_m3_s2 = *gm_;
    model_.radius_m = *radius_;
  }

  std::string file_;
  const std::string& text_;
  gravity::Truncation truncation_;
  GravityModelData model_;
  std::optional<double> gm_, radius_;
  std::optional<int> max_degree_;
  std::vector<std::string_view> f_;
  std::vector<int> seen_;  // line where (n, m) was given, 0 = not yet
  std::map<std::string, int> key_lines_;  // header key → its line
  int line_no_ = 0;
  bool in_header_ = true;
  int N_ = -1, M_ = -1;
};

}  // namespace

GravityModelData read_icgem_file(const std::filesystem::path& path, const gravity::Truncation& truncation) {
  const std::string text = detail::read_whole_file(path, "gravity model file");
  return IcgemParser(path.string(), text, truncation).parse(path);
}

std::string format_icgem(const GravityModelData& model) {
  const SphericalHarmonicCoefficients& c = model.coefficients;
  fmt::memory_buffer b;
  fmt::format_to(std::back_inserter(b),
                 "generated by Meridian\n{}\nbegin_of_head\nproduct_type gravity_field\nmodelname {}\n"
                 "earth_gravity_constant {:.17g}\nradius {:.17g}\nmax_degree {}\nnorm fully_normalized\n"
                 "tide_system {}\nerrors no\nkey L M C S\nend_of_head\n",
                 model.description, model.name, model.gm_m3_s2, model.radius_m, c.max_degree(),
                 model.tide_system.empty() ? "unknown" : model.tide_system);
  for (int n = 0; n <= c.max_degree(); ++n)
    for (int m = 0; m <= std::min(n, c.max_order()); ++m)
      fmt::format_to(std::back_inserter(b), "gfc {} {} {:.16e} {:.16e}\n", n, m, c.c(n, m), c.s(n, m));
  return fmt::to_string(b);
}

}  // namespace meridian::io
