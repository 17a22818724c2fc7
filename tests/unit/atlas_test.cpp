// The law atlas against closed forms written here from the bar's Delassus matrix and the
// one-contact LCP of Newton + Coulomb (never the atlas's own earlier output): the
// stick/slide/reversal map, the sign of the energy change, the paper's first impact on the map, and
// Frémond's and Stronge's laws, which never create energy anywhere on it.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "fremond/fremond.hpp"

namespace fremond {
namespace {

// The paper's bar: m = 1, l = 0.5, J = m l²/3. Its lower end (contact 0, body point r = (−l, 0))
// at angle θ is a = (−l cos θ, −l sin θ) from the centre, so on the ground (n = (0, 1), t = (1, 0))
// W_N = (0, 1, −l cos θ), W_T = (1, 0, l sin θ) and G = Wᵀ M⁻¹ W has, per unit mass,
struct Delassus {
  double NN, NT, TT;
};
Delassus bar_delassus(double theta) {
  const double m = 1.0, l = 0.5, J = m * l * l / 3.0, c = std::cos(theta), s = std::sin(theta);
  return {1.0 / m + l * l * c * c / J, -l * l * c * s / J, 1.0 / m + l * l * s * s / J};
}

// Newton + Coulomb on one contact (paper eqs. 5-8) with D_NA < 0: the contact closes, D_NE =
// −e D_NA. Sticking (D_TE = 0): G P = b with b = (−(1 + e) D_NA, −D_TA), kept iff |P_T| ≤ μ P_N.
// Sliding with σ = sign D_TE: P_T = −σ μ P_N, P_N = b_N / (G_NN − σ μ G_NT) > 0, D_TE = D_TA +
// P_N (G_NT − σ μ G_TT), kept iff σ D_TE > 0. For μ|G_NT| < G_NN exactly one of them holds.
struct NewtonCoulomb {
  AtlasMode mode = AtlasMode::unknown;
  double P_N = 0, P_T = 0, D_TE = 0;
  double energy_change = 0;  // P·z (eq. 9), z the mean velocity
};
NewtonCoulomb newton_coulomb(const Delassus& G, double D_NA, double D_TA, double e, double mu) {
  NewtonCoulomb out;
  const double bN = -(1.0 + e) * D_NA, bT = -D_TA, det = G.NN * G.TT - G.NT * G.NT;
  const double PN = (G.TT * bN - G.NT * bT) / det, PT = (G.NN * bT - G.NT * bN) / det;
  if (std::fabs(PT) <= mu * PN) {
    out = {AtlasMode::stick, PN, PT, 0.0, 0.0};
  } else {
    for (const double sigma : {1.0, -1.0}) {
      const double pn = bN / (G.NN - sigma * mu * G.NT);
      const double dte = D_TA + pn * (G.NT - sigma * mu * G.TT);
      if (pn > 0 && sigma * dte > 0) {
        out = {sigma * D_TA < 0 ? AtlasMode::reversal : AtlasMode::slide, pn, -sigma * mu * pn, dte,
               0.0};
        break;
      }
    }
  }
  out.energy_change = out.P_N * 0.5 * (1.0 - e) * D_NA + out.P_T * 0.5 * (D_TA + out.D_TE);
  return out;
}

Scene paper_bar() {
  return bar_scene(BarParameters{}, ImpactLaw::newton(0.9));
}

// Every cell of a map whose closed-form neighbours (the 8 around it) all agree with it: the
// boundary between two regions is only resolved to a cell.
template <class T>
bool inside_region(const std::vector<T>& expected, int nt, int np, int i, int j) {
  for (int di = -1; di <= 1; ++di)
    for (int dj = -1; dj <= 1; ++dj) {
      const int a = i + di, b = j + dj;
      if (a < 0 || b < 0 || a >= nt || b >= np) continue;
      if (expected[static_cast<std::size_t>(a * np + b)] !=
          expected[static_cast<std::size_t>(i * np + j)])
        return false;
    }
  return true;
}

AtlasOptions newton_coulomb_map(double mu, int n) {
  AtlasOptions o;
  o.laws = {"newton_coulomb"};
  o.values = {mu};
  o.e = 0.9;
  o.theta_count = o.psi_count = n;
  o.theta_min = 0.0;
  o.theta_max = std::numbers::pi;  // both sides: the lower end's a_x changes sign at π/2
  o.speed = 1.0;
  return o;
}

TEST(Atlas, ProblemHasTheContactVelocitiesAsked) {
  const Scene bar = paper_bar();
  for (const double spin : {-1.5, 0.0, 0.7}) {
    const SmallImpactProblem pb = atlas_problem(bar, 0, 0.3, -2.0, spin, 3.0);
    const double c = std::cos(0.3), s = std::sin(0.3), l = 0.5;
    EXPECT_NEAR(pb.qdot_A(1) - l * c * pb.qdot_A(2), 3.0 * std::sin(-2.0), 1e-14);
    EXPECT_NEAR(pb.qdot_A(0) + l * s * pb.qdot_A(2), 3.0 * std::cos(-2.0), 1e-14);
    EXPECT_NEAR(pb.qdot_A(2) * std::sqrt(1.0 / 12.0) / 3.0, spin, 1e-14);
  }
}

// (a) The mode map of Newton + Coulomb is the closed form's, cell by cell, away from one cell of
// the boundaries.
TEST(Atlas, NewtonCoulombModeMapIsTheClosedForm) {
  int reversal = 0;
  for (const double mu : {0.3, 1.0}) {
    SCOPED_TRACE("mu = " + std::to_string(mu));
    const int n = 120;
    const AtlasResult r = law_atlas(paper_bar(), newton_coulomb_map(mu, n));
    ASSERT_EQ(r.points(), static_cast<std::size_t>(n * n));
    std::vector<AtlasMode> expected(r.points());
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const std::size_t c = r.config(0, i, j);
        EXPECT_NEAR(r.D_NA[c], std::sin(r.psi[j]), 1e-15);
        EXPECT_NEAR(r.D_TA[c], std::cos(r.psi[j]), 1e-15);
        expected[c] = newton_coulomb(bar_delassus(r.theta[i]), r.D_NA[c], r.D_TA[c], 0.9, mu).mode;
      }
    int compared = 0, stick = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const std::size_t c = r.config(0, i, j);
        ASSERT_NE(expected[c], AtlasMode::unknown);
        if (!inside_region(expected, n, n, i, j)) continue;
        ++compared;
        stick += expected[c] == AtlasMode::stick;
        reversal += expected[c] == AtlasMode::reversal;
        EXPECT_EQ(static_cast<AtlasMode>(r.mode[c]), expected[c])
            << "theta " << r.theta[i] << " psi " << r.psi[j];
        EXPECT_EQ(r.solutions[c], 1);
      }
    EXPECT_GT(compared, n * n * 8 / 10);
    EXPECT_GT(stick, n * n / 20);
  }
  EXPECT_GT(reversal, 0);  // every mode is on the maps (reversals need a small μ)
}

