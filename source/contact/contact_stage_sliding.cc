// Finite sliding (Contact/Sliding = finite): the contact stage's pairs on
// the current configuration. At the start of every load step after the
// first, the pairs are formed on the last step's configuration (which slave
// points or basis functions face a master there); during the step's solve,
// the operator forms the same pairs again at every Newton iterate (their
// master points, frames and gaps) through pairs_at().

#include <igabde/contact/contact_stage.h>

#include <algorithm>
#include <map>

namespace igabde
{
  namespace contact
  {
    namespace
    {
      /// Body::reset_surfaces() on every body when it leaves scope (an
      /// input error in a pairing included).
      template <int dim>
      class MovedSurfaces
      {
      public:
        MovedSurfaces(
          const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies,
          const std::vector<Vector<double>>                             &u)
          : bodies(bodies)
        {
          for (unsigned int b = 0; b < bodies.size(); ++b)
            bodies[b]->move_surfaces(u[b]);
        }

        ~MovedSurfaces()
        {
          for (const auto &body : bodies)
            body->reset_surfaces();
        }

      private:
        const std::vector<std::unique_ptr<discretization::Body<dim>>> &bodies;
      };
    } // namespace



    template <int dim>
    std::vector<ContactPair<dim>>
    ContactStage<dim>::pairs_on(
      const std::vector<Vector<double>>                       &u,
      const std::vector<double>                               &factors,
      const std::vector<std::vector<types::global_dof_index>> &keys) const
    {
      std::vector<ContactPair<dim>> result;
      pairs_with_derivatives_on(u, factors, keys, result, nullptr);
      return result;
    }



    template <int dim>
    bool
    ContactStage<dim>::pairs_with_derivatives_on(
      const std::vector<Vector<double>>                       &u,
      const std::vector<double>                               &factors,
      const std::vector<std::vector<types::global_dof_index>> &keys,
      std::vector<ContactPair<dim>>                           &result,
      std::vector<PairDerivatives<dim>> *derivatives) const
    {
      AssertDimension(u.size(), bodies.size());
      const bool restricted = !keys.empty();
      Assert(!restricted || keys.size() == settings.interactions.size(),
             ExcInternalError());
      Assert(derivatives == nullptr || restricted, ExcInternalError());
      const MovedSurfaces<dim> moved(bodies, u);
      result.clear();
      if (derivatives != nullptr)
        derivatives->clear();
      for (unsigned int k = 0; k < settings.interactions.size(); ++k)
        {
          if (restricted && keys[k].empty())
            continue;
          const ContactInteraction &c          = settings.interactions[k];
          const bool                deformable = c.master_body < bodies.size();
          // The master's samples on its moved surface, or the obstacle
          // where its motion puts it.
          std::unique_ptr<ContactSurface<dim>> moved_master;
          if (deformable)
            moved_master =
              std::make_unique<BodyFace<dim>>(*bodies[c.master_body],
                                              c.master_faces);
          else if (obstacles[c.obstacle]->moves())
            moved_master =
              std::make_unique<PlacedObstacle<dim>>(*obstacles[c.obstacle],
                                                    factors);
          const ContactSurface<dim> &master =
            moved_master ?
              *moved_master :
              static_cast<const ContactSurface<dim> &>(*obstacles[c.obstacle]);
          const std::string context = settings.interactions.size() == 1 ?
                                        settings.context :
                                        settings.context + " (" + c.name + ")";
          std::vector<ContactPair<dim>> pairs;
          if (derivatives != nullptr)
            {
              std::vector<PairDerivatives<dim>> d;
              if (!pairings[k]->make_pairs_with_derivatives(
                    *bodies[c.slave_body],
                    c.slave_faces,
                    master,
                    context,
                    keys[k],
                    pairs,
                    d))
                return false;
              AssertDimension(d.size(), pairs.size());
              for (auto &entry : d)
                derivatives->push_back(std::move(entry));
            }
          else
            pairs = restricted ?
                      pairings[k]->make_pairs_of(*bodies[c.slave_body],
                                                 c.slave_faces,
                                                 master,
                                                 context,
                                                 keys[k]) :
                      pairings[k]->make_pairs(*bodies[c.slave_body],
                                              c.slave_faces,
                                              master,
                                              context);
          append_pairs(std::move(pairs), k, result);
        }
      return true;
    }



    template <int dim>
    std::vector<std::pair<unsigned int, types::global_dof_index>>
    ContactStage<dim>::pair_keys() const
    {
      std::vector<std::pair<unsigned int, types::global_dof_index>> keys;
      for (const ContactPair<dim> &pair : pair_list)
        keys.emplace_back(pair.interaction, pair.slave_key);
      return keys;
    }



