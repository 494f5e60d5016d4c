#include <igabde/base/utilities.h>

#include <igabde/contact/condensation.h>

#include <algorithm>

namespace igabde
{
  namespace contact
  {
    namespace
    {
      /**
       * A combination of free rigid modes that moves no pair along any of
       * its directions (with frictionless pairs on a plane: the slide along
       * the plane) is not fixed by the contact problem: its column space
       * leaves G singular whatever the pairs do. If no load drives it, hold
       * it at zero (the columns of G become a basis of the resisted
       * combinations, @p modes.basis maps them back); if a load drives it,
       * nothing can balance that load and the scene is refused.
       */
      template <int dim>
      void
      hold_unresisted_modes(
        RigidModeColumns                                     &modes,
        const Eigen::VectorXd                                &motion,
        const std::vector<const discretization::Body<dim> *> &bodies,
        const std::string                                    &context,
        std::vector<bool>                                    &held)
      {
        const Eigen::Index n = modes.G.cols();
        if (n == 0 || modes.G.rows() == 0)
          return;
        // Columns scaled by the size of each mode's motion at the pairs'
        // points (@p motion: all components, not only those along the
        // pairs' directions), so that the rank test does not depend on
        // the units of the modes and a column is the share of its mode's
        // motion that moves pairs along their directions: a mode that
        // moves the pairs only along frame components of round-off (a
        // slide along a flat face whose normals carry 1e-17 across) has a
        // share of round-off, not a unit column.
        Eigen::VectorXd scale(n);
        for (Eigen::Index a = 0; a < n; ++a)
          {
            const double norm = motion(a);
            scale(a)          = norm > 0. ? 1. / norm : 1.;
          }
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd(modes.G *
                                                      scale.asDiagonal(),
                                                    Eigen::ComputeFullV);
        const Eigen::VectorXd                  &sigma = svd.singularValues();
        Eigen::Index                            rank  = 0;
        while (rank < n && sigma(rank) > 1e-8 * sigma(0))
          ++rank;
        if (rank == n)
          return;
        const Eigen::MatrixXd V = scale.asDiagonal() * svd.matrixV();
        const double          load_scale =
          std::max(modes.loads.norm(), modes.history_loads.norm());
        for (Eigen::Index j = rank; j < n; ++j)
          {
            Eigen::VectorXd v = V.col(j);
            v /= v.norm();
            Eigen::Index main = 0;
            v.cwiseAbs().maxCoeff(&main);
            const auto [b, k] = modes.alpha_modes[main];
            const std::string name =
              "Body " + std::to_string(b + 1) + "'s free rigid mode '" +
              bodies[b]->free_rigid_mode_names()[k] + "'";
            const double load =
              std::max(std::abs(v.dot(modes.loads)),
                       (modes.history_loads.transpose() * v).norm());
            AssertThrow(
              !(load > 1e-10 * load_scale),
              base::ExcInput(
                context + ": " + name +
                " carries a load that no contact pair can balance (it moves "
                "no pair along a direction that carries force; frictionless "
                "pairs push only along their normals). Hold it with a support "
                "(Supports) or give the contact friction."));
            held[main] = true;
          }
        modes.basis         = V.leftCols(rank);
        modes.G             = modes.G * modes.basis;
        modes.loads         = modes.basis.transpose() * modes.loads;
        modes.history_loads = modes.basis.transpose() * modes.history_loads;
      }
    } // namespace