// The Painlevé-type region: where μ|G_NT| > G_NN − the bar from μ = 4/3 on − one sliding mode's
// normal percussion changes sign. The number of Newton + Coulomb solutions is that of the modes of
// newton_coulomb() that hold (sticking, sliding each way), counted here: on the bar's impacts,
// with D_NA < 0 and restitution, it is one in every cell, also inside that region.
int newton_coulomb_solutions(const Delassus& G, double D_NA, double D_TA, double e, double mu) {
  const double bN = -(1.0 + e) * D_NA, bT = -D_TA, det = G.NN * G.TT - G.NT * G.NT;
  const double PN = (G.TT * bN - G.NT * bT) / det, PT = (G.NN * bT - G.NT * bN) / det;
  int count = PN > 0 && std::fabs(PT) <= mu * PN ? 1 : 0;
  for (const double sigma : {1.0, -1.0}) {
    const double pn = bN / (G.NN - sigma * mu * G.NT);
    const double dte = D_TA + pn * (G.NT - sigma * mu * G.TT);
    count += pn > 0 && sigma * dte > 0 ? 1 : 0;
  }
  return count;
}

TEST(Atlas, NewtonCoulombSolutionCountIsTheClosedFormsInThePainleveRegion) {
  const int n = 100;
  const double mu = 2.0;
  AtlasOptions o = newton_coulomb_map(mu, n);
  o.solver.check_uniqueness = true;
  const AtlasResult r = law_atlas(paper_bar(), o);
  int painleve = 0;
  for (int i = 0; i < n; ++i) {
    const Delassus G = bar_delassus(r.theta[i]);
    painleve += mu * std::fabs(G.NT) > G.NN;
    for (int j = 0; j < n; ++j) {
      const std::size_t c = r.config(0, i, j);
      EXPECT_EQ(r.solutions[c], newton_coulomb_solutions(G, r.D_NA[c], r.D_TA[c], 0.9, mu))
          << "theta " << r.theta[i] << " psi " << r.psi[j];
    }
  }
  EXPECT_GT(painleve, n / 4);  // a good part of the map lies in the region
}

