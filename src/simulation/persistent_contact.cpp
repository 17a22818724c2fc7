// The persistent-contact impulse of a step by contact-mode enumeration (persistent_contact.hpp).
#include "fremond/simulation/persistent_contact.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "fremond/core/enum_names.hpp"
#include "simulation/detail/min_norm_solve.hpp"

namespace fremond {

namespace {
constexpr detail::EnumNames<ContactMode, 4> kModes{{{ContactMode::open, "open"},
                                                    {ContactMode::stick, "stick"},
                                                    {ContactMode::slide_forward, "slide_forward"},
                                                    {ContactMode::slide_back, "slide_back"}}};
constexpr detail::EnumNames<StepVelocity, 2> kStepVelocity{
    {{StepVelocity::end, "end"}, {StepVelocity::mean, "mean"}}};
}  // namespace

std::string_view to_string(StepVelocity v) {
  return detail::enum_to_string(kStepVelocity, v);
}
StepVelocity step_velocity_from_string(std::string_view s) {
  return detail::enum_from_string(kStepVelocity, s, "step velocity");
}

std::string_view to_string(ContactMode m) {
  return detail::enum_to_string(kModes, m);
}
ContactMode contact_mode_from_string(std::string_view s) {
  return detail::enum_from_string(kModes, s, "contact mode");
}

namespace {

constexpr int kMax = PersistentContactProblem::kMax;
constexpr int kMaxRows = 2 * kMax;
using Sys = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxRows, kMaxRows>;
using Rhs = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxRows, 1>;

// Relative tolerances of the mode checks: a mode is accepted when its conditions hold to this
// fraction of the velocity (or percussion) scale of the problem. The linear solve itself is exact
// to rounding; these only absorb that rounding.
constexpr double kTolerance = 1e-10;

struct Scales {
  double v = 0.0;  // velocity scale
  double p = 0.0;  // percussion scale
};

// Tries one mode vector; on success fills `out` and returns true.
bool try_mode(const PersistentContactProblem& pb, const ContactMode* mode, const Scales& sc,
              PersistentContactResult& out) {
  const int c = pb.contacts;
  const bool mean_n = pb.normal == StepVelocity::mean;
  const bool mean_t = pb.friction == StepVelocity::mean;
  const Eigen::Vector3d v_sum = pb.v_before + pb.v_free;
  // Columns: one per closed contact (normal, with the sliding friction folded in), one more per
  // sticking contact (its tangential percussion). Rows: V_N = 0 per closed contact, V_T = 0 per
  // sticking contact (for a mean velocity, 2V = D_before + D_E = 0).
  std::array<Eigen::Vector3d, kMaxRows> col, row;
  std::array<double, kMaxRows> rhs{};
  std::array<int, kMax> ncol{}, tcol{};
  std::array<double, kMax> sigma{};  // P_T = sigma μ P_N for a sliding contact
  int n = 0;
  for (int k = 0; k < c; ++k) {
    ncol[k] = tcol[k] = -1;
    if (mode[k] == ContactMode::open) continue;
    sigma[k] = mode[k] == ContactMode::slide_forward ? -1.0
               : mode[k] == ContactMode::slide_back  ? 1.0
                                                     : 0.0;
    col[n] = pb.W_N[k] + sigma[k] * pb.mu[k] * pb.W_T[k];
    row[n] = pb.W_N[k];
    rhs[n] = -pb.W_N[k].dot(mean_n ? v_sum : pb.v_free);
    ncol[k] = n++;
  }
  for (int k = 0; k < c; ++k) {
    if (mode[k] != ContactMode::stick) continue;
    col[n] = pb.W_T[k];
    row[n] = pb.W_T[k];
    rhs[n] = -pb.W_T[k].dot(mean_t ? v_sum : pb.v_free);
    tcol[k] = n++;
  }
  // The system A x = rhs, A_rj = row_rᵀ M⁻¹ col_j; one and two unknowns in closed form (the usual
  // case of one contact, sliding or sticking), more by LU, and by the minimum-norm solution when
  // the rows are dependent.
  std::array<double, kMaxRows> x{};
  const auto a = [&](int r, int j) { return row[r].dot(pb.minv.cwiseProduct(col[j])); };
  bool solved = false;
  if (n == 1) {
    const double a00 = a(0, 0);
    if (!(std::fabs(a00) > 0.0)) return false;
    x[0] = rhs[0] / a00;
    solved = true;
  } else if (n == 2) {
    const double a00 = a(0, 0), a01 = a(0, 1), a10 = a(1, 0), a11 = a(1, 1);
    const double det = a00 * a11 - a01 * a10;
    const double scale = std::max({std::fabs(a00), std::fabs(a01), std::fabs(a10), std::fabs(a11)});
    if (std::fabs(det) > 1e-8 * scale * scale) {  // far from singular: Cramer's rule is accurate
      x[0] = (rhs[0] * a11 - a01 * rhs[1]) / det;
      x[1] = (a00 * rhs[1] - a10 * rhs[0]) / det;
      solved = true;
    }
  }
  if (!solved && n > 0) {
    Sys A(n, n);
    Rhs b(n);
    for (int r = 0; r < n; ++r) {
      b(r) = rhs[r];
      for (int j = 0; j < n; ++j) A(r, j) = a(r, j);
    }
    const auto consistent = [&](const Rhs& sol) {
      return sol.allFinite() && (A * sol - b).cwiseAbs().maxCoeff() <= kTolerance * sc.v;
    };
    Rhs sol = A.partialPivLu().solve(b);
    if (!consistent(sol)) {
      // Dependent rows (a flat bar sticking at both ends: four rows, three degrees of freedom).
      sol = detail::min_norm_solve(A, b);
      if (!consistent(sol)) return false;
    }
    for (int r = 0; r < n; ++r) x[r] = sol(r);
  }
  Eigen::Vector3d impulse = Eigen::Vector3d::Zero();
  for (int k = 0; k < c; ++k) {
    out.P_N[k] = ncol[k] >= 0 ? x[ncol[k]] : 0.0;
    out.P_T[k] = tcol[k] >= 0 ? x[tcol[k]] : sigma[k] * pb.mu[k] * out.P_N[k];
    impulse += out.P_N[k] * pb.W_N[k] + out.P_T[k] * pb.W_T[k];
  }
  const Eigen::Vector3d v = pb.v_free + pb.minv.cwiseProduct(impulse);
  const double tv = kTolerance * sc.v, tp = kTolerance * sc.p;
  for (int k = 0; k < c; ++k) {
    const double vN = mean_n ? 0.5 * pb.W_N[k].dot(pb.v_before + v) : pb.W_N[k].dot(v);
    const double zT = mean_t ? 0.5 * pb.W_T[k].dot(pb.v_before + v) : pb.W_T[k].dot(v);
    switch (mode[k]) {
      case ContactMode::open:
        if (vN < -tv) return false;
        break;
      case ContactMode::stick:
        if (out.P_N[k] < -tp || std::fabs(out.P_T[k]) > pb.mu[k] * out.P_N[k] + tp) return false;
        break;
      case ContactMode::slide_forward:
        if (out.P_N[k] < -tp || (pb.mu[k] > 0.0 && zT < -tv)) return false;
        break;
      case ContactMode::slide_back:
        if (out.P_N[k] < -tp || (pb.mu[k] > 0.0 && zT > tv)) return false;
        break;
    }
  }
  out.v = v;
  for (int k = 0; k < c; ++k) out.mode[k] = mode[k];
  return true;
}

// One contact, the common case of a body resting, rocking or sliding on one point: the same
// modes and checks as try_mode, with the 2×2 Delassus matrix formed once and every mode in closed
// form. What does not depend on the step velocities (the Delassus entries, the contact velocities
// of v_before and v_free, the scales) is formed once per problem, so that the dissipative step's
// second solve (Coulomb on the mean) does not form it again.
struct OneContact {
  Eigen::Vector3d mn, mt;    // M⁻¹ W_N, M⁻¹ W_T
  double gnn, gnt, gtt, mu;  // Delassus entries, friction coefficient
  double n_before, n_free;   // W_Nᵀ v_before, W_Nᵀ v_free
  double t_before, t_free;   // W_Tᵀ v_before, W_Tᵀ v_free
  Scales sc;

