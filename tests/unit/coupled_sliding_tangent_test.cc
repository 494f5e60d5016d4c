// Finite sliding's full tangent (coupled::CoupledSystem::linearize_geometry,
// Contact/Sliding tangent = full): the law rows' derivative and the
// displacement rows' derivative are those of the residual with the pairs
// formed again at every configuration, checked against central
// differences of it. The pairs are closest points of three slave points on
// a unit square's top against a rigid circle above it (gap |x - c| - R,
// normal (x - c) / |x - c|, slip the slave's displacement), formed here in
// closed form, so that the reference is independent of the pairing code;
// the forces are nonzero, so that the normal's turn gives a geometric
// stiffness. The forward differences of linearize_geometry() (step 1e-6
// of an element) err by about the step times the normal's curvature over
// the tangent's size, 1e-6 relative or less here; the central differences
// by 1e-10: the bound 1e-5 leaves a margin of 10. The frozen tangent (C at
// the iterate) misses the normal's turn and the gap's change of direction,
// terms of relative size |p| / (E R) (forces 0.2, E = 1, R = 1.45, spread
// over the elements' stiffness): it must miss by more than 1e-3, a hundred
// times the bound, so that the test tells the two apart.
// Both discretisations, and the derivatives formed through
// FiniteSliding::pairs_of (the pairs of each group of unknowns alone, as
// the contact stage forms them) as well as through pairs_at (all pairs at
// every group), and from the pairs' derivatives in closed form
// (FiniteSliding::linearization_of, derived here by hand for the circle).

#include <igabde/nurbs/geometry_builders.h>

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <igabde/contact/contact_path.h>
#include <igabde/contact/pairing.h>

#include <igabde/coupled/coupled_system.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

namespace coupled_sliding_tangent
{
  using namespace igabde;
  using namespace igabde::discretization;

