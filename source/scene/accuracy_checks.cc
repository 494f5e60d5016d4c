// The accuracy checks of a scene (Checks: uniform pressure, Hertz line,
// point and elliptical contact, the rounded punch, error norms against an
// exact solution), after the last load step: the AccuracyChecks
// postprocessor.

#include <igabde/base/utilities.h>

#include <igabde/nurbs/nurbs_patch.h>

#include <igabde/discretization/body_description.h>

#include <igabde/postprocess/contact_checks.h>
#include <igabde/scene/postprocessors.h>
#include <igabde/scene/step_results.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <tuple>

namespace igabde
{
  namespace scene
  {
    namespace
    {
      /// The Hertz check's axis: Checks/Hertz axis point and direction,
      /// empty ones the origin and the last coordinate direction.
      template <int dim>
      std::pair<Point<dim>, Tensor<1, dim>>
      hertz_axis(const ChecksParameters &checks)
      {
        Point<dim>     point;
        Tensor<1, dim> direction;
        direction[dim - 1] = 1.;
        if (!checks.hertz_axis_point.empty())
          point = point_of<dim>(checks.hertz_axis_point);
        if (!checks.hertz_axis_direction.empty())
          direction = point_of<dim>(checks.hertz_axis_direction);
        return {point, direction};
      }



      /**
       * The depth of the elements next to the patch face @p face (their
       * size along the face's outward normal) where the most heavily
       * loaded pair of @p pairs sits: the span of the face's normal
       * parametric direction next to the face, mapped by the Jacobian there.
       */
      template <int dim>
      double
      element_depth_under_contact(
        const nurbs::NurbsPatch<dim>               &patch,
        const unsigned int                          face,
        const std::vector<contact::PairState<dim>> &pairs)
      {
        const contact::PairState<dim> *centre = nullptr;
        for (const auto &pair : pairs)
          if (pair.area > 0. &&
              (centre == nullptr || pair.pressure() > centre->pressure()))
            centre = &pair;
        if (centre == nullptr || !(centre->pressure() > 0.))
          return 0.;
        const Point<dim> xi =
          patch.closest_point_on_face(face, centre->location);
        const unsigned int         d      = face / 2;
        const std::vector<double> &breaks = patch.breakpoints(d);
        const double               h =
          (face % 2 == 0 ? breaks[1] - breaks[0] :
                           breaks.back() - breaks[breaks.size() - 2]);
        const Tensor<2, dim> J = patch.jacobian(xi);
        Tensor<1, dim>       dx;
        for (unsigned int i = 0; i < dim; ++i)
          dx[i] = J[i][d] * h;
        return std::abs(dx * patch.outward_normal(face, xi));
      }



      /**
       * The accuracy checks after the last load step: error norms against
       * the exact solution and the contact checks the scene asks for
       * (uniform pressure, Hertz), into the summary's checks and warnings,
       * a line each to the log.
       */
      template <int dim>
      class AccuracyChecks : public Postprocessor<dim>
      {
      public:
        std::string
        timer_section() const override
        {
          return "postprocess";
        }

