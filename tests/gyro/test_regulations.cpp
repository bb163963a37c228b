// The checks of the coal-mine surveying regulations (gyro/regulations.hpp,
// spec §7.1) on simulated campaigns with one field mistake each.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include <boost/math/distributions/chi_squared.hpp>

#include <gtest/gtest.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/error.hpp"
#include "meridian/core/units.hpp"
#include "meridian/gyro/campaign.hpp"
#include "meridian/gyro/campaign_simulator.hpp"
#include "meridian/gyro/instrument_spec.hpp"
#include "meridian/gyro/orientations.hpp"
#include "meridian/gyro/plausibility.hpp"
#include "meridian/gyro/regulations.hpp"

using namespace meridian;
using namespace meridian::gyro;

namespace {

SimulatedCampaign clean(std::uint64_t seed = 3) {
  CampaignTruth t = example_campaign_truth();
  t.known_before = 3;
  t.known_after = 3;
  return simulate_campaign(t, seed);
}

// The first check whose name starts with `prefix` and contains `also`.
const Check* find_check(const CampaignResult& r, const std::string& prefix, const std::string& also = "") {
  for (const auto& c : r.checks)
    if (c.name.rfind(prefix, 0) == 0 && c.name.find(also) != std::string::npos) return &c;
  return nullptr;
}

bool has_warning(const CampaignResult& r, const std::string& text) {
  return std::any_of(r.warnings.begin(), r.warnings.end(),
                     [&](const std::string& w) { return w.find(text) != std::string::npos; });
}
}  // namespace

TEST(Regulations, LimitsFollowTheAccuracyClass) {
  const RegulationLimits c15 = regulation_limits(15);
  EXPECT_NEAR(c15.run_difference_rad / units::kArcsecond, 40, 1e-12);
  EXPECT_NEAR(c15.constant_difference_rad / units::kArcsecond, 40, 1e-12);
  EXPECT_NEAR(c15.orientation_difference_rad / units::kArcsecond, 40, 1e-12);
  EXPECT_NEAR(c15.orientation_mean_sigma_rad / units::kArcsecond, 10, 1e-12);
  EXPECT_NEAR(c15.zero_position_div, 0.5, 0);
  const RegulationLimits c25 = regulation_limits(20);  // a 20" instrument is held to the 25" column
  EXPECT_NEAR(c25.run_difference_rad / units::kArcsecond, 70, 1e-12);
  EXPECT_NEAR(c25.orientation_difference_rad / units::kArcsecond, 60, 1e-12);
  EXPECT_NEAR(c25.orientation_mean_sigma_rad / units::kArcsecond, 15, 1e-12);
  const RegulationLimits c5 = regulation_limits(5);
  EXPECT_NEAR(c5.run_difference_rad / units::kArcsecond, 10, 1e-12);
  EXPECT_NEAR(c5.constant_means_rad / units::kArcsecond, 15, 1e-12);
  EXPECT_NEAR(regulation_limits(50).run_difference_rad / units::kArcsecond, 140,
              1e-9);  // 70" × 50/25
  EXPECT_THROW(regulation_limits(0), InputError);
  Tolerances t;
  t.instrument_constant_difference_rad = 30 * units::kArcsecond;
  const RegulationLimits o = apply_tolerances(c15, t);
  EXPECT_NEAR(o.constant_difference_rad / units::kArcsecond, 30, 1e-12);
  EXPECT_NEAR(o.constant_means_rad / units::kArcsecond, 30,
              1e-12);  // the same limit for the means unless set apart
  t.instrument_constant_means_rad = 35 * units::kArcsecond;
  EXPECT_NEAR(apply_tolerances(c15, t).constant_means_rad / units::kArcsecond, 35, 1e-12);
}

TEST(Regulations, CleanCampaignPassesEveryCheck) {
  const auto sim = clean();
  const CampaignResult r = process(sim.input);
  for (const auto& c : r.checks) EXPECT_TRUE(c.pass) << c.name << " " << c.value << " " << c.tolerance;
  EXPECT_TRUE(r.all_checks_pass());
  ASSERT_NE(find_check(r, "programme: runs on the known line before"), nullptr);
  ASSERT_NE(find_check(r, "zero position alpha_p"), nullptr);
  ASSERT_NE(find_check(r, "any two runs on the known line"), nullptr);
  ASSERT_TRUE(r.constant_one_run_sigma_rad && r.line_one_run_sigma_rad);
  // m = sqrt([vv]/(n-1)) of the instrument constants, recomputed here.
  std::vector<double> e;
  for (const auto* v : {&r.instrument_constant->before, &r.instrument_constant->after})
    for (const auto& x : *v) e.push_back(wrap_signed_rad(x.value));
  double mean = 0, vv = 0;
  for (double x : e) mean += x / static_cast<double>(e.size());
  for (double x : e) vv += (x - mean) * (x - mean);
  EXPECT_NEAR(*r.constant_one_run_sigma_rad / units::kArcsecond,
              std::sqrt(vv / static_cast<double>(e.size() - 1)) / units::kArcsecond, 1e-9);
}