  /// The largest deviation, relative to the derivative's size, of the
  /// system's derivatives from central differences of its residual, at a
  /// random state and direction; @p full: the full sliding tangent;
  /// @p subsets: FiniteSliding::pairs_of given.
  std::pair<double, double>
  tangent_errors(const Type type,
                 const bool full,
                 const bool subsets     = false,
                 const bool closed_form = false)
  {
    BodyDescription<2> d;
    d.geometry = nurbs::make_box<2>(Point<2>(0., 0.), Point<2>(1., 1.));
    nurbs::elevate_to_degree(d.geometry, 2);
    nurbs::subdivide(d.geometry, std::array<unsigned int, 2>{{3, 2}});
    d.material.youngs_modulus = 1.;
    d.material.poisson_ratio  = 0.3;
    DirichletCondition<2> condition;
    condition.boundary_id = 2;
    condition.components  = {{true, true}};
    d.dirichlet.push_back(condition);
    DiscretizationSettings settings;
    settings.type   = type;
    settings.degree = 2;
    auto body       = create_body<2>(d, settings);
    body->setup();
    body->ensure_assembled();

    const Point<2>                centre(0.5, 2.5);
    const double                  radius = 1.45;
    std::vector<Point<2>>         slave  = {Point<2>(0.3, 1.),
                                            Point<2>(0.6, 1.),
                                            Point<2>(0.85, 1.)};
    std::vector<PointOperator<2>> ops;
    for (const auto &X : slave)
      ops.push_back(body->point_operator(X));
    const unsigned int n_dofs = body->n_dofs();
    // The pairs at the configuration w (closed form: the circle's closest
    // point).
    const auto pairs_at = [&](const Eigen::VectorXd &w) {
      Vector<double> u(n_dofs);
      for (unsigned int i = 0; i < n_dofs; ++i)
        u[i] = w[i];
      std::vector<contact::ContactPair<2>> pairs;
      for (unsigned int i = 0; i < slave.size(); ++i)
        {
          contact::ContactPair<2> pair;
          const Tensor<1, 2>      du = ops[i].displacement(u);
          const Point<2>          x  = slave[i] + du;
          const Tensor<1, 2>      n  = (x - centre) / (x - centre).norm();
          pair.x1                    = x;
          pair.x2                    = centre + radius * n;
          pair.frame                 = contact::local_frame<2>(n);
          pair.normal1               = -n;
          pair.gap                   = (x - centre).norm() - radius;
          pair.area                  = 0.3;
          pair.op1                   = ops[i];
          pair.master_body           = numbers::invalid_unsigned_int;
          pair.obstacle              = 0;
          pair.slave_key             = i;
          pair.step_slip             = du;
          pairs.push_back(pair);
        }
      return pairs;
    };

    const Eigen::VectorXd        zero   = Eigen::VectorXd::Zero(n_dofs);
    std::vector<const Body<2> *> bodies = {body.get()};
    coupled::CoupledSystem<2>    system(bodies,
                                     pairs_at(zero),
                                     2,
                                     Eigen::MatrixXd(6, 0),
                                     coupled::Solver::mumps);
    const Eigen::VectorXd        q = Eigen::VectorXd::Zero(6);
    contact::FiniteSliding<2>    sliding;
    sliding.pairs_at = pairs_at;
    sliding.q        = &q;
    sliding.tangent =
      full ? contact::SlidingTangent::full : contact::SlidingTangent::frozen;
    if (subsets)
      sliding.pairs_of = [&](const Eigen::VectorXd           &w,
                             const std::vector<unsigned int> &indices) {
        const auto                           all = pairs_at(w);
        std::vector<contact::ContactPair<2>> some;
        for (const unsigned int i : indices)
          some.push_back(all.at(i));
        return some;
      };
    if (closed_form)
      // The pairs' derivatives by hand: d gap = n . dx, dn = (I - n n) dx
      // / |x - c|, the frame's from the normal's, d slip = dx, with
      // dx = w_k e_c for the unknown (k, c) of the slave operator; the
      // operators do not change.
      sliding.linearization_of =
        [&](const Eigen::VectorXd                      &w,
            const std::vector<unsigned int>            &indices,
            std::vector<contact::PairLinearization<2>> &result) {
          const auto all = pairs_at(w);
          result.clear();
          for (const unsigned int i : indices)
            {
              contact::PairLinearization<2> L;
              L.pair                 = all.at(i);
              const Tensor<1, 2> n   = L.pair.frame[0];
              const double       rho = L.pair.gap + radius;
              for (unsigned int k = 0; k < ops[i].weights.size(); ++k)
                for (unsigned int c = 0; c < 2; ++c)
                  {
                    const std::pair<unsigned int, types::global_dof_index> u(
                      0,
                      ops[i].dofs[k][c]);
                    const double wk = ops[i].weights[k];
                    L.gap.emplace_back(u, wk * n[c]);
                    L.slip[c].emplace_back(u, wk);
                    Tensor<1, 2> dx;
                    dx[c]                 = wk;
                    const Tensor<1, 2> dn = (dx - (dx * n) * n) / rho;
                    const Tensor<2, 2> dT =
                      contact::local_frame_change(n, L.pair.frame, dn);
                    for (unsigned int r = 0; r < 2; ++r)
                      for (unsigned int e = 0; e < 2; ++e)
                        L.frame[r][e].emplace_back(u, dT[r][e]);
                  }
              L.op1.resize(L.pair.op1.weights.size());
              result.push_back(L);
            }
          return true;
        };
    system.set_finite_sliding(sliding);

    // A random state (held unknowns at zero) and direction, and forces.
    std::mt19937                     random(11);
    std::uniform_real_distribution<> uniform(-1., 1.);
    Eigen::VectorXd                  w(n_dofs), v(n_dofs);
    for (unsigned int i = 0; i < n_dofs; ++i)
      {
        w[i] = body->is_held(i) ? 0. : 0.03 * uniform(random);
        v[i] = body->is_held(i) ? 0. : uniform(random);
      }
    contact::ContactIterate x;
    x.w = w;
    x.p = Eigen::VectorXd(6);
    x.p << 0.2, 0.05, 0.1, -0.03, 0.15, 0.02;

    // The residual with the pairs formed at w: the pair displacements
    // u = C w + q + offset and the displacement equations K w - C^T p.
    const auto residual =
      [&](const Eigen::VectorXd &at, Eigen::VectorXd &u, Eigen::VectorXd &E) {
        contact::ContactIterate y = x;
        y.w                       = at;
        system.update_geometry(y);
        u = system.apply_C(at) + q + *system.displacement_offset();
        E = system.displacement_equations(at, x.p);
      };
    const double    eps = 1e-5;
    Eigen::VectorXd u_plus, E_plus, u_minus, E_minus;
    residual(w + eps * v, u_plus, E_plus);
    residual(w - eps * v, u_minus, E_minus);
    const Eigen::VectorXd du = (u_plus - u_minus) / (2. * eps);
    const Eigen::VectorXd dE = (E_plus - E_minus) / (2. * eps);

    system.update_geometry(x);
    system.linearize_geometry(x);
    const Eigen::VectorXd Ju = system.apply_C_derivative(v);
    const Eigen::VectorXd JE =
      system.tangent_equations(v, Eigen::VectorXd::Zero(6));
    return {(Ju - du).norm() / du.norm(), (JE - dE).norm() / dE.norm()};
  }
} // namespace coupled_sliding_tangent

TEST(CoupledSlidingTangent, FullTangentIsTheDerivativeOfThePairs)
{
  for (const auto type : {igabde::discretization::Type::nurbs,
                          igabde::discretization::Type::lagrange})
    {
      const auto [gaps, forces] =
        coupled_sliding_tangent::tangent_errors(type, true);
      EXPECT_LT(gaps, 1e-5);
      EXPECT_LT(forces, 1e-5);
      const auto [subset_gaps, subset_forces] =
        coupled_sliding_tangent::tangent_errors(type, true, true);
      EXPECT_LT(subset_gaps, 1e-5);
      EXPECT_LT(subset_forces, 1e-5);
      // The same from the pairs' derivatives in closed form
      // (FiniteSliding::linearization_of): no differences of their own,
      // the central differences' 1e-10 with the same margin.
      const auto [closed_gaps, closed_forces] =
        coupled_sliding_tangent::tangent_errors(type, true, false, true);
      EXPECT_LT(closed_gaps, 1e-5);
      EXPECT_LT(closed_forces, 1e-5);
      // The frozen tangent is not: the test can tell them apart.
      const auto [frozen_gaps, frozen_forces] =
        coupled_sliding_tangent::tangent_errors(type, false);
      EXPECT_GT(std::max(frozen_gaps, frozen_forces), 1e-3);
    }
}
