// Finite sliding on the full path: the pairs formed again at every
// iterate (update_geometry()) and the Newton matrix's derivatives of the
// pairs by the configuration (linearize_geometry()).

#include <igabde/base/utilities.h>

#include <igabde/coupled/coupled_system.h>

#include <algorithm>
#include <map>
#include <tuple>

namespace igabde
{
  namespace coupled
  {
    template <int dim>
    void
    CoupledSystem<dim>::set_finite_sliding(
      const contact::FiniteSliding<dim> &sliding)
    {
      // The scene reader refuses the Krylov solver with finite sliding.
      AssertThrow(!krylov,
                  ExcMessage("Contact/Sliding = finite factorises the Newton "
                             "matrix (Contact/Full system solver = mumps or "
                             "klu)"));
      // The rigid-mode columns G would follow the pairs too.
      AssertThrow(n_alpha == 0,
                  base::ExcInput(
                    "Contact/Sliding = finite with a body that only its "
                    "contacts hold (a free rigid mode): hold every body by "
                    "Supports, Point supports or Face motions"));
      Assert(sliding.q != nullptr, ExcInternalError());
      this->sliding = sliding;
      geometry_at.resize(0);
      // The pairs are formed again once the bodies have moved by more than
      // 1e-8 of the smallest mean element size: a pairing is exact to
      // about 1e-10 of an element (the weighted gap's element cuts), so
      // that below this the new pairs would differ from the last ones by
      // their own round-off, and the Newton iteration would stall on it.
      const double h =
        *std::min_element(element_size.begin(), element_size.end());
      geometry_tolerance = 1e-8 * h;
    }



    template <int dim>
    void
    CoupledSystem<dim>::update_geometry(const contact::ContactIterate &x)
    {
      if (!sliding.pairs_at)
        return;
      // The geometric tangent belongs to the linearisation's iterate.
      geometric_valid = false;
      if (geometry_at.size() == x.w.size() &&
          (x.w - geometry_at).lpNorm<Eigen::Infinity>() <= geometry_tolerance)
        return;
      pairs_now = sliding.pairs_at(x.w);
      const std::vector<contact::ContactPair<dim>> &pairs = pairs_now;
      AssertDimension(pairs.size(), n_pairs);
      const auto old_rows = C_rows;
      set_C_rows(pairs);
      // The Newton matrix's pattern follows the master points into other
      // elements; MUMPS' analysis then starts afresh.
      bool same_pattern = true;
      for (unsigned int r = 0; r < C_rows.size() && same_pattern; ++r)
        {
          same_pattern = C_rows[r].size() == old_rows[r].size();
          for (unsigned int k = 0; k < C_rows[r].size() && same_pattern; ++k)
            same_pattern = C_rows[r][k].first == old_rows[r][k].first;
        }
      if (!same_pattern)
        {
          direct.reset();
          direct_problem.reset();
          build_pattern();
        }
      // u = C w + q + offset is the pairs' displacement at w: the gap at
      // its configuration in the normal rows, and in the tangential rows
      // the step's slip on the current tangents. The Newton matrix keeps
      // C at the current master points (where the forces act): the slip's
      // derivative by the master's unknowns is the step's master point's,
      // which differs by the master's strain over the step's slip.
      const Eigen::VectorXd  Cw = apply_C(x.w);
      const Eigen::VectorXd &q  = *sliding.q;
      offset                    = Eigen::VectorXd::Zero(d * n_pairs);
      for (unsigned int i = 0; i < n_pairs; ++i)
        {
          offset[d * i] = pairs[i].gap - Cw[d * i] - q[d * i];
          for (unsigned int s = 1; s < d; ++s)
            offset[d * i + s] = pairs[i].frame[s] * pairs[i].step_slip -
                                Cw[d * i + s] - q[d * i + s];
        }
      geometry_at = x.w;
    }



    template <int dim>
    void
    CoupledSystem<dim>::forget_geometry()
    {
      geometry_at.resize(0);
      geometric_valid = false;
      extra_pattern.clear();
    }



    template <int dim>
    const Eigen::VectorXd *
    CoupledSystem<dim>::displacement_offset() const
    {
      return sliding.pairs_at ? &offset : nullptr;
    }


