#include <igabde/base/nearest_points.h>
#include <igabde/base/utilities.h>

#include <igabde/contact/master_side.h>
#include <igabde/contact/pairing.h>
#include <igabde/contact/weighted_gap_derivatives.h>

#include <deal.II/base/quadrature_lib.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

// The weighted-gap (mortar-like) pairing: one pair per basis function of
// the slave face, its integrals over the slave elements cut where the
// master's element edges project.

namespace igabde
{
  namespace contact
  {
    namespace
    {
      using internal::FaceProjector;
      using internal::MasterSide;

      /// The integrals of one slave basis function N_j.
      template <int dim>
      struct WeightedIntegrals
      {
        double                                    area = 0.;
        double                                    gap  = 0.;
        Tensor<1, dim>                            normal;
        Tensor<1, dim>                            x1, x2;
        std::map<types::global_dof_index, double> op1, op2;
      };



      /// Adds N_j R_A (for every A of @p op) times @p w to @p row, and
      /// remembers the unknowns of each A in @p dofs.
      template <int dim>
      void
      add_row(const discretization::PointOperator<dim>           &op,
              const double                                        w,
              std::map<types::global_dof_index, double>          &row,
              std::map<types::global_dof_index,
                       std::array<types::global_dof_index, dim>> &dofs)
      {
        for (unsigned int b = 0; b < op.weights.size(); ++b)
          if (op.weights[b] != 0.)
            {
              row[op.dofs[b][0]] += w * op.weights[b];
              dofs[op.dofs[b][0]] = op.dofs[b];
            }
      }



      /// The operator (1/A) row, without entries below round-off.
      template <int dim>
      discretization::PointOperator<dim>
      make_operator(
        const std::map<types::global_dof_index, double>          &row,
        const double                                              area,
        const std::map<types::global_dof_index,
                       std::array<types::global_dof_index, dim>> &dofs)
      {
        discretization::PointOperator<dim> op;
        for (const auto &[key, value] : row)
          if (std::abs(value / area) > 1e-14)
            {
              op.weights.push_back(value / area);
              op.dofs.push_back(dofs.at(key));
            }
        return op;
      }



