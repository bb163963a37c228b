#include "meridian/maglev/wavelet.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "meridian/core/checks.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/scratch_array.hpp"

namespace meridian::maglev {
namespace {

#include "daubechies_filters.inc"

std::span<const double> scaling_filter(int order) {
  switch (order) {
    case 2:
      return kDb2;
    case 3:
      return kDb3;
    case 4:
      return kDb4;
    case 5:
      return kDb5;
    case 6:
      return kDb6;
    case 7:
      return kDb7;
    case 8:
      return kDb8;
    case 9:
      return kDb9;
    case 10:
      return kDb10;
    default:
      break;
  }
  throw InputError(fmt::format("Daubechies wavelet db{} is not available (db2 … db10)", order),
                   ErrorContext{{}, std::nullopt, "wavelet"});
}

// Half-sample symmetric extension: index m of the infinite extension → index in [0, n).
std::size_t symmetric_index(std::ptrdiff_t m, std::size_t n) {
  const auto period = static_cast<std::ptrdiff_t>(2 * n);
  std::ptrdiff_t p = m % period;
  if (p < 0) p += period;
  return p < static_cast<std::ptrdiff_t>(n) ? static_cast<std::size_t>(p)
                                            : static_cast<std::size_t>(period - 1 - p);
}

// out[o] = Σ_j f[j]·e[first + 2o + j] for both filters at once (the inner loop of every
// forward level: contiguous, branch-free; F fixed at compile time so it unrolls).
template <std::size_t F>
void correlate_down_fixed(const double* e, const double* pl, const double* ph, double* a, double* d,
                          std::size_t m) {
  double lo[F], hi[F];
  for (std::size_t j = 0; j < F; ++j) {
    lo[j] = pl[j];
    hi[j] = ph[j];
  }
  for (std::size_t o = 0; o < m; ++o) {
    const double* x = e + 2 * o;
    double sa = 0.0, sd = 0.0;
    for (std::size_t j = 0; j < F; ++j) {
      sa += lo[j] * x[j];
      sd += hi[j] * x[j];
    }
    a[o] = sa;
    d[o] = sd;
  }
}

// y[2q] = Σ_{j<F/2} rec_lo[2j]·a[q+F/2−1−j] + rec_hi[2j]·d[…]; y[2q+1] with the odd taps.
template <std::size_t F>
void upsample_valid_fixed(const double* a, const double* d, const double* rl, const double* rh,
                          double* y, std::size_t count) {
  constexpr std::size_t F2 = F / 2;
  // Taps reversed so that the inner loop runs forwards over a and d.
  double le[F2], lo[F2], he[F2], ho[F2];
  for (std::size_t j = 0; j < F2; ++j) {
    le[F2 - 1 - j] = rl[2 * j];
    lo[F2 - 1 - j] = rl[2 * j + 1];
    he[F2 - 1 - j] = rh[2 * j];
    ho[F2 - 1 - j] = rh[2 * j + 1];
  }
  for (std::size_t q = 0; q < count; ++q) {
    double se = 0.0, so = 0.0;
    for (std::size_t j = 0; j < F2; ++j) {
      const double av = a[q + j];
      const double dv = d[q + j];
      se += le[j] * av + he[j] * dv;
      so += lo[j] * av + ho[j] * dv;
    }
    y[2 * q] = se;
    y[2 * q + 1] = so;
  }
}

#define MERIDIAN_MAGLEV_DISPATCH(F, CALL)                \
  switch (F) {                                           \
    case 4:                                              \
      CALL(4);                                           \
      break;                                             \
    case 6:                                              \
      CALL(6);                                           \
      break;                                             \
    case 8:                                              \
      CALL(8);                                           \
      break;                                             \
    case 10:                                             \
      CALL(10);                                          \
      break;                                             \
    case 12:                                             \
      CALL(12);                                          \
      break;                                             \
    case 14:                                             \
      CALL(14);                                          \
      break;                                             \
    case 16:                                             \
      CALL(16);                                          \
      break;                                             \
    case 18:                                             \
      CALL(18);                                          \
      break;                                             \
    case 20:                                             \
      CALL(20);                                          \
      break;                                             \
    default:                                             \
      throw NumericalError("unsupported filter length"); \
  }

}  // namespace

std::string to_string(ExtensionMode mode) {
  return mode == ExtensionMode::Symmetric ? "symmetric" : "periodization";
}

ExtensionMode extension_mode_from_string(std::string_view text) {
  if (text == "symmetric") return ExtensionMode::Symmetric;
  if (text == "periodization") return ExtensionMode::Periodization;
  throw InputError(fmt::format("unknown extension mode \"{}\" (symmetric or periodization)", text),
                   ErrorContext{{}, std::nullopt, "mode"});
}

Wavelet::Wavelet(int order) : order_(order) {
  const auto h = scaling_filter(order);
  const std::size_t F = h.size();
  rec_lo_.assign(h.begin(), h.end());
  dec_lo_.resize(F);
  dec_hi_.resize(F);
  rec_hi_.resize(F);
  for (std::size_t k = 0; k < F; ++k) {
    dec_lo_[k] = h[F - 1 - k];
    dec_hi_[k] = (k % 2 == 0) ? -h[k] : h[k];
  }
  for (std::size_t k = 0; k < F; ++k) rec_hi_[k] = dec_hi_[F - 1 - k];
}

Wavelet Wavelet::from_name(std::string_view name) {
  std::string lower(name);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower.size() >= 3 && lower.size() <= 4 && lower.starts_with("db")) {
    int order = 0;
    bool digits = true;
    for (std::size_t i = 2; i < lower.size(); ++i) {
      if (lower[i] < '0' || lower[i] > '9') digits = false;
      order = order * 10 + (lower[i] - '0');
    }
    if (digits && order >= 2 && order <= 10 && lower[2] != '0') return Wavelet(order);
  }
  throw InputError(fmt::format("unknown wavelet \"{}\" (db2 … db10)", name),
                   ErrorContext{{}, std::nullopt, "wavelet"});
}