    template <int dim>
    void
    CoupledSystem<dim>::linearize_geometry(const contact::ContactIterate &x)
    {
      const bool full =
        sliding.tangent == contact::SlidingTangent::full ||
        sliding.tangent == contact::SlidingTangent::differences ||
        (sliding.tangent == contact::SlidingTangent::adaptive &&
         exact_tangent_wanted);
      if (!sliding.pairs_at || !full)
        return;
      update_geometry(x);
      const std::vector<contact::ContactPair<dim>> &pairs = pairs_now;
      AssertDimension(x.p.size(), d * n_pairs);

      // The pairs whose derivatives the Newton matrix takes: those that
      // carry a force or nearly touch. The law's rows of the others hold
      // their forces at zero whatever their gaps, and they add no force to
      // the displacement rows; their rows keep C.
      const double h_min =
        *std::min_element(element_size.begin(), element_size.end());
      std::vector<unsigned int> active;
      std::vector<bool>         is_active(n_pairs, false);
      for (unsigned int i = 0; i < n_pairs; ++i)
        if (x.p.segment(d * i, d).squaredNorm() > 0. ||
            pairs[i].gap < 0.1 * h_min)
          {
            active.push_back(i);
            is_active[i] = true;
          }

      J_rows.assign(d * n_pairs, {});
      for (unsigned int i = 0; i < n_pairs; ++i)
        if (!is_active[i])
          for (unsigned int s = 0; s < d; ++s)
            J_rows[d * i + s] = C_rows[d * i + s];
      std::map<std::pair<unsigned int, unsigned int>, double> K;
      std::vector<contact::PairLinearization<dim>>            linearized;
      if (sliding.tangent != contact::SlidingTangent::differences &&
          sliding.linearization_of &&
          sliding.linearization_of(x.w, active, linearized))
        add_closed_form_tangent(x, active, linearized, K);
      else
        add_difference_tangent(x, pairs, active, K);
      for (auto &row : J_rows)
        std::sort(row.begin(), row.end());
      geometric_entries.clear();
      for (const auto &[entry, v] : K)
        geometric_entries.emplace_back(entry.first, entry.second, v);
      geometric_at    = x.w;
      geometric_valid = true;

      // Entries the pattern of K and C does not hold: the pattern again,
      // and MUMPS' analysis, where some are new.
      std::vector<std::pair<unsigned int, unsigned int>> entries;
      for (unsigned int r = 0; r < J_rows.size(); ++r)
        for (const auto &[g, v] : J_rows[r])
          entries.emplace_back(n_u + r, g);
      for (const auto &[entry, v] : K)
        entries.push_back(entry);
      std::sort(entries.begin(), entries.end());
      if (!std::includes(extra_pattern.begin(),
                         extra_pattern.end(),
                         entries.begin(),
                         entries.end()))
        {
          std::vector<std::pair<unsigned int, unsigned int>> merged;
          std::set_union(extra_pattern.begin(),
                         extra_pattern.end(),
                         entries.begin(),
                         entries.end(),
                         std::back_inserter(merged));
          extra_pattern = std::move(merged);
          direct.reset();
          direct_problem.reset();
          build_pattern();
        }
    }



    template <int dim>
    void
    CoupledSystem<dim>::add_closed_form_tangent(
      const contact::ContactIterate                           &x,
      const std::vector<unsigned int>                         &active,
      const std::vector<contact::PairLinearization<dim>>      &linearized,
      std::map<std::pair<unsigned int, unsigned int>, double> &K)
    {
      AssertDimension(linearized.size(), active.size());
      // A body's unknown in the system's numbering, or none where it is
      // held (or the body is not deformable).
      const auto global =
        [&](const typename contact::PairLinearization<dim>::Unknown &u)
        -> unsigned int {
        if (u.first >= bodies.size())
          return numbers::invalid_unsigned_int;
        const unsigned int g = offsets[u.first] + u.second;
        return held[g] ? numbers::invalid_unsigned_int : g;
      };
      for (unsigned int j = 0; j < active.size(); ++j)
        {
          const unsigned int                     i    = active[j];
          const contact::PairLinearization<dim> &L    = linearized[j];
          const contact::ContactPair<dim>       &pair = L.pair;
          // The rows of u: the gap, and the step's slip on the tangents,
          // d (T_s . slip) = dT_s . slip + T_s . d slip.
          std::map<unsigned int, double> row;
          for (const auto &[u, v] : L.gap)
            if (const unsigned int g = global(u);
                g != numbers::invalid_unsigned_int)
              row[g] += v;
          J_rows[d * i].assign(row.begin(), row.end());
          for (unsigned int s = 1; s < d; ++s)
            {
              row.clear();
              for (unsigned int c = 0; c < dim; ++c)
                {
                  for (const auto &[u, v] : L.frame[s][c])
                    if (const unsigned int g = global(u);
                        g != numbers::invalid_unsigned_int)
                      row[g] += v * pair.step_slip[c];
                  for (const auto &[u, v] : L.slip[c])
                    if (const unsigned int g = global(u);
                        g != numbers::invalid_unsigned_int)
                      row[g] += pair.frame[s][c] * v;
                }
              J_rows[d * i + s].assign(row.begin(), row.end());
            }
          // The pair's force on the unknowns, -sign R_k (T^T p)_c, by the
          // configuration: the operators' weights and the frame's turn.
          Tensor<1, dim> force;
          for (unsigned int s = 0; s < d; ++s)
            for (unsigned int c = 0; c < dim; ++c)
              force[c] += pair.frame[s][c] * x.p[d * i + s];
          std::map<unsigned int, Tensor<1, dim>> d_force;
          for (unsigned int s = 0; s < d; ++s)
            for (unsigned int c = 0; c < dim; ++c)
              for (const auto &[u, v] : L.frame[s][c])
                if (const unsigned int g = global(u);
                    g != numbers::invalid_unsigned_int)
                  d_force[g][c] += v * x.p[d * i + s];
          for (const unsigned int b : {pair.slave_body, pair.master_body})
            {
              if (b >= bodies.size())
                continue;
              double      sign = 0.;
              const auto &op   = *pair.operator_on(b, sign);
              const auto &d_op = &op == &pair.op1 ? L.op1 : L.op2;
              AssertDimension(d_op.size(), op.weights.size());
              for (unsigned int k = 0; k < op.weights.size(); ++k)
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    const unsigned int r = offsets[b] + op.dofs[k][c];
                    if (held[r])
                      continue;
                    for (const auto &[u, v] : d_op[k])
                      if (const unsigned int g = global(u);
                          g != numbers::invalid_unsigned_int)
                        K[{r, g}] -= sign * v * force[c];
                    for (const auto &[g, df] : d_force)
                      K[{r, g}] -= sign * op.weights[k] * df[c];
                  }
            }
        }
    }



