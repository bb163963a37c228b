#pragma once
/// \file gyro_jobs.hpp
/// Running a gyro file from disk to result: read it, load the engines it
/// names (a gravity model for ξ, η), process it, and give every error the file
/// and line of the field it concerns. Shared by `meridian gyro reduce`,
/// `gyro campaign`, `gyro orientations`, `gyro transit-factor`, `gyro stochastic`,
/// `demo` and the Python package, and by any program that processes field books.
/// A gravity model is loaded only when a campaign names one.

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "meridian/core/progress.hpp"
#include "meridian/gyro/campaign.hpp"
#include "meridian/gyro/orientations.hpp"
#include "meridian/gyro/reduce.hpp"
#include "meridian/gyro/stochastic_book.hpp"
#include "meridian/gyro/transit_calibration.hpp"
#include "meridian/io/gyro_files.hpp"

namespace meridian::io {

/// Gravity models named by campaign files, each loaded once (by its lookup
/// path and truncation) and shared between the files that name it: loading
/// a degree-2190 model takes a noticeable fraction of a second and 77 MB.
class DeflectionModels {
 public:
  /// The loaded model for `ref` (loaded now if new). ξ and η are the
  /// components of the model's plumb line (gravity::FieldValues::xi_astro_rad,
  /// eta_astro_rad).
  /// Throws the gravity module's InputError/ParseError/IoError when the model
  /// cannot be found or read (field "gravity_model.model" when the error
  /// names no file of its own).
  const gyro::DeflectionModel& get(const gyro::GravityModelRef& ref);

 private:
  std::map<std::pair<std::string, int>, std::shared_ptr<const gyro::DeflectionModel>> loaded_;
};

/// A reduce file and its result.
struct ReduceJob {
  GyroReduceFile file;
  gyro::ReduceResult result;
};

/// Read and reduce a `gyro reduce` file.
ReduceJob run_reduce_file(const std::filesystem::path& path, Progress* progress = nullptr);

/// A campaign file and its result.
struct CampaignJob {
  CampaignFile file;
  gyro::CampaignResult result;
};

/// Read a campaign file, load its gravity model (through `models` when
/// given, so several files share one load) and process it.
CampaignJob run_campaign_file(const std::filesystem::path& path, DeflectionModels* models = nullptr,
                              Progress* progress = nullptr);

/// Where in the campaign file a check's field (gyro::Check::field) was booked: the file,
/// the line of its innermost key and the key path; the file alone for a check of the
/// whole job.
ErrorContext check_place(const CampaignJob& job, const gyro::Check& check);

/// Independent orientations of one line, one campaign file each.
struct OrientationsJob {
  std::vector<CampaignJob> orientations;
  gyro::OrientationsResult result;
};

/// Run each campaign file (sharing the gravity models they name) and combine
/// their grid azimuths (gyro::combine_orientations; its errors name the file).
OrientationsJob run_orientation_files(const std::vector<std::filesystem::path>& paths, Progress* progress = nullptr);

/// Read a reduce file with two determinations and calibrate the transit factor.
gyro::TransitFactorCalibration run_transit_factor_file(const std::filesystem::path& path);

/// `meridian gyro stochastic FILE`: read a reduce book, or a campaign file (recognised by its
/// top-level `campaign:`), split it into its reversal-point series (gyro::stochastic_book) and
/// analyse every series of at least 6 readings (gyro::process). Throws the reader's
/// ParseError/InputError (file, line, field) and the analysis' InputError/NumericalError at the
/// file and line of the series' field ("determinations[2].reversals"), or of the field
/// "determinations" ("line.determinations"; the line of its first element) when no series is
/// long enough. No gravity model is loaded.
gyro::StochasticBookResult run_stochastic_file(const std::filesystem::path& path, Progress* progress = nullptr);

}  // namespace meridian::io
