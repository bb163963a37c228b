#include "meridian/gravity/icgem.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <sstream>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/core/utf8.hpp"
#include "text_util.hpp"

namespace meridian::gravity {
namespace {

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open gravity model file", {path.string(), {}, ""});
  std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw IoError("error reading gravity model file", {path.string(), {}, ""});
  return s;
}

// Gfc lines a complete model to degree n, order m needs (2 ≤ degree; degrees
// 0 and 1 may be omitted).
std::uint64_t required_lines(int n, int m) {
  if (n < 2) return 0;
  const std::uint64_t N = static_cast<std::uint64_t>(n), M = static_cast<std::uint64_t>(m);
  const std::uint64_t k = std::min(N, M);  // degrees 2..k have every order
  const std::uint64_t full = k >= 2 ? (k + 1) * (k + 2) / 2 - 3 : 0;
  return full + (N - std::max<std::uint64_t>(k, 1)) * (M + 1);
}

std::string lower(std::string_view s) {
  std::string r(s);
  std::transform(r.begin(), r.end(), r.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return r;
}

}  // namespace

GravityModelData read_icgem_file(const std::filesystem::path& path, const Truncation& truncation) {
  const std::string file = path.string();
  const std::string text = slurp(path);
  GravityModelData model;
  model.source_file = file;
  std::optional<double> gm, radius;
  std::optional<int> max_degree;
  std::vector<std::string_view> f;
  std::size_t pos = 0;
  int line_no = 0;
  bool in_header = true;
  auto fail = [&](const std::string& msg, const std::string& field = {}) -> ParseError {
    return ParseError(msg, {file, line_no, field});
  };
  // Header text that reaches outputs (JSON, HTML) must be UTF-8.
  auto text_value = [&](std::string_view v, const char* key) {
    if (const auto bad = first_invalid_utf8(v))
      throw fail(fmt::format("{} is not UTF-8 text (byte 0x{:02X} at position {})", key,
                             static_cast<unsigned char>(v[*bad]), *bad + 1),
                 key);
    return std::string(v);
  };
  std::vector<int> seen;  // line where (n, m) was given, 0 = not yet
  int N = -1, M = -1;
  while (pos < text.size()) {
    const std::size_t eol = std::min(text.find('\n', pos), text.size());
    const std::string_view line(text.data() + pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    detail::split_fields(line, f);
    if (f.empty()) continue;
    if (in_header) {
      const std::string key = lower(f[0]);
      if (key == "end_of_head") {
        in_header = false;
        if (!gm) throw fail("header has no earth_gravity_constant", "earth_gravity_constant");
        if (!radius) throw fail("header has no radius", "radius");
        if (!max_degree) throw fail("header has no max_degree", "max_degree");
        N = truncation.max_degree < 0 ? *max_degree : std::min(truncation.max_degree, *max_degree);
        const int mo = truncation.max_order < 0 ? N : truncation.max_order;
        M = std::min(mo, N);
        // A header's degree is a claim about the file: check it against the
        // file's size before allocating (the shortest line "gfc 2 0 0 0" has
        // 11 characters and a line end), so memory stays proportional to it.
        const std::uint64_t lines = required_lines(N, M), bytes = lines > 0 ? 12 * lines - 1 : 0;
        if (bytes > text.size())
          throw fail(fmt::format("max_degree {} cannot be right: a complete model to degree {} (order {}) has {} gfc "
                                 "lines, at least {} bytes, and the file has {} bytes",
                                 *max_degree, N, M, lines, bytes, text.size()),
                     "max_degree");
        model.file_max_degree = *max_degree;
        model.coefficients = SphericalHarmonicCoefficients(N, M);
        seen.assign(model.coefficients.size(), 0);
        continue;
      }
      auto number = [&](const char* what) {
        if (f.size() < 2) throw fail(fmt::format("{} has no value", what), what);
        const auto v = detail::parse_double(f[1]);
        if (!v || !std::isfinite(*v) || *v <= 0)
          throw fail(fmt::format("{} must be a positive number, got \"{}\"", what, f[1]), what);
        return *v;
      };
      if (key == "earth_gravity_constant") gm = number("earth_gravity_constant");
      else if (key == "radius") radius = number("radius");
      else if (key == "max_degree") {
        const auto v = f.size() >= 2 ? detail::parse_int(f[1]) : std::nullopt;
        if (!v || *v < 0) throw fail("max_degree must be a non-negative integer", "max_degree");
        max_degree = *v;
      } else if (key == "modelname" && f.size() >= 2) model.name = text_value(f[1], "modelname");
      else if (key == "tide_system" && f.size() >= 2) model.tide_system = text_value(f[1], "tide_system");
      else if (key == "product_type" && f.size() >= 2 && lower(f[1]) != "gravity_field")
        throw fail(fmt::format("product_type \"{}\" is not a gravity_field", f[1]), "product_type");
      else if (key == "norm" && f.size() >= 2 && lower(f[1]) != "fully_normalized")
        throw fail(fmt::format("normalisation \"{}\" is not supported (only fully_normalized)", f[1]), "norm");
      else if (key == "norm" && f.size() >= 2) model.normalization = std::string(f[1]);
      continue;
    }
    const std::string key = lower(f[0]);
    if (key == "gfct" || key == "trnd" || key == "acos" || key == "asin" || key == "dot")
      throw fail(fmt::format("time-variable record \"{}\" is not supported (static gfc models only)", f[0]), key);
    if (key != "gfc") throw fail(fmt::format("unknown record \"{}\" (expected gfc)", f[0]));
    if (f.size() < 5) throw fail(fmt::format("gfc line has {} fields, expected at least 5 (gfc n m C S)", f.size()));
    const auto n = detail::parse_int(f[1]), m = detail::parse_int(f[2]);
    if (!n || !m) throw fail("degree and order must be integers", "n m");
    if (*m < 0 || *n < *m) throw fail(fmt::format("invalid (n, m) = ({}, {})", *n, *m), "n m");
    if (*n > model.file_max_degree)
      throw fail(fmt::format("degree {} exceeds the header's max_degree {}", *n, model.file_max_degree), "n");
    const auto c = detail::parse_double(f[3]), s = detail::parse_double(f[4]);
    if (!c || !std::isfinite(*c)) throw fail(fmt::format("C is not a number: \"{}\"", f[3]), "C");
    if (!s || !std::isfinite(*s)) throw fail(fmt::format("S is not a number: \"{}\"", f[4]), "S");
    // Fully normalised coefficients are at most 1 in absolute value (C̄00 = 1).
    if (std::abs(*c) > 1) throw fail(fmt::format("C = {:g} is not a fully normalised coefficient (|C| <= 1)", *c), "C");
    if (std::abs(*s) > 1) throw fail(fmt::format("S = {:g} is not a fully normalised coefficient (|S| <= 1)", *s), "S");
    for (std::size_t i = 5; i < f.size(); ++i)
      if (!detail::parse_double(f[i])) throw fail(fmt::format("field {} is not a number: \"{}\"", i + 1, f[i]));
    if (*n > N || *m > M) continue;  // truncated away
    const std::size_t k = model.coefficients.index(*n, *m);
    if (seen[k] != 0)
      throw fail(fmt::format("duplicate coefficient (n, m) = ({}, {}), first given on line {}", *n, *m, seen[k]), "n m");
    seen[k] = line_no;
    if (*m == 0 && *s != 0) throw fail(fmt::format("S for order 0 must be zero, got {}", *s), "S");
    model.coefficients.set(*n, *m, *c, *s);
  }
  if (in_header) throw ParseError("no end_of_head line: not an ICGEM file or truncated header", {file, line_no, ""});
  if (!seen.empty() && seen[0] == 0) model.coefficients.set(0, 0, 1.0, 0.0);
  for (int n = 2; n <= N; ++n)
    for (int m = 0; m <= std::min(n, M); ++m)
      if (seen[model.coefficients.index(n, m)] == 0)
        throw ParseError(fmt::format("missing coefficient (n, m) = ({}, {}) (file truncated or incomplete?)", n, m),
                         {file, line_no, "gfc"});
  model.gm_m3_s2 = *gm;
  model.radius_m = *radius;
  if (model.name.empty()) model.name = path.stem().string();
  return model;
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

}  // namespace meridian::gravity
