#pragma once
/// \file grid_spec.hpp
/// A regular geographic grid for gravity-field synthesis (issue 14): the
/// region W/E/S/N and the spacing in degrees, the registration (GMT's
/// gridline or pixel `-r` convention), one constant ellipsoidal height and
/// the quantities to compute. Validation and node coordinates; parsing of
/// GMT-style region and spacing strings for the command line.
///
/// Nodes: columns i = 0 … columns−1 from west to east, rows j = 0 … rows−1
/// from south to north (the order of NetCDF/GMT grids: y increasing).
/// * Gridline registration (GMT default): lon_i = W + i·Δλ, lat_j = S + j·Δφ,
///   the nodes on the region's edges (columns = (E − W)/Δλ + 1).
/// * Pixel (cell) registration (GMT `-r`): nodes at the centres of the cells,
///   lon_i = W + (i + ½)·Δλ, lat_j = S + (j + ½)·Δφ (columns = (E − W)/Δλ).
/// The last gridline node is set to E (N) exactly, so a grid to 90° has its
/// row exactly at the pole.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace meridian::gravity {

/// GMT's registration of a grid's nodes: gridline (nodes on the region's
/// edges, GMT `node_offset` 0) or pixel (nodes at cell centres, GMT `-r`,
/// `node_offset` 1).
enum class GridRegistration { Gridline, Pixel };

/// A quantity synthesised on a grid. Inside the library values are SI and
/// radians; file writers convert (ξ, η to arc-seconds, Δg and the
/// disturbance vector to mGal). Definitions as GravityField (gravity_field.hpp):
enum class GridQuantity {
  Xi,                ///< ξ (rad), north–south deflection; > 0: plumb line north of the normal (Φ > φ)
  Eta,               ///< η (rad), east–west deflection; > 0: plumb line east of the normal (Λ > λ)
  Geoid,             ///< N (m), geoid height above the ellipsoid at (φ, λ); the grid's height is ignored
  Anomaly,           ///< Δg = −∂T/∂r − 2T/r (m/s²), spherical gravity anomaly (GeographicLib Dg01)
  DisturbanceEast,   ///< δg_east = (1/(r cos ψ)) ∂T/∂λ (m/s²), ∇T in the local geocentric frame, > 0 east
  DisturbanceNorth,  ///< δg_north = (1/r) ∂T/∂ψ (m/s²), ∇T local geocentric north component, > 0 north
  DisturbanceUp,     ///< δg_up = ∂T/∂r (m/s²), ∇T radial component, > 0 outward (up)
};

/// The name used on the command line and in files: xi, eta, geoid, anomaly,
/// dg_east, dg_north, dg_up.
std::string_view to_string(GridQuantity q) noexcept;
/// Inverse of to_string (also accepts "n" for geoid, "dg" for anomaly).
/// Throws InputError naming the accepted names.
GridQuantity grid_quantity_from_string(std::string_view name);
/// A comma-separated list of names ("xi,eta,geoid"), each as grid_quantity_from_string, in
/// order; empty names are skipped (repeats are left for GridSpec::validate to refuse).
std::vector<GridQuantity> parse_grid_quantities(std::string_view list);
/// "gridline" or "pixel".
std::string_view to_string(GridRegistration r) noexcept;

/// Per-node ellipsoidal heights, one parallel at a time: fill `heights_m` (columns() values,
/// west to east, metres above the reference ellipsoid) for row `row` (0 = southernmost).
/// Called on the thread that runs synthesize_grid, rows in order, once each. May throw.
using GridHeightSource = std::function<void(std::size_t row, std::span<double> heights_m)>;