    template <int dim>
    std::vector<Vector<double>>
    ContactStage<dim>::from_paired_configuration(
      const std::vector<Vector<double>> &v) const
    {
      std::vector<Vector<double>> result = v;
      if (paired_at.size() == v.size())
        for (unsigned int b = 0; b < v.size(); ++b)
          result[b] -= paired_at[b];
      return result;
    }



    template <int dim>
    void
    ContactStage<dim>::form_step_pairs(TimerOutput &timer)
    {
      if (!has_previous)
        return;
      std::map<std::pair<unsigned int, types::global_dof_index>, unsigned int>
        before;
      for (unsigned int i = 0; i < x_keys.size(); ++i)
        before[x_keys[i]] = i;
      const Eigen::VectorXd            p_before      = x.p;
      const std::vector<ContactStatus> status_before = status;
      std::map<std::pair<unsigned int, types::global_dof_index>, Tensor<2, dim>>
        frame_before;
      for (const ContactPair<dim> &pair : pair_list)
        frame_before[{pair.interaction, pair.slave_key}] = pair.frame;
      {
        TimerOutput::Scope t(timer, "contact: pairs");
        pair_list = pairs_on(sliding_u, sliding_factors);
      }
      // The tangents of the pairs formed again follow the last step's, so
      // that the carried friction forces keep their directions.
      for (ContactPair<dim> &pair : pair_list)
        if (const auto it =
              frame_before.find({pair.interaction, pair.slave_key});
            it != frame_before.end())
          pair.frame = local_frame(pair.frame[0], it->second);
      paired_at      = sliding_u;
      paired_factors = sliding_factors;
      {
        TimerOutput::Scope t(timer, prepare_section);
        contact_path->prepare(pair_list, contact);
      }
      pair_list = contact.pairs;
      // The last step's forces and states where the same slave part is
      // paired again; the pairs new to the set start open.
      const unsigned int n = pair_list.size();
      x.p                  = Eigen::VectorXd::Zero(m * n);
      status.assign(n, ContactStatus::open);
      const auto keys = pair_keys();
      for (unsigned int i = 0; i < n; ++i)
        if (const auto it = before.find(keys[i]); it != before.end())
          {
            const unsigned int j = it->second;
            if (m * (j + 1) <= p_before.size())
              x.p.segment(m * i, m) = p_before.segment(m * j, m);
            if (j < status_before.size())
              status[i] = status_before[j];
          }
      x_keys            = keys;
      x.alpha           = Eigen::VectorXd::Zero(contact.problem.n_alpha());
      previous_external = Eigen::VectorXd::Zero(m * n);
    }



    template <int dim>
    std::vector<ContactPair<dim>>
    ContactStage<dim>::pairs_at(const Eigen::VectorXd &w) const
    {
      return pairs_at(w, nullptr);
    }



    template <int dim>
    std::vector<ContactPair<dim>>
    ContactStage<dim>::pairs_of(const Eigen::VectorXd           &w,
                                const std::vector<unsigned int> &indices) const
    {
      return pairs_at(w, &indices);
    }



    template <int dim>
    std::vector<Vector<double>>
    ContactStage<dim>::configuration_at(const Eigen::VectorXd &w) const
    {
      std::vector<Vector<double>> config = sliding_base;
      unsigned int                offset = 0;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          if (config[b].size() != bodies[b]->n_dofs())
            config[b].reinit(bodies[b]->n_dofs());
          for (unsigned int i = 0; i < bodies[b]->n_dofs(); ++i)
            config[b][i] += w[offset + i];
          offset += bodies[b]->n_dofs();
        }
      return config;
    }



    template <int dim>
    Tensor<1, dim>
    ContactStage<dim>::step_slip_of(
      const ContactPair<dim>            &pair,
      const std::vector<Vector<double>> &relative) const
    {
      // The step's slip: the slave point's displacement over the step
      // against the master material point of the step's pair, whose
      // slave point faced it at the step's start (the convected
      // coordinate held over the step).
      Tensor<1, dim> du = pair.op1.displacement(relative[pair.slave_body]);
      if (pair.master_body < bodies.size())
        du -= pair.op2.displacement(relative[pair.master_body]);
      else if (const Obstacle<dim> *obstacle = obstacle_of(pair);
               obstacle != nullptr && obstacle->moves())
        {
          // The obstacle's material point the pair faced (at rest:
          // its point moved back from where the step's pairs put it)
          // carried to where the solve's factors put it.
          const Point<dim> c = obstacle->pivot();
          const Point<dim> at_rest =
            c + transpose(obstacle->rotation(paired_factors)) *
                  (pair.x2 - c - obstacle->translation(paired_factors));
          du -= obstacle->placed(at_rest, solve_factors) - pair.x2;
        }
      return du;
    }



