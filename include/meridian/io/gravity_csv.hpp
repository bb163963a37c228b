#pragma once
/// \file gravity_csv.hpp
/// The CSV output of `meridian gravity points`: one header line, then one
/// row per point:
///
///     lat_deg,lon_deg,h_m,xi_arcsec,eta_arcsec,geoid_m
///     37.8400000000,112.5600000000,850.0000,-2.011822970,-0.158325893,20.699554278
///
/// latitude and longitude in decimal degrees with 10 decimals (as given,
/// longitude not wrapped), h in metres with 4, ξ and η (GravityField's
/// xi_rad, eta_rad: astronomic minus geodetic, docs/gravity-field.md) in
/// arc-seconds with 9, the geoid height N in metres with 9.

#include <span>
#include <string>
#include <string_view>

#include "meridian/gravity/gravity_field.hpp"

namespace meridian::io {

/// The header line, newline included.
std::string_view gravity_points_csv_header() noexcept;

/// Append one row per point (`values[i]` belongs to `points[i]`) to `out`.
/// Throws InputError when the sizes differ.
void append_gravity_points_csv(std::string& out, std::span<const gravity::GeodeticPoint> points,
                               std::span<const gravity::FieldValues> values);

}  // namespace meridian::io
