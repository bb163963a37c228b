#pragma once
/// \file gravity_model_lookup.hpp
/// Find and read a gravity model given a path or a name: the one way every front end and
/// runner loads a model (the CLI, Python, the gyro campaign and deflection-of-the-vertical
/// runners). Gives plain data (gravity::GravityModelData); the engine is built from it by the
/// caller (gravity::GravityField, or io::load_gravity_field in gravity_jobs.hpp).

#include <filesystem>
#include <string>
#include <vector>

#include "meridian/gravity/gravity_model.hpp"

namespace meridian::io {

/// Directories searched for a model given by name, in order:
/// $GEOGRAPHICLIB_GRAVITY_PATH, else $GEOGRAPHICLIB_DATA/gravity, then the
/// installed defaults /usr/share/GeographicLib/gravity (Debian) and
/// /usr/local/share/GeographicLib/gravity (GeographicLib's default).
std::vector<std::filesystem::path> gravity_search_path();

/// Resolve `name_or_path`: an existing file (`.gfc`, `.egm`; `X.egm.cof`
/// maps to `X.egm`), or a name such as `egm2008` looked up as `NAME.egm` /
/// `NAME.gfc` (case-insensitive name match) in gravity_search_path().
/// Throws InputError (field "--model", no file) listing the directories searched when
/// nothing is found, or when `name_or_path` is empty.
std::filesystem::path resolve_model(const std::string& name_or_path);

/// resolve_model, then read by extension: .gfc → read_icgem_file (gravity_icgem.hpp), .egm →
/// read_egm_file (gravity_egm.hpp), truncated on load. Errors: resolve_model's, the readers',
/// InputError naming the file for another extension.
gravity::GravityModelData load_model(const std::string& name_or_path, const gravity::Truncation& truncation = {});

}  // namespace meridian::io
