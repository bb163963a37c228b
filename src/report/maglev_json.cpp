#include "meridian/report/maglev_json.hpp"

#include "meridian/core/units.hpp"

namespace meridian::report {
namespace {
using nlohmann::json;

json solution(const maglev::TwoPositionSolution& s) {
  return {{"alpha1_arcsec", units::rad_to_arcsec(s.alpha1_rad.value)},
          {"alpha1_sigma_arcsec", units::rad_to_arcsec(s.alpha1_rad.sigma)},
          {"north_deg", units::rad_to_deg(s.north_rad.value)},
          {"north_sigma_arcsec", units::rad_to_arcsec(s.north_rad.sigma)},
          {"bias_A", s.bias_A.value},
          {"bias_sigma_A", s.bias_A.sigma}};
}

json position(const maglev::PositionResult& p) {
  const maglev::PositionSeries& series = p.series;
  json j = {{"samples", p.samples},
            {"kept_samples", p.kept_samples},
            {"mean_all_A", p.raw.mean},
            {"mean_all_sigma_A", p.raw.sigma},
            {"n_eff_all", p.raw.n_eff},
            {"mean_cleaned_A", p.cleaned_mean_A.value},
            {"mean_cleaned_sigma_A", p.cleaned_mean_A.sigma},
            {"n_eff_kept", p.kept.n_eff},
            {"median_A", p.median_A},
            {"variance_raw_A2", p.variance_raw_A2},
            {"variance_cleaned_A2", p.variance_cleaned_A2},
            {"wavelet_noise_sigma_A", p.noise_sigma_A},
            {"denoise_levels", p.denoise_levels}};
  if (p.huber_failed.empty()) {
    j["huber_A"] = p.huber_A.value;
    j["huber_sigma_A"] = p.huber_A.sigma;
  } else {
    j["huber_failed"] = p.huber_failed;
  }
  if (p.stationarity) {
    const auto& st = *p.stationarity;
    json segs = json::array();
    for (const auto& s : st.segments)
      segs.push_back({{"begin", s.begin},
                      {"end", s.end},
                      {"begin_s", series.time_s[s.begin]},
                      {"end_s", series.time_s[s.end - 1]},
                      {"mean_A", s.mean},
                      {"z_mean", s.z_mean},
                      {"p_mean", s.p_mean},
                      {"q_autocovariance", s.q_autocovariance},
                      {"p_autocovariance", s.p_autocovariance},
                      {"kept", s.kept}});
    j["segment_length"] = st.segment_length;
    j["segment_alpha"] = st.segment_alpha;
    j["reference_mean_A"] = st.reference_mean;
    j["rejected_segments"] = st.rejected();
    j["segments"] = segs;
  }
  return j;
}
}  // namespace

json maglev_reduce_to_json(const maglev::ReduceResult& r) {
  json j = {{"amplitude_A", r.amplitude_A.value},
            {"scale_A_s_per_rad", r.scale_A_s_per_rad.value},
            {"latitude_deg", units::rad_to_deg(r.latitude_rad)},
            {"processed", r.options.process},
            {"position1", position(r.position1)},
            {"position2", position(r.position2)},
            {"result", solution(r.processed)},
            {"plain", solution(r.plain)},
            {"plausibility",
             {{"sample_noise_arcsec", units::rad_to_arcsec(r.sample_noise_rad)},
              {"unit_slip_suspected", r.unit_slip_suspected}}},
            {"notes", r.notes},
            {"warnings", r.warnings}};
  if (r.drift) {
    const auto& d = *r.drift;
    json blocks = json::array();
    for (const auto& b : d.blocks)
      blocks.push_back({{"position", b.position}, {"begin", b.begin}, {"end", b.end},
                        {"begin_s", b.begin_s}, {"end_s", b.end_s}});
    j["drift"] = {{"model", maglev::to_string(d.model)},
                  {"sequence", d.sequence},
                  {"blocks", blocks},
                  {"reference_time_s", d.reference_time_s},
                  {"rate_A_per_s", d.rate_A_per_s.value},
                  {"rate_sigma_A_per_s", d.rate_A_per_s.sigma},
                  {"z", d.z},
                  {"p", d.p},
                  {"significant", d.significant},
                  {"sigma_inflation", d.sigma_inflation},
                  {"separable", d.separable},
                  {"alpha1_correction_arcsec", units::rad_to_arcsec(d.alpha1_correction_rad)},
                  {"residual_long_run_variance_A2", d.long_run_variance_A2},
                  {"residual_n_eff", d.n_eff}};
    if (d.curvature_A_per_s2) {
      j["drift"]["curvature_A_per_s2"] = d.curvature_A_per_s2->value;
      j["drift"]["curvature_sigma_A_per_s2"] = d.curvature_A_per_s2->sigma;
    }
    if (d.curvature_check_z) j["drift"]["curvature_check_z"] = *d.curvature_check_z;
  }
  json settling = json::array();
  for (const auto& c : r.settling) {
    json e = {{"position", c.position}, {"block_begin_s", c.block_begin_s}, {"cut_s", c.cut_s},
              {"samples_cut", c.samples_cut}, {"detected", c.detected}, {"limited", c.limited}};
    if (c.detected) {
      e["amplitude_A"] = c.amplitude_A;
      e["tau_s"] = c.tau_s;
      e["z"] = c.z;
    }
    settling.push_back(e);
  }
  j["settling"] = settling;
  if (r.median) j["median"] = solution(*r.median);
  if (r.huber) j["huber"] = solution(*r.huber);
  if (r.symmetry)
    j["symmetry"] = {{"z", r.symmetry->z}, {"p", r.symmetry->p}, {"passed", r.symmetry->passed}};
  if (r.chain) {
    const auto& c = *r.chain;
    j["azimuth"] = {
        {"gyro_deg", units::rad_to_deg(c.gyro_azimuth_rad.value)},
        {"gyro_sigma_arcsec", units::rad_to_arcsec(c.gyro_azimuth_rad.sigma)},
        {"astronomic_deg", units::rad_to_deg(c.astronomic_azimuth_rad.value)},
        {"astronomic_sigma_arcsec", units::rad_to_arcsec(c.astronomic_azimuth_rad.sigma)},
        {"geodetic_deg", units::rad_to_deg(c.geodetic_azimuth_rad.value)},
        {"geodetic_sigma_arcsec", units::rad_to_arcsec(c.geodetic_azimuth_rad.sigma)},
        {"grid_deg", units::rad_to_deg(c.grid_azimuth_rad.value)},
        {"grid_sigma_arcsec", units::rad_to_arcsec(c.grid_azimuth_rad.sigma)},
        {"notes", c.notes}};
  }
  if (r.options.process && r.options.denoise) {
    const auto& d = r.options.denoising;
    j["denoising"] = {{"wavelet", maglev::Wavelet(d.wavelet_order).name()},
                      {"level", d.level},
                      {"mode", maglev::to_string(d.mode)},
                      {"threshold", maglev::to_string(d.kind)},
                      {"rule", maglev::to_string(d.rule)}};
  }
  return j;
}

json maglev_calibration_to_json(const maglev::CalibrationResult& r) {
  auto line = [](const maglev::LineFit& f) {
    return json{{"slope_A", f.slope_A_per_rad.value}, {"slope_sigma_A", f.slope_A_per_rad.sigma},
                {"intercept_A", f.intercept_A.value}, {"intercept_sigma_A", f.intercept_A.sigma},
                {"sigma0", f.global_test.sigma0},     {"residuals_A", f.residuals_A}};
  };
  json cov = json::array();
  for (const auto& row : r.covariance) cov.push_back(row);
  json j = {{"kind", "maglev-calibration"},
          {"model", "I_k = k_k*sin(alpha - alpha*) + I*"},
          {"position1", line(r.position1)},
          {"position2", line(r.position2)},
          {"mean_line", line(r.mean_line)},
          {"trend_deviation_A", r.trend_deviation_A_per_rad.value},
          {"trend_deviation_sigma_A", r.trend_deviation_A_per_rad.sigma},
          {"trend_significant", r.trend_significant},
          {"best_azimuth_arcsec", units::rad_to_arcsec(r.best_azimuth_rad.value)},
          {"best_azimuth_sigma_arcsec", units::rad_to_arcsec(r.best_azimuth_rad.sigma)},
          {"constant_deviation_A", r.constant_deviation_A.value},
          {"constant_deviation_sigma_A", r.constant_deviation_A.sigma},
          {"scale_A_s_per_rad", r.scale_A_s_per_rad.value},
          {"scale_sigma_A_s_per_rad", r.scale_A_s_per_rad.sigma},
          {"mean_line_constant", r.mean_line_constant},
          {"instrument_constant_arcsec", units::rad_to_arcsec(r.best_azimuth_rad.value)},
          {"instrument_constant_sigma_arcsec", units::rad_to_arcsec(r.best_azimuth_rad.sigma)},
          {"fit",
           {{"sigma0", r.fit_test.sigma0},
            {"dof", r.fit_test.dof},
            {"vtpv", r.fit_test.vtpv},
            {"p_value", r.fit_test.p_value},
            {"rejected", r.fit_test.rejected},
            {"iterations", r.iterations},
            {"parameters", {"k1_A", "k2_A", "alpha_star_rad", "I_star_A"}},
            {"covariance", cov}}},
          {"linear_lines",
           {{"best_azimuth_arcsec", units::rad_to_arcsec(r.linear_best_azimuth_rad.value)},
            {"best_azimuth_sigma_arcsec", units::rad_to_arcsec(r.linear_best_azimuth_rad.sigma)},
            {"scale_A_s_per_rad", r.linear_scale_A_s_per_rad.value},
            {"scale_sigma_A_s_per_rad", r.linear_scale_A_s_per_rad.sigma}}},
          {"plausibility", {{"unit_slip_suspected", r.unit_slip_suspected}}},
          {"notes", r.notes},
          {"warnings", r.warnings}};
  if (r.scale_ratio_to_nominal)
    j["plausibility"]["scale_ratio_to_nominal"] = *r.scale_ratio_to_nominal;
  return j;
}

}  // namespace meridian::report