std::string Wavelet::name() const { return fmt::format("db{}", order_); }

std::size_t dwt_coefficient_length(std::size_t n, std::size_t filter_length, ExtensionMode mode) {
  if (mode == ExtensionMode::Periodization) return (n + 1) / 2;
  return (n + filter_length - 1) / 2;
}

int max_level(std::size_t n, const Wavelet& wavelet) {
  const std::size_t f = wavelet.filter_length() - 1;
  if (n < f) return 0;
  int level = 0;
  // ⌊log2(n/f)⌋ in integers: the largest p with f·2^p ≤ n.
  while ((f << (level + 1)) <= n) ++level;
  return level;
}

namespace {

// One forward level of x into a and d (dwt_coefficient_length values each).
void dwt_into(std::span<const double> x, const Wavelet& wavelet, ExtensionMode mode,
              double* approximation, double* detail) {
  const std::size_t n = x.size();
  const std::size_t F = wavelet.filter_length();
  const std::size_t m = dwt_coefficient_length(n, F, mode);
  // cA[o] = Σ_j dec_lo[j]·x_e[i_o − j] = Σ_j' rec_lo[j']·x_e[i_o − F + 1 + j'], with
  // i_o = 2o + 1 (symmetric) or F/2 + 2o (periodization). Outputs whose taps all fall inside
  // x are computed straight from x; the few at the ends through the extension.
  const bool sym = mode == ExtensionMode::Symmetric;
  const std::size_t np = n + (n % 2);  // periodization: period, last sample repeated when odd
  const auto period = static_cast<std::ptrdiff_t>(np);
  auto extended = [&](std::ptrdiff_t t) {
    if (sym) return x[symmetric_index(t, n)];
    std::ptrdiff_t p = t % period;
    if (p < 0) p += period;
    return static_cast<std::size_t>(p) < n ? x[static_cast<std::size_t>(p)] : x[n - 1];
  };
  const std::size_t first = sym ? 1 : F / 2;  // i_0
  const double* rl = wavelet.rec_lo().data();
  const double* rh = wavelet.rec_hi().data();
  // Interior: i_o − F + 1 ≥ 0 and i_o ≤ n − 1.
  std::size_t o_lo = 0;
  while (o_lo < m && first + 2 * o_lo < F - 1) ++o_lo;
  std::size_t o_hi = o_lo;  // one past the last interior output
  if (first + 2 * o_lo <= n - 1) o_hi = std::min(m, (n - 1 - first) / 2 + 1);
  if (o_hi < o_lo) o_hi = o_lo;
  for (std::size_t o = 0; o < m; ++o) {
    if (o == o_lo && o_hi > o_lo) {
#define MERIDIAN_CALL(N)                                                   \
  correlate_down_fixed<N>(x.data() + (first + 2 * o_lo - (F - 1)), rl, rh, \
                          approximation + o_lo, detail + o_lo, o_hi - o_lo)
      MERIDIAN_MAGLEV_DISPATCH(F, MERIDIAN_CALL)
#undef MERIDIAN_CALL
      o = o_hi - 1;
      continue;
    }
    const auto base =
        static_cast<std::ptrdiff_t>(first + 2 * o) - static_cast<std::ptrdiff_t>(F - 1);
    double sa = 0.0, sd = 0.0;
    for (std::size_t j = 0; j < F; ++j) {
      const double v = extended(base + static_cast<std::ptrdiff_t>(j));
      sa += rl[j] * v;
      sd += rh[j] * v;
    }
    approximation[o] = sa;
    detail[o] = sd;
  }
}

// Length of one inverse level from m coefficients.
std::size_t idwt_length(std::size_t m, std::size_t F, ExtensionMode mode) {
  return mode == ExtensionMode::Symmetric ? 2 * (m - F / 2 + 1) : 2 * m;
}

void check_idwt_input(std::size_t m, const Wavelet& wavelet, ExtensionMode mode) {
  if (mode == ExtensionMode::Symmetric) {
    const std::size_t F2 = wavelet.filter_length() / 2;
    if (m < F2)
      throw InputError(fmt::format("{} coefficients are too few to reconstruct with {} ({} needed)",
                                   m, wavelet.name(), F2));
  } else if (m == 0) {
    throw InputError("no coefficients to reconstruct");
  }
}

// One inverse level of m coefficients into y (idwt_length values); check_idwt_input first.
void idwt_into(const double* a, const double* d, std::size_t m, const Wavelet& wavelet,
               ExtensionMode mode, double* y) {
  const std::size_t F = wavelet.filter_length();
  const double* rl = wavelet.rec_lo().data();
  const double* rh = wavelet.rec_hi().data();
  if (mode == ExtensionMode::Symmetric) {
#define MERIDIAN_CALL(N) upsample_valid_fixed<N>(a, d, rl, rh, y, m - F / 2 + 1)
    MERIDIAN_MAGLEV_DISPATCH(F, MERIDIAN_CALL)
#undef MERIDIAN_CALL
    return;
  }
  // Periodization: the adjoint of the periodic forward transform, z[i_o + j'] +=
  // rec_lo[j']·a[o] + rec_hi[j']·d[o] with i_o = F/2 + 2o, then folded with period 2m.
  const std::size_t np = 2 * m;
  std::vector<double> z(np + F + F / 2, 0.0);
  for (std::size_t o = 0; o < m; ++o) {
    double* p = z.data() + F / 2 + 2 * o;
    const double av = a[o], dv = d[o];
    for (std::size_t j = 0; j < F; ++j) p[j] += rl[j] * av + rh[j] * dv;
  }
  std::fill(y, y + np, 0.0);
  const auto shift = static_cast<std::ptrdiff_t>(F) - 1;
  const auto period = static_cast<std::ptrdiff_t>(np);
  for (std::size_t t = 0; t < z.size(); ++t) {
    std::ptrdiff_t p = (static_cast<std::ptrdiff_t>(t) - shift) % period;
    if (p < 0) p += period;
    y[static_cast<std::size_t>(p)] += z[t];
  }
}

// wavedec's checks of x and the level.
void check_decomposition(std::span<const double> x, const Wavelet& wavelet, int level) {
  require_finite(x, "series");
  const int top = max_level(x.size(), wavelet);
  if (top < 1)
    throw InputError(fmt::format("{} samples are too few for any level with {} (level 1 needs at "
                                 "least {} samples)",
                                 x.size(), wavelet.name(), 2 * (wavelet.filter_length() - 1)),
                     ErrorContext{{}, std::nullopt, "level"});
  if (level < 1 || level > top)
    throw InputError(
        fmt::format(
            "level {} is not possible for {} samples with {}: levels 1 … {} (a level p needs "
            "at least {}·2^p samples)",
            level, x.size(), wavelet.name(), top, wavelet.filter_length() - 1),
        ErrorContext{{}, std::nullopt, "level"});
}

}  // namespace



