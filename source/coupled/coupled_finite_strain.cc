// The coupled system of bodies at finite strain: the reference state of
// a step, the bodies' internal forces and tangents at an iterate, and the
// products with that tangent. The assembly and the direct solvers are in
// coupled_system.cc.
//
// Its own translation unit outside the unity batches, as coupled_krylov.cc:
// the members defined here are instantiated one by one below, and
// coupled_system.cc instantiates the class.

#include <igabde/base/memory_record.h>
#include <igabde/base/utilities.h>
#include <igabde/linear_algebra/sparse_cholesky.h>

#include <igabde/coupled/coupled_system.h>
#include <igabde/coupled/mumps_pivot_order.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_CrsMatrix.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace igabde
{
  namespace coupled
  {
    template <int dim>
    void
    CoupledSystem<dim>::set_reference(const Eigen::VectorXd     &u,
                                      const std::vector<double> &step_factors)
    {
      if (!any_finite)
        return;
      AssertDimension(u.size(), n_u);
      factors = step_factors;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        if (finite[b])
          {
            const unsigned int n = bodies[b]->n_dofs();
            reference[b].reinit(n);
            for (unsigned int i = 0; i < n; ++i)
              reference[b][i] = u[offsets[b] + i];
            const Vector<double> g = bodies[b]->prescribed_values(factors);
            support_moves[b].reinit(n);
            for (unsigned int i = 0; i < n; ++i)
              if (held[offsets[b] + i])
                support_moves[b][i] = g[i] - reference[b][i];
            loads[b] = bodies[b]->external_load_vector(factors);
          }
      have_residual = false;
      linearized    = false;
      linearize_bodies(Eigen::VectorXd::Zero(n_u));
    }



    template <int dim>
    bool
    CoupledSystem<dim>::evaluate_bodies(const Eigen::VectorXd &w,
                                        const bool             tangent) const
    {
      const bool same_residual =
        have_residual && residual_at.size() == w.size() && residual_at == w;
      const bool same_tangent =
        linearized && linearized_at.size() == w.size() && linearized_at == w;
      if (same_residual && (!tangent || same_tangent))
        return residual_finite;
      residual_finite = true;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          if (!finite[b])
            continue;
          const discretization::Body<dim> &body = *bodies[b];
          Vector<double>                   u    = reference[b];
          for (unsigned int i = 0; i < u.size(); ++i)
            u[i] += w[offsets[b] + i];
          residuals[b]            = 0.;
          SparseMatrix<double> *T = tangent ? &tangents[b] : nullptr;
          if (T != nullptr)
            *T = 0.;
          const double min_J =
            body.internal_force(u, body.finite_law(), residuals[b], T);
          if (!(min_J > 0.))
            {
              residual_finite = false;
              continue;
            }
          const double internal = residuals[b].l2_norm();
          if (!body.follower_pressures(factors).empty())
            body.add_follower_pressure(u, factors, residuals[b], T);
          residuals[b] -= loads[b];
          force_norms[b] = std::max(internal, loads[b].l2_norm());
        }
      have_residual = true;
      residual_at   = w;
      if (tangent)
        {
          linearized    = true;
          linearized_at = w;
        }
      return residual_finite;
    }



    template <int dim>
    void
    CoupledSystem<dim>::linearize_bodies(const Eigen::VectorXd &w)
    {
      if (any_finite)
        evaluate_bodies(w, true);
    }



    template <int dim>
    Eigen::VectorXd
    CoupledSystem<dim>::tangent_equations(const Eigen::VectorXd &v_w,
                                          const Eigen::VectorXd &v_p) const
    {
      if (!any_finite)
        {
          Eigen::VectorXd r = frozen_equations(v_w, v_p);
          add_geometric_term(v_w, r);
          return r;
        }
      Assert(linearized, ExcMessage("linearize_bodies() first"));
      AssertDimension(v_w.size(), n_u);
      AssertDimension(v_p.size(), d * n_pairs);
      Eigen::VectorXd r(n_u);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          const SparseMatrix<double> &K =
            finite[b] ? tangents[b] : bodies[b]->stiffness_matrix();
          // At finite strain the free rows depend on the held unknowns
          // too (they move to the supports' values during the solve).
          Vector<double> vb(K.m()), rb(K.m());
          for (unsigned int i = 0; i < K.m(); ++i)
            vb[i] =
              held[offsets[b] + i] && !finite[b] ? 0. : v_w[offsets[b] + i];
          K.vmult(rb, vb);
          for (unsigned int i = 0; i < K.m(); ++i)
            r[offsets[b] + i] = rb[i];
        }
      for (unsigned int row = 0; row < d * n_pairs; ++row)
        for (const auto &[g, v] : C_rows[row])
          r[g] -= v * v_p[row];
      add_geometric_term(v_w, r);
      for (unsigned int g = 0; g < n_u; ++g)
        if (held[g])
          r[g] = v_w[g];
      return r;
    }



    template <int dim>
    Eigen::VectorXd
    CoupledSystem<dim>::tangent_transpose(const Eigen::VectorXd &h) const
    {
      if (!any_finite)
        return frozen_equations(h, Eigen::VectorXd::Zero(d * n_pairs));
      Assert(linearized, ExcMessage("linearize_bodies() first"));
      AssertDimension(h.size(), n_u);
      Eigen::VectorXd r(n_u);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          const SparseMatrix<double> &K =
            finite[b] ? tangents[b] : bodies[b]->stiffness_matrix();
          Vector<double> hb(K.m()), rb(K.m());
          for (unsigned int i = 0; i < K.m(); ++i)
            hb[i] = held[offsets[b] + i] ? 0. : h[offsets[b] + i];
          K.Tvmult(rb, hb);
          // J = [K_ff K_fh; 0 I] at finite strain: the held rows of J^T h
          // are K_fh^T h_f + h_h.
          for (unsigned int i = 0; i < K.m(); ++i)
            r[offsets[b] + i] = !held[offsets[b] + i] ? rb[i] :
                                finite[b] ? rb[i] + h[offsets[b] + i] :
                                            h[offsets[b] + i];
        }
      return r;
    }



    template void
    CoupledSystem<2>::set_reference(const Eigen::VectorXd &,
                                    const std::vector<double> &);
    template bool
    CoupledSystem<2>::evaluate_bodies(const Eigen::VectorXd &,
                                      const bool) const;
    template void
    CoupledSystem<2>::linearize_bodies(const Eigen::VectorXd &);
    template Eigen::VectorXd
    CoupledSystem<2>::tangent_equations(const Eigen::VectorXd &,
                                        const Eigen::VectorXd &) const;
    template Eigen::VectorXd
    CoupledSystem<2>::tangent_transpose(const Eigen::VectorXd &) const;
    template void
    CoupledSystem<3>::set_reference(const Eigen::VectorXd &,
                                    const std::vector<double> &);
    template bool
    CoupledSystem<3>::evaluate_bodies(const Eigen::VectorXd &,
                                      const bool) const;
    template void
    CoupledSystem<3>::linearize_bodies(const Eigen::VectorXd &);
    template Eigen::VectorXd
    CoupledSystem<3>::tangent_equations(const Eigen::VectorXd &,
                                        const Eigen::VectorXd &) const;
    template Eigen::VectorXd
    CoupledSystem<3>::tangent_transpose(const Eigen::VectorXd &) const;
  } // namespace coupled
} // namespace igabde
