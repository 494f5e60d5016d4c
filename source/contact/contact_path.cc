#include <igabde/base/utilities.h>

#include <igabde/contact/contact_path.h>

#include <algorithm>
#include <sstream>

namespace igabde
{
  namespace contact
  {
    template <int dim>
    CondensedPath<dim>::CondensedPath(
      const std::vector<const discretization::Body<dim> *> &bodies,
      const unsigned int                                    n_components,
      const bool                                            schur,
      const std::string                                    &context,
      std::ostream                                         &log,
      const bool                                            progress)
      : bodies(bodies)
      , m(n_components)
      , schur(schur)
      , context(context)
      , log(log)
      , progress(progress)
    {}



    template <int dim>
    discretization::FactorizationRequest<dim>
    CondensedPath<dim>::factorization_request(
      const unsigned int                   b,
      const std::vector<ContactPair<dim>> &pairs) const
    {
      // The flexibility on the pairs and the field recovery solve with the
      // bodies' factors; K is read no more than the support reactions do.
      discretization::FactorizationRequest<dim> request;
      if (schur)
        for (const auto &pair : pairs)
          {
            double sign = 0.;
            if (const auto *op = pair.operator_on(b, sign))
              request.interface.push_back(*op);
          }
      request.matrix_read_afterwards = false;
      request.solves_afterwards      = true;
      return request;
    }



    template <int dim>
    void
    CondensedPath<dim>::prepare(const std::vector<ContactPair<dim>> &pairs,
                                CondensedContact<dim>               &contact)
    {
      contact   = condense<dim>(pairs, bodies, m, context, log, progress);
      condensed = std::make_unique<CondensedOperator>(contact.problem.W);
    }



    template <int dim>
    ContactOperator &
    CondensedPath<dim>::op()
    {
      return *condensed;
    }



    template <int dim>
    void
    CondensedPath<dim>::add_response(const std::vector<Vector<double>> &loads,
                                     const ContactIterate &,
                                     std::vector<Vector<double>> &u) const
    {
      // One solve per body on its factorisation.
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          std::vector<Vector<double>> column(1, loads[b]);
          bodies[b]->solve(column);
          u[b] += column[0];
        }
    }



    template <int dim>
    std::string
    CondensedPath<dim>::description(const CondensedContact<dim> &) const
    {
      return "";
    }



    template <int dim>
    CoupledPath<dim>::CoupledPath(
      const std::vector<const discretization::Body<dim> *> &bodies,
      const unsigned int                                    n_components,
      const CoupledFactory<dim>                            &factory,
      const std::string                                    &context,
      std::ostream                                         &log)
      : bodies(bodies)
      , m(n_components)
      , factory(factory)
      , context(context)
      , log(log)
    {
      AssertThrow(factory,
                  ExcMessage("the full contact path needs a coupled-system "
                             "factory (coupled::coupled_factory())"));
    }



    template <int dim>
    discretization::FactorizationRequest<dim>
    CoupledPath<dim>::factorization_request(
      const unsigned int,
      const std::vector<ContactPair<dim>> &) const
    {
      // The coupled system is assembled from every body's K on every rank
      // and factorised as a whole; the bodies only solve their load cases.
      discretization::FactorizationRequest<dim> request;
      request.matrix_read_afterwards = true;
      request.solves_afterwards      = false;
      return request;
    }



    template <int dim>
    void
    CoupledPath<dim>::prepare(const std::vector<ContactPair<dim>> &pair_list,
                              CondensedContact<dim>               &contact)
    {
      RigidModeColumns modes =
        rigid_mode_columns<dim>(pair_list, bodies, m, context, log);

      // Pairs whose points move with held unknowns only (and with no rigid
      // mode) carry no information; leave them out as condense() does.
      std::vector<unsigned int> keep;
      const double              max_g =
        modes.G.size() > 0 ? modes.G.cwiseAbs().maxCoeff() : 0.;
      for (unsigned int i = 0; i < pair_list.size(); ++i)
        {
          bool moves = false;
          for (unsigned int b = 0; b < bodies.size(); ++b)
            {
              double      sign = 0.;
              const auto *op   = pair_list[i].operator_on(b, sign);
              if (op == nullptr)
                continue;
              for (unsigned int k = 0; k < op->weights.size(); ++k)
                for (unsigned int c = 0; c < dim; ++c)
                  moves = moves || (op->weights[k] != 0. &&
                                    !bodies[b]->is_held(op->dofs[k][c]));
            }
          const double g_row =
            modes.G.cols() > 0 ? modes.G.row(m * i).cwiseAbs().maxCoeff() : 0.;
          if (moves || g_row > 1e-12 * max_g)
            keep.push_back(i);
        }
      contact = kept_pairs_contact(pair_list, keep, modes, m, context);
      FiniteSliding<dim> sliding;
      if (this->sliding.pairs_at)
        {
          // The path's pairs are the kept ones: pairs_at() gives all.
          AssertThrow(keep.size() == pair_list.size(),
                      ExcMessage(context +
                                 ": Contact/Sliding = finite "
                                 "with pairs whose points move with held "
                                 "unknowns only; hold fewer unknowns on the "
                                 "contact faces"));
          sliding   = this->sliding;
          sliding.q = &contact.problem.q;
        }
      coupled = factory(bodies, contact.pairs, m, contact.problem.G, sliding);
      static_cast<const ContactData &>(contact.problem).check_consistency();
    }



    template <int dim>
    ContactOperator &
    CoupledPath<dim>::op()
    {
      return *coupled;
    }



    template <int dim>
    void
    CoupledPath<dim>::add_response(const std::vector<Vector<double>> &,
                                   const ContactIterate        &x,
                                   std::vector<Vector<double>> &u) const
    {
      // Solved already: w holds the bodies' contact displacement.
      unsigned int offset = 0;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          for (unsigned int i = 0; i < bodies[b]->n_dofs(); ++i)
            u[b][i] += x.w[offset + i];
          offset += bodies[b]->n_dofs();
        }
    }



    template <int dim>
    std::string
    CoupledPath<dim>::description(const CondensedContact<dim> &contact) const
    {
      std::ostringstream s;
      s << "coupled system of " << coupled->n_dofs() << " displacement and "
        << contact.problem.n_rows() + contact.problem.n_alpha()
        << " contact unknowns, " << coupled->n_nonzeros()
        << " nonzeros in its Newton matrix";
      return s.str();
    }



    template <int dim>
    void
    CoupledPath<dim>::set_reference(const std::vector<Vector<double>> &u,
                                    const std::vector<double>         &factors)
    {
      if (!coupled->finite_strain())
        return;
      Eigen::VectorXd whole(coupled->n_dofs());
      unsigned int    offset = 0;
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          for (unsigned int i = 0; i < bodies[b]->n_dofs(); ++i)
            whole[offset + i] = u[b].size() > 0 ? u[b][i] : 0.;
          offset += bodies[b]->n_dofs();
        }
      coupled->set_reference(whole, factors);
    }



    template <int dim>
    void
    CoupledPath<dim>::set_finite_sliding(const FiniteSliding<dim> &sliding)
    {
      this->sliding = sliding;
    }



    template <int dim>
    double
    CoupledPath<dim>::n_nonzeros() const
    {
      return coupled ? coupled->n_nonzeros() : 0.;
    }



    template class CondensedPath<2>;
    template class CondensedPath<3>;
    template class CoupledPath<2>;
    template class CoupledPath<3>;
  } // namespace contact
} // namespace igabde
