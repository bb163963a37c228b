#pragma once
/// \file gravity_field.hpp
/// Spherical-harmonic synthesis of the disturbing potential T = W − U and its
/// derivatives: geoid height, gravity disturbance, spherical gravity anomaly
/// and the deflection of the vertical (ξ, η), at scattered points, in
/// vectorised multi-threaded batches.
///
/// Definitions (identical to GeographicLib's GravityModel so values compare
/// one to one; see docs/gravity-field.md):
/// * T excludes the degree-0 term (GM_model − GM_ref)/r (as GeographicLib's
///   SphericalAnomaly and GeoidHeight) unless `include_degree_zero` is set.
/// * ξ = −(1/γ) (1/r) ∂T/∂ψ, η = −(1/γ) (1/(r cos ψ)) ∂T/∂λ with ψ the
///   geocentric latitude at the point and γ = |∇U| the normal gravity at the
///   point (GeographicLib SphericalAnomaly xi, eta). Positive ξ: plumb line
///   points north of the ellipsoid normal (astronomic latitude greater).
///   Frames (ECEF, ENU, geocentric local) and the ξ, η sign convention are
///   stated once in geodesy/frames.hpp.
/// * Geoid height N = T(φ, λ, h = 0)/γ0(φ) + correction (Bruns; GeographicLib
///   GeoidHeight), γ0 Somigliana's normal gravity on the ellipsoid.
/// * Spherical anomaly Δg = −∂T/∂r − 2T/r (GeographicLib Dg01).
/// * Variant (not in GeographicLib's SphericalAnomaly): the astronomic
///   deflection ξ_a = Φ − φ, η_a = (Λ − λ) cos φ exactly as the spec README
///   defines it, with (Φ, Λ) the direction of the full gravity vector
///   g = ∇U + ∇T at the point and φ, λ the geodetic coordinates. It differs
///   from ξ, η by up to ~0.1″ (the geocentric-frame rotation φ − ψ applied
///   to the radial gravity disturbance, and the curvature of the normal
///   plumb line with height).
///
/// Numerics: fully normalised associated Legendre functions divided by
/// cos^m ψ and scaled by 1e-280 (Holmes & Featherstone 2002, forward column
/// recursion), summed over m by complex Horner in cos ψ·e^{iλ}, so every
/// latitude including the poles is stable to degree ≥ 2700.

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "meridian/gravity/gravity_model.hpp"
#include "meridian/gravity/normal_gravity.hpp"
#include "meridian/gravity/simd_kernel.hpp"

