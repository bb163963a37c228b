#pragma once
// Private to report_gyro: the Vega-Lite plots of gyro observations and
// results, used by the HTML report mappings (gyro_html.cpp).

#include <string>
#include <vector>

#include "meridian/gyro/determination.hpp"
#include "meridian/report/format.hpp"
#include "meridian/report/html.hpp"

namespace meridian::report::gyro_plots {

/// Non-tracking observations (timed crossings, reversal readings) with the
/// model curve — the unified fit's when given, else the method's β, B and
/// T_B — and the method's β (else the fit's) as a dashed rule.
Plot oscillation_plot(const gyro::DeterminationInput& in, const gyro::UnifiedFitResult* unified,
                      const gyro::BetaResult* method);
/// Standardised residuals of the unified fit.
Plot fit_residual_plot(const gyro::UnifiedFitResult& f);
/// Every method's N_G relative to the reported one, with ±σ bars.
Plot methods_plot(const gyro::DeterminationResult& r);
/// Tracking reversal readings and the fitted model about M.
Plot tracking_plot(const gyro::DeterminationInput& in, const gyro::ReversalResult& fit, const AngleFormat& f);
/// Residuals of a tracking fit.
Plot tracking_residual_plot(const gyro::ReversalResult& fit);
/// Motor-off runs and their centres.
Plot zero_position_plot(const gyro::DeterminationInput& in, const gyro::ZeroPositionSummary& z);
/// Values with ±σ bars about their mean, and the mean's σ as a band.
Plot spread_plot(const std::string& title, const std::vector<std::string>& labels,
                 const std::vector<gyro::Uncertain>& values, double mean, double mean_sigma,
                 const std::string& x_title, const std::string& caption);

}  // namespace meridian::report::gyro_plots
