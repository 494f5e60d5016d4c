#include <igabde/base/files.h>
#include <igabde/base/nearest_points.h>
#include <igabde/base/utilities.h>

#include <igabde/contact/contact_surface.h>

#include <igabde/postprocess/contact_output.h>

#include <deal.II/base/data_out_base.h>

#include <deal.II/numerics/data_component_interpretation.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <iomanip>
#include <limits>

namespace igabde
{
  namespace postprocess
  {
    using namespace dealii;

    template <int dim>
    std::vector<double>
    recovered_pressures(const discretization::Body<dim>            &body1,
                        const std::vector<types::boundary_id>      &faces,
                        const Vector<double>                       &u1,
                        const std::vector<contact::PairState<dim>> &pairs)
    {
      std::vector<double> p(pairs.size(),
                            std::numeric_limits<double>::quiet_NaN());
      if (pairs.empty())
        return p;
      const contact::BodyFace<dim> surface(body1, faces);
      const auto                  &samples = surface.sample_points();
      std::vector<Point<dim>>      locations;
      for (const auto &s : samples)
        locations.push_back(s.location);
      const base::NearestPoints<dim> index(std::move(locations));
      for (unsigned int i = 0; i < pairs.size(); ++i)
        {
          // The pair's point where the body's stress is (its reference
          // position: the pair's own location unless it slides finitely).
          const Point<dim> &at      = pairs[i].material_location;
          const auto       &nearest = samples[index.nearest(at)];
          // The closest point of the contact face; its nearest sample
          // point (on the face too) if the stress cannot be evaluated
          // there (a Lagrange face's projection just past its side). The
          // normal is Body 1's outward normal at that point, not the
          // pair's: a weighted-gap pair's frame is the master's, and on
          // a curved face away from the contact -n.sigma.n with the
          // master's normal reads the hoop stress, not the (zero) traction.
          const auto closest = surface.closest_point(at, &nearest);
          for (const auto *x : {&closest, &nearest})
            try
              {
                p[i] = -x->normal * (body1.stress(u1, x->location) * x->normal);
                break;
              }
            catch (const ExceptionBase &)
              {}
        }
      return p;
    }



    template <int dim>
    void
    write_pair_csv(const std::vector<contact::PairState<dim>> &pairs,
                   const std::vector<double>                  &recovered,
                   const std::string                          &filename)
    {
      std::ofstream      csv = base::open_for_writing(filename);
      const unsigned int m =
        pairs.empty() ? 1 : pairs.front().force_local.size();
      // The interaction (1-based) only when there are several.
      const bool interactions =
        std::any_of(pairs.begin(), pairs.end(), [](const auto &pair) {
          return pair.interaction > 0;
        });
      csv << "pair";
      if (interactions)
        csv << ",interaction";
      const char *xyz = "xyz";
      for (unsigned int d = 0; d < dim; ++d)
        csv << "," << xyz[d];
      csv << ",area,gap,p_n";
      for (unsigned int s = 1; s < m; ++s)
        csv << ",p_t" << s;
      csv << ",pressure,recovered_pressure";
      for (unsigned int s = 1; s < m; ++s)
        csv << ",slip_t" << s;
      csv << ",status\n" << std::setprecision(12);
      for (unsigned int i = 0; i < pairs.size(); ++i)
        {
          const auto &pair = pairs[i];
          csv << i;
          if (interactions)
            csv << "," << pair.interaction + 1;
          for (unsigned int d = 0; d < dim; ++d)
            csv << "," << pair.location[d];
          csv << "," << pair.area << "," << pair.displacement_local[0];
          for (unsigned int s = 0; s < m; ++s)
            csv << "," << pair.force_local[s];
          csv << "," << pair.pressure() << "," << recovered[i];
          for (unsigned int s = 1; s < m; ++s)
            csv << "," << pair.displacement_local[s];
          csv << "," << contact::to_string(pair.status) << "\n";
        }
    }



    template <int dim>
    void
    write_pair_vtu(const std::vector<contact::PairState<dim>> &pairs,
                   const std::vector<double>                  &recovered,
                   const std::string                          &filename)
    {
      const bool friction =
        !pairs.empty() && pairs.front().force_local.size() > 1;
      std::vector<std::string> names = {"pressure",
                                        "recovered_pressure",
                                        "gap",
                                        "status"};
      for (unsigned int d = 0; d < dim; ++d)
        names.emplace_back("contact_force");
      if (friction)
        for (unsigned int d = 0; d < dim; ++d)
          names.emplace_back("slip");
      // The interaction (1-based) only when there are several, last.
      const bool interactions =
        std::any_of(pairs.begin(), pairs.end(), [](const auto &pair) {
          return pair.interaction > 0;
        });
      if (interactions)
        names.emplace_back("interaction");
      std::vector<
        std::tuple<unsigned int,
                   unsigned int,
                   std::string,
                   DataComponentInterpretation::DataComponentInterpretation>>
        vectors;
      vectors.emplace_back(
        4,
        4 + dim - 1,
        "contact_force",
        DataComponentInterpretation::component_is_part_of_vector);
      if (friction)
        vectors.emplace_back(
          4 + dim,
          4 + 2 * dim - 1,
          "slip",
          DataComponentInterpretation::component_is_part_of_vector);

      std::vector<DataOutBase::Patch<0, dim>> patches(pairs.size());
      for (unsigned int i = 0; i < pairs.size(); ++i)
        {
          const auto &pair  = pairs[i];
          auto       &patch = patches[i];
          patch.vertices[0] = pair.location;
          patch.patch_index = i;
          patch.data.reinit(names.size(), 1);
          unsigned int row     = 0;
          patch.data(row++, 0) = pair.pressure();
          patch.data(row++, 0) = recovered[i];
          patch.data(row++, 0) = pair.displacement_local[0];
          patch.data(row++, 0) = static_cast<int>(pair.status);
          for (unsigned int d = 0; d < dim; ++d)
            patch.data(row++, 0) = pair.force[d];
          if (friction)
            for (unsigned int d = 0; d < dim; ++d)
              patch.data(row++, 0) = pair.slip[d];
          if (interactions)
            patch.data(row++, 0) = pair.interaction + 1;
        }
      std::ofstream out = base::open_for_writing(filename);
      DataOutBase::write_vtu(patches,
                             names,
                             vectors,
                             base::vtu_flags(patches),
                             out);
    }



    template std::vector<double>
    recovered_pressures<2>(const discretization::Body<2> &,
                           const std::vector<types::boundary_id> &,
                           const Vector<double> &,
                           const std::vector<contact::PairState<2>> &);
    template std::vector<double>
    recovered_pressures<3>(const discretization::Body<3> &,
                           const std::vector<types::boundary_id> &,
                           const Vector<double> &,
                           const std::vector<contact::PairState<3>> &);
    template void
    write_pair_csv<2>(const std::vector<contact::PairState<2>> &,
                      const std::vector<double> &,
                      const std::string &);
    template void
    write_pair_csv<3>(const std::vector<contact::PairState<3>> &,
                      const std::vector<double> &,
                      const std::string &);
    template void
    write_pair_vtu<2>(const std::vector<contact::PairState<2>> &,
                      const std::vector<double> &,
                      const std::string &);
    template void
    write_pair_vtu<3>(const std::vector<contact::PairState<3>> &,
                      const std::vector<double> &,
                      const std::string &);
  } // namespace postprocess
} // namespace igabde
