#pragma once
/// \file egm_format.hpp
/// GeographicLib's gravity model format: `NAME.egm` (text metadata, first
/// line `EGMF-1`) and `NAME.egm.cof` (binary: 8-byte ID, then int32 N, M and
/// little-endian doubles C̄ (m = 0..M, n = m..N) and S̄ (m = 1..M, n = m..N),
/// then the same for the correction set, N = M = −1 when absent). In the
/// file C̄00 is 0: GeographicLib adds the GM/r term itself.

#include <filesystem>

#include "meridian/gravity/gravity_model.hpp"

namespace meridian::gravity {

/// Read `path` (the `.egm` file; `.egm.cof` beside it). Errors (ParseError /
/// IoError naming the file and line or byte offset): missing signature or
/// keys, ID mismatch, bad N/M, truncated or over-long `.cof`, non-zero C̄00,
/// non-finite coefficients, Schmidt normalisation, big-endian data.
GravityModelData read_egm_file(const std::filesystem::path& path, const Truncation& truncation = {});

/// Write `prefix.egm` and `prefix.egm.cof` atomically so GeographicLib's
/// GravityModel(name = prefix's file name, path = its directory) reads the
/// same model. Throws InputError when C̄00 ≠ 1 (not representable).
void write_egm_files(const GravityModelData& model, const std::filesystem::path& prefix);

}  // namespace meridian::gravity