/// A grid to synthesise. Degrees at this edge (GMT's units); the engine
/// converts to radians.
struct GridSpec {
  double west_deg = 0;   ///< W, degrees east; any value, E − W ≤ 360
  double east_deg = 0;   ///< E > W
  double south_deg = 0;  ///< S ≥ −90
  double north_deg = 0;  ///< N ≤ 90, N > S
  double lon_spacing_deg = 0;  ///< Δλ > 0; (E − W)/Δλ must be a whole number (to 1e-9 relative)
  double lat_spacing_deg = 0;  ///< Δφ > 0; (N − S)/Δφ must be a whole number (to 1e-9 relative)
  GridRegistration registration = GridRegistration::Gridline;
  double height_m = 0;  ///< ellipsoidal height of every node, [kMinHeight_m, kMaxHeight_m] (N ignores it)
  /// Empty: every node at height_m. Set: per-node heights (height_m is then unused), each
  /// checked as it arrives (InputError, field "rows[j].points[i].h"); only the per-parallel
  /// path can use them, evaluating every node as a scattered point (GravityField::evaluate,
  /// O(N²) per node: meant for regional grids).
  GridHeightSource node_heights;
  std::vector<GridQuantity> quantities;  ///< at least one, no repeats; the order of the outputs

  /// At most this many nodes in a grid (2³² ≈ 4.3·10⁹: a 20″ global grid);
  /// larger grids are refused before any work.
  static constexpr std::uint64_t kMaxNodes = std::uint64_t{1} << 32;

  /// Throws InputError (field "region", "spacing", "height", "quantities")
  /// for: non-finite values; W ≥ E or E − W > 360°; S ≥ N, S < −90° or
  /// N > 90°; a spacing ≤ 0 or not dividing the region's width/height; a
  /// spacing that gives no node (pixel registration with a spacing larger
  /// than the region); more than kMaxNodes nodes; a height outside
  /// [kMinHeight_m, kMaxHeight_m]; no or repeated quantities.
  void validate() const;

  std::size_t columns() const;  ///< nodes per row (validate() first)
  std::size_t rows() const;     ///< rows (parallels)
  std::uint64_t nodes() const { return static_cast<std::uint64_t>(columns()) * rows(); }
  /// Longitude of column i (degrees, in [W, E]); W + i·Δλ (+ Δλ/2 for pixel), E exactly for the last gridline column.
  double lon_deg(std::size_t i) const;
  /// Latitude of row j (degrees, j = 0 the southernmost); N exactly for the last gridline row.
  double lat_deg(std::size_t j) const;
  /// Column i's longitude in radians (lon_deg(i) converted), as the engine evaluates it.
  double lon_rad(std::size_t i) const;
  /// Row j's latitude in radians (lat_deg(j) converted, clamped to [−π/2, π/2] so ±90° stays
  /// a valid latitude after rounding), as the engine evaluates it.
  double lat_rad(std::size_t j) const;
  /// True when the columns cover the whole parallel: E − W = 360° (to 1e-9°). Every
  /// spacing that passes validate() then divides 360°.
  bool global_longitude() const;
  /// 360°/Δλ, the samples per parallel of the FFT path; 0 when Δλ does not divide 360° (to
  /// 1e-9 relative), when the FFT path cannot be used.
  std::size_t samples_per_turn() const;
};

/// GMT-style region "W/E/S/N" in decimal degrees (e.g. "-10/30/35/60", "0/360/-90/90"),
/// or "g" (0/360/−90/90) and "d" (−180/180/−90/90). Sets W, E, S, N of `spec`.
/// Throws InputError (field "--region") for a malformed string; ranges are
/// checked by GridSpec::validate().
void parse_grid_region(std::string_view text, GridSpec& spec);

/// GMT-style spacing: a number with an optional unit, "d" degrees (default),
/// "m" arc-minutes, "s" arc-seconds ("30s", "5m", "0.5d", "0.25"), returned in degrees.
/// "X/Y" gives a longitude and a latitude spacing (`lat_deg` receives Y; a
/// single value sets both). Throws InputError (field "--spacing").
void parse_grid_spacing(std::string_view text, double& lon_deg, double& lat_deg);

}  // namespace meridian::gravity
