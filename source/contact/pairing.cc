#include <igabde/base/nearest_points.h>
#include <igabde/base/utilities.h>

#include <igabde/contact/pairing.h>

#include <deal.II/base/quadrature_lib.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

namespace igabde
{
  namespace contact
  {
    template <int dim>
    Tensor<2, dim>
    local_frame(const Tensor<1, dim> &n)
    {
      Tensor<2, dim> T;
      T[0] = n;
      if (dim == 2)
        {
          T[1][0] = -n[1];
          T[1][1] = n[0];
        }
      else
        {
          unsigned int axis = 0;
          for (unsigned int d = 1; d < dim; ++d)
            if (std::abs(n[d]) < std::abs(n[axis]))
              axis = d;
          Tensor<1, dim> e;
          e[axis]          = 1.;
          Tensor<1, dim> a = e - (e * n) * n;
          a /= a.norm();
          T[1] = a;
          if constexpr (dim == 3)
            T[2] = cross_product_3d(n, a);
        }
      return T;
    }



    namespace
    {
      /// Size of the slave point cloud: the scale of the tolerances below.
      template <int dim>
      double
      cloud_size(const std::vector<discretization::SurfacePoint<dim>> &slave)
      {
        double size = 0.;
        for (const auto &s : slave)
          size = std::max(size, (s.location - slave[0].location).norm());
        return std::max(size, 1e-300);
      }



      /// The R-tree over the locations of @p samples.
      template <int dim>
      std::unique_ptr<base::NearestPoints<dim>>
      index_samples(
        const std::vector<discretization::SurfacePoint<dim>> &samples)
      {
        std::vector<Point<dim>> locations;
        for (const auto &s : samples)
          locations.push_back(s.location);
        return std::make_unique<base::NearestPoints<dim>>(std::move(locations));
      }



      /**
       * The pair of a slave point and the master point it faces: frame from
       * the master normal, gap, and the checks that the surfaces face each
       * other and do not overlap (penetration beyond round-off, 1e-10 of
       * the contact face's size).
       */



      /// The refusal when the two contact faces do not face each other.
      template <int dim>
      std::string
      not_facing(const std::string         &context,
                 const Point<dim>          &location,
                 const ContactSurface<dim> &master)
      {
        return context + ": the contact surfaces do not face each other at (" +
               base::to_string(location) +
               "): the outward normal of Body 1's contact face points "
               "away from " +
               master.description() +
               (master.deformable() ?
                  std::string("; check Contact/Slave face and "
                              "Contact/Master face.") :
                  std::string(" (check Body 2/Plane normal: it must "
                              "point towards Body 1) and Contact/Slave "
                              "face."));
      }



      /// The refusal of an initial penetration.
      template <int dim>
      std::string
      penetrates(const std::string         &context,
                 const ContactSurface<dim> &master,
                 const double               gap)
      {
        return context + ": Body 1 initially penetrates " +
               master.description() + " (gap " + std::to_string(gap) +
               "); move the bodies apart.";
      }



