#include <igabde/base/utilities.h>

#include <igabde/discretization/nurbs_surface.h>

#include <igabde/postprocess/exact_solutions.h>
#include <igabde/scene/body_factory.h>
#include <igabde/scene/geometry.h>

#include <deal.II/base/function_parser.h>

namespace igabde
{
  namespace scene
  {



    template <int dim>
    std::optional<discretization::ExactSolution<dim>>
    make_exact_solution(const AllParameters &parameters,
                        const std::string   &scene_file)
    {
      elasticity::IsotropicMaterial<dim> material;
      material.youngs_modulus = parameters.bodies[0].youngs_modulus;
      material.poisson_ratio  = parameters.bodies[0].poisson_ratio;
      material.plane_model    = parameters.plane_model;
      const auto &e           = parameters.exact;
      if (e.type == ExactSolutionType::kirsch)
        {
          AssertThrow(dim == 2,
                      base::ExcInput(scene_file +
                                     ": Exact solution/Type = kirsch is a "
                                     "2D solution; set Dimension = 2."));
          if constexpr (dim == 2)
            return postprocess::kirsch_solution(e.remote_tension,
                                                e.hole_radius,
                                                material);
        }
      else if (e.type == ExactSolutionType::lame)
        return postprocess::lame_solution<dim>(e.inner_radius,
                                               e.outer_radius,
                                               e.pressure,
                                               material);
      return std::nullopt;
    }