TEST(Regulations, InstrumentConstantsOfSingleRunsAreCompared) {
  // One run on the known line pointed 80" off: its E spreads from the others
  // while the before and after means still agree within 40".
  auto sim = clean();
  sim.input.known_line->before[1].target_reading_rad->value += 80 * units::kArcsecond;
  const CampaignResult r = process(sim.input);
  const Check* runs = find_check(r, "any two runs on the known line");
  ASSERT_NE(runs, nullptr);
  EXPECT_FALSE(runs->pass);
  double lo = 1e9, hi = -1e9;
  for (const auto* v : {&r.instrument_constant->before, &r.instrument_constant->after})
    for (const auto& x : *v) {
      lo = std::min(lo, wrap_signed_rad(x.value) / units::kArcsecond);
      hi = std::max(hi, wrap_signed_rad(x.value) / units::kArcsecond);
    }
  EXPECT_NEAR(runs->value, hi - lo, 1e-6);
  EXPECT_GT(runs->value, 60.0);
  EXPECT_TRUE(find_check(r, "instrument constant, mean after - mean before")->pass);
  EXPECT_FALSE(r.all_checks_pass());
}

TEST(Regulations, KnownAzimuthDisagreeingWithCoordinatesFails) {
  auto sim = clean();
  sim.input.known_line->azimuth.value_rad.value += 1.0 * units::kDegree;
  const CampaignResult r = process(sim.input);
  const Check* c = find_check(r, "known line: the given grid azimuth against its coordinates");
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(c->pass);
  EXPECT_NEAR(c->value, 3600.0, 0.5);
  EXPECT_FALSE(find_check(r, "instrument constant E plausible")->pass);
  EXPECT_TRUE(has_warning(r, "differs by +3600.0"));
}

TEST(Regulations, MissingZeroPositionIsReportedAndFails) {
  auto sim = clean();
  auto& d = sim.input.line.determinations[0];
  d.zero_before.reset();
  d.zero_after.reset();
  d.zero_position.reset();
  const CampaignResult r = process(sim.input);
  const Check* c = find_check(r, "zero position observed, line.determinations[0]");
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(c->pass);
  EXPECT_TRUE(has_warning(r, "line.determinations[0]"));
  EXPECT_TRUE(has_warning(r, "no zero position observed"));
}

// The regulations want the motor-off zero position before and after every run: one side only
// leaves its stability unchecked, and is a failed check, not a warning only.
TEST(Regulations, ZeroPositionOnOneSideOnlyFails) {
  auto sim = clean();
  const CampaignResult both = process(sim.input);
  EXPECT_TRUE(both.all_checks_pass());
  EXPECT_EQ(find_check(both, "zero position observed before and after"), nullptr);
  sim.input.line.determinations[1].zero_after.reset();
  const CampaignResult r = process(sim.input);
  const Check* c = find_check(r, "zero position observed before and after, line.determinations[1]");
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(c->pass);
  EXPECT_NE(c->name.find("(only before)"), std::string::npos) << c->name;
  EXPECT_DOUBLE_EQ(c->value, 1.0);
  EXPECT_DOUBLE_EQ(c->tolerance, 2.0);
  EXPECT_FALSE(r.all_checks_pass());
  EXPECT_TRUE(find_check(r, "zero position after - before, line.determinations[1]") == nullptr);
}

TEST(Regulations, ZeroPositionBeyondItsLimitFails) {
  auto sim = clean();
  for (double& a : sim.input.line.determinations[1].zero_before->reversals_div) a += 0.8;
  for (double& a : sim.input.line.determinations[1].zero_after->reversals_div) a += 0.8;
  const CampaignResult r = process(sim.input);
  const Check* c = find_check(r, "zero position alpha_p", "line.determinations[1]");
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(c->pass);
  EXPECT_GT(std::fabs(c->value), 0.5);
}

TEST(Regulations, RunBookedTwiceIsFlagged) {
  auto sim = clean();
  sim.input.line.determinations.push_back(sim.input.line.determinations[0]);
  const CampaignResult r = process(sim.input);
  const Check* c = find_check(r, "no run booked twice");
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(c->pass);
  EXPECT_TRUE(has_warning(r, "line.determinations[0] and line.determinations[3]"));
}

