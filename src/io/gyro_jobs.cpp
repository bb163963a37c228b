#include "meridian/io/gyro_jobs.hpp"

#include <utility>

#include <fmt/format.h>

#include "meridian/core/error.hpp"
#include "meridian/io/document.hpp"
#include "meridian/io/source_map.hpp"
#include "meridian/gravity/gravity_field.hpp"
#include "gravity_model_ref.hpp"

namespace meridian::io {
namespace {

// A field book's fields: the lines its reader recorded.
SourceMap book(const std::string& file, const FieldLines& lines) {
  SourceMap m;
  m.add_document(file, lines);
  return m;
}

}  // namespace

const gyro::DeflectionModel& DeflectionModels::get(const gyro::GravityModelRef& ref) {
  const auto key = std::make_pair(ref.lookup, ref.max_degree);
  if (const auto it = loaded_.find(key); it != loaded_.end()) return *it->second;
  gravity::GravityModelData data = detail::load_named_model(ref.lookup, ref.max_degree);
  auto field = std::make_shared<const gravity::GravityField>(std::move(data));  // takes the coefficients
  auto model = std::make_shared<gyro::DeflectionModel>();
  model->description = fmt::format("{} (degree {})", data.name.empty() ? ref.source : data.name,
                                   field->max_degree());
  model->sigma_eta_rad = ref.sigma_eta_rad;
  model->sigma_xi_rad = ref.sigma_xi_rad;
  model->deflection = [field](double lat_rad, double lon_rad, double height_m) {
    const gravity::FieldValues v =
        field->evaluate(gravity::GeodeticPoint{lat_rad, lon_rad, height_m}, gravity::Quantities::Deflection);
    return geodesy::Deflection{v.xi_astro_rad, v.eta_astro_rad};
  };
  return *loaded_.emplace(key, std::move(model)).first->second;
}

ReduceJob run_reduce_file(const std::filesystem::path& path, Progress* progress) {
  ReduceJob job{read_gyro_reduce_file(path), {}};
  job.result = located(book(job.file.file, job.file.lines), [&] { return gyro::process(job.file.input, progress); });
  return job;
}

CampaignJob run_campaign_file(const std::filesystem::path& path, DeflectionModels* models, Progress* progress) {
  CampaignJob job{read_campaign_file(path), {}};
  const CampaignFile& f = job.file;
  job.result = located(book(f.file, f.lines), [&] {
    DeflectionModels own;
    const gyro::DeflectionModel* deflection = nullptr;
    if (f.campaign.gravity_model) deflection = &(models ? *models : own).get(*f.campaign.gravity_model);
    return gyro::process(f.campaign, progress, deflection);
  });
  return job;
}

ErrorContext check_place(const CampaignJob& job, const gyro::Check& check) {
  if (!check.field.empty())
    if (auto where = book(job.file.file, job.file.lines).place(check.field)) return *where;
  return {job.file.file, std::nullopt, check.field};
}

OrientationsJob run_orientation_files(const std::vector<std::filesystem::path>& paths, Progress* progress) {
  OrientationsJob job;
  DeflectionModels models;
  std::vector<gyro::CampaignResult> results;
  for (const auto& p : paths) {
    job.orientations.push_back(run_campaign_file(p, &models, progress));
    results.push_back(job.orientations.back().result);
  }
  // "orientations[i]" is the file of orientation i.
  SourceMap files;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const std::string field = "orientations[" + std::to_string(i) + "]";
    files.add_place(field, {paths[i].string(), std::nullopt, field});
  }
  job.result = located(files, [&] { return gyro::combine_orientations(results); });
  return job;
}

gyro::TransitFactorCalibration run_transit_factor_file(const std::filesystem::path& path) {
  const GyroReduceFile f = read_gyro_reduce_file(path);
  return located(book(f.file, f.lines), [&] { return gyro::calibrate_transit_factor(f.input); });
}

gyro::StochasticBookResult run_stochastic_file(const std::filesystem::path& path, Progress* progress) {
  // A campaign file (top-level `campaign:`) holds its determinations in known_line.before,
  // known_line.after and line.determinations; a reduce file in determinations.
  if (Node::load_file(path).has("campaign")) {
    const CampaignFile f = read_campaign_file(path);
    gyro::StochasticBookInput in = gyro::stochastic_book(f.campaign);
    in.file = f.file;
    return located(book(f.file, f.lines), [&] { return gyro::process(in, progress); });
  }
  const GyroReduceFile f = read_gyro_reduce_file(path);
  gyro::StochasticBookInput in = gyro::stochastic_book(f.input);
  in.file = f.file;
  return located(book(f.file, f.lines), [&] { return gyro::process(in, progress); });
}

}  // namespace meridian::io
