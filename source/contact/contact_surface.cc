#include <igabde/base/utilities.h>

#include <igabde/contact/contact_surface.h>

#include <limits>

namespace igabde
{
  namespace contact
  {
    template <int dim>
    BodyFace<dim>::BodyFace(const discretization::Body<dim>       &body,
                            const std::vector<types::boundary_id> &faces)
      : body(body)
      , faces(faces)
    {
      Assert(!faces.empty(), ExcInternalError());
      if (faces.size() == 1)
        {
          samples = body.surface_points(faces[0]);
          return;
        }
      // Several faces: each alone (its samples computed once, there),
      // their samples together, and each face's indexed.
      for (const types::boundary_id face : faces)
        {
          single_faces.push_back(std::make_unique<BodyFace<dim>>(
            body,
            std::vector<types::boundary_id>{face}));
          const auto &points = single_faces.back()->sample_points();
          samples.insert(samples.end(), points.begin(), points.end());
          std::vector<Point<dim>> locations;
          for (const auto &p : points)
            locations.push_back(p.location);
          face_index.push_back(
            std::make_unique<base::NearestPoints<dim>>(locations));
        }
    }



    template <int dim>
    std::vector<const ContactSurface<dim> *>
    BodyFace<dim>::parts() const
    {
      if (single_faces.empty())
        return {this};
      std::vector<const ContactSurface<dim> *> result;
      for (const auto &face : single_faces)
        result.push_back(face.get());
      return result;
    }



    template <int dim>
    bool
    BodyFace<dim>::normal_continuous() const
    {
      // Where the normal may turn, at an element edge (C^0: FE_Q, degree
      // 1, a repeated knot) or where two of the faces meet, it must turn
      // by less than 0.05 (3 degrees): tangent-continuous geometry bent by
      // the strain (a circle's double knot or two quarter rings under a
      // die's contact: 0.017 measured on the 3D ironing die), not the
      // facets of a curved FE_Q(1) face (0.1 on the 2D ironing die's 32).
      // Checked on every break line of each face at its elements'
      // midpoints, the normals either side, and on a face's edges against
      // the other faces there. A NURBS face of degree 2 or more with
      // single knots passes: it is C^1.
      const std::vector<const ContactSurface<dim> *> all  = parts();
      const double                                   turn = 5e-2;
      for (unsigned int p = 0; p < all.size(); ++p)
        {
          const auto grid = all[p]->face_grid();
          for (unsigned int k = 0; k + 1 < dim; ++k)
            {
              const auto  &breaks = grid.breaks[k];
              const double extent = breaks.back() - breaks.front();
              // Points along the other face direction (3D): its elements'
              // midpoints.
              std::vector<double> across = {0.};
              if constexpr (dim == 3)
                {
                  const auto &other = grid.breaks[1 - k];
                  across.clear();
                  for (unsigned int e = 0; e + 1 < other.size(); ++e)
                    across.push_back(0.5 * (other[e] + other[e + 1]));
                }
              for (unsigned int b = 0; b < breaks.size(); ++b)
                for (const double a : across)
                  {
                    Point<dim - 1> eta;
                    if constexpr (dim == 3)
                      eta[1 - k] = a;
                    const bool end = b == 0 || b + 1 == breaks.size();
                    if (!end)
                      {
                        eta[k]        = breaks[b] - 1e-9 * extent;
                        const auto lo = all[p]->face_point(eta);
                        eta[k]        = breaks[b] + 1e-9 * extent;
                        const auto hi = all[p]->face_point(eta);
                        if ((lo.normal - hi.normal).norm() > turn)
                          return false;
                        continue;
                      }
                    eta[k]             = breaks[b];
                    const auto   point = all[p]->face_point(eta);
                    const double size  = point.tangents[k].norm() * extent;
                    for (unsigned int q = 0; q < all.size(); ++q)
                      {
                        if (q == p)
                          continue;
                        const auto &samples = all[q]->sample_points();
                        if (samples.empty())
                          continue;
                        const auto *nearest = &samples.front();
                        for (const auto &sample : samples)
                          if (sample.location.distance(point.location) <
                              nearest->location.distance(point.location))
                            nearest = &sample;
                        const auto other =
                          all[q]->closest_point(point.location, nearest);
                        if (other.location.distance(point.location) <
                              1e-8 * size &&
                            (other.normal - point.normal).norm() > turn)
                          return false;
                      }
                  }
            }
        }
      return true;
    }



    template <int dim>
    bool
    BodyFace<dim>::deformable() const
    {
      return true;
    }



    template <int dim>
    std::string
    BodyFace<dim>::description() const
    {
      std::string names;
      for (const types::boundary_id face : faces)
        names += (names.empty() ? "" : "+") + body.face_name(face);
      return body.name() + "'s face " + names;
    }



    template <int dim>
    const std::vector<discretization::SurfacePoint<dim>> &
    BodyFace<dim>::sample_points() const
    {
      return samples;
    }



    template <int dim>
    discretization::SurfacePoint<dim>
    BodyFace<dim>::closest_point(
      const Point<dim>                        &location,
      const discretization::SurfacePoint<dim> *nearest) const
    {
      Assert(nearest != nullptr, ExcInternalError());
      if (faces.size() == 1)
        return body.closest_surface_point(faces[0], location, *nearest);
      // Every face from its own nearest sample; the closest wins.
      discretization::SurfacePoint<dim> best;
      double best_distance = std::numeric_limits<double>::max();
      for (unsigned int k = 0; k < single_faces.size(); ++k)
        {
          const auto &face_samples = single_faces[k]->sample_points();
          if (face_samples.empty())
            continue;
          const auto point = single_faces[k]->closest_point(
            location,
            &face_samples[face_index[k]->nearest(location)]);
          const double distance = point.location.distance(location);
          if (distance < best_distance)
            {
              best_distance = distance;
              best          = point;
            }
        }
      return best;
    }



    template <int dim>
    discretization::FaceGrid<dim>
    ContactSurface<dim>::face_grid() const
    {
      AssertThrow(false,
                  ExcMessage(description() + " has no face coordinates."));
      return {};
    }



    template <int dim>
    discretization::FacePoint<dim>
    ContactSurface<dim>::face_point(const Point<dim - 1> &) const
    {
      AssertThrow(false,
                  ExcMessage(description() + " has no face coordinates."));
      return {};
    }



    template <int dim>
    discretization::FaceSecondDerivatives<dim>
    ContactSurface<dim>::face_second_derivatives(const Point<dim - 1> &) const
    {
      AssertThrow(false,
                  ExcMessage(description() + " has no face coordinates."));
      return {};
    }



    template <int dim>
    discretization::FaceGrid<dim>
    BodyFace<dim>::face_grid() const
    {
      AssertThrow(faces.size() == 1,
                  ExcMessage(description() +
                             ": face coordinates exist on each patch face "
                             "alone (parts())."));
      return body.face_grid(faces[0]);
    }



    template <int dim>
    discretization::FacePoint<dim>
    BodyFace<dim>::face_point(const Point<dim - 1> &eta) const
    {
      return body.face_point(faces[0], eta);
    }



    template <int dim>
    discretization::FaceSecondDerivatives<dim>
    BodyFace<dim>::face_second_derivatives(const Point<dim - 1> &eta) const
    {
      return body.face_second_derivatives(faces[0], eta);
    }



    template class ContactSurface<2>;
    template class ContactSurface<3>;
    template class BodyFace<2>;
    template class BodyFace<3>;
  } // namespace contact
} // namespace igabde
