// Grid synthesis (issue 14): every node of global (poles included) and regional grids against
// the scattered-point path GravityField::evaluate; the FFT and per-parallel paths against each
// other; folding of orders above Nλ/2; threads; the grid specification's checks and parsers.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <stdexcept>
#include <vector>

#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gravity/grid_spec.hpp"
#include "meridian/gravity/grid_synthesis.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "meridian/gravity/simd_kernel.hpp"
#include "meridian/gravity/synthetic.hpp"

namespace gtest_grid {

using namespace meridian;
using namespace meridian::gravity;

constexpr double kArcsecTol = 1e-9;  // ″, ξ and η
constexpr double kMetreTol = 1e-9;   // m, N
constexpr double kMgalTol = 1e-9;    // mGal, Δg and the disturbance vector
constexpr double kMgal = 1e-5;       // m/s² per mGal

const std::vector<GridQuantity> kAll = {GridQuantity::Xi,      GridQuantity::Eta,
                                        GridQuantity::Geoid,   GridQuantity::Anomaly,
                                        GridQuantity::DisturbanceEast, GridQuantity::DisturbanceNorth,
                                        GridQuantity::DisturbanceUp};

GravityModelData grid_model(int degree, bool with_correction = false) {
  SyntheticModelOptions o;
  o.max_degree = degree;
  o.seed = 1414;
  GravityModelData m = make_synthetic_model(o);
  if (with_correction) {
    // A zeta-to-N correction set of lower degree, with a height offset, as in a .egm.cof.
    GeoidCorrection c{SphericalHarmonicCoefficients(12, 12), 1.5, 0.25};
    for (int n = 0; n <= 12; ++n)
      for (int m2 = 0; m2 <= n; ++m2) c.coefficients.set(n, m2, 0.01 / (n + 1), m2 ? 0.02 / (n + m2 + 1) : 0.0);
    m.correction = c;
  }
  return m;
}

// Every node of the grid, as rows of quantity-major values (SI and radians).
struct Grid {
  GridSynthesisResult result;
  std::vector<std::vector<double>> rows;
  std::vector<double> lat_deg;
};

Grid run(const GravityField& f, const GridSpec& spec, GridOptions options = {}) {
  Grid g;
  g.result = synthesize_grid(
      f, spec,
      [&](const GridRow& r) {
        EXPECT_EQ(r.row, g.rows.size());  // in order, south to north
        EXPECT_EQ(r.columns, spec.columns());
        g.rows.emplace_back(r.data.begin(), r.data.end());
        g.lat_deg.push_back(r.lat_deg);
      },
      nullptr, options);
  return g;
}

double scale_of(GridQuantity q) {
  switch (q) {
    case GridQuantity::Xi:
    case GridQuantity::Eta: return units::kArcsecond;
    case GridQuantity::Geoid: return 1.0;
    default: return kMgal;
  }
}
double tolerance_of(GridQuantity q) {
  switch (q) {
    case GridQuantity::Xi:
    case GridQuantity::Eta: return kArcsecTol;
    case GridQuantity::Geoid: return kMetreTol;
    default: return kMgalTol;
  }
}
double value_of(const FieldValues& v, GridQuantity q) {
  switch (q) {
    case GridQuantity::Xi: return v.xi_rad;
    case GridQuantity::Eta: return v.eta_rad;
    case GridQuantity::Geoid: return v.geoid_m;
    case GridQuantity::Anomaly: return v.anomaly_m_s2;
    case GridQuantity::DisturbanceEast: return v.dT_east_m_s2;
    case GridQuantity::DisturbanceNorth: return v.dT_north_m_s2;
    case GridQuantity::DisturbanceUp: return v.dT_up_m_s2;
  }
  return NAN;
}

// Largest difference (in the output unit: ″, m, mGal) per quantity between the grid and
// GravityField::evaluate at every node, which must be within tolerance.
void expect_matches_points(const GravityField& f, const GridSpec& spec, const Grid& g) {
  ASSERT_EQ(g.rows.size(), spec.rows());
  const std::size_t cols = spec.columns();
  std::vector<GeodeticPoint> pts;
  for (std::size_t j = 0; j < spec.rows(); ++j)
    for (std::size_t i = 0; i < cols; ++i) pts.push_back({spec.lat_rad(j), spec.lon_rad(i), spec.height_m});
  const std::vector<FieldValues> ref = f.evaluate(pts);
  for (std::size_t k = 0; k < spec.quantities.size(); ++k) {
    const GridQuantity q = spec.quantities[k];
    double worst = 0, largest = 0;
    for (std::size_t j = 0; j < spec.rows(); ++j)
      for (std::size_t i = 0; i < cols; ++i) {
        const double want = value_of(ref[j * cols + i], q) / scale_of(q);
        const double got = g.rows[j][k * cols + i] / scale_of(q);
        worst = std::max(worst, std::abs(got - want));
        largest = std::max(largest, std::abs(want));
      }
    EXPECT_LE(worst, tolerance_of(q)) << to_string(q) << " (largest |value| " << largest << ")";
    EXPECT_GT(largest, 100 * tolerance_of(q)) << to_string(q) << ": the test needs values that are not zero";
  }
}

GridSpec spec_of(double w, double e, double s, double n, double spacing_deg, double height_m = 0,
                 GridRegistration reg = GridRegistration::Gridline, std::vector<GridQuantity> q = kAll) {
  GridSpec spec;
  spec.west_deg = w, spec.east_deg = e, spec.south_deg = s, spec.north_deg = n;
  spec.lon_spacing_deg = spec.lat_spacing_deg = spacing_deg;
  spec.height_m = height_m;
  spec.registration = reg;
  spec.quantities = std::move(q);
  return spec;
}

TEST(GridSynthesis, GlobalGridWithPolesEqualsPointsAtEveryNode) {
  // Degree 80 on a 5° grid: Nλ = 72 < 2·80, so orders 37…80 are folded.
  const GravityField f(grid_model(80));
  const GridSpec spec = spec_of(0, 360, -90, 90, 5, 1500);
  const Grid g = run(f, spec);
  EXPECT_EQ(g.result.path_used, GridPath::Fft);
  EXPECT_EQ(g.result.fft_length, 72u);
  EXPECT_EQ(spec.columns(), 73u);
  EXPECT_EQ(spec.rows(), 37u);
  EXPECT_EQ(g.lat_deg.front(), -90.0);
  EXPECT_EQ(g.lat_deg.back(), 90.0);
  expect_matches_points(f, spec, g);
}

TEST(GridSynthesis, Degree360And2190GlobalGridsWithPolesEqualPoints) {
  // The validation degrees and quantities (1e-9″, 1e-9 m). 15° at degree 2190:
  // Nλ = 24, so nearly every order is folded; 13 rows make blocks of 7 and 6 parallels on two
  // threads, one block of 13 on one. (Δg of this synthetic model reaches 7870 mGal at degree
  // 2190, where the two paths differ by 2e-9 mGal, 3e-13 relative: not compared here.)
  for (int degree : {360, 2190}) {
    SCOPED_TRACE(degree);
    const GravityField f(grid_model(degree));
    const GridSpec spec = spec_of(0, 360, -90, 90, 15, 0, GridRegistration::Gridline,
                                  {GridQuantity::Xi, GridQuantity::Eta, GridQuantity::Geoid});
    const Grid g = run(f, spec);
    EXPECT_EQ(g.result.path_used, GridPath::Fft);
    expect_matches_points(f, spec, g);
  }
}

TEST(GridSynthesis, GlobalPixelGridFromMinus180EqualsPoints) {
  const GravityField f(grid_model(64));
  const GridSpec spec = spec_of(-180, 180, -90, 90, 7.5, 0, GridRegistration::Pixel);
  const Grid g = run(f, spec);
  EXPECT_EQ(g.result.path_used, GridPath::Fft);
  EXPECT_EQ(spec.columns(), 48u);
  EXPECT_EQ(spec.rows(), 24u);
  EXPECT_DOUBLE_EQ(spec.lon_deg(0), -176.25);
  EXPECT_DOUBLE_EQ(spec.lat_deg(23), 86.25);
  expect_matches_points(f, spec, g);
}

TEST(GridSynthesis, FoldingWithVeryFewSamplesPerParallel) {
  // Nλ = 5 (odd) samples of a degree-60 field: every order but 0…2 folds.
  const GravityField f(grid_model(60));
  GridSpec spec = spec_of(10, 370, -90, 90, 72, 0, GridRegistration::Gridline,
                          {GridQuantity::Geoid, GridQuantity::Xi, GridQuantity::Eta});
  spec.lat_spacing_deg = 15;
  const Grid g = run(f, spec);
  EXPECT_EQ(g.result.path_used, GridPath::Fft);
  EXPECT_EQ(g.result.fft_length, 5u);
  expect_matches_points(f, spec, g);
}

TEST(GridSynthesis, RegionalGridsByTheFftPathEqualPoints) {
  // A wide band at degree 100: the automatic choice is the FFT path (91·101 ≥ 2·3·180).
  const GravityField f(grid_model(100));
  const GridSpec band = spec_of(-30, 150, -30, 30, 2, 500, GridRegistration::Gridline,
                                {GridQuantity::Xi, GridQuantity::Eta, GridQuantity::Geoid});
  const Grid a = run(f, band);
  EXPECT_EQ(a.result.path_used, GridPath::Fft);
  EXPECT_EQ(a.result.fft_length, 180u);
  expect_matches_points(f, band, a);
  // Forced on a small pixel-registered region at the pole, and at a 3.75° spacing (Nλ = 96).
  GridOptions fft;
  fft.path = GridPath::Fft;
  const GridSpec cap = spec_of(100, 160, -90, -60, 3.75, 0, GridRegistration::Pixel, kAll);
  const Grid b = run(f, cap, fft);
  EXPECT_EQ(b.result.path_used, GridPath::Fft);
  EXPECT_EQ(b.result.fft_length, 96u);
  expect_matches_points(f, cap, b);
}

TEST(GridSynthesis, RegionalGridUsesParallelPathAndEqualsPoints) {
  const GravityField f(grid_model(90));
  const GridSpec spec = spec_of(-10, 30, 35, 60, 2.5, 800);
  const Grid g = run(f, spec);
  EXPECT_EQ(g.result.path_used, GridPath::Parallel);
  EXPECT_EQ(g.result.fft_length, 0u);
  EXPECT_EQ(spec.columns(), 17u);
  EXPECT_EQ(spec.rows(), 11u);
  expect_matches_points(f, spec, g);
}

TEST(GridSynthesis, RegionalCapAtThePoleEqualsPoints) {
  const GravityField f(grid_model(70));
  const GridSpec spec = spec_of(100, 160, -90, -70, 4, 0, GridRegistration::Gridline, kAll);
  const Grid g = run(f, spec);
  EXPECT_EQ(g.result.path_used, GridPath::Parallel);
  EXPECT_EQ(g.lat_deg.front(), -90.0);
  expect_matches_points(f, spec, g);
}

TEST(GridSynthesis, FftAndParallelPathsAgreeWithCorrectionAndDegreeZero) {
  FieldOptions fo;
  fo.include_degree_zero = true;
  const GravityField f(grid_model(100, true), fo);
  const GridSpec spec = spec_of(0, 360, -90, 90, 6, 2000);
  GridOptions fft, par;
  fft.path = GridPath::Fft;
  par.path = GridPath::Parallel;
  const Grid a = run(f, spec, fft), b = run(f, spec, par);
  EXPECT_EQ(a.result.path_used, GridPath::Fft);
  EXPECT_EQ(b.result.path_used, GridPath::Parallel);
  const std::size_t cols = spec.columns();
  for (std::size_t k = 0; k < spec.quantities.size(); ++k) {
    const GridQuantity q = spec.quantities[k];
    double worst = 0;
    for (std::size_t j = 0; j < spec.rows(); ++j)
      for (std::size_t i = 0; i < cols; ++i)
        worst = std::max(worst, std::abs(a.rows[j][k * cols + i] - b.rows[j][k * cols + i]) / scale_of(q));
    EXPECT_LE(worst, tolerance_of(q)) << to_string(q);
  }
  expect_matches_points(f, spec, a);
}

TEST(GridSynthesis, ResultsDoNotDependOnThreadsOrBatches) {
  const GravityField f(grid_model(40));
  const GridSpec spec = spec_of(0, 360, -90, 90, 10, 0, GridRegistration::Gridline,
                                {GridQuantity::Eta, GridQuantity::Anomaly});
  GridOptions one, three;
  one.threads = 1;
  three.threads = 3;
  three.max_buffer_bytes = 2 * spec.columns() * 2 * sizeof(double);  // two parallels per batch
  const Grid a = run(f, spec, one), b = run(f, spec, three);
  EXPECT_EQ(a.result.threads, 1u);
  EXPECT_EQ(b.result.threads, 3u);
  EXPECT_EQ(a.rows, b.rows);  // bit for bit
}

TEST(GridSynthesis, EveryKernelsBlocksOfParallelsEqualPoints) {
  // The FFT path sums the columns of up to 16 parallels per pass over the coefficients, in the
  // field's SIMD kernel (2, 4 or 8 parallels per vector). 37 rows on one thread are blocks of
  // 16, 16 and 5 (spare lanes); each kernel against the points of the same field, and the
  // kernels against each other.
  const GravityModelData model = grid_model(120, true);
  const GridSpec spec = spec_of(0, 360, -90, 90, 5, 250);
  ASSERT_EQ(spec.rows(), 37u);
  GridOptions one;
  one.threads = 1;
  std::vector<Grid> grids;
  for (SimdKernel k : supported_simd_kernels()) {
    SCOPED_TRACE(std::string(to_string(k)));
    FieldOptions o;
    o.simd_kernel = k;
    o.threads = 1;
    const GravityField f(model, o);
    grids.push_back(run(f, spec, one));
    EXPECT_EQ(grids.back().result.path_used, GridPath::Fft);
    expect_matches_points(f, spec, grids.back());
  }
  // 1e-12 of each quantity's largest |value| (a node near zero has no relative precision).
  const std::size_t cols = spec.columns();
  for (std::size_t qi = 0; qi < spec.quantities.size(); ++qi) {
    double largest = 0;
    for (const auto& row : grids[0].rows)
      for (std::size_t i = 0; i < cols; ++i) largest = std::max(largest, std::abs(row[qi * cols + i]));
    for (std::size_t g = 1; g < grids.size(); ++g)
      for (std::size_t j = 0; j < spec.rows(); ++j)
        for (std::size_t i = 0; i < cols; ++i)
          EXPECT_LE(std::abs(grids[0].rows[j][qi * cols + i] - grids[g].rows[j][qi * cols + i]), 1e-12 * largest)
              << to_string(spec.quantities[qi]) << " row " << j << " column " << i;
  }
}

TEST(GridSynthesis, ProgressCountsParallelsAndSinkErrorsPropagate) {
  struct Count : Progress {
    std::size_t last = 0, total = 0;
    void update(std::size_t done, std::size_t t, std::string_view) override { last = done, total = t; }
    void finish() override {}
  } progress;
  const GravityField f(grid_model(20));
  const GridSpec spec = spec_of(0, 20, 0, 20, 5, 0, GridRegistration::Gridline, {GridQuantity::Geoid});
  synthesize_grid(f, spec, [](const GridRow&) {}, &progress);
  EXPECT_EQ(progress.last, 5u);
  EXPECT_EQ(progress.total, 5u);
  std::size_t calls = 0;
  EXPECT_THROW(synthesize_grid(f, spec,
                               [&](const GridRow&) {
                                 if (++calls == 2) throw IoError("disk full");
                               }),
               IoError);
  EXPECT_EQ(calls, 2u);
}

void expect_input_error(const GridSpec& spec, const std::string& field, GridOptions o = {}) {
  try {
    choose_grid_path(spec, o);
    ADD_FAILURE() << "no error for field " << field;
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, field) << e.what();
  }
}

