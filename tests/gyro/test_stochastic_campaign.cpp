// The campaign option stochastic_model (gyro/stochastic_determination.hpp): white is the
// reduction as before, a model that cannot be used falls back to white noise bit for bit with a
// warning (an error for a determination's own request), N_G under Markov-1 is the GLS of (R1)
// with the reported covariance, and on Markov-1 reading errors its σ matches the Monte Carlo
// scatter better than white noise.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/campaign.hpp"
#include "meridian/gyro/campaign_simulator.hpp"
#include "meridian/gyro/markov_covariance.hpp"
#include "meridian/gyro/simulator.hpp"
#include "meridian/gyro/stochastic.hpp"
#include "meridian/gyro/stochastic_determination.hpp"

namespace {

using namespace meridian;
using namespace meridian::gyro;
using ::testing::HasSubstr;

constexpr double kCentreRad = 284.0 * units::kDegree + 5.0 * units::kArcminute;

// The simulated example campaign reduced to the line with one tracking determination of `n`
// reversals (no zero-position runs, so N_G = M) and the instrument constant given: the reading
// errors follow Markov-1 (ρ, σ_Δ = 2", σ_X0 = 5"), the booked σ of a reading is σ_Δ.
CampaignInput sc_tracking_campaign(int n, double rho, std::uint64_t seed) {
  CampaignInput in = simulate_campaign(example_campaign_truth(), 2026).input;
  in.known_line.reset();
  in.instrument_constant_rad = Uncertain{0.0, 1.0 * units::kArcsecond};
  DeterminationInput d;
  for (const auto& x : in.line.determinations)
    if (x.mode == Mode::Tracking) d = x;
  EXPECT_EQ(d.mode, Mode::Tracking);
  d.zero_before.reset();
  d.zero_after.reset();
  d.zero_position = std::nullopt;
  d.method = ReversalMethod::NonlinearLsq;
  TrackingSimulation sim;
  sim.centre_rad = kCentreRad;
  sim.amplitude_rad = 4800.0 * units::kArcsecond;
  sim.kappa = 0.002;
  sim.reversals = n;
  sim.reading_noise =
      NoiseModel::markov1(2.0 * units::kArcsecond, rho, 5.0 * units::kArcsecond);
  d.tracking.reversals_rad = simulate_tracking(sim, seed);
  d.tracking.sigma_reading_rad = 2.0 * units::kArcsecond;
  in.line.determinations = {d};
  return in;
}

double sc_arcsec(double a, double b) { return std::remainder(a - b, 2 * units::kPi) / units::kArcsecond; }

TEST(StochasticCampaign, WhiteIsTheDefaultAndChangesNothing) {
  const CampaignInput base = simulate_campaign(example_campaign_truth(), 1234).input;
  ASSERT_EQ(base.stochastic_model, StochasticChoice::White);
  const CampaignResult a = process(base);
  for (const auto& d : a.determinations) {
    EXPECT_EQ(d.stochastic.requested, StochasticChoice::White);
    EXPECT_EQ(d.stochastic.used, "white");
    EXPECT_FALSE(d.stochastic.fallback);
  }
  // Every series of the example has 5 readings: markov1 cannot be used anywhere, and the
  // fallback is white noise bit for bit, with a warning per determination.
  CampaignInput m1 = base;
  m1.stochastic_model = StochasticChoice::Markov1;
  const CampaignResult b = process(m1);
  ASSERT_EQ(a.determinations.size(), b.determinations.size());
  for (std::size_t i = 0; i < a.determinations.size(); ++i) {
    const auto& x = a.determinations[i];
    const auto& y = b.determinations[i];
    EXPECT_EQ(x.primary.north.north_rad, y.primary.north.north_rad);
    EXPECT_EQ(x.primary.north.sigma_rad, y.primary.north.sigma_rad);
    EXPECT_TRUE(y.stochastic.fallback);
    EXPECT_EQ(y.stochastic.used, "white");
    EXPECT_FALSE(y.stochastic.reason.empty());
  }
  EXPECT_EQ(a.chain.grid_azimuth_rad.value, b.chain.grid_azimuth_rad.value);
  EXPECT_EQ(a.chain.grid_azimuth_rad.sigma, b.chain.grid_azimuth_rad.sigma);
  int fallbacks = 0;
  for (const auto& w : b.warnings)
    if (w.find("stochastic_model markov1 cannot be used") != std::string::npos) ++fallbacks;
  EXPECT_EQ(fallbacks, static_cast<int>(b.determinations.size() + b.known_before.size() +
                                        b.known_after.size()));
  // The tracking run says why: its 5 readings.
  bool said = false;
  for (const auto& w : b.warnings)
    said = said || w.find("has 5 reversal readings, the markov1 model needs at least 6") !=
                       std::string::npos;
  EXPECT_TRUE(said);
}

// The series of the campaign's line determination in arcsec from the first reading's degree.
std::vector<double> sc_series_arcsec(const CampaignInput& in, double* ref_rad) {
  const std::vector<double> un = unwrap_circle_readings(in.line.determinations[0].tracking.reversals_rad);
  *ref_rad = std::floor(un.front() / units::kDegree) * units::kDegree;
  std::vector<double> arcsec;
  for (double x : un) arcsec.push_back((x - *ref_rad) / units::kArcsecond);
  return arcsec;
}

TEST(StochasticCampaign, Markov1IsTheGlsOfR1WithTheReportedCovariance) {
  CampaignInput in = sc_tracking_campaign(20, 0.6, 3);
  in.stochastic_model = StochasticChoice::Markov1;
  const CampaignResult r = process(in);
  const DeterminationResult& d = r.determinations.at(0);
  ASSERT_FALSE(d.stochastic.fallback) << d.stochastic.reason;
  EXPECT_EQ(d.stochastic.used, "markov1-ml");
  ASSERT_EQ(d.stochastic.rho.size(), 1u);
  // Rebuild D from the reported ρ, σ_1, σ_2 and the series in arcsec from the first reading's
  // whole degree; the GLS of (R1) gives M, and N_G = M without a zero position.
  double ref = 0.0;
  const std::vector<double> arcsec = sc_series_arcsec(in, &ref);
  const double s1 = d.stochastic.sigma1_arcsec, s2 = d.stochastic.sigma2_arcsec;
  const Eigen::MatrixXd D = markov1_factors(20, d.stochastic.rho[0]).covariance(s1 * s1, s2 * s2);
  const R1GlsFit g = reversal_gls_nonlinear(arcsec, D);
  EXPECT_NEAR(sc_arcsec(d.primary.north.north_rad, ref + g.centre.value * units::kArcsecond), 0.0,
              1e-6);
  EXPECT_NEAR(d.primary.north.sigma_rad / units::kArcsecond, g.centre.sigma, 1e-9);
  EXPECT_EQ(d.primary.north.zero_correction_rad, 0.0);
  // The reversal fit of the report carries the same centre, and says how it was computed.
  EXPECT_NEAR(sc_arcsec(d.primary.reversal->centre.value, d.primary.north.north_rad), 0.0, 1e-9);
  EXPECT_THAT(d.primary.reversal->notes.back(), HasSubstr("under markov1-ml"));
  // The truth within 3σ; white noise gives a different σ.
  EXPECT_LT(std::fabs(sc_arcsec(d.primary.north.north_rad, kCentreRad)),
            3.0 * d.primary.north.sigma_rad / units::kArcsecond);
  const CampaignResult w = process(sc_tracking_campaign(20, 0.6, 3));
  EXPECT_NE(w.determinations[0].primary.north.sigma_rad, d.primary.north.sigma_rad);
  // A_G follows N_G.
  EXPECT_NEAR(sc_arcsec(r.gyro_azimuths[0].value, w.gyro_azimuths[0].value),
              -sc_arcsec(d.primary.north.north_rad, w.determinations[0].primary.north.north_rad),
              1e-6);
}

TEST(StochasticCampaign, WhiteNoiseSigmaWarningSaysWhatGivesSigma) {
  // Booked σ 0.5" against readings scattering by more: the global test of the white-noise fit
  // rejects; under markov1 the warning says that N_G's σ comes from the GLS instead, and the
  // reports' sigma basis says GLS.
  CampaignInput in = sc_tracking_campaign(20, 0.6, 8);
  in.line.determinations[0].tracking.sigma_reading_rad = 0.5 * units::kArcsecond;
  const CampaignResult w = process(in);
  ASSERT_TRUE(w.determinations[0].primary.reversal->reading_sigma_test->rejected);
  in.stochastic_model = StochasticChoice::Markov1;
  const CampaignResult m = process(in);
  const auto& d = m.determinations[0];
  ASSERT_FALSE(d.stochastic.fallback) << d.stochastic.reason;
  EXPECT_TRUE(d.primary.reversal->sigma_from_gls);
  EXPECT_FALSE(w.determinations[0].primary.reversal->sigma_from_gls);
  bool said = false;
  for (const auto& x : d.warnings)
    said = said || (x.find("a-posteriori sigma is used for white noise; N_G and its sigma are from "
                           "the GLS under markov1-ml instead") != std::string::npos);
  EXPECT_TRUE(said);
}

TEST(StochasticCampaign, Markov2AndRecommended) {
  int markov2_used = 0, recommended_other = 0, recommended_white = 0;
  for (std::uint64_t seed = 40; seed < 48; ++seed) {
    CampaignInput in = sc_tracking_campaign(20, 0.6, seed);
    double ref = 0.0;
    const std::vector<double> arcsec = sc_series_arcsec(in, &ref);
    // markov2: the GLS of (R1) under the reported Markov-2 covariance, or a fallback that says
    // why (a degenerate fit).
    in.stochastic_model = StochasticChoice::Markov2;
    const CampaignResult m2 = process(in);
    const auto& d2 = m2.determinations[0];
    if (d2.stochastic.fallback) {
      EXPECT_THAT(d2.stochastic.reason, HasSubstr("markov2-ml"));
    } else {
      ++markov2_used;
      EXPECT_EQ(d2.stochastic.used, "markov2-ml");
      ASSERT_EQ(d2.stochastic.rho.size(), 2u);
      const double s1 = d2.stochastic.sigma1_arcsec, s2 = d2.stochastic.sigma2_arcsec;
      const Eigen::MatrixXd D = markov2_factors(20, d2.stochastic.rho[0], d2.stochastic.rho[1])
                                    .covariance(s1 * s1, s2 * s2);
      const R1GlsFit g = reversal_gls_nonlinear(arcsec, D);
      EXPECT_NEAR(sc_arcsec(d2.primary.north.north_rad, ref + g.centre.value * units::kArcsecond),
                  0.0, 1e-6);
      EXPECT_NEAR(d2.primary.north.sigma_rad / units::kArcsecond, g.centre.sigma, 1e-9);
    }
    // recommended: the model the full comparison of the same series recommends.
    in.stochastic_model = StochasticChoice::Recommended;
    const CampaignResult rc = process(in);
    const auto& dr = rc.determinations[0];
    StochasticInput si;  // the determination's series as booked
    si.kind = SeriesKind::Circle;
    si.readings = in.line.determinations[0].tracking.reversals_rad;
    si.booked_sigma = in.line.determinations[0].tracking.sigma_reading_rad;
    const StochasticResult full = analyse_stochastic(si);
    const ModelFit& rec = full.models[static_cast<std::size_t>(full.recommended)];
    EXPECT_FALSE(dr.stochastic.fallback);
    if (rec.model == StochasticModel::WhiteNoise) {
      ++recommended_white;
      EXPECT_EQ(dr.stochastic.used, "white");
      EXPECT_EQ(dr.stochastic.reason, "the comparison recommends white noise");
      const CampaignResult w = process(sc_tracking_campaign(20, 0.6, seed));
      EXPECT_EQ(dr.primary.north.north_rad, w.determinations[0].primary.north.north_rad);
      EXPECT_EQ(dr.primary.north.sigma_rad, w.determinations[0].primary.north.sigma_rad);
    } else {
      ++recommended_other;
      EXPECT_EQ(dr.stochastic.used, to_string(rec.model));
      ASSERT_TRUE(rec.r1.has_value());
      EXPECT_NEAR(sc_arcsec(dr.primary.north.north_rad, ref + rec.r1->centre.value * units::kArcsecond),
                  0.0, 1e-9);
      EXPECT_NEAR(dr.primary.north.sigma_rad / units::kArcsecond, rec.r1->centre.sigma, 1e-12);
    }
  }
  std::printf("markov2 used %d of 8; recommended: white %d, other %d\n", markov2_used,
              recommended_white, recommended_other);
  EXPECT_GT(markov2_used, 0);
  EXPECT_GT(recommended_other, 0);
}

TEST(StochasticCampaign, LinearMethodUsesTheGlsOfR2) {
  CampaignInput in = sc_tracking_campaign(20, 0.6, 4);
  in.line.determinations[0].method = ReversalMethod::LinearLsq;
  in.stochastic_model = StochasticChoice::Markov1;
  const CampaignResult r = process(in);
  const DeterminationResult& d = r.determinations.at(0);
  ASSERT_FALSE(d.stochastic.fallback) << d.stochastic.reason;
  double ref = 0.0;
  const std::vector<double> arcsec = sc_series_arcsec(in, &ref);
  const double s1 = d.stochastic.sigma1_arcsec, s2 = d.stochastic.sigma2_arcsec;
  const Eigen::MatrixXd D = markov1_factors(20, d.stochastic.rho[0]).covariance(s1 * s1, s2 * s2);
  const GlsFit g = reversal_gls(arcsec, D);
  EXPECT_NEAR(sc_arcsec(d.primary.north.north_rad, ref + g.y(0) * units::kArcsecond), 0.0, 1e-6);
  EXPECT_NEAR(d.primary.north.sigma_rad / units::kArcsecond, std::sqrt(g.covariance(0, 0)), 1e-9);
}

TEST(StochasticCampaign, RequestsThatCannotBeHonoured) {
  // Schuler has no GLS: the campaign-wide request falls back with a warning saying so.
  CampaignInput in = sc_tracking_campaign(20, 0.6, 5);
  in.line.determinations[0].method = ReversalMethod::Schuler;
  in.stochastic_model = StochasticChoice::Markov1;
  const CampaignResult r = process(in);
  EXPECT_TRUE(r.determinations[0].stochastic.fallback);
  EXPECT_THAT(r.determinations[0].stochastic.reason, HasSubstr("schuler"));
  bool warned = false;
  for (const auto& w : r.warnings)
    warned = warned || (w.rfind("line.determinations[0]: stochastic_model markov1 cannot be used", 0) == 0);
  EXPECT_TRUE(warned);
  // The determination's own request is an error naming its field.
  in.line.determinations[0].stochastic_model = StochasticChoice::Markov1;
  try {
    process(in);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "line.determinations[0].stochastic_model");
    EXPECT_THAT(e.message(), HasSubstr("schuler"));
  }
  // Markov-2 needs 8 readings.
  CampaignInput few = sc_tracking_campaign(7, 0.6, 6);
  few.line.determinations[0].stochastic_model = StochasticChoice::Markov2;
  EXPECT_THROW(process(few), InputError);
  // A determination's own "white" overrides the campaign's model.
  CampaignInput own = sc_tracking_campaign(20, 0.6, 7);
  own.stochastic_model = StochasticChoice::Markov1;
  own.line.determinations[0].stochastic_model = StochasticChoice::White;
  const CampaignResult ow = process(own);
  const CampaignResult plain = process(sc_tracking_campaign(20, 0.6, 7));
  EXPECT_EQ(ow.determinations[0].primary.north.north_rad,
            plain.determinations[0].primary.north.north_rad);
  EXPECT_EQ(ow.determinations[0].stochastic.used, "white");
  EXPECT_FALSE(ow.determinations[0].stochastic.fallback);
  // Names.
  EXPECT_EQ(stochastic_choice_from_string("recommended"), StochasticChoice::Recommended);
  EXPECT_THROW(stochastic_choice_from_string("markov3"), InputError);
}