        void
        execute(const StepContext<dim> &context,
                StepRecord &,
                RunSummary &summary) override
        {
          if (!context.last_step)
            return;
          const auto              &parameters = context.parameters;
          const auto              &bodies     = context.bodies;
          const auto              &exact      = context.exact;
          const auto              *pairs      = context.pairs;
          const auto              &u          = context.u;
          const auto              &factors    = context.factors;
          auto                    &pcout      = context.screen;
          nlohmann::json           checks     = nlohmann::json::object();
          std::vector<std::string> warnings;
          const auto               report_warnings =
            [&](const std::vector<std::string> &messages) {
              for (const std::string &w : messages)
                {
                  pcout << "  warning: " << w << std::endl;
                  warnings.push_back(w);
                }
            };
          // The checks' references (exact solutions, the uniform pressure, the
          // Hertz loads) are for every load history at factor 1. The last
          // step's factors scale them when every history that loads or moves a
          // body has the same factor lambda (elasticity is linear, and the
          // Hertz references follow their load); otherwise none applies.
          std::vector<double> acting;
          for (const auto &body : bodies)
            for (unsigned int h = 0; h < body->n_histories(); ++h)
              if (body->description().acts_in_history(h))
                acting.push_back(h < factors.size() ? factors[h] : 0.);
          const bool common =
            std::all_of(acting.begin(), acting.end(), [&](const double f) {
              return f == acting.front();
            });
          const double lambda = acting.empty() ? 1. : acting.front();
          const bool   contact_checks =
            pairs != nullptr && (parameters.checks.uniform_pressure > 0. ||
                                 parameters.checks.hertz_line_load > 0. ||
                                 parameters.checks.hertz_point_load > 0. ||
                                 parameters.checks.rounded_punch_load > 0.);
          const bool any_check        = exact || contact_checks;
          const bool references_apply = common && lambda != 0.;
          if (any_check && !references_apply)
            {
              std::ostringstream w;
              w << "Checks: the references are for the loads at factor 1, and "
                << (common ? "the last step's factors are 0" :
                             "the last step's load histories have different "
                             "factors (Load path)")
                << ", so no check is evaluated; end the load path with every "
                   "factor at 1 (or all at one value, which scales the "
                   "references)";
              report_warnings({w.str()});
            }
          else if (any_check && lambda != 1.)
            {
              checks["reference_factor"] = lambda;
              pcout
                << "  checks: the references scaled by the last step's factor "
                << lambda << std::endl;
            }
          if (exact && references_apply)
            {
              Vector<double> scaled = u[0];
              scaled /= lambda;
              const auto norms = bodies[0]->compute_errors(scaled, *exact);
              AssertThrow(std::isfinite(norms.l2_relative) &&
                            std::isfinite(norms.energy_relative),
                          ExcMessage(
                            "the error norms are not finite (overflow "
                            "in the exact solution or the field: check "
                            "the loads and Young's modulus of the "
                            "scene)."));
              checks["l2_error"]     = norms.l2_relative;
              checks["energy_error"] = norms.energy_relative;
              pcout << "  relative L2 error " << std::setprecision(4)
                    << std::scientific << norms.l2_relative
                    << ", relative energy error " << norms.energy_relative
                    << std::defaultfloat << std::setprecision(6) << std::endl;
            }

          if (contact_checks && references_apply && lambda < 0.)
            report_warnings(
              {"Checks: the contact checks' references are for a pressing load, "
               "and the last step's factors are negative, so they are not "
               "evaluated"});
          // The contact checks of one group of pairs: every pair with one
          // interaction, or each interaction's own (E* from its two bodies,
          // the depth of its slave's elements), into @p out.
          const auto contact_checks_of =
            [&](const std::vector<contact::PairState<dim>> &group,
                const InteractionParameters                &interaction,
                const std::string                          &label,
                nlohmann::json                             &out) {
              const std::vector<unsigned int> deformable =
                parameters.deformable_bodies();
              const auto position = [&](const unsigned int scene_body) {
                const auto i = std::find(deformable.begin(),
                                         deformable.end(),
                                         scene_body - 1);
                return i == deformable.end() ?
                         numbers::invalid_unsigned_int :
                         static_cast<unsigned int>(i - deformable.begin());
              };
              const discretization::Body<dim> &slave =
                *bodies[position(interaction.slave_body)];
              const unsigned int m = position(interaction.master_body);
              const elasticity::IsotropicMaterial<dim> *master =
                m < bodies.size() ? &bodies[m]->material() : nullptr;
              if (parameters.checks.uniform_pressure > 0.)
                {
                  const double worst = postprocess::pressure_uniformity<dim>(
                    group,
                    lambda * parameters.checks.uniform_pressure);
                  out["pressure_uniformity"] = worst;
                  // Below 1e-10 the figure is round-off: said, not printed.
                  pcout << "  " << label
                        << "pressure uniformity max |p_i/p - 1| "
                        << std::setprecision(3) << std::scientific;
                  if (worst < 1e-10)
                    pcout << "< 1e-10";
                  else
                    pcout << "= " << worst;
                  pcout << std::defaultfloat << std::setprecision(6)
                        << std::endl;
                }
              // What every Hertz check takes: E* of the two bodies (the
              // second rigid when there is none) and the axis.
              const auto set_modulus_and_axis = [&](auto &hertz) {
                hertz.effective_modulus =
                  postprocess::effective_modulus<dim>(slave.material(), master);
                std::tie(hertz.axis_point, hertz.axis_direction) =
                  hertz_axis<dim>(parameters.checks);
              };
              // The line and the sphere's checks also take the radius and
              // the depth of Body 1's elements under the contact.
              const auto set_hertz_inputs = [&](auto &hertz) {
                // Default: the curved body's radius, the rigid
                // obstacle's when Body 2 is a cylinder or sphere.
                const BodyParameters &other =
                  parameters.bodies[interaction.master_body - 1];
                hertz.radius =
                  parameters.checks.hertz_radius > 0. ?
                    parameters.checks.hertz_radius :
                    (other.type == BodyType::rigid_cylinder ||
                         other.type == BodyType::rigid_sphere ?
                       other.radius :
                       parameters.bodies[interaction.slave_body - 1].radius);
                set_modulus_and_axis(hertz);
                hertz.element_depth = element_depth_under_contact(
                  slave.geometry_patch(discretization::patch_of_face<dim>(
                    interaction.slave_faces.front())),
                  discretization::local_face<dim>(
                    interaction.slave_faces.front()),
                  group);
              };
              // Hertz's and Johnson's solutions are frictionless. Friction
              // leaves them exact only between similar bodies (Dundurs beta =
              // 0); between dissimilar ones (a rigid plane, other moduli) it
              // changes the contact (Spence's problem), so the check's
              // differences are not the discretisation's alone (|beta| below
              // 1e-3: negligible).
              const auto friction_note = [&](const std::string &reference) {
                std::vector<std::string> note;
                const double             beta =
                  postprocess::dundurs_beta<dim>(slave.material(), master);
                if (interaction.friction_coefficient > 0. &&
                    std::abs(beta) >= 1e-3)
                  {
                    std::ostringstream w;
                    w << "Checks: " << reference
                      << " solution is frictionless; "
                         "with Contact/Friction coefficient = "
                      << interaction.friction_coefficient
                      << " between dissimilar bodies (Dundurs beta = "
                      << std::setprecision(3) << beta
                      << ") friction changes the contact (Spence's problem), "
                         "so the differences to it are not the "
                         "discretisation's alone";
                    note.push_back(w.str());
                  }
                return note;
              };
              if (parameters.checks.hertz_line_load > 0.)
                {
                  if constexpr (dim == 2)
                    {
                      postprocess::HertzCheck hertz;
                      hertz.line_load =
                        lambda * parameters.checks.hertz_line_load;
                      set_hertz_inputs(hertz);
                      const auto r                  = hertz.evaluate(group);
                      out["hertz_half_width"]       = r.half_width;
                      out["hertz_half_width_exact"] = r.half_width_exact;
                      out["hertz_half_width_error"] =
                        std::abs(r.half_width / r.half_width_exact - 1.);
                      out["hertz_peak_pressure"]       = r.peak_pressure;
                      out["hertz_peak_pressure_exact"] = r.peak_pressure_exact;
                      out["pressure_l2_rel_error"]     = r.profile_l2_error;
                      out["hertz_loaded_pairs"]        = r.n_loaded;
                      out["hertz_edge_pair_spacing"]   = r.edge_pair_spacing;
                      out["hertz_half_width_moment"]   = r.half_width_moment;
                      out["hertz_half_width_moment_error"] =
                        std::abs(r.half_width_moment / r.half_width_exact - 1.);
                      out["hertz_max_pair_deviation"] = r.max_pair_deviation;
                      out["hertz_inner_pairs"]        = r.n_inner_pairs;
                      pcout << "  " << label << "Hertz: half-width "
                            << std::setprecision(5) << r.half_width
                            << " (Johnson " << r.half_width_exact
                            << "), peak pressure " << r.peak_pressure
                            << " (Johnson " << r.peak_pressure_exact
                            << "), profile L2 error " << std::setprecision(3)
                            << r.profile_l2_error << std::setprecision(6)
                            << std::endl;
                      report_warnings(r.warnings);
                      report_warnings(friction_note("Johnson's"));
                    }
                }
              if (parameters.checks.rounded_punch_load > 0.)
                {
                  if constexpr (dim == 2)
                    {
                      postprocess::RoundedPunchCheck punch;
                      punch.line_load =
                        lambda * parameters.checks.rounded_punch_load;
                      punch.flat_half_width =
                        parameters.checks.rounded_punch_flat_half_width;
                      punch.corner_radius =
                        parameters.checks.rounded_punch_corner_radius;
                      set_modulus_and_axis(punch);
                      const auto r                     = punch.evaluate(group);
                      out["punch_half_width_exact"]    = r.half_width_exact;
                      out["punch_peak_pressure"]       = r.peak_pressure;
                      out["punch_peak_pressure_exact"] = r.peak_pressure_exact;
                      out["punch_peak_location_exact"] = r.peak_location_exact;
                      out["punch_max_pair_deviation"]  = r.max_pair_deviation;
                      out["punch_loaded_pairs"]        = r.n_loaded;
                      out["punch_inner_pairs"]         = r.n_inner_pairs;
                      pcout
                        << "  " << label << "rounded punch: peak pressure "
                        << std::setprecision(5) << r.peak_pressure
                        << " (closed form " << r.peak_pressure_exact
                        << " at |x| = " << r.peak_location_exact
                        << "), half-width " << r.half_width_exact
                        << ", largest pair deviation " << std::setprecision(3)
                        << 100. * r.max_pair_deviation
                        << " % of the peak inside 0.9 a" << std::setprecision(6)
                        << std::endl;
                      report_warnings(
                        friction_note("Ciavarella, Hills and Monno's"));
                    }
                }
              if (parameters.checks.hertz_point_load > 0. &&
                  !parameters.checks.hertz_curvatures.empty())
                {
                  if constexpr (dim == 3)
                    {
                      const auto &k = parameters.checks.hertz_curvatures;
                      const auto &t =
                        parameters.checks.hertz_principal_direction;
                      postprocess::HertzEllipticCheck hertz;
                      hertz.load = lambda * parameters.checks.hertz_point_load;
                      hertz.curvature_x = 0.5 * (k[0] + k[2]);
                      hertz.curvature_y = 0.5 * (k[1] + k[3]);
                      set_modulus_and_axis(hertz);
                      hertz.principal_direction =
                        Tensor<1, 3>({t[0], t[1], t[2]});
                      const auto  r                 = hertz.evaluate(group);
                      const auto &x                 = r.exact;
                      out["hertz_semi_axes_exact"]  = {x.semi_axis_x,
                                                       x.semi_axis_y};
                      out["hertz_eccentricity"]     = x.eccentricity;
                      out["hertz_semi_axes_moment"] = {r.semi_axis_x_moment,
                                                       r.semi_axis_y_moment};
                      out["hertz_semi_axes_moment_error"] = std::max(
                        std::abs(r.semi_axis_x_moment / x.semi_axis_x - 1.),
                        std::abs(r.semi_axis_y_moment / x.semi_axis_y - 1.));
                      out["hertz_peak_pressure"]       = r.peak_pressure;
                      out["hertz_peak_pressure_exact"] = x.peak_pressure;
                      out["hertz_peak_pressure_error"] =
                        std::abs(r.peak_pressure / x.peak_pressure - 1.);
                      out["pressure_l2_rel_error"] = r.profile_l2_error;
                      out["hertz_loaded_pairs"]    = r.n_loaded;
                      pcout << "  " << label << "Hertz (elliptical): semi-axes "
                            << std::setprecision(5) << r.semi_axis_x_moment
                            << ", " << r.semi_axis_y_moment << " (Hertz "
                            << x.semi_axis_x << ", " << x.semi_axis_y
                            << "), peak pressure " << r.peak_pressure
                            << " (Hertz " << x.peak_pressure
                            << "), profile L2 error " << std::setprecision(3)
                            << r.profile_l2_error << std::setprecision(6)
                            << std::endl;
                      report_warnings(r.warnings);
                      report_warnings(friction_note("Hertz's"));
                    }
                }
              else if (parameters.checks.hertz_point_load > 0.)
                {
                  if constexpr (dim == 3)
                    {
                      postprocess::HertzPointCheck hertz;
                      hertz.load = lambda * parameters.checks.hertz_point_load;
                      set_hertz_inputs(hertz);
                      const auto r                = hertz.evaluate(group);
                      out["hertz_contact_radius"] = r.contact_radius;
                      out["hertz_contact_radius_exact"] =
                        r.contact_radius_exact;
                      out["hertz_contact_radius_error"] = std::abs(
                        r.contact_radius / r.contact_radius_exact - 1.);
                      out["hertz_contact_radius_moment"] =
                        r.contact_radius_moment;
                      out["hertz_contact_radius_moment_error"] = std::abs(
                        r.contact_radius_moment / r.contact_radius_exact - 1.);
                      out["hertz_peak_pressure"]       = r.peak_pressure;
                      out["hertz_peak_pressure_exact"] = r.peak_pressure_exact;
                      out["hertz_peak_pressure_error"] =
                        std::abs(r.peak_pressure / r.peak_pressure_exact - 1.);
                      out["pressure_l2_rel_error"]    = r.profile_l2_error;
                      out["hertz_max_pair_deviation"] = r.max_pair_deviation;
                      out["hertz_inner_pairs"]        = r.n_inner_pairs;
                      out["hertz_loaded_pairs"]       = r.n_loaded;
                      out["hertz_fitted_pairs"]       = r.n_fitted;
                      pcout << "  " << label << "Hertz: contact radius "
                            << std::setprecision(5) << r.contact_radius
                            << " (Hertz " << r.contact_radius_exact
                            << "), peak pressure " << r.peak_pressure
                            << " (Hertz " << r.peak_pressure_exact
                            << "), profile L2 error " << std::setprecision(3)
                            << r.profile_l2_error << std::setprecision(6)
                            << std::endl;
                      report_warnings(r.warnings);
                      report_warnings(friction_note("Hertz's"));
                    }
                }
            };
          if (pairs != nullptr && references_apply && lambda > 0.)
            {
              const auto &interactions = parameters.contact.interactions;
              if (interactions.size() == 1)
                contact_checks_of(*pairs, interactions[0], "", checks);
              else
                {
                  // Each interaction on its own pairs; the top-level keys
                  // are the first's, but the pressure uniformity is the
                  // worst of all.
                  nlohmann::json list  = nlohmann::json::array();
                  double         worst = 0.;
                  for (unsigned int k = 0; k < interactions.size(); ++k)
                    {
                      std::vector<contact::PairState<dim>> group;
                      for (const auto &pair : *pairs)
                        if (pair.interaction == k)
                          group.push_back(pair);
                      nlohmann::json out = nlohmann::json::object();
                      contact_checks_of(group,
                                        interactions[k],
                                        interactions[k].name + ": ",
                                        out);
                      if (out.contains("pressure_uniformity"))
                        worst =
                          std::max(worst,
                                   out["pressure_uniformity"].get<double>());
                      if (k == 0)
                        checks.update(out);
                      out["name"] = interactions[k].name;
                      list.push_back(out);
                    }
                  if (checks.contains("pressure_uniformity"))
                    checks["pressure_uniformity"] = worst;
                  checks["interactions"] = list;
                }
            }
          summary.checks = checks;
          summary.warnings.insert(summary.warnings.end(),
                                  warnings.begin(),
                                  warnings.end());
        }
      };
    } // namespace



    template <int dim>
    std::unique_ptr<Postprocessor<dim>>
    make_accuracy_checks()
    {
      return std::make_unique<AccuracyChecks<dim>>();
    }



    template std::unique_ptr<Postprocessor<2>>
    make_accuracy_checks<2>();
    template std::unique_ptr<Postprocessor<3>>
    make_accuracy_checks<3>();
  } // namespace scene
} // namespace igabde