TEST(Regulations, ShortProgrammeFailsAndClassSetsTheLimit) {
  auto sim = clean();
  sim.input.known_line->after.resize(1);
  const CampaignResult r = process(sim.input);
  const Check* c = find_check(r, "programme: runs on the known line after");
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(c->pass);
  EXPECT_TRUE(c->minimum);
  // A 5"-class instrument is held to 10" between runs on the line.
  auto five = clean();
  five.input.instrument.accuracy_class_arcsec = 5;
  const CampaignResult r5 = process(five.input);
  EXPECT_NEAR(find_check(r5, "any two runs on the line")->tolerance, 10.0, 1e-12);
  five.input.tolerances.determination_difference_rad = 25 * units::kArcsecond;
  const CampaignResult r25 = process(five.input);
  const Check* o = find_check(r25, "any two runs on the line");
  EXPECT_NEAR(o->tolerance, 25.0, 1e-12);
  EXPECT_NE(o->source.find("tolerances.determination_difference_arcsec"), std::string::npos);
}

TEST(Plausibility, TimesBookedAsMinutesDotSecondsAreAnErrorNamingTheRun) {
  auto sim = clean();
  auto& d = sim.input.line.determinations[0];
  ASSERT_EQ(d.mode, Mode::NonTracking);
  // 4 min 39.6 s booked as 4.396 and so on: the period collapses to seconds.
  for (auto& c : d.nontracking.crossings)
    for (double& t : c.times_s) t = std::floor(t / 60.0) + std::fmod(t, 60.0) / 100.0;
  try {
    (void)process(sim.input);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field.rfind("line.determinations[0].crossings[", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("m.ss"), std::string::npos) << e.what();
  }
  // Without a stated period the bound is what a gyro-theodolite can do.
  NonTrackingObservations o;
  o.crossings.push_back({0.0, {4.4, 8.0, 11.4}, +1});
  EXPECT_THROW(check_plausible(o), InputError);
  o.crossings[0].times_s = {51.8, 247.3, 470.0};
  EXPECT_NO_THROW(check_plausible(o));
  o.period_s = Uncertain{418.0, 0.0};
  EXPECT_NO_THROW(check_plausible(o));
  o.period_s = Uncertain{200.0, 0.0};  // the passages say 418 s
  EXPECT_THROW(check_plausible(o), InputError);
  o.period_s.reset();
  o.reversals_div = {7.7, -94.0};  // a decimal point lost
  try {
    check_plausible(o);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().field, "reversals_div[1]");
  }
}

