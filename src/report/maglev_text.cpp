#include "meridian/report/maglev_text.hpp"

#include <cmath>

#include <fmt/format.h>

#include "meridian/core/angle.hpp"
#include "meridian/core/dms.hpp"
#include "meridian/core/units.hpp"

namespace meridian::report {
namespace {

std::string solution_line(const char* name, const maglev::TwoPositionSolution& s) {
  return fmt::format("  {:<22} α1 = {:>14} ± {:.3f}\"   N_G = {} ± {:.3f}\"   b = {:.9g} A\n", name,
                     format_dms(Angle::radians(s.alpha1_rad.value), {3, true, true}),
                     units::rad_to_arcsec(s.alpha1_rad.sigma),
                     format_direction_dms(Angle::radians(s.north_rad.value), {3, true, false}),
                     units::rad_to_arcsec(s.north_rad.sigma), s.bias_A.value);
}

std::string position_block(const char* name, const maglev::PositionResult& p) {
  std::string out = fmt::format("{}: {} samples, {} kept\n", name, p.samples, p.kept_samples);
  out += fmt::format("  mean all samples     {:.10g} A ± {:.3g} A (n_eff {:.0f})\n", p.raw.mean,
                     p.raw.sigma, p.raw.n_eff);
  out += fmt::format("  mean cleaned, kept   {:.10g} A ± {:.3g} A (n_eff {:.0f})\n",
                     p.cleaned_mean_A.value, p.cleaned_mean_A.sigma, p.kept.n_eff);
  out += fmt::format("  median / Huber, kept {:.10g} A / {}\n", p.median_A,
                     p.huber_failed.empty() ? fmt::format("{:.10g} A", p.huber_A.value) : "failed: " + p.huber_failed);
  out += fmt::format("  variance raw {:.3e} A², cleaned kept {:.3e} A²\n", p.variance_raw_A2,
                     p.variance_cleaned_A2);
  if (p.stationarity) {
    const auto& st = *p.stationarity;
    out += fmt::format("  segments of {} samples, each test at α = {:.4g}: {} kept, {} rejected\n",
                       st.segment_length, st.segment_alpha,
                       st.segments.size() - st.rejected().size(), st.rejected().size());
    for (std::size_t i = 0; i < st.segments.size(); ++i) {
      const auto& s = st.segments[i];
      if (s.kept) continue;
      out += fmt::format(
          "    rejected segment {:>3}: samples {}…{}  mean {:.9g} A  z = {:.2f}{}  Q = {:.1f}{}\n",
          i, s.begin, s.end - 1, s.mean, s.z_mean, s.mean_passed ? "" : " (fails)",
          s.q_autocovariance, s.autocovariance_passed ? "" : " (fails)");
    }
  }
  return out;
}
std::string drift_block(const maglev::DriftResult& d) {
  std::string out = fmt::format(
      "drift ({}, common clock, blocks {}): rate {:+.4e} ± {:.3e} A/s at t = {:.3f} s (z = {:.2f}, "
      "{})\n",
      maglev::to_string(d.model), d.sequence, d.rate_A_per_s.value, d.rate_A_per_s.sigma,
      d.reference_time_s, d.z, d.significant ? "significant" : "not significant");
  if (d.curvature_A_per_s2)
    out += fmt::format("  curvature {:+.4e} ± {:.3e} A/s²\n", d.curvature_A_per_s2->value,
                       d.curvature_A_per_s2->sigma);
  out += fmt::format(
      "  α1 corrected by {:+.3f}\"; σ(α1) ×{:.2f} for the drift's uncertainty ({}); residual "
      "σ_LR {:.3e} A, n_eff {:.0f}\n",
      units::rad_to_arcsec(d.alpha1_correction_rad), d.sigma_inflation,
      d.separable ? "separable" : "CANNOT BE WELL SEPARATED", std::sqrt(d.long_run_variance_A2),
      d.n_eff);
  for (const auto& b : d.blocks)
    out += fmt::format("  block: position {}  {:.3f} … {:.3f} s  ({} samples)\n", b.position,
                       b.begin_s, b.end_s, b.end - b.begin);
  return out;
}
}  // namespace

std::string maglev_reduce_text(const maglev::ReduceResult& r) {
  std::string out = "Maglev gyro two-position determination\n";
  out += fmt::format("directive amplitude A = K·ω·cos φ = {:.9g} A\n\n", r.amplitude_A.value);
  out += position_block("position 1", r.position1);
  out += position_block("position 2", r.position2);
  if (r.drift) out += drift_block(*r.drift);
  out += "\nresults (α1 east of north; N_G = r1 − α1)\n";
  out += solution_line("processed", r.processed);
  out += solution_line("plain means", r.plain);
  if (r.median) out += solution_line("medians", *r.median);
  if (r.huber) out += solution_line("Huber means", *r.huber);
  out += fmt::format("  processed − plain: {:+.3f}\"\n",
                     units::rad_to_arcsec(r.processed.alpha1_rad.value - r.plain.alpha1_rad.value));
  if (r.symmetry)
    out += fmt::format("symmetry about the prior bias: z = {:.2f}, p = {:.3f} ({})\n",
                       r.symmetry->z, r.symmetry->p, r.symmetry->passed ? "passed" : "FAILED");
  if (r.chain) {
    const auto& c = *r.chain;
    out += fmt::format(
        "gyro azimuth A_G {} ± {:.2f}\"\nastronomic A     {} ± {:.2f}\"\ngeodetic α       {} ± "
        "{:.2f}\"\ngrid T           {} ± {:.2f}\"\n",
        format_direction_dms(Angle::radians(c.gyro_azimuth_rad.value)),
        units::rad_to_arcsec(c.gyro_azimuth_rad.sigma),
        format_direction_dms(Angle::radians(c.astronomic_azimuth_rad.value)),
        units::rad_to_arcsec(c.astronomic_azimuth_rad.sigma),
        format_direction_dms(Angle::radians(c.geodetic_azimuth_rad.value)),
        units::rad_to_arcsec(c.geodetic_azimuth_rad.sigma),
        format_direction_dms(Angle::radians(c.grid_azimuth_rad.value)),
        units::rad_to_arcsec(c.grid_azimuth_rad.sigma));
    for (const auto& n : c.notes) out += "note: " + n + "\n";
  }
  for (const auto& n : r.notes) out += "note: " + n + "\n";
  for (const auto& w : r.warnings) out += "WARNING: " + w + "\n";
  return out;
}

std::string maglev_calibration_text(const maglev::CalibrationResult& r) {
  std::string out =
      "Maglev gyro multi-angle calibration (I = k·sin(α − α*) + I*, k in A/rad, joint fit)\n";
  auto line = [&](const char* name, const maglev::LineFit& f) {
    out += fmt::format("  {:<10} k = {:.9g} ± {:.3g} A/rad   c = {:.9g} ± {:.3g} A   σ̂0 = {:.2f}\n",
                       name, f.slope_A_per_rad.value, f.slope_A_per_rad.sigma, f.intercept_A.value,
                       f.intercept_A.sigma, f.global_test.sigma0);
  };
  line("position 1", r.position1);
  line("position 2", r.position2);
  line("mean line", r.mean_line);
  out += fmt::format(
      "model check: σ̂0 = {:.2f} (dof {}, p = {:.3g}, {}); σ below scaled by σ̂0; {} iterations\n",
      r.fit_test.sigma0, r.fit_test.dof, r.fit_test.p_value,
      r.fit_test.rejected ? "REJECTED" : "passed", r.iterations);
  out += fmt::format("trend deviation k1 + k2 = {:.6g} ± {:.3g} A/rad (z = {:.2f}, {})\n",
                     r.trend_deviation_A_per_rad.value, r.trend_deviation_A_per_rad.sigma,
                     r.trend_z, r.trend_significant ? "significant" : "not significant");
  out += fmt::format("instrument constant α* = {} ± {:.3f}\" (best set-up azimuth)\n",
                     format_dms(Angle::radians(r.best_azimuth_rad.value), {3, true, true}),
                     units::rad_to_arcsec(r.best_azimuth_rad.sigma));
  out += fmt::format("constant deviation  I* = {:.6e} ± {:.3g} A\n", r.constant_deviation_A.value,
                     r.constant_deviation_A.sigma);
  out += fmt::format("scale from slopes   K  = {:.6f} ± {:.4f} A·s/rad\n",
                     r.scale_A_s_per_rad.value, r.scale_A_s_per_rad.sigma);
  out += fmt::format("straight lines k·sin α + c (for comparison): α* = {:.3f}\", K = {:.6f}\n",
                     units::rad_to_arcsec(r.linear_best_azimuth_rad.value),
                     r.linear_scale_A_s_per_rad.value);
  out += fmt::format("mean line slope z = {:.2f}: the constant deviation is {}\n", r.mean_slope_z,
                     r.mean_line_constant ? "constant" : "NOT constant (calibration defect)");
  out += "residuals (fit − observed, A):\n";
  for (std::size_t i = 0; i < r.position1.residuals_A.size(); ++i)
    out += fmt::format("  set-up {:>2}: {:+.3e}  {:+.3e}\n", i + 1, r.position1.residuals_A[i],
                       r.position2.residuals_A[i]);
  for (const auto& n : r.notes) out += "note: " + n + "\n";
  for (const auto& w : r.warnings) out += "WARNING: " + w + "\n";
  return out;
}

std::string maglev_denoise_text(const maglev::DenoiseResult& r) {
  const maglev::DenoiseOptions& o = r.options;
  std::string thresholds;
  for (double l : r.thresholds) thresholds += fmt::format(" {:.6g}", l);
  return fmt::format(
      "meridian maglev denoise: {} levels {}, mode {}, {} {} threshold\nnoise sigma {:.6g} A; "
      "thresholds (level 1 first):{}",
      maglev::Wavelet(o.wavelet_order).name(), o.level, maglev::to_string(o.mode),
      maglev::to_string(o.rule), maglev::to_string(o.kind), r.noise_sigma, thresholds);
}

}  // namespace meridian::report