      template <int dim>
      ContactPair<dim>
      make_pair(const discretization::SurfacePoint<dim> &s,
                const discretization::SurfacePoint<dim> &m,
                const ContactSurface<dim>               &master,
                const double                             size,
                const std::string                       &context)
      {
        ContactPair<dim> pair;
        pair.x1                = s.location;
        pair.op1               = s.op;
        pair.area              = s.tributary_area;
        pair.x2                = m.location;
        pair.op2               = m.op;
        const Tensor<1, dim> n = m.normal;
        AssertThrow(s.normal * n < 0.,
                    base::ExcInput(not_facing(context, s.location, master)));
        pair.frame   = local_frame<dim>(n);
        pair.normal1 = s.normal;
        pair.gap     = (pair.x1 - pair.x2) * n;
        AssertThrow(pair.gap >= -1e-10 * size,
                    base::ExcInput(penetrates(context, master, pair.gap)));
        pair.gap = std::max(pair.gap, 0.);
        return pair;
      }
      /**
       * The points @p points of several faces with the coincident ones
       * (within 1e-10 of the cloud's size: the edge two patch faces share)
       * made one: tributary areas summed, normals averaged by area, the
       * first one's operator (the faces' traces agree there: the patches'
       * control points are glued).
       */
      template <int dim>
      std::vector<discretization::SurfacePoint<dim>>
      merge_coincident_points(
        const std::vector<discretization::SurfacePoint<dim>> &points)
      {
        const double tolerance = 1e-10 * cloud_size(points);
        // Sorted along x, coincident points are neighbours within the
        // tolerance in x.
        std::vector<unsigned int> order(points.size());
        std::iota(order.begin(), order.end(), 0u);
        std::sort(order.begin(), order.end(), [&](const auto a, const auto b) {
          return points[a].location[0] < points[b].location[0];
        });
        std::vector<int> merged_into(points.size(), -1);
        for (unsigned int k = 0; k < order.size(); ++k)
          for (unsigned int l = k + 1;
               l < order.size() &&
               points[order[l]].location[0] - points[order[k]].location[0] <=
                 tolerance;
               ++l)
            {
              const unsigned int a = std::min(order[k], order[l]);
              const unsigned int b = std::max(order[k], order[l]);
              if (merged_into[b] < 0 && merged_into[a] < 0 &&
                  points[a].location.distance(points[b].location) <= tolerance)
                merged_into[b] = a;
            }
        std::vector<discretization::SurfacePoint<dim>> result;
        std::vector<int>                               position(points.size());
        std::vector<Tensor<1, dim>>                    normal_sum;
        for (unsigned int i = 0; i < points.size(); ++i)
          if (merged_into[i] < 0)
            {
              position[i] = result.size();
              result.push_back(points[i]);
              normal_sum.push_back(points[i].tributary_area * points[i].normal);
            }
        for (unsigned int i = 0; i < points.size(); ++i)
          if (merged_into[i] >= 0)
            {
              const int p = position[merged_into[i]];
              result[p].tributary_area += points[i].tributary_area;
              normal_sum[p] += points[i].tributary_area * points[i].normal;
            }
        for (unsigned int p = 0; p < result.size(); ++p)
          if (normal_sum[p].norm() > 0.)
            result[p].normal = normal_sum[p] / normal_sum[p].norm();
        return result;
      }
    } // namespace



    template <int dim>
    std::vector<ContactPair<dim>>
    PointPairing<dim>::make_pairs(
      const discretization::Body<dim>       &slave_body,
      const std::vector<types::boundary_id> &slave_faces,
      const ContactSurface<dim>             &master,
      const std::string                     &context) const
    {
      std::vector<discretization::SurfacePoint<dim>> slave;
      for (const types::boundary_id face : slave_faces)
        {
          const auto points = slave_body.surface_points(face);
          slave.insert(slave.end(), points.begin(), points.end());
        }
      AssertThrow(!slave.empty(),
                  base::ExcInput(context + ": Contact/Slave face " +
                                 slave_body.face_name(slave_faces.front()) +
                                 " of Body 1 has no contact points."));
      if (slave_faces.size() > 1)
        slave = merge_coincident_points(slave);
      return make_pairs(slave, master, context);
    }



    template <int dim>
    std::vector<ContactPair<dim>>
    PointPairing<dim>::make_pairs(
      const std::vector<discretization::SurfacePoint<dim>> &slave,
      const ContactSurface<dim>                            &master,
      const std::string                                    &context) const
    {
      const double size    = cloud_size(slave);
      const auto  &samples = master.sample_points();
      AssertThrow(!master.deformable() || !samples.empty(),
                  base::ExcInput(context + ": " + master.description() +
                                 " has no contact points."));
      std::vector<ContactPair<dim>> pairs;
      const auto                    index = index_samples(samples);
      for (const auto &s : slave)
        pairs.push_back(
          make_pair(s,
                    master.deformable() ?
                      facing_point(s,
                                   samples[index->nearest(s.location)],
                                   master,
                                   size,
                                   context) :
                      master.closest_point(s.location, nullptr),
                    master,
                    size,
                    context));
      return pairs;
    }



    template <int dim>
    std::string
    NodeToNodePairing<dim>::name() const
    {
      return "node-to-node";
    }



    template <int dim>
    discretization::SurfacePoint<dim>
    NodeToNodePairing<dim>::facing_point(
      const discretization::SurfacePoint<dim> &s,
      const discretization::SurfacePoint<dim> &nearest,
      const ContactSurface<dim>               &master,
      const double                             size,
      const std::string                       &context) const
    {
      const double distance = (nearest.location - s.location).norm();
      AssertThrow(
        distance <= 1e-8 * size,
        base::ExcInput(
          context +
          ": Contact/Pairing = node-to-node needs matching surfaces, but "
          "the point (" +
          [&] {
            std::ostringstream o;
            o << s.location;
            return o.str();
          }() +
          ") of Body 1 has no coincident point on " + master.description() +
          " (nearest at distance " + std::to_string(distance) +
          "); use Contact/Pairing = node-to-surface."));
      return nearest;
    }



