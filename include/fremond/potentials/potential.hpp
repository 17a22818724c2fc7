#pragma once
/// @file The interface of a pseudo-potential of dissipation (paper §5.2; docs/laws.md).
///
/// A pseudo-potential is a convex, lower semicontinuous function φ: R → R ∪ {+∞}, non-negative and
/// zero at the origin, of one contact's *mean* velocity z (docs/concepts.md). The impact law is the
/// inclusion −P ∈ ∂φ(z). Solvers use, in this order of preference, the proximal map
///     prox_{τφ}(x) = argmin_y  φ(y) + (y − x)²/(2τ)
/// with its derivative (semismooth Newton), then the subdifferential, then value and one
/// subgradient (the NLopt fallback). The conjugate φ*(s) = sup_z s z − φ(z), where known, certifies
/// an answer through the Fenchel–Young gap φ(z) + φ*(s) − s z ≥ 0, zero exactly when s ∈ ∂φ(z).
///
/// Non-virtual interface: the public members check their arguments and call the protected `do_*`
/// hooks, which a user's potential overrides. Copying is through `clone()` only (no slicing).
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <string_view>

namespace fremond {

/// A closed interval [lo, hi] of the extended real line; empty when lo > hi (the subdifferential of
/// a function outside its domain).
struct Interval {
  double lo = 0.0;
  double hi = 0.0;

  static Interval point(double v) { return {v, v}; }
  static Interval empty() { return {1.0, -1.0}; }
  bool is_empty() const { return lo > hi; }
  /// Distance from s to the interval (0 inside, +∞ for an empty interval).
  double distance(double s) const {
    if (is_empty()) return std::numeric_limits<double>::infinity();
    if (s < lo) return lo - s;
    if (s > hi) return s - hi;
    return 0.0;
  }
  bool contains(double s, double tol = 0.0) const { return distance(s) <= tol; }
  /// Minkowski sum, the subdifferential of a sum where one term is continuous.
  friend Interval operator+(Interval a, Interval b) {
    if (a.is_empty() || b.is_empty()) return empty();
    return {a.lo + b.lo, a.hi + b.hi};
  }
};

/// What a potential can do, so a driver can pick the cheapest exact method it allows.
/// Eight bytes, aligned: returned in one register and stored with one move (five bools would be
/// spilled byte by byte and reloaded as a word, a store-forwarding stall at every solve's setup).
struct alignas(8) PotentialCapabilities {
  bool prox = false;             ///< prox_{τφ} is available (exact or to machine precision).
  bool prox_derivative = false;  ///< an element of the generalized derivative of the prox is given.
  bool subdifferential = false;  ///< the whole interval ∂φ(z), not only one subgradient.
  bool conjugate = false;        ///< φ* is known in closed form.
  bool quadratic = false;  ///< φ is piecewise quadratic (affine prox on pieces): closed form.
};

/// A convex pseudo-potential of one scalar contact velocity.
class Potential {
 public:
  virtual ~Potential() = default;
  Potential(const Potential&) = delete;
  Potential& operator=(const Potential&) = delete;
  Potential(Potential&&) = delete;
  Potential& operator=(Potential&&) = delete;

  /// The registry name of the kind (e.g. "power"); a user's potential names itself.
  std::string_view name() const { return do_name(); }
  /// A copy of this potential with the same parameters.
  std::unique_ptr<Potential> clone() const { return do_clone(); }
  PotentialCapabilities capabilities() const { return do_capabilities(); }

  /// φ(z); +∞ outside the domain.
  double value(double z) const { return do_value(z); }
  /// ∂φ(z) as an interval (empty outside the domain). Potentials without a full subdifferential
  /// return the single subgradient.
  Interval subdifferential(double z) const;
  /// One element of ∂φ(z) (the one of least magnitude where the interval is known).
  double subgradient(double z) const { return do_subgradient(z); }
  /// prox_{τφ}(x) for τ > 0; `dprox`, when not null, receives an element of the Clarke derivative
  /// of the map x ↦ prox_{τφ}(x), a number in [0, 1]. At x = ±∞ the answer is the limit of the
  /// prox: the end of dom φ on that side (±∞ for a potential finite on the whole line). Throws
  /// InvalidArgument when τ ≤ 0 or not finite, when x is NaN, or when the potential has no prox.
  double prox(double x, double tau, double* dprox = nullptr) const;
  /// φ*(s); +∞ outside its domain. Throws InvalidArgument when the conjugate is not known.
  double conjugate(double s) const;
  /// Fenchel–Young gap φ(z) + φ*(s) − s z (≥ 0; 0 iff s ∈ ∂φ(z)); NaN when the conjugate is
  /// unknown.
  double fenchel_young_gap(double z, double s) const;

  /// One line describing the parameters, e.g. "power(k=85.36, p=3)".
  std::string describe() const { return do_describe(); }

 protected:
  Potential() = default;

  virtual std::string_view do_name() const = 0;
  virtual std::unique_ptr<Potential> do_clone() const = 0;
  virtual PotentialCapabilities do_capabilities() const = 0;
  virtual double do_value(double z) const = 0;
  virtual double do_subgradient(double z) const = 0;
  /// Default: the single subgradient.
  virtual Interval do_subdifferential(double z) const { return Interval::point(do_subgradient(z)); }
  /// Default: prox by bisection on the monotone inclusion 0 ∈ y − x + τ∂φ(y), exact to the last bit
  /// of y; used only when capabilities().subdifferential is true.
  virtual double do_prox(double x, double tau, double* dprox) const;
  virtual double do_conjugate(double s) const;
  virtual std::string do_describe() const { return std::string(do_name()); }
};

using PotentialPtr = std::unique_ptr<Potential>;

namespace detail {
/// Copyable owner of a potential (deep copy through clone()).
class PotentialHandle {
 public:
  PotentialHandle() = default;
  PotentialHandle(PotentialPtr p) : p_(std::move(p)) {}  // NOLINT: implicit by design
  PotentialHandle(const PotentialHandle& o) : p_(o.p_ ? o.p_->clone() : nullptr) {}
  PotentialHandle& operator=(const PotentialHandle& o) {
    if (this != &o) p_ = o.p_ ? o.p_->clone() : nullptr;
    return *this;
  }
  PotentialHandle(PotentialHandle&&) noexcept = default;
  PotentialHandle& operator=(PotentialHandle&&) noexcept = default;
  const Potential* get() const { return p_.get(); }
  const Potential& operator*() const { return *p_; }
  const Potential* operator->() const { return p_.get(); }
  explicit operator bool() const { return static_cast<bool>(p_); }

 private:
  PotentialPtr p_;
};
}  // namespace detail

}  // namespace fremond
