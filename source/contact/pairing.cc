#include <igabde/base/nearest_points.h>
#include <igabde/base/utilities.h>

#include <igabde/contact/pairing.h>

#include <algorithm>
#include <cmath>
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



    template <int dim>
    Tensor<2, dim>
    local_frame(const Tensor<1, dim> &n, const Tensor<2, dim> &near)
    {
      if constexpr (dim == 3)
        {
          Tensor<1, dim> a = near[1] - (near[1] * n) * n;
          if (a.norm() > 0.5)
            {
              Tensor<2, dim> T;
              T[0] = n;
              T[1] = a / a.norm();
              T[2] = cross_product_3d(n, T[1]);
              return T;
            }
        }
      (void)near;
      return local_frame<dim>(n);
    }



    template <int dim>
    Tensor<2, dim>
    local_frame_change(const Tensor<1, dim> &n,
                       const Tensor<2, dim> &near,
                       const Tensor<1, dim> &dn)
    {
      Tensor<2, dim> dT;
      dT[0] = dn;
      if constexpr (dim == 2)
        {
          (void)near;
          dT[1][0] = -dn[1];
          dT[1][1] = dn[0];
        }
      else
        {
          // The first tangent a / |a|, a = t - (t . n) n, with t near's
          // first tangent or, where local_frame() falls back, its axis.
          Tensor<1, dim> t = near[1];
          if ((t - (t * n) * n).norm() <= 0.5)
            {
              unsigned int axis = 0;
              for (unsigned int d = 1; d < dim; ++d)
                if (std::abs(n[d]) < std::abs(n[axis]))
                  axis = d;
              t       = Tensor<1, dim>();
              t[axis] = 1.;
            }
          const Tensor<1, dim> a  = t - (t * n) * n;
          const Tensor<1, dim> T1 = a / a.norm();
          const Tensor<1, dim> da = -(t * dn) * n - (t * n) * dn;
          dT[1]                   = (da - (T1 * da) * T1) / a.norm();
          if constexpr (dim == 3)
            dT[2] = cross_product_3d(dn, T1) + cross_product_3d(n, dT[1]);
        }
      return dT;
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
        pair.frame             = local_frame<dim>(n);
        pair.normal1           = s.normal;
        pair.gap               = (pair.x1 - pair.x2) * n;
        AssertThrow(pair.gap >= -1e-10 * size,
                    base::ExcInput(
                      internal::penetrates(context, master, pair.gap)));
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
    bool
    PairingExclusions<dim>::keep(const Point<dim>     &s,
                                 const Tensor<1, dim> &n_s,
                                 const Point<dim>     &m,
                                 const Tensor<1, dim> &n_m,
                                 const double          size)
    {
      ++candidates;
      // Normals are unit vectors, or zero where a face's measure vanishes
      // (a collapsed edge): no direction to push along.
      if (!(n_s.norm() > 0.5 && n_m.norm() > 0.5))
        {
          if (degenerate++ == 0)
            first_degenerate = s;
          return false;
        }
      if (search_distance > 0. && s.distance(m) > search_distance)
        {
          if (beyond++ == 0)
            first_beyond = s;
          return false;
        }
      if (!(n_s * n_m < 0.))
        {
          if (not_facing++ == 0)
            first_not_facing = s;
          return false;
        }
      // At an orthogonal projection s - m is along the normal; a clamped
      // one (past the master's edge) leaves a tangential offset. Round-off
      // of the projection's Newton: far below 1e-8 of the scale.
      const Tensor<1, dim> d      = s - m;
      const Tensor<1, dim> offset = d - (d * n_m) * n_m;
      if (offset.norm() > 1e-8 * std::max(size, d.norm()))
        {
          if (outside++ == 0)
            first_outside = s;
          return false;
        }
      return true;
    }



    template <int dim>
    void
    PairingExclusions<dim>::leave_out_unprojected(const Point<dim> &s)
    {
      ++candidates;
      if (unprojected++ == 0)
        first_unprojected = s;
    }



    namespace internal
    {
      template <int dim>
      std::string
      nothing_faces(const std::string            &context,
                    const PairingExclusions<dim> &exclusions,
                    const ContactSurface<dim>    &master)
      {
        if (exclusions.not_facing > 0)
          return not_facing(context, exclusions.first_not_facing, master);
        if (exclusions.beyond > 0)
          return context +
                 ": no contact point of the slave face lies "
                 "within the search distance " +
                 base::number_text(exclusions.search_distance) + " of " +
                 master.description() + " (the first at (" +
                 base::to_string(exclusions.first_beyond) +
                 ")): raise Contact/Search distance, or check the faces "
                 "and the bodies' placement.";
        if (exclusions.degenerate > 0 && exclusions.outside == 0 &&
            exclusions.unprojected == 0)
          return context +
                 ": every contact point of the slave face has a "
                 "degenerate normal (the first at (" +
                 base::to_string(exclusions.first_degenerate) +
                 ")): the face collapses to a point or a line (a collapsed "
                 "edge of the geometry); name another face in "
                 "Contact/Slave face.";
        if (exclusions.outside == 0)
          return context + ": the closest-point projection on " +
                 master.description() +
                 " settled for no contact point of "
                 "Body 1 (the first tried at (" +
                 base::to_string(exclusions.first_unprojected) +
                 ")): check Contact/Slave face and Contact/Master face.";
        return context +
               ": no contact point of Body 1 lies within the "
               "extent of " +
               master.description() + " (the first at (" +
               base::to_string(exclusions.first_outside) +
               ") projects onto its edge): check Contact/Slave face and "
               "Contact/Master face, and the bodies' placement.";
      }



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
                  std::string(
                    ", and so does every other point of Contact/Slave face: "
                    "no part of it faces Contact/Master face; choose the "
                    "faces that touch (Body 1's slave face, Body 2's master "
                    "face).") :
                  std::string(" (check Body 2: a plane's Plane normal "
                              "must point towards Body 1; a cylinder, "
                              "sphere or rigid surface must lie outside "
                              "Body 1, a rigid surface's Contact/Master "
                              "face with its outward side towards it) and "
                              "Contact/Slave face."));
      }



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
    } // namespace internal



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
      this->left_out                      = PairingExclusions<dim>();
      this->left_out.search_distance      = this->search_distance;
      for (const auto &s : slave)
        {
          const discretization::SurfacePoint<dim> m =
            master.deformable() ?
              facing_point(s,
                           samples[index->nearest(s.location)],
                           master,
                           size,
                           context) :
              master.closest_point(s.location, nullptr);
          if (this->left_out
                .keep(s.location, s.normal, m.location, m.normal, size))
            pairs.push_back(make_pair(s, m, master, size, context));
        }
      AssertThrow(!pairs.empty(),
                  base::ExcInput(
                    internal::nothing_faces(context, this->left_out, master)));
      // A point's pressure is its force over its tributary area: a kept
      // point whose collocated area is not positive (the Greville
      // collocation of a face whose parametrisation nearly stops there,
      // next to a repeated control point) cannot carry one, and its pair
      // would give a wrong pressure without a sign of it.
      for (const auto &pair : pairs)
        if (!(pair.area > 0.))
          {
            std::ostringstream o;
            o << "the contact point (" << base::to_string(pair.x1)
              << ") gets the tributary area " << pair.area
              << ", not positive: the face's parametrisation nearly stops "
                 "there (a repeated or nearly repeated control point), and "
                 "a point-wise pair there cannot carry a pressure";
            throw ExcNonPositiveTributaryArea(o.str());
          }
      return pairs;
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
    template Tensor<2, 2>
    local_frame<2>(const Tensor<1, 2> &, const Tensor<2, 2> &);
    template Tensor<2, 3>
    local_frame<3>(const Tensor<1, 3> &, const Tensor<2, 3> &);
    template Tensor<2, 2>
    local_frame_change<2>(const Tensor<1, 2> &,
                          const Tensor<2, 2> &,
                          const Tensor<1, 2> &);
    template Tensor<2, 3>
    local_frame_change<3>(const Tensor<1, 3> &,
                          const Tensor<2, 3> &,
                          const Tensor<1, 3> &);
    template <int dim>
    std::vector<ContactPair<dim>>
    PairingStrategy<dim>::make_pairs_of(
      const discretization::Body<dim>            &slave_body,
      const std::vector<types::boundary_id>      &slave_faces,
      const ContactSurface<dim>                  &master,
      const std::string                          &context,
      const std::vector<types::global_dof_index> &keys) const
    {
      std::vector<ContactPair<dim>> kept;
      for (ContactPair<dim> &pair :
           make_pairs(slave_body, slave_faces, master, context))
        if (std::binary_search(keys.begin(), keys.end(), pair.slave_key))
          kept.push_back(std::move(pair));
      return kept;
    }



    template <int dim>
    bool
    PairingStrategy<dim>::make_pairs_with_derivatives(
      const discretization::Body<dim> &,
      const std::vector<types::boundary_id> &,
      const ContactSurface<dim> &,
      const std::string &,
      const std::vector<types::global_dof_index> &,
      std::vector<ContactPair<dim>> &,
      std::vector<PairDerivatives<dim>> &) const
    {
      return false;
    }



    template class PairingStrategy<2>;
    template class PairingStrategy<3>;
    template class PointPairing<2>;
    template class PointPairing<3>;
    template class NodeToNodePairing<2>;
    template class NodeToNodePairing<3>;
    template class NodeToSurfacePairing<2>;
    template class NodeToSurfacePairing<3>;
    template std::string
    internal::not_facing<2>(const std::string &,
                            const Point<2> &,
                            const ContactSurface<2> &);
    template std::string
    internal::not_facing<3>(const std::string &,
                            const Point<3> &,
                            const ContactSurface<3> &);
    template struct PairingExclusions<2>;
    template struct PairingExclusions<3>;
    template std::string
    internal::nothing_faces<2>(const std::string &,
                               const PairingExclusions<2> &,
                               const ContactSurface<2> &);
    template std::string
    internal::nothing_faces<3>(const std::string &,
                               const PairingExclusions<3> &,
                               const ContactSurface<3> &);
    template std::string
    internal::penetrates<2>(const std::string &,
                            const ContactSurface<2> &,
                            const double);
    template std::string
    internal::penetrates<3>(const std::string &,
                            const ContactSurface<3> &,
                            const double);
    template std::unique_ptr<PairingStrategy<2>>
    create_pairing_strategy<2>(const Pairing);
    template std::unique_ptr<PairingStrategy<3>>
    create_pairing_strategy<3>(const Pairing);
  } // namespace contact
} // namespace igabde
