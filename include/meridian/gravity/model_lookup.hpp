#pragma once
/// \file model_lookup.hpp
/// Find and load a gravity model given a path or a name.

#include <filesystem>
#include <string>
#include <vector>

#include "meridian/gravity/gravity_model.hpp"

namespace meridian::gravity {

/// Directories searched for a model given by name, in order:
/// $GEOGRAPHICLIB_GRAVITY_PATH, else $GEOGRAPHICLIB_DATA/gravity, then the
/// installed defaults /usr/share/GeographicLib/gravity (Debian) and
/// /usr/local/share/GeographicLib/gravity (GeographicLib's default).
std::vector<std::filesystem::path> gravity_search_path();

/// Resolve `name_or_path`: an existing file (`.gfc`, `.egm`; `X.egm.cof`
/// maps to `X.egm`), or a name such as `egm2008` looked up as `NAME.egm` /
/// `NAME.gfc` (case-insensitive name match) in gravity_search_path().
/// Throws InputError listing the directories searched when nothing is found.
std::filesystem::path resolve_model(const std::string& name_or_path);

/// resolve_model, then read by extension (.gfc → ICGEM, .egm → GeographicLib).
GravityModelData load_model(const std::string& name_or_path, const Truncation& truncation = {});

}  // namespace meridian::gravity