TEST(Orientations, TwoIndependentOrientationsOfOneLine) {
  // Two simulated orientations that pass their own checks (seeds chosen so:
  // at α = 1 % one check in a hundred fails by chance).
  const CampaignResult a = process(clean(41).input);
  const CampaignResult b = process(clean(42).input);
  ASSERT_TRUE(a.all_checks_pass() && b.all_checks_pass());
  const OrientationsResult r = combine_orientations({a, b});
  const double d = std::fabs(wrap_signed_rad(a.chain.grid_azimuth_rad.value - b.chain.grid_azimuth_rad.value));
  EXPECT_NEAR(r.mean.max_difference, d, 1e-15);
  // σ of the mean in closed form: both calibrate on the same known line (σ_k of its given azimuth)
  // with the same η booked at the same two points, so cov(T1, T2) = σ_k² + (tan φ_A σ_ηA)² + (tan φ_C σ_ηC)²
  // (no zenith term here) and var(mean) = (σ1² + σ2² + 2 cov)/4; the own parts are bounded by |T1 − T2|/2.
  ASSERT_FALSE(a.chain.zenith_term_applied);
  const auto sq = [](double x) { return x * x; };
  const KnownLineInput& k = *a.input.known_line;
  ASSERT_TRUE(k.from.eta_rad && a.input.line.from.eta_rad);
  const double cov = sq(k.azimuth.value_rad.sigma) + sq(std::tan(a.known_station->lat_rad) * k.from.eta_rad->sigma) +
                     sq(std::tan(a.station.lat_rad) * a.input.line.from.eta_rad->sigma);
  const double s1 = a.chain.grid_azimuth_rad.sigma, s2 = b.chain.grid_azimuth_rad.sigma;
  EXPECT_NEAR(r.covariance_rad2[0][1], cov, 1e-22);
  EXPECT_NEAR(r.covariance_rad2[1][0], cov, 1e-22);
  EXPECT_NEAR(r.mean.sigma_propagated, std::sqrt(sq(s1) + sq(s2) + 2 * cov) / 2, 1e-15);
  EXPECT_NEAR(r.sigma_if_independent_rad, std::hypot(s1, s2) / 2, 1e-15);
  const double own = std::sqrt(sq(s1) + sq(s2) - 2 * cov) / 2;
  EXPECT_NEAR(r.mean.mean.sigma, std::sqrt(sq(std::max(own, d / 2)) + cov), 1e-15);
  EXPECT_EQ(r.shared_sources.size(), 3u);
  // each orientation's own checks, the difference, the σ of the mean, orientation 2 has no run of orientation 1
  ASSERT_EQ(r.checks.size(), 5u);
  EXPECT_TRUE(r.checks[4].pass);
  EXPECT_TRUE(r.checks[0].pass && r.checks[1].pass);
  EXPECT_NEAR(r.checks[2].tolerance, 40.0, 1e-12);
  EXPECT_NEAR(r.checks[3].tolerance, 10.0, 1e-12);
  EXPECT_TRUE(r.all_checks_pass());
  // A second orientation 60" off fails the difference rule.
  CampaignResult c = b;
  c.chain.grid_azimuth_rad.value += 60 * units::kArcsecond;
  const OrientationsResult bad = combine_orientations({a, c});
  EXPECT_FALSE(bad.checks[2].pass);
  EXPECT_FALSE(bad.all_checks_pass());
  // An orientation that fails its own checks fails the combination.
  CampaignResult failing = b;
  failing.checks.front().pass = false;
  EXPECT_FALSE(combine_orientations({a, failing}).checks[1].pass);
  // The same runs twice are not two independent orientations: the check names the runs.
  const OrientationsResult twice = combine_orientations({a, a});
  EXPECT_FALSE(twice.checks[4].pass);
  EXPECT_NE(twice.checks[4].name.find("line.determinations[0] = orientation 1's line.determinations[0]"), std::string::npos)
      << twice.checks[4].name;
  // Orientation 2 with orientation 1's calibration runs (its own line runs) is not independent either.
  SimulatedCampaign reuse = clean(42);
  reuse.input.known_line->before = clean(41).input.known_line->before;
  const OrientationsResult same_e = combine_orientations({a, process(reuse.input)});
  EXPECT_FALSE(same_e.checks[4].pass);
  EXPECT_EQ(same_e.checks[4].value, 3.0);  // the three runs before
  EXPECT_EQ(same_e.checks[4].field, "orientations[1]");
  // The tightest limits of the orientations apply.
  CampaignResult strict = b;
  strict.limits.orientation_difference_rad = 15 * units::kArcsecond;
  EXPECT_NEAR(combine_orientations({a, strict}).checks[2].tolerance, 15.0, 1e-12);
  // The same point under another name (a full-width digit) is the same line, with a note.
  CampaignResult renamed = b;
  renamed.station.name = a.station.name + "\uFF13";
  const OrientationsResult same = combine_orientations({a, renamed});
  EXPECT_TRUE(std::any_of(same.notes.begin(), same.notes.end(), [](const std::string& n) {
    return n.find("the same point by its coordinates") != std::string::npos;
  }));
  // A name that is the same after NFKC (a full-width Ｃ for C) is the same name: no note.
  ASSERT_EQ(a.station.name.substr(0, 1), "C");
  CampaignResult full_width = b;
  full_width.station.name = "\uFF23" + a.station.name.substr(1);
  const OrientationsResult fw = combine_orientations({a, full_width});
  EXPECT_TRUE(std::none_of(fw.notes.begin(), fw.notes.end(), [](const std::string& n) {
    return n.find("the same point by its coordinates") != std::string::npos;
  }));
  // A station 42 m away under the same name is another line: 42 m north is 42/6371000 rad.
  CampaignResult moved = b;
  moved.station.lat_rad += 42.0 / 6371000.0;
  EXPECT_NEAR(point_distance_m(moved.station, b.station), 42.0, 1e-6);
  try {
    combine_orientations({a, moved});
    ADD_FAILURE() << "a station moved 42 m was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("42.000 m from the station"), std::string::npos) << e.what();
  }
  CampaignResult near = b;
  near.station.lat_rad += 0.02 / 6371000.0;  // 2 cm: the same mark
  EXPECT_NO_THROW(combine_orientations({a, near}));
  // A file that names no target (no line.to) beside one that does is refused, naming it.
  ASSERT_TRUE(b.target);
  CampaignResult no_target = b;
  no_target.target.reset();
  no_target.input.line.to.reset();
  try {
    combine_orientations({a, no_target});
    ADD_FAILURE() << "an orientation without a target was taken for the same line";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("orientation 2 names no target (line.to)"), std::string::npos) << e.what();
  }
  EXPECT_THROW(combine_orientations({a}), InputError);
}