    template <int dim>
    std::string
    NodeToSurfacePairing<dim>::name() const
    {
      return "node-to-surface";
    }



    template <int dim>
    discretization::SurfacePoint<dim>
    NodeToSurfacePairing<dim>::facing_point(
      const discretization::SurfacePoint<dim> &s,
      const discretization::SurfacePoint<dim> &nearest,
      const ContactSurface<dim>               &master,
      const double                             size,
      const std::string &) const
    {
      // The coincident master point where the surfaces match (within
      // round-off of the face's size), else the closest point.
      if ((nearest.location - s.location).norm() <= 1e-8 * size)
        return nearest;
      return master.closest_point(s.location, &nearest);
    }



    namespace
    {
      /**
       * Closest-point projection on a deformable master face in its face
       * coordinates: Gauss-Newton on |x(eta) - x|^2 from the nearest of
       * the face's element corners and midpoints, clamped to the face.
       */
      template <int dim>
      class FaceProjector
      {
      public:
        FaceProjector(const ContactSurface<dim> &master,
                      const std::string         &context)
          : master(master)
          , grid(master.face_grid())
          , context(context)
        {
          std::array<std::vector<double>, dim - 1> coords;
          unsigned int                             n = 1;
          for (unsigned int k = 0; k < dim - 1; ++k)
            {
              const auto &b = grid.breaks[k];
              for (unsigned int e = 0; e + 1 < b.size(); ++e)
                {
                  coords[k].push_back(b[e]);
                  coords[k].push_back(0.5 * (b[e] + b[e + 1]));
                }
              coords[k].push_back(b.back());
              n *= coords[k].size();
              extent = std::max(extent, b.back() - b.front());
            }
          std::vector<Point<dim>> sample_x;
          for (unsigned int i = 0; i < n; ++i)
            {
              Point<dim - 1> eta;
              unsigned int   rest = i;
              for (unsigned int k = 0; k < dim - 1; ++k)
                {
                  eta[k] = coords[k][rest % coords[k].size()];
                  rest /= coords[k].size();
                }
              sample_eta.push_back(eta);
              sample_x.push_back(master.face_point(eta).location);
            }
          index =
            std::make_unique<base::NearestPoints<dim>>(std::move(sample_x));
        }

        /// The face coordinates of the point of the face closest to @p x.
        Point<dim - 1>
        project(const Point<dim> &x) const
        {
          Point<dim - 1> eta = sample_eta[index->nearest(x)];
          for (unsigned int it = 0; it < 100; ++it)
            {
              const auto           fp = master.face_point(eta);
              const Tensor<1, dim> r  = x - fp.location;
              Point<dim - 1>       next;
              if (dim == 2)
                next[0] =
                  eta[0] + (fp.tangents[0] * r) / fp.tangents[0].norm_square();
              else
                {
                  const auto  &t   = fp.tangents;
                  const double a00 = t[0] * t[0];
                  const double a01 = t[0] * t[dim - 2];
                  const double a11 = t[dim - 2] * t[dim - 2];
                  const double b0  = t[0] * r;
                  const double b1  = t[dim - 2] * r;
                  const double det = a00 * a11 - a01 * a01;
                  next[0]          = eta[0] + (a11 * b0 - a01 * b1) / det;
                  next[dim - 2]    = eta[dim - 2] + (a00 * b1 - a01 * b0) / det;
                }
              for (unsigned int k = 0; k < dim - 1; ++k)
                next[k] = std::clamp(next[k],
                                     grid.breaks[k].front(),
                                     grid.breaks[k].back());
              const double step = (next - eta).norm();
              eta               = next;
              if (step <= 1e-14 * extent)
                return eta;
            }
          AssertThrow(false,
                      ExcMessage(
                        context + ": the closest point projection of (" +
                        base::to_string(x) + ") on " + master.description() +
                        " did not converge in 100 iterations."));
          return eta;
        }

        const ContactSurface<dim>          &master;
        const discretization::FaceGrid<dim> grid;

      private:
        const std::string                         context;
        double                                    extent = 0.;
        std::vector<Point<dim - 1>>               sample_eta;
        std::unique_ptr<base::NearestPoints<dim>> index;
      };



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
    } // namespace



    template <int dim>
    WeightedGapPairing<dim>::WeightedGapPairing(const bool dual)
      : dual(dual)
    {}