    template <int dim>
    RigidModeColumns
    rigid_mode_columns(
      const std::vector<ContactPair<dim>>                  &pair_list,
      const std::vector<const discretization::Body<dim> *> &bodies,
      const unsigned int                                    m,
      const std::string                                    &context,
      std::ostream                                         &log)
    {
      RigidModeColumns   result;
      const unsigned int nc          = pair_list.size();
      auto              &alpha_modes = result.alpha_modes;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        for (unsigned int k = 0; k < bodies[b]->free_rigid_modes().size(); ++k)
          alpha_modes.emplace_back(b, k);
      result.G.resize(m * nc, alpha_modes.size());
      result.loads.resize(alpha_modes.size());
      unsigned int n_h = 1;
      for (const auto *body : bodies)
        n_h = std::max(n_h, body->n_histories());
      result.history_loads = Eigen::MatrixXd::Zero(alpha_modes.size(), n_h);
      // The size of each mode's motion at the pairs' points.
      Eigen::VectorXd motion = Eigen::VectorXd::Zero(alpha_modes.size());
      for (unsigned int a = 0; a < alpha_modes.size(); ++a)
        {
          const auto [b, k] = alpha_modes[a];
          const auto &mode  = bodies[b]->free_rigid_modes()[k];
          result.loads(a)   = mode * bodies[b]->load_vector();
          for (unsigned int h = 0; h < bodies[b]->n_histories(); ++h)
            result.history_loads(a, h) =
              mode * bodies[b]->history_load_vector(h);
          for (unsigned int i = 0; i < nc; ++i)
            {
              double      sign = 0.;
              const auto *op   = pair_list[i].operator_on(b, sign);
              if (op == nullptr)
                {
                  result.G.block(m * i, a, m, 1).setZero();
                  continue;
                }
              const Tensor<1, dim> r = op->displacement(mode);
              motion(a) += r.norm_square();
              for (unsigned int s = 0; s < m; ++s)
                result.G(m * i + s, a) = sign * (pair_list[i].frame[s] * r);
            }
          motion(a) = std::sqrt(motion(a));
        }
      result.basis =
        Eigen::MatrixXd::Identity(alpha_modes.size(), alpha_modes.size());
      std::vector<bool> held(alpha_modes.size(), false);
      hold_unresisted_modes(result, motion, bodies, context, held);
      // One line per mode, once its fate is known.
      for (unsigned int a = 0; a < alpha_modes.size(); ++a)
        {
          const auto [b, k] = alpha_modes[a];
          log << "  " << bodies[b]->name() << ": free rigid mode '"
              << bodies[b]->free_rigid_mode_names()[k] << "' "
              << (held[a] ? "moves no contact pair and carries no load: held "
                            "at zero" :
                            "closed by the contact equilibrium (exact, no "
                            "springs)")
              << std::endl;
        }
      return result;
    }



    template <int dim>
    CondensedContact<dim>
    condense(const std::vector<ContactPair<dim>>                  &pair_list,
             const std::vector<const discretization::Body<dim> *> &bodies,
             const unsigned int                                    m,
             const std::string                                    &context,
             std::ostream                                         &log,
             const bool                                            progress)
    {
      const unsigned int nc = pair_list.size();
      Eigen::MatrixXd    FL(m * nc, m * nc);
      FL.setZero();
      // Each body's share where it is factorised (under MPI the bodies'
      // groups at the same time), then handed to every rank: on the pairs
      // that touch the body (rows[b], their rows of F^L), each direction
      // with the sign of the body's side.
      std::vector<FullMatrix<double>>        flexibilities(bodies.size());
      std::vector<std::vector<unsigned int>> rows(bodies.size());
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          std::vector<discretization::PointOperator<dim>> ops;
          std::vector<Tensor<1, dim>>                     directions;
          for (unsigned int j = 0; j < nc; ++j)
            {
              double      sign = 0.;
              const auto *op   = pair_list[j].operator_on(b, sign);
              if (op == nullptr)
                continue;
              for (unsigned int s = 0; s < m; ++s)
                {
                  rows[b].push_back(m * j + s);
                  ops.push_back(*op);
                  directions.push_back(sign * pair_list[j].frame[s]);
                }
            }
          if (bodies[b]->factorizes_here() && !ops.empty())
            flexibilities[b] = bodies[b]->flexibility_in_group(ops, directions);
        }
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          if (rows[b].empty())
            continue;
          bodies[b]->share_flexibility(flexibilities[b]);
          const FullMatrix<double>        &Fb = flexibilities[b];
          const std::vector<unsigned int> &r  = rows[b];
          for (unsigned int i = 0; i < r.size(); ++i)
            for (unsigned int j = 0; j < r.size(); ++j)
              FL(r[i], r[j]) += Fb(i, j);
          // Dense blocks of the contact unknowns squared each (large at
          // B2's 16x64x16: doc/performance.md): none is kept longer than it
          // serves.
          flexibilities[b] = FullMatrix<double>();
          if (progress)
            log << "  contact: " << bodies[b]->name() << " condensed onto "
                << r.size() << " pair directions"
                << (bodies[b]->has_schur_complement() ?
                      " (Schur complement on " +
                        std::to_string(bodies[b]->n_interface_dofs()) +
                        " face unknowns)" :
                      " (one solve per column)")
                << std::endl;
        }

      // Rigid modes left free by the supports: u = K^+ f + R alpha, with the
      // equilibrium R^T (f_ext + f_contact) = 0 joining the BDE system.
      RigidModeColumns modes =
        rigid_mode_columns<dim>(pair_list, bodies, m, context, log);
      const Eigen::MatrixXd &GL = modes.G;