TEST(Regulations, LooserFileLimitsAreSaidAloud) {
  auto sim = clean();
  sim.input.tolerances.determination_difference_rad = 400 * units::kArcsecond;
  const CampaignResult r = process(sim.input);
  const Check* c = find_check(r, "any two runs on the line");
  ASSERT_NE(c, nullptr);
  EXPECT_NE(c->source.find("tolerances.determination_difference_arcsec in the file"), std::string::npos);
  EXPECT_TRUE(has_warning(r, "tolerances.determination_difference_arcsec = 400\" in the file is looser than the 40\""));
  // Meridian's own limits say so.
  EXPECT_NE(find_check(r, "instrument constant E plausible")->source.find("Meridian"), std::string::npos);
}

TEST(Regulations, DeflectionHeldInEIsNotAppliedTwice) {
  // E calibrated on a grid azimuth without eta at the known station holds the
  // deflection there; eta given at the line's station alone must not be
  // applied on top of it.
  CampaignTruth t = example_campaign_truth();
  t.give_eta = false;
  auto sim = simulate_campaign(t, 7);
  const CampaignResult without = process(sim.input);
  sim.input.line.from.eta_rad = Uncertain{-5.0 * units::kArcsecond, 0.5 * units::kArcsecond};
  const CampaignResult with_station_eta = process(sim.input);
  EXPECT_FALSE(with_station_eta.chain.laplace_applied);
  EXPECT_DOUBLE_EQ(with_station_eta.chain.grid_azimuth_rad.value, without.chain.grid_azimuth_rad.value);
  bool noted = false;
  for (const auto& n : with_station_eta.notes) noted = noted || n.find("not applied: E was calibrated") != std::string::npos;
  EXPECT_TRUE(noted);
  // With eta at both stations both are applied.
  sim.input.known_line->from.eta_rad = Uncertain{-4.0 * units::kArcsecond, 0.5 * units::kArcsecond};
  EXPECT_TRUE(process(sim.input).chain.laplace_applied);
}

TEST(Regulations, TargetRoundsThatDisagreeWarn) {
  auto sim = clean();
  auto& d = sim.input.line.determinations[0];
  const double r = d.target_reading_rad->value;
  d.target_reading_rad.reset();
  d.target_rounds = {{TargetRound::When::Before, r - 5 * units::kArcsecond,
                      r + units::kPi + 5 * units::kArcsecond},
                     {TargetRound::When::After, r - 5 * units::kArcsecond,
                      r + units::kPi + 65 * units::kArcsecond}};  // one face 1' off
  const CampaignResult res = process(sim.input);
  EXPECT_TRUE(has_warning(res, "line.determinations[0]: the target rounds disagree"));
  // A failed check, not a warning only: the directions (L + R - 180)/2 spread by 30", limit 10".
  const Check* c = find_check(res, "target rounds agree, line.determinations[0]");
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(c->pass);
  EXPECT_NEAR(c->value, 30.0, 1e-6);
  EXPECT_NEAR(c->tolerance, 10.0, 1e-9);
  EXPECT_FALSE(res.all_checks_pass());
  // The other runs book no rounds (their target reading only): the instrument's 2C is this
  // run's median, so which round is wrong cannot be told from the sign.
  d.target_rounds[1].face_right_rad = r + units::kPi + 6 * units::kArcsecond;
  const CampaignResult ok = process(sim.input);
  EXPECT_FALSE(has_warning(ok, "target rounds disagree"));
  EXPECT_TRUE(find_check(ok, "target rounds agree, line.determinations[0]")->pass);
}

// A round booked with its faces swapped is 180° from the other rounds and its 2C is the
// instrument's negated: the check names that round.
TEST(Regulations, RoundWithFacesSwappedIsNamed) {
  auto sim = clean();
  const double two_c = 12 * units::kArcsecond;  // the instrument's collimation, 2C = L - (R - 180)
  for (auto* v : {&sim.input.line.determinations}) {
    for (auto& d : *v) {
      const double r = d.target_reading_rad->value;
      d.target_reading_rad.reset();
      d.target_rounds = {{TargetRound::When::Before, r + two_c / 2, r + units::kPi - two_c / 2},
                         {TargetRound::When::After, r + two_c / 2 + units::kArcsecond, r + units::kPi - two_c / 2}};
    }
  }
  ASSERT_TRUE(find_check(process(sim.input), "target rounds agree, line.determinations[1]")->pass);
  auto& round = sim.input.line.determinations[1].target_rounds[1];
  std::swap(round.face_left_rad, round.face_right_rad);
  const CampaignResult r = process(sim.input);
  const Check* c = find_check(r, "target rounds agree, line.determinations[1]");
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(c->pass);
  EXPECT_NE(c->name.find("target_rounds[1] is 180 deg from the others, face left and face right swapped?"),
            std::string::npos)
      << c->name;
  EXPECT_EQ(c->field, "line.determinations[1].target_rounds[1]");
  EXPECT_NEAR(c->value, 180.0 * 3600.0, 2.0);
}