      /**
       * The break points of the slave element [@p lo, @p hi] of face
       * @p slave_face in each face direction: its ends, and against a
       * deformable master the points where the projection of the element's
       * centre line crosses a master element edge or passes from one master
       * face to the next, so that every piece integrates a smooth
       * integrand.
       */
      template <int dim>
      std::array<std::vector<double>, dim - 1>
      element_cuts(const discretization::Body<dim> &slave_body,
                   const types::boundary_id         slave_face,
                   const Point<dim - 1>            &lo,
                   const Point<dim - 1>            &hi,
                   const MasterSide<dim>           &master)
      {
        constexpr unsigned int                   fd = dim - 1;
        std::array<std::vector<double>, dim - 1> cuts;
        for (unsigned int k = 0; k < fd; ++k)
          cuts[k] = {lo[k], hi[k]};
        if (master.projectors.empty())
          return cuts;
        // Cuts where the projection of the element's centre line in
        // direction k crosses a master element edge, or passes from
        // one master face to the next (an edge too).
        for (unsigned int k = 0; k < fd; ++k)
          {
            const auto slave_point = [&](const double t) {
              Point<fd> eta = 0.5 * (lo + hi);
              eta[k]        = t;
              return slave_body.face_point(slave_face, eta).location;
            };
            // The crossings of master face @p part's element edges
            // between t = a and b, both projected on that face.
            const auto cut_between = [&](const double       a,
                                         const double       b,
                                         const unsigned int part) {
              const auto &projector  = *master.projectors[part];
              const auto  master_eta = [&](const double t) {
                return projector.project(slave_point(t));
              };
              const Point<fd> at_a = master_eta(a);
              const Point<fd> at_b = master_eta(b);
              for (unsigned int c = 0; c < fd; ++c)
                {
                  const auto  &mb  = projector.grid.breaks[c];
                  const double tol = 1e-12 * (mb.back() - mb.front());
                  // The inner breaks strictly between the two ends' master
                  // coordinates (beyond round-off), found by bisection of
                  // the sorted breaks: the rest are not crossed, and a
                  // sweep over all of them made the search grow as the
                  // number of slave elements times the master's breaks.
                  const double low   = std::min(at_a[c], at_b[c]) + tol;
                  const double high  = std::max(at_a[c], at_b[c]) - tol;
                  const auto   first = std::max<std::size_t>(
                    std::upper_bound(mb.begin(), mb.end(), low) - mb.begin(),
                    1);
                  for (std::size_t i = first; i + 1 < mb.size() && mb[i] < high;
                       ++i)
                    {
                      // The crossing t of master_eta(t)[c] = mb[i],
                      // by TOMS 748 (Alefeld, Potra and Shi) on the
                      // bracket.
                      const double fa = at_a[c] - mb[i], fb = at_b[c] - mb[i];
                      if (!((fa > tol && fb < -tol) || (fa < -tol && fb > tol)))
                        continue;
                      std::uintmax_t max_iterations = 200;
                      const auto bracket = boost::math::tools::toms748_solve(
                        [&](const double t) {
                          return master_eta(t)[c] - mb[i];
                        },
                        a,
                        b,
                        fa,
                        fb,
                        // To 1e-10 of the element: far below what the
                        // quadrature's pieces need, and above the noise
                        // of the projections (1e-14 of the master face's
                        // extent, which on a fine mesh is more than 1e-14
                        // of one element: a tighter bracket then never
                        // closes and the solve ran to its iteration limit,
                        // so the cost per pair grew with the mesh).
                        [&](const double x, const double y) {
                          return std::abs(y - x) <= 1e-10 * (hi[k] - lo[k]);
                        },
                        max_iterations);
                      cuts[k].push_back(0.5 * (bracket.first + bracket.second));
                    }
                }
            };
            // From a to b: where the closest master face changes,
            // found by bisection, a cut; each stretch cut at its
            // face's edges.
            const auto part_at = [&](const double t) {
              return master.project(slave_point(t)).first;
            };
            double             a       = lo[k];
            unsigned int       part_a  = part_at(a);
            const unsigned int part_hi = part_at(hi[k]);
            for (unsigned int stretch = 0;
                 part_a != part_hi && stretch < master.projectors.size();
                 ++stretch)
              {
                double left = a, right = hi[k];
                while (right - left > 1e-14 * (hi[k] - lo[k]))
                  {
                    const double middle = 0.5 * (left + right);
                    (part_at(middle) == part_a ? left : right) = middle;
                  }
                const double t = 0.5 * (left + right);
                cut_between(a, t, part_a);
                cuts[k].push_back(t);
                a      = t;
                part_a = part_at(right);
              }
            cut_between(a, hi[k], part_a);
            std::sort(cuts[k].begin(), cuts[k].end());
            cuts[k].erase(std::unique(cuts[k].begin(),
                                      cuts[k].end(),
                                      [&](const double x, const double y) {
                                        return y - x <= 1e-13 * (hi[k] - lo[k]);
                                      }),
                          cuts[k].end());
          }
        return cuts;
      }



