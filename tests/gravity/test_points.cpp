// The `gravity points` workflow pieces: one chunk evaluated (against the
// model at every point), the summary statistics (against a direct two-pass
// computation of the same numbers) and the thinned sample (against its
// closed-form rule).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gravity/points.hpp"
#include "meridian/gravity/points_summary.hpp"
#include "meridian/gravity/synthetic.hpp"
#include "meridian/gravity/thinned_sample.hpp"
#include "test_units.hpp"

namespace {

using namespace meridian;
using namespace meridian::gravity;
using gtest_gravity::kArcsec;
using gtest_gravity::kDeg;

FieldValues values(double xi, double eta, double n) {
  FieldValues v{};
  v.xi_rad = xi;
  v.eta_rad = eta;
  v.geoid_m = n;
  return v;
}

// Two passes over stored numbers: the textbook definitions.
struct Direct {
  double min, max, mean, rms, sd;
};
Direct direct(const std::vector<double>& x) {
  Direct d{x[0], x[0], 0, 0, 0};
  for (double v : x) {
    d.min = std::min(d.min, v);
    d.max = std::max(d.max, v);
    d.mean += v;
    d.rms += v * v;
  }
  const double n = static_cast<double>(x.size());
  d.mean /= n;
  d.rms = std::sqrt(d.rms / n);
  for (double v : x) d.sd += (v - d.mean) * (v - d.mean);
  d.sd = std::sqrt(d.sd / (n - 1));
  return d;
}

void expect_matches(const RunningStatistics& s, const std::vector<double>& x, double tol) {
  const Direct d = direct(x);
  EXPECT_EQ(s.count(), x.size());
  EXPECT_EQ(s.min(), d.min);
  EXPECT_EQ(s.max(), d.max);
  EXPECT_NEAR(s.mean(), d.mean, tol);
  EXPECT_NEAR(s.rms(), d.rms, tol);
  EXPECT_NEAR(s.std_dev(), d.sd, tol);
}

TEST(PointsSummary, StatisticsEqualATwoPassComputation) {
  std::mt19937_64 rng(17);
  std::normal_distribution<double> xi(3 * kArcsec, 5 * kArcsec), eta(-2 * kArcsec, 4 * kArcsec);
  // N of tens of metres varying by millimetres: a one-pass sum of squares
  // would lose the spread; Welford's update must not.
  std::normal_distribution<double> n(31.5, 0.002);
  std::uniform_real_distribution<double> lat(-60, 70), lon(-170, 175), h(-400, 8000);
  PointsSummary s(100);
  std::vector<double> xs, es, ns, lats, lons, hs;
  std::vector<GeodeticPoint> pts;
  std::vector<FieldValues> vals;
  for (int i = 0; i < 20000; ++i) {
    pts.push_back({lat(rng) * kDeg, lon(rng) * kDeg, h(rng)});
    vals.push_back(values(xi(rng), eta(rng), n(rng)));
    xs.push_back(vals.back().xi_rad);
    es.push_back(vals.back().eta_rad);
    ns.push_back(vals.back().geoid_m);
    lats.push_back(pts.back().lat_rad);
    lons.push_back(pts.back().lon_rad);
    hs.push_back(pts.back().height_m);
  }
  // Fed in uneven chunks.
  for (std::size_t b = 0; b < pts.size();) {
    const std::size_t e = std::min(pts.size(), b + 1 + b % 977);
    s.add(std::span(pts).subspan(b, e - b), std::span(vals).subspan(b, e - b));
    b = e;
  }
  EXPECT_EQ(s.count(), 20000u);
  expect_matches(s.xi_rad(), xs, 1e-12 * kArcsec);
  expect_matches(s.eta_rad(), es, 1e-12 * kArcsec);
  expect_matches(s.geoid_m(), ns, 1e-12);
  EXPECT_NEAR(s.geoid_m().std_dev(), 0.002, 0.0001);  // the generating sigma, as a sanity check
  EXPECT_EQ(s.bounds().lat_min_rad, *std::min_element(lats.begin(), lats.end()));
  EXPECT_EQ(s.bounds().lat_max_rad, *std::max_element(lats.begin(), lats.end()));
  EXPECT_EQ(s.bounds().lon_min_rad, *std::min_element(lons.begin(), lons.end()));
  EXPECT_EQ(s.bounds().lon_max_rad, *std::max_element(lons.begin(), lons.end()));
  EXPECT_EQ(s.bounds().height_min_m, *std::min_element(hs.begin(), hs.end()));
  EXPECT_EQ(s.bounds().height_max_m, *std::max_element(hs.begin(), hs.end()));
}

TEST(PointsSummary, FewPointsAndBadValues) {
  PointsSummary s;
  EXPECT_EQ(s.count(), 0u);
  EXPECT_TRUE(std::isnan(s.xi_rad().mean()));
  EXPECT_TRUE(std::isnan(s.bounds().lat_min_rad));
  s.add({0.1, 0.2, 5}, values(2e-5, -1e-5, 12.5));
  EXPECT_EQ(s.geoid_m().mean(), 12.5);
  EXPECT_EQ(s.geoid_m().rms(), 12.5);
  EXPECT_TRUE(std::isnan(s.geoid_m().std_dev()));  // not stated for one value
  EXPECT_EQ(s.bounds().height_min_m, 5);
  s.add({0.3, 0.1, 7}, values(4e-5, -3e-5, 13.5));
  EXPECT_DOUBLE_EQ(s.geoid_m().std_dev(), std::sqrt(0.5));
  EXPECT_DOUBLE_EQ(s.xi_rad().rms(), std::sqrt((4e-10 + 16e-10) / 2));
  // A non-finite value is refused before anything is counted.
  EXPECT_THROW(s.add({0, 0, 0}, values(0, NAN, 1)), InputError);
  EXPECT_EQ(s.count(), 2u);
  EXPECT_EQ(s.xi_rad().count(), 2u);
  const std::vector<GeodeticPoint> p(2);
  const std::vector<FieldValues> v(1);
  EXPECT_THROW(s.add(p, v), InputError);
}

// The rule of thinned_sample.hpp, computed directly: indices 0, k, 2k, …
// below n with k the smallest power of two such that ceil(n/k) <= capacity.
std::vector<std::uint64_t> expected_indices(std::uint64_t n, std::size_t capacity) {
  std::uint64_t k = 1;
  while ((n + k - 1) / k > capacity) k *= 2;
  std::vector<std::uint64_t> out;
  for (std::uint64_t i = 0; i < n; i += k) out.push_back(i);
  return out;
}

std::vector<std::uint64_t> sampled(std::uint64_t n, std::size_t capacity) {
  ThinnedSample s(capacity);
  for (std::uint64_t i = 0; i < n; ++i)
    s.add({static_cast<double>(i) * 1e-6, 0, 0}, values(0, 0, static_cast<double>(i)));
  std::vector<std::uint64_t> out;
  for (const auto& p : s.points()) {
    EXPECT_EQ(p.geoid_m, static_cast<double>(p.index));  // the point's own values are kept
    out.push_back(p.index);
  }
  EXPECT_EQ(s.seen(), n);
  return out;
}

TEST(ThinnedSample, FollowsTheRuleBoundedAndSpreadOverTheWholeLine) {
  for (std::size_t cap : {1u, 2u, 3u, 7u, 64u, 100u}) {
    for (std::uint64_t n : {0ull, 1ull, 5ull, 63ull, 64ull, 65ull, 99ull, 100ull, 101ull, 199ull,
                            200ull, 201ull, 1000ull, 4097ull}) {
      const auto got = sampled(n, cap);
      EXPECT_EQ(got, expected_indices(n, cap)) << "n " << n << " capacity " << cap;
      EXPECT_LE(got.size(), cap);
      if (n == 0) continue;
      EXPECT_EQ(got.front(), 0u);
      // Spread: the last kept point is within one stride of the end, and
      // more than half the capacity is used once there are enough points.
      const std::uint64_t stride = got.size() > 1 ? got[1] - got[0] : std::max<std::uint64_t>(n, 1);
      EXPECT_GE(got.back() + stride, n) << "n " << n << " capacity " << cap;
      if (n >= cap && cap > 1) {
        EXPECT_GT(2 * got.size(), cap) << "n " << n << " capacity " << cap;
      }
    }
  }
}

TEST(ThinnedSample, LongStreamIsDeterministic) {
  const auto a = sampled(1000003, 20000), b = sampled(1000003, 20000);
  EXPECT_EQ(a, b);
  EXPECT_EQ(a, expected_indices(1000003, 20000));
  EXPECT_EQ(a.size(), 15626u);  // stride 64: ceil(1000003 / 64)
}

TEST(GravityPoints, ChunkEvaluationAgreesWithTheModelAtEveryPoint) {
  SyntheticModelOptions o;
  o.max_degree = 120;
  o.seed = 5;
  const GravityField field(make_synthetic_model(o));
  std::vector<GeodeticPoint> line;
  for (int i = 0; i < 2000; ++i)
    line.push_back({(47.0 + i * 2e-4) * kDeg, (8.0 + i * 3e-4) * kDeg, 400.0 + i * 0.1});
  // Scattered: the full model at each point, one at a time.
  const auto all = evaluate_points(field, line, PointsOptions{});
  ASSERT_EQ(all.size(), line.size());
  for (std::size_t i = 0; i < line.size(); i += 97) {
    const FieldValues one = field.evaluate(line[i]);
    EXPECT_NEAR(all[i].xi_rad, one.xi_rad, 1e-12 * kArcsec);
    EXPECT_NEAR(all[i].geoid_m, one.geoid_m, 1e-12);
  }
  // Along the track: within the stated tolerances of the full model.
  PointsOptions track;
  track.track_tolerance_rad = 1e-3 * kArcsec;
  track.track_tolerance_geoid_m = 1e-4;
  EXPECT_TRUE(track.along_track());
  EXPECT_GT(points_chunk_size(track), points_chunk_size(PointsOptions{}));
  const auto interp = evaluate_points(field, line, track);
  double worst = 0, worst_n = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    worst = std::max({worst, std::abs(interp[i].xi_rad - all[i].xi_rad),
                      std::abs(interp[i].eta_rad - all[i].eta_rad)});
    worst_n = std::max(worst_n, std::abs(interp[i].geoid_m - all[i].geoid_m));
  }
  EXPECT_LT(worst, 1.5 * track.track_tolerance_rad);
  EXPECT_LT(worst_n, 1.5 * track.track_tolerance_geoid_m);
  EXPECT_THROW(evaluate_points(field, std::vector<GeodeticPoint>{{2.0, 0, 0}}, PointsOptions{}),
               InputError);
}

}  // namespace