// The line booked the wrong way round: the gyro azimuth of "C->D" is that of D->C's reverse,
// 180 deg from the azimuth of the coordinates; it fails whatever limit the file sets.
TEST(Regulations, LineBookedFromToSwappedFails) {
  auto sim = clean();
  const CampaignResult ok = process(sim.input);
  const Check* c0 = find_check(ok, "the line ", "against the azimuth of its coordinates");
  ASSERT_NE(c0, nullptr);
  EXPECT_TRUE(c0->pass);
  EXPECT_EQ(c0->field, "line.to");
  // The value is T minus atan2(dy, dx) of the booked coordinates, recomputed here.
  const auto& f = sim.input.line.from;
  const auto& t = *sim.input.line.to;
  ASSERT_TRUE(f.x_north_m && t.x_north_m);
  const double coord = std::atan2(*t.y_east_m - *f.y_east_m, *t.x_north_m - *f.x_north_m);
  EXPECT_NEAR(c0->value, wrap_signed_rad(ok.chain.grid_azimuth_rad.value - coord) / units::kArcsecond, 1e-6);
  EXPECT_NEAR(c0->tolerance, 40.0, 1e-9);  // 15" class: the limit of two orientations

  std::swap(sim.input.line.from.x_north_m, sim.input.line.to->x_north_m);
  std::swap(sim.input.line.from.y_east_m, sim.input.line.to->y_east_m);
  std::swap(sim.input.line.from.name, sim.input.line.to->name);
  sim.input.tolerances.line_coordinates_rad = 10 * units::kDegree;  // a loose file limit does not hide it
  const CampaignResult r = process(sim.input);
  const Check* c = find_check(r, "the line ", "against the azimuth of its coordinates");
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(c->pass);
  EXPECT_NE(c->name.find("from and to swapped?"), std::string::npos) << c->name;
  EXPECT_NEAR(std::fabs(c->value), 648000.0, 3600.0);
  EXPECT_TRUE(has_warning(r, "booked the wrong way round?"));
}

TEST(Regulations, LineAgainstCoordinatesHasAnEditableLimit) {
  auto sim = clean();
  // The target moved sideways by 60" of the line's length: the traverse and the gyro disagree.
  auto& f = sim.input.line.from;
  auto& t = *sim.input.line.to;
  const double dx = *t.x_north_m - *f.x_north_m, dy = *t.y_east_m - *f.y_east_m;
  const double turn = 60 * units::kArcsecond;
  t.x_north_m = *f.x_north_m + dx * std::cos(turn) - dy * std::sin(turn);
  t.y_east_m = *f.y_east_m + dx * std::sin(turn) + dy * std::cos(turn);
  const CampaignResult r = process(sim.input);
  const Check* c = find_check(r, "the line ", "against the azimuth of its coordinates");
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(c->pass);
  EXPECT_GT(std::fabs(c->value), 40.0);
  sim.input.tolerances.line_coordinates_rad = 90 * units::kArcsecond;
  const CampaignResult r2 = process(sim.input);
  const Check* loose = find_check(r2, "the line ", "against the azimuth of its coordinates");
  EXPECT_TRUE(loose->pass);
  EXPECT_EQ(loose->source, "tolerances.line_coordinates_arcsec in the file");
}

// A given grid azimuth is its coordinates' own: it agrees with them to their rounding, and a
// 10" typo fails (the class's 15" would pass it).
TEST(Regulations, KnownGridAzimuthIsHeldToItsCoordinatesRounding) {
  auto sim = clean();
  auto& k = *sim.input.known_line;
  for (std::optional<double>* v : {&k.from.x_north_m, &k.from.y_east_m, &k.to->x_north_m, &k.to->y_east_m})
    **v = std::round(**v * 1000.0) / 1000.0;  // booked to 1 mm, as the reader records it:
  for (PointInput* p : {&k.from, &*k.to}) p->x_half_unit_m = p->y_half_unit_m = 0.0005;
  const double dx = *k.to->x_north_m - *k.from.x_north_m, dy = *k.to->y_east_m - *k.from.y_east_m;
  k.azimuth.value_rad.value = wrap_positive_rad(std::atan2(dy, dx));
  const double limit = (0.001 * std::fabs(dx) + 0.001 * std::fabs(dy)) / (dx * dx + dy * dy) / units::kArcsecond + 0.5;
  const CampaignResult ok = process(sim.input);
  const Check* c0 = find_check(ok, "known line: the given grid azimuth against its coordinates, to their rounding");
  ASSERT_NE(c0, nullptr);
  EXPECT_TRUE(c0->pass);
  EXPECT_NEAR(c0->tolerance, limit, 1e-9) << c0->source;
  EXPECT_EQ(c0->field, "known_line.azimuth.value");
  k.azimuth.value_rad.value += 10 * units::kArcsecond;
  const CampaignResult r = process(sim.input);
  const Check* c = find_check(r, "known line: the given grid azimuth against its coordinates");
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(c->pass);
  EXPECT_NEAR(c->value, 10.0, 1e-6);
}