    template <int dim>
    std::vector<ContactPair<dim>>
    ContactStage<dim>::pairs_at(const Eigen::VectorXd           &w,
                                const std::vector<unsigned int> *indices) const
    {
      const std::vector<Vector<double>> config = configuration_at(w);
      // The step's pairs alone (all of them where @p indices is nullptr):
      // the pairing integrates only the slave elements their functions
      // live on, to the same numbers, and skips the rest of the slave
      // faces, which faced no master at the step's start.
      std::vector<std::vector<types::global_dof_index>> keys(
        settings.interactions.size());
      for (unsigned int j = 0;
           j < (indices != nullptr ? indices->size() : pair_list.size());
           ++j)
        {
          const ContactPair<dim> &pair =
            pair_list[indices != nullptr ? (*indices)[j] : j];
          keys[pair.interaction].push_back(pair.slave_key);
        }
      for (auto &list : keys)
        std::sort(list.begin(), list.end());
      std::map<std::pair<unsigned int, types::global_dof_index>, unsigned int>
                                    formed_index;
      std::vector<ContactPair<dim>> formed =
        pairs_on(config, solve_factors, keys);
      for (unsigned int j = 0; j < formed.size(); ++j)
        formed_index[{formed[j].interaction, formed[j].slave_key}] = j;
      const std::vector<Vector<double>> relative =
        from_paired_configuration(config);
      std::vector<ContactPair<dim>> result;
      const unsigned int            n =
        indices != nullptr ? indices->size() : pair_list.size();
      result.reserve(n);
      for (unsigned int j = 0; j < n; ++j)
        {
          const ContactPair<dim> &pair =
            pair_list[indices != nullptr ? (*indices)[j] : j];
          const Tensor<1, dim> du = step_slip_of(pair, relative);
          const auto it = formed_index.find({pair.interaction, pair.slave_key});
          if (it != formed_index.end())
            {
              result.push_back(formed[it->second]);
              result.back().frame =
                local_frame(result.back().frame[0], pair.frame);
              result.back().step_slip = du;
              continue;
            }
          // No longer facing the master there: the step's pair, its gap
          // at the configuration along its own linearisation.
          ContactPair<dim> kept = pair;
          kept.gap += pair.frame[0] * du;
          kept.step_slip = du;
          result.push_back(std::move(kept));
        }
      return result;
    }



    template <int dim>
    bool
    ContactStage<dim>::linearization_of(
      const Eigen::VectorXd               &w,
      const std::vector<unsigned int>     &indices,
      std::vector<PairLinearization<dim>> &result) const
    {
      using Unknown  = typename PairLinearization<dim>::Unknown;
      using Gradient = typename PairLinearization<dim>::Gradient;
      const std::vector<Vector<double>> config = configuration_at(w);
      std::vector<std::vector<types::global_dof_index>> keys(
        settings.interactions.size());
      for (const unsigned int i : indices)
        keys[pair_list[i].interaction].push_back(pair_list[i].slave_key);
      for (auto &list : keys)
        std::sort(list.begin(), list.end());
      std::vector<ContactPair<dim>>     formed;
      std::vector<PairDerivatives<dim>> derivatives;
      if (!pairs_with_derivatives_on(config,
                                     solve_factors,
                                     keys,
                                     formed,
                                     &derivatives))
        return false;
      std::map<std::pair<unsigned int, types::global_dof_index>, unsigned int>
        formed_index;
      for (unsigned int j = 0; j < formed.size(); ++j)
        formed_index[{formed[j].interaction, formed[j].slave_key}] = j;
      const std::vector<Vector<double>> relative =
        from_paired_configuration(config);

      result.clear();
      result.reserve(indices.size());
      for (const unsigned int i : indices)
        {
          const ContactPair<dim> &step_pair = pair_list[i];
          PairLinearization<dim>  L;
          // The step's slip by the unknowns: the step's operators.
          const bool deformable = step_pair.master_body < bodies.size();
          for (unsigned int c = 0; c < dim; ++c)
            {
              for (unsigned int k = 0; k < step_pair.op1.weights.size(); ++k)
                L.slip[c].emplace_back(Unknown(step_pair.slave_body,
                                               step_pair.op1.dofs[k][c]),
                                       step_pair.op1.weights[k]);
              if (deformable)
                for (unsigned int k = 0; k < step_pair.op2.weights.size(); ++k)
                  L.slip[c].emplace_back(Unknown(step_pair.master_body,
                                                 step_pair.op2.dofs[k][c]),
                                         -step_pair.op2.weights[k]);
            }
          const Tensor<1, dim> du = step_slip_of(step_pair, relative);
          const auto           it =
            formed_index.find({step_pair.interaction, step_pair.slave_key});
          if (it == formed_index.end())
            {
              // Kept along its own linearisation: gap + frame[0] . du.
              L.pair = step_pair;
              L.pair.gap += step_pair.frame[0] * du;
              L.pair.step_slip = du;
              for (unsigned int c = 0; c < dim; ++c)
                for (const auto &[u, v] : L.slip[c])
                  L.gap.emplace_back(u, step_pair.frame[0][c] * v);
              L.op1.resize(L.pair.op1.weights.size());
              L.op2.resize(L.pair.op2.weights.size());
              result.push_back(std::move(L));
              continue;
            }
          L.pair           = formed[it->second];
          L.pair.frame     = local_frame(L.pair.frame[0], step_pair.frame);
          L.pair.step_slip = du;
          const PairDerivatives<dim> &d = derivatives[it->second];
          // The pairing's unknowns (0: slave, 1: master) as (body, dof).
          const auto body_of =
            [&](const typename PairDerivatives<dim>::Unknown &u) {
              return Unknown(u.first == 0 ? L.pair.slave_body :
                                            L.pair.master_body,
                             u.second);
            };
          const auto mapped =
            [&](const typename PairDerivatives<dim>::Gradient &g) {
              Gradient out;
              out.reserve(g.size());
              for (const auto &[u, v] : g)
                out.emplace_back(body_of(u), v);
              return out;
            };
          L.gap = mapped(d.gap);
          for (const auto &g : d.op1)
            L.op1.push_back(mapped(g));
          for (const auto &g : d.op2)
            L.op2.push_back(mapped(g));
          // The frame's by the normal's.
          std::map<Unknown, Tensor<1, dim>> dn;
          for (unsigned int e = 0; e < dim; ++e)
            for (const auto &[u, v] : d.normal[e])
              dn[body_of(u)][e] += v;
          for (const auto &[u, dn_u] : dn)
            {
              const Tensor<2, dim> dT =
                local_frame_change(L.pair.frame[0], step_pair.frame, dn_u);
              for (unsigned int r = 0; r < dim; ++r)
                for (unsigned int c = 0; c < dim; ++c)
                  if (dT[r][c] != 0.)
                    L.frame[r][c].emplace_back(u, dT[r][c]);
            }
          result.push_back(std::move(L));
        }
      return true;
    }



