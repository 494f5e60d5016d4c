#ifndef igabde_scene_body_factory_h
#define igabde_scene_body_factory_h

#include <igabde/discretization/body.h>
#include <igabde/discretization/body_description.h>

#include <igabde/contact/obstacle.h>

#include <igabde/scene/parameters.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace igabde
{
  namespace scene
  {
    /**
     * @brief The exact solution the scene names (Exact solution/Type), with
     * the material of Body 1; none for Type = none. @p scene_file names the
     * file in messages.
     */
    template <int dim>
    std::optional<discretization::ExactSolution<dim>>
    make_exact_solution(const AllParameters &parameters,
                        const std::string   &scene_file);

    /**
     * @brief The dim-dimensional description of @p body ("Body 1" or
     * "Body 2", @p name): material, exact geometry, supports, tractions
     * ('exact' ones from @p exact), point loads and body force, each load
     * on its history.
     */
    template <int dim>
    discretization::BodyDescription<dim>
    make_body_description(
      const AllParameters                                     &parameters,
      const BodyParameters                                    &body,
      const std::string                                       &name,
      const std::string                                       &scene_file,
      const std::optional<discretization::ExactSolution<dim>> &exact);

    /**
     * @brief The deformable bodies of the scene in its order (IgaBody or
     * LagrangeBody after Discretization/Type; the b-th is Body
     * AllParameters::deformable_bodies()[b] + 1); nothing is assembled
     * yet.
     */
    template <int dim>
    std::vector<std::unique_ptr<discretization::Body<dim>>>
    create_bodies(
      const AllParameters                                     &parameters,
      const std::string                                       &scene_file,
      const std::optional<discretization::ExactSolution<dim>> &exact);

    /**
     * @brief The rigid obstacles of the scene in its order (the k-th is
     * Body AllParameters::obstacle_bodies()[k] + 1), each with its
     * prescribed motion; a rigid surface has the master faces of the
     * interactions that name it.
     */
    template <int dim>
    std::vector<std::unique_ptr<contact::Obstacle<dim>>>
    create_obstacles(const AllParameters &parameters,
                     const std::string   &scene_file);
  } // namespace scene
} // namespace igabde

#endif