namespace {

TEST(GravityFieldConstruction, MovingTheModelInGivesTheSameFieldAndKeepsTheMetadata) {
  SyntheticModelOptions o;
  o.max_degree = 60;
  o.seed = 77;
  GravityModelData model = make_synthetic_model(o);
  model.name = "moved";
  model.file_max_degree = 60;
  const GravityField copied(model);
  const GravityField moved(std::move(model));
  // The moved-from model keeps what model_info reads; its coefficients are an empty set.
  EXPECT_EQ(model.name, "moved");
  EXPECT_EQ(model.file_max_degree, 60);
  EXPECT_EQ(model.coefficients.max_degree(), 0);
  EXPECT_EQ(model.coefficients.size(), 1u);
  EXPECT_EQ(model_info(model, moved).max_degree, 60);
  for (double lat : {-89.5, -33.0, 0.0, 47.0, 90.0}) {
    const FieldValues a = copied.evaluate({lat * kDeg, 1.3, 250.0});
    const FieldValues b = moved.evaluate({lat * kDeg, 1.3, 250.0});
    EXPECT_EQ(a.xi_rad, b.xi_rad) << lat;  // bit for bit: the same coefficients
    EXPECT_EQ(a.eta_rad, b.eta_rad) << lat;
    EXPECT_EQ(a.geoid_m, b.geoid_m) << lat;
    EXPECT_NE(a.xi_rad, 0.0) << lat;
  }
}

}  // namespace