    template <int dim>
    std::string
    WeightedGapPairing<dim>::name() const
    {
      return dual ? "weighted-gap" : "weighted-gap-standard";
    }



    template <int dim>
    std::vector<ContactPair<dim>>
    WeightedGapPairing<dim>::make_pairs(
      const discretization::Body<dim>       &slave_body,
      const std::vector<types::boundary_id> &slave_faces,
      const ContactSurface<dim>             &master,
      const std::string                     &context) const
    {
      constexpr unsigned int fd = dim - 1;
      // One projector per master face (a surface over several patches has
      // one face coordinate system per patch face).
      const std::vector<const ContactSurface<dim> *>   parts = master.parts();
      std::vector<std::unique_ptr<FaceProjector<dim>>> projectors;
      if (master.deformable())
        for (const ContactSurface<dim> *part : parts)
          projectors.push_back(
            std::make_unique<FaceProjector<dim>>(*part, context));
      // The master face holding the point closest to @p x, and the point's
      // face coordinates there.
      const auto project = [&](const Point<dim> &x) {
        if (projectors.size() == 1)
          return std::make_pair(0u, projectors[0]->project(x));
        // A face far from x may leave the clamped Gauss-Newton cycling on
        // its edge: such a face is not the closest one.
        std::pair<unsigned int, Point<fd>> best;
        double best_distance = std::numeric_limits<double>::max();
        for (unsigned int k = 0; k < projectors.size(); ++k)
          try
            {
              const Point<fd> eta = projectors[k]->project(x);
              const double    distance =
                parts[k]->face_point(eta).location.distance(x);
              if (distance < best_distance)
                {
                  best_distance = distance;
                  best          = {k, eta};
                }
            }
          catch (const ExceptionBase &)
            {
              if (k + 1 == projectors.size() &&
                  best_distance == std::numeric_limits<double>::max())
                throw;
            }
        return best;
      };

      std::map<types::global_dof_index, WeightedIntegrals<dim>> integrals;
      const bool dual_basis = dual;
      // The smallest gap at the quadrature points: the bodies overlap
      // where it is negative.
      double min_pointwise_gap = std::numeric_limits<double>::max();
      std::map<types::global_dof_index,
               std::array<types::global_dof_index, dim>>
        dofs1, dofs2;

      // The master point facing the slave point @p x: location, normal and
      // operator.
      const auto facing = [&](const Point<dim> &x) {
        discretization::FacePoint<dim> m;
        if (!projectors.empty())
          {
            const auto [k, eta] = project(x);
            m                   = parts[k]->face_point(eta);
          }
        else
          {
            const auto cp = master.closest_point(x, nullptr);
            m.location    = cp.location;
            m.normal      = cp.normal;
          }
        return m;
      };

      // Slave elements, one by one, face by face: the integrals of a basis
      // function that two faces share (glued patches) add up.
      for (const types::boundary_id slave_face : slave_faces)
        {
          const auto sgrid = slave_body.face_grid(slave_face);
          // Gauss rule exact for N_j R_B on flat faces (degree p_s + p_m per
          // direction) with one point to spare for the measure.
          unsigned int master_degree = projectors.empty() ? sgrid.degree : 0;
          for (const auto &projector : projectors)
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
              Point<fd>                           lo, hi;
              std::array<std::vector<double>, fd> cuts;
              unsigned int                        rest = element;
              for (unsigned int k = 0; k < fd; ++k)
                {
                  const unsigned int e = rest % n_elements[k];
                  rest /= n_elements[k];
                  lo[k]   = sgrid.breaks[k][e];
                  hi[k]   = sgrid.breaks[k][e + 1];
                  cuts[k] = {lo[k], hi[k]};
                }

              // Cuts where the projection of the element's centre line in
              // direction k crosses a master element edge, or passes from
              // one master face to the next (an edge too).
              if (!projectors.empty())
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
                      const auto &projector  = *projectors[part];
                      const auto  master_eta = [&](const double t) {
                        return projector.project(slave_point(t));
                      };
                      const Point<fd> at_a = master_eta(a);
                      const Point<fd> at_b = master_eta(b);
                      for (unsigned int c = 0; c < fd; ++c)
                        {
                          const auto  &mb  = projector.grid.breaks[c];
                          const double tol = 1e-12 * (mb.back() - mb.front());
                          for (unsigned int i = 1; i + 1 < mb.size(); ++i)
                            {
                              // The crossing t of master_eta(t)[c] = mb[i],
                              // by TOMS 748 (Alefeld, Potra and Shi) on the
                              // bracket.
                              const double fa = at_a[c] - mb[i],
                                           fb = at_b[c] - mb[i];
                              if (!((fa > tol && fb < -tol) ||
                                    (fa < -tol && fb > tol)))
                                continue;
                              std::uintmax_t max_iterations = 200;
                              const auto     bracket =
                                boost::math::tools::toms748_solve(
                                  [&](const double t) {
                                    return master_eta(t)[c] - mb[i];
                                  },
                                  a,
                                  b,
                                  fa,
                                  fb,
                                  [&](const double x, const double y) {
                                    return std::abs(y - x) <=
                                           1e-14 * (hi[k] - lo[k]);
                                  },
                                  max_iterations);
                              cuts[k].push_back(
                                0.5 * (bracket.first + bracket.second));
                            }
                        }
                    };
                    // From a to b: where the closest master face changes,
                    // found by bisection, a cut; each stretch cut at its
                    // face's edges.
                    const auto part_at = [&](const double t) {
                      return project(slave_point(t)).first;
                    };
                    double             a       = lo[k];
                    unsigned int       part_a  = part_at(a);
                    const unsigned int part_hi = part_at(hi[k]);
                    for (unsigned int stretch = 0;
                         part_a != part_hi && stretch < projectors.size();
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
                                              [&](const double x,
                                                  const double y) {
                                                return y - x <=
                                                       1e-13 * (hi[k] - lo[k]);
                                              }),
                                  cuts[k].end());
                  }