      /**
       * Basis functions of the face whose unknowns supports hold in every
       * component: their pressure goes straight into the support, on both
       * sides where Body 2 is held there too (a clamped edge lying in the
       * contact face, as in B2), and their pairs then make the flexibility
       * singular in the normal direction. As mortar methods do at a
       * Dirichlet boundary of the slave side, each is merged into the
       * nearest free function of the face (N_k + N_j: every integral
       * of WeightedIntegrals is linear in N_j, so the pairs' sums add up);
       * the merged basis still sums to one, so a uniform pressure stays
       * exact.
       */
      template <int dim>
      void
      merge_held_functions(
        const discretization::Body<dim>                           &slave_body,
        const double                                               total,
        std::map<types::global_dof_index, WeightedIntegrals<dim>> &integrals,
        const std::map<types::global_dof_index,
                       std::array<types::global_dof_index, dim>>  &dofs1,
        std::map<types::global_dof_index, internal::IntegralDerivatives<dim>>
          *derivatives)
      {
        std::vector<types::global_dof_index> held, free;
        for (const auto &[key, in] : integrals)
          if (in.area > 1e-12 * total)
            {
              bool supported = true;
              for (unsigned int c = 0; c < dim; ++c)
                supported =
                  supported && slave_body.is_supported(dofs1.at(key)[c]);
              (supported ? held : free).push_back(key);
            }
        if (!free.empty())
          for (const auto j : held)
            {
              const auto &in_j = integrals.at(j);
              const auto  x_j  = in_j.x1 / in_j.area;
              auto        best = free.front();
              double      dist = std::numeric_limits<double>::max();
              for (const auto k : free)
                {
                  const auto  &in_k = integrals.at(k);
                  const double d    = (in_k.x1 / in_k.area - x_j).norm();
                  if (d < dist)
                    {
                      dist = d;
                      best = k;
                    }
                }
              auto &in_k = integrals.at(best);
              in_k.area += in_j.area;
              in_k.gap += in_j.gap;
              in_k.normal += in_j.normal;
              in_k.x1 += in_j.x1;
              in_k.x2 += in_j.x2;
              for (const auto &[dof, value] : in_j.op1)
                in_k.op1[dof] += value;
              for (const auto &[dof, value] : in_j.op2)
                in_k.op2[dof] += value;
              integrals.erase(j);
              if (derivatives != nullptr)
                if (const auto it = derivatives->find(j);
                    it != derivatives->end())
                  {
                    (*derivatives)[best].add(it->second);
                    derivatives->erase(it);
                  }
            }
      }



      /**
       * A point of the slave element [@p lo, @p hi] at which none of the
       * element's basis functions vanishes: the B-splines are positive
       * inside their support, and FE_Q's Lagrange functions vanish only at
       * the other nodes, none of which sits at 1 - 1/sqrt(2) of the
       * element in every direction.
       */
      template <int dim>
      Point<dim - 1>
      generic_point(const Point<dim - 1> &lo, const Point<dim - 1> &hi)
      {
        Point<dim - 1> eta;
        for (unsigned int k = 0; k + 1 < dim; ++k)
          eta[k] = lo[k] + (1. - 1. / std::sqrt(2.)) * (hi[k] - lo[k]);
        return eta;
      }



      /// Whether one of the basis functions @p keys (sorted: their first
      /// unknowns) lives on the slave element [@p lo, @p hi].
      template <int dim>
      bool
      lives_on_element(const discretization::Body<dim>            &slave_body,
                       const types::boundary_id                    slave_face,
                       const Point<dim - 1>                       &lo,
                       const Point<dim - 1>                       &hi,
                       const std::vector<types::global_dof_index> &keys)
      {
        const auto s =
          slave_body.face_point(slave_face, generic_point<dim>(lo, hi));
        for (unsigned int a = 0; a < s.op.weights.size(); ++a)
          if (s.op.weights[a] != 0. &&
              std::binary_search(keys.begin(), keys.end(), s.op.dofs[a][0]))
            return true;
        return false;
      }