      // Pairs whose two points are both held by supports carry no
      // information: their flexibility rows and rigid-mode rows vanish
      // (to round-off: 1e-12 of the largest entry). Leave them out (a pinned
      // point of a floating body keeps its rigid motion, so it stays).
      double max_diag = 0., max_g = 0.;
      for (unsigned int i = 0; i < m * nc; ++i)
        max_diag = std::max(max_diag, FL(i, i));
      if (GL.size() > 0)
        max_g = GL.cwiseAbs().maxCoeff();
      std::vector<unsigned int> keep;
      for (unsigned int i = 0; i < nc; ++i)
        {
          const double g_row =
            (GL.cols() > 0 ? GL.row(m * i).cwiseAbs().maxCoeff() : 0.);
          if (FL(m * i, m * i) > 1e-12 * max_diag || g_row > 1e-12 * max_g)
            keep.push_back(i);
        }
      CondensedContact<dim> result =
        kept_pairs_contact(pair_list, keep, modes, m, context);
      ContactProblem &problem = result.problem;
      Eigen::MatrixXd W;
      if (keep.size() == nc)
        W = std::move(FL);
      else
        {
          W.resize(m * keep.size(), m * keep.size());
          for (unsigned int i = 0; i < keep.size(); ++i)
            for (unsigned int j = 0; j < keep.size(); ++j)
              W.block(m * i, m * j, m, m) =
                FL.block(m * keep[i], m * keep[j], m, m);
          FL = Eigen::MatrixXd();
        }
      // |W - W^T| / |W|, and W made exactly symmetric, in place.
      const double w_norm    = W.norm();
      double       asymmetry = 0.;
      for (Eigen::Index j = 0; j < W.cols(); ++j)
        for (Eigen::Index i = j + 1; i < W.rows(); ++i)
          {
            const double d = W(i, j) - W(j, i);
            asymmetry += 2. * d * d;
            W(i, j) = W(j, i) = 0.5 * (W(i, j) + W(j, i));
          }
      result.asymmetry = std::sqrt(asymmetry) / std::max(w_norm, 1e-300);
      problem.W        = std::move(W);
      problem.check_consistency();
      return result;
    }



    template <int dim>
    CondensedContact<dim>
    kept_pairs_contact(const std::vector<ContactPair<dim>> &pair_list,
                       const std::vector<unsigned int>     &keep,
                       const RigidModeColumns              &modes,
                       const unsigned int                   m,
                       const std::string                   &context)
    {
      AssertThrow(!keep.empty(),
                  base::ExcInput(context +
                                 ": every contact pair is held by supports on "
                                 "both sides; nothing can touch."));
      CondensedContact<dim> result;
      result.n_dropped                = pair_list.size() - keep.size();
      result.alpha_modes              = modes.alpha_modes;
      result.alpha_basis              = modes.basis;
      result.rigid_mode_loads         = modes.loads;
      result.rigid_mode_history_loads = modes.history_loads;
      ContactProblem &problem         = result.problem;
      problem.G.resize(m * keep.size(), modes.G.cols());
      for (unsigned int i = 0; i < keep.size(); ++i)
        {
          result.pairs.push_back(pair_list[keep[i]]);
          problem.G.middleRows(m * i, m) = modes.G.middleRows(m * keep[i], m);
        }
      problem.n_contacts   = result.pairs.size();
      problem.n_components = m;
      problem.q            = Eigen::VectorXd::Zero(m * result.pairs.size());
      for (const ContactPair<dim> &pair : result.pairs)
        problem.mu.push_back(pair.friction_coefficient);
      problem.name = context;
      problem.b    = Eigen::VectorXd::Zero(modes.G.cols());
      return result;
    }



    template RigidModeColumns
    rigid_mode_columns(const std::vector<ContactPair<2>> &,
                       const std::vector<const discretization::Body<2> *> &,
                       const unsigned int,
                       const std::string &,
                       std::ostream &);
    template RigidModeColumns
    rigid_mode_columns(const std::vector<ContactPair<3>> &,
                       const std::vector<const discretization::Body<3> *> &,
                       const unsigned int,
                       const std::string &,
                       std::ostream &);
    template CondensedContact<2>
    kept_pairs_contact(const std::vector<ContactPair<2>> &,
                       const std::vector<unsigned int> &,
                       const RigidModeColumns &,
                       const unsigned int,
                       const std::string &);
    template CondensedContact<3>
    kept_pairs_contact(const std::vector<ContactPair<3>> &,
                       const std::vector<unsigned int> &,
                       const RigidModeColumns &,
                       const unsigned int,
                       const std::string &);
    template CondensedContact<2>
    condense(const std::vector<ContactPair<2>> &,
             const std::vector<const discretization::Body<2> *> &,
             const unsigned int,
             const std::string &,
             std::ostream &,
             const bool);
    template CondensedContact<3>
    condense(const std::vector<ContactPair<3>> &,
             const std::vector<const discretization::Body<3> *> &,
             const unsigned int,
             const std::string &,
             std::ostream &,
             const bool);
  } // namespace contact
} // namespace igabde
