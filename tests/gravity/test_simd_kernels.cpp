// Every summation kernel this CPU can run (gravity/simd_kernel.hpp) against GeographicLib and
// against each other, on every batch size of one pass and beyond: a kernel that a machine
// picks by itself must never be one that no test ran (issue 14).

#include <GeographicLib/GravityModel.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "gravity_test_support.hpp"
#include "test_units.hpp"

namespace {

using namespace gtest_gravity;
using meridian::gravity::FieldOptions;
using meridian::gravity::FieldValues;
using meridian::gravity::GravityField;
using meridian::gravity::Quantities;
using meridian::gravity::SimdKernel;

// Sets an environment variable for one scope and restores it.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (old_.empty())
      ::unsetenv(name_);
    else
      ::setenv(name_, old_.c_str(), 1);
  }

 private:
  const char* name_;
  std::string old_;
};

GravityField field_with(const meridian::gravity::GravityModelData& m, SimdKernel k) {
  FieldOptions o;
  o.simd_kernel = k;
  o.threads = 1;
  return GravityField(m, o);
}

TEST(SimdKernels, EveryKernelAgreesWithGeographicLibAndTheOthers) {
  const std::string name = synthetic_files(360);
  const GeographicLib::GravityModel gl(name, scratch_dir().string());
  const auto model = meridian::io::read_egm_file(scratch_dir() / (name + ".egm"));
  const auto pts = test_points(40, 11);
  std::vector<meridian::gravity::GeodeticPoint> gp;
  for (const auto& p : pts) gp.push_back(geodetic(p));

  const auto kernels = meridian::gravity::supported_simd_kernels();
  ASSERT_FALSE(kernels.empty());
  EXPECT_EQ(kernels.front(), SimdKernel::Baseline);
  std::string names;
  for (SimdKernel k : kernels) names += " " + std::string(to_string(k));
  std::printf("[ kernels ] this CPU runs:%s\n", names.c_str());

  const GravityField reference = field_with(model, SimdKernel::Baseline);
  const std::vector<FieldValues> ref = reference.evaluate(gp);
  for (SimdKernel k : kernels) {
    SCOPED_TRACE(std::string(to_string(k)));
    const GravityField f = field_with(model, k);
    EXPECT_EQ(f.simd_kernel(), k);
    // Every batch length from 1 to 17 (partial passes of every width) and the whole set.
    for (std::size_t n = 1; n <= 17; ++n) {
      const std::vector<FieldValues> v =
          f.evaluate(std::span<const meridian::gravity::GeodeticPoint>(gp.data() + 3, n));
      for (std::size_t i = 0; i < n; ++i) {
        const FieldValues& a = v[i];
        const FieldValues& b = ref[i + 3];
        // 1e-12 of the quantity's size over the set (ξ, η ~ 10″, N ~ 50 m, T ~ 500 m²/s²).
        EXPECT_NEAR(a.xi_rad, b.xi_rad, 1e-12 * 1e-4) << "n " << n << " i " << i;
        EXPECT_NEAR(a.eta_rad, b.eta_rad, 1e-12 * 1e-4) << "n " << n << " i " << i;
        EXPECT_NEAR(a.geoid_m, b.geoid_m, 1e-12 * 100) << "n " << n << " i " << i;
        EXPECT_NEAR(a.disturbing_potential_m2_s2, b.disturbing_potential_m2_s2, 1e-12 * 1000);
        EXPECT_NEAR(a.anomaly_m_s2, b.anomaly_m_s2, 1e-12 * 1e-3);
      }
    }
    const std::vector<FieldValues> v = f.evaluate(gp);
    double worst_arcsec = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      double dg01, xi, eta;
      gl.SphericalAnomaly(pts[i].lat_deg, pts[i].lon_deg, pts[i].h_m, dg01, xi, eta);
      EXPECT_NEAR(v[i].xi_rad / kArcsec, xi * 3600, 1e-6);
      EXPECT_NEAR(v[i].eta_rad / kArcsec, eta * 3600, 1e-6);
      EXPECT_NEAR(v[i].geoid_m, gl.GeoidHeight(pts[i].lat_deg, pts[i].lon_deg), 1e-6);
      worst_arcsec = std::max({worst_arcsec, std::abs(v[i].xi_rad / kArcsec - xi * 3600),
                               std::abs(v[i].eta_rad / kArcsec - eta * 3600)});
    }
    std::printf("[ %s ] max |xi, eta - GeographicLib| %.2e\"\n", std::string(to_string(k)).c_str(), worst_arcsec);
  }
}