  explicit OneContact(const PersistentContactProblem& pb) {
    const Eigen::Vector3d& n = pb.W_N[0];
    const Eigen::Vector3d& t = pb.W_T[0];
    mn = pb.minv.cwiseProduct(n);
    mt = pb.minv.cwiseProduct(t);
    gnn = n.dot(mn);
    gnt = n.dot(mt);
    gtt = t.dot(mt);
    mu = pb.mu[0];
    n_before = n.dot(pb.v_before);
    n_free = n.dot(pb.v_free);
    t_before = t.dot(pb.v_before);
    t_free = t.dot(pb.v_free);
    // As in scales(), expression for expression (the same bits; gnn is its W_Nᵀ M⁻¹ W_N).
    sc.v = std::max({0.0, std::fabs(n_free), std::fabs(t_free), std::fabs(t_before)});
    if (gnn > 0.0) sc.p = std::max(0.0, sc.v / gnn);
    sc.v = std::max(sc.v, 1e-300);
    sc.p = std::max(sc.p, 1e-300);
  }

  bool solve(const Eigen::Vector3d& v_free, StepVelocity normal, StepVelocity friction,
             const ContactMode* warm, PersistentContactResult& out) const {
    const bool mean_n = normal == StepVelocity::mean, mean_t = friction == StepVelocity::mean;
    // V = f (c + D_free + G P): f = ½ and c = D_before for a mean velocity, f = 1 and c = 0 else.
    const double fn = mean_n ? 0.5 : 1.0, ft = mean_t ? 0.5 : 1.0;
    const double an = (mean_n ? n_before : 0.0) + n_free;
    const double at = (mean_t ? t_before : 0.0) + t_free;
    const double tv = kTolerance * sc.v, tp = kTolerance * sc.p;
    const auto attempt = [&](ContactMode m) {
      ++out.modes_tried;
      double pn = 0.0, pt = 0.0;
      switch (m) {
        case ContactMode::open:
          if (fn * an < -tv) return false;
          break;
        case ContactMode::stick: {
          if (mu == 0.0) return false;
          const double det = gnn * gtt - gnt * gnt;
          if (!(det > 1e-12 * gnn * gtt)) return false;
          pn = (-an * gtt + gnt * at) / det;
          pt = (-at * gnn + gnt * an) / det;
          if (pn < -tp || std::fabs(pt) > mu * pn + tp) return false;
          break;
        }
        case ContactMode::slide_forward:
        case ContactMode::slide_back: {
          const double sigma = m == ContactMode::slide_forward ? -1.0 : 1.0;
          if (mu == 0.0 && sigma > 0.0) return false;
          const double a = gnn + sigma * mu * gnt;
          if (!(std::fabs(a) > 0.0)) return false;
          pn = -an / a;
          pt = sigma * mu * pn;
          if (pn < -tp) return false;
          if (mu > 0.0) {
            const double vt = ft * (at + gnt * pn + gtt * pt);
            if (sigma < 0.0 ? vt < -tv : vt > tv) return false;
          }
          break;
        }
      }
      out.P_N[0] = pn;
      out.P_T[0] = pt;
      out.v = v_free + pn * mn + pt * mt;
      out.mode[0] = m;
      return true;
    };
    if (warm && attempt(warm[0])) return true;
    const ContactMode along = at >= 0.0 ? ContactMode::slide_forward : ContactMode::slide_back;
    const ContactMode against = at >= 0.0 ? ContactMode::slide_back : ContactMode::slide_forward;
    const std::array<ContactMode, 4> order =
        an >= 0.0
            ? std::array<ContactMode, 4>{ContactMode::open, ContactMode::stick, along, against}
            : std::array<ContactMode, 4>{ContactMode::stick, along, against, ContactMode::open};
    for (const ContactMode m : order)
      if (attempt(m)) return true;
    return false;
  }
};

Scales scales(const PersistentContactProblem& pb) {
  Scales sc;
  for (int k = 0; k < pb.contacts; ++k) {
    sc.v = std::max({sc.v, std::fabs(pb.W_N[k].dot(pb.v_free)), std::fabs(pb.W_T[k].dot(pb.v_free)),
                     std::fabs(pb.W_T[k].dot(pb.v_before))});
    const double g = pb.W_N[k].dot(pb.minv.cwiseProduct(pb.W_N[k]));
    if (g > 0.0) sc.p = std::max(sc.p, sc.v / g);
  }
  sc.v = std::max(sc.v, 1e-300);
  sc.p = std::max(sc.p, 1e-300);
  return sc;
}

// Two or more contacts: the warm modes, then every mode (see solve_persistent_contact).
bool solve_many(const PersistentContactProblem& pb, const ContactMode* warm, const Scales& sc,
                PersistentContactResult& out) {
  const int c = pb.contacts;
  std::array<ContactMode, kMax> mode{};
  if (warm) {
    for (int k = 0; k < c; ++k) mode[k] = warm[k];
    ++out.modes_tried;
    if (try_mode(pb, mode.data(), sc, out)) return true;
  }
  // Every mode, each contact's modes in the order its free motion suggests: open first when the
  // contact leaves without a percussion, then sticking, then sliding against its free slip.
  // Frictionless contacts have only "open" and "slide" (P_T = 0).
  std::array<std::array<ContactMode, 4>, kMax> order;
  for (int k = 0; k < c; ++k) {
    const bool mn = pb.normal == StepVelocity::mean, mt = pb.friction == StepVelocity::mean;
    const double vn = pb.W_N[k].dot(pb.v_free) + (mn ? pb.W_N[k].dot(pb.v_before) : 0.0);
    const double vt = pb.W_T[k].dot(pb.v_free) + (mt ? pb.W_T[k].dot(pb.v_before) : 0.0);
    const ContactMode along = vt >= 0.0 ? ContactMode::slide_forward : ContactMode::slide_back;
    const ContactMode against = vt >= 0.0 ? ContactMode::slide_back : ContactMode::slide_forward;
    if (vn >= 0.0)
      order[k] = {ContactMode::open, ContactMode::stick, along, against};
    else
      order[k] = {ContactMode::stick, along, against, ContactMode::open};
  }
  std::array<int, kMax> idx{};
  while (true) {
    bool skip = false;
    for (int k = 0; k < c; ++k) {
      mode[k] = order[k][idx[k]];
      if (pb.mu[k] == 0.0 && (mode[k] == ContactMode::stick || mode[k] == ContactMode::slide_back))
        skip = true;
    }
    if (!skip) {
      ++out.modes_tried;
      if (try_mode(pb, mode.data(), sc, out)) return true;
    }
    int k = 0;
    while (k < c && ++idx[k] == 4) idx[k++] = 0;
    if (k == c) break;
  }
  return false;
}

}  // namespace

double step_energy(const PersistentContactProblem& pb, const PersistentContactResult& r,
                   double* rounding) {
  double e = 0.0, size = 0.0;
  const Eigen::Vector3d vm = 0.5 * (pb.v_before + r.v);
  // The rounding of z = W v (a zero z of a closed or sticking contact comes out as a few units of
  // the velocities) bounds that of P·z: |P| |W|·(|v_before| + |v⁺|) units.
  const Eigen::Vector3d va = 0.5 * (pb.v_before.cwiseAbs() + r.v.cwiseAbs());
  for (int k = 0; k < pb.contacts; ++k) {
    e += r.P_N[k] * pb.W_N[k].dot(vm) + r.P_T[k] * pb.W_T[k].dot(vm);
    size += std::fabs(r.P_N[k]) * pb.W_N[k].cwiseAbs().dot(va) +
            std::fabs(r.P_T[k]) * pb.W_T[k].cwiseAbs().dot(va);
  }
  if (rounding) *rounding = 16.0 * std::numeric_limits<double>::epsilon() * size;
  return e;
}

PersistentContactResult solve_persistent_contact(const PersistentContactProblem& pb,
                                                 const ContactMode* warm) {
  PersistentContactResult out;
  out.v = pb.v_free;
  const int c = pb.contacts;
  if (c <= 0 || c > kMax) return out;
  out.solved = c == 1 ? OneContact(pb).solve(pb.v_free, pb.normal, pb.friction, warm, out)
                      : solve_many(pb, warm, scales(pb), out);
  if (!out.solved) out.v = pb.v_free;
  return out;
}

PersistentContactResult solve_dissipative_step(PersistentContactProblem& pb,
                                               const ContactMode* warm) {
  pb.normal = StepVelocity::mean;
  pb.friction = StepVelocity::end;
  const int c = pb.contacts;
  PersistentContactResult out;  // the one object returned: built in the caller's result
  out.v = pb.v_free;
  if (c <= 0 || c > kMax) return out;
  // The scales and, for one contact, the Delassus entries and contact velocities do not depend on
  // which velocity Coulomb's law acts on: formed once for both solves.
  const auto solve = [&](const OneContact* one, const Scales& sc, PersistentContactResult& r) {
    r.solved =
        one ? one->solve(pb.v_free, pb.normal, pb.friction, warm, r) : solve_many(pb, warm, sc, r);
    if (!r.solved) r.v = pb.v_free;
  };
  const auto both = [&](const OneContact* one, const Scales& sc) {
    solve(one, sc, out);
    double rounding = 0.0;
    if (out.solved && step_energy(pb, out, &rounding) <= rounding) return;
    pb.friction = StepVelocity::mean;
    PersistentContactResult m;
    solve(one, sc, m);
    if (m.solved) out = m;
  };
  if (c == 1) {
    const OneContact one(pb);
    both(&one, one.sc);
  } else {
    both(nullptr, scales(pb));
  }
  return out;
}

}  // namespace fremond
