#include <igabde/contact/contact_stage.h>

#include <algorithm>

// What the contact stage reports after a step: the pairs' states, its
// summary, and the small-sliding range figures.

namespace igabde
{
  namespace contact
  {
    template <int dim>
    std::optional<std::pair<double, Point<dim>>>
    ContactStage<dim>::largest_sliding(const std::vector<Vector<double>> &u,
                                       const std::vector<double> &factors) const
    {
      // Finite sliding forms the pairs on the current configuration.
      if (settings.finite_sliding)
        return std::nullopt;
      if (std::none_of(pair_list.begin(), pair_list.end(), [&](const auto &p) {
            return obstacle_of(p) == nullptr;
          }))
        return std::nullopt;
      return largest_tangential(u, factors, false);
    }



    template <int dim>
    std::optional<std::pair<double, Point<dim>>>
    ContactStage<dim>::largest_normal_turn(
      const std::vector<Vector<double>> &u,
      const std::vector<double>         &factors) const
    {
      if (settings.finite_sliding)
        return std::nullopt;
      if (std::none_of(pair_list.begin(), pair_list.end(), [&](const auto &p) {
            const Obstacle<dim> *obstacle = obstacle_of(p);
            return obstacle != nullptr && !obstacle->flat();
          }))
        return std::nullopt;
      return largest_tangential(u, factors, true);
    }



    template <int dim>
    std::pair<double, Point<dim>>
    ContactStage<dim>::largest_tangential(const std::vector<Vector<double>> &u,
                                          const std::vector<double> &factors,
                                          const bool over_radius) const
    {
      std::pair<double, Point<dim>> result(0., Point<dim>());
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        {
          const ContactPair<dim> &pair     = pair_list[i];
          const Obstacle<dim>    *obstacle = obstacle_of(pair);
          // Over the radius: the pairs on curved obstacles; else those on
          // deformable masters (a rigid plane's gap and normal stay exact
          // whatever the slide).
          if (!(pair_spacing[i] > 0.) ||
              (over_radius ? obstacle == nullptr || obstacle->flat() :
                             obstacle != nullptr))
            continue;
          const Tensor<1, dim> du =
            pair.op1.displacement(u[pair.slave_body]) -
            (obstacle ? obstacle->displacement(pair.x2, factors) :
                        pair.op2.displacement(u[pair.master_body]));
          const Tensor<1, dim> &n = pair_list[i].frame[0];
          // A pair open by more than its spacing cannot touch in this
          // configuration: where it now faces does not matter yet.
          if (pair_list[i].gap + du * n > pair_spacing[i])
            continue;
          const double ratio =
            (du - (du * n) * n).norm() /
            (over_radius ? obstacle->curvature_radius() : pair_spacing[i]);
          if (ratio > result.first)
            result = {ratio, pair_list[i].x1};
        }
      return result;
    }



    template <int dim>
    std::vector<PairState<dim>>
    ContactStage<dim>::pair_states() const
    {
      std::vector<PairState<dim>> states;
      if (status.empty())
        return states;
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        {
          PairState<dim> s;
          s.location          = pair_list[i].x1;
          s.material_location = s.location;
          if (settings.finite_sliding)
            {
              const auto &body    = *bodies[pair_list[i].slave_body];
              const auto &op      = pair_list[i].op1;
              s.material_location = Point<dim>();
              for (unsigned int k = 0; k < op.weights.size(); ++k)
                for (unsigned int c = 0; c < dim; ++c)
                  s.material_location[c] +=
                    op.weights[k] * body.dof_location(op.dofs[k][c])[c];
            }
          s.interaction = pair_list[i].interaction;
          s.slave_body  = pair_list[i].slave_body;
          s.normal      = pair_list[i].normal1;
          s.area        = pair_list[i].area;
          for (unsigned int k = 0; k < m; ++k)
            {
              s.force_local.push_back(x.p(m * i + k));
              s.displacement_local.push_back(u_rel(m * i + k));
            }
          s.force = global_force(i, x.p);
          for (unsigned int k = 1; k < m; ++k)
            s.slip += u_rel(m * i + k) * pair_list[i].frame[k];
          s.status = status[i];
          states.push_back(s);
        }
      return states;
    }



    template <int dim>
    ContactSummary
    ContactStage<dim>::summary() const
    {
      ContactSummary s;
      for (const auto &pair : pair_list)
        s.initial_gaps = s.initial_gaps || pair.gap > 0.;
      s.n_pairs        = pair_list.size();
      s.n_unknowns     = contact.problem.n_rows() + contact.problem.n_alpha();
      s.friction       = (m > 1);
      s.rigid_obstacle = !obstacles.empty();
      for (const auto &obstacle : obstacles)
        {
          s.obstacle_kind +=
            (s.obstacle_kind.empty() ? "" : ", ") + obstacle->kind();
          s.obstacle_moves = s.obstacle_moves || obstacle->moves();
        }
      s.n_interactions = settings.interactions.size();
      s.interaction_pairs.assign(s.n_interactions, 0);
      for (const auto &pair : pair_list)
        ++s.interaction_pairs[pair.interaction];
      s.floating_rigid_modes = contact.alpha_modes.size();
      s.pairs_left_out       = contact.n_dropped;
      for (const auto &pairing : pairings)
        {
          const PairingExclusions<dim> &e = pairing->exclusions();
          s.slave_candidates += e.candidates;
          s.left_out_not_facing += e.not_facing;
          s.left_out_outside += e.outside;
          s.left_out_unprojected += e.unprojected;
          s.left_out_degenerate += e.degenerate;
          s.left_out_beyond += e.beyond;
          s.left_out_of_quadrature =
            s.left_out_of_quadrature || e.quadrature_points;
        }
      s.algorithm                   = settings.solver.algorithm;
      s.path                        = resolved_path;
      s.path_reason                 = path_why;
      s.estimated_condensed_seconds = estimated_condensed_seconds;
      s.estimated_full_seconds      = estimated_full_seconds;
      s.cost_inputs                 = cost_inputs;
      s.coupled_nonzeros = contact_path ? contact_path->n_nonzeros() : 0.;
      s.warnings         = setup_warnings;
      return s;
    }



    template std::optional<std::pair<double, Point<2>>>
    ContactStage<2>::largest_sliding(const std::vector<Vector<double>> &,
                                     const std::vector<double> &) const;
    template std::optional<std::pair<double, Point<2>>>
    ContactStage<2>::largest_normal_turn(const std::vector<Vector<double>> &,
                                         const std::vector<double> &) const;
    template std::pair<double, Point<2>>
    ContactStage<2>::largest_tangential(const std::vector<Vector<double>> &,
                                        const std::vector<double> &,
                                        const bool) const;
    template std::vector<PairState<2>>
    ContactStage<2>::pair_states() const;
    template ContactSummary
    ContactStage<2>::summary() const;
    template std::optional<std::pair<double, Point<3>>>
    ContactStage<3>::largest_sliding(const std::vector<Vector<double>> &,
                                     const std::vector<double> &) const;
    template std::optional<std::pair<double, Point<3>>>
    ContactStage<3>::largest_normal_turn(const std::vector<Vector<double>> &,
                                         const std::vector<double> &) const;
    template std::pair<double, Point<3>>
    ContactStage<3>::largest_tangential(const std::vector<Vector<double>> &,
                                        const std::vector<double> &,
                                        const bool) const;
    template std::vector<PairState<3>>
    ContactStage<3>::pair_states() const;
    template ContactSummary
    ContactStage<3>::summary() const;
  } // namespace contact
} // namespace igabde