    template <int dim>
    discretization::BodyDescription<dim>
    make_body_description(
      const AllParameters                                     &parameters,
      const BodyParameters                                    &body,
      const std::string                                       &name,
      const std::string                                       &scene_file,
      const std::optional<discretization::ExactSolution<dim>> &exact)
    {
      const std::string where = scene_file + ": " + name + "/";
      discretization::BodyDescription<dim> d;
      // "Body 3" -> "body3": file names and log lines.
      d.name                    = "body" + name.substr(name.find(' ') + 1);
      d.material.youngs_modulus = body.youngs_modulus;
      d.material.poisson_ratio  = body.poisson_ratio;
      d.material.plane_model    = parameters.plane_model;
      d.material.validate(scene_file + ": " + name);
      d.kinematics = body.kinematics;
      d.model      = body.material;

      {
        nurbs::MultiPatchGeometry<dim> geometry =
          make_geometry<dim>(body, where, parameters.discretization.degree);
        d.geometry = std::move(geometry.patches.front());
        d.more_patches.assign(std::make_move_iterator(geometry.patches.begin() +
                                                      1),
                              std::make_move_iterator(geometry.patches.end()));
        d.interfaces = std::move(geometry.interfaces);
        d.notes      = std::move(geometry.notes);
      }

      // The body grammar was read and checked with the parameters
      // (BodyParameters::parse_parameters); here it only becomes
      // dim-dimensional.
      const auto tensor = [](const std::vector<double> &v) {
        Tensor<1, dim> t;
        for (unsigned int i = 0; i < dim; ++i)
          t[i] = v[i];
        return t;
      };
      for (const SupportParameters &support : body.supports)
        {
          discretization::DirichletCondition<dim> bc;
          bc.boundary_id = static_cast<types::boundary_id>(support.face);
          for (unsigned int c = 0; c < dim; ++c)
            {
              bc.components[c] = support.components[c];
              bc.value[c]      = support.values[c];
              if (!support.expressions[c].empty())
                {
                  std::vector<std::string> expressions(dim, "0");
                  expressions[c] = support.expressions[c];
                  const auto f   = make_function_parser<dim>(expressions, 0.);
                  bc.field[c]    = [f, c](const Point<dim> &x) {
                    return f->value(x, c);
                  };
                }
            }
          bc.history = parameters.load_path.history_index(support.history, 1);
          d.dirichlet.push_back(bc);
        }
      // A face motion is a support whose components are the linear field
      // u = d + r x (x - c) about the face's centroid c, or the point the
      // entry names ('about').
      for (const FaceMotionParameters &motion : body.face_motions)
        {
          discretization::DirichletCondition<dim> bc;
          bc.boundary_id = static_cast<types::boundary_id>(motion.face);
          Point<dim> centre =
            d.patch(discretization::patch_of_face<dim>(motion.face))
              .face_centroid(discretization::local_face<dim>(motion.face));
          if (!motion.centre.empty())
            for (unsigned int c = 0; c < dim; ++c)
              centre[c] = motion.centre[c];
          Tensor<1, dim> displacement;
          for (unsigned int c = 0; c < dim; ++c)
            displacement[c] = motion.motion[c];
          const std::vector<double> rotation(motion.motion.begin() + dim,
                                             motion.motion.end());
          const auto                field =
            [displacement, rotation, centre](const Point<dim> &x) {
              const Tensor<1, dim> y = x - centre;
              Tensor<1, dim>       u = displacement;
              if constexpr (dim == 2)
                {
                  u[0] -= rotation[0] * y[1];
                  u[1] += rotation[0] * y[0];
                }
              else
                for (unsigned int a = 0; a < 3; ++a)
                  u[a] += rotation[(a + 1) % 3] * y[(a + 2) % 3] -
                          rotation[(a + 2) % 3] * y[(a + 1) % 3];
              return u;
            };
          for (unsigned int c = 0; c < dim; ++c)
            {
              bc.components[c] = true;
              bc.field[c]      = [field, c](const Point<dim> &x) {
                return field(x)[c];
              };
            }
          bc.history = parameters.load_path.history_index(motion.history, 1);
          d.face_motions.push_back(
            {bc.boundary_id,
             centre,
             static_cast<unsigned int>(d.dirichlet.size()),
             displacement,
             rotation});
          d.dirichlet.push_back(bc);
        }
      d.hold_rotation_face = body.hold_rotation_face;
      for (const TractionParameters &traction : body.tractions)
        {
          discretization::NeumannCondition<dim> bc;
          bc.boundary_id = static_cast<types::boundary_id>(traction.face);
          bc.history = parameters.load_path.history_index(traction.history, 0);
          switch (traction.kind)
            {
              case TractionParameters::Kind::pressure:
                {
                  const double p = traction.values[0];
                  bc.traction    = [p](const Point<dim> &,
                                    const Tensor<1, dim> &n) {
                    return -p * n;
                  };
                  bc.pressure = p;
                  break;
                }
              case TractionParameters::Kind::vector:
                {
                  const Tensor<1, dim> t = tensor(traction.values);
                  bc.traction            = [t](const Point<dim> &,
                                    const Tensor<1, dim> &) {
                    return t;
                  };
                  break;
                }
              case TractionParameters::Kind::exact:
                {
                  Assert(exact.has_value(), ExcInternalError());
                  const auto stress = exact->stress;
                  bc.traction       = [stress](const Point<dim>     &x,
                                         const Tensor<1, dim> &n) {
                    return stress(x) * n;
                  };
                  break;
                }
              case TractionParameters::Kind::function:
                {
                  const auto at_time = [&traction](const double t) {
                    const auto f =
                      make_function_parser<dim>(traction.expressions, t);
                    return [f](const Point<dim> &x, const Tensor<1, dim> &) {
                      Tensor<1, dim> value;
                      for (unsigned int c = 0; c < dim; ++c)
                        value[c] = f->value(x, c);
                      return value;
                    };
                  };
                  if (!traction.uses_t)
                    {
                      bc.traction = at_time(0.);
                      break;
                    }
                  // One traction per step, each on its own history
                  // (AllParameters::parse_parameters).
                  for (unsigned int s = 0; s < traction.step_t.size(); ++s)
                    {
                      discretization::NeumannCondition<dim> step = bc;
                      step.traction = at_time(traction.step_t[s]);
                      step.history  = traction.step_histories[s];
                      d.tractions.push_back(step);
                    }
                  continue;
                }
            }
          d.tractions.push_back(bc);
        }
      for (const PointLoadParameters &load : body.point_loads)
        {
          discretization::PointLoad<dim> point_load;
          point_load.location = Point<dim>(tensor(load.location));
          point_load.force    = tensor(load.force);
          point_load.history =
            parameters.load_path.history_index(load.history, 0);
          d.point_loads.push_back(point_load);
        }
      for (const PointSupportParameters &support : body.point_supports)
        {
          discretization::PointSupport<dim> point_support;
          point_support.location = Point<dim>(tensor(support.location));
          for (unsigned int c = 0; c < dim; ++c)
            {
              point_support.components[c] = support.components[c];
              point_support.value[c]      = support.values[c];
            }
          point_support.history =
            parameters.load_path.history_index(support.history, 1);
          d.point_supports.push_back(point_support);
        }
      for (const MomentParameters &moment : body.moments)
        d.moments.push_back(
          {static_cast<types::boundary_id>(moment.face),
           moment.moment,
           parameters.load_path.history_index(moment.history, 0)});
      d.body_force = tensor(body.body_force);
      if (!body.body_force_expressions.empty())
        {
          const auto f =
            make_function_parser<dim>(body.body_force_expressions, 0.);
          d.body_force_field = [f](const Point<dim> &x) {
            Tensor<1, dim> value;
            for (unsigned int c = 0; c < dim; ++c)
              value[c] = f->value(x, c);
            return value;
          };
        }
      return d;
    }



    template <int dim>
    std::vector<std::unique_ptr<discretization::Body<dim>>>
    create_bodies(
      const AllParameters                                     &parameters,
      const std::string                                       &scene_file,
      const std::optional<discretization::ExactSolution<dim>> &exact)
    {
      const discretization::DiscretizationSettings &settings =
        parameters.discretization;
      std::vector<std::unique_ptr<discretization::Body<dim>>> bodies;
      for (const unsigned int b : parameters.deformable_bodies())
        bodies.push_back(discretization::create_body<dim>(
          make_body_description<dim>(parameters,
                                     parameters.bodies[b],
                                     "Body " + std::to_string(b + 1),
                                     scene_file,
                                     exact),
          settings));
      return bodies;
    }