      /// Whether supports hold some basis function of the slave faces in
      /// every component (merge_held_functions()).
      template <int dim>
      bool
      holds_a_face_function(const discretization::Body<dim>       &slave_body,
                            const std::vector<types::boundary_id> &slave_faces)
      {
        for (const types::boundary_id slave_face : slave_faces)
          {
            const auto   grid = slave_body.face_grid(slave_face);
            unsigned int n    = 1;
            for (unsigned int k = 0; k + 1 < dim; ++k)
              n *= grid.breaks[k].size() - 1;
            for (unsigned int element = 0; element < n; ++element)
              {
                Point<dim - 1> lo, hi;
                unsigned int   rest = element;
                for (unsigned int k = 0; k + 1 < dim; ++k)
                  {
                    const unsigned int e = rest % (grid.breaks[k].size() - 1);
                    rest /= grid.breaks[k].size() - 1;
                    lo[k] = grid.breaks[k][e];
                    hi[k] = grid.breaks[k][e + 1];
                  }
                const auto s =
                  slave_body.face_point(slave_face, generic_point<dim>(lo, hi));
                for (unsigned int a = 0; a < s.op.weights.size(); ++a)
                  {
                    bool held = true;
                    for (unsigned int c = 0; c < dim; ++c)
                      held = held && slave_body.is_supported(s.op.dofs[a][c]);
                    if (held)
                      return true;
                  }
              }
          }
        return false;
      }
    } // namespace



    template <int dim>
    WeightedGapPairing<dim>::WeightedGapPairing(const bool dual)
      : dual(dual)
    {}



    template <int dim>
    std::vector<ContactPair<dim>>
    WeightedGapPairing<dim>::make_pairs(
      const discretization::Body<dim>       &slave_body,
      const std::vector<types::boundary_id> &slave_faces,
      const ContactSurface<dim>             &master,
      const std::string                     &context) const
    {
      return form_pairs(slave_body, slave_faces, master, context, nullptr);
    }



    template <int dim>
    std::vector<ContactPair<dim>>
    WeightedGapPairing<dim>::make_pairs_of(
      const discretization::Body<dim>            &slave_body,
      const std::vector<types::boundary_id>      &slave_faces,
      const ContactSurface<dim>                  &master,
      const std::string                          &context,
      const std::vector<types::global_dof_index> &keys) const
    {
      const PairingExclusions<dim>  kept = this->left_out;
      std::vector<ContactPair<dim>> pairs =
        form_pairs(slave_body, slave_faces, master, context, &keys);
      this->left_out = kept;
      return pairs;
    }



    template <int dim>
    bool
    WeightedGapPairing<dim>::make_pairs_with_derivatives(
      const discretization::Body<dim>            &slave_body,
      const std::vector<types::boundary_id>      &slave_faces,
      const ContactSurface<dim>                  &master,
      const std::string                          &context,
      const std::vector<types::global_dof_index> &keys,
      std::vector<ContactPair<dim>>              &pairs,
      std::vector<PairDerivatives<dim>>          &derivatives) const
    {
      if (!master.normal_continuous())
        return false;
      const PairingExclusions<dim> kept = this->left_out;
      derivatives.clear();
      pairs          = form_pairs(slave_body,
                         slave_faces,
                         master,
                         context,
                         &keys,
                         &derivatives);
      this->left_out = kept;
      return true;
    }