// (b) Where Newton + Coulomb creates energy on the bar, from the closed form's P·z.
TEST(Atlas, NewtonCoulombEnergySignIsTheClosedForm) {
  const int n = 120;
  const AtlasResult r = law_atlas(paper_bar(), newton_coulomb_map(1.0, n));
  std::vector<int> expected(r.points());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::size_t c = r.config(0, i, j);
      const double dT =
          newton_coulomb(bar_delassus(r.theta[i]), r.D_NA[c], r.D_TA[c], 0.9, 1.0).energy_change;
      expected[c] = dT > 0 ? 1 : -1;
      // The ratio itself, to the rounding of the closed form.
      EXPECT_NEAR(r.energy_ratio[c], dT / r.kinetic_energy[c], 1e-12);
    }
  int gains = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::size_t c = r.config(0, i, j);
      if (!inside_region(expected, n, n, i, j)) continue;
      gains += expected[c] > 0;
      EXPECT_EQ(r.energy_ratio[c] > 0 ? 1 : -1, expected[c]);
      // A gain beyond the certificate's tolerance fails (15); a loss passes.
      EXPECT_EQ(r.admissible[c] == 1, expected[c] < 0);
      if (expected[c] > 0) {
        EXPECT_EQ(static_cast<Inequality>(r.failed[c]), Inequality::total_15);
      }
    }
  EXPECT_GT(gains, 0);  // the paper's Fig. 5 is not alone
}

// (c) The paper's bar at its first impact lies on the map where solve_impact puts it.
TEST(Atlas, PaperBarFirstImpactIsOnTheMap) {
  for (const PaperLaw which : {PaperLaw::newton_coulomb, PaperLaw::fremond_coulomb}) {
    const Scene scene = paper_bar_scene(which);
    SCOPED_TRACE(std::string(to_string(which)));
    const FirstImpact first = first_impact(scene, 10.0);
    ASSERT_TRUE(first.found);
    ASSERT_EQ(first.contacts[0], 0);
    const SmallImpactProblem pb = impact_problem(scene, first.state, first.contacts.data(), 1);
    const SmallImpactResult direct = solve_impact(pb, scene.law);
    const double D_NA = pb.W_N.col(0).dot(pb.qdot_A), D_TA = pb.W_T.col(0).dot(pb.qdot_A);
    const double theta = first.state.q(2), psi = std::atan2(D_NA, D_TA);
    EXPECT_DOUBLE_EQ(theta, std::numbers::pi / 4);

    AtlasOptions o;
    o.laws = {which == PaperLaw::newton_coulomb ? "newton_coulomb" : "fremond"};
    o.theta_count = o.psi_count = 21;  // the middle cell's centre is the first impact
    o.theta_min = theta - 0.2;
    o.theta_max = theta + 0.2;
    o.psi_min = psi - 0.3;
    o.psi_max = psi + 0.3;
    const AtlasResult r = law_atlas(scene, o);  // speed and contact: the first impact's
    EXPECT_EQ(r.contact, 0);
    EXPECT_NEAR(r.speed, std::hypot(D_NA, D_TA), 1e-14);
    const std::size_t p = r.index(0, 0, 0, 10, 10);
    EXPECT_NEAR(r.theta[10], theta, 1e-15);
    EXPECT_NEAR(r.psi[10], psi, 1e-15);
    EXPECT_NEAR(r.energy_ratio[p] * r.kinetic_energy[r.config(0, 10, 10)], direct.energy_change,
                1e-12);
    EXPECT_EQ(r.admissible[p] == 1, direct.admissibility.admissible);
    EXPECT_EQ(static_cast<Inequality>(r.failed[p]), direct.admissibility.failed);
    if (which == PaperLaw::newton_coulomb) {
      // The paper's Fig. 5: it creates energy, 0.668 J (README).
      EXPECT_NEAR(direct.energy_change, 0.668, 1e-3);
      EXPECT_FALSE(direct.admissibility.admissible);
    } else {
      // k_N calibrated as the preset's: the same law.
      EXPECT_NEAR(r.fremond_k_N[0], paper_bar_normal_stiffness(), 1e-9);
    }
  }
}

