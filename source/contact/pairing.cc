#include <igabde/base/utilities.h>

#include <igabde/contact/pairing.h>

#include <algorithm>
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
          Tensor<1, dim> b;
          b[0] = n[1] * a[2] - n[2] * a[1];
          b[1] = n[2] * a[0] - n[0] * a[2];
          b[2] = n[0] * a[1] - n[1] * a[0];
          T[2] = b;
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



      /// The index of the sample nearest to @p x.
      template <int dim>
      unsigned int
      nearest_sample(
        const std::vector<discretization::SurfacePoint<dim>> &samples,
        const Point<dim>                                     &x)
      {
        unsigned int best = 0;
        for (unsigned int m = 1; m < samples.size(); ++m)
          if ((samples[m].location - x).norm() <
              (samples[best].location - x).norm())
            best = m;
        return best;
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
        AssertThrow(s.normal * n < 0.,
                    base::ExcInput(
                      context +
                      ": the contact surfaces do not face each "
                      "other at (" +
                      [&] {
                        std::ostringstream o;
                        o << s.location;
                        return o.str();
                      }() +
                      "): the outward normal of Body 1's contact face points "
                      "away from " +
                      master.description() +
                      (master.deformable() ?
                         std::string("; check Contact/Slave face and "
                                     "Contact/Master face.") :
                         std::string(" (check Body 2/Plane normal: it must "
                                     "point towards Body 1) and Contact/Slave "
                                     "face."))));
        pair.frame = local_frame<dim>(n);
        pair.gap   = (pair.x1 - pair.x2) * n;
        AssertThrow(pair.gap >= -1e-10 * size,
                    base::ExcInput(context + ": Body 1 initially penetrates " +
                                   master.description() + " (gap " +
                                   std::to_string(pair.gap) +
                                   "); move the bodies apart."));
        pair.gap = std::max(pair.gap, 0.);
        return pair;
      }
    } // namespace



    template <int dim>
    std::vector<ContactPair<dim>>
    PairingStrategy<dim>::make_pairs(
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
      for (const auto &s : slave)
        pairs.push_back(
          make_pair(s,
                    master.deformable() ?
                      facing_point(s,
                                   samples[nearest_sample(samples, s.location)],
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



    std::vector<std::string>
    available_pairing_strategies()
    {
      return {"node-to-surface", "node-to-node"};
    }



    template <int dim>
    std::unique_ptr<PairingStrategy<dim>>
    create_pairing_strategy(const std::string &name)
    {
      // One line per strategy.
      if (name == "node-to-surface")
        return std::make_unique<NodeToSurfacePairing<dim>>();
      if (name == "node-to-node")
        return std::make_unique<NodeToNodePairing<dim>>();

      std::string names;
      for (const auto &n : available_pairing_strategies())
        names += (names.empty() ? "" : ", ") + n;
      AssertThrow(false,
                  base::ExcInput("Contact/Pairing = " + name +
                                 " is not available; use one of: " + names +
                                 "."));
      return nullptr;
    }



    template Tensor<2, 2>
    local_frame<2>(const Tensor<1, 2> &);
    template Tensor<2, 3>
    local_frame<3>(const Tensor<1, 3> &);
    template class PairingStrategy<2>;
    template class PairingStrategy<3>;
    template class NodeToNodePairing<2>;
    template class NodeToNodePairing<3>;
    template class NodeToSurfacePairing<2>;
    template class NodeToSurfacePairing<3>;
    template std::unique_ptr<PairingStrategy<2>>
    create_pairing_strategy<2>(const std::string &);
    template std::unique_ptr<PairingStrategy<3>>
    create_pairing_strategy<3>(const std::string &);
  } // namespace contact
} // namespace igabde