DwtLevel dwt(std::span<const double> x, const Wavelet& wavelet, ExtensionMode mode) {
  require_finite(x, "series");
  const std::size_t m = dwt_coefficient_length(x.size(), wavelet.filter_length(), mode);
  DwtLevel out;
  out.approximation.resize(m);
  out.detail.resize(m);
  dwt_into(x, wavelet, mode, out.approximation.data(), out.detail.data());
  return out;
}

std::vector<double> idwt(std::span<const double> a, std::span<const double> d,
                         const Wavelet& wavelet, ExtensionMode mode) {
  if (a.size() != d.size())
    throw InputError(fmt::format("approximation ({}) and detail ({}) coefficients differ in length",
                                 a.size(), d.size()));
  check_idwt_input(a.size(), wavelet, mode);
  std::vector<double> y(idwt_length(a.size(), wavelet.filter_length(), mode));
  idwt_into(a.data(), d.data(), a.size(), wavelet, mode, y.data());
  return y;
}

WaveletCoefficients wavedec(std::span<const double> x, const Wavelet& wavelet, ExtensionMode mode,
                            int level) {
  check_decomposition(x, wavelet, level);
  WaveletCoefficients out;
  out.coefficients.resize(static_cast<std::size_t>(level) + 1);
  std::vector<double> a;
  std::span<const double> current = x;
  for (int l = 1; l <= level; ++l) {
    const std::size_t m = dwt_coefficient_length(current.size(), wavelet.filter_length(), mode);
    std::vector<double> next(m);
    auto& d = out.coefficients[static_cast<std::size_t>(level - l + 1)];
    d.resize(m);
    dwt_into(current, wavelet, mode, next.data(), d.data());
    a = std::move(next);
    current = a;
  }
  out.coefficients[0] = std::move(a);
  return out;
}