// (d) Frémond's laws, and Stronge's, never create energy anywhere on the map: every spin, every
// μ, every e.
TEST(Atlas, DissipativeLawsNeverCreateEnergy) {
  AtlasOptions o;
  o.laws = {"fremond", "stronge_coulomb", "newton_coulomb"};
  o.values = {0.0, 0.3, 1.0, 2.0};
  o.spins = {-1.0, 0.0, 1.0};
  o.theta_count = o.psi_count = 40;
  o.theta_max = std::numbers::pi;
  std::size_t calls = 0;
  o.progress = [&](std::size_t done, std::size_t total) {
    ++calls;
    EXPECT_LE(done, total);
  };
  for (const AtlasParameter parameter : {AtlasParameter::mu, AtlasParameter::e}) {
    o.parameter = parameter;
    if (parameter == AtlasParameter::e) o.values = {0.2, 0.5, 0.9};
    const AtlasResult r = law_atlas(paper_bar(), o);
    std::size_t converged = 0, created = 0;
    for (std::size_t l = 0; l < 2; ++l)
      for (std::size_t v = 0; v < r.values.size(); ++v)
        for (std::size_t c = 0; c < r.configurations(); ++c) {
          const std::size_t p = (l * r.values.size() + v) * r.configurations() + c;
          if (static_cast<SolverStatus>(r.status[p]) != SolverStatus::converged) continue;
          ++converged;
          EXPECT_LE(r.energy_ratio[p], 1e-9) << r.laws[l] << " point " << p;
          EXPECT_EQ(r.admissible[p], 1) << r.laws[l] << " point " << p;
          // Frémond's Coulomb acts on the mean velocity: inside its bound z_T = 0, so D_TE = −D_TA.
          if (l == 0 && static_cast<AtlasMode>(r.mode[p]) == AtlasMode::stick &&
              r.values[v] > 0.0) {
            EXPECT_NEAR(r.D_TE[p], -r.D_TA[c], 1e-9 * r.speed) << "point " << p;
          }
        }
    for (std::size_t p = 2 * r.values.size() * r.configurations(); p < r.points(); ++p)
      created += r.energy_ratio[p] > 1e-9;
    EXPECT_GT(converged, 2 * r.values.size() * r.configurations() * 99 / 100);
    EXPECT_GT(created, 0u);  // Newton + Coulomb on the same map does
    // The reference's own distance is zero; another law's is not.
    EXPECT_EQ(r.distance[0], 0.0);
    EXPECT_GT(r.distance[r.points() - 1], 0.0);
  }
  EXPECT_GT(calls, 0u);
}

TEST(Atlas, RefusesBadOptionsNamingThem) {
  const auto refused = [](const std::function<void(AtlasOptions&)>& change) {
    AtlasOptions o;
    change(o);
    try {
      o.validate();
    } catch (const InvalidArgument& e) {
      return e.name();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(refused([](auto& o) { o.laws = {"newton", "lagrange"}; }), "laws[1]");
  EXPECT_EQ(refused([](auto& o) { o.laws = {"newton", "newton"}; }), "laws[1]");
  EXPECT_EQ(refused([](auto& o) { o.laws.clear(); }), "laws");
  EXPECT_EQ(refused([](auto& o) { o.reference = "poisson"; }), "reference");
  EXPECT_EQ(refused([](auto& o) { o.values = {1.0, -0.5}; }), "values[1]");
  EXPECT_EQ(refused([](auto& o) {
              o.parameter = AtlasParameter::e;
              o.values = {1.0};
            }),
            "values[0]");  // Frémond's k_N cannot be calibrated to e = 1
  EXPECT_EQ(refused([](auto& o) { o.theta_count = 0; }), "theta_count");
  EXPECT_EQ(refused([](auto& o) { o.psi_max = 0.5; }), "psi_max");
  EXPECT_EQ(refused([](auto& o) { o.psi_min = -4.0; }), "psi_min");
  EXPECT_EQ(refused([](auto& o) { o.theta_max = o.theta_min; }), "theta_max");
  EXPECT_EQ(refused([](auto& o) { o.speed = -1.0; }), "speed");
  EXPECT_EQ(refused([](auto& o) { o.spins = {NAN}; }), "spins[0]");
  EXPECT_EQ(refused([](auto& o) { o.fremond_p = 1.0; }), "fremond_p");
  EXPECT_EQ(refused([](auto&) {}), "(accepted)");
  AtlasOptions o;
  o.contact = 2;
  EXPECT_THROW(law_atlas(paper_bar(), o), InvalidArgument);
}

}  // namespace
}  // namespace fremond