    template <int dim>
    void
    CoupledSystem<dim>::add_difference_tangent(
      const contact::ContactIterate                           &x,
      const std::vector<contact::ContactPair<dim>>            &pairs,
      const std::vector<unsigned int>                         &active,
      std::map<std::pair<unsigned int, unsigned int>, double> &K)
    {
      std::vector<bool> is_active(n_pairs, false);
      for (const unsigned int i : active)
        is_active[i] = true;
      const double h_min =
        *std::min_element(element_size.begin(), element_size.end());
      // The free unknowns each pair reads: its gap, slip and frame depend

      // on those of its two operators (the slave's basis functions over
      // the pair's support, the master's at its points).
      std::vector<std::vector<unsigned int>> reads(n_pairs);
      for (const unsigned int i : active)
        {
          for (const unsigned int b :
               {pairs[i].slave_body, pairs[i].master_body})
            {
              if (b >= bodies.size())
                continue;
              double      sign = 0.;
              const auto &op   = *pairs[i].operator_on(b, sign);
              for (unsigned int k = 0; k < op.weights.size(); ++k)
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    const unsigned int g = offsets[b] + op.dofs[k][c];
                    if (!held[g])
                      reads[i].push_back(g);
                  }
            }
          std::sort(reads[i].begin(), reads[i].end());
          reads[i].erase(std::unique(reads[i].begin(), reads[i].end()),
                         reads[i].end());
        }

      // Colours: unknowns that no pair reads together share one, so that
      // one pairing per colour gives every pair's derivative by each of
      // its unknowns (Curtis, Powell and Reid's grouping of a sparse
      // Jacobian's columns).
      std::map<unsigned int, std::vector<unsigned int>> pairs_of;
      for (const unsigned int i : active)
        for (const unsigned int g : reads[i])
          pairs_of[g].push_back(i);
      std::map<unsigned int, unsigned int> colour;
      unsigned int                         n_colours = 0;
      for (const auto &[g, list] : pairs_of)
        {
          std::vector<bool> taken(n_colours + 1, false);
          for (const unsigned int i : list)
            for (const unsigned int h : reads[i])
              if (const auto it = colour.find(h); it != colour.end())
                taken[it->second] = true;
          unsigned int c = 0;
          while (taken[c])
            ++c;
          colour[g] = c;
          n_colours = std::max(n_colours, c + 1);
        }

