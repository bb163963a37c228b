#pragma once
/// \file grid_synthesis.hpp
/// Synthesis of ξ, η, N, Δg and the gravity-disturbance vector on a regular
/// latitude/longitude grid (GridSpec), parallel by parallel, in threads, with
/// each finished parallel handed to a sink in order (south to north) so
/// memory stays bounded by a few parallels whatever the grid's size.
///
/// Two paths give the same numbers (to rounding, ~1e-15 relative) as
/// GravityField::evaluate at every node:
/// * FFT (GridPath::Fft; a longitude spacing that divides 360°, one height):
///   per parallel, the order-m column sums of the stable recursion
///   (Holmes & Featherstone 2002, as GravityField) give the Fourier
///   coefficients a_m, b_m of each quantity, f(λ) = Σm a_m cos mλ + b_m sin mλ;
///   one real inverse FFT of length Nλ = 360°/Δλ (FFTW c2r) per quantity
///   samples the whole parallel from the grid's first longitude on; a regional
///   grid keeps its first columns. Orders m ≥ Nλ/2 are folded exactly
///   (e^{imλ_k} = e^{i(m mod Nλ)λ_k} at the nodes, with the Hermitian partner):
///   no aliasing error and no truncation, whatever the degree.
/// * Per parallel (GridPath::Parallel; any grid): GravityCircle per parallel,
///   O(M) per node.
/// Formulas, units, signs: docs/gravity-field.md, "Grids".

#include <cstddef>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include "meridian/core/progress.hpp"
#include "meridian/gravity/grid_spec.hpp"
#include "meridian/gravity/gravity_field.hpp"

namespace meridian::gravity {

/// How a grid is synthesised.
enum class GridPath {
  Auto,      ///< see choose_grid_path
  Fft,       ///< one real FFT per parallel and quantity (longitude spacing dividing 360°, one height)
  Parallel,  ///< GravityCircle per parallel, O(M) per node (per-node heights: GravityField::evaluate)
};
/// "auto", "fft", "parallel".
std::string_view to_string(GridPath p) noexcept;
/// Inverse of to_string; InputError (field "path") otherwise.
GridPath grid_path_from_string(std::string_view name);

struct GridOptions {
  GridPath path = GridPath::Auto;
  /// Threads working on parallels; 0 = std::thread::hardware_concurrency().
  unsigned threads = 0;
  /// Bound on the memory of parallels in flight (values of all quantities,
  /// 8 bytes each): parallels are computed in batches of at most this many
  /// bytes and at least one. A grid whose single parallel exceeds it is
  /// refused (InputError, field "spacing") before any work.
  std::size_t max_buffer_bytes = std::size_t{1} << 30;
};

/// One finished parallel. values(k) holds quantity spec.quantities[k] at every
/// column (west to east), in SI units and radians: ξ, η in rad, N in m, Δg
/// and δg in m/s² (GridQuantity documents the signs).
struct GridRow {
  std::size_t row = 0;     ///< 0 = southernmost
  double lat_deg = 0;      ///< GridSpec::lat_deg(row)
  std::size_t columns = 0;
  std::span<const double> data;  ///< quantities × columns, quantity-major
  std::span<const double> values(std::size_t k) const { return data.subspan(k * columns, columns); }
};

/// Receives each parallel once, in row order, on the calling thread. The
/// span is valid only during the call. May throw: synthesis stops and the
/// exception propagates.
using GridRowSink = std::function<void(const GridRow&)>;

struct GridSynthesisResult {
  GridPath path_used = GridPath::Parallel;  ///< Fft or Parallel, never Auto
  std::size_t rows = 0, columns = 0;
  std::size_t fft_length = 0;  ///< Nλ of the FFT path (0 for Parallel)
  /// Threads over parallels. With per-node heights 1: parallels run in order on the calling
  /// thread and GravityField::evaluate spreads each one's nodes over FieldOptions::threads.
  unsigned threads = 1;
  bool per_node_heights = false;  ///< GridSpec::node_heights was used
};

/// Checks a spec and options without computing, and returns the path that
/// synthesize_grid would use for a model of maximum order `max_order`.
/// Auto: Fft when the longitude spacing divides 360° and the grid has one
/// height, and either the grid is global in longitude or the per-parallel
/// path's O(columns·(M + 1)) per parallel exceeds the FFT's, estimated as
/// 2·quantities·Nλ (columns·(M + 1) ≥ 2·quantities·Nλ: a rule from the
/// measured costs, docs/gravity-field.md §6); else Parallel. Throws
/// InputError as GridSpec::validate(), for GridPath::Fft with a longitude
/// spacing that does not divide 360° or with per-node heights (field
/// "path"), and for a parallel larger than options.max_buffer_bytes (field
/// "spacing").
GridPath choose_grid_path(const GridSpec& spec, const GridOptions& options = {}, int max_order = 0);

/// Synthesise the grid: checks everything first (choose_grid_path), then
/// calls `sink` for every row from south to north, and `progress` (may be
/// null) with rows done of rows. Throws as choose_grid_path; NumericalError
/// when a value is not finite (a damaged model), field "rows[j]"; whatever
/// the sink throws. Thread-safe: the field is shared read-only; FFTW plans
/// are made under a process-wide lock (FFTW's planner is not thread-safe).
GridSynthesisResult synthesize_grid(const GravityField& field, const GridSpec& spec, const GridRowSink& sink,
                                    Progress* progress = nullptr, const GridOptions& options = {});

}  // namespace meridian::gravity
