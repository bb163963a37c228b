#pragma once
/// \file deflection_model.hpp
/// ξ and η at the stations of a campaign from a model of the Earth's gravity
/// field (gyro-theodolite spec §6, step 3), seen by gyro only through a function
/// of position: gyro does not load or evaluate gravity models itself. The
/// campaign file names the model (GravityModelRef); the caller loads it once
/// (io/gyro_jobs.hpp does so with the gravity module) and passes a
/// DeflectionModel to process().

#include <functional>
#include <string>

#include "meridian/geodesy/frames.hpp"
#include "meridian/gyro/defaults.hpp"

namespace meridian::gyro {

/// A gravity model as a campaign file names it (`gravity_model:`).
struct GravityModelRef {
  std::string source;     ///< name or path as written in the file (e.g. "egm2008", "models/x.gfc")
  /// Where to look it up: the path beside the campaign file when such a file
  /// exists, else `source` (a path or a model name found where GeographicLib
  /// keeps its models).
  std::string lookup;
  int max_degree = -1;    ///< truncate on load; −1: the model's full degree
  double sigma_eta_rad = kDefaultModelEtaSigma_rad;  ///< commission error assumed for η
  double sigma_xi_rad = kDefaultModelXiSigma_rad;    ///< commission error assumed for ξ
};

/// ξ and η from a loaded model: the deflection of the model's plumb line,
/// ξ = Φ − φ and η = (Λ − λ)·cos φ (astronomic minus geodetic; ξ > 0 when
/// the astronomic zenith lies north of the ellipsoid normal, η > 0 east of
/// it; geodesy/frames.hpp).
struct DeflectionModel {
  std::string description;    ///< for notes, e.g. "EGM2008 (degree 2190)"
  double sigma_eta_rad = kDefaultModelEtaSigma_rad;  ///< σ assumed for every η it gives
  double sigma_xi_rad = kDefaultModelXiSigma_rad;    ///< σ assumed for every ξ it gives
  /// ξ and η (radians) at geodetic latitude and longitude (radians) and
  /// ellipsoidal height (m). May throw meridian::Error for points it cannot
  /// evaluate.
  std::function<geodesy::Deflection(double lat_rad, double lon_rad, double height_m)> deflection;
};

}  // namespace meridian::gyro