              // The element's dual basis (biorthogonal to its face basis):
              // psi_j = sum_k A_jk N_k with A = D M^{-1}, M_jk = int_e N_j N_k,
              // D = diag(int_e N_j), so that int_e psi_j N_k = delta_jk D_jj.
              std::map<types::global_dof_index, unsigned int> local;
              Eigen::MatrixXd                                 dual;
              if (dual_basis)
                {
                  std::vector<std::vector<std::pair<unsigned int, double>>>
                                               values;
                  std::vector<double>          dAs;
                  std::array<unsigned int, fd> n_q1;
                  unsigned int                 nq_e = 1;
                  for (unsigned int k = 0; k < fd; ++k)
                    {
                      n_q1[k] = rule.size();
                      nq_e *= rule.size();
                    }
                  for (unsigned int q = 0; q < nq_e; ++q)
                    {
                      Point<fd>    eta;
                      double       weight = 1.;
                      unsigned int qr     = q;
                      for (unsigned int k = 0; k < fd; ++k)
                        {
                          const unsigned int iq = qr % n_q1[k];
                          qr /= n_q1[k];
                          eta[k] = lo[k] + (hi[k] - lo[k]) * rule.point(iq)[0];
                          weight *= (hi[k] - lo[k]) * rule.weight(iq);
                        }
                      const auto s = slave_body.face_point(slave_face, eta);
                      dAs.push_back(weight * s.measure);
                      values.emplace_back();
                      for (unsigned int a = 0; a < s.op.weights.size(); ++a)
                        if (s.op.weights[a] != 0.)
                          {
                            const auto key = s.op.dofs[a][0];
                            const auto it =
                              local.emplace(key, local.size()).first;
                            values.back().emplace_back(it->second,
                                                       s.op.weights[a]);
                          }
                    }
                  const unsigned int n            = local.size();
                  Eigen::MatrixXd    M            = Eigen::MatrixXd::Zero(n, n);
                  Eigen::VectorXd    D            = Eigen::VectorXd::Zero(n);
                  double             element_area = 0.;
                  for (unsigned int q = 0; q < values.size(); ++q)
                    {
                      element_area += dAs[q];
                      for (const auto &[j, nj] : values[q])
                        {
                          D(j) += nj * dAs[q];
                          for (const auto &[k, nk] : values[q])
                            M(j, k) += nj * nk * dAs[q];
                        }
                    }
                  // Functions of the cell that vanish on the face (FE_Q) have
                  // no share: identity rows keep M regular, D = 0 drops them.
                  for (unsigned int j = 0; j < n; ++j)
                    if (D(j) <= 1e-12 * element_area)
                      {
                        M.row(j).setZero();
                        M.col(j).setZero();
                        M(j, j) = 1.;
                        D(j)    = 0.;
                      }
                  dual = D.asDiagonal() * M.inverse();
                }

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
                    const auto s = slave_body.face_point(slave_face, eta);
                    const auto m = facing(s.location);
                    AssertThrow(s.normal * m.normal < 0.,
                                base::ExcInput(
                                  not_facing(context, s.location, master)));
                    const double dA   = weight * s.measure;
                    const double g    = (s.location - m.location) * m.normal;
                    min_pointwise_gap = std::min(min_pointwise_gap, g);
                    if (!dual_basis)
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
                        Eigen::VectorXd N = Eigen::VectorXd::Zero(local.size());
                        for (unsigned int a = 0; a < s.op.weights.size(); ++a)
                          if (s.op.weights[a] != 0.)
                            N(local.at(s.op.dofs[a][0])) = s.op.weights[a];
                        const Eigen::VectorXd psi = dual * N;
                        for (const auto &[key, j] : local)
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

