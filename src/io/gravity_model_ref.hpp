#pragma once
// Private to the io targets (not installed): how a file names a gravity model
// (`gravity_model: {model: …, max_degree: …}`) and how it is loaded, shared by the gyro campaign
// and the deflection-of-the-vertical runners so both resolve and report it alike. The model is
// loaded through io_gravity (io/gravity_model_lookup.hpp), as by every other caller.

#include <filesystem>
#include <optional>
#include <string>

#include "meridian/core/error.hpp"
#include "meridian/io/gravity_model_lookup.hpp"

namespace meridian::io::detail {

/// Where to look `source` up: the file beside `document` (the campaign or configuration) when
/// such a file exists, else `source` as written (a path, or a model name found where
/// GeographicLib keeps its models).
inline std::string model_lookup_path(const std::filesystem::path& document, const std::string& source) {
  const std::filesystem::path beside = document.parent_path() / source;
  return std::filesystem::exists(beside) ? beside.string() : source;
}

/// io::load_model(lookup) truncated to max_degree (−1: full). An error that names no file (the
/// model was not found) becomes one of the field "gravity_model.model", class kept, for the
/// caller to locate in its document; a bad model file names itself and passes unchanged.
inline gravity::GravityModelData load_named_model(const std::string& lookup, int max_degree) {
  try {
    return load_model(lookup, gravity::Truncation{max_degree, -1});
  } catch (Error& e) {
    if (!e.context().file.empty()) throw;
    e.relocate({"", std::nullopt, "gravity_model.model"});
    throw;
  }
}

}  // namespace meridian::io::detail