// A tracking run booked without sigma_reading_arcsec is checked against the class's default
// (class/3, 5" for 15"): a reversal booked 1' wrong fails although no sigma was booked.
TEST(Regulations, TrackingRunWithoutStatedSigmaIsCheckedAgainstTheClassDefault) {
  CampaignTruth truth = example_campaign_truth();
  truth.sigma_tracking_arcsec = 3.0;
  auto sim = simulate_campaign(truth, 5);
  const auto unbook = [](std::vector<DeterminationInput>& v) {
    for (auto& d : v) d.tracking.sigma_reading_rad = std::numeric_limits<double>::quiet_NaN();
  };
  unbook(sim.input.known_line->before);
  unbook(sim.input.known_line->after);
  unbook(sim.input.line.determinations);
  std::size_t k = 0;
  while (k < sim.input.line.determinations.size() && sim.input.line.determinations[k].mode != Mode::Tracking) ++k;
  ASSERT_LT(k, sim.input.line.determinations.size());
  const std::string run = "line.determinations[" + std::to_string(k) + "]";
  const CampaignResult ok = process(sim.input);
  const Check* c0 = find_check(ok, "tracking readings scatter as stated, " + run);
  ASSERT_NE(c0, nullptr);
  EXPECT_TRUE(c0->pass) << c0->value;
  // The limit is 5" sqrt(chi2_0.99(dof)/dof), from Boost's quantile here independently of adjust.
  const int dof = ok.determinations[k].primary.reversal->dof;
  ASSERT_GT(dof, 0);
  const double chi2 = boost::math::quantile(boost::math::chi_squared(dof), 0.99);
  EXPECT_NEAR(c0->tolerance, 5.0 * std::sqrt(chi2 / dof), 1e-9);
  EXPECT_NE(c0->source.find("class's default"), std::string::npos) << c0->source;
  EXPECT_EQ(c0->field, run + ".reversals");
  sim.input.line.determinations[k].tracking.reversals_rad[1] += 60 * units::kArcsecond;
  const CampaignResult r = process(sim.input);
  const Check* c = find_check(r, "tracking readings scatter as stated, " + run);
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(c->pass) << c->value;
}

TEST(Regulations, AccuracyClassFromTheInstrumentsName) {
  EXPECT_EQ(accuracy_class_from_name("JT15 陀螺经纬仪"), 15.0);
  EXPECT_EQ(accuracy_class_from_name("jt-5 No. 12"), 5.0);
  EXPECT_EQ(accuracy_class_from_name("Y/JT 15"), 15.0);
  EXPECT_EQ(accuracy_class_from_name("GAK1 on a T2"), 15.0);
  EXPECT_FALSE(accuracy_class_from_name("BJT15").has_value());
  EXPECT_FALSE(accuracy_class_from_name("JT150").has_value());
  EXPECT_FALSE(accuracy_class_from_name("JT15B").has_value());
  EXPECT_FALSE(accuracy_class_from_name("Gyromat 2000").has_value());
}

// The class sets every limit: not booked is a failed check (with the class used stated), and a
// class looser than the instrument's name states fails.
TEST(Regulations, AccuracyClassMustBeBookedAndMatchTheName) {
  auto sim = clean();
  sim.input.instrument.name = "JT15 No. 7";
  sim.input.instrument.accuracy_class_arcsec = 15;
  const CampaignResult ok = process(sim.input);
  const Check* c0 = find_check(ok, "accuracy class booked against the instrument's name");
  ASSERT_NE(c0, nullptr);
  EXPECT_TRUE(c0->pass);
  sim.input.instrument.accuracy_class_arcsec = 5;  // tighter than the name: accepted (the job may then fail others)
  const CampaignResult tight = process(sim.input);
  EXPECT_TRUE(find_check(tight, "accuracy class booked against the instrument's name")->pass);
  sim.input.instrument.accuracy_class_arcsec = 25;
  const CampaignResult loose = process(sim.input);
  const Check* c = find_check(loose, "accuracy class booked against the instrument's name");
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(c->pass);
  EXPECT_EQ(c->field, "instrument.accuracy_class_arcsec");
  EXPECT_NEAR(loose.limits.run_difference_rad / units::kArcsecond, 70.0, 1e-9);  // what a 25" class gets
  // Not booked: the class of the name (JT5: 5") sets the limits, and the check fails.
  sim.input.instrument.name = "JT5";
  sim.input.instrument.accuracy_class_arcsec = 15;
  sim.input.instrument.accuracy_class_booked = false;
  const CampaignResult unbooked = process(sim.input);
  const Check* b = find_check(unbooked, "accuracy class booked (not booked: the 5\" limits of the class of its name");
  ASSERT_NE(b, nullptr) << unbooked.checks.front().name;
  EXPECT_FALSE(b->pass);
  EXPECT_NEAR(unbooked.limits.run_difference_rad / units::kArcsecond, 10.0, 1e-9);
  sim.input.instrument.name = "gyro No. 3";
  EXPECT_NE(find_check(process(sim.input), "accuracy class booked (not booked: the 15\" limits of Meridian's default"),
            nullptr);
}