      // Basis functions of the face whose unknowns supports hold in every
      // component: their pressure goes straight into the support, on both
      // sides where Body 2 is held there too (a clamped edge lying in the
      // contact face, as in B2), and their pairs then make the flexibility
      // singular in the normal direction. As mortar methods do at a
      // Dirichlet boundary of the slave side, each is merged into the
      // nearest free function of the face (N_k + N_j: every integral
      // above is linear in N_j, so the pairs' sums add up); the merged
      // basis still sums to one, so a uniform pressure stays exact.
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
            }
      }

      std::vector<ContactPair<dim>> pairs;
      for (const auto &[key, in] : integrals)
        {
          // Basis functions of the body that vanish on the face have no
          // integral; those of the face have a positive one (B-splines,
          // FE_Q tensor-product bases).
          if (in.area <= 1e-12 * total)
            {
              AssertThrow(in.area >= -1e-12 * total, ExcInternalError());
              continue;
            }
          ContactPair<dim> pair;
          pair.area    = in.area;
          pair.x1      = Point<dim>(in.x1 / in.area);
          pair.x2      = Point<dim>(in.x2 / in.area);
          pair.frame   = local_frame<dim>(in.normal / in.normal.norm());
          pair.normal1 = -pair.frame[0];
          pair.gap     = in.gap / in.area;
          pair.op1     = make_operator<dim>(in.op1, in.area, dofs1);
          pair.op2     = make_operator<dim>(in.op2, in.area, dofs2);
          pairs.push_back(pair);
        }
      AssertThrow(!pairs.empty(),
                  base::ExcInput(context + ": Contact/Slave face " +
                                 slave_body.face_name(slave_faces.front()) +
                                 " of Body 1 has no contact points."));
      double size = 0.;
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
      AssertThrow(min_pointwise_gap >= -1e-10 * size,
                  base::ExcInput(
                    penetrates(context, master, min_pointwise_gap)));
      for (auto &pair : pairs)
        if (pair.gap >= -1e-10 * size)
          pair.gap = std::max(pair.gap, 0.);
      return pairs;
    }



    std::vector<std::string>
    available_pairing_strategies()
    {
      return {to_string(Pairing::node_to_surface),
              to_string(Pairing::node_to_node),
              to_string(Pairing::weighted_gap),
              to_string(Pairing::weighted_gap_standard)};
    }



    template <int dim>
    std::unique_ptr<PairingStrategy<dim>>
    create_pairing_strategy(const Pairing pairing)
    {
      // One line per strategy.
      switch (pairing)
        {
          case Pairing::node_to_surface:
            return std::make_unique<NodeToSurfacePairing<dim>>();
          case Pairing::node_to_node:
            return std::make_unique<NodeToNodePairing<dim>>();
          case Pairing::weighted_gap:
            return std::make_unique<WeightedGapPairing<dim>>(true);
          case Pairing::weighted_gap_standard:
            return std::make_unique<WeightedGapPairing<dim>>(false);
        }
      return nullptr;
    }



    template Tensor<2, 2>
    local_frame<2>(const Tensor<1, 2> &);
    template Tensor<2, 3>
    local_frame<3>(const Tensor<1, 3> &);
    template class PointPairing<2>;
    template class PointPairing<3>;
    template class WeightedGapPairing<2>;
    template class WeightedGapPairing<3>;
    template class NodeToNodePairing<2>;
    template class NodeToNodePairing<3>;
    template class NodeToSurfacePairing<2>;
    template class NodeToSurfacePairing<3>;
    template std::unique_ptr<PairingStrategy<2>>
    create_pairing_strategy<2>(const Pairing);
    template std::unique_ptr<PairingStrategy<3>>
    create_pairing_strategy<3>(const Pairing);
  } // namespace contact
} // namespace igabde