std::vector<double> waverec(const WaveletCoefficients& c, const Wavelet& wavelet,
                            ExtensionMode mode) {
  if (c.coefficients.size() < 2)
    throw InputError("a reconstruction needs the approximation and at least one detail level");
  std::vector<double> a = c.coefficients[0];
  for (std::size_t k = 1; k < c.coefficients.size(); ++k) {
    const auto& d = c.coefficients[k];
    if (a.size() == d.size() + 1) {
      a.pop_back();
    } else if (a.size() != d.size()) {
      throw InputError(fmt::format("coefficient level {} has {} values where {} are expected", k,
                                   d.size(), a.size()));
    }
    a = idwt(a, d, wavelet, mode);
  }
  return a;
}

std::vector<double> edit_coefficients(std::span<const double> x, const Wavelet& wavelet,
                                      ExtensionMode mode, int level,
                                      const std::function<void(const CoefficientViews&)>& edit) {
  check_decomposition(x, wavelet, level);
  const std::size_t F = wavelet.filter_length();
  const auto p = static_cast<std::size_t>(level);
  // len[l]: coefficients per array at level l (len[0] = n). One scratch array holds every
  // detail level and every approximation, each approximation slot one longer than needed: the
  // inverse transform of level l writes the reconstructed approximation of level l − 1 (len[l−1]
  // or len[l−1] + 1 values) into that level's slot, free by then.
  std::vector<std::size_t> len(p + 1);
  len[0] = x.size();
  std::size_t total = 0;
  for (std::size_t l = 1; l <= p; ++l) {
    len[l] = dwt_coefficient_length(len[l - 1], F, mode);
    total += 2 * len[l] + 1;
  }
  ScratchArray scratch(total);
  std::vector<double*> detail(p + 1), approx(p + 1);
  double* next = scratch.data();
  for (std::size_t l = 1; l <= p; ++l) {
    detail[l] = next;
    approx[l] = next + len[l];
    next += 2 * len[l] + 1;
  }
  std::span<const double> current = x;
  for (std::size_t l = 1; l <= p; ++l) {
    dwt_into(current, wavelet, mode, approx[l], detail[l]);
    current = {approx[l], len[l]};
  }
  CoefficientViews views(p + 1);
  views[0] = {approx[p], len[p]};
  for (std::size_t k = 1; k <= p; ++k) views[k] = {detail[p - k + 1], len[p - k + 1]};
  edit(views);

  std::vector<double> out;
  const double* a = approx[p];
  std::size_t a_len = len[p];
  for (std::size_t l = p; l >= 1; --l) {
    if (a_len == len[l] + 1) --a_len;  // waverec's trim
    check_idwt_input(a_len, wavelet, mode);
    const std::size_t y_len = idwt_length(a_len, F, mode);
    double* y;
    if (l > 1) {
      if (y_len > len[l - 1] + 1)  // cannot happen for wavedec's lengths; never write past a slot
        throw NumericalError("wavelet reconstruction longer than its level");
      y = approx[l - 1];
    } else {
      out = large_zero_vector(y_len);
      y = out.data();
    }
    idwt_into(a, detail[l], a_len, wavelet, mode, y);
    a = y;
    a_len = y_len;
  }
  out.resize(x.size());
  return out;
}

}  // namespace meridian::maglev
