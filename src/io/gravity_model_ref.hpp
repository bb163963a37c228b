#pragma once
// Private to the io targets (not installed): how a file names a gravity model
// (`gravity_model: {model: …, max_degree: …}`) and how it is loaded, shared by the gyro campaign
// and the deflection-of-the-vertical runners so both resolve and report it alike.

#include <filesystem>
#include <optional>
#include <string>

#include "meridian/core/error.hpp"
#include "meridian/gravity/model_lookup.hpp"

namespace meridian::io::detail {

/// Where to look `source` up: the file beside `document` (the campaign or configuration) when
/// such a file exists, else `source` as written (a path, or a model name found where
/// GeographicLib keeps its models).
inline std::string model_lookup_path(const std::filesystem::path& document, const std::string& source) {
  const std::filesystem::path beside = document.parent_path() / source;
  return std::filesystem::exists(beside) ? beside.string() : source;
}

/// gravity::load_model(lookup) truncated to max_degree (−1: full). An error that names no file
/// (the model was not found) becomes an InputError of the field "gravity_model.model", for the
/// caller to locate in its document; a bad model file names itself and passes unchanged.
inline gravity::GravityModelData load_named_model(const std::string& lookup, int max_degree) {
  try {
    return gravity::load_model(lookup, gravity::Truncation{max_degree, -1});
  } catch (const Error& e) {
    if (!e.context().file.empty()) throw;
    throw InputError(e.message(), {"", std::nullopt, "gravity_model.model"});
  }
}

}  // namespace meridian::io::detail