      // What the Newton matrix differentiates: the rows of u (gap, and the
      // step's slip on the tangents) and each pair's force on the
      // unknowns, -C^T p at the iterate's forces.
      const auto values = [&](const contact::ContactPair<dim> &pair,
                              const unsigned int               s) {
        return s == 0 ? pair.gap : pair.frame[s] * pair.step_slip;
      };
      const auto forces = [&](const contact::ContactPair<dim> &pair,
                              const unsigned int               i) {
        std::map<unsigned int, double> f;
        for (const unsigned int b : {pair.slave_body, pair.master_body})
          {
            if (b >= bodies.size())
              continue;
            double      sign = 0.;
            const auto &op   = *pair.operator_on(b, sign);
            for (unsigned int k = 0; k < op.weights.size(); ++k)
              for (unsigned int c = 0; c < dim; ++c)
                {
                  const unsigned int g = offsets[b] + op.dofs[k][c];
                  if (held[g])
                    continue;
                  double v = 0.;
                  for (unsigned int s = 0; s < d; ++s)
                    if (std::abs(pair.frame[s][c]) > 1e-12)
                      v += pair.frame[s][c] * x.p[d * i + s];
                  f[g] -= sign * op.weights[k] * v;
                }
          }
        return f;
      };

      // A step of 1e-6 of the smallest element: the pairing's own
      // round-off (1e-10 of an element) is then 1e-4 of the derivative.
      const double                                h = 1e-6 * h_min;
      std::vector<std::map<unsigned int, double>> base(n_pairs);
      for (const unsigned int i : active)
        base[i] = forces(pairs[i], i);
      for (unsigned int c = 0; c < n_colours; ++c)
        {
          Eigen::VectorXd w = x.w;
          for (const auto &[g, colour_g] : colour)
            if (colour_g == c)
              w[g] += h;
          // The pairs that read an unknown of this colour, and the one
          // they read.
          std::vector<unsigned int> touched, unknown;
          for (const unsigned int i : active)
            for (const unsigned int r : reads[i])
              if (colour[r] == c)
                {
                  touched.push_back(i);
                  unknown.push_back(r);
                }
          std::vector<contact::ContactPair<dim>> moved;
          if (sliding.pairs_of)
            moved = sliding.pairs_of(w, touched);
          else
            {
              const std::vector<contact::ContactPair<dim>> all =
                sliding.pairs_at(w);
              AssertDimension(all.size(), n_pairs);
              for (const unsigned int i : touched)
                moved.push_back(all[i]);
            }
          AssertDimension(moved.size(), touched.size());
          for (unsigned int j = 0; j < touched.size(); ++j)
            {
              const unsigned int i = touched[j], g = unknown[j];
              for (unsigned int s = 0; s < d; ++s)
                {
                  const double v =
                    (values(moved[j], s) - values(pairs[i], s)) / h;
                  if (v != 0.)
                    J_rows[d * i + s].emplace_back(g, v);
                }
              std::map<unsigned int, double> f = forces(moved[j], i);
              for (const auto &[r, v] : base[i])
                f[r] -= v;
              for (const auto &[r, v] : f)
                if (v != 0.)
                  K[{r, g}] += v / h;
            }
        }
    }



    template <int dim>
    Eigen::VectorXd
    CoupledSystem<dim>::apply_C_derivative(const Eigen::VectorXd &v) const
    {
      if (!geometric_valid)
        return apply_C(v);
      AssertDimension(v.size(), n_u);
      return apply_rows(J_rows, v);
    }



    template <int dim>
    void
    CoupledSystem<dim>::add_geometric_term(const Eigen::VectorXd &v,
                                           Eigen::VectorXd       &r) const
    {
      if (geometric_valid)
        for (const auto &[row, column, value] : geometric_entries)
          r[row] += value * v[column];
    }



    template void
    CoupledSystem<2>::set_finite_sliding(const contact::FiniteSliding<2> &);
    template void
    CoupledSystem<3>::set_finite_sliding(const contact::FiniteSliding<3> &);
    template void
    CoupledSystem<2>::update_geometry(const contact::ContactIterate &);
    template void
    CoupledSystem<3>::update_geometry(const contact::ContactIterate &);
    template void
    CoupledSystem<2>::forget_geometry();
    template void
    CoupledSystem<3>::forget_geometry();
    template const Eigen::VectorXd *
    CoupledSystem<2>::displacement_offset() const;
    template const Eigen::VectorXd *
    CoupledSystem<3>::displacement_offset() const;
    template void
    CoupledSystem<2>::linearize_geometry(const contact::ContactIterate &);
    template void
    CoupledSystem<3>::linearize_geometry(const contact::ContactIterate &);
    template Eigen::VectorXd
    CoupledSystem<2>::apply_C_derivative(const Eigen::VectorXd &) const;
    template Eigen::VectorXd
    CoupledSystem<3>::apply_C_derivative(const Eigen::VectorXd &) const;
    template void
    CoupledSystem<2>::add_geometric_term(const Eigen::VectorXd &,
                                         Eigen::VectorXd &) const;
    template void
    CoupledSystem<3>::add_geometric_term(const Eigen::VectorXd &,
                                         Eigen::VectorXd &) const;
  } // namespace coupled
} // namespace igabde