TEST(GridSpec, BadSpecificationsAreRefusedBeforeAnyWork) {
  expect_input_error(spec_of(30, 30, 0, 10, 1), "region");          // W = E
  expect_input_error(spec_of(40, 30, 0, 10, 1), "region");          // W > E
  expect_input_error(spec_of(0, 361, 0, 10, 1), "region");          // wider than 360°
  expect_input_error(spec_of(0, 10, -91, 10, 1), "region");         // S < −90
  expect_input_error(spec_of(0, 10, 0, 90.5, 0.5), "region");       // N > 90
  expect_input_error(spec_of(0, 10, 10, 10, 1), "region");          // S = N
  expect_input_error(spec_of(0, 10, 0, NAN, 1), "region");
  expect_input_error(spec_of(0, 10, 0, 10, 0), "spacing");
  expect_input_error(spec_of(0, 10, 0, 10, -1), "spacing");
  expect_input_error(spec_of(0, 10, 0, 10, 3), "spacing");          // does not divide 10°
  expect_input_error(spec_of(0, 1, 0, 1, 30), "spacing");           // no node
  expect_input_error(spec_of(0, 360, -90, 90, 1.0 / 36000), "spacing");  // 0.1″: > 2³² nodes
  expect_input_error(spec_of(0, 10, 0, 10, 1, 2e7), "height");
  expect_input_error(spec_of(0, 10, 0, 10, 1, 0, GridRegistration::Gridline, {}), "quantities");
  expect_input_error(spec_of(0, 10, 0, 10, 1, 0, GridRegistration::Gridline, {GridQuantity::Xi, GridQuantity::Xi}),
                     "quantities");
  GridOptions fft;
  fft.path = GridPath::Fft;
  expect_input_error(spec_of(0, 7, 0, 7, 0.7), "path", fft);  // FFT asked for a spacing not dividing 360°
  GridOptions small;
  small.max_buffer_bytes = 1000;
  expect_input_error(spec_of(0, 360, 0, 10, 1), "spacing", small);  // one parallel > the buffer
  EXPECT_EQ(choose_grid_path(spec_of(0, 360, 0, 10, 1)), GridPath::Fft);
  EXPECT_EQ(choose_grid_path(spec_of(0, 7, 0, 7, 0.7), {}, 2190), GridPath::Parallel);  // 0.7° does not divide 360°
  // Regional, spacing dividing 360°: FFT when columns·(M + 1) ≥ 2·quantities·Nλ (7 quantities, Nλ = 360).
  EXPECT_EQ(choose_grid_path(spec_of(0, 350, 0, 10, 1), {}, 0), GridPath::Parallel);   // 351 < 5040
  EXPECT_EQ(choose_grid_path(spec_of(0, 350, 0, 10, 1), {}, 14), GridPath::Fft);       // 5265 ≥ 5040
  EXPECT_EQ(choose_grid_path(spec_of(0, 10, 0, 10, 1), {}, 360), GridPath::Parallel);  // 3971 < 5040
  EXPECT_EQ(choose_grid_path(spec_of(0, 10, 0, 10, 1), {}, 460), GridPath::Fft);       // 5071 ≥ 5040
}