// A point's values are the same bits whatever batch it is evaluated in: alone, with its
// neighbours in groups of every size, with points near a pole in its group (whose lanes take
// the derivative's recursion while it takes the identity) or in a pair of groups.
TEST(SimdKernels, APointsValuesDoNotDependOnItsBatch) {
  meridian::gravity::SyntheticModelOptions o;
  o.max_degree = 120;
  o.seed = 5;
  const auto model = meridian::gravity::make_synthetic_model(o);
  std::vector<meridian::gravity::GeodeticPoint> gp;
  // Near-pole lanes (|lat| > 84.26°, u < 0.1) scattered among the others.
  const double lats[] = {10, 84.5, -30, 84.2, 89.9, 55, -86, 0.5, -84.1, 70, 88, -12, 84.26, -89.99, 33, 47};
  for (int i = 0; i < 40; ++i)
    gp.push_back({lats[i % 16] * kDeg, (17.0 * i - 150) * kDeg, 100.0 * (i % 5)});
  for (SimdKernel k : meridian::gravity::supported_simd_kernels()) {
    SCOPED_TRACE(std::string(to_string(k)));
    const GravityField f = field_with(model, k);
    const std::vector<FieldValues> whole = f.evaluate(gp);
    for (std::size_t chunk : {1u, 2u, 3u, 4u, 5u, 7u, 8u, 9u, 13u, 16u, 17u}) {
      for (std::size_t first = 0; first < gp.size(); first += chunk) {
        const std::size_t n = std::min(chunk, gp.size() - first);
        const std::vector<FieldValues> v =
            f.evaluate(std::span<const meridian::gravity::GeodeticPoint>(gp.data() + first, n));
        for (std::size_t i = 0; i < n; ++i) {
          const FieldValues& a = v[i];
          const FieldValues& b = whole[first + i];
          SCOPED_TRACE(testing::Message() << "chunk " << chunk << " point " << first + i);
          EXPECT_EQ(a.xi_rad, b.xi_rad);
          EXPECT_EQ(a.eta_rad, b.eta_rad);
          EXPECT_EQ(a.geoid_m, b.geoid_m);
          EXPECT_EQ(a.disturbing_potential_m2_s2, b.disturbing_potential_m2_s2);
          EXPECT_EQ(a.anomaly_m_s2, b.anomaly_m_s2);
          EXPECT_EQ(a.dT_north_m_s2, b.dT_north_m_s2);
          EXPECT_EQ(a.dT_east_m_s2, b.dT_east_m_s2);
          EXPECT_EQ(a.dT_up_m_s2, b.dT_up_m_s2);
        }
      }
    }
  }
}

TEST(SimdKernels, AutoTakesTheWidestOrTheEnvironmentsChoice) {
  const auto kernels = meridian::gravity::supported_simd_kernels();
  {
    ScopedEnv e(meridian::gravity::kSimdKernelEnv, "");
    EXPECT_EQ(meridian::gravity::resolve_simd_kernel(SimdKernel::Auto), kernels.back());
  }
  for (SimdKernel k : kernels) {
    ScopedEnv e(meridian::gravity::kSimdKernelEnv, std::string(to_string(k)).c_str());
    EXPECT_EQ(meridian::gravity::resolve_simd_kernel(SimdKernel::Auto), k);
    // An explicit choice wins over the environment.
    EXPECT_EQ(meridian::gravity::resolve_simd_kernel(SimdKernel::Baseline), SimdKernel::Baseline);
  }
  ScopedEnv e(meridian::gravity::kSimdKernelEnv, "avx9000");
  try {
    (void)meridian::gravity::resolve_simd_kernel(SimdKernel::Auto);
    FAIL() << "no error";
  } catch (const meridian::InputError& err) {
    EXPECT_EQ(err.context().field, "MERIDIAN_SIMD_KERNEL");
    EXPECT_NE(std::string(err.what()).find("avx9000"), std::string::npos) << err.what();
  }
}

TEST(SimdKernels, NamesRoundTripAndUnsupportedKernelsAreInputErrors) {
  for (SimdKernel k : {SimdKernel::Auto, SimdKernel::Baseline, SimdKernel::X86_64_V3, SimdKernel::X86_64_V4})
    EXPECT_EQ(meridian::gravity::parse_simd_kernel(to_string(k)), k);
  EXPECT_THROW(meridian::gravity::parse_simd_kernel("AVX2"), meridian::InputError);
  for (SimdKernel k : {SimdKernel::X86_64_V3, SimdKernel::X86_64_V4}) {
    if (meridian::gravity::simd_kernel_supported(k)) continue;
    meridian::gravity::SyntheticModelOptions o;
    o.max_degree = 4;
    EXPECT_THROW(field_with(meridian::gravity::make_synthetic_model(o), k), meridian::InputError) << to_string(k);
  }
}

}  // namespace
