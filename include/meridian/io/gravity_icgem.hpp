#pragma once
/// \file gravity_icgem.hpp
/// ICGEM `.gfc` gravity-field files (http://icgem.gfz-potsdam.de, format
/// description "ICGEM-Format-2011"): header keys up to `end_of_head`, then
/// `gfc n m C S [sigmaC sigmaS]` lines. Fortran `D` exponents are accepted.
/// The reader gives plain data (gravity::GravityModelData); the engine is built
/// from it by the caller (gravity::GravityField).

#include <filesystem>
#include <string>

#include "meridian/gravity/gravity_model.hpp"

namespace meridian::io {

/// Read an ICGEM file. Requirements (else ParseError/InputError naming the
/// file and line): `product_type gravity_field` (if present),
/// `earth_gravity_constant`, `radius`, `max_degree`, `norm` absent or
/// `fully_normalized`; only static `gfc` lines (time-variable `gfct`, `trnd`,
/// `acos`, `asin` are rejected); 0 ≤ m ≤ n ≤ max_degree; no duplicate
/// (n, m); every (n, m) with 2 ≤ n ≤ kept degree present (degrees 0 and 1
/// may be omitted: C̄00 = 1, degree 1 = 0); |C̄|, |S̄| ≤ 1; `modelname` and
/// `tide_system` UTF-8 text; GM and radius within Meridian's terrestrial ranges
/// (3.5e14…4.5e14 m³/s², 6.0e6…6.6e6 m; docs/reliability.md); no header key it reads
/// given twice; no line over 1 MiB. Lines beyond the truncation are checked for
/// syntax but not stored. The header's max_degree is checked against the
/// file's size before anything is allocated. The reference field is WGS84.
/// IoError when the file cannot be opened or read.
gravity::GravityModelData read_icgem_file(const std::filesystem::path& path, const gravity::Truncation& truncation = {});

/// The model as ICGEM text (17 significant digits, so reading it back gives
/// bit-identical coefficients).
std::string format_icgem(const gravity::GravityModelData& model);

}  // namespace meridian::io