TEST(GridSpec, NodesOfBothRegistrations) {
  GridSpec s = spec_of(-10, 30, 35, 60, 0.25);
  s.validate();
  EXPECT_EQ(s.columns(), 161u);
  EXPECT_EQ(s.rows(), 101u);
  EXPECT_EQ(s.lon_deg(160), 30.0);
  EXPECT_EQ(s.lat_deg(100), 60.0);
  EXPECT_DOUBLE_EQ(s.lon_deg(4), -9.0);
  s.registration = GridRegistration::Pixel;
  EXPECT_EQ(s.columns(), 160u);
  EXPECT_EQ(s.rows(), 100u);
  EXPECT_DOUBLE_EQ(s.lon_deg(0), -9.875);
  EXPECT_DOUBLE_EQ(s.lat_deg(99), 59.875);
  EXPECT_FALSE(s.global_longitude());
  GridSpec g = spec_of(0, 360, -90, 90, 1.0 / 60);
  EXPECT_TRUE(g.global_longitude());
  EXPECT_EQ(g.samples_per_turn(), 21600u);
  EXPECT_EQ(g.lat_rad(g.rows() - 1), units::kPi / 2);
  EXPECT_EQ(g.lat_rad(0), -units::kPi / 2);
}

TEST(GridSpec, ParsesGmtRegionAndSpacing) {
  GridSpec s;
  parse_grid_region("-10/30/35.5/60", s);
  EXPECT_EQ(s.west_deg, -10);
  EXPECT_EQ(s.east_deg, 30);
  EXPECT_EQ(s.south_deg, 35.5);
  EXPECT_EQ(s.north_deg, 60);
  parse_grid_region("g", s);
  EXPECT_EQ(s.east_deg - s.west_deg, 360);
  parse_grid_region("d", s);
  EXPECT_EQ(s.west_deg, -180);
  for (const char* bad : {"", "1/2/3", "1/2/3/4/5", "a/2/3/4", "1//3/4", "1/2/3/4x"}) {
    try {
      parse_grid_region(bad, s);
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.context().field, "--region");
    }
  }
  double x = 0, y = 0;
  parse_grid_spacing("30s", x, y);
  EXPECT_DOUBLE_EQ(x, 30.0 / 3600);
  EXPECT_EQ(x, y);
  parse_grid_spacing("5m", x, y);
  EXPECT_DOUBLE_EQ(x, 5.0 / 60);
  parse_grid_spacing("0.5d", x, y);
  EXPECT_EQ(x, 0.5);
  parse_grid_spacing("0.25", x, y);
  EXPECT_EQ(x, 0.25);
  parse_grid_spacing("1m/2m", x, y);
  EXPECT_DOUBLE_EQ(x, 1.0 / 60);
  EXPECT_DOUBLE_EQ(y, 2.0 / 60);
  for (const char* bad : {"", "x", "5q", "-5m", "0", "1m/", "nan"}) {
    try {
      parse_grid_spacing(bad, x, y);
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.context().field, "--spacing");
    }
  }
  EXPECT_EQ(grid_quantity_from_string("dg_up"), GridQuantity::DisturbanceUp);
  EXPECT_THROW(grid_quantity_from_string("zeta"), InputError);
  EXPECT_EQ(grid_path_from_string("fft"), GridPath::Fft);
  EXPECT_THROW(grid_path_from_string("fast"), InputError);
}

}  // namespace gtest_grid