    template std::vector<std::pair<unsigned int, types::global_dof_index>>
    ContactStage<2>::pair_keys() const;
    template std::vector<std::pair<unsigned int, types::global_dof_index>>
    ContactStage<3>::pair_keys() const;
    template std::vector<Vector<double>>
    ContactStage<2>::from_paired_configuration(
      const std::vector<Vector<double>> &) const;
    template std::vector<Vector<double>>
    ContactStage<3>::from_paired_configuration(
      const std::vector<Vector<double>> &) const;
    template void
    ContactStage<2>::form_step_pairs(TimerOutput &);
    template void
    ContactStage<3>::form_step_pairs(TimerOutput &);
    template std::vector<ContactPair<2>>
    ContactStage<2>::pairs_at(const Eigen::VectorXd &) const;
    template std::vector<ContactPair<3>>
    ContactStage<3>::pairs_at(const Eigen::VectorXd &) const;
    template std::vector<ContactPair<2>>
    ContactStage<2>::pairs_of(const Eigen::VectorXd &,
                              const std::vector<unsigned int> &) const;
    template std::vector<ContactPair<3>>
    ContactStage<3>::pairs_of(const Eigen::VectorXd &,
                              const std::vector<unsigned int> &) const;
    template std::vector<ContactPair<2>>
    ContactStage<2>::pairs_at(const Eigen::VectorXd &,
                              const std::vector<unsigned int> *) const;
    template std::vector<ContactPair<3>>
    ContactStage<3>::pairs_at(const Eigen::VectorXd &,
                              const std::vector<unsigned int> *) const;
    template bool
    ContactStage<2>::linearization_of(
      const Eigen::VectorXd &,
      const std::vector<unsigned int> &,
      std::vector<PairLinearization<2>> &) const;
    template bool
    ContactStage<3>::linearization_of(
      const Eigen::VectorXd &,
      const std::vector<unsigned int> &,
      std::vector<PairLinearization<3>> &) const;
    template std::vector<ContactPair<2>>
    ContactStage<2>::pairs_on(
      const std::vector<Vector<double>> &,
      const std::vector<double> &,
      const std::vector<std::vector<types::global_dof_index>> &) const;
    template std::vector<ContactPair<3>>
    ContactStage<3>::pairs_on(
      const std::vector<Vector<double>> &,
      const std::vector<double> &,
      const std::vector<std::vector<types::global_dof_index>> &) const;
  } // namespace contact
} // namespace igabde