namespace meridian::gravity {

namespace detail {
class SynthesisTable;
}

/// A point given by geodetic coordinates on the model's reference ellipsoid.
struct GeodeticPoint {
  double lat_rad = 0;   ///< geodetic latitude, [−π/2, π/2]
  double lon_rad = 0;   ///< longitude, east positive (any value)
  double height_m = 0;  ///< ellipsoidal height, [kMinHeight_m, kMaxHeight_m]
};

/// Heights accepted (metres above the reference ellipsoid). Below −12 km
/// lies inside the Earth's masses where the series is not meant to be
/// used; above 10 000 km the high-degree terms are numerically zero.
inline constexpr double kMinHeight_m = -12000.0;
inline constexpr double kMaxHeight_m = 1.0e7;

/// What to compute.
enum class Quantities : unsigned {
  Deflection = 1u,  ///< T, gradient, ξ, η, Δg at the point's height
  Geoid = 2u,       ///< N at the point's (φ, λ) (height ignored)
  All = 3u,
};

/// True when the request `what` includes quantity q (Quantities is a bit set).
constexpr bool includes(Quantities what, Quantities q) {
  return (static_cast<unsigned>(what) & static_cast<unsigned>(q)) != 0;
}

/// Results at one point. NaN where not requested. Frames and deflection
/// signs: geodesy/frames.hpp.
struct FieldValues {
  double disturbing_potential_m2_s2;  ///< T at the point (m²/s²)
  double xi_rad;                      ///< north–south deflection ξ (rad)
  double eta_rad;                     ///< east–west deflection η (rad)
  double geoid_m;                     ///< geoid height N (m) at (φ, λ)
  double anomaly_m_s2;                ///< spherical gravity anomaly Δg = −∂T/∂r − 2T/r (m/s²)
  double dT_east_m_s2;                ///< (1/(r cos ψ)) ∂T/∂λ (m/s²), local geocentric east
  double dT_north_m_s2;               ///< (1/r) ∂T/∂ψ (m/s²), local geocentric north
  double dT_up_m_s2;                  ///< ∂T/∂r (m/s²), radial
  double normal_gravity_m_s2;         ///< γ = |∇U| at the point (m/s²)
  double xi_astro_rad;                ///< Φ − φ of the actual plumb line (rad), see the file comment
  double eta_astro_rad;               ///< (Λ − λ) cos φ, Λ − λ in (−π, π] (rad)
};

struct FieldOptions {
  /// Include (GM_model − GM_ref)/r in T (GeographicLib's Disturbance); the
  /// default leaves it out as GeographicLib's GeoidHeight/SphericalAnomaly do.
  bool include_degree_zero = false;
  /// Threads for batch evaluation; 0 = std::thread::hardware_concurrency().
  unsigned threads = 0;
  /// Instruction set of the summation kernel (simd_kernel.hpp). Auto: MERIDIAN_SIMD_KERNEL if
  /// set, else the widest this CPU supports. The kernels agree to about 1e-15 relative.
  SimdKernel simd_kernel = SimdKernel::Auto;
};

/// The synthesis engine for one model. Immutable and thread-safe after
/// construction. It keeps its own copy of C̄, S̄ (16 bytes per coefficient pair; the
/// recursion coefficients are formed during evaluation from tables of O(N) roots).
class GravityField {
 public:
  /// Throws InputError for an empty/invalid model (GM, a not positive), or for a
  /// FieldOptions::simd_kernel (or MERIDIAN_SIMD_KERNEL) this CPU cannot run. Copies the
  /// model's coefficients.
  explicit GravityField(const GravityModelData& model, FieldOptions options = {});
  /// As above, but takes the coefficients over from `model` instead of copying them (38 MB at
  /// degree 2190): `GravityField(io::read_egm_file(path))` loads a model without a copy. `model`
  /// keeps its metadata (name, GM, radius, correction, … for model_info) and is left with an
  /// all-zero degree-0 coefficient set.
  explicit GravityField(GravityModelData&& model, FieldOptions options = {});
  ~GravityField();
  GravityField(GravityField&&) noexcept;
  GravityField& operator=(GravityField&&) noexcept;

  int max_degree() const noexcept;
  int max_order() const noexcept;
  /// The summation kernel in use (concrete: never SimdKernel::Auto).
  SimdKernel simd_kernel() const noexcept;
  const NormalGravity& normal() const noexcept { return normal_; }
  double model_gm_m3_s2() const noexcept { return gm_; }
  double model_radius_m() const noexcept { return radius_m_; }

  /// All quantities at one point. Throws InputError for a latitude outside
  /// ±90°, a height outside [kMinHeight_m, kMaxHeight_m] or non-finite input;
  /// NumericalError when a requested value is not finite (a model whose
  /// coefficients, GM or radius are out of range): never NaN or infinity.
  FieldValues evaluate(const GeodeticPoint& p, Quantities what = Quantities::All) const;

  /// Many points, vectorised across points and spread over
  /// FieldOptions::threads threads. Result i belongs to points[i]. All
  /// points are validated first (InputError with field "points[i]");
  /// NumericalError as the single-point evaluate, field "points[i]".
  std::vector<FieldValues> evaluate(std::span<const GeodeticPoint> points,
                                    Quantities what = Quantities::All) const;

  /// Validate one point (throws InputError as above).
  static void check_point(const GeodeticPoint& p);

  /// Internal: synthesis tables (used by GravityCircle).
  const detail::SynthesisTable& disturbing_table() const noexcept { return *table_; }
  const detail::SynthesisTable* correction_table() const noexcept { return correction_.get(); }
  double correction_multiplier() const noexcept { return corr_mult_; }
  bool include_degree_zero() const noexcept { return include_degree_zero_; }
  double degree_zero_gm_m3_s2() const noexcept { return dgm_; }

 private:
  GravityField(const GravityModelData& model, SphericalHarmonicCoefficients coefficients, FieldOptions options);
  void evaluate_block(const GeodeticPoint* p, std::size_t count, Quantities what, FieldValues* out) const;

  NormalGravity normal_;
  double gm_ = 0, radius_m_ = 0, corr_mult_ = 1, dgm_ = 0;
  bool include_degree_zero_ = false;
  unsigned threads_ = 0;
  std::unique_ptr<detail::SynthesisTable> table_;       // T: C̄ − normal zonal, C̄00 = 0
  std::unique_ptr<detail::SynthesisTable> correction_;  // geoid correction, or null
};

}  // namespace meridian::gravity