    namespace
    {
      template <int dim>
      std::unique_ptr<contact::Obstacle<dim>>
      create_obstacle(const AllParameters &parameters,
                      const unsigned int   index,
                      const std::string   &scene_file)
      {
        const BodyParameters &body = parameters.bodies[index];
        const std::string     name = "Body " + std::to_string(index + 1);
        // The scene reader has refused zero normals and axes, radii <= 0,
        // missing faces and malformed motions already.
        const auto point_of = [](const std::vector<double> &values) {
          Point<dim> p;
          for (unsigned int d = 0; d < dim && d < values.size(); ++d)
            p[d] = values[d];
          return p;
        };
        std::unique_ptr<contact::Obstacle<dim>> obstacle;
        switch (body.type)
          {
            case BodyType::rigid_plane:
              obstacle = std::make_unique<contact::RigidPlane<dim>>(
                point_of(body.plane_point),
                point_of(body.plane_normal));
              break;
            case BodyType::rigid_cylinder:
              obstacle = std::make_unique<contact::RigidCylinder<dim>>(
                point_of(body.centre),
                body.radius,
                point_of(body.axis));
              break;
            case BodyType::rigid_sphere:
              obstacle =
                std::make_unique<contact::RigidSphere<dim>>(point_of(
                                                              body.centre),
                                                            body.radius);
              break;
            case BodyType::rigid_surface:
              {
                // The exact geometry as given (no degree elevation), split
                // into its Subdivisions: the closest-point search samples
                // each span; its faces those the interactions name.
                const nurbs::MultiPatchGeometry<dim> geometry =
                  make_geometry<dim>(body, scene_file + ": " + name + "/", 1);
                std::vector<unsigned int> faces;
                for (const InteractionParameters &c :
                     parameters.contact.interactions)
                  if (c.master_body == index + 1)
                    faces.insert(faces.end(),
                                 c.master_faces.begin(),
                                 c.master_faces.end());
                std::sort(faces.begin(), faces.end());
                faces.erase(std::unique(faces.begin(), faces.end()),
                            faces.end());
                obstacle = std::make_unique<contact::RigidSurface<dim>>(
                  discretization::make_nurbs_surface(geometry.patches, faces),
                  body.geometry == Geometry::file ?
                    body.geometry_file :
                    "Geometry = " + to_string(body.geometry));
                break;
              }
            default:
              Assert(false, ExcInternalError());
          }
        std::vector<contact::RigidMotion<dim>> motion;
        for (const ObstacleMotionParameters &term : body.motion)
          {
            contact::RigidMotion<dim> m;
            m.history     = parameters.load_path.history_index(term.history, 1);
            m.translation = point_of(term.translation);
            if (dim == 2)
              m.rotation[2] = term.rotation[0];
            else
              for (unsigned int d = 0; d < 3; ++d)
                m.rotation[d] = term.rotation[d];
            motion.push_back(m);
          }
        obstacle->set_motion(motion);
        return obstacle;
      }
    } // namespace



    template <int dim>
    std::vector<std::unique_ptr<contact::Obstacle<dim>>>
    create_obstacles(const AllParameters &parameters,
                     const std::string   &scene_file)
    {
      std::vector<std::unique_ptr<contact::Obstacle<dim>>> obstacles;
      for (const unsigned int b : parameters.obstacle_bodies())
        obstacles.push_back(create_obstacle<dim>(parameters, b, scene_file));
      return obstacles;
    }



    template std::vector<std::unique_ptr<contact::Obstacle<2>>>
    create_obstacles<2>(const AllParameters &, const std::string &);
    template std::vector<std::unique_ptr<contact::Obstacle<3>>>
    create_obstacles<3>(const AllParameters &, const std::string &);
    template std::optional<discretization::ExactSolution<2>>
    make_exact_solution<2>(const AllParameters &, const std::string &);
    template std::optional<discretization::ExactSolution<3>>
    make_exact_solution<3>(const AllParameters &, const std::string &);
    template discretization::BodyDescription<2>
    make_body_description<2>(
      const AllParameters &,
      const BodyParameters &,
      const std::string &,
      const std::string &,
      const std::optional<discretization::ExactSolution<2>> &);
    template discretization::BodyDescription<3>
    make_body_description<3>(
      const AllParameters &,
      const BodyParameters &,
      const std::string &,
      const std::string &,
      const std::optional<discretization::ExactSolution<3>> &);
    template std::vector<std::unique_ptr<discretization::Body<2>>>
    create_bodies<2>(const AllParameters &,
                     const std::string &,
                     const std::optional<discretization::ExactSolution<2>> &);
    template std::vector<std::unique_ptr<discretization::Body<3>>>
    create_bodies<3>(const AllParameters &,
                     const std::string &,
                     const std::optional<discretization::ExactSolution<3>> &);
  } // namespace scene
} // namespace igabde
