#pragma once
/// \file gravity_egm.hpp
/// GeographicLib's gravity model format: `NAME.egm` (text metadata, first
/// line `EGMF-1`) and `NAME.egm.cof` (binary: 8-byte ID, then int32 N, M and
/// little-endian doubles C̄ (m = 0..M, n = m..N) and S̄ (m = 1..M, n = m..N),
/// then the same for the correction set, N = M = −1 when absent). In the
/// file C̄00 is 0: GeographicLib adds the GM/r term itself. The reader gives
/// plain data (gravity::GravityModelData); the engine is built from it by the
/// caller (gravity::GravityField).
///
/// Loading is performance-tuned (docs/benchmarks.md, "Model loading"): an untruncated set is
/// read in 256 KB chunks straight into arrays that are neither zero-filled nor faulted in page
/// by page, and each chunk's range check is a vectorised scan while it is in cache.

#include <filesystem>

#include "meridian/gravity/gravity_model.hpp"

namespace meridian::io {

/// Read `path` (the `.egm` file; `.egm.cof` beside it). Errors (ParseError /
/// IoError naming the file and line or byte offset): missing signature or
/// keys, ID mismatch, bad N/M, truncated or over-long `.cof`, non-zero C̄00,
/// non-finite coefficients, |C̄|, |S̄| > 1 in the gravitational set or beyond
/// 1000 m in the correction set, Schmidt normalisation, big-endian data, a
/// Name or Description that is not UTF-8; ModelMass, ReferenceMass, ModelRadius,
/// ReferenceRadius, Flattening outside Meridian's terrestrial ranges (docs/reliability.md);
/// a key given twice; a line over 1 MiB.
gravity::GravityModelData read_egm_file(const std::filesystem::path& path, const gravity::Truncation& truncation = {});

/// Write `prefix.egm` and `prefix.egm.cof` atomically so GeographicLib's
/// GravityModel(name = prefix's file name, path = its directory) reads the
/// same model. Throws InputError when C̄00 ≠ 1 (not representable), IoError
/// when a file cannot be written.
void write_egm_files(const gravity::GravityModelData& model, const std::filesystem::path& prefix);

}  // namespace meridian::io