    template <int dim>
    std::vector<ContactPair<dim>>
    WeightedGapPairing<dim>::form_pairs(
      const discretization::Body<dim>            &slave_body,
      const std::vector<types::boundary_id>      &slave_faces,
      const ContactSurface<dim>                  &master,
      const std::string                          &context,
      const std::vector<types::global_dof_index> *keys,
      std::vector<PairDerivatives<dim>>          *derivatives) const
    {
      constexpr unsigned int fd = dim - 1;
      const MasterSide<dim>  master_side(master, context);
      this->left_out                   = PairingExclusions<dim>();
      this->left_out.quadrature_points = true;
      this->left_out.search_distance   = this->search_distance;
      // The scale of round-off: the slave faces' extent, from their
      // element corners along each face direction (a closed face, whose
      // ends coincide, included).
      double size = 0.;
      {
        std::vector<Point<dim>> corners;
        for (const types::boundary_id slave_face : slave_faces)
          {
            const auto grid = slave_body.face_grid(slave_face);
            Point<fd>  lo;
            for (unsigned int k = 0; k < fd; ++k)
              lo[k] = grid.breaks[k].front();
            for (unsigned int k = 0; k < fd; ++k)
              for (const double b : grid.breaks[k])
                {
                  Point<fd> eta = lo;
                  eta[k]        = b;
                  corners.push_back(
                    slave_body.face_point(slave_face, eta).location);
                }
          }
        for (const auto &c : corners)
          size = std::max(size, c.distance(corners.front()));
      }

      // Only the elements of the functions asked for, unless supports hold
      // one of the faces' functions (merge_held_functions() would need the
      // integrals of its neighbours).
      const bool restricted =
        keys != nullptr && !holds_a_face_function(slave_body, slave_faces);

      std::map<types::global_dof_index, WeightedIntegrals<dim>> integrals;
      const bool dual_basis = dual;
      // The smallest gap at the quadrature points: the bodies overlap
      // where it is negative.
      double min_pointwise_gap = std::numeric_limits<double>::max();
      std::map<types::global_dof_index,
               std::array<types::global_dof_index, dim>>
        dofs1, dofs2;
      // Their derivatives by the unknowns, where asked for.
      std::map<types::global_dof_index, internal::IntegralDerivatives<dim>>
        integral_derivatives;

      // Slave elements, one by one, face by face: the integrals of a basis
      // function that two faces share (glued patches) add up.
      for (const types::boundary_id slave_face : slave_faces)
        {
          const auto sgrid = slave_body.face_grid(slave_face);
          // Gauss rule exact for N_j R_B on flat faces (degree p_s + p_m per
          // direction) with one point to spare for the measure.
          unsigned int master_degree =
            master_side.projectors.empty() ? sgrid.degree : 0;
          for (const auto &projector : master_side.projectors)
            master_degree = std::max(master_degree, projector->grid.degree);
          const QGauss<1> rule((sgrid.degree + master_degree) / 2 + 2);
          std::array<unsigned int, fd> n_elements;
          unsigned int                 n_total = 1;
          for (unsigned int k = 0; k < fd; ++k)
            {
              n_elements[k] = sgrid.breaks[k].size() - 1;
              n_total *= n_elements[k];
            }
          for (unsigned int element = 0; element < n_total; ++element)
            {
              Point<fd>    lo, hi;
              unsigned int rest = element;
              for (unsigned int k = 0; k < fd; ++k)
                {
                  const unsigned int e = rest % n_elements[k];
                  rest /= n_elements[k];
                  lo[k] = sgrid.breaks[k][e];
                  hi[k] = sgrid.breaks[k][e + 1];
                }
              if (restricted &&
                  !lives_on_element(slave_body, slave_face, lo, hi, *keys))
                continue;
              // An element whose centre lines do not all project is
              // integrated uncut: its points are projected one by one
              // below, and those that do not settle are left out.
              std::array<std::vector<double>, fd> cuts;
              try
                {
                  cuts =
                    element_cuts(slave_body, slave_face, lo, hi, master_side);
                }
              catch (const base::ExcInput &)
                {
                  for (unsigned int k = 0; k < fd; ++k)
                    cuts[k] = {lo[k], hi[k]};
                }
              const internal::ElementDualBasis<dim> dual =
                dual_basis ? internal::element_dual_basis<dim>(slave_body,
                                                               slave_face,
                                                               lo,
                                                               hi,
                                                               rule) :
                             internal::ElementDualBasis<dim>();

              // Every piece with the tensor Gauss rule.
              std::array<unsigned int, fd> n_pieces;
              unsigned int                 n_piece_total = 1;
              for (unsigned int k = 0; k < fd; ++k)
                {
                  n_pieces[k] = cuts[k].size() - 1;
                  n_piece_total *= n_pieces[k];
                }
              const unsigned int nq       = rule.size();
              unsigned int       nq_total = 1;
              for (unsigned int k = 0; k < fd; ++k)
                nq_total *= nq;
              // The element's quadrature points with their master points;
              // those that do not face the master within its extent are
              // left out, and the integrals run over the rest.
              using Sample = internal::ElementSample<dim>;
              std::vector<Sample> samples;
              bool                whole = true;
              for (unsigned int piece = 0; piece < n_piece_total; ++piece)
                for (unsigned int q = 0; q < nq_total; ++q)
                  {
                    Point<fd>    eta;
                    double       weight = 1.;
                    unsigned int pr = piece, qr = q;
                    for (unsigned int k = 0; k < fd; ++k)
                      {
                        const unsigned int i  = pr % n_pieces[k];
                        const unsigned int iq = qr % nq;
                        pr /= n_pieces[k];
                        qr /= nq;
                        const double a = cuts[k][i], b = cuts[k][i + 1];
                        eta[k] = a + (b - a) * rule.point(iq)[0];
                        weight *= (b - a) * rule.weight(iq);
                      }
                    Sample sample;
                    sample.s      = slave_body.face_point(slave_face, eta);
                    sample.weight = weight;
                    sample.eta    = eta;
                    try
                      {
                        sample.m = master_side.facing(sample.s.location,
                                                      &sample.part,
                                                      &sample.xi);
                      }
                    catch (const base::ExcInput &)
                      {
                        this->left_out.leave_out_unprojected(sample.s.location);
                        whole = false;
                        continue;
                      }
                    if (this->left_out.keep(sample.s.location,
                                            sample.s.normal,
                                            sample.m.location,
                                            sample.m.normal,
                                            size))
                      samples.push_back(std::move(sample));
                    else
                      whole = false;
                  }
              // The dual basis is biorthogonal over the whole element: on
              // the part of one that faces the master its negative lobes
              // would make a gap out of nothing, so a cut element weights
              // with the face basis N_j (still a mean of the gap).
              const bool dual_here = dual_basis && whole;
              if (derivatives != nullptr)
                internal::add_element_derivatives<dim>(master_side,
                                                       samples,
                                                       dual_here ? &dual :
                                                                   nullptr,
                                                       integral_derivatives);
              for (const Sample &sample : samples)
                {
                  const auto  &s      = sample.s;
                  const auto  &m      = sample.m;
                  const double weight = sample.weight;
                  const double dA     = weight * s.measure;
                  const double g      = (s.location - m.location) * m.normal;
                  min_pointwise_gap   = std::min(min_pointwise_gap, g);
                  if (!dual_here)
                    {
                      for (unsigned int a = 0; a < s.op.weights.size(); ++a)
                        if (s.op.weights[a] != 0.)
                          {
                            const double w  = s.op.weights[a] * dA;
                            auto        &in = integrals[s.op.dofs[a][0]];
                            in.area += w;
                            in.gap += w * g;
                            in.normal += w * m.normal;
                            in.x1 += w * s.location;
                            in.x2 += w * m.location;
                            add_row<dim>(s.op, w, in.op1, dofs1);
                            add_row<dim>(m.op, w, in.op2, dofs2);
                          }
                    }
                  else
                    {
                      Eigen::VectorXd N =
                        Eigen::VectorXd::Zero(dual.local.size());
                      for (unsigned int a = 0; a < s.op.weights.size(); ++a)
                        if (s.op.weights[a] != 0.)
                          N(dual.local.at(s.op.dofs[a][0])) = s.op.weights[a];
                      const Eigen::VectorXd psi = dual.A * N;
                      for (const auto &[key, j] : dual.local)
                        {
                          const double w_n = N(j) * dA;
                          const double w_d = psi(j) * dA;
                          if (w_n == 0. && w_d == 0.)
                            continue;
                          auto &in = integrals[key];
                          // Areas, frames and locations with the face basis
                          // (non-negative); gaps and operators with the dual.
                          in.area += w_n;
                          in.gap += w_d * g;
                          in.normal += w_n * m.normal;
                          in.x1 += w_n * s.location;
                          in.x2 += w_n * m.location;
                          add_row<dim>(s.op, w_d, in.op1, dofs1);
                          add_row<dim>(m.op, w_d, in.op2, dofs2);
                        }
                    }
                }
            }
        }

      double total = 0.;
      for (const auto &entry : integrals)
        total += entry.second.area;
      merge_held_functions<dim>(slave_body,
                                total,
                                integrals,
                                dofs1,
                                derivatives != nullptr ? &integral_derivatives :
                                                         nullptr);
      if (keys != nullptr)
        {
          // The functions asked for: the others' integrals may be partial.
          for (auto it = integrals.begin(); it != integrals.end();)
            it = std::binary_search(keys->begin(), keys->end(), it->first) ?
                   std::next(it) :
                   integrals.erase(it);
        }

      std::vector<ContactPair<dim>> pairs;
      for (const auto &[key, in] : integrals)
        {
          // Basis functions of the body that vanish on the face have no
          // integral; those of the face have a positive one over the whole
          // face (B-splines, FE_Q tensor-product bases). Over the part of
          // it whose points were kept, an FE_Q vertex function may keep
          // only its negative lobe (an element cut by the search distance
          // or the master's edge): it faces nothing with a positive area
          // and is left out with the points that were.
          if (in.area <= 1e-12 * total)
            continue;
          ContactPair<dim> pair;
          pair.area      = in.area;
          pair.x1        = Point<dim>(in.x1 / in.area);
          pair.x2        = Point<dim>(in.x2 / in.area);
          pair.frame     = local_frame<dim>(in.normal / in.normal.norm());
          pair.normal1   = -pair.frame[0];
          pair.gap       = in.gap / in.area;
          pair.op1       = make_operator<dim>(in.op1, in.area, dofs1);
          pair.op2       = make_operator<dim>(in.op2, in.area, dofs2);
          pair.slave_key = key;
          pairs.push_back(pair);
          if (derivatives != nullptr)
            derivatives->push_back(
              internal::pair_derivatives<dim>(in.area,
                                              in.gap,
                                              in.normal,
                                              in.op1,
                                              in.op2,
                                              integral_derivatives[key]));
        }
      if (keys != nullptr)
        return pairs;
      AssertThrow(this->left_out.candidates > this->left_out.n_left_out(),
                  base::ExcInput(
                    internal::nothing_faces(context, this->left_out, master)));
      AssertThrow(!pairs.empty(),
                  base::ExcInput(context + ": Contact/Slave face " +
                                 slave_body.face_name(slave_faces.front()) +
                                 " of Body 1 has no contact points."));
      size = 0.;
      for (const auto &pair : pairs)
        size = std::max(size, (pair.x1 - pairs[0].x1).norm());
      // Overlap is judged on the pointwise gap. A dual-weighted gap
      // int psi_j g / int N_j may be negative where the bodies do not
      // overlap: psi_j has negative lobes, and a curved face touching the
      // other in the middle of a knot span has a gap that grows
      // quadratically from zero there, whose dual-weighted mean on the
      // span's middle function is negative, of order h^2 / R (the half
      // disc of V6 on 29 spans: -0.0033 with R = 8). It is the mortar
      // discretisation's gap, consistent to that order, and is kept: the
      // contact pushes that pair open. Only round-off is cut to zero.
      // On a moved configuration (finite sliding: the last step's state)
      // the bodies may overlap as the discrete solution does, and that
      // overlap is the gap the next solve starts from.
      if (slave_body.surfaces_moved())
        return pairs;
      AssertThrow(min_pointwise_gap >= -1e-10 * size,
                  base::ExcInput(
                    internal::penetrates(context, master, min_pointwise_gap)));
      for (auto &pair : pairs)
        if (pair.gap >= -1e-10 * size)
          pair.gap = std::max(pair.gap, 0.);
      return pairs;
    }



    template class WeightedGapPairing<2>;
    template class WeightedGapPairing<3>;
  } // namespace contact
} // namespace igabde
