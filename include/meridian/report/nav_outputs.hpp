#pragma once
/// \file nav_outputs.hpp
/// Outputs of the marine navigation workflow (nav/navigation.hpp; shared/spec/navigation.md §7;
/// docs/file-formats.md "Navigation outputs"): a text summary, the JSON summary, the track of
/// one method as CSV, the tracks of several methods as GeoJSON and the rejected observations as
/// CSV. Plane coordinates x = north, y = east (m); velocities and biases in m/s; times in the
/// job's seconds. Keys and columns carry their unit. No output holds a NaN: JSON writes null,
/// CSV an empty field.
///
/// JSON keys: epochs, lops_used, fixes_used, method_order (the names in the result's order),
/// methods {name: {epochs, rms_m, max_error_m, mean_nees, error_epochs, per_minute_rms_m,
/// estimates_bias, bias_north_m_s, bias_east_m_s, sigma_bias_north_m_s, sigma_bias_east_m_s,
/// final_position {time_s, x_north_m, y_east_m, sigma_x_m, sigma_y_m, cov_xy_m2}, parameters
/// [{chain, name, value, sigma}], rejected_lops, flagged_fixes}}, rejected [{kind, index,
/// method, time_s, misclosure_m, statistic, reason}], skipped [{kind, index, time_s, reason}],
/// notes, warnings. Without truth rms_m, max_error_m, mean_nees and error_epochs are null and
/// per_minute_rms_m is []; a bin without truth is null. The bias and its σ are those of the
/// method's last epoch; a σ the method does not give (methods I and II, and the methods without
/// a bias) is null.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "meridian/nav/navigation.hpp"

namespace meridian::report {

/// Plain aligned text for a hydrographer: the line (epochs, time span, observations used,
/// rejected, skipped), one row per method (RMS and max error, mean NEES with truth; final bias
/// with σ; rejections), the chain parameters with σ, the per-minute RMS table with truth, notes
/// and warnings.
std::string nav_summary_text(const nav::Result& result);

/// The JSON summary (keys in the file comment).
nlohmann::json nav_to_json(const nav::Result& result);

/// The track of `method` as named columns, the one mapping of a track to columns (the track CSV
/// and the Python package's arrays): `names` time_s, x_m, y_m[, lat_deg, lon_deg], sigma_x_m,
/// sigma_y_m, cov_xy_m2, bias_north_m_s, bias_east_m_s, sigma_bias_north_m_s,
/// sigma_bias_east_m_s with `values[i]` the column of names[i], one value per epoch; `flags` the
/// sum of the nav::TrackFlag bits per epoch. x_m is north, y_m east (m); lat_deg, lon_deg (WGS 84
/// degrees of the result's projection, longitude in [−180°, 180°]) only when the result has a
/// projection. A σ of the bias the method does not state (not finite or 0: methods I and II, and
/// the methods without a bias) is NaN when `unstated_sigma_as_nan` (as the JSON's null), else as
/// held (0). Throws InputError naming `method` when the result does not hold it, or when the
/// projection gives a non-finite position.
struct NavTrackColumns {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;
  std::vector<unsigned> flags;
};
NavTrackColumns nav_track_columns(const nav::Result& result, nav::Method method, bool unstated_sigma_as_nan);

/// The track of `method`: `# ` comment lines (the method; the flag bits), a header, one row per
/// epoch: the columns of nav_track_columns (σ as held), then flags. Numbers in the shortest form
/// that reads back to the same double (round trip), an empty field when not finite. Errors as
/// nav_track_columns.
std::string nav_track_csv(const nav::Result& result, nav::Method method);

/// RFC 7946 GeoJSON: a FeatureCollection with one Feature per method of `methods` (empty: every
/// method of the result), geometry a LineString of [longitude, latitude] in degrees rounded to
/// 1e-9° (a MultiLineString cut at ±180° when the track crosses the antimeridian, a Point for a
/// one-epoch track), properties {feature: "track", method, epochs, start_time_s, end_time_s,
/// rms_m (with truth)}; then one Point per rejected observation of a listed method, at that
/// method's position at the epoch nearest its time, properties {feature: "rejected", kind,
/// index, method, time_s, misclosure_m, statistic, reason}. Latitudes and longitudes from the
/// result's projection. Throws InputError when the result has no projection (GeoJSON needs
/// geographic coordinates: the job needs a projection), when a method is not in the result, or
/// when the projection gives a position that is not geographic.
std::string nav_track_geojson(const nav::Result& result, const std::vector<nav::Method>& methods);

/// RFC 4180 CSV of Result::rejected: header kind,index,method,time_s,misclosure_m,statistic,reason;
/// kind "lop" or "fix", index into the input's LOPs or fixes (0-based), the reason always in
/// double quotes (a quote doubled); LF line ends, one line per row (a line break inside a reason
/// is written as a space). Numbers as in the track CSV. Skipped observations are in the JSON
/// and the text.
std::string nav_rejected_csv(const nav::Result& result);

}  // namespace meridian::report
