#pragma once
/// \file dov_columns.hpp
/// A deflection-of-the-vertical line as columns: the form the Python package exchanges (numpy
/// arrays, python/meridian/dov.py), named and in the units of the line CSV (dov_files.hpp):
/// degrees, arc-seconds, the two attitude matrices C_b^n (LGU/GNSS) and C_b^{n′} (INS/GNSS)
/// with rows E, N, U. The one mapping between dov::Sample, dov::Truth and these columns.

#include <vector>

#include "meridian/dov/deflection.hpp"

namespace meridian::io {

struct DovLineColumns {
  std::vector<double> time_s, lat_deg, lon_deg, height_m, speed_m_s;
  /// The matrices of sample k are elements 9k … 9k + 8, row by row: (i, j) at 9k + 3i + j.
  std::vector<double> lgu_body_to_nav, ins_body_to_nav;
  bool has_model = true;  ///< false: no model columns (a line file without them)
  std::vector<double> model_eta_arcsec, model_xi_arcsec;  ///< η_G, ξ_G (″)
  bool has_truth = false;                                 ///< the truth columns below
  std::vector<double> truth_eta_arcsec, truth_xi_arcsec;  ///< the true η, ξ (″)
};

/// The columns of `samples` and `truth` (empty, or one per sample: has_truth); the model
/// columns only when `model` (a line file without them has NaN model values).
DovLineColumns dov_line_columns(const std::vector<dov::Sample>& samples,
                                const std::vector<dov::Truth>& truth, bool model);

/// The Input of a line given as columns (with the model columns; default options, no origin).
/// InputError "the line's arrays must have one length" (field "line") when the scalar or truth
/// columns differ in length, "must have the shape (n, 3, 3)" (field "lgu_body_to_nav" or
/// "ins_body_to_nav") for matrices of another count. Values are not checked here:
/// dov::process names a bad one "samples[k].<member>" (dov_jobs.hpp, run_dov_columns, gives
/// the column and element).
dov::Input dov_input(const DovLineColumns& line);

}  // namespace meridian::io