namespace gtest_grid {

TEST(GridSynthesis, PerNodeHeightsEqualPointsAtEveryNode) {
  const GravityField f(grid_model(60));
  GridSpec spec = spec_of(-20, 20, 30, 60, 5, 0, GridRegistration::Gridline, kAll);
  auto height = [](std::size_t j, std::size_t i) { return 100.0 * static_cast<double>(j) - 37.5 * static_cast<double>(i) + 250; };
  std::vector<std::size_t> asked;
  spec.node_heights = [&](std::size_t row, std::span<double> h) {
    asked.push_back(row);
    for (std::size_t i = 0; i < h.size(); ++i) h[i] = height(row, i);
  };
  const Grid g = run(f, spec);
  EXPECT_EQ(g.result.path_used, GridPath::Parallel);
  EXPECT_TRUE(g.result.per_node_heights);
  EXPECT_EQ(asked.size(), spec.rows());
  const std::size_t cols = spec.columns();
  for (std::size_t k = 0; k < spec.quantities.size(); ++k) {
    const GridQuantity q = spec.quantities[k];
    double worst = 0;
    for (std::size_t j = 0; j < spec.rows(); ++j)
      for (std::size_t i = 0; i < cols; ++i) {
        const FieldValues v = f.evaluate({spec.lat_rad(j), spec.lon_rad(i), height(j, i)});
        worst = std::max(worst, std::abs(g.rows[j][k * cols + i] - value_of(v, q)) / scale_of(q));
      }
    EXPECT_LE(worst, tolerance_of(q)) << to_string(q);
  }
  // A constant per-node height gives the constant-height grid (the GravityCircle path).
  GridSpec constant = spec_of(-20, 20, 30, 60, 5, 800, GridRegistration::Gridline, kAll);
  GridSpec per_node = constant;
  per_node.node_heights = [](std::size_t, std::span<double> h) { std::fill(h.begin(), h.end(), 800.0); };
  const Grid a = run(f, constant), b = run(f, per_node);
  for (std::size_t j = 0; j < spec.rows(); ++j)
    for (std::size_t k = 0; k < spec.quantities.size(); ++k)
      for (std::size_t i = 0; i < cols; ++i)
        EXPECT_NEAR(a.rows[j][k * cols + i] / scale_of(spec.quantities[k]),
                    b.rows[j][k * cols + i] / scale_of(spec.quantities[k]), tolerance_of(spec.quantities[k]));
}

TEST(GridSynthesis, PerNodeHeightErrors) {
  const GravityField f(grid_model(20));
  GridSpec spec = spec_of(0, 360, -90, 90, 30, 0, GridRegistration::Gridline, {GridQuantity::Xi});
  spec.node_heights = [](std::size_t row, std::span<double> h) {
    std::fill(h.begin(), h.end(), 0.0);
    if (row == 2) h[3] = 2e7;  // above kMaxHeight_m
  };
  EXPECT_EQ(choose_grid_path(spec), GridPath::Parallel);  // global, but heights vary
  GridOptions fft;
  fft.path = GridPath::Fft;
  expect_input_error(spec, "path", fft);
  try {
    synthesize_grid(f, spec, [](const GridRow&) {});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "rows[2].points[3].h") << e.what();
  }
  spec.node_heights = [](std::size_t, std::span<double>) { throw IoError("height grid unreadable"); };
  EXPECT_THROW(synthesize_grid(f, spec, [](const GridRow&) {}), IoError);
}

}  // namespace gtest_grid