TEST(StochasticCampaign, Markov1SigmaMatchesTheScatterBetterThanWhite) {
  // 300 campaigns with Markov-1 reading errors (ρ = 0.6, σ_Δ = 2", σ_X0 = 5", 20 reversals):
  // the rms reported σ(N_G) against the empirical scatter of N_G, white noise against markov1.
  const int runs = 300;
  std::vector<double> nw, nm;
  double sw2 = 0.0, sm2 = 0.0;
  int fallbacks = 0;
  for (int k = 0; k < runs; ++k) {
    CampaignInput in = sc_tracking_campaign(20, 0.6, 500 + static_cast<std::uint64_t>(k));
    const CampaignResult w = process(in);
    in.stochastic_model = StochasticChoice::Markov1;
    const CampaignResult m = process(in);
    const auto& dw = w.determinations[0];
    const auto& dm = m.determinations[0];
    if (dm.stochastic.fallback) ++fallbacks;
    nw.push_back(sc_arcsec(dw.primary.north.north_rad, kCentreRad));
    nm.push_back(sc_arcsec(dm.primary.north.north_rad, kCentreRad));
    sw2 += std::pow(dw.primary.north.sigma_rad / units::kArcsecond, 2);
    sm2 += std::pow(dm.primary.north.sigma_rad / units::kArcsecond, 2);
  }
  const auto scatter = [](const std::vector<double>& v) {
    double mean = 0.0, s = 0.0;
    for (double x : v) mean += x / static_cast<double>(v.size());
    for (double x : v) s += (x - mean) * (x - mean);
    return std::sqrt(s / static_cast<double>(v.size() - 1));
  };
  const double ratio_white = std::sqrt(sw2 / runs) / scatter(nw);
  const double ratio_markov1 = std::sqrt(sm2 / runs) / scatter(nm);
  RecordProperty("ratio_white", std::to_string(ratio_white));
  RecordProperty("ratio_markov1", std::to_string(ratio_markov1));
  std::printf("rms sigma / scatter: white %.3f (scatter %.3f\"), markov1 %.3f (scatter %.3f\"), "
              "%d fallbacks\n",
              ratio_white, scatter(nw), ratio_markov1, scatter(nm), fallbacks);
  EXPECT_LT(std::fabs(ratio_markov1 - 1.0), std::fabs(ratio_white - 1.0));
  EXPECT_LT(std::fabs(ratio_markov1 - 1.0), 0.2);
}

}  // namespace