TEST(Orientations, SharedKnownLineAndEtaCorrelateTheOrientationsAsStated) {
  // Monte Carlo: pairs of orientations whose runs are independent but whose known line azimuth and
  // booked η carry one common error per pair, drawn with their booked σ. The sample covariance of the
  // two orientations' errors must be the stated C_12 (within 3 standard errors of a sample covariance,
  // sqrt((σ1²σ2² + C²)/n)) and clearly not the 0 of independence; the mean's σ must not be optimistic.
  std::mt19937_64 rng(2026);
  std::normal_distribution<double> unit(0.0, 1.0);
  const int pairs = 400;
  double s12 = 0, c12 = 0, v1 = 0, v2 = 0, zz = 0;
  for (int p = 0; p < pairs; ++p) {
    SimulatedCampaign a = clean(1000 + 2 * p), b = clean(1001 + 2 * p);
    const double ek = unit(rng) * a.input.known_line->azimuth.value_rad.sigma;
    const double ea = unit(rng) * a.input.known_line->from.eta_rad->sigma;
    const double ec = unit(rng) * a.input.line.from.eta_rad->sigma;
    for (SimulatedCampaign* s : {&a, &b}) {
      s->input.known_line->azimuth.value_rad.value += ek;
      s->input.known_line->from.eta_rad->value += ea;
      s->input.line.from.eta_rad->value += ec;
    }
    const CampaignResult ra = process(a.input), rb = process(b.input);
    const OrientationsResult r = combine_orientations({ra, rb});
    const double e1 = wrap_signed_rad(ra.chain.grid_azimuth_rad.value - a.true_grid_azimuth_rad);
    const double e2 = wrap_signed_rad(rb.chain.grid_azimuth_rad.value - b.true_grid_azimuth_rad);
    s12 += e1 * e2;
    c12 += r.covariance_rad2[0][1];
    v1 += e1 * e1, v2 += e2 * e2;
    const double e = wrap_signed_rad(r.mean.mean.value - a.true_grid_azimuth_rad);
    zz += (e / r.mean.mean.sigma) * (e / r.mean.mean.sigma);
  }
  const double n = pairs, as2 = units::kArcsecond * units::kArcsecond;
  const double sample = s12 / n, stated = c12 / n;
  const double se = std::sqrt((v1 / n) * (v2 / n) + sample * sample) / std::sqrt(n);
  std::printf("cov(T1, T2) over %d pairs: sample %.2f, stated %.2f, standard error %.2f arcsec^2; RMS of "
              "error/sigma of the mean %.3f\n",
              pairs, sample / as2, stated / as2, se / as2, std::sqrt(zz / n));
  EXPECT_LT(std::abs(sample - stated), 3 * se);
  EXPECT_GT(sample, 3 * se);  // independence (cov 0) is refuted
  EXPECT_LT(std::sqrt(zz / n), 1.15);
}

TEST(Regulations, AZeroPositionTypedInIsNotObservedBeforeAndAfter) {
  // The regulations want motor-off runs before and after every run: a value booked instead is held to
  // the rule of a run observed on one side only (helper trial, issue 36: it used to pass).
  auto sim = clean();
  auto& d = sim.input.line.determinations[1];
  d.zero_before.reset();
  d.zero_after.reset();
  d.zero_position = Uncertain{-0.2, 0.05};
  const CampaignResult r = process(sim.input);
  const Check* c = find_check(r, "zero position observed before and after, line.determinations[1]", "given as a value");
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE(c->pass);
  EXPECT_EQ(c->field, "line.determinations[1].zero_position");
  EXPECT_FALSE(r.all_checks_pass());
}
